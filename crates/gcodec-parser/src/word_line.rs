//! Lines of constant DIN words read straight from their bytes:
//! `G1 X100.037 Y-200.5 F1000`, `N20 G0 Z.5`.
//!
//! Most lines of large programs (CAM output) have exactly this shape, and
//! lexing them token by token, then reading the tokens ([`crate::fast`]),
//! costs several times what one pass over the bytes costs. This module
//! accepts only lines whose tokens are beyond doubt: an optional block
//! number `N<digits>` first, then words of one address letter, an
//! optional sign touching it and a plain decimal number touching that
//! (`5`, `5.`, `.5`, `1.5`), separated by blanks or touching
//! (`G0X1Y2`), into a [`WordLine`], from which the block the fast path
//! builds from the same line's tokens is made ([`WordLine::block`]); a
//! streamed run's lowering takes most such lines without the block.
//! Anything else — a comment, a skip mark, a name, an `L`, `N` or `R`
//! word, an exponent, `=`, a bracket, a byte beyond ASCII — is not read,
//! and the line is lexed and parsed as before. The blocks are checked
//! against the grammar's by `tests/fast_path.rs` (through
//! [`crate::parse_bytes`], which reads lines this way) and against
//! [`crate::parse_chunk`]'s by `tests/chunks.rs`.

use gcodec_lang::addresses::letter_str;
use gcodec_source::Span;

use crate::ast::{Block, BlockNumber, NumberLit, Statement, StatementKind, Word, WordValue};
use crate::fast::whole_number;
use crate::grammar::number_bytes_value;

/// Most words a line may hold here; a longer line is lexed.
const MAX_WORDS: usize = 16;

/// A line of constant DIN words read from its bytes: what its block
/// holds, without the block. Lowering takes most such lines as they are
/// (`G1 X… Y… F…`); [`WordLine::block`] gives the block the parser gives
/// for the others.
#[derive(Clone, Debug)]
pub struct WordLine {
    /// The line without its line end (nor a CR before it).
    span: Span,
    number: Option<BlockNumber>,
    words: [ConstantWord; MAX_WORDS],
    count: usize,
}

impl Default for WordLine {
    fn default() -> Self {
        Self {
            span: Span::new(0, 0),
            number: None,
            words: [ConstantWord::default(); MAX_WORDS],
            count: 0,
        }
    }
}

/// A word of a [`WordLine`]: an address letter with a constant touching
/// it (`X-1.5`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ConstantWord {
    /// The address letter, in upper case.
    pub letter: u8,
    /// The constant, its sign applied.
    pub value: f64,
    /// Written without a point (`G1`, not `G1.`).
    pub integer: bool,
    /// The word, from its letter to its last digit.
    pub span: Span,
}

impl WordLine {
    /// Reads the line `src[start..end]` (without its line end) into this
    /// one if it holds only a block number and constant DIN words;
    /// `false`, leaving this one in no particular state, otherwise.
    pub fn read(&mut self, src: &[u8], start: usize, end: usize) -> bool {
        let Some(line) = src.get(start..end) else {
            return false;
        };
        // A CR before the line end is no part of the block.
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        let mut scan = Scan { line, at: 0 };
        scan.blanks();
        self.number = None;
        if matches!(scan.peek(), Some(b'N' | b'n')) {
            let letter = scan.at;
            scan.at += 1;
            let digits = scan.at;
            while scan.peek().is_some_and(|b| b.is_ascii_digit()) {
                scan.at += 1;
            }
            // `N10=…` is an assignment; `N10.5` no block number.
            if !scan.ends_word() {
                return false;
            }
            let Some(value) = whole_number(&line[digits..scan.at]) else {
                return false;
            };
            self.number = Some(BlockNumber {
                span: span(start, letter, scan.at),
                main: false,
                value,
            });
            scan.blanks();
        }
        self.count = 0;
        while scan.at < line.len() {
            let Some(slot) = self.words.get_mut(self.count) else {
                return false;
            };
            let Some(word) = scan.word(start) else {
                return false;
            };
            *slot = word;
            self.count += 1;
            scan.blanks();
        }
        self.span = span(start, 0, line.len());
        self.count > 0 || self.number.is_some()
    }

    /// The line without its line end.
    pub fn span(&self) -> Span {
        self.span
    }

    /// The words, in the order written.
    pub fn words(&self) -> &[ConstantWord] {
        &self.words[..self.count]
    }

    /// The block of the line, as the parser gives it.
    pub fn block(&self) -> Block {
        Block {
            span: self.span,
            skip: None,
            number: self.number.clone(),
            label: None,
            statements: self.words().iter().map(ConstantWord::statement).collect(),
            comment: None,
            depth: 0,
        }
    }
}

