//! Feeds arbitrary bytes to the parser and checks what every parse must
//! satisfy (the invariants the property tests check too: no panic, one
//! block per line, every span in bounds with `start <= end` and the true
//! 1-based line and column of its start, every diagnostic labelled in
//! bounds); that the fast path builds exactly what the grammar builds; then
//! renders the diagnostics, which exercises the miette path (byte-offset
//! mapping for non-UTF-8 sources).

#![no_main]

#[path = "../../crates/gcodec-parser/tests/common/invariants.rs"]
mod invariants;

use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let parse = gcodec_parser::parse_bytes("fuzz.mpf", data);
    if let Err(problem) = invariants::check_parse_of(data, &parse) {
        panic!("{problem}");
    }
    let grammar = gcodec_parser::parse_bytes_with_grammar_only("fuzz.mpf", data);
    assert_eq!(parse.program, grammar.program, "fast path and grammar differ");
    assert_eq!(parse.diagnostics, grammar.diagnostics, "fast path and grammar differ");
    let file = SourceFile::new("fuzz.mpf", data);
    let rendered = render_diagnostics(&parse.diagnostics, Some(&file), RenderOptions::default());
    assert_eq!(rendered.is_empty(), parse.diagnostics.is_empty());
});
