//! The shared corpus of real programs must parse without a false error.
//!
//! The corpus belongs to others and lives outside the repository
//! (`../shared/corpus` beside the checkout, or `GCODEC_CORPUS_DIR`). Where it
//! is absent the tests print a notice and pass, so the README's test command
//! works in any clone.

use std::path::Path;

use gcodec_parser::parse;
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};
use gcodec_testkit::corpus::EXPECTED_PARSE_ERRORS as EXPECTED_ERRORS;

/// The conformance list annotates deliberate syntax errors; it is checked
/// line by line in `syntax_check.rs` instead.
fn is_syntax_check(path: &Path) -> bool {
    path.file_name()
        .is_some_and(|n| n.eq_ignore_ascii_case("SYNTAX_CHECK.SPF"))
}

#[test]
fn every_corpus_program_parses_without_errors() {
    let Some(dir) = gcodec_testkit::corpus_dir() else {
        return;
    };
    let files = gcodec_testkit::programs(&dir);
    assert!(
        files.len() >= 50,
        "expected the whole corpus, found {} files",
        files.len()
    );
    let mut failures = String::new();
    let mut checked = 0;
    let mut expected_seen = [false; EXPECTED_ERRORS.len()];
    for path in files.iter().filter(|p| !is_syntax_check(p)) {
        let file = SourceFile::read(path).expect("readable corpus file");
        let parsed = parse(&file);
        checked += 1;
        let shown = path.display().to_string();
        let errors: Vec<_> = parsed
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
            .filter(|d| {
                let line = d.span().map_or(0, |s| parsed.program.line_col(s.start).0);
                let expected = EXPECTED_ERRORS.iter().position(|(name, l, code)| {
                    shown.contains(name) && *l == line && *code == d.code.name()
                });
                expected.inspect(|&i| expected_seen[i] = true).is_none()
            })
            .cloned()
            .collect();
        if !errors.is_empty() {
            failures.push_str(&render_diagnostics(
                &errors,
                Some(&file),
                RenderOptions::default(),
            ));
        }
        let bytes = file.bytes();
        let lines = bytes.iter().filter(|&&b| b == b'\n').count()
            + usize::from(bytes.last().is_some_and(|&b| b != b'\n'));
        assert_eq!(parsed.program.blocks.len(), lines, "{}", path.display());
    }
    for (seen, (name, line, code)) in expected_seen.iter().zip(EXPECTED_ERRORS) {
        if !seen {
            failures.push_str(&format!("{name}:{line}: expected {code}, not reported\n"));
        }
    }
    eprintln!("parsed {checked} corpus programs");
    assert!(
        failures.is_empty(),
        "false errors in the corpus:\n{failures}"
    );
}
