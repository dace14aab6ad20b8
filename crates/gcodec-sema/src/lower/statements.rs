//! Statements other than words and control flow: declarations,
//! assignments, frames, calls, messages and returns.

use gcodec_ail::{AxisValue, Op, Value};
use gcodec_parser::ast::{self, CallTarget, StatementKind};
use gcodec_source::Span;

use crate::{ggroups, values};

use super::{BlockPlan, Lowering, axis_name};

impl Lowering<'_> {
    pub(super) fn statement(
        &mut self,
        index: usize,
        statement: &ast::Statement,
        plan: &mut BlockPlan,
    ) {
        let span = statement.span;
        match &statement.kind {
            StatementKind::If(_)
            | StatementKind::While(_)
            | StatementKind::Until(_)
            | StatementKind::For(_)
            | StatementKind::EndFor
            | StatementKind::Goto(_)
            | StatementKind::IfGoto(_) => self.flow_statement(index, statement, plan),
            // Their labels and jumps come from the structure pairing.
            StatementKind::Else
            | StatementKind::EndIf
            | StatementKind::EndWhile
            | StatementKind::Loop
            | StatementKind::EndLoop
            | StatementKind::Repeat => {}
            StatementKind::Def(def) => self.declare(def, span, plan),
            // `TRANS X10 Y5`, `AROT RPL=45`, `MIRROR X0`; the bare keyword
            // resets. The executor composes the frame chain.
            StatementKind::Frame(frame) => {
                let values = frame
                    .words
                    .iter()
                    .map(|w| {
                        let value = w.word.value(w.span);
                        if let ast::WordValue::Assigned { expr, .. } = &*value {
                            self.check_variables(expr);
                        }
                        let (value, mode) = values::word_value(&value);
                        AxisValue {
                            axis: axis_name(w.word.address()),
                            value,
                            mode,
                        }
                    })
                    .collect();
                plan.other.push((
                    Op::Frame {
                        op: frame.op.keyword().to_owned(),
                        values,
                    },
                    span,
                ));
            }
            StatementKind::Ret(ret) => {
                let values = ret
                    .args
                    .iter()
                    .flatten()
                    .map(|a| a.as_ref().map_or(Value::Const(0.0), values::value))
                    .collect();
                plan.tail.push((Op::Return { values }, span));
            }
            StatementKind::Word(word) => self.word(word, span, plan),
            StatementKind::Assign(assign) => match &assign.value {
                ast::Initializer::Expr(e) => {
                    self.check_variable(&assign.target);
                    self.check_variables(e);
                    plan.other.push((
                        Op::Assign {
                            target: Box::new(values::variable(&assign.target)),
                            value: values::value(e),
                        },
                        span,
                    ));
                }
                _ => self.not_lowered(span, "an assignment of a list of values"),
            },
            StatementKind::Call(call) => self.call(call, span, plan),
            kind => self.not_lowered(span, statement_name(kind)),
        }
    }

    /// `DEF TYPE name[dims]=init, …`: one declaration per variable.
    pub(super) fn declare(&mut self, def: &ast::Def, span: Span, plan: &mut BlockPlan) {
        let data_type = match &def.ty.kind {
            ast::TypeKind::Int => "INT",
            ast::TypeKind::Real => "REAL",
            ast::TypeKind::Bool => "BOOL",
            ast::TypeKind::Char => "CHAR",
            ast::TypeKind::String { .. } => "STRING",
            ast::TypeKind::Axis => "AXIS",
            ast::TypeKind::Frame => "FRAME",
        };
        for var in &def.vars {
            let init = match &var.init {
                None => Vec::new(),
                Some(ast::Initializer::Expr(e)) => vec![Some(values::value(e))],
                Some(ast::Initializer::List { items, .. }) => items
                    .iter()
                    .map(|i| i.as_ref().map(values::value))
                    .collect(),
                Some(ast::Initializer::Rep { .. }) => {
                    self.not_lowered(var.span, "a `REP` initialiser");
                    continue;
                }
            };
            plan.other.push((
                Op::Declare(Box::new(gcodec_ail::Declare {
                    name: var.name.to_ascii_uppercase().to_string(),
                    data_type: data_type.to_owned(),
                    dims: var.dims.iter().map(values::value).collect(),
                    init,
                })),
                span,
            ));
        }
    }

    pub(super) fn call(&mut self, call: &ast::Call, span: Span, plan: &mut BlockPlan) {
        let name = match &call.target {
            CallTarget::Name { name, .. } => name.clone(),
            // `L123`: the program `L123`, digits as written.
            CallTarget::Number { digits, .. } => format!("L{digits}").into(),
        };
        let upper = name.to_ascii_uppercase();
        let upper = upper.as_str();
        if call.args.is_none() {
            // `DIAMON`, `SUPA`, `CFC`: G commands written as names.
            if let Some((group, index)) = ggroups::lookup(upper) {
                return self.g_code(group, index, span, plan);
            }
            if upper == "STOPRE" {
                return plan.other.push((
                    Op::Stop {
                        reason: upper.to_string(),
                    },
                    span,
                ));
            }
        }
        if upper == "MSG" {
            if let Some(args) = &call.args {
                let text = match args.as_slice() {
                    [] => Some(Value::Expr(Box::new(gcodec_ail::Expr::String {
                        value: String::new(),
                    }))),
                    [Some(text)] | [Some(text), _] => {
                        self.check_variables(text);
                        Some(Value::Expr(Box::new(values::tree(text))))
                    }
                    _ => None,
                };
                if let Some(text) = text {
                    return plan.other.push((Op::Message { text }, span));
                }
            }
        }
        // A subprogram, cycle or predefined procedure: the executor finds
        // it on the search path or knows it.
        let args = call.args.as_deref().unwrap_or_default();
        for arg in args.iter().flatten() {
            self.check_variables(arg);
        }
        let passes = call
            .passes
            .as_ref()
            .map(|p| values::word_value(&p.word.value(p.span)).0);
        plan.calls.push((
            Op::Call(Box::new(gcodec_ail::Call {
                target: upper.to_string(),
                args: args.iter().map(|a| a.as_ref().map(values::value)).collect(),
                passes,
                modal: false,
            })),
            span,
        ));
    }
}

/// How a statement kind [`Lowering::statement`] does not lower is named
/// in its warning.
fn statement_name(kind: &StatementKind) -> &'static str {
    use StatementKind as S;
    match kind {
        S::Redef(_) => "`REDEF`",
        S::Define(_) => "`DEFINE`",
        S::Proc(_) => "`PROC`",
        S::EndProc => "`ENDPROC`",
        S::Extern(_) => "`EXTERN`",
        S::IndirectCall(_) => "`CALL`",
        S::PCall(_) => "`PCALL`",
        S::MCall(_) => "`MCALL`",
        S::RepeatSection(_) => "`REPEAT` of a section",
        S::Case(_) => "`CASE`",
        S::SyncAction(_) => "a synchronous action",
        _ => "this statement",
    }
}
