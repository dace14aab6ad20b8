//! A file's diagnostics kept in memory are bounded; every one is counted.

use gcodec_parser::parse_bytes_in_chunks;
use gcodec_source::{MAX_KEPT_PER_FILE, Severity, codes};

/// More bad blocks than a file keeps diagnostics of, parsed in chunks:
/// the first are kept (in source order), all are counted. (A line of
/// `?` is the cheapest bad block: the lexer alone reports it.)
#[test]
fn a_file_keeps_a_bounded_number_of_diagnostics_and_counts_all() {
    let bad = MAX_KEPT_PER_FILE + 50;
    let src = "?\n".repeat(bad);
    let parse = parse_bytes_in_chunks("bad.mpf", src.as_bytes(), 3);
    let diagnostics = &parse.diagnostics;
    assert_eq!(diagnostics.len(), MAX_KEPT_PER_FILE);
    assert_eq!(diagnostics.total(), bad as u64);
    assert_eq!(
        diagnostics.omitted().by_code(),
        [(codes::parse::INVALID_CHARACTER, Severity::Error, 50)]
    );
    let last = diagnostics.last().and_then(|d| d.span()).expect("a span");
    assert_eq!(last.start as usize, (MAX_KEPT_PER_FILE - 1) * 2);
    assert!(parse.has_errors());
}
