//! A golden fixture in the other output formats, and the profile's
//! `[program]` settings a run obeys.

mod common;

use std::path::PathBuf;
use std::sync::Arc;

use common::golden::{Output, golden};
use common::runs::{RunSetup, compile_main, run_main};
use gcodec_driver::Definitions;
use gcodec_driver::SearchPath;
use gcodec_exec::channel::RunOptions;
use gcodec_exec::event::{CountingSink, ProgramEndReason};
use gcodec_source::SourceFile;
use gcodec_testkit::Fixture;

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(gcodec_testkit::fixtures::root("run")).join(name)
}

#[test]
fn motion_jsonl() {
    let motion = Fixture::read("run", &fixture("motion.mpf"));
    insta::assert_snapshot!(golden(&motion, Output::Jsonl));
}

#[test]
fn motion_csv() {
    let motion = Fixture::read("run", &fixture("motion.mpf"));
    insta::assert_snapshot!(golden(&motion, Output::Csv));
}

/// Under tool radius compensation the CSV's positions are the tool
/// centre's, in block order, though the rows wait for the look-ahead.
#[test]
fn compensated_csv_rows_follow_the_tool_centre() {
    let square = Fixture::read("run", &fixture("compensation_outside_g450.mpf"));
    insta::assert_snapshot!(golden(&square, Output::Csv));
}

/// Runs `file` with the fixture mill and `program` as the profile's
/// `[program]` section; the end reason.
fn end_with_program_settings(file: &str, program: &str) -> ProgramEndReason {
    let mill = std::fs::read_to_string(fixture("mill.toml")).expect("profile");
    let profile = gcodec_profile::load(&format!("{mill}\n[program]\n{program}\n")).expect("valid");
    let profile = Arc::new(profile);
    let options = RunOptions::for_profile(&profile);
    let text = std::fs::read(fixture(file)).expect("fixture");
    let source = Arc::new(SourceFile::new(file, text));
    let definitions = Arc::new(Definitions::new());
    let main = compile_main(&source, &profile, &definitions);
    let run = RunSetup {
        profile,
        options,
        definitions,
        search: SearchPath::new(),
    };
    run_main(main.program, run, &mut CountingSink::default(), None).reason
}

#[test]
fn the_profile_can_let_runs_go_on_after_m0() {
    use ProgramEndReason as End;
    assert_eq!(end_with_program_settings("stop.mpf", ""), End::Stopped);
    assert_eq!(
        end_with_program_settings("stop.mpf", "stop_at_m0 = false"),
        End::M30
    );
}

#[test]
fn the_circle_tolerance_comes_from_the_profile() {
    use ProgramEndReason as End;
    // arcs.mpf ends with an arc whose end point is 41.1 mm off its circle
    // (radius 5 at the start, 46.1 at the end).
    assert_eq!(end_with_program_settings("arcs.mpf", ""), End::Alarm);
    assert_eq!(
        end_with_program_settings("arcs.mpf", "circle_error_const = 41.2"),
        End::M30
    );
}
