//! gcodec's tool-centre path against LinuxCNC's: each program of
//! `tests/fixtures/compensation/linuxcnc` is a pair, `NAME.ngc` for
//! LinuxCNC and `NAME.mpf` for SINUMERIK, of one contour, each block on
//! the same line with the same `N` word in both. `NAME.rs274.txt` is what
//! LinuxCNC's interpreter printed for the `.ngc`
//! (`scripts/linuxcnc-compensation/record.sh`); the `.mpf` runs here on
//! `profile.toml`, whose tools have the radii of `tools.tbl`.
//!
//! What is compared is the interior of the contour: the blocks after the
//! approach (the line marked `; approach`, which selects `G41`/`G42`) and
//! before the retract (marked `; retract`, `G40`), where both controls
//! offset the same contour the same way. In each such block, gcodec's
//! motion events with a tool centre (the inserted ones too) are compared
//! in order with LinuxCNC's moves of the block, within 1e-3 mm in X and
//! Y; a program without compensation compares the contour points (`to`).
//! The approach and retract differ between the controls by design (the
//! fixtures' README says how LinuxCNC does them).

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_driver::event::{Event, EventKind, MotionEvent, VecSink};
use gcodec_driver::{RunSetup, load_profile, read_source, run_main};
use gcodec_source::{SourceFile, TextEncoding};
use gcodec_testkit::linuxcnc::{self, BlockMove, CallKind};

/// How far apart, in X and in Y, the two controls' points may be: the
/// acceptance of tool radius compensation. rs274 prints 4 decimals.
const TOLERANCE: f64 = 1e-3;

fn fixture_dir() -> PathBuf {
    gcodec_testkit::repo().join("tests/fixtures/compensation/linuxcnc")
}

/// One pair of programs and LinuxCNC's recording of it.
struct Case {
    name: String,
    mpf_path: PathBuf,
    mpf: String,
    ngc: String,
    recording: Vec<linuxcnc::Call>,
}

impl Case {
    fn read(ngc_path: &Path) -> Self {
        let name = ngc_path
            .file_stem()
            .expect("a file name")
            .to_string_lossy()
            .into_owned();
        let dir = ngc_path.parent().expect("the fixture folder");
        let read = |file: String| {
            std::fs::read_to_string(dir.join(&file))
                .unwrap_or_else(|e| panic!("{file}: {e} (every NAME.ngc has NAME.mpf and NAME.rs274.txt; record.sh writes the recording)"))
        };
        let ngc = read(format!("{name}.ngc"));
        let mpf = read(format!("{name}.mpf"));
        let recording = linuxcnc::parse(&read(format!("{name}.rs274.txt")))
            .unwrap_or_else(|e| panic!("{name}.rs274.txt: {e}"));
        Self {
            mpf_path: dir.join(format!("{name}.mpf")),
            name,
            mpf,
            ngc,
            recording,
        }
    }

    /// Whether LinuxCNC compensated: its recording switches compensation on.
    fn compensated(&self) -> bool {
        self.recording
            .iter()
            .any(|call| matches!(call.what, CallKind::CompensationOn(_)))
    }

    /// The (`N` word, line) of the line of the `.mpf` ending in `marker`.
    fn marked(&self, marker: &str) -> (u32, u32) {
        let numbers = linuxcnc::block_numbers(&self.mpf);
        let line = self
            .mpf
            .lines()
            .position(|l| l.trim_end().ends_with(marker))
            .unwrap_or_else(|| panic!("{}.mpf has no line marked `{marker}`", self.name))
            as u32
            + 1;
        let number = numbers
            .iter()
            .find(|(_, l)| **l == line)
            .map(|(n, _)| *n)
            .unwrap_or_else(|| panic!("{}.mpf line {line} has no N word", self.name));
        (number, line)
    }

    /// The interior blocks, (`N` word, line), in order: every numbered
    /// line between the approach and the retract.
    fn interior(&self) -> Vec<(u32, u32)> {
        let (_, approach) = self.marked("; approach");
        let (_, retract) = self.marked("; retract");
        let mut blocks: Vec<(u32, u32)> = linuxcnc::block_numbers(&self.mpf)
            .into_iter()
            .filter(|(_, line)| (approach + 1..retract).contains(line))
            .collect();
        blocks.sort_by_key(|(_, line)| *line);
        blocks
    }

