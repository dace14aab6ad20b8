//! Control flow: `IF`/`ELSE`/`ENDIF`, `WHILE`, `FOR`, `LOOP`,
//! `REPEAT`/`UNTIL`, `REPEAT` sections, `CASE` and the `GOTO` jumps with
//! their targets. Structures are paired later (`crate::structure`); here
//! each keyword is one statement.

use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::expressions::var_ref;
use super::words::word_only;
use super::{Ctx, Ex, In};
use crate::ast::*;
use crate::error::SyntaxError;

/// Keywords that are a whole statement by themselves. `REPEAT` is not
/// among them: it may be followed by the labels of a section.
pub(crate) fn structure_keyword(t: T) -> Option<StatementKind> {
    Some(match t {
        T::Else => StatementKind::Else,
        T::EndIf => StatementKind::EndIf,
        T::EndWhile => StatementKind::EndWhile,
        T::EndFor => StatementKind::EndFor,
        T::Loop => StatementKind::Loop,
        T::EndLoop => StatementKind::EndLoop,
        T::EndProc => StatementKind::EndProc,
        _ => return None,
    })
}

/// A [`structure_keyword`] as a statement.
pub(super) fn structure_keyword_statement<'t>()
-> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    any().try_map(|t: T, span| {
        structure_keyword(t).ok_or(SyntaxError {
            span,
            found: Some(t),
            expected: 0,
            label: None,
            custom: None,
        })
    })
}

/// `IF cond` opens a structure; `IF cond GOTOF target` is a jump.
pub(super) fn if_statement<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::If)
        .ignore_then(expr.clone())
        .then(jump(g, expr).or_not())
        .map(|(condition, jump)| match jump {
            Some(jump) => StatementKind::IfGoto(Box::new(IfGoto { condition, jump })),
            None => StatementKind::If(Box::new(Condition { condition })),
        })
}

/// `WHILE cond` and `UNTIL cond` (closing `REPEAT`): a keyword and a
/// condition.
pub(super) fn condition_statement<'t>(
    keyword: T,
    kind: fn(Box<Condition>) -> StatementKind,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(keyword)
        .ignore_then(expr.map(|condition| Condition { condition }))
        .map(move |c| kind(Box::new(c)))
}

/// `FOR var = start TO end`.
pub(super) fn for_statement<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::For)
        .ignore_then(var_ref(g, expr.clone()))
        .then_ignore(just(T::Eq))
        .then(expr.clone())
        .then_ignore(just(T::To))
        .then(expr)
        .map(|((var, start), end)| StatementKind::For(Box::new(For { var, start, end })))
}

/// `REPEAT start [end] [P=n]`, `REPEATB label [P=n]`: a program section
/// run again.
pub(super) fn repeat_section<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    select! { T::Repeat => false, T::RepeatB => true }
        .then(section_target(g))
        .then(section_target(g).or_not())
        .then(passes_word(g, expr).or_not())
        .map(|(((single_block, start), end), passes)| {
            StatementKind::RepeatSection(Box::new(RepeatSection {
                single_block,
                start,
                end,
                passes: passes.flatten().map(Box::new),
            }))
        })
}

/// `REPEAT` alone, opening `REPEAT … UNTIL`.
pub(super) fn repeat<'t>() -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::Repeat).to(StatementKind::Repeat)
}

/// `CASE selector OF value GOTOF target … DEFAULT GOTOF target`.
pub(super) fn case<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let case_value = expr.clone();
    just(T::Case)
        .ignore_then(expr.clone())
        .then_ignore(just(T::Of))
        .then(
            case_value
                .then(jump(g, expr.clone()))
                .map(|(value, jump)| CaseArm { value, jump })
                .repeated()
                .collect::<Vec<_>>(),
        )
        .then(just(T::Default).ignore_then(jump(g, expr)).or_not())
        .map(|((selector, arms), default)| {
            StatementKind::Case(Box::new(Case {
                selector,
                arms,
                default,
            }))
        })
}

/// `GOTOF target` and the other jumps, as a statement.
pub(super) fn goto<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    jump(g, expr).map(|j| StatementKind::Goto(Box::new(j)))
}

/// A jump target: label, block number or string expression.
pub(super) fn jump_target<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, JumpTarget, Ex> + Clone + 't {
    let label = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then_ignore(
            // A label is a plain name; a name followed by an operator or
            // parenthesis is an expression.
            one_of([T::LParen, T::LBracket, T::Concat]).not().rewind(),
        )
        .map(move |s| JumpTarget::Label {
            span: g.span(s),
            name: g.name(s),
        });
    let block_number = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            let is_n = g.bytes(l)[0].eq_ignore_ascii_case(&b'N') && n.start == l.end;
            let digits = g.text(n);
            match digits.parse::<u64>() {
                Ok(value) if is_n => Ok(Some(value)),
                Err(_) if is_n && digits.bytes().all(|b| b.is_ascii_digit()) => Ok(None),
                _ => Err(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_WORD,
                    "a jump target is a label, a block number `N…` or a string",
                    None,
                )),
            }
        })
        .validate(move |value, e, emitter| {
            let span: SimpleSpan = e.span();
            JumpTarget::BlockNumber {
                span: g.span(span),
                value: super::prefix::block_number_value(value, span, g, emitter),
            }
        });
    choice((label, block_number, expr.map(JumpTarget::Expr))).labelled("jump target")
}

/// A label or block number (REPEAT sections take no string expressions,
/// which keeps `REPEAT A B P=3` unambiguous).
fn section_target<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, JumpTarget, Ex> + Clone + 't {
    let never = select! { T::Error => () }.try_map(|_, s| {
        Err::<Expr, _>(SyntaxError::custom(
            s,
            codes::parse::INVALID_WORD,
            "unreachable",
            None,
        ))
    });
    jump_target(g, never).labelled("label")
}

fn goto_kind<'t>() -> impl Parser<'t, In<'t>, GotoKind, Ex> + Clone + 't {
    select! {
        T::Goto => GotoKind::Goto,
        T::GotoF => GotoKind::GotoF,
        T::GotoB => GotoKind::GotoB,
        T::GotoC => GotoKind::GotoC,
        T::GotoS => GotoKind::GotoS,
    }
}

fn jump<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Jump, Ex> + Clone + 't {
    goto_kind()
        .then(jump_target(g, expr).or_not())
        .try_map(|(goto, target), span| match (goto, &target) {
            (GotoKind::GotoS, Some(_)) => Err(SyntaxError::custom(
                span,
                codes::parse::INVALID_WORD,
                "`GOTOS` takes no target",
                Some("GOTOS jumps back to the program start"),
            )),
            (GotoKind::GotoS, None) | (_, Some(_)) => Ok(Jump { goto, target }),
            (_, None) => Err(SyntaxError::custom(
                span,
                codes::parse::MISSING_JUMP_TARGET,
                "jump without a target",
                Some("name a label, a block number (`N100`) or a string expression"),
            )),
        })
}

/// `P3` / `P=3` after REPEAT (`None` when the word was malformed and its
/// error already emitted).
fn passes_word<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Option<SpannedWord>, Ex> + Clone + 't {
    word_only(
        g,
        expr,
        |w| w.address() == "P" && w.extension().is_none(),
        "expected the number of passes `P=n`",
        None,
    )
}
