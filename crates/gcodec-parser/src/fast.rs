//! A fast path for the commonest blocks: DIN words with constant values
//! (`N10 G1 Y2 F200 ; cut`), named addresses with a constant
//! (`CR=-20.5`), and structure keywords standing alone (`ENDIF`).
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
use crate::grammar::{
    BlockBody, Ctx, Spanned, is_named_address, letter_name, number_value, structure_keyword,
};

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
    // A structure keyword standing alone (`ENDIF`, `ELSE`, `LOOP`, …).
    if let [(kind, span)] = &tokens[i..] {
        // Alone on its block, `REPEAT` opens a REPEAT … UNTIL structure.
        let alone =
            structure_keyword(*kind).or((*kind == T::Repeat).then_some(StatementKind::Repeat));
        let Some(kind) = alone else {
            return constant_words_from(tokens, i, g, skip, number);
        };
        return Some(BlockBody {
            skip,
            number,
            label: None,
            statements: vec![Statement {
                span: g.span(*span),
                kind,
            }],
        });
    }
    constant_words_from(tokens, i, g, skip, number)
}

/// The words from token `i` on.
fn constant_words_from(
    tokens: &[Spanned],
    mut i: usize,
    g: &Ctx<'_>,
    skip: Option<SkipLevel>,
    number: Option<BlockNumber>,
) -> Option<BlockBody> {
    // Every word starts with a letter or a name: that is the exact
    // statement count when the block qualifies.
    let words = tokens[i..]
        .iter()
        .filter(|(k, _)| matches!(k, T::Letter | T::Ident))
        .count();
    let mut statements = Vec::with_capacity(words);
    while i < tokens.len() {
        if tokens[i].0 == T::Ident {
            let (statement, next) = named_constant(tokens, i, g)?;
            statements.push(statement);
            i = next;
            continue;
        }
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
        let span = g.span(SimpleSpan::from(letter.start..n.end));
        statements.push(Statement {
            span,
            kind: StatementKind::Word(Word::new(
                span,
                letter_name(address),
                g.span(letter),
                None,
                WordValue::Constant(NumberLit {
                    span: g.span(SimpleSpan::from(value_start..n.end)),
                    value,
                    integer: text.bytes().all(|b| b.is_ascii_digit()),
                }),
            )),
        });
    }
    Some(BlockBody {
        skip,
        number,
        label: None,
        statements,
    })
}

/// `CR=-20.5`: a multi-letter address with a signed constant, built as the
/// grammar builds it (a number, or a unary sign over a number). Returns the
/// statement and the index of the next token.
fn named_constant(tokens: &[Spanned], i: usize, g: &Ctx<'_>) -> Option<(Statement, usize)> {
    let (T::Ident, name) = tokens[i] else {
        return None;
    };
    let text = g.text(name);
    if !is_named_address(text) || !matches!(tokens.get(i + 1), Some((T::Eq, _))) {
        return None;
    }
    let mut j = i + 2;
    let sign = match tokens.get(j) {
        Some(&(T::Minus, s)) => Some((UnaryOp::Neg, s)),
        Some(&(T::Plus, s)) => Some((UnaryOp::Plus, s)),
        _ => None,
    };
    if sign.is_some() {
        j += 1;
    }
    let &(T::Number, n) = tokens.get(j)? else {
        return None;
    };
    j += 1;
    // Anything but the start of the next word could continue the value.
    if !matches!(tokens.get(j), None | Some((T::Letter | T::Ident, _))) {
        return None;
    }
    let digits = g.text(n);
    let number = Expr {
        span: g.span(n),
        kind: ExprKind::Number {
            value: number_value(digits)?,
            integer: digits.bytes().all(|b| b.is_ascii_digit()),
        },
    };
    let expr = match sign {
        None => number,
        Some((op, s)) => Expr {
            span: g.span(SimpleSpan::from(s.start..n.end)),
            kind: ExprKind::Unary {
                op,
                operand: Box::new(number),
            },
        },
    };
    let span = g.span(SimpleSpan::from(name.start..n.end));
    let statement = Statement {
        span,
        kind: StatementKind::Word(Word::new(
            span,
            text.to_ascii_uppercase().into(),
            g.span(name),
            None,
            WordValue::Assigned {
                modifier: None,
                expr: Box::new(expr),
            },
        )),
    };
    Some((statement, j))
}
