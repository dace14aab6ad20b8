//! `gcodec check`: the fixture tree `tests/fixtures/check/` (a clean
//! program, one with a lowering error, one with a warning, a definition
//! file, a folder its `gcodec.toml` assigns the lathe profile, and files
//! that are never checked) in each output format; exit codes; unreadable
//! files; bad configurations; rule levels and the command line's choice
//! of codes; the corpus checked with the configuration kept for it.

mod common;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Stdio;

use common::temp_tree as tree;
use common::{
    EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, assert_fits_schema, checked_in_schema, code, command,
    gcodec, gcodec_in, sarif_schema, stderr, stdout,
};
use serde_json::Value as Json;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/check")
}

const CLEAN: &str = "N10 G90\nN20 G0 X10\nN30 M30\n";
const ERROR: &str = "N10 R1 = UNDEFINED_NAME\nN20 M30\n";
const WARNING: &str = "N10 M77\nN20 M30\n";

#[test]
fn full_output_groups_the_reports_per_file_then_sums_up() {
    let out = gcodec_in(&fixtures(), ["check"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{}", stderr(&out));
    assert_eq!(stderr(&out), "");
    insta::assert_snapshot!("check_full", stdout(&out));
}

#[test]
fn concise_output_is_one_line_per_diagnostic() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "concise"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    insta::assert_snapshot!("check_concise", stdout(&out));
}

#[test]
fn json_output_is_an_array_of_diagnostics_as_data() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "json"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let records: Json = serde_json::from_str(&stdout(&out)).expect("JSON");
    let first = &records[0];
    assert_eq!(first["file"], "lowering_error.mpf");
    assert_eq!(
        (first["line"].clone(), first["column"].clone()),
        (3.into(), 10.into())
    );
    insta::assert_snapshot!("check_json", stdout(&out));
}

#[test]
fn statistics_count_by_code() {
    let out = gcodec_in(&fixtures(), ["check", "--statistics"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    insta::assert_snapshot!("check_statistics", stdout(&out));
}

#[test]
fn hidden_excluded_and_other_files_are_not_checked() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "json"]);
    let text = stdout(&out);
    assert!(
        !text.contains("skipped.mpf") && !text.contains("notes.txt"),
        "{text}"
    );
    let full = gcodec_in(&fixtures(), ["check"]);
    assert!(
        stdout(&full).contains("checked 5 files:"),
        "{}",
        stdout(&full)
    );
}

