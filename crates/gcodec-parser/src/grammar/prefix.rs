//! The block prefix: the skip mark (`/`, `/0` … `/9`), the block number
//! (`N10`, main block `:10`) and the label (`LOOP1:`).

use chumsky::input::Emitter;
use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::{Ctx, Ex, In};
use crate::ast::*;
use crate::error::SyntaxError;

/// `/` or `/n`.
pub(super) fn skip_mark<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, SkipLevel, Ex> + Clone + 't {
    just(T::Slash)
        .map_with(|_, e| e.span())
        .then(
            select! { T::Number => () }
                .map_with(|_, e| e.span())
                .or_not(),
        )
        .try_map(
            move |(slash, level): (SimpleSpan, Option<SimpleSpan>), span: SimpleSpan| match level {
                None => Ok(SkipLevel {
                    span: g.span(slash),
                    level: 0,
                }),
                // `/ 5`: level 0 or 5? Nothing documents the control's
                // reading, and the two skip under different switches.
                Some(n) if n.start != slash.end => Err(SyntaxError::custom(
                    span,
                    codes::parse::SEPARATED_SKIP_LEVEL,
                    format!(
                        "a blank between the skip mark `/` and the number `{}`",
                        g.text(n)
                    ),
                    Some("write the level against the mark (`/5`), or `/` alone for level 0"),
                )),
                Some(n) => match g.text(n).parse::<u8>() {
                    Ok(level) if level <= 9 => Ok(SkipLevel {
                        span: g.span(span),
                        level,
                    }),
                    _ => Err(SyntaxError::custom(
                        span,
                        codes::parse::INVALID_SKIP_LEVEL,
                        format!("skip level `/{}` is not 0 to 9", g.text(n)),
                        Some("skip levels are `/` and `/0` … `/9`"),
                    )),
                },
            },
        )
}

/// `N10`; `N10=` is not a block number. Digits beyond the range of a
/// block number (`N999999999999999999999`) are diagnosed, naming them as
/// written, rather than left to be read as an `N` word.
pub(super) fn block_number<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, BlockNumber, Ex> + Clone + 't {
    select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            if !g.bytes(l)[0].eq_ignore_ascii_case(&b'N') || n.start != l.end {
                return Err(SyntaxError {
                    span,
                    found: Some(T::Letter),
                    expected: 0,
                    label: None,
                    custom: None,
                });
            }
            let digits = g.text(n);
            match digits.parse::<u64>() {
                Ok(value) => Ok(Some(value)),
                Err(_) if digits.bytes().all(|b| b.is_ascii_digit()) => Ok(None),
                Err(_) => Err(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_BLOCK_NUMBER,
                    format!("block number `N{digits}` is not a whole number"),
                    None,
                )),
            }
        })
        .then_ignore(just(T::Eq).not().rewind())
        .validate(move |value, e, emitter| {
            let span: SimpleSpan = e.span();
            BlockNumber {
                span: g.span(span),
                main: false,
                value: block_number_value(value, span, g, emitter),
            }
        })
}

/// The block number read at `span`, or, where its digits are beyond 64
/// bits (`None`), 0 with the diagnosis emitted naming them as written: the
/// block is then in error, so the placeholder goes nowhere.
pub(super) fn block_number_value(
    value: Option<u64>,
    span: SimpleSpan,
    g: Ctx<'_>,
    emitter: &mut Emitter<SyntaxError>,
) -> u64 {
    value.unwrap_or_else(|| {
        emitter.emit(SyntaxError::custom(
            span,
            codes::parse::INVALID_NUMBER,
            format!("block number `{}` is out of range", g.text(span)),
            Some("block numbers are N0 … N18446744073709551615"),
        ));
        0
    })
}

/// `:10`, a main block number.
pub(super) fn main_block_number<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, BlockNumber, Ex> + Clone + 't {
    just(T::Colon)
        .ignore_then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |n, span| {
            g.text(n)
                .parse::<u64>()
                .map(|value| BlockNumber {
                    span: g.span(span),
                    main: true,
                    value,
                })
                .map_err(|_| {
                    SyntaxError::custom(
                        span,
                        codes::parse::INVALID_BLOCK_NUMBER,
                        format!("main block number `:{}` is not a whole number", g.text(n)),
                        None,
                    )
                })
        })
}

/// `NAME:`.
pub(super) fn label<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, LabelDef, Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then_ignore(just(T::Colon))
        .map_with(move |name, e| LabelDef {
            span: g.span(e.span()),
            name: g.name(name),
        })
}