/// The block of the line `src[start..end]` (without its line end), if
/// the line holds only a block number and constant DIN words.
pub(crate) fn read(src: &[u8], start: usize, end: usize) -> Option<Block> {
    let mut line = WordLine::default();
    line.read(src, start, end).then(|| line.block())
}

/// The span of `from..to` in the line starting at `start`.
fn span(start: usize, from: usize, to: usize) -> Span {
    Span::new((start + from) as u32, (start + to) as u32)
}

/// A position in a line.
struct Scan<'a> {
    line: &'a [u8],
    at: usize,
}

impl Scan<'_> {
    fn peek(&self) -> Option<u8> {
        self.line.get(self.at).copied()
    }

    /// Steps over the blanks the lexer skips here.
    fn blanks(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t')) {
            self.at += 1;
        }
    }

    /// Whether a number ending here ends its word as the lexer reads
    /// it: at a blank, the line's end, or a letter that starts the next
    /// word (a letter touching a letter would make a name, `EX` an
    /// exponent).
    fn ends_word(&self) -> bool {
        match self.peek() {
            None | Some(b' ' | b'\t') => true,
            Some(b) if b.is_ascii_alphabetic() => matches!(
                self.line.get(self.at + 1),
                Some(b'0'..=b'9' | b'.' | b'+' | b'-')
            ),
            _ => false,
        }
    }

    /// The word here, of the line starting at `start`: a letter other
    /// than `L`, `N` or `R`, an optional sign and a plain decimal number
    /// (`5`, `5.`, `.5`, `1.5`), all touching, ending its word.
    fn word(&mut self, start: usize) -> Option<ConstantWord> {
        let letter = self.at;
        let address = self.peek()?.to_ascii_uppercase();
        if !address.is_ascii_uppercase() || matches!(address, b'L' | b'N' | b'R') {
            return None;
        }
        self.at += 1;
        let negative = self.peek() == Some(b'-');
        if matches!(self.peek(), Some(b'+' | b'-')) {
            self.at += 1;
        }
        let digits_start = self.at;
        let mut mantissa = 0u64;
        let mut digits = 0;
        let mut fraction = None;
        loop {
            match self.peek() {
                Some(b @ b'0'..=b'9') => {
                    mantissa = mantissa.wrapping_mul(10).wrapping_add(u64::from(b - b'0'));
                    digits += 1;
                    fraction = fraction.map(|f: usize| f + 1);
                }
                Some(b'.') if fraction.is_none() => fraction = Some(0),
                _ => break,
            }
            self.at += 1;
        }
        if digits == 0 || !self.ends_word() {
            return None;
        }
        let text = &self.line[digits_start..self.at];
        // Beyond 15 digits the mantissa may not be exact: the general
        // reading rounds it.
        let value = if digits <= 15 {
            crate::grammar::short_decimal_value(mantissa, fraction.unwrap_or(0))
        } else {
            None
        };
        let value = match value {
            Some(value) => value,
            None => number_bytes_value(text)?,
        };
        Some(ConstantWord {
            letter: address,
            value: if negative { -value } else { value },
            integer: fraction.is_none(),
            span: span(start, letter, self.at),
        })
    }
}

impl ConstantWord {
    /// The statement of this word, as the fast path builds it.
    fn statement(&self) -> Statement {
        let word_span = self.span;
        let value_start = word_span.start + 1;
        Statement {
            span: word_span,
            kind: StatementKind::Word(Word::new(
                word_span,
                letter_str(self.letter),
                Span::new(word_span.start, value_start),
                None,
                WordValue::Constant(NumberLit {
                    span: Span::new(value_start, word_span.end),
                    value: self.value,
                    integer: self.integer,
                }),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::read;

    fn reads(line: &str) -> bool {
        read(line.as_bytes(), 0, line.len()).is_some()
    }

    /// The lines this path is for are read here, not lexed. What every
    /// line reads as, here or by the lexer, and its near misses, is
    /// compared with the grammar in `tests/fast_path.rs`.
    #[test]
    fn constant_word_lines_are_read() {
        for line in [
            "G1 X100.037 Y200.053 F1000",
            "N10 G1 X-1.5 Y+2 Z.5 F200",
            "n10 g1 x-.5 y5.",
            "N10G1X1Y2",
            "  N10  G1\tX1  ",
            "G1 X1\r",
            "N10",
            "X99999999999999999999999",
        ] {
            assert!(reads(line), "{line:?}");
        }
    }
}
