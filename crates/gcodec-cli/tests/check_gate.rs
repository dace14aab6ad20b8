//! `gcodec check` as a gate over legacy programs: suppression comments
//! in the programs (`tests/fixtures/check-suppress/`), the baseline
//! file, and `--run` (`tests/fixtures/check-run/`).

mod common;

use std::path::{Path, PathBuf};

use common::temp_tree as tree;
use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, code, gcodec_in, stderr, stdout};

fn fixtures(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/fixtures")
        .join(name)
}

fn concise_in(dir: &Path, args: &[&str]) -> (i32, String) {
    let mut all = vec!["check", "--output-format", "concise"];
    all.extend_from_slice(args);
    let out = gcodec_in(dir, all);
    assert_eq!(stderr(&out), "", "{}", stdout(&out));
    (code(&out), stdout(&out))
}

#[test]
fn suppressions_drop_their_codes_on_their_block_or_in_the_file() {
    let (exit, text) = concise_in(&fixtures("check-suppress"), &[]);
    assert_eq!(exit, EXIT_CLEAN);
    insta::assert_snapshot!("check_suppressions_concise", text);
    let out = gcodec_in(&fixtures("check-suppress"), ["check", "blocks.mpf"]);
    insta::assert_snapshot!("check_suppressions_full", stdout(&out));
}

#[test]
fn the_suppressions_own_codes_follow_the_rule_levels() {
    let dir = fixtures("check-suppress");
    let (exit, text) = concise_in(&dir, &["--ignore", "gcodec::check::*"]);
    assert_eq!(exit, EXIT_CLEAN);
    assert!(!text.contains("gcodec::check::"), "{text}");
    let (exit, text) = concise_in(&dir, &["--deny", "warnings"]);
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    let unused: Vec<&str> = text
        .lines()
        .filter(|l| l.contains("[gcodec::check::unused_suppression]"))
        .collect();
    assert_eq!(unused.len(), 2, "{text}");
    assert!(unused.iter().all(|l| l.contains(": error[")), "{text}");
    // `--select` keeps every other code out before the suppressions
    // apply, so these suppress nothing (as ruff's `RUF100` says of
    // suppressions of codes not enabled).
    let (_, text) = concise_in(&dir, &["--select", "check::unused_suppression"]);
    assert_eq!(text.lines().count(), 5, "{text}");
}

#[test]
fn a_suppression_of_a_code_the_levels_drop_is_unused() {
    let dir = tree(
        "allowed",
        &[
            (
                "gcodec.toml",
                "[rules]\n\"lower::unknown_m_function\" = \"allow\"\n",
            ),
            (
                "a.mpf",
                "N10 M77 ; gcodec: allow(lower::unknown_m_function)\nN20 M30\n",
            ),
        ],
    );
    let (exit, text) = concise_in(&dir, &[]);
    assert_eq!(exit, EXIT_CLEAN);
    assert_eq!(
        text,
        "a.mpf:1:25: warning[gcodec::check::unused_suppression] the suppression of \
         `gcodec::lower::unknown_m_function` suppressed nothing on this block\n"
    );
}

#[test]
fn a_suppressed_error_no_longer_fails_the_check() {
    let program = "; gcodec: allow(lower::undefined_variable)\nN10 R1 = UNDEFINED_NAME\nN20 M30\n";
    let dir = tree("error", &[("a.mpf", program)]);
    assert_eq!(concise_in(&dir, &[]), (EXIT_CLEAN, String::new()));
    let dir = tree("error-kept", &[("a.mpf", &program[43..])]);
    assert_eq!(concise_in(&dir, &[]).0, EXIT_DIAGNOSTICS);
}

#[test]
fn without_run_the_run_time_errors_are_not_found() {
    assert_eq!(
        concise_in(&fixtures("check-run"), &[]),
        (EXIT_CLEAN, String::new())
    );
}

#[test]
fn run_finds_run_time_errors_in_main_programs_and_their_calls() {
    let dir = fixtures("check-run");
    let (exit, text) = concise_in(&dir, &["--run", "--max-steps", "1000"]);
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    let library = dir.join("library").canonicalize().expect("the fixtures");
    let text = text.replace(&library.display().to_string(), "[LIBRARY]");
    insta::assert_snapshot!("check_run_concise", text);
}

#[test]
fn max_steps_needs_run() {
    let out = gcodec_in(&fixtures("check-run"), ["check", "--max-steps", "5"]);
    assert_eq!(code(&out), common::EXIT_USAGE);
    assert!(stderr(&out).contains("--run"), "{}", stderr(&out));
}

/// A subprogram two programs call, which the check reads too: its
/// lowering warning is reported once, and so is its run-time error.
#[test]
fn a_called_programs_findings_are_reported_once_against_its_file() {
    let sub = "N10 M77\nN20 R3 = 5 / R1\nN30 M17\n";
    let main = "N10 R1 = 0\nN20 SUB\nN30 M30\n";
    let dir = tree(
        "called",
        &[("a.mpf", main), ("b.mpf", main), ("SUB.SPF", sub)],
    );
    let (exit, text) = concise_in(&dir, &["--run"]);
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    assert_eq!(
        text,
        "SUB.SPF:1:5: warning[gcodec::lower::unknown_m_function] M77 is not a predefined M function\n\
         SUB.SPF:2:5: error[gcodec::run::division_by_zero] `/` by zero\n"
    );
}

