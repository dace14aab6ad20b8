//! Subprogram calls and returns: calls by name (`CONTOUR`, `CYCLE81(…)`),
//! `CALL` (indirect, and of a section `BLOCK … TO …`), `PCALL` (by
//! path), `MCALL` (modal) and `RET`. Calls by number (`L123`) are words
//! and read in [`super::words`].

use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::control::jump_target;
use super::{Ctx, Ex, In, args};
use crate::ast::*;
use crate::error::SyntaxError;

/// `NAME`, `NAME(args)`: a subprogram or cycle called by name.
pub(super) fn call_by_name<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then(args(expr).or_not())
        .map(move |(s, args)| call_of_name(g, s, args))
}

/// The call of the name at `s` with `args` (`None`: no parentheses).
fn call_of_name(g: Ctx<'_>, s: SimpleSpan, args: Option<Vec<Option<Expr>>>) -> StatementKind {
    StatementKind::Call(Box::new(Call {
        target: CallTarget::Name {
            span: g.span(s),
            name: g.name(s),
        },
        args,
        passes: None,
    }))
}

/// `EXTCALL "NAME"`: the call of an external program as CAM systems
/// write it, without the parentheses of the documented `EXTCALL("NAME")`;
/// it reads as that form.
pub(super) fn extcall_without_parentheses<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .filter(move |s: &SimpleSpan| g.text(*s).eq_ignore_ascii_case("EXTCALL"))
        .then_ignore(just(T::String).rewind())
        .then(expr)
        .map(move |(s, program)| call_of_name(g, s, Some(vec![Some(program)])))
}

/// `RET`, `RET(args)`.
pub(super) fn ret<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::Ret)
        .ignore_then(args(expr).or_not())
        .map(|args| StatementKind::Ret(Box::new(Ret { args })))
}

/// `CALL program`, `CALL BLOCK start TO end`, `CALL program BLOCK … TO …`.
pub(super) fn indirect_call<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let call_section = just(T::Block)
        .ignore_then(jump_target(g, expr.clone()))
        .then_ignore(just(T::To))
        .then(jump_target(g, expr.clone()));
    just(T::Call)
        .ignore_then(just(T::Block).not().rewind().ignore_then(expr).or_not())
        .then(call_section.or_not())
        .try_map(|(program, section), span| {
            if program.is_none() && section.is_none() {
                Err(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_WORD,
                    "`CALL` needs a program name or `BLOCK … TO …`",
                    Some("write e.g. `CALL \"PART1\"`"),
                ))
            } else {
                Ok(StatementKind::IndirectCall(Box::new(IndirectCall {
                    program,
                    section,
                })))
            }
        })
}

/// `PCALL path(args)`: a call of the program at an absolute path.
pub(super) fn pcall<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::PCall)
        .ignore_then(
            select! { T::Slash => (), T::Ident => (), T::Letter => (), T::Number => () }
                .repeated()
                .at_least(1)
                .to_span(),
        )
        .then(args(expr).or_not())
        .map(move |(path, args): (SimpleSpan, _)| {
            StatementKind::PCall(Box::new(PCall {
                path: g.name(path),
                path_span: g.span(path),
                args,
            }))
        })
}

/// `MCALL call` selects a modal call; `MCALL` alone ends it.
pub(super) fn mcall<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::MCall)
        .ignore_then(named_call(g, expr).or_not())
        .map(|call| StatementKind::MCall(Box::new(MCall { call })))
}

/// A subprogram call by name (for `MCALL`): `NAME`, `NAME(args)`, `L12`.
fn named_call<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Call, Ex> + Clone + 't {
    let by_name = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .map(move |s| CallTarget::Name {
            span: g.span(s),
            name: g.name(s),
        });
    let by_number = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            if g.bytes(l)[0].eq_ignore_ascii_case(&b'L')
                && n.start == l.end
                && g.bytes(n).iter().all(u8::is_ascii_digit)
            {
                Ok(CallTarget::Number {
                    span: g.span(span),
                    digits: g.name(n),
                })
            } else {
                Err(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_WORD,
                    "expected a program name or `L` number",
                    None,
                ))
            }
        });
    choice((by_name, by_number))
        .then(args(expr).or_not())
        .map(|(target, args)| Call {
            target,
            args,
            passes: None,
        })
}
