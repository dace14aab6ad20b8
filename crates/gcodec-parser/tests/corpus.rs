//! The shared corpus of real programs must parse without a false error.
//!
//! The corpus belongs to others and lives outside the repository
//! (`../shared/corpus` beside the checkout, or `GCODEC_CORPUS_DIR`). Where it
//! is absent the tests print a notice and pass, so the README's test command
//! works in any clone.

use std::path::Path;

use gcodec_parser::parse;
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};

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
    for path in files.iter().filter(|p| !is_syntax_check(p)) {
        let file = SourceFile::read(path).expect("readable corpus file");
        let parsed = parse(&file);
        checked += 1;
        let errors: Vec<_> = parsed
            .diagnostics
            .iter()
            .filter(|d| d.is_error())
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
    eprintln!("parsed {checked} corpus programs");
    assert!(
        failures.is_empty(),
        "false errors in the corpus:\n{failures}"
    );
}
