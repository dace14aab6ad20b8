//! `gcodec lower` and `gcodec run` read `gcodec.toml` as `gcodec check`
//! does (`tests/fixtures/program-config/`): found upward from the
//! program or named with `--config`, its `[[files]]` give the profile
//! unless the command line names one, its `search_paths` are searched
//! for subprograms, its rule levels and ignores apply.

mod common;

use std::path::{Path, PathBuf};

use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec_in, stderr, stdout};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/program-config")
}

#[test]
fn the_configuration_assigns_the_programs_profile() {
    let out = gcodec_in(&fixtures(), ["lower", "lathe/turn.mpf"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert_eq!(stderr(&out), "");
}

#[test]
fn the_command_lines_profile_wins_over_the_configurations() {
    let out = gcodec_in(
        &fixtures(),
        [
            "lower",
            "lathe/turn.mpf",
            "--profile",
            "../../../profiles/default.toml",
            "--output-format",
            "concise",
        ],
    );
    assert_eq!(code(&out), EXIT_DIAGNOSTICS);
    assert!(
        stderr(&out).contains("error[gcodec::lower::no_transverse_axis]"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn rule_levels_and_a_files_ignores_apply() {
    let denied = gcodec_in(
        &fixtures(),
        ["lower", "m77.mpf", "--output-format", "concise"],
    );
    assert_eq!(code(&denied), EXIT_DIAGNOSTICS);
    insta::assert_snapshot!("program_config_denied", stderr(&denied));
    let quiet = gcodec_in(&fixtures(), ["lower", "quiet.mpf"]);
    assert_eq!(code(&quiet), EXIT_CLEAN);
    assert_eq!(stderr(&quiet), "");
    let run = gcodec_in(
        &fixtures(),
        ["run", "m77.mpf", "--output-format", "concise"],
    );
    assert_eq!(code(&run), EXIT_DIAGNOSTICS);
    assert_eq!(stderr(&run), stderr(&denied));
}

#[test]
fn run_finds_subprograms_on_the_configurations_search_paths() {
    let out = gcodec_in(&fixtures(), ["run", "lathe/turn.mpf", "--format", "text"]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stdout(&out).contains("return CYC1"), "{}", stdout(&out));
}

#[test]
fn a_named_configuration_replaces_the_one_found() {
    let dir = std::env::temp_dir().join(format!("gcodec-program-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let empty = dir.join("gcodec.toml");
    std::fs::write(&empty, "").expect("write");
    let config = empty.to_str().expect("UTF-8");
    let out = gcodec_in(&fixtures(), ["lower", "m77.mpf", "--config", config]);
    // At its own level, a warning: exit 0.
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert!(stderr(&out).contains("M77 is not a predefined M function"));
    std::fs::write(&empty, "unknown_key = 1\n").expect("write");
    let bad = gcodec_in(
        &fixtures(),
        [
            "run",
            "m77.mpf",
            "--config",
            config,
            "--output-format",
            "json",
        ],
    );
    assert_eq!(code(&bad), EXIT_USAGE);
    let records: serde_json::Value = serde_json::from_str(&stderr(&bad)).expect("JSON");
    assert_eq!(records[0]["code"], "gcodec::config::schema");
}
