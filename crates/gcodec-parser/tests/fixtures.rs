//! Snapshot tests over the parse fixtures in `tests/fixtures/parse/`.
//!
//! Each fixture is a small program of our own covering one construct
//! family. Good fixtures must parse without any diagnostic; their syntax
//! tree is snapshotted as JSON. Fixtures under `errors/` must yield at least
//! one error; their rendered diagnostics are snapshotted.
//!
//! Files are parsed under a name relative to the repository root, so the
//! snapshots hold no absolute paths. Review changed snapshots with
//! `cargo insta review`, or accept them with
//! `INSTA_UPDATE=always cargo test -p gcodec-parser --test fixtures`.

use std::path::{Path, PathBuf};

use gcodec_parser::parse;
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};

/// The fixture directory as the snapshots name it.
const FIXTURE_DIR: &str = "tests/fixtures/parse";

fn repo_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// Reads a fixture and names it relative to the repository root.
fn load(relative: &str) -> SourceFile {
    let name = format!("{FIXTURE_DIR}/{relative}");
    let bytes = std::fs::read(repo_root().join(&name))
        .unwrap_or_else(|e| panic!("cannot read fixture {name}: {e}"));
    SourceFile::new(name, bytes)
}

fn settings(file: &SourceFile) -> insta::Settings {
    let mut settings = insta::Settings::clone_current();
    settings.set_prepend_module_to_snapshot(false);
    settings.set_input_file(repo_root().join(file.name()));
    settings.set_omit_expression(true);
    settings
}

/// Lines of the file, counting a last line without a line end.
fn line_count(bytes: &[u8]) -> usize {
    bytes.iter().filter(|&&b| b == b'\n').count()
        + usize::from(bytes.last().is_some_and(|&b| b != b'\n'))
}

fn check_good(snapshot: &str, relative: &str) {
    let file = load(relative);
    let parsed = parse(&file);
    assert!(
        parsed.diagnostics.is_empty(),
        "{relative} should parse cleanly:\n{}",
        render_diagnostics(
            &parsed.diagnostics,
            Some(&file),
            RenderOptions {
                color: false,
                limit: None,
            }
        )
    );
    assert_eq!(
        parsed.program.blocks.len(),
        line_count(file.bytes()),
        "{relative}: one block per line"
    );
    settings(&file).bind(|| insta::assert_json_snapshot!(snapshot, parsed.program));
}

fn check_error(snapshot: &str, relative: &str) {
    let file = load(relative);
    let parsed = parse(&file);
    assert!(
        parsed.has_errors(),
        "{relative} should yield at least one error"
    );
    assert_eq!(
        parsed.program.blocks.len(),
        line_count(file.bytes()),
        "{relative}: one block per line, also with errors"
    );
    let rendered = render_diagnostics(
        &parsed.diagnostics,
        Some(&file),
        RenderOptions {
            color: false,
            limit: None,
        },
    );
    settings(&file).bind(|| insta::assert_snapshot!(snapshot, rendered));
}

/// Every fixture must have a test; the list is checked against the
/// directory by [`every_fixture_has_a_test`].
macro_rules! fixtures {
    (
        good { $($good:ident => $good_file:literal,)* }
        errors { $($bad:ident => $bad_file:literal,)* }
    ) => {
        $(
            #[test]
            fn $good() {
                check_good(stringify!($good), $good_file);
            }
        )*
        $(
            #[test]
            fn $bad() {
                check_error(stringify!($bad), $bad_file);
            }
        )*
        const ALL_FIXTURES: &[&str] = &[$($good_file,)* $($bad_file,)*];
    };
}

fixtures! {
    good {
        words_and_addresses => "words_and_addresses.mpf",
        numbers => "numbers.mpf",
        block_structure => "block_structure.mpf",
        crlf_line_ends => "crlf_line_ends.mpf",
        expressions_precedence => "expressions_precedence.mpf",
        nesting_64_parentheses => "nesting_64_parentheses.mpf",
        variables => "variables.mpf",
        procs_and_calls => "procs_and_calls.spf",
        control_flow => "control_flow.mpf",
        frames => "frames.mpf",
        sync_actions => "sync_actions.mpf",
        messages => "messages.mpf",
        def_extern_forms => "def_extern_forms.spf",
    }
    errors {
        error_word_blank_after_address => "errors/word_blank_after_address.mpf",
        error_word_numbered_and_indexed => "errors/word_numbered_and_indexed.mpf",
        error_word_t_with_index => "errors/word_t_with_index.mpf",
        error_word_f_with_extension => "errors/word_f_with_extension.mpf",
        error_word_string_without_eq => "errors/word_string_without_eq.mpf",
        error_word_r_number_and_index => "errors/word_r_number_and_index.mpf",
        error_word_missing_separator => "errors/word_missing_separator.mpf",
        error_bad_hex_constant => "errors/bad_hex_constant.mpf",
        error_bad_bin_constant => "errors/bad_bin_constant.mpf",
        error_unclosed_string => "errors/unclosed_string.mpf",
        error_invalid_characters => "errors/invalid_characters.mpf",
        error_unclosed_if => "errors/unclosed_if.mpf",
        error_unclosed_while => "errors/unclosed_while.mpf",
        error_unclosed_for => "errors/unclosed_for.mpf",
        error_unclosed_repeat => "errors/unclosed_repeat.mpf",
        error_endif_without_if => "errors/endif_without_if.mpf",
        error_else_twice => "errors/else_twice.mpf",
        error_misplaced_header => "errors/misplaced_header.mpf",
        error_nesting_65_parentheses => "errors/nesting_65_parentheses.mpf",
        error_several_errors => "errors/several_errors.mpf",
        error_number_out_of_range => "errors/number_out_of_range.mpf",
    }
}

#[test]
fn every_fixture_has_a_test() {
    fn collect(dir: &Path, prefix: &str, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).expect("fixture directory") {
            let entry = entry.expect("directory entry");
            let name = entry.file_name().to_string_lossy().into_owned();
            if entry.path().is_dir() {
                collect(&entry.path(), &format!("{prefix}{name}/"), out);
            } else {
                out.push(format!("{prefix}{name}"));
            }
        }
    }
    let mut found = Vec::new();
    collect(&repo_root().join(FIXTURE_DIR), "", &mut found);
    found.sort();
    let mut listed: Vec<String> = ALL_FIXTURES.iter().map(|s| (*s).to_owned()).collect();
    listed.sort();
    assert_eq!(found, listed, "fixture files and tests differ");
}

/// A file with several independent errors: every error is reported in one
/// run, and the blocks between them still parse.
#[test]
fn several_errors_are_all_reported_and_parsing_resumes() {
    let file = load("errors/several_errors.mpf");
    let parsed = parse(&file);
    let mut error_lines: Vec<u32> = parsed
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .filter_map(|d| d.span().map(|s| file.line_col(s.start).0))
        .collect();
    error_lines.sort_unstable();
    assert_eq!(error_lines, [3, 5, 6, 7, 8, 9]);
    // The good blocks around the bad ones keep their statements.
    for line in [2, 4, 10] {
        let block = &parsed.program.blocks[line - 1];
        assert!(
            !block.statements.is_empty(),
            "block on line {line} lost its statements"
        );
    }
}
