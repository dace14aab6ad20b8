//! The chumsky grammar of one block: its prefix (skip mark, block number,
//! label) and its statements, one module per family of constructs.
//!
//! The driver hands over the significant tokens of one line (blanks and the
//! comment removed); adjacency, which matters in SINUMERIK (`X1=` versus
//! `X1 A=`, `M5` versus `M 5`), is read from the byte spans. This module
//! holds the block entry point, the source access every family uses and
//! the small combinators they share.

mod calls;
mod control;
mod declarations;
mod expressions;
mod frames;
mod names;
mod numbers;
pub(crate) mod operators;
mod prefix;
mod statements;
mod sync;
mod words;

use chumsky::input::MappedInput;
use chumsky::prelude::*;
use compact_str::CompactString;
use gcodec_lexer::TokenKind as T;
use std::borrow::Cow;

use gcodec_source::{Encoding, Span, codes};

pub(crate) use control::structure_keyword;
pub(crate) use numbers::{number_bytes_value, short_decimal_value};

use crate::ast::*;
use crate::error::SyntaxError;
use crate::macros::Expanded;

pub(crate) type Spanned = (T, SimpleSpan);
pub(crate) type In<'t> = MappedInput<'t, T, SimpleSpan, &'t [Spanned]>;
pub(crate) type Ex = extra::Err<SyntaxError>;

/// Everything a block holds besides its comment.
#[derive(Debug)]
pub(crate) struct BlockBody {
    pub skip: Option<SkipLevel>,
    pub number: Option<BlockNumber>,
    pub label: Option<LabelDef>,
    pub statements: Vec<Statement>,
}

/// Source access for the grammar's closures: the bytes the tokens index
/// (the file's, or a line with its macros expanded) and how their spans
/// map to the file.
#[derive(Clone, Copy)]
pub(crate) struct Ctx<'s> {
    pub src: &'s [u8],
    pub expansion: Option<&'s Expanded>,
    /// What the bytes of comments and strings are read in.
    pub encoding: Encoding,
}

impl<'s> Ctx<'s> {
    /// The file's own bytes, read in `encoding`.
    pub fn new(src: &'s [u8], encoding: Encoding) -> Self {
        Self {
            src,
            expansion: None,
            encoding,
        }
    }

    /// A line with its macros expanded, read in `encoding`.
    pub fn expanded(expansion: &'s Expanded, encoding: Encoding) -> Self {
        Self {
            src: &expansion.bytes,
            expansion: Some(expansion),
            encoding,
        }
    }

    /// A token span as a span of the file.
    pub fn span(&self, s: SimpleSpan) -> Span {
        match self.expansion {
            None => Span::new(s.start as u32, s.end as u32),
            Some(expansion) => expansion.map_span(s),
        }
    }

    pub fn bytes(&self, s: SimpleSpan) -> &'s [u8] {
        &self.src[s.start..s.end]
    }

    /// Token text; tokens other than strings and comments are ASCII.
    pub fn text(&self, s: SimpleSpan) -> &'s str {
        std::str::from_utf8(self.bytes(s)).unwrap_or("")
    }

    fn name(&self, s: SimpleSpan) -> CompactString {
        CompactString::from(self.text(s))
    }

    /// Program text (a comment, a string) in the file's encoding; short
    /// text is stored inline, without a temporary `String`.
    pub fn decode_text(&self, bytes: &[u8]) -> CompactString {
        match self.encoding.decode(bytes) {
            Cow::Borrowed(text) => CompactString::from(text),
            Cow::Owned(text) => CompactString::from(text),
        }
    }
}
/// The block: skip mark, block number, label, then its statements.
pub(crate) fn block<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, BlockBody, Ex> + 't {
    prefix::skip_mark(g)
        .or_not()
        .then(choice((prefix::block_number(g), prefix::main_block_number(g))).or_not())
        .then(prefix::label(g).or_not())
        .then(statements::statements(g))
        .map(|(((skip, number), label), statements)| BlockBody {
            skip,
            number,
            label,
            statements,
        })
}

/// `(a, , c)` argument list; omitted arguments are `None`, `()` is empty.
fn args<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Option<Expr>>, Ex> + Clone + 't {
    expr.or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .map(|v| {
            if v.len() == 1 && v[0].is_none() {
                Vec::new()
            } else {
                v
            }
        })
        .delimited_by(just(T::LParen), just(T::RParen))
}

/// `[a, b, c]` index list.
fn indices<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Expr>, Ex> + Clone + 't {
    expr.separated_by(just(T::Comma))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(just(T::LBracket), just(T::RBracket))
}

/// A declared name: an identifier, or a letter with digits touching it
/// (`R0`, `X1`; such names shadow addresses and are judged by later stages).
fn name_token<'t>() -> impl Parser<'t, In<'t>, SimpleSpan, Ex> + Clone + 't {
    let ident = select! { T::Ident => () }.map_with(|_, e| e.span());
    let letter = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(
            select! { T::Number => () }
                .map_with(|_, e| e.span())
                .or_not(),
        )
        .try_map(|(l, n): (SimpleSpan, Option<SimpleSpan>), span| match n {
            None => Ok(l),
            Some(n) if n.start == l.end => Ok(span),
            Some(_) => Err(SyntaxError::custom(
                span,
                codes::parse::INVALID_WORD,
                "a name cannot contain a blank",
                None,
            )),
        });
    ident.or(letter)
}

/// A statement kind with the span it was read from; `None` stays `None`
/// (a malformed statement whose error was emitted).
fn spanned<'t, 's: 't>(
    g: Ctx<'s>,
    kind: impl Parser<'t, In<'t>, Option<StatementKind>, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Option<Statement>, Ex> + Clone + 't {
    kind.map_with(move |kind, e| {
        kind.map(|kind| Statement {
            span: g.span(e.span()),
            kind,
        })
    })
}