    /// Runs the `.mpf` on the fixtures' profile: its events, after
    /// checking that neither lowering nor the run found an error.
    fn run(&self) -> Vec<Event> {
        let profile_path = fixture_dir().join("profile.toml");
        let text = std::fs::read(&profile_path).expect("profile.toml");
        let (profile, _) = load_profile(&SourceFile::new("profile.toml", text))
            .unwrap_or_else(|e| panic!("profile.toml: {e:?}"));
        let max_len = *profile.program.max_file_size.get_ref();
        let mut setup = RunSetup::new(profile);
        setup.profile_file = Some(profile_path);
        let file = read_source(&self.mpf_path, max_len, TextEncoding::default())
            .unwrap_or_else(|d| panic!("{}: {}", self.name, d.message));
        let mut sink = VecSink::new();
        let report = run_main(Arc::new(file), &setup, &mut sink, None);
        report.outcome.expect("the run writes its events");
        let errors: Vec<String> = report
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .map(|d| format!("{}: {}", d.code, d.message))
            .chain(sink.events.iter().filter_map(|event| match &event.kind {
                EventKind::Diagnostic(d) if d.severity == gcodec_source::Severity::Error => Some(
                    format!("line {}: {}: {}", event.source.line, d.code, d.message),
                ),
                _ => None,
            }))
            .collect();
        assert!(
            errors.is_empty(),
            "{}.mpf does not run cleanly in gcodec:\n{}",
            self.name,
            errors.join("\n")
        );
        sink.events
    }
}

/// Every pair of the fixture folder, by name.
fn cases() -> Vec<Case> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(fixture_dir())
        .expect("the fixture folder")
        .map(|entry| entry.expect("a folder entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == "ngc"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no .ngc fixtures");
    paths.iter().map(|path| Case::read(path)).collect()
}

/// A point of either control's path, as the table shows it.
struct Point {
    what: String,
    x: f64,
    y: f64,
}

impl Point {
    fn show(point: Option<&Point>) -> String {
        match point {
            Some(p) => format!("{:<18} ({:>9.4}, {:>9.4})", p.what, p.x, p.y),
            None => format!("{:<41}", "-"),
        }
    }
}

/// LinuxCNC's moves of each block, by `N` word.
fn linuxcnc_points(moves: &[BlockMove]) -> BTreeMap<u32, Vec<Point>> {
    let mut points: BTreeMap<u32, Vec<Point>> = BTreeMap::new();
    for m in moves {
        if let Some(block) = m.block {
            points.entry(block).or_default().push(Point {
                what: m.motion.kind.name().to_owned(),
                x: m.motion.end[0],
                y: m.motion.end[1],
            });
        }
    }
    points
}

/// Which of gcodec's points are compared.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Compared {
    /// The tool centre (`tool.tool_to`) of the motions that have one.
    ToolCentre,
    /// The contour (`to`) of every motion.
    Contour,
}

/// gcodec's points of each line of the main program.
fn gcodec_points(events: &[Event], compared: Compared) -> BTreeMap<u32, Vec<Point>> {
    let mut points: BTreeMap<u32, Vec<Point>> = BTreeMap::new();
    for event in events {
        let EventKind::Motion(motion) = &event.kind else {
            continue;
        };
        if event.source.level != 0 {
            continue;
        }
        let end = match compared {
            Compared::ToolCentre => motion.tool.as_ref().map(|tool| &tool.tool_to),
            Compared::Contour => Some(&motion.to),
        };
        let Some(end) = end else { continue };
        let (Some(x), Some(y)) = (end.get("X"), end.get("Y")) else {
            continue;
        };
        points.entry(event.source.line).or_default().push(Point {
            what: motion_name(motion),
            x,
            y,
        });
    }
    points
}

fn motion_name(motion: &MotionEvent) -> String {
    match motion.inserted {
        Some(inserted) => inserted.name().to_owned(),
        // The name as the events spell it (`linear`, `arc_cw`).
        None => motion.motion.name().to_owned(),
    }
}

