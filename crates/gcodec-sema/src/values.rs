//! Syntax-tree expressions and word values as AIL values.

use std::borrow::Cow;

use gcodec_ail::{self as ail, Value};
use gcodec_lang::{DimensionMode, UnaryOp};
use gcodec_parser::ast::{self, ExprKind, WordValue};
use gcodec_source::Span;

/// An expression as an AIL value: a plain number stays a constant (so do
/// signed numbers, `-5`), anything else becomes a tree.
pub(crate) fn value(expr: &ast::Expr) -> Value {
    match constant(expr) {
        Some(v) => Value::Const(v),
        None => Value::Expr(Box::new(tree(expr))),
    }
}

/// The number an expression is written as, if it is one (`5`, `-5`, `+.5`).
pub(crate) fn constant(expr: &ast::Expr) -> Option<f64> {
    match &expr.kind {
        ExprKind::Number { value, .. } => Some(*value),
        ExprKind::Unary {
            op: UnaryOp::Neg,
            operand,
        } => constant(operand).map(|v| -v),
        ExprKind::Unary {
            op: UnaryOp::Plus,
            operand,
        } => constant(operand),
        _ => None,
    }
}

/// A word's value and its dimension modifier (`AC`, `IC`, …) if written.
pub(crate) fn word_value(value: &WordValue) -> (Value, Option<DimensionMode>) {
    match value {
        WordValue::Constant(n) => (Value::Const(n.value), None),
        WordValue::Assigned { modifier, expr } => {
            (self::value(expr), modifier.as_ref().map(|m| m.kind))
        }
    }
}

/// A whole number written as a constant (`M3`, `T=5`, `D1`), if the value
/// is one.
pub(crate) fn whole_number(value: &WordValue) -> Option<f64> {
    match value {
        WordValue::Constant(n) if n.integer => Some(n.value),
        WordValue::Assigned {
            modifier: None,
            expr,
        } => match &expr.kind {
            ExprKind::Number {
                value,
                integer: true,
            } => Some(*value),
            _ => None,
        },
        _ => None,
    }
}

/// The text at `span` of the program `source`, as written: a value out of
/// range is named so (`T0099999999999`), never through its REAL, which
/// drops leading zeros and changes the digits beyond the 15th.
pub(crate) fn written(source: &[u8], span: Span) -> Cow<'_, str> {
    source
        .get(span.start as usize..span.end as usize)
        .map_or(Cow::Borrowed(""), String::from_utf8_lossy)
}

/// The number a word's value is written as (`0099` of `T=0099`), for
/// naming it ([`written`]).
pub(crate) fn written_number<'s>(source: &'s [u8], value: &WordValue) -> Cow<'s, str> {
    let span = match value {
        WordValue::Constant(n) => n.span,
        WordValue::Assigned { expr, .. } => expr.span,
    };
    written(source, span)
}

/// An expression as the outline writes it, for the `raw` form of a
/// computed value (`M1=DIR`, `T=NAMES[I]`).
pub(crate) fn source_text(expr: &ast::Expr) -> String {
    let mut text = String::new();
    let _ = gcodec_parser::write_expr(expr, &mut text);
    text
}

/// The expression tree. Recursion follows the parser's bounded depth
/// (`MAX_EXPRESSION_DEPTH`, `MAX_OPERATORS_PER_BLOCK`).
pub(crate) fn tree(expr: &ast::Expr) -> ail::Expr {
    match &expr.kind {
        ExprKind::Number { value, .. } => ail::Expr::Number { value: *value },
        ExprKind::String { value } => ail::Expr::String {
            value: value.to_string(),
        },
        ExprKind::Bool { value } => ail::Expr::Bool { value: *value },
        ExprKind::Var { var } => variable(var),
        ExprKind::Call(call) => ail::Expr::Call {
            name: ail::Callee::named(&call.name),
            args: call.args.iter().map(|a| a.as_ref().map(tree)).collect(),
        },
        ExprKind::Unary { op, operand } => ail::Expr::Unary {
            operator: *op,
            operand: Box::new(tree(operand)),
        },
        ExprKind::Binary(b) => ail::Expr::Binary {
            operator: b.op,
            lhs: Box::new(tree(&b.lhs)),
            rhs: Box::new(tree(&b.rhs)),
        },
    }
}

/// A variable reference as an AIL variable.
pub(crate) fn variable(var: &ast::VarRef) -> ail::Expr {
    ail::Expr::Var {
        var_kind: match var.kind {
            ast::VarKind::RParameter => ail::VarKind::RParameter,
            ast::VarKind::Name => ail::VarKind::User,
            ast::VarKind::System => ail::VarKind::System,
        },
        name: match var.kind {
            ast::VarKind::RParameter => ail::VarName::Text(Cow::Borrowed("R")),
            ast::VarKind::Name => {
                ail::VarName::Text(Cow::Owned(var.name.to_ascii_uppercase().to_string()))
            }
            ast::VarKind::System => {
                ail::VarName::named(Cow::Owned(var.name.to_ascii_uppercase().to_string()))
            }
        },
        indices: var.indices.iter().map(tree).collect(),
    }
}
