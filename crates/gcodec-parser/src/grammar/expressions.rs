//! Expressions: constants, variable references, function calls and
//! parentheses as operands, combined by a pratt parser over the operator
//! table; and initializers, the right side of `=` (an expression, a list,
//! `SET(…)`, `REP(…)`).

use chumsky::input::MapExtra;
use chumsky::pratt::{infix, left, prefix};
use chumsky::prelude::*;
use chumsky::primitive::select;
use gcodec_lang::{BinaryOp, UnaryOp};
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::numbers::number_value;
use super::operators::{self, Associativity, Precedence};
use super::{Ctx, Ex, In, args, indices};

use crate::ast::*;
use crate::error::SyntaxError;

/// The expression grammar with Siemens precedence.
pub(crate) fn expr<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    recursive(move |expr| {
        let var = var_ref(g, expr.clone()).map(|var| Expr {
            span: var.span,
            kind: ExprKind::Var { var: Box::new(var) },
        });
        let atom = choice((
            number(g),
            radix_number(g),
            string(g),
            boolean(g),
            function_call(g, expr.clone()),
            var,
            parenthesised(g, expr),
        ))
        .labelled("expression");
        with_operators(g, atom)
    })
}

/// A decimal constant. An out-of-range number is diagnosed but parsing
/// goes on, so the message names the number rather than the statement
/// around it.
fn number<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    select! { T::Number => () }.validate(move |_, e, emitter| {
        let s: SimpleSpan = e.span();
        let text = g.text(s);
        let value = number_value(text).unwrap_or_else(|| {
            emitter.emit(SyntaxError::custom(
                s,
                codes::parse::INVALID_NUMBER,
                format!("number `{text}` is out of range"),
                Some("REAL values range over about ±1.8·10^308"),
            ));
            0.0
        });
        Expr {
            span: g.span(s),
            kind: ExprKind::Number {
                value,
                integer: text.bytes().all(|b| b.is_ascii_digit()),
            },
        }
    })
}

/// A hexadecimal (`'H1F'`) or binary (`'B101'`) constant.
fn radix_number<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    select! { T::HexNumber => 16, T::BinNumber => 2 }.try_map(move |radix, s: SimpleSpan| {
        let text = g.text(s);
        u64::from_str_radix(&text[2..text.len() - 1], radix)
            .map(|v| Expr {
                span: g.span(s),
                kind: ExprKind::Number {
                    value: v as f64,
                    integer: true,
                },
            })
            .map_err(|_| {
                SyntaxError::custom(
                    s,
                    codes::parse::INVALID_NUMBER,
                    format!("constant `{text}` is too large"),
                    None,
                )
            })
    })
}

/// A string constant, `"…"`.
fn string<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    select! { T::String => () }.map_with(move |_, e| {
        let s: SimpleSpan = e.span();
        let bytes = g.bytes(s);
        let value = g.decode_text(&bytes[1..bytes.len() - 1]);
        Expr {
            span: g.span(s),
            kind: ExprKind::String {
                value: Box::new(value),
            },
        }
    })
}

/// `TRUE`, `FALSE`.
fn boolean<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    select! { T::True => true, T::False => false }.map_with(move |value, e| Expr {
        span: g.span(e.span()),
        kind: ExprKind::Bool { value },
    })
}

/// `SIN(30)`, `AC(5)`, `USERFUNC(…)`.
fn function_call<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then(args(expr))
        .map_with(move |(name_span, args), e| Expr {
            span: g.span(e.span()),
            kind: ExprKind::Call(Box::new(CallExpr {
                name: g.name(name_span),
                name_span: g.span(name_span),
                args,
            })),
        })
}

/// `(…)`; the span of a parenthesised expression includes the parentheses.
fn parenthesised<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    expr.delimited_by(just(T::LParen), just(T::RParen))
        .map_with(move |mut inner: Expr, e| {
            inner.span = g.span(e.span());
            inner
        })
}

/// Operands joined by the operators of [`operators`]: one operator parser
/// per precedence class, because after every operand the pratt loop tries
/// each once, and fewer classes mean fewer failed attempts on the hot path.
fn with_operators<'t, 's: 't>(
    g: Ctx<'s>,
    atom: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    let binary =
        move |lhs: Expr, op: BinaryOp, rhs: Expr, e: &mut MapExtra<'t, '_, In<'t>, Ex>| Expr {
            span: g.span(e.span()),
            kind: ExprKind::Binary(Box::new(BinaryExpr { op, lhs, rhs })),
        };
    let class = move |precedence: Precedence| {
        let associativity = match precedence.associativity {
            Associativity::Left => left(u16::from(precedence.power)),
        };
        let op = select(move |t: T, _| {
            operators::binary_token(t)
                .filter(|(_, class)| class.power == precedence.power)
                .map(|(op, _)| op)
        });
        infix(associativity, op, binary)
    };
    let unary = prefix(
        u16::from(operators::PREFIX_POWER),
        select(|t: T, _| operators::unary_token(t)),
        move |op: UnaryOp, operand: Expr, e: &mut MapExtra<'t, '_, In<'t>, Ex>| Expr {
            span: g.span(e.span()),
            kind: ExprKind::Unary {
                op,
                operand: Box::new(operand),
            },
        },
    );
    // Destructured, so a class added to the table cannot be left out here.
    let [c0, c1, c2, c3, c4, c5, c6, c7, c8, c9, c10] = operators::PRECEDENCES;
    atom.pratt((
        unary,
        class(c0),
        class(c1),
        class(c2),
        class(c3),
        class(c4),
        class(c5),
        class(c6),
        class(c7),
        class(c8),
        class(c9),
        class(c10),
    ))
}

