//! Statements other than words and control flow: declarations,
//! assignments, frames, calls, messages and returns.

use gcodec_ail::{Op, Value};
use gcodec_parser::ast::{self, StatementKind};

use crate::values;

use super::{BlockPlan, Lowering};

impl Lowering<'_> {
    pub(super) fn statement(
        &mut self,
        block: &ast::Block,
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
            | StatementKind::IfGoto(_)
            | StatementKind::Case(_)
            | StatementKind::RepeatSection(_) => self.flow_statement(index, statement, plan),
            // Their labels and jumps come from the structure pairing.
            StatementKind::Else
            | StatementKind::EndIf
            | StatementKind::EndWhile
            | StatementKind::Loop
            | StatementKind::EndLoop
            | StatementKind::Repeat => {}
            StatementKind::Def(def) => self.declare(def, span, plan),
            StatementKind::Frame(frame) => self.frame(block, frame, span, plan),
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
            StatementKind::Assign(assign) => {
                // `FAD=5`, `SPOS2=90`, `XV=10`: addresses the parser reads
                // as assignments.
                if !self.address_assignment(assign, span, plan) {
                    self.assign(assign, span, plan);
                }
            }
            StatementKind::Redef(redef) => self.redefine(redef, span),
            StatementKind::Define(define) => self.define_macro(define, span),
            StatementKind::Call(call) => self.call(call, span, plan),
            StatementKind::IndirectCall(call) => self.indirect_call(call, span, plan),
            StatementKind::PCall(call) => self.path_call(call, span, plan),
            StatementKind::MCall(call) => self.modal_call(call, span, plan),
            StatementKind::Proc(proc) => self.procedure(proc, span, plan),
            // The end of a procedure's text: a return.
            StatementKind::EndProc => plan.tail.push((Op::Return { values: Vec::new() }, span)),
            StatementKind::Extern(decl) => self.external(decl, span, plan),
            kind => self.not_lowered(span, statement_name(kind)),
        }
    }
}

/// How a statement kind [`Lowering::statement`] does not lower is named
/// in its warning.
fn statement_name(kind: &StatementKind) -> &'static str {
    use StatementKind as S;
    match kind {
        S::SyncAction(_) => "a synchronous action",
        _ => "this statement",
    }
}
