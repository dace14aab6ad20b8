//! Lossless lexer for SINUMERIK (Siemens mode) part programs.
//!
//! The lexer works on bytes, so comments in Latin-1, CP1252 or CP1251 never
//! fail; every token is a [`TokenKind`] and a byte range. Nothing is
//! skipped: blanks, comments and line ends are tokens too (trivia), and the
//! concatenated token texts reproduce the file exactly.
//!
//! DIN words are split the way the control reads them: an identifier needs
//! two leading letters (or `_`), so `G53G0Z-205` lexes as
//! `G` `53` `G` `0` `Z` `-` `205` while `CYCLE81` and `_MM0` are identifiers.
//! Whether `X1=10` addresses axis `X1` or `X1` sets `X` to 1 is decided by
//! the parser, which sees whether the letter, the digits and `=` touch.

mod token;

pub use token::TokenKind;

use gcodec_source::Span;
use logos::Logos;

/// One token: its kind and where it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub kind: TokenKind,
    /// Byte offset of the first byte.
    pub start: u32,
    /// Byte offset one past the last byte.
    pub end: u32,
}

impl Token {
    /// The byte range, for slicing the source.
    pub fn range(&self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// Iterates over all tokens of a source, trivia included.
///
/// Bytes that start no token become [`TokenKind::Error`] tokens one byte long,
/// so the iterator never stops early and never panics.
pub struct Lexer<'src> {
    inner: logos::Lexer<'src, TokenKind>,
}

impl<'src> Lexer<'src> {
    /// A lexer over `src`.
    pub fn new(src: &'src [u8]) -> Self {
        Self {
            inner: TokenKind::lexer(src),
        }
    }
}

impl Iterator for Lexer<'_> {
    type Item = Token;

    #[inline]
    fn next(&mut self) -> Option<Token> {
        let kind = self.inner.next()?.unwrap_or(TokenKind::Error);
        let span = self.inner.span();
        Some(Token {
            kind,
            start: span.start as u32,
            end: span.end as u32,
        })
    }
}

/// Lexes a whole source into a vector (convenient for tools and tests; the
/// parser streams instead).
pub fn lex(src: &[u8]) -> Vec<Token> {
    Lexer::new(src).collect()
}

/// The span of a token.
pub fn token_span(token: &Token) -> Span {
    Span::new(token.start, token.end)
}

#[cfg(test)]
mod tests;
