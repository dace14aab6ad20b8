//! Helpers shared by the integration tests of the gcodec crates; a
//! dev-dependency only, never a dependency of a library.
//!
//! - [`agreement`]: the fast paths of lowering and running against the
//!   general ones, for the tests and the fuzz targets.
//! - [`paths`]: where the programs are (the repository, the shared
//!   corpus and reference) and how a corpus program is shown.
//! - [`fixtures`]: a fixture of `tests/fixtures/KIND/`, its `; KIND:` line
//!   and its snapshot (the scheme is in `tests/fixtures/README.md`).
//! - [`profiles`]: the shipped profiles and small test machines.
//! - [`corpus`]: the machines and definitions the corpus was written for.
//! - [`peer`]: the verdicts on the peer interpreter's example programs
//!   (issue 20) and the configuration they run with.
//! - [`schema`]: the checked-in JSON Schemas are current.
//! - [`linuxcnc`]: LinuxCNC's interpreter as a reference, its recorded
//!   canonical calls (`rs274`) read back as moves, each with its block.
//! - [`compile`]: the compile set-up a test repeats (parse a program that
//!   must parse cleanly, lower it for a profile). It stays thin so that
//!   the pipeline's facade can take its place.

pub mod agreement;
pub mod compile;
pub mod corpus;
pub mod fixtures;
pub mod linuxcnc;
pub mod paths;
pub mod peer;
pub mod profiles;
pub mod schema;

pub use compile::lower_clean;
pub use fixtures::{Fixture, Header};
pub use paths::{
    all_programs, corpus_dir, each_program, each_program_on, programs, reference_dir, repo, shown,
};
pub use profiles::{machine, profile};
pub use schema::assert_schema_current;