#[test]
fn a_clean_file_exits_0() {
    let out = gcodec_in(&fixtures(), ["check", "clean.mpf", "MGUD.DEF"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stdout(&out));
    assert_eq!(
        stdout(&out),
        "checked 2 files: 0 errors, 0 warnings, 0 advice (in 0 files)\n"
    );
}

#[test]
fn the_configuration_assigns_a_folder_its_profile_and_definitions() {
    let assigned = gcodec_in(&fixtures(), ["check", "lathe", "clean.mpf"]);
    assert_eq!(code(&assigned), EXIT_CLEAN, "{}", stdout(&assigned));
    // With a configuration that assigns nothing, the lathe program is
    // checked on the built-in profile and SAFE_Z is not defined.
    let empty = tree("no_assignment", &[("gcodec.toml", "")]);
    let config = empty.join("gcodec.toml");
    let out = gcodec_in(
        &fixtures(),
        [
            "check".as_ref(),
            "--config".as_ref(),
            config.as_os_str(),
            "lathe".as_ref(),
            "clean.mpf".as_ref(),
            "--output-format".as_ref(),
            "concise".as_ref(),
        ],
    );
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let text = stdout(&out);
    assert!(
        text.contains("lathe/shaft.mpf:3:17: error[gcodec::lower::no_transverse_axis]"),
        "{text}"
    );
    assert!(
        text.contains("clean.mpf:5:16: error[gcodec::lower::undefined_variable]"),
        "{text}"
    );
}

#[test]
fn the_configuration_is_found_upward_from_the_path_checked() {
    let out = gcodec_in(&fixtures().join("lathe"), ["check", "shaft.mpf"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stdout(&out));
    let out = gcodec_in(&fixtures().join("lathe"), ["check"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stdout(&out));
}

#[test]
fn an_unreadable_file_is_a_diagnostic_and_the_check_goes_on() {
    let dir = tree("unreadable", &[("a.mpf", CLEAN), ("c.mpf", ERROR)]);
    std::os::unix::fs::symlink(dir.join("nowhere"), dir.join("b.mpf")).expect("symlink");
    let out = gcodec_in(&dir, ["check", "--output-format", "concise"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let text = stdout(&out);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 2, "{text}");
    assert!(
        lines[0].starts_with("b.mpf: error[gcodec::io::read] cannot read `b.mpf`: "),
        "{text}"
    );
    assert!(
        lines[1].starts_with("c.mpf:1:10: error[gcodec::lower::undefined_variable]"),
        "{text}"
    );
}

#[test]
fn a_path_that_does_not_exist_is_exit_2() {
    let out = gcodec_in(&fixtures(), ["check", "no_such_folder"]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("gcodec::io::read"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_bad_configuration_is_a_diagnostic_into_it_and_exit_2() {
    let cases = [
        (
            "[rulez]\n",
            "gcodec::config::schema",
            "unknown field `rulez`",
        ),
        (
            "include = [\n",
            "gcodec::config::syntax",
            "invalid check configuration",
        ),
        (
            "[rules]\n\"lower::unknown_m_functon\" = \"deny\"\n",
            "gcodec::config::unknown_code",
            "did you mean `gcodec::lower::unknown_m_function`?",
        ),
        (
            "[rules]\n\"gcodec::lower::*\" = \"loud\"\n",
            "gcodec::config::schema",
            "unknown variant `loud`",
        ),
        (
            "exclude = [\"a/[b\"]\n",
            "gcodec::config::bad_glob",
            "is not a glob",
        ),
        (
            "[[files]]\nglob = \"*.mpf\"\nprofile = \"missing.toml\"\n",
            "gcodec::config::unusable_file",
            "missing.toml` cannot be read",
        ),
    ];
    for (i, (config, expected_code, message)) in cases.iter().enumerate() {
        let dir = tree(
            &format!("bad_config_{i}"),
            &[("gcodec.toml", config), ("a.mpf", CLEAN)],
        );
        let out = gcodec_in(&dir, ["check"]);
        let text = stderr(&out);
        assert_eq!(code(&out), EXIT_USAGE, "{config}: {text}");
        assert!(
            text.contains(expected_code) && text.contains(message),
            "{config}: {text}"
        );
        assert!(
            text.contains("gcodec.toml"),
            "{config}: the report names the file: {text}"
        );
        assert_eq!(stdout(&out), "", "{config}");
    }
}

#[test]
fn a_profile_with_errors_is_reported_against_itself_and_the_configuration() {
    let dir = tree(
        "bad_profile",
        &[
            (
                "gcodec.toml",
                "[[files]]\nglob = \"*.mpf\"\nprofile = \"bad.toml\"\n",
            ),
            ("bad.toml", "[machine]\nnmae = \"x\"\n"),
            ("a.mpf", CLEAN),
        ],
    );
    let out = gcodec_in(&dir, ["check"]);
    assert_eq!(code(&out), EXIT_USAGE);
    let text = stderr(&out);
    assert!(text.contains("gcodec::config::unusable_file"), "{text}");
    assert!(
        text.contains("gcodec::profile::schema") && text.contains("bad.toml"),
        "{text}"
    );
}

#[test]
fn rule_levels_and_per_file_ignores_of_the_configuration_apply() {
    let config = "[rules]\n\"gcodec::lower::unknown_m_function\" = \"deny\"\n\
                  \"gcodec::lower::*\" = \"allow\"\n\n\
                  [[files]]\nglob = \"legacy/**\"\nignore = [\"lower::unknown_m_function\"]\n";
    let dir = tree(
        "rules",
        &[
            ("gcodec.toml", config),
            ("error.mpf", ERROR),
            ("warning.mpf", WARNING),
            ("legacy/warning.mpf", WARNING),
        ],
    );
    let out = gcodec_in(&dir, ["check", "--output-format", "concise"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert_eq!(
        stdout(&out),
        "warning.mpf:1:5: error[gcodec::lower::unknown_m_function] M77 is not a predefined M function\n"
    );
}

#[test]
fn select_ignore_and_deny_warnings_choose_the_diagnostics() {
    let concise = |args: &[&str]| {
        let mut all = vec!["check", "--output-format", "concise"];
        all.extend_from_slice(args);
        let out = gcodec_in(&fixtures(), all);
        (code(&out), stdout(&out))
    };
    let (exit, text) = concise(&["--select", "lower::unknown_m_function"]);
    assert_eq!(exit, EXIT_CLEAN);
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(text.starts_with("warning.mpf:3:5: warning["), "{text}");
    let (exit, text) = concise(&["--ignore", "gcodec::lower::*"]);
    assert_eq!((exit, text.as_str()), (EXIT_CLEAN, ""));
    let (exit, text) = concise(&["warning.mpf", "--deny", "warnings"]);
    assert_eq!(exit, EXIT_DIAGNOSTICS);
    assert!(
        text.starts_with("warning.mpf:3:5: error[gcodec::lower::unknown_m_function]"),
        "{text}"
    );
    let (exit, text) = concise(&[
        "--select",
        "gcodec::lower::undefined_variable,gcodec::lower::unknown_m_function",
        "--ignore",
        "lower::undefined_variable",
    ]);
    assert_eq!(exit, EXIT_CLEAN);
    assert_eq!(text.lines().count(), 1, "{text}");
}

#[test]
fn a_code_the_registry_lacks_is_a_usage_error_with_the_code_meant() {
    let out = gcodec_in(
        &fixtures(),
        ["check", "--select", "lower::unknown_m_functon"],
    );
    assert_eq!(code(&out), EXIT_USAGE);
    let text = stderr(&out);
    assert!(
        text.contains("did you mean `gcodec::lower::unknown_m_function`?"),
        "{text}"
    );
}

#[test]
fn standard_input_is_checked_under_its_stdin_filename() {
    let shaft = std::fs::read(fixtures().join("lathe/shaft.mpf")).expect("fixture");
    let run = |name: &str| {
        let mut child = command([
            "check",
            "-",
            "--stdin-filename",
            name,
            "--output-format",
            "concise",
        ])
        .current_dir(fixtures())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("gcodec runs");
        child
            .stdin
            .take()
            .expect("stdin")
            .write_all(&shaft)
            .expect("write");
        child.wait_with_output().expect("gcodec ends")
    };
    let assigned = run("lathe/piped.mpf");
    assert_eq!(code(&assigned), EXIT_CLEAN, "{}", stdout(&assigned));
    let elsewhere = run("piped.mpf");
    assert_eq!(code(&elsewhere), EXIT_DIAGNOSTICS);
    assert!(
        stdout(&elsewhere).starts_with("piped.mpf:3:17: error[gcodec::lower::no_transverse_axis]")
    );
}

#[test]
fn check_help_says_explain_explains_every_code() {
    let out = gcodec(["check", "--help"]);
    assert_eq!(code(&out), EXIT_CLEAN);
    assert!(
        stdout(&out).contains("`gcodec explain CODE`"),
        "{}",
        stdout(&out)
    );
}

/// Fails when `docs/schema/check.schema.json` is stale.
#[test]
fn the_checked_in_schema_is_current() {
    gcodec_testkit::assert_schema_current(
        "check.schema.json",
        &gcodec_driver::check::check_json_schema(),
        "cargo test -p gcodec-cli --test check",
    );
}

/// The JSON output is valid against its checked-in schema.
#[test]
fn the_json_output_fits_the_schema() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "json"]);
    let records: Json = serde_json::from_str(&stdout(&out)).expect("JSON");
    assert!(!records.as_array().expect("an array").is_empty());
    assert_fits_schema(&checked_in_schema("check.schema.json"), &records);
}

/// The SARIF output is one SARIF 2.1.0 log, valid against the standard's
/// schema: the codes that occur as rules with their help, a result per
/// diagnostic with its place, secondary labels as related locations.
#[test]
fn sarif_output_is_a_sarif_log_valid_against_its_schema() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "sarif"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{}", stderr(&out));
    let log: Json = serde_json::from_str(&stdout(&out)).expect("JSON");
    assert_fits_schema(&sarif_schema(), &log);
    let run = &log["runs"][0];
    assert_eq!(run["columnKind"], "unicodeCodePoints");
    let rules = run["tool"]["driver"]["rules"].as_array().expect("rules");
    let results = run["results"].as_array().expect("results");
    let json = gcodec_in(&fixtures(), ["check", "--output-format", "json"]);
    let records: Json = serde_json::from_str(&stdout(&json)).expect("JSON");
    assert_eq!(results.len(), records.as_array().expect("array").len());
    for (result, record) in results.iter().zip(records.as_array().expect("array")) {
        let index = result["ruleIndex"].as_u64().expect("an index") as usize;
        assert_eq!(rules[index]["id"], result["ruleId"]);
        assert_eq!(result["ruleId"], record["code"]);
        let place = &result["locations"][0]["physicalLocation"];
        assert_eq!(place["artifactLocation"]["uri"], record["file"]);
        assert_eq!(place["region"]["startLine"], record["line"]);
        assert_eq!(place["region"]["startColumn"], record["column"]);
        assert_eq!(place["region"]["endColumn"], record["end_column"]);
    }
    assert!(rules.iter().all(|rule| {
        rule["help"]["markdown"]
            .as_str()
            .is_some_and(|h| !h.is_empty())
            && rule["defaultConfiguration"]["level"].is_string()
    }));
    let text = stdout(&out).replace(env!("CARGO_PKG_VERSION"), "[VERSION]");
    insta::assert_snapshot!("check_sarif", text);
}

/// A diagnostic with a second label (a duplicate block number points at
/// the first block) gives the result a related location; a file that
/// cannot be read gives one without a region. Still a valid log.
#[test]
fn sarif_results_carry_related_locations_and_places_without_regions() {
    let dir = tree(
        "sarif-related",
        &[
            ("twice.mpf", "N10 G0 X1 F100\nN10 G1 X2\nM30\n"),
            ("sub dir/ä.mpf", WARNING),
        ],
    );
    std::os::unix::fs::symlink(dir.join("nowhere.mpf"), dir.join("dangling.mpf")).expect("link");
    let out = gcodec_in(&dir, ["check", "--output-format", "sarif"]);
    let log: Json = serde_json::from_str(&stdout(&out)).expect("JSON");
    assert_fits_schema(&sarif_schema(), &log);
    let results = log["runs"][0]["results"].as_array().expect("results");
    let unreadable = results
        .iter()
        .find(|r| {
            r["locations"][0]["physicalLocation"]["artifactLocation"]["uri"] == "dangling.mpf"
        })
        .expect("the dangling link's result");
    assert!(unreadable["locations"][0]["physicalLocation"]["region"].is_null());
    let duplicate = results
        .iter()
        .find(|r| r["ruleId"] == "gcodec::lint::duplicate_block_number")
        .expect("a duplicate block number");
    let related = &duplicate["relatedLocations"][0];
    assert_eq!(related["physicalLocation"]["region"]["startLine"], 1);
    assert_eq!(related["id"], 1);
    assert!(
        stdout(&out).contains("\"uri\": \"sub%20dir/%C3%A4.mpf\""),
        "{}",
        stdout(&out)
    );
}

/// The acceptance of `gcodec check`: the shared corpus checked with the
/// configuration kept for it (`tests/corpus-check/gcodec.toml`, which
/// assigns each folder its machine's profile and definition files as the
/// corpus tests do) reports no error but the corpus's expected ones, and
/// each of those.
#[test]
fn the_corpus_checks_with_only_its_expected_errors() {
    let Some(corpus) = gcodec_testkit::corpus_dir() else {
        return;
    };
    let corpus = std::path::absolute(corpus).expect("a path");
    let repo = std::path::absolute(gcodec_testkit::repo()).expect("a path");
    // The configuration is written for the corpus beside the checkout
    // (`../shared/corpus`, as CI has it); that layout is made of links in
    // a folder of this run, for a checkout that is elsewhere.
    let layout = tree("corpus_layout", &[]);
    let checkout = layout.join("gcodec");
    let kept = checkout.join("tests/corpus-check");
    std::fs::create_dir_all(layout.join("shared")).expect("temp dir");
    std::fs::create_dir_all(&kept).expect("temp dir");
    let link = |from: &Path, to: &Path| std::os::unix::fs::symlink(from, to).expect("symlink");
    link(&corpus, &layout.join("shared/corpus"));
    link(&repo.join("profiles"), &checkout.join("profiles"));
    for entry in std::fs::read_dir(repo.join("tests/corpus-check")).expect("kept folder") {
        let entry = entry.expect("an entry");
        link(&entry.path(), &kept.join(entry.file_name()));
    }
    let out = gcodec_in(
        &checkout,
        [
            "check",
            "--config",
            "tests/corpus-check/gcodec.toml",
            "../shared/corpus",
            "--output-format",
            "json",
        ],
    );
    assert!(
        [EXIT_CLEAN, EXIT_DIAGNOSTICS].contains(&code(&out)),
        "{}",
        stderr(&out)
    );
    assert_eq!(
        stderr(&out),
        "",
        "no panic, no problem with the configuration"
    );
    let records: Json = serde_json::from_str(&stdout(&out)).expect("JSON");
    let expected: Vec<_> = gcodec_testkit::corpus::EXPECTED_PARSE_ERRORS
        .iter()
        .chain(gcodec_testkit::corpus::EXPECTED_LOWERING_ERRORS)
        .collect();
    let mut seen = vec![false; expected.len()];
    let mut unexpected = Vec::new();
    let records = records.as_array().expect("an array");
    assert!(
        records.len() >= expected.len(),
        "the corpus was checked: {records:?}"
    );
    for record in records {
        if record["level"] != "error" {
            continue;
        }
        let (file, line, code) = (
            record["file"].as_str().unwrap_or(""),
            record["line"].as_u64().unwrap_or(0),
            record["code"].as_str().unwrap_or(""),
        );
        match expected.iter().position(|(part, l, c)| {
            file.contains(part) && u64::from(*l) == line && c.name() == code
        }) {
            Some(i) => seen[i] = true,
            None => unexpected.push(format!("{file}:{line}: {code} {}", record["message"])),
        }
    }
    for (seen, (file, line, code)) in seen.iter().zip(&expected) {
        if !seen {
            unexpected.push(format!("{file}:{line}: expected {code}, not reported"));
        }
    }
    assert!(unexpected.is_empty(), "{}", unexpected.join("\n"));
}

#[test]
fn github_output_is_one_workflow_command_per_diagnostic() {
    let out = gcodec_in(&fixtures(), ["check", "--output-format", "github"]);
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    let text = stdout(&out);
    assert!(
        text.lines()
            .all(|l| l.starts_with("::error file=") || l.starts_with("::warning file=")),
        "{text}"
    );
    assert!(
        text.contains("::error file=lowering_error.mpf,line=3,col=10,"),
        "{text}"
    );
    // The code is the title; its `:` are escaped, as GitHub reads them.
    assert!(text.contains(",title=gcodec%3A%3Alower%3A%3A"), "{text}");
    insta::assert_snapshot!("check_github", text);
}

#[test]
fn a_stdin_filename_without_the_path_dash_is_a_usage_error() {
    let out = gcodec_in(
        &fixtures(),
        ["check", "--stdin-filename", "A.MPF", "clean.mpf"],
    );
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("`--stdin-filename`"),
        "{}",
        stderr(&out)
    );
}
