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
