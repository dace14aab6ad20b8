//! `--output-format` of `gcodec lower` and `gcodec run`: `full` (the
//! default) renders on stderr as before; the data formats write one
//! document of every diagnostic on stderr after the command, alone
//! there, with each diagnostic against the file it is in (a called
//! subprogram's run-time diagnostics against the subprogram).

mod common;

use std::path::PathBuf;

use common::{
    EXIT_CLEAN, assert_fits_schema, checked_in_schema, code, gcodec_in, sarif_schema, stderr,
    stdout,
};
use serde_json::Value as Json;

/// A main program with a lowering warning that calls a subprogram with a
/// run-time warning.
fn programs(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gcodec-formats-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("MAIN.MPF"), "N5 M77\nN10 SUBA\nN20 M30\n").expect("write");
    std::fs::write(dir.join("SUBA.SPF"), "N10 G1 X10\nN20 M17\n").expect("write");
    dir
}

#[test]
fn lower_writes_json_diagnostics_on_stderr_and_the_listing_on_stdout() {
    let dir = programs("lower-json");
    let out = gcodec_in(&dir, ["lower", "MAIN.MPF", "--output-format", "json"]);
    assert_eq!(code(&out), EXIT_CLEAN);
    assert!(stdout(&out).contains("M77"), "{}", stdout(&out));
    let records: Json = serde_json::from_str(&stderr(&out)).expect("stderr is the JSON alone");
    assert_fits_schema(&checked_in_schema("check.schema.json"), &records);
    insta::assert_snapshot!("lower_json", stderr(&out));
}

#[test]
fn lower_full_is_the_default_rendering() {
    let dir = programs("lower-full");
    let default = gcodec_in(&dir, ["lower", "MAIN.MPF"]);
    let full = gcodec_in(&dir, ["lower", "MAIN.MPF", "--output-format", "full"]);
    assert_eq!(stderr(&default), stderr(&full));
    assert!(stderr(&default).contains("M77 is not a predefined M function"));
}

#[test]
fn run_reports_each_diagnostic_against_its_own_file() {
    let dir = programs("run-concise");
    let out = gcodec_in(&dir, ["run", "MAIN.MPF", "--output-format", "concise"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    // The event stream is on stdout as before, the diagnostics among it.
    assert!(stdout(&out).contains("\"gcodec::run::no_feed\""));
    insta::assert_snapshot!("run_concise", stderr(&out));
}

#[test]
fn run_writes_a_valid_sarif_log_with_the_subprograms_file() {
    let dir = programs("run-sarif");
    let out = gcodec_in(&dir, ["run", "MAIN.MPF", "--output-format", "sarif"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let log: Json = serde_json::from_str(&stderr(&out)).expect("stderr is the log alone");
    assert_fits_schema(&sarif_schema(), &log);
    let results = log["runs"][0]["results"].as_array().expect("results");
    let uri_of = |rule: &str| {
        let result = results
            .iter()
            .find(|r| r["ruleId"] == rule)
            .unwrap_or_else(|| panic!("{rule} in {log}"));
        result["locations"][0]["physicalLocation"]["artifactLocation"]["uri"].clone()
    };
    assert_eq!(uri_of("gcodec::run::no_feed"), "SUBA.SPF");
    assert_eq!(uri_of("gcodec::lower::unknown_m_function"), "MAIN.MPF");
}

#[test]
fn a_run_that_cannot_start_reports_in_the_format_chosen() {
    let dir = programs("run-missing");
    let out = gcodec_in(&dir, ["run", "GONE.MPF", "--output-format", "json"]);
    assert_eq!(code(&out), common::EXIT_USAGE);
    let records: Json = serde_json::from_str(&stderr(&out)).expect("stderr is the JSON alone");
    assert_eq!(records[0]["file"], "GONE.MPF");
    assert_eq!(records[0]["code"], "gcodec::io::read");
}