/// Compares the interior of `case`: `Err` with a table of every interior
/// point of both controls, the rows marked where the points differ or one
/// control has none.
fn compare(case: &Case, compared: Compared) -> Result<(), String> {
    let expected = linuxcnc_points(&linuxcnc::attribute(&case.recording));
    let actual = gcodec_points(&case.run(), compared);
    let mut table = String::new();
    let mut failed = false;
    for (number, line) in case.interior() {
        let none = Vec::new();
        let lcnc = expected.get(&number).unwrap_or(&none);
        let ours = actual.get(&line).unwrap_or(&none);
        for index in 0..lcnc.len().max(ours.len()).max(1) {
            let (a, b) = (lcnc.get(index), ours.get(index));
            let (dx, dy, ok) = match (a, b) {
                (Some(a), Some(b)) => {
                    let (dx, dy) = (b.x - a.x, b.y - a.y);
                    (
                        format!("{dx:>9.4}"),
                        format!("{dy:>9.4}"),
                        dx.abs() <= TOLERANCE && dy.abs() <= TOLERANCE,
                    )
                }
                _ => (format!("{:>9}", "-"), format!("{:>9}", "-"), false),
            };
            failed |= !ok;
            let block = format!("N{number} line {line} #{}", index + 1);
            let row = format!(
                "{block:<19} {}  {}  {dx} {dy}  {}",
                Point::show(a),
                Point::show(b),
                if ok { "" } else { "<- differs" }
            );
            writeln!(table, "{}", row.trim_end()).expect("write to a String");
        }
    }
    if failed {
        Err(format!(
            "{}: gcodec's {} points differ from LinuxCNC's by more than {TOLERANCE} mm (gcodec - LinuxCNC):\n\
             {:<19} {:<41}  {:<41}  {:>9} {:>9}\n{table}",
            case.name,
            if compared == Compared::ToolCentre {
                "tool-centre"
            } else {
                "contour"
            },
            "block",
            "LinuxCNC",
            "gcodec",
            "dX",
            "dY",
        ))
    } else {
        Ok(())
    }
}

/// Compares every case of `select`: fails with each case's table.
fn compare_all(select: impl Fn(&Case) -> bool, compared: Compared) {
    let cases: Vec<Case> = cases().into_iter().filter(|c| select(c)).collect();
    assert!(!cases.is_empty(), "no fixture of this kind");
    let failures: Vec<String> = cases
        .iter()
        .filter_map(|case| compare(case, compared).err())
        .collect();
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn fixture_pairs_line_up_and_the_markers_are_where_linuxcnc_switches() {
    for case in cases() {
        // Every N word is on the same line in both programs.
        assert_eq!(
            linuxcnc::block_numbers(&case.ngc),
            linuxcnc::block_numbers(&case.mpf),
            "{}: the .ngc and .mpf number their lines differently",
            case.name
        );
        let (approach, _) = case.marked("; approach");
        let (retract, _) = case.marked("; retract");
        assert!(
            case.interior().len() >= 2,
            "{}: an interior of one block",
            case.name
        );
        let switches: Vec<(Option<u32>, bool)> = case
            .recording
            .iter()
            .filter_map(|call| match call.what {
                CallKind::CompensationOn(_) => Some((call.reading, true)),
                CallKind::CompensationOff => Some((call.reading, false)),
                CallKind::Move(_) => None,
            })
            .collect();
        if case.compensated() {
            assert_eq!(
                switches,
                [(Some(approach), true), (Some(retract), false)],
                "{}: LinuxCNC switches compensation on and off elsewhere than at the marked lines",
                case.name
            );
        } else {
            assert!(switches.is_empty(), "{}", case.name);
        }
        // Every interior block moves in LinuxCNC: a block without a move
        // would be compared with nothing.
        let moves = linuxcnc_points(&linuxcnc::attribute(&case.recording));
        for (number, _) in case.interior() {
            assert!(
                moves.contains_key(&number),
                "{}: N{number} has no move",
                case.name
            );
        }
    }
}

#[test]
fn every_program_runs_in_gcodec_without_an_error() {
    for case in cases() {
        let events = case.run();
        assert!(
            events
                .iter()
                .any(|e| matches!(e.kind, EventKind::ProgramEnd(_))),
            "{}: the run does not reach M30",
            case.name
        );
    }
}

/// Without compensation both controls trace the programmed contour: this
/// checks the harness (reading rs274, matching blocks, the events) apart
/// from the compensation.
#[test]
fn uncompensated_contours_agree_with_linuxcnc() {
    compare_all(|case| !case.compensated(), Compared::Contour);
}

#[test]
fn compensated_tool_centres_agree_with_linuxcnc() {
    compare_all(Case::compensated, Compared::ToolCentre);
}

/// The table a failing comparison writes: each block, both points and
/// their difference, the rows that differ marked. Here gcodec's contour
/// is held against LinuxCNC's tool-centre path, which is off by the tool
/// radius and has an arc at each outside corner.
#[test]
fn a_difference_fails_with_a_table_of_the_points() {
    let cases = cases();
    let case = cases
        .iter()
        .find(|c| c.name == "square_outside_g41")
        .expect("the square fixture");
    let table = compare(case, Compared::Contour).expect_err("the contour is not the tool path");
    insta::assert_snapshot!(table);
}