#[test]
fn run_findings_follow_suppressions_and_a_program_with_errors_is_not_run() {
    let dir = tree(
        "run-suppressed",
        &[
            (
                "a.mpf",
                "N10 R1 = 0\nN20 R2 = 1 / R1 ; gcodec: allow(run::division_by_zero)\nN30 M30\n",
            ),
            // A lowering error: the run's division is never reached.
            (
                "b.mpf",
                "N10 R1 = 0\nN20 R2 = 1 / R1\nN30 R3 = UNDEFINED_NAME\nN40 M30\n",
            ),
        ],
    );
    let (exit, text) = concise_in(&dir, &["--run"]);
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    assert_eq!(
        text,
        "b.mpf:3:10: error[gcodec::lower::undefined_variable] `UNDEFINED_NAME` is not defined\n"
    );
}

/// The files of the baseline fixtures, as `(name, contents)`.
fn baseline_fixtures() -> Vec<(&'static str, String)> {
    let dir = fixtures("check-baseline");
    ["gcodec.toml", "legacy/clamp.mpf", "legacy/gud.mpf"]
        .into_iter()
        .map(|name| {
            let text = std::fs::read_to_string(dir.join(name)).expect("a fixture");
            (name, text)
        })
        .collect()
}

#[test]
fn write_baseline_writes_every_finding_sorted_and_exits_0() {
    let files = baseline_fixtures();
    let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    let dir = tree("write-baseline", &files);
    let out = gcodec_in(&dir, ["check", "--write-baseline", "baseline.json"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert_eq!(stdout(&out), "");
    assert_eq!(
        stderr(&out),
        "wrote 4 findings in 3 entries to baseline.json\n"
    );
    let written = std::fs::read_to_string(dir.join("baseline.json")).expect("written");
    let checked_in = std::fs::read_to_string(fixtures("check-baseline").join("baseline.json"))
        .expect("the fixture");
    assert_eq!(written, checked_in);
}

#[test]
fn a_baseline_drops_the_findings_it_lists() {
    let out = gcodec_in(
        &fixtures("check-baseline"),
        ["check", "--baseline", "baseline.json"],
    );
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stdout(&out));
    assert_eq!(
        stdout(&out),
        "checked 2 files: 0 errors, 0 warnings, 0 advice (in 0 files)\n"
    );
    assert_eq!(
        stderr(&out),
        "4 findings matched the baseline and are not reported\n"
    );
}

/// Lines added above a known finding leave it matched; one more copy
/// of it and a new finding are reported; a fixed one is told of.
#[test]
fn only_new_findings_fail_and_fixed_entries_are_told() {
    let baseline = std::fs::read_to_string(fixtures("check-baseline").join("baseline.json"))
        .expect("the fixture");
    let clamp = "; Two clamp M functions on one line, and one more below.\n\
                 ; (a comment added)\nN10 G90\nN20 M77 M77\nN30 G0 X10\nN40 M77\nN45 M77\nN50 M30\n";
    let dir = tree(
        "new-findings",
        &[
            ("gcodec.toml", ""),
            ("baseline.json", &baseline),
            ("legacy/clamp.mpf", clamp),
            ("legacy/gud.mpf", "N10 R1 = 1\nN20 M30\n"),
            ("new.mpf", "N10 M78\nN20 M30\n"),
        ],
    );
    let (exit, text) = {
        let out = gcodec_in(
            &dir,
            [
                "check",
                "--baseline",
                "baseline.json",
                "--output-format",
                "concise",
                "--deny",
                "warnings",
            ],
        );
        assert_eq!(
            stderr(&out),
            "3 findings matched the baseline and are not reported\n\
             1 baseline entry is fixed; rewrite with --write-baseline\n"
        );
        (code(&out), stdout(&out))
    };
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    assert_eq!(
        text,
        "legacy/clamp.mpf:7:5: error[gcodec::lower::unknown_m_function] M77 is not a predefined M function\n\
         new.mpf:1:5: error[gcodec::lower::unknown_m_function] M78 is not a predefined M function\n"
    );
}

#[test]
fn a_baseline_that_is_none_is_exit_2_with_a_diagnostic() {
    let dir = fixtures("check-baseline");
    let out = gcodec_in(&dir, ["check", "--baseline", "bad_baseline.json"]);
    assert_eq!(code(&out), common::EXIT_USAGE);
    assert_eq!(stdout(&out), "");
    insta::assert_snapshot!("check_bad_baseline", stderr(&out));
    let out = gcodec_in(&dir, ["check", "--baseline", "missing.json"]);
    assert_eq!(code(&out), common::EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::io::read"),
        "{}",
        stderr(&out)
    );
    let out = gcodec_in(
        &dir,
        [
            "check",
            "--baseline",
            "baseline.json",
            "--write-baseline",
            "b.json",
        ],
    );
    assert_eq!(code(&out), common::EXIT_USAGE);
}
