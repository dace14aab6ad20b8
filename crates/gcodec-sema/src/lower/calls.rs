//! Calls and signatures: subprogram and cycle calls by name and number,
//! `CALL`, `PCALL`, `MCALL`, `PROC` and `EXTERN`, and the argument checks
//! for calls whose signature the file declares.

use std::collections::HashMap;

use gcodec_ail::{Op, Value};
use gcodec_lang::ggroups;
use gcodec_lang::procedures::Procedure;
use gcodec_parser::ast::{self, CallTarget, JumpTarget, StatementKind};
use gcodec_source::{Diagnostic, Span, codes};

use crate::values;

use super::{BlockPlan, Lowering};
/// A signature the file declares: by a `PROC` of its own or `EXTERN`.
pub(super) struct Signature {
    /// Per parameter: its name (none in `EXTERN`) and whether it is `VAR`.
    params: Vec<(Option<String>, bool)>,
    /// Where it is declared, for the diagnostic.
    span: Span,
}

/// Adds the signature of `statement`, a `PROC` or `EXTERN` (else nothing
/// is added), to those of its program, by name in upper case. The later
/// declaration of a name wins, as a later `EXTERN` replaces an earlier one
/// on the control.
pub(super) fn add_signature(statement: &ast::Statement, found: &mut HashMap<String, Signature>) {
    let (name, signature) = match &statement.kind {
        StatementKind::Proc(proc) => (
            &proc.name,
            Signature {
                params: proc
                    .params
                    .iter()
                    .map(|p| (Some(p.name.to_string()), p.by_reference))
                    .collect(),
                span: proc.name_span,
            },
        ),
        StatementKind::Extern(decl) => (
            &decl.name,
            Signature {
                params: decl.params.iter().map(|p| (None, p.by_reference)).collect(),
                span: statement.span,
            },
        ),
        _ => return,
    };
    found.insert(name.to_ascii_uppercase().to_string(), signature);
}

