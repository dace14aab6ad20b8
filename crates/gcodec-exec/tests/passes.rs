//! Where each pass of a repeated call is reported: every `call` event of
//! a `REPEAT` section or of a subprogram called with `P` points at the
//! block that wrote the call, pass after pass (SPEC §11.1), not at the
//! last block the previous pass ran.

use std::sync::Arc;

use gcodec_driver::{RunSetup, run_main};
use gcodec_exec::event::{Event, EventKind, VecSink};
use gcodec_source::SourceFile;

/// The (file, line) of every `call` event of `program` (`MAIN.MPF`), with
/// `PASS3.SPF` beside it on the search path.
fn call_positions(program: &str) -> Vec<(String, u32)> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    std::fs::write(dir.path().join("PASS3.SPF"), "G1 X1 F100\nM17\n").expect("write PASS3.SPF");
    let mut setup = RunSetup::new(gcodec_profile::builtin().expect("the built-in profile"));
    setup.search_dirs = vec![dir.path().to_owned()];
    let file = Arc::new(SourceFile::new("MAIN.MPF", program));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    assert!(
        !report.diagnostics.iter().any(|d| d.is_error()),
        "{:#?}",
        report.diagnostics
    );
    sink.events
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
