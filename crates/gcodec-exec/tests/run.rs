//! Golden event streams: every program of `tests/fixtures/run/` runs with
//! the profile and options its first lines name
//! (`; run: profile=mill.toml no-stop skip=1 max-steps=20`), and its text
//! trace with the run's summary is an insta snapshot. Subprograms are
//! found next to the fixture. The numbers were checked by hand when the
//! snapshots were accepted (see the fixtures' comments).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{CsvWriter, JsonlSink, TextSink};
use gcodec_exec::loader::{FileLoader, SearchPath, compile, program_name};
use gcodec_sema::Definitions;
use gcodec_source::SourceFile;

mod common;

use common::setup::{FIXTURES, Setup, at_repo_root, setup};

enum Output {
    Text,
    Jsonl,
    Csv,
}

fn run(path: &Path, output: Output) -> String {
    let text = std::fs::read_to_string(path).expect("fixture");
    let Setup { profile, options } = setup(path, &text);
    let file = SourceFile::new(path.to_string_lossy().replace('\\', "/"), text.as_bytes());
    let definitions = Arc::new(Definitions::new());
    let main = compile(
        program_name(path),
        Arc::new(file),
        &profile,
        &definitions,
        false,
    );
    assert!(
        !main.has_errors,
        "{} has lowering errors: {:#?}",
        path.display(),
        main.diagnostics
    );
    let mut out = String::new();
    for d in &main.diagnostics {
        if let gcodec_exec::event::EventKind::Diagnostic(d) = &d.kind {
            out.push_str(&format!(
                "lowering: {} {}: {}\n",
                d.severity.name(),
                d.code,
                d.message
            ));
        }
    }
    let mut loader = FileLoader::new(SearchPath::new(), Arc::clone(&profile), definitions);
    let mut buffer = Vec::new();
    let outcome = match output {
        Output::Text => {
            let mut sink = TextSink::new(&mut buffer);
            Channel::new(profile, options, &mut loader, &mut sink).run(main.program)
        }
        Output::Jsonl => {
            let mut sink = JsonlSink::new(&mut buffer);
            Channel::new(profile, options, &mut loader, &mut sink).run(main.program)
        }
        Output::Csv => {
            let mut csv = CsvWriter::for_profile(Vec::new(), &profile).expect("header");
            let mut sink = gcodec_exec::event::CountingSink::default();
            let outcome = Channel::new(profile, options, &mut loader, &mut sink)
                .with_observer(&mut csv)
                .run(main.program);
            buffer = csv.into_inner().expect("rows");
            outcome
        }
    }
    .expect("the run writes to memory");
    out.push_str(&String::from_utf8(buffer).expect("UTF-8 events"));
    out.push('\n');
    out.push_str(&outcome.summary.to_string());
    out
}

fn fixture(name: &str) -> PathBuf {
    at_repo_root();
    Path::new(FIXTURES).join(name)
}

macro_rules! golden {
    ($($test:ident => $file:literal),* $(,)?) => {$(
        #[test]
        fn $test() {
            insta::assert_snapshot!(stringify!($test), run(&fixture($file), Output::Text));
        }
    )*};
}

golden! {
    motion => "motion.mpf",
    arcs => "arcs.mpf",
    offsets => "offsets.mpf",
    control => "control.mpf",
    calls => "calls.mpf",
    tools => "tools.mpf",
    tool_management => "tool_management.mpf",
    stop => "stop.mpf",
    skip => "skip.mpf",
    sections => "sections.mpf",
    helix => "helix.mpf",
    limits => "limits.mpf",
    variables => "variables.mpf",
    lathe => "lathe.mpf",
}

#[test]
fn motion_jsonl() {
    insta::assert_snapshot!(run(&fixture("motion.mpf"), Output::Jsonl));
}

#[test]
fn motion_csv() {
    insta::assert_snapshot!(run(&fixture("motion.mpf"), Output::Csv));
}

/// Runs `file` with the fixture mill and `program` as the profile's
/// `[program]` section; the end reason.
fn end_with_program_settings(file: &str, program: &str) -> gcodec_exec::event::ProgramEndReason {
    let mill = std::fs::read_to_string(fixture("mill.toml")).expect("profile");
    let profile = gcodec_profile::load(&format!("{mill}\n[program]\n{program}\n")).expect("valid");
    let profile = Arc::new(profile);
    let options = RunOptions::for_profile(&profile);
    let text = std::fs::read(fixture(file)).expect("fixture");
    let source = SourceFile::new(file, text);
    let definitions = Arc::new(Definitions::new());
    let main = compile("MAIN", Arc::new(source), &profile, &definitions, false);
    let mut loader = FileLoader::new(SearchPath::new(), Arc::clone(&profile), definitions);
    let mut sink = gcodec_exec::event::CountingSink::default();
    Channel::new(profile, options, &mut loader, &mut sink)
        .run(main.program)
        .expect("memory")
        .reason
}

#[test]
fn the_profile_can_let_runs_go_on_after_m0() {
    use gcodec_exec::event::ProgramEndReason as End;
    assert_eq!(end_with_program_settings("stop.mpf", ""), End::Stopped);
    assert_eq!(
        end_with_program_settings("stop.mpf", "stop_at_m0 = false"),
        End::M30
    );
}

#[test]
fn the_circle_tolerance_comes_from_the_profile() {
    use gcodec_exec::event::ProgramEndReason as End;
    // arcs.mpf ends with an arc whose end point is 41.1 mm off its circle
    // (radius 5 at the start, 46.1 at the end).
    assert_eq!(end_with_program_settings("arcs.mpf", ""), End::Alarm);
    assert_eq!(
        end_with_program_settings("arcs.mpf", "circle_error_const = 41.2"),
        End::M30
    );
}
