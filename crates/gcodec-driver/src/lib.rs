//! The facade over gcodec's pipeline: everything that parses, lowers and
//! runs a program goes through here, so that the stages are wired in one
//! place.
//!
//! - [`check`]: `gcodec check`, a tree of programs and definition files
//!   checked as its `gcodec.toml` says, the diagnostics as data.
//! - [`diagnostics`]: the diagnostics of a file as every command hands
//!   them on ([`diagnostics::FileReport`]) and as data
//!   ([`diagnostics::DiagnosticRecord`]).
//! - [`compile()`]: parse and lower one program, as a main program or a
//!   subprogram ([`ProgramKind`]), against a profile and definitions.
//! - [`lower`]: `gcodec lower`, a program lowered streamed, its
//!   instructions handed on as they are made ([`lower_streamed`]) and
//!   written as the AIL document in JSON or as the listing.
//! - [`load_profile`]: a machine profile checked in full (its form and
//!   its G codes), [`load_builtin_profile`] the built-in one without
//!   parsing its text; [`Definitions`], the global names of definition
//!   files.
//! - [`loader`]: the programs a running program calls, found on a search
//!   path ([`FileLoader`]) or given as text ([`MemoryLoader`]).
//! - [`run_main`]: a main program run as `gcodec run` runs it, streamed
//!   ([`stream`]), its events handed to an [`event::EventSink`], the
//!   files it loads kept in [`LoadedFiles`] for labelling its diagnostic
//!   events ([`runtime_diagnostic`]).
//!
//! The parts of the lower crates that are the facade's API too are
//! re-exported: the syntax tree as text and the AIL listing, the run's
//! options, events and sinks.

pub mod check;
pub mod compile;
pub mod diagnostics;
mod loaded_files;
pub mod loader;
pub mod lower;
mod meant_command;
pub mod run;
mod setup;
pub mod stream;

pub use compile::{Compiled, compile, compile_linted, compile_text, parse_with};
pub use diagnostics::runtime_diagnostic;
pub use gcodec_ail::{Document, write_listing};
pub use gcodec_exec::budget::DEFAULT_MAX_WORK;
pub use gcodec_exec::channel::{BlockObserver, Channel, RunOptions, RunOutcome};
pub use gcodec_exec::event;
pub use gcodec_exec::{machine, session, toolchanger};
pub use gcodec_parser::{Parse, parse, write_tree};
pub use gcodec_sema::{Definitions, ProgramKind};
pub use loaded_files::LoadedFiles;
pub use loader::{FileLoader, MemoryLoader, SearchPath, program_name};
pub use lower::lower_streamed;
pub use run::{RunReport, RunSetup, globals, run_main, run_program};
pub use setup::{
    ProfileError, builtin_profile_file, load_builtin_profile, load_profile, load_toolchanger,
    read_source,
};
pub use stream::{StreamOptions, run_streamed};
