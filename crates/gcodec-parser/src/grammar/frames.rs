//! Frame instructions: `TRANS X10 Y5`, `AROT Z45`, `MIRROR X0`, … — a
//! frame operation and the axis words it takes.

use chumsky::prelude::*;
use gcodec_lang::FrameOp;
use gcodec_lexer::TokenKind as T;

use super::words::{named_word, word_only};
use super::{Ctx, Ex, In};
use crate::ast::*;
use crate::error::SyntaxError;

/// A frame operation and its words; malformed words were diagnosed and
/// are left out.
pub(super) fn frame<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .try_map(move |s, _| {
            FrameOp::from_name(g.text(s)).ok_or(SyntaxError {
                span: s,
                found: Some(T::Ident),
                expected: 0,
                label: None,
                custom: None,
            })
        })
        .then(frame_word(g, expr).repeated().collect::<Vec<_>>())
        .map(|(op, words)| {
            StatementKind::Frame(Box::new(Frame {
                op,
                words: words.into_iter().flatten().collect(),
            }))
        })
}

/// An axis word (`X10`, `CR=5`), `None` when it was malformed.
fn frame_word<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Option<SpannedWord>, Ex> + Clone + 't {
    word_only(
        g,
        expr.clone(),
        |_| true,
        "frame instructions take axis words only",
        Some("write e.g. `TRANS X10 Y5` in a block of its own"),
    )
    .or(named_word(g, expr).map_with(move |word, e| {
        Some(SpannedWord {
            span: g.span(e.span()),
            word,
        })
    }))
}
