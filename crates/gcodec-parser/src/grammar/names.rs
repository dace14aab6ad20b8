//! The name a declaration introduces (`DEF` variables, `PROC`
//! parameters), read and judged by the identifier rules of the control
//! (Fundamentals 10/2004, p. 60): the first two characters are letters or
//! `_`, and a name is no keyword or address of the language.
//!
//! The name is the whole run of name characters the lexer cut into
//! pieces (`P1X` is a letter, a number and a letter), so a bad name is
//! one error at the declaration, never a shorter name followed by words.

use chumsky::prelude::*;
use gcodec_lang::identifiers::invalid_name;
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::{Ctx, Ex, In};
use crate::error::SyntaxError;

/// The span of a declared name; an invalid one is diagnosed and kept, so
/// the statement stays a declaration.
pub(super) fn declared_name<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, SimpleSpan, Ex> + Clone + 't {
    let piece = any()
        .filter(move |t: &T| is_name_piece(*t))
        .map_with(|_, e| e.span())
        .filter(move |s: &SimpleSpan| g.bytes(*s).iter().copied().all(is_name_byte));
    // A piece continues the name when it touches it: tokens cover the
    // line, so the byte before a touching piece is a name byte.
    let touching =
        piece.filter(move |s: &SimpleSpan| s.start > 0 && is_name_byte(g.src[s.start - 1]));
    piece
        .then(touching.repeated().collect::<Vec<_>>())
        .map(|(first, rest)| {
            SimpleSpan::from(first.start..rest.last().map_or(first.end, |s| s.end))
        })
        .validate(move |span, _, emitter| {
            if let Some((message, help)) = invalid_name(g.text(span)) {
                emitter.emit(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_NAME,
                    message,
                    Some(help),
                ));
            }
            span
        })
}

/// Tokens a name may be cut into: names, address letters, digits, keywords
/// and the lone `_` (an error token on its own).
fn is_name_piece(t: T) -> bool {
    matches!(t, T::Ident | T::Letter | T::Number | T::Error) || t.is_keyword()
}

fn is_name_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_'
}
