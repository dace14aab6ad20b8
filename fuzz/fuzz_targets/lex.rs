//! Feeds arbitrary bytes to the lexer: the tokens must be non-empty,
//! contiguous, start at 0 and end at the input's end, so that their texts
//! concatenated reproduce the input exactly.

#![no_main]

use gcodec_lexer::{Lexer, lex};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut at = 0u32;
    let mut rebuilt = Vec::with_capacity(data.len());
    for token in Lexer::new(data) {
        assert_eq!(token.start, at, "{token:?} is not contiguous");
        assert!(token.end > token.start, "{token:?} is empty");
        rebuilt.extend_from_slice(&data[token.range()]);
        at = token.end;
    }
    assert_eq!(at as usize, data.len(), "tokens stop short of the end");
    assert_eq!(rebuilt, data);
    // The collecting form agrees with the streaming one.
    assert_eq!(lex(data), Lexer::new(data).collect::<Vec<_>>());
});
