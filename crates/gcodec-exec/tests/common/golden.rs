//! A golden fixture's run written out: its lowering diagnostics, its
//! events in one of the output formats, then the run's summary.

use std::sync::Arc;

use gcodec_driver::Definitions;
use gcodec_driver::SearchPath;
use gcodec_exec::event::{CountingSink, CsvWriter, EventKind, JsonlSink, TextSink};
use gcodec_testkit::Fixture;

use super::runs::{RunSetup, compile_main, run_main};
use super::setup::{Setup, at_repo_root, setup};

pub enum Output {
    Text,
    Jsonl,
    Csv,
}

/// Runs `fixture` with the profile and options its `; run:` line names,
/// from the repository root; subprograms are found next to it.
pub fn golden(fixture: &Fixture, output: Output) -> String {
    at_repo_root();
    let Setup { profile, options } = setup(fixture);
    let file = Arc::new(fixture.file.clone());
    let definitions = Arc::new(Definitions::new());
    let main = compile_main(&file, &profile, &definitions);
    assert!(
        !main.has_errors,
        "{} has lowering errors: {:#?}",
        fixture.relative, main.diagnostics
    );
    let mut out = String::new();
    for d in &main.diagnostics {
        if let EventKind::Diagnostic(d) = &d.kind {
            out.push_str(&format!(
                "lowering: {} {}: {}\n",
                d.severity.name(),
                d.code,
                d.message
            ));
        }
    }
    let run = RunSetup {
        profile: Arc::clone(&profile),
        options,
        definitions,
        search: SearchPath::new(),
    };
    let mut buffer = Vec::new();
    let outcome = match output {
        Output::Text => run_main(main.program, run, &mut TextSink::new(&mut buffer), None),
        Output::Jsonl => run_main(main.program, run, &mut JsonlSink::new(&mut buffer), None),
        Output::Csv => {
            let mut csv = CsvWriter::for_profile(Vec::new(), &profile).expect("header");
            let outcome = run_main(
                main.program,
                run,
                &mut CountingSink::default(),
                Some(&mut csv),
            );
            buffer = csv.into_inner().expect("rows");
            outcome
        }
    };
    out.push_str(&String::from_utf8(buffer).expect("UTF-8 events"));
    out.push('\n');
    out.push_str(&outcome.summary.to_string());
    out
}
