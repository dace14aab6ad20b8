//! Every command's output when it cannot be written: a closed pipe on
//! stdout ends the command quietly with exit 0; stdout on a full disk is
//! `gcodec::io::write` and exit 2; stderr that cannot be written is exit
//! 2 without a word. None of them panics.

mod common;

use std::fs::File;
use std::process::{Output, Stdio};

use common::*;

/// A command of each family, with a program that makes them write to
/// both stdout and stderr where they can (written for `test` alone: the
/// tests run at once).
fn commands(test: &str) -> Vec<Vec<String>> {
    // A block with a syntax error, which the run stops at: a diagnostic
    // on stderr after the tree, the listing or the first events.
    let program = temp_file(test, "BAD.MPF", "N10 G0 X10 Y10\nN20 X=\nN30 M30\n");
    let program = program.display().to_string();
    let with = |args: &[&str]| {
        args.iter()
            .map(|a| a.replace("PROGRAM", &program))
            .collect::<Vec<_>>()
    };
    vec![
        with(&["parse", "PROGRAM"]),
        with(&["parse", "--format", "json", "PROGRAM"]),
        with(&["lower", "PROGRAM"]),
        with(&["lower", "--format", "json", "PROGRAM"]),
        with(&["run", "PROGRAM"]),
        with(&["run", "--format", "text", "PROGRAM"]),
        with(&["run", "--format", "csv", "PROGRAM"]),
        with(&["profile", "show"]),
        with(&["profile", "show", "--format", "json"]),
        with(&["explain", "--list"]),
        with(&["explain", "invalid_word"]),
        with(&["--help"]),
    ]
}

fn dev_full() -> File {
    File::options()
        .write(true)
        .open("/dev/full")
        .expect("/dev/full")
}

/// A pipe whose reading end is closed before `gcodec` starts, so that
/// its first write fails, however little it writes.
fn closed_pipe() -> std::io::PipeWriter {
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    writer
}

/// Runs `gcodec` with `args` and its stdout on `stdout`; it must not
/// panic.
fn with_stdout(args: &[String], stdout: impl Into<Stdio>) -> Output {
    let out = command(args).stdout(stdout).output().expect("gcodec runs");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !err.contains("panicked") && out.status.code().is_some(),
        "{args:?} panicked: {err}"
    );
    out
}

#[test]
fn a_closed_stdout_pipe_ends_every_command_quietly_with_0() {
    for args in commands("closed-stdout") {
        let out = with_stdout(&args, closed_pipe());
        assert_eq!(code(&out), EXIT_CLEAN, "{args:?}: {}", stderr(&out));
        assert!(
            !stderr(&out).contains("gcodec::io::write"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

#[test]
fn stdout_on_a_full_disk_is_io_write_and_exit_2() {
    for args in commands("full-stdout") {
        let out = with_stdout(&args, dev_full());
        assert_eq!(code(&out), EXIT_USAGE, "{args:?}");
        let err = stderr(&out);
        assert_eq!(
            err.matches("gcodec::io::write").count(),
            1,
            "{args:?}: {err}"
        );
    }
}

/// Every command that writes to stderr exits 2 when it cannot; one that
/// writes nothing there keeps its exit code.
#[test]
fn stderr_that_cannot_be_written_is_exit_2() {
    for args in commands("failed-stderr") {
        let written = command(&args)
            .stdout(Stdio::null())
            .output()
            .expect("gcodec runs");
        let expected = if written.stderr.is_empty() {
            code(&written)
        } else {
            EXIT_USAGE
        };
        for stderr in [Stdio::from(dev_full()), Stdio::from(closed_pipe())] {
            let out = command(&args)
                .stdout(Stdio::null())
                .stderr(stderr)
                .output()
                .expect("gcodec runs");
            assert_eq!(code(&out), expected, "{args:?}");
        }
    }
}

/// The commands above that write to stderr at all: the test above would
/// prove nothing if none did.
#[test]
fn the_program_writes_to_stderr_in_parse_lower_and_run() {
    for args in commands("stderr-written")
        .iter()
        .filter(|a| ["parse", "lower", "run"].contains(&&*a[0]))
    {
        let out = command(args)
            .stdout(Stdio::null())
            .output()
            .expect("gcodec runs");
        assert!(!out.stderr.is_empty(), "{args:?} wrote nothing to stderr");
    }
}

/// ESC and BEL from a program's string are escaped in every text format
/// (the syntax tree, the listing, the run's trace) and in the diagnostics
/// that quote them, and written exactly by the JSON formats (as JSON's
/// `\u001b` escapes).
#[test]
fn control_characters_are_escaped_in_text_and_exact_in_json() {
    let program = temp_file(
        "escapes",
        "TITLE\u{1b}.MPF",
        "MSG(\"a\u{1b}]0;title\u{7}b\")\nN20 X1 ?\nM30\n",
    );
    let program = program.display().to_string();
    let shown = "a\\x1b]0;title\\x07b";
    for format in [
        ["parse", "--format", "text"],
        ["lower", "--format", "text"],
        ["run", "--format", "text"],
    ] {
        let out = gcodec(format.iter().copied().chain([program.as_str()]));
        let (text, err) = (stdout(&out), stderr(&out));
        assert!(text.contains(shown), "{format:?}: {text}");
        assert!(err.contains("TITLE\\x1b.MPF"), "{format:?}: {err}");
        for written in [&text, &err] {
            assert!(
                !written.chars().any(|c| c.is_control() && c != '\n'),
                "{format:?}: {written:?}"
            );
        }
    }
    for format in [["parse", "--format", "json"], ["run", "--format", "jsonl"]] {
        let out = gcodec(format.iter().copied().chain([program.as_str()]));
        let text = stdout(&out);
        assert!(
            text.contains("a\\u001b]0;title\\u0007b"),
            "{format:?}: {text}"
        );
    }
}

/// A usage error echoes the argument it does not know: no control
/// character of it reaches stderr, and the exit is 2.
#[test]
fn usage_errors_echo_no_control_characters() {
    let out = gcodec(["run", "--no-such\u{1b}]0;title\u{7}"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("unexpected argument '--no-such"), "{err}");
    assert!(!err.chars().any(|c| c.is_control() && c != '\n'), "{err:?}");
}
