//! Feeds arbitrary bytes to macro expansion: the bytes before the first
//! NUL are a definition file (`DEFINE … AS …` lines), the rest a main
//! program that uses them. Checks what every parse must satisfy with
//! macros expanded (no panic, one block per line, every span in bounds
//! and at its true line and column: a node a macro produced sits at its
//! use in the program), that lowering the expanded program does not
//! panic, and renders every diagnostic against the program.

#![no_main]

#[path = "../../crates/gcodec-parser/tests/common/invariants.rs"]
mod invariants;

use std::sync::{Arc, LazyLock};

use gcodec_driver::{Definitions, ProgramKind, compile, parse_with};
use gcodec_profile::Profile;
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};
use libfuzzer_sys::fuzz_target;

static PROFILE: LazyLock<Profile> =
    LazyLock::new(|| gcodec_profile::builtin().expect("the built-in profile"));

fuzz_target!(|data: &[u8]| {
    let (definition_file, program) = match data.iter().position(|&b| b == 0) {
        Some(at) => (&data[..at], &data[at + 1..]),
        None => (data, &[][..]),
    };
    let mut definitions = Definitions::new();
    let _ = definitions.load_bytes("UMAC.DEF", definition_file);
    let file = SourceFile::new("fuzz.mpf", program);
    let parse = parse_with(&file, &definitions);
    if let Err(problem) = invariants::check_parse_of(file.bytes(), &parse) {
        panic!("{problem}");
    }
    let compiled = compile(Arc::new(file), ProgramKind::Main, &PROFILE, &definitions);
    let rendered =
        render_diagnostics(&compiled.diagnostics, Some(&compiled.file), RenderOptions::default());
    assert_eq!(rendered.is_empty(), compiled.diagnostics.is_empty());
});