impl Lowering<'_> {
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
        if let Some(action) = super::interrupts::control_action(upper)
            && let Some(args) = &call.args
        {
            return self.interrupt_control(upper, action, args, span, plan);
        }
        if upper == "EXTCALL"
            && let Some(args) = &call.args
        {
            return self.external_call(args, span, plan);
        }
        if upper == "MSG"
            && let Some(args) = &call.args
        {
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
        // A subprogram, cycle or predefined procedure: the executor finds
        // it on the search path or knows it.
        let op = self.subprogram_call(upper, call, span, false);
        plan.calls.push((op, span));
    }

    /// The `call` instruction of `NAME(args) P=n`, its arguments checked
    /// against the signature the file declares for `NAME`.
    fn subprogram_call(&mut self, upper: &str, call: &ast::Call, span: Span, modal: bool) -> Op {
        let args = call.args.as_deref().unwrap_or_default();
        for arg in args.iter().flatten() {
            self.check_variables(arg);
        }
        self.check_arguments(upper, args, span);
        let passes = call
            .passes
            .as_ref()
            .map(|p| values::word_value(&p.word.value(p.span)).0);
        Op::Call(Box::new(gcodec_ail::Call {
            target: upper.to_string(),
            target_expr: None,
            section: None,
            by_path: false,
            external: false,
            args: args.iter().map(|a| a.as_ref().map(values::value)).collect(),
            passes,
            modal,
        }))
    }

    /// Arguments against a declared signature: not more than it has, and
    /// a variable for each `VAR` parameter (the callee writes to it).
    fn check_arguments(&mut self, upper: &str, args: &[Option<ast::Expr>], span: Span) {
        let Some(signature) = self.outline.signatures.get(upper) else {
            if let Some(procedure) = Procedure::named(upper) {
                self.check_procedure_arity(procedure, args.len(), span);
            }
            return;
        };
        let declared = signature.span;
        if args.len() > signature.params.len() {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::TOO_MANY_ARGUMENTS,
                    format!(
                        "`{upper}` takes {} argument{}, this call passes {}",
                        signature.params.len(),
                        if signature.params.len() == 1 { "" } else { "s" },
                        args.len()
                    ),
                )
                .with_label(span, "this call")
                .with_label(declared, "declared here")
                .with_help("the control rejects the call (alarm 12340); leave out the extra arguments or fix the declaration"),
            );
        }
        let mut problems = Vec::new();
        for ((name, by_reference), arg) in signature.params.iter().zip(args) {
            let Some(arg) = arg else { continue };
            if *by_reference && !matches!(arg.kind, ast::ExprKind::Var { .. }) {
                problems.push((name.clone(), arg.span));
            }
        }
        for (name, at) in problems {
            let which = name.map_or_else(String::new, |n| format!(" `{n}`"));
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::ARGUMENT_NOT_VARIABLE,
                    format!("the parameter{which} of `{upper}` is `VAR`: it needs a variable"),
                )
                .with_label(at, "not a variable")
                .with_label(declared, "declared here")
                .with_help("the subprogram writes its result back through a `VAR` parameter; pass a variable or R parameter"),
            );
        }
    }

    /// A predefined procedure's arguments against its arity, where the
    /// catalogue's signature settles it.
    fn check_procedure_arity(&mut self, procedure: Procedure, count: usize, span: Span) {
        let arity = procedure.arity();
        if arity.accepts(count) {
            return;
        }
        let takes = match (arity.min, arity.max) {
            (0, Some(0)) => "no arguments".to_owned(),
            (1, Some(1)) => "1 argument".to_owned(),
            (n, Some(m)) if n == m => format!("{n} arguments"),
            (n, Some(m)) if m == n + 1 => format!("{n} or {m} arguments"),
            (n, Some(m)) => format!("{n} to {m} arguments"),
            (n, None) => format!("at least {n} arguments"),
        };
        let name = procedure.name();
        self.diagnostics.push(
            Diagnostic::new(
                codes::lower::ARGUMENT_COUNT,
                format!(
                    "the predefined procedure `{name}` takes {takes}, this call passes {count}"
                ),
            )
            .with_label(span, "this call")
            .with_help(format!(
                "the control rejects the call; pass {takes} to `{name}`"
            )),
        );
    }

    /// `CALL "NAME"`, `CALL PROGRAM1`, `CALL BLOCK A TO B`,
    /// `CALL "P" BLOCK "N10" TO "N20"`: the name is computed when the call
    /// runs; without one, the section of the calling program runs.
    pub(super) fn indirect_call(
        &mut self,
        call: &ast::IndirectCall,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let target_expr = call.program.as_ref().map(|p| {
            self.check_variables(p);
            values::tree(p)
        });
        let section = call
            .section
            .as_ref()
            .map(|(from, to)| gcodec_ail::CallSection {
                from: self.section_bound(from),
                to: self.section_bound(to),
            });
        plan.calls.push((
            Op::Call(Box::new(gcodec_ail::Call {
                target: String::new(),
                target_expr,
                section,
                by_path: false,
                external: false,
                args: Vec::new(),
                passes: None,
                modal: false,
            })),
            span,
        ));
    }

    /// `EXTCALL("/_N_EXT_DIR/SUB")`, `EXTCALL "SUB"`: a program from
    /// external storage, its name or path computed when the call runs.
    fn external_call(&mut self, args: &[Option<ast::Expr>], span: Span, plan: &mut BlockPlan) {
        let [Some(program)] = args else {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::INVALID_VALUE,
                    format!("`EXTCALL` takes one program name, {} given", args.len()),
                )
                .with_label(span, "here")
                .with_help("write `EXTCALL(\"NAME\")` or `EXTCALL(\"path/NAME\")`"),
            );
        };
        self.check_variables(program);
        plan.calls.push((
            Op::Call(Box::new(gcodec_ail::Call {
                target: String::new(),
                target_expr: Some(values::tree(program)),
                section: None,
                by_path: false,
                external: true,
                args: Vec::new(),
                passes: None,
                modal: false,
            })),
            span,
        ));
    }

    /// A label or block number of `CALL … BLOCK … TO …` as a STRING the
    /// executor searches in the called program.
    fn section_bound(&mut self, bound: &JumpTarget) -> Value {
        let text = match bound {
            JumpTarget::Label { name, .. } => name.to_ascii_uppercase().to_string(),
            JumpTarget::BlockNumber { value, .. } => crate::flow::number_text(*value),
            JumpTarget::Expr(e) => {
                self.check_variables(e);
                return values::value(e);
            }
        };
        Value::Expr(Box::new(gcodec_ail::Expr::String { value: text }))
    }

    /// `PCALL /_N_WKS_DIR/_N_W_WPD/_N_SUB_SPF(1,2)`: a call by path.
    pub(super) fn path_call(&mut self, call: &ast::PCall, span: Span, plan: &mut BlockPlan) {
        let args = call.args.as_deref().unwrap_or_default();
        for arg in args.iter().flatten() {
            self.check_variables(arg);
        }
        plan.calls.push((
            Op::Call(Box::new(gcodec_ail::Call {
                target: call.path.to_string(),
                target_expr: None,
                section: None,
                by_path: true,
                external: false,
                args: args.iter().map(|a| a.as_ref().map(values::value)).collect(),
                passes: None,
                modal: false,
            })),
            span,
        ));
    }

    /// `MCALL NAME(args)`: called after every later traversing block;
    /// `MCALL` alone ends it.
    pub(super) fn modal_call(&mut self, call: &ast::MCall, span: Span, plan: &mut BlockPlan) {
        let op = match &call.call {
            None => Op::CancelModalCall,
            Some(inner) => {
                let upper = match &inner.target {
                    CallTarget::Name { name, .. } => name.to_ascii_uppercase().to_string(),
                    CallTarget::Number { digits, .. } => format!("L{digits}"),
                };
                self.subprogram_call(&upper, inner, span, true)
            }
        };
        plan.calls.push((op, span));
    }

    /// `PROC NAME(REAL A, VAR INT B) SBLOF`: the program's signature. It
    /// must be the program's first block (language reference §8.5).
    pub(super) fn procedure(&mut self, proc: &ast::Proc, span: Span, plan: &mut BlockPlan) {
        if self.outline.first_statement != Some(span) {
            self.diagnostics.push(
                Diagnostic::new(codes::lower::PROC_NOT_FIRST, "`PROC` must open the program")
                    .with_label(span, "after other statements")
                    .with_help("the control accepts `PROC` only in the first block of a program; move it there"),
            );
        }
        let params = proc
            .params
            .iter()
            .map(|p| {
                if let Some(default) = &p.default {
                    self.check_variables(default);
                }
                self.check_string_length(&p.ty.kind);
                gcodec_ail::Parameter {
                    name: p.name.to_ascii_uppercase().to_string(),
                    data_type: crate::types::from_ast(&p.ty.kind),
                    by_reference: p.by_reference,
                    dims: p.dims.iter().map(values::value).collect(),
                    default: p.default.as_ref().map(values::value),
                }
            })
            .collect();
        plan.other.push((
            Op::Procedure(Box::new(gcodec_ail::Procedure {
                name: proc.name.to_ascii_uppercase().to_string(),
                params,
                attributes: proc
                    .attributes
                    .iter()
                    .map(|a| a.name.to_ascii_uppercase().to_string())
                    .collect(),
            })),
            span,
        ));
    }

    /// `EXTERN NAME(REAL, VAR INT)`: kept for the executor, and the
    /// signature calls in this file are checked against.
    pub(super) fn external(&mut self, decl: &ast::Extern, span: Span, plan: &mut BlockPlan) {
        let params = decl
            .params
            .iter()
            .map(|p| gcodec_ail::ExternalParameter {
                data_type: crate::types::from_ast(&p.ty.kind),
                by_reference: p.by_reference,
                dims: p
                    .dims
                    .iter()
                    .map(|d| d.as_ref().map(values::value))
                    .collect(),
            })
            .collect();
        plan.other.push((
            Op::External(Box::new(gcodec_ail::External {
                name: decl.name.to_ascii_uppercase().to_string(),
                params,
            })),
            span,
        ));
    }
}
