//! Checks of the variables a program reads and writes.

use gcodec_parser::ast;
use gcodec_source::Diagnostic;

use crate::sysvars;

use super::{Lowering, UNKNOWN_SYSTEM_VARIABLE};

impl Lowering<'_> {
    /// Reports the unknown system variables of an expression. Recursion
    /// follows the parser's bounded expression depth.
    pub(super) fn check_variables(&mut self, expr: &ast::Expr) {
        match &expr.kind {
            ast::ExprKind::Var { var } => self.check_variable(var),
            ast::ExprKind::Call(call) => {
                for arg in call.args.iter().flatten() {
                    self.check_variables(arg);
                }
            }
            ast::ExprKind::Unary { operand, .. } => self.check_variables(operand),
            ast::ExprKind::Binary(b) => {
                self.check_variables(&b.lhs);
                self.check_variables(&b.rhs);
            }
            _ => {}
        }
    }

    pub(super) fn check_variable(&mut self, var: &ast::VarRef) {
        if var.kind == ast::VarKind::System && sysvars::lookup(&var.name).is_none() {
            self.diagnostics.push(
                Diagnostic::error(
                    UNKNOWN_SYSTEM_VARIABLE,
                    format!("`{}` is not a system variable of the control", var.name),
                )
                .with_label(var.span, "unknown")
                .with_help("check the spelling against the SINUMERIK lists of system variables and machine data"),
            );
        }
        for index in &var.indices {
            self.check_variables(index);
        }
    }
}
