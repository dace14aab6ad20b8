//! A golden fixture in the other output formats, the profile's
//! `[program]` settings a run obeys, and what the CSV writer and a sink
//! without motions get from every run fixture.

mod common;

use std::path::PathBuf;
use std::sync::Arc;

use common::golden::{Output, golden};
use common::runs::{RunSetup, compile_main, run_main};
use common::setup::{Setup, at_repo_root, run_fixtures, setup};
use gcodec_driver::Definitions;
use gcodec_driver::SearchPath;
use gcodec_exec::channel::{BlockObserver, RunOptions};
use gcodec_exec::event::{
    BlockRow, CountingSink, CsvRows, CsvWriter, Event, EventKind, EventSink, ProgramEndReason,
    VecSink,
};
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

/// A run fixture that lowers without errors, compiled, with what it
/// runs on.
struct RunnableFixture {
    name: String,
    profile: Arc<gcodec_profile::Profile>,
    options: RunOptions,
    definitions: Arc<Definitions>,
    program: Arc<gcodec_exec::program::Program>,
}

impl RunnableFixture {
    /// Every run fixture that lowers without errors.
    fn all() -> Vec<Self> {
        at_repo_root();
        run_fixtures()
            .iter()
            .filter_map(|path| {
                let fixture = Fixture::read("run", path);
                let Setup { profile, options } = setup(&fixture);
                let file = Arc::new(fixture.file.clone());
                let definitions = Arc::new(Definitions::new());
                let main = compile_main(&file, &profile, &definitions);
                (!main.has_errors).then(|| Self {
                    name: fixture.relative.clone(),
                    profile,
                    options,
                    definitions,
                    program: main.program,
                })
            })
            .collect()
    }

    /// Runs it into `sink`, and `observer` if one.
    fn run(
        &self,
        sink: &mut dyn EventSink,
        observer: Option<&mut dyn BlockObserver>,
    ) -> gcodec_exec::channel::RunOutcome {
        let setup = RunSetup {
            profile: Arc::clone(&self.profile),
            options: self.options.clone(),
            definitions: Arc::clone(&self.definitions),
            search: SearchPath::new(),
        };
        run_main(Arc::clone(&self.program), setup, sink, observer)
    }
}

/// Hands the CSV writer each row with its promise (`unchanged`) taken
/// back, so the writer compares every row; counts the promises.
struct Unpromised<'w> {
    csv: &'w mut CsvWriter<Vec<u8>>,
    promised: usize,
}

impl BlockObserver for Unpromised<'_> {
    fn block(&mut self, row: &BlockRow) -> std::io::Result<()> {
        self.promised += usize::from(row.unchanged);
        let mut row = row.clone();
        row.unchanged = false;
        row.columns_unchanged = false;
        self.csv.row(&row)
    }
}

/// The executor's promises that a row's state columns, or all but its
/// positions, are the row before's let the writer skip comparing them;
/// the CSV is then what comparing every row writes, in both row
/// selections, for every run fixture (loops, calls, frames, compensation
/// with held rows).
#[test]
fn csv_rows_promised_unchanged_are_written_as_compared_rows() {
    let mut promised = 0;
    for fixture in RunnableFixture::all() {
        for rows in [CsvRows::Changes, CsvRows::EveryBlock] {
            let csv = |unpromised: bool| {
                let mut csv = CsvWriter::for_profile(Vec::new(), &fixture.profile)
                    .expect("header")
                    .with_rows(rows);
                let mut count = 0;
                let mut events = CountingSink::default();
                if unpromised {
                    let mut observer = Unpromised {
                        csv: &mut csv,
                        promised: 0,
                    };
                    fixture.run(&mut events, Some(&mut observer));
                    count = observer.promised;
                } else {
                    fixture.run(&mut events, Some(&mut csv));
                }
                (csv.into_inner().expect("rows"), count)
            };
            let (as_promised, _) = csv(false);
            let (compared, count) = csv(true);
            assert!(
                as_promised == compared,
                "{} ({rows:?}): the promised rows differ\n{}\n---\n{}",
                fixture.name,
                String::from_utf8_lossy(&as_promised),
                String::from_utf8_lossy(&compared)
            );
            promised += count;
        }
    }
    assert!(promised > 100, "only {promised} rows promised unchanged");
}

/// Keeps every event it is sent, and takes no motions.
#[derive(Default)]
struct NoMotions(VecSink);

impl EventSink for NoMotions {
    fn event(&mut self, event: &Event) -> std::io::Result<()> {
        self.0.event(event)
    }

    fn takes_motions(&self) -> bool {
        false
    }
}

/// A sink that takes no motions gets every other event of the run, in
/// the same order, and the run's figures are the same, for every run
/// fixture (compensated ones included, whose motions the path stage
/// builds all the same).
#[test]
fn a_sink_without_motions_gets_every_other_event() {
    let mut compared = 0;
    for fixture in RunnableFixture::all() {
        let mut all = VecSink::new();
        let with = fixture.run(&mut all, None);
        let mut others = NoMotions::default();
        let without = fixture.run(&mut others, None);
        let expected: Vec<&Event> = all
            .events
            .iter()
            .filter(|e| !matches!(e.kind, EventKind::Motion(_)))
            .collect();
        let got: Vec<&Event> = others.0.events.iter().collect();
        assert_eq!(got, expected, "{}", fixture.name);
        assert_eq!(
            without.summary.to_string(),
            with.summary.to_string(),
            "{}",
            fixture.name
        );
        compared += usize::from(all.events.len() > expected.len());
    }
    assert!(compared >= 10, "only {compared} fixtures with motions");
}