/// A variable reference: `R1`, `R[i]`, `NAME`, `NAME[i,j]`, `$SYS[…]`, and
/// axis names inside expressions (`X`, `X1`).
pub(crate) fn var_ref<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, VarRef, Ex> + Clone + 't {
    let r_or_axis = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(
            select! { T::Number => () }
                .map_with(|_, e| e.span())
                .or_not(),
        )
        .then(indices(expr.clone()).or_not())
        .try_map(move |((letter, digits), idx), span| {
            let digits = digits.filter(|d| d.start == letter.end);
            letter_reference(g, letter, digits, idx, span)
        });
    let named = select! { T::Ident => VarKind::Name, T::SystemVar => VarKind::System }
        .map_with(|k, e| (k, e.span()))
        .then(indices(expr).or_not())
        .map_with(move |((kind, name), idx), e| VarRef {
            span: g.span(e.span()),
            kind,
            name: g.name(name),
            indices: idx.unwrap_or_default(),
        });
    choice((r_or_axis, named))
}

/// A reference led by one letter: an R parameter (`R1`, `R[i]`) or an
/// axis name (`X`, `X1`, `X[i]`); `digits` are those touching the letter.
fn letter_reference(
    g: Ctx<'_>,
    letter: SimpleSpan,
    digits: Option<SimpleSpan>,
    idx: Option<Vec<Expr>>,
    span: SimpleSpan,
) -> Result<VarRef, SyntaxError> {
    let l = g.bytes(letter)[0].to_ascii_uppercase();
    match (l, digits, idx) {
        (b'R', Some(d), None) => {
            let text = g.text(d);
            if !text.bytes().all(|b| b.is_ascii_digit()) {
                return Err(SyntaxError::custom(
                    d,
                    codes::parse::INVALID_WORD,
                    format!("R parameter number `{text}` is not an integer"),
                    None,
                ));
            }
            Ok(VarRef {
                span: g.span(span),
                kind: VarKind::RParameter,
                name: "R".into(),
                indices: vec![Expr {
                    span: g.span(d),
                    kind: ExprKind::Number {
                        value: number_value(text).unwrap_or(0.0),
                        integer: true,
                    },
                }],
            })
        }
        (b'R', None, Some(idx)) => Ok(VarRef {
            span: g.span(span),
            kind: VarKind::RParameter,
            name: "R".into(),
            indices: idx,
        }),
        (_, Some(_), Some(_)) => Err(SyntaxError::custom(
            span,
            codes::parse::INVALID_WORD,
            format!(
                "`{}` cannot be indexed: a numbered address takes no `[…]`",
                g.text(SimpleSpan::from(letter.start..letter.end + 1))
            ),
            None,
        )),
        (_, Some(d), None) => {
            // An axis name with a number (`X1`) inside an expression.
            let text = g.text(d);
            if !text.bytes().all(|b| b.is_ascii_digit()) {
                return Err(SyntaxError::custom(
                    span,
                    codes::parse::INVALID_WORD,
                    "a number cannot follow an address letter inside an expression",
                    Some(
                        "write `=` values as expressions: `X=R1+5`; numbered axes need an integer, e.g. `X1`",
                    ),
                ));
            }
            Ok(VarRef {
                span: g.span(span),
                kind: VarKind::Name,
                name: g.name(SimpleSpan::from(letter.start..d.end)),
                indices: Vec::new(),
            })
        }
        (_, None, idx) => Ok(VarRef {
            span: g.span(span),
            kind: VarKind::Name,
            name: g.name(letter),
            indices: idx.unwrap_or_default(),
        }),
    }
}

/// The right side of `=`: an expression, `(a, b)`, `SET(…)` or `REP(…)`.
pub(crate) fn initializer<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Initializer, Ex> + Clone + 't {
    let list_items = expr
        .clone()
        .or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .delimited_by(just(T::LParen), just(T::RParen));
    let set = just(T::Set)
        .ignore_then(list_items.clone())
        .map_with(move |items, e| Initializer::List {
            span: g.span(e.span()),
            set: true,
            items,
        });
    let rep = just(T::Rep)
        .ignore_then(
            expr.clone()
                .separated_by(just(T::Comma))
                .at_least(1)
                .collect::<Vec<_>>()
                .delimited_by(just(T::LParen), just(T::RParen)),
        )
        .map_with(move |args, e| Initializer::Rep {
            span: g.span(e.span()),
            args,
        });
    // `(a, b, …)` with at least one comma is a list; `(a)` is an expression.
    let paren_list = list_items
        .filter(|items: &Vec<Option<Expr>>| items.len() > 1)
        .map_with(move |items, e| Initializer::List {
            span: g.span(e.span()),
            set: false,
            items,
        });
    choice((set, rep, paren_list, expr.map(Initializer::Expr)))
}
