//! Every main program of the shared corpus runs to its end, or to a
//! clearly diagnosed external dependency: a subprogram or cycle that is
//! not in the corpus, a variable of the machine the corpus does not hold
//! (its other GUD files, the measuring cycles' results). Nothing else may
//! stop a run, and nothing may panic. The end of every run is a snapshot,
//! so a change in how far a program gets is seen in review.
//!
//! Programs run with the machine they were written for (the mapping of
//! the lowering corpus test), `M0` does not stop (`--no-stop`), and the
//! corpus's subprogram directories are on the search path.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_driver::SearchPath;
use gcodec_exec::channel::RunOptions;
use gcodec_exec::event::{CountingSink, Event, EventKind, EventSink, ProgramEndReason};
use gcodec_source::{Severity, SourceFile};
use gcodec_testkit::corpus::{definitions, machine_profile};
use gcodec_testkit::{corpus_dir, programs};

mod common;

use common::runs::{RunSetup, compile_main, run_main};

/// What may end a run early: what lies outside the corpus.
const EXTERNAL: &[&str] = &[
    "gcodec::run::cycle_alarm",
    "gcodec::run::program_not_found",
    "gcodec::run::system_variable",
    "gcodec::run::undefined_variable",
];

/// Runs that stop on an error of the program itself, with the reason it
/// is the program's: program, code.
const STOPS_IN_THE_PROGRAM: &[(&str, &str)] = &[
    // `PROC CYCLE32(REAL VELO, INT DIR)` run as a main program: its
    // parameters take their defaults, and `M1=DIR` with `DIR=0` is `M1=0`,
    // the program stop with an extension the control rejects.
    (
        "real/deathaxe+sublime-s840d/example.mpf",
        "gcodec::run::m_extension_forbidden",
    ),
    // `SETAL(12345)` in a test of the CEAD interpreter, which passes over
    // the call: on the control the alarm ends the run
    // (`gcodec_testkit::peer::REJECTIONS`).
    ("peer-cead/function_calls.mpf", "gcodec::run::cycle_alarm"),
];

/// Keeps the last error diagnostic and counts the rest.
#[derive(Default)]
struct Outcome {
    counts: CountingSink,
    last_error: Option<(String, u32, String)>,
}

impl EventSink for Outcome {
    fn event(&mut self, event: &Event) -> std::io::Result<()> {
        if let EventKind::Diagnostic(d) = &event.kind
            && d.severity == Severity::Error
        {
            self.last_error = Some((d.code.to_string(), event.source.line, d.message.to_string()));
        }
        self.counts.event(event)
    }
}

/// The directories of the corpus that hold subprograms and cycles.
fn subprogram_dirs(corpus: &Path) -> Vec<PathBuf> {
    let mut dirs = Vec::new();
    for path in programs(corpus) {
        let spf = path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("spf"));
        if let (true, Some(dir)) = (spf, path.parent())
            && !dirs.iter().any(|d: &PathBuf| d == dir)
        {
            dirs.push(dir.to_path_buf());
        }
    }
    dirs.sort();
    dirs
}

#[test]
fn every_main_program_runs_to_its_end_or_a_diagnosed_dependency() {
    let Some(corpus) = corpus_dir() else {
        return;
    };
    let dirs = subprogram_dirs(&corpus);
    let mains: Vec<PathBuf> = programs(&corpus)
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("mpf")))
        .collect();
    assert!(
        mains.len() >= 40,
        "found only {} main programs",
        mains.len()
    );
    let mut report = String::new();
    let mut failures = Vec::new();
    for path in &mains {
        let shown = gcodec_testkit::shown(&corpus, path);
        let profile = Arc::new(machine_profile(&shown).1);
        let definitions = Arc::new(definitions(&corpus, &shown));
        let file = Arc::new(SourceFile::new(
            shown.clone(),
            std::fs::read(path).expect("read"),
        ));
        let main = compile_main(&file, &profile, &definitions);
        if main.has_errors {
            // Errors the lowering test expects (`EXPECTED_LOWERING_ERRORS`,
            // `EXPECTED_PARSE_ERRORS`), listed there with their reasons.
            report.push_str(&format!("{shown}: not run (lowering errors)\n"));
            continue;
        }
        let mut options = RunOptions::for_profile(&profile);
        options.stop_at_m0 = false;
        options.max_steps = 200_000;
        let run = RunSetup {
            profile,
            options,
            definitions,
            search: SearchPath::new().with_dirs(dirs.iter().cloned()),
        };
        let mut sink = Outcome::default();
        // Runs resolve relative to the corpus: the main program's file name
        // is shown relative to it.
        let outcome = with_dir(&corpus, || run_main(main.program, run, &mut sink, None));
        let end = match (&outcome.reason, &sink.last_error) {
            (ProgramEndReason::Alarm, Some((code, line, message))) => {
                let in_program = STOPS_IN_THE_PROGRAM.contains(&(shown.as_str(), code.as_str()));
                if !EXTERNAL.contains(&code.as_str()) && !in_program {
                    failures.push(format!("{shown}:{line}: {code}: {message}"));
                }
                format!("alarm {code} at line {line}")
            }
            (reason, _) => format!("{reason:?}"),
        };
        report.push_str(&format!(
            "{shown}: {end}, {} blocks\n",
            outcome.summary.blocks
        ));
    }
    assert!(
        failures.is_empty(),
        "runs stopped for reasons inside the corpus:\n{}",
        failures.join("\n")
    );
    insta::assert_snapshot!(report);
}

/// Runs `f` with the current directory set to `dir` (the loader resolves
/// the caller's directory from the file name).
fn with_dir<R>(dir: &Path, f: impl FnOnce() -> R) -> R {
    let previous = std::env::current_dir().expect("current dir");
    std::env::set_current_dir(dir).expect("corpus dir");
    let result = f();
    std::env::set_current_dir(previous).expect("back");
    result
}
