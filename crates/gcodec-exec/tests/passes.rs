//! Where each pass of a repeated call is reported: every `call` event of
//! a `REPEAT` section or of a subprogram called with `P` points at the
//! block that wrote the call, pass after pass (SPEC §11.1), not at the
//! last block the previous pass ran.

use gcodec_driver::RunSetup;
use gcodec_exec::event::{Event, EventKind};

mod common;

/// The (file, line) of every `call` event of `program` (`MAIN.MPF`), with
/// `PASS3.SPF` beside it on the search path.
fn call_positions(program: &str) -> Vec<(String, u32)> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    std::fs::write(dir.path().join("PASS3.SPF"), "G1 X1 F100\nM17\n").expect("write PASS3.SPF");
    let mut setup = RunSetup::new(gcodec_profile::builtin().expect("the built-in profile"));
    setup.search_dirs = vec![dir.path().to_owned()];
    common::runs::events_of_text_with(&setup, "MAIN.MPF", program)
        .iter()
        .filter(|e: &&Event| matches!(e.kind, EventKind::Call(_)))
        .map(|e| (e.source.file.to_string(), e.source.line))
        .collect()
}

#[test]
fn every_pass_of_a_repeat_section_is_reported_at_the_repeat_block() {
    let ran = call_positions("ANF:\nG1 X1 F100\nENDE:\nREPEAT ANF ENDE P=3\nM30\n");
    assert_eq!(ran, vec![("MAIN.MPF".to_owned(), 4); 3]);
    let ran = call_positions("ANF:\nG1 X1 F100\nX2\nREPEATB ANF P=2\nM30\n");
    assert_eq!(ran, vec![("MAIN.MPF".to_owned(), 4); 2]);
}

#[test]
fn every_pass_of_a_subprogram_call_is_reported_at_the_call() {
    let ran = call_positions("G0 X0\nPASS3 P3\nM30\n");
    assert_eq!(ran, vec![("MAIN.MPF".to_owned(), 2); 3]);
}
