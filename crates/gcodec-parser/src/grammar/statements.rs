//! The statement dispatch: which family reads the statement under the
//! cursor. Address words come first because most statements are words;
//! statements led by a keyword are tried only when a keyword is next.

use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;

use super::expressions::expr;
use super::frames::frame;
use super::words::{assignment_or_named_word, word_statement};
use super::{Ctx, Ex, In, calls, control, declarations, spanned, sync};
use crate::ast::*;

/// All statements that may follow a block's number and label.
pub(crate) fn statements<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, Vec<Statement>, Ex> + 't {
    let expr = expr(g).boxed();
    let starts_with_keyword = any().filter(|t: &T| t.is_keyword()).rewind();
    let statement = choice((
        word_statement(g, expr.clone()),
        frame(g, expr.clone()).map(Some),
        assignment_or_named_word(g, expr.clone()).map(Some),
        calls::extcall_without_parentheses(g, expr.clone()).map(Some),
        calls::call_by_name(g, expr.clone()).map(Some),
        starts_with_keyword
            .ignore_then(keyword_statement(g, expr))
            .map(Some),
    ));
    spanned(g, statement)
        .repeated()
        .collect::<Vec<_>>()
        .map(|statements| statements.into_iter().flatten().collect())
}

/// Statements led by a keyword token.
fn keyword_statement<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    choice((
        control::if_statement(g, expr.clone()),
        control::structure_keyword_statement(),
        control::condition_statement(T::While, StatementKind::While, expr.clone()),
        control::condition_statement(T::Until, StatementKind::Until, expr.clone()),
        control::for_statement(g, expr.clone()),
        control::repeat_section(g, expr.clone()),
        control::repeat(),
        control::case(g, expr.clone()),
        control::goto(g, expr.clone()),
        declarations::def(g, expr.clone()),
        declarations::redef(g, expr.clone()),
        declarations::define(g),
        declarations::proc_def(g, expr.clone()),
        declarations::extern_decl(g, expr.clone()),
        calls::ret(expr.clone()),
        calls::indirect_call(g, expr.clone()),
        calls::pcall(g, expr.clone()),
        calls::mcall(g, expr.clone()),
        sync::sync_action(g, expr),
    ))
}
