//! The name a declaration introduces (`DEF` variables, `PROC`
//! parameters), read and judged by the identifier rules of the control
//! (Fundamentals 10/2004, p. 60): the first two characters are letters or
//! `_`, and a name is no keyword or address of the language.
//!
//! The name is the whole run of name characters the lexer cut into
//! pieces (`P1X` is a letter, a number and a letter), so a bad name is
//! one error at the declaration, never a shorter name followed by words.

use chumsky::prelude::*;
use gcodec_lang::addresses::is_written_as_address;
use gcodec_lang::{ggroups, keywords};
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

/// What is wrong with `name` as a declared name, and how to fix it.
fn invalid_name(name: &str) -> Option<(String, &'static str)> {
    const RENAME: &str = "begin the name with two letters or `_`; Siemens recommends user names \
                          that begin with `U` (`U_COUNT`) or contain `_`";
    let bytes = name.as_bytes();
    if let [letter] = bytes {
        return Some((
            format!(
                "`{}` is an address letter and cannot name a variable",
                *letter as char
            ),
            RENAME,
        ));
    }
    if let Some(at) = bytes[..2]
        .iter()
        .position(|b| !(b.is_ascii_alphabetic() || *b == b'_'))
    {
        return Some((
            format!(
                "`{name}` is not a name: its first two characters must be letters or `_`, and \
                 `{}` is not",
                bytes[at] as char
            ),
            RENAME,
        ));
    }
    let what = if keywords::is_reserved(name) {
        "a keyword"
    } else if ggroups::lookup(name).is_some() {
        "a G command"
    } else if is_written_as_address(name) {
        "an address"
    } else {
        return None;
    };
    Some((
        format!("`{name}` is {what} of the NC language and cannot name a variable"),
        "choose another name; Siemens recommends user names that begin with `U` or contain `_`",
    ))
}

#[cfg(test)]
mod tests {
    use super::invalid_name;

    #[test]
    fn names_begin_with_two_letters_or_underscores() {
        for good in ["DEPTH", "_Z", "__1", "U_COUNT", "AB12"] {
            assert_eq!(invalid_name(good), None, "{good}");
        }
        for bad in ["I", "P1X", "R2D2", "K1", "N1", "_1LBL", "1A"] {
            assert!(invalid_name(bad).is_some(), "{bad}");
        }
    }

    #[test]
    fn keywords_g_commands_and_addresses_name_nothing() {
        for bad in ["IF", "endfor", "TRUE", "DIAMON", "CR", "SPOS"] {
            assert!(invalid_name(bad).is_some(), "{bad}");
        }
    }
}
