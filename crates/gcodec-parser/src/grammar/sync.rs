//! Synchronous actions: `[ID=n | IDS=n] [WHEN | WHENEVER | EVERY | FROM
//! condition] DO actions`, where the actions are words, assignments and
//! calls.

use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;

use super::calls::call_by_name;
use super::words::{assignment_or_named_word, word_statement};
use super::{Ctx, Ex, In, spanned};
use crate::ast::*;

/// One synchronous action statement.
pub(super) fn sync_action<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let action = spanned(
        g,
        choice((
            word_statement(g, expr.clone()),
            assignment_or_named_word(g, expr.clone()).map(Some),
            call_by_name(g, expr.clone()).map(Some),
        )),
    );
    let sync_id = select! { T::Id => false, T::Ids => true }
        .then_ignore(just(T::Eq))
        .then(expr.clone())
        .map_with(move |(is_static, value), e| SyncId {
            span: g.span(e.span()),
            is_static,
            value,
        });
    let trigger = select! {
        T::When => SyncTriggerKind::When,
        T::Whenever => SyncTriggerKind::Whenever,
        T::Every => SyncTriggerKind::Every,
        T::From => SyncTriggerKind::From,
    }
    .then(expr)
    .map_with(move |(kind, condition), e| SyncTrigger {
        span: g.span(e.span()),
        kind,
        condition,
    });
    sync_id
        .or_not()
        .then(trigger.or_not())
        .then_ignore(just(T::Do))
        .then(action.repeated().at_least(1).collect::<Vec<_>>())
        .map(|((id, trigger), actions)| {
            StatementKind::SyncAction(Box::new(SyncAction {
                id,
                trigger,
                actions: actions.into_iter().flatten().collect(),
            }))
        })
}
