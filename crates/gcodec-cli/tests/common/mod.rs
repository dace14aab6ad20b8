//! Helpers shared by the end-to-end tests of the `gcodec` binary.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Exit codes documented in `commands.rs`.
pub const EXIT_CLEAN: i32 = 0;
pub const EXIT_DIAGNOSTICS: i32 = 1;
pub const EXIT_USAGE: i32 = 2;

/// Writes `contents` to `name` in a temporary folder of this test run
/// (one per `test`, so tests running in parallel do not meet).
pub fn temp_file(test: &str, name: &str, contents: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gcodec-cli-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, contents).expect("write");
    path
}

/// A fresh temporary folder of this test run holding `files` (`(name,
/// contents)`, names may have folders), one per `test`.
pub fn temp_tree(test: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gcodec-tree-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (name, contents) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().expect("a folder")).expect("temp dir");
        std::fs::write(path, contents).expect("write");
    }
    dir
}

/// Runs `gcodec` with `args`, as a pipe (not a terminal), with a backtrace
/// requested so that any panic would show.
pub fn gcodec<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    command(args).output().expect("gcodec runs")
}

/// [`gcodec`] run in the directory `dir`, so that the file names it
/// prints are as short as the arguments.
pub fn gcodec_in<I, S>(dir: &Path, args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    command(args)
        .current_dir(dir)
        .output()
        .expect("gcodec runs")
}

/// The `gcodec` command with `args`, for a test that sets up its own
/// stdin, stdout and stderr.
pub fn command<I, S>(args: I) -> Command
where
    I: IntoIterator<Item = S>,
    S: AsRef<std::ffi::OsStr>,
{
    let mut command = Command::new(env!("CARGO_BIN_EXE_gcodec"));
    command
        .args(args)
        .env("RUST_BACKTRACE", "1")
        .env_remove("NO_COLOR");
    command
}

pub fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).expect("stdout is UTF-8")
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8(out.stderr.clone()).expect("stderr is UTF-8")
}

pub fn code(out: &Output) -> i32 {
    out.status
        .code()
        .expect("gcodec exited normally, not by a signal")
}

/// The JSON Schema checked in as `docs/schema/SCHEMA_FILE`.
pub fn checked_in_schema(schema_file: &str) -> serde_json::Value {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../docs/schema")
        .join(schema_file);
    let text = std::fs::read_to_string(&path).expect("the schema");
    serde_json::from_str(&text).expect("the schema is JSON")
}

/// The SARIF 2.1.0 schema checked in (`docs/schema/sarif-2.1.0.json`, the
/// copy serde-sarif ships), its erratum corrected: the pattern of a
/// language tag, `^[a-zA-Z]{2}|^[a-zA-Z]{2}-[a-zA-Z]{2}]?$`, has a stray
/// `]` that makes it no regular expression a validator compiles; it means
/// `en` or `en-US`.
pub fn sarif_schema() -> serde_json::Value {
    let text = checked_in_schema("sarif-2.1.0.json").to_string().replace(
        "^[a-zA-Z]{2}|^[a-zA-Z]{2}-[a-zA-Z]{2}]?$",
        "^[a-zA-Z]{2}(-[a-zA-Z]{2})?$",
    );
    serde_json::from_str(&text).expect("still JSON")
}

/// Fails unless `instance` is valid against `schema`, listing every
/// error.
pub fn assert_fits_schema(schema: &serde_json::Value, instance: &serde_json::Value) {
    let validator = jsonschema::validator_for(schema).expect("a usable schema");
    let errors: Vec<String> = validator
        .iter_errors(instance)
        .map(|e| format!("{} at {}", e, e.instance_path()))
        .collect();
    assert!(errors.is_empty(), "not valid:\n{}", errors.join("\n"));
}
