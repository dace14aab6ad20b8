//! Helpers shared by the semantic stage's integration tests: the parser's
//! (where the repository and the corpus are) plus the shipped profiles.

#![allow(dead_code, unused_imports)]

#[path = "../../../gcodec-parser/tests/common/mod.rs"]
mod parser_common;

pub use parser_common::{corpus_dir, programs, repo};

/// A shipped profile, by file name (`lathe_828d.toml`).
pub fn profile(name: &str) -> gcodec_profile::Profile {
    let text = std::fs::read_to_string(repo().join("profiles").join(name)).expect("profile");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"))
}
