//! Interrupt routines (`gcodec_lang::interrupts`): `SETINT(3) PRIO=1
//! LIFT_Z LIFTFAST BLSYNC` assigns the routine `LIFT_Z` to input 3, and
//! `ENABLE(3)`, `DISABLE(3)`, `CLRINT(3)` act on the assignment. The
//! parser reads `SETINT`'s block word by word (a call of `SETINT`, an
//! assignment to `PRIO`, calls of `LIFT_Z`, `LIFTFAST`, `BLSYNC`); here
//! they are taken together, so that the routine is not called at once.

use std::ops::RangeInclusive;

use gcodec_ail::{InterruptAction, InterruptAssign, Op, Value};
use gcodec_lang::ggroups;
use gcodec_lang::interrupts::{self, BLOCK_SYNC, INPUTS, LIFT_FAST, PRIORITIES, PRIORITY};
use gcodec_parser::ast::{self, CallTarget, StatementKind};
use gcodec_source::{Diagnostic, Span, codes};

use crate::values;

use super::{BlockPlan, Lowering};

/// The interrupt switch a procedure name is, if any.
pub(super) fn control_action(upper: &str) -> Option<InterruptAction> {
    match upper {
        "ENABLE" => Some(InterruptAction::Enable),
        "DISABLE" => Some(InterruptAction::Disable),
        "CLRINT" => Some(InterruptAction::Clear),
        _ => None,
    }
}

/// The name of a call written without parentheses and passes (`LIFT_Z`),
/// upper case.
fn bare_name(statement: &ast::Statement) -> Option<String> {
    match &statement.kind {
        StatementKind::Call(call) if call.args.is_none() && call.passes.is_none() => {
            match &call.target {
                CallTarget::Name { name, .. } => Some(name.to_ascii_uppercase().to_string()),
                CallTarget::Number { .. } => None,
            }
        }
        _ => None,
    }
}

/// The input of `SETINT(3)`, `SETINT(R1)`: the one argument of a call
/// named `SETINT` (`None` when the statement is not one).
fn setint_args(statement: &ast::Statement) -> Option<(&[Option<ast::Expr>], Span)> {
    match &statement.kind {
        StatementKind::Call(call) => match (&call.target, &call.args) {
            (CallTarget::Name { name, .. }, Some(args)) if name.eq_ignore_ascii_case("SETINT") => {
                Some((args.as_slice(), statement.span))
            }
            _ => None,
        },
        _ => None,
    }
}

fn interrupt_error(message: String, span: Span, label: &str, help: &str) -> Diagnostic {
    Diagnostic::new(codes::lower::INTERRUPT, message)
        .with_label(span, label.to_owned())
        .with_help(help.to_owned())
}

impl Lowering<'_> {
    /// `SETINT(n) PRIO=p NAME [LIFTFAST] [BLSYNC]`: the interrupt
    /// assignment of `block`, if it has one, put in the plan; the indices
    /// of the statements it took are returned (the rest lower as usual).
    pub(super) fn interrupt_assignment(
        &mut self,
        block: &ast::Block,
        plan: &mut BlockPlan,
    ) -> Vec<usize> {
        let statements = &block.statements;
        let Some((at, (args, setint))) = statements
            .iter()
            .enumerate()
            .find_map(|(i, s)| setint_args(s).map(|found| (i, found)))
        else {
            return Vec::new();
        };
        let mut taken = vec![at];
        let input = self.interrupt_input("SETINT", args, setint);
        let mut priority = None;
        let mut routine: Option<(String, Span)> = None;
        let (mut lift_fast, mut block_sync) = (false, false);
        for (i, statement) in statements.iter().enumerate() {
            if let StatementKind::Assign(assign) = &statement.kind
                && assign.target.kind == ast::VarKind::Name
                && assign.target.indices.is_empty()
                && assign.target.name.eq_ignore_ascii_case(PRIORITY)
                && let ast::Initializer::Expr(expr) = &assign.value
            {
                taken.push(i);
                priority = Some(self.interrupt_number(PRIORITY, expr, &PRIORITIES));
                continue;
            }
            let Some(name) = bare_name(statement) else {
                continue;
            };
            match name.as_str() {
                LIFT_FAST => lift_fast = true,
                BLOCK_SYNC => block_sync = true,
                // `SETINT(3) PRIO=1 LIFT_Z G1`: a G command is no routine.
                _ if ggroups::lookup(&name).is_some() => continue,
                _ => {
                    if let Some((first, first_span)) = &routine {
                        self.diagnostics.push(
                            interrupt_error(
                                format!("`SETINT` names two routines, `{first}` and `{name}`"),
                                statement.span,
                                "second routine",
                                "an input has one interrupt routine; assign the other to another input in a block of its own",
                            )
                            .with_label(*first_span, "first routine"),
                        );
                    } else {
                        routine = Some((name, statement.span));
                    }
                }
            }
            taken.push(i);
        }
        if routine.is_none() && !lift_fast {
            self.diagnostics.push(interrupt_error(
                "`SETINT` names no interrupt routine".to_owned(),
                setint,
                "no routine",
                "name the routine after the priority (`SETINT(3) PRIO=1 LIFT_Z`), or write `LIFTFAST` for a fast retraction only",
            ));
        }
        // `Some(None)`: written, and rejected.
        if priority.is_none() {
            self.diagnostics.push(interrupt_error(
                "`SETINT` without a priority".to_owned(),
                setint,
                "no `PRIO=`",
                "give the priority 1…128 in the same block (`SETINT(3) PRIO=1 LIFT_Z`; 1 is the highest)",
            ));
        }
        if let (Some(input), Some(Some(priority))) = (input, priority) {
            plan.other.push((
                Op::InterruptAssign(Box::new(InterruptAssign {
                    input,
                    priority,
                    routine: routine.map(|(name, _)| name),
                    lift_fast,
                    block_sync,
                })),
                setint,
            ));
        }
        taken
    }

    /// `ENABLE(3)`, `DISABLE(R1)`, `CLRINT(3)`.
    pub(super) fn interrupt_control(
        &mut self,
        upper: &str,
        action: InterruptAction,
        args: &[Option<ast::Expr>],
        span: Span,
        plan: &mut BlockPlan,
    ) {
        if let Some(input) = self.interrupt_input(upper, args, span) {
            plan.other
                .push((Op::InterruptControl { action, input }, span));
        }
    }

    /// The one input in parentheses of `SETINT`, `ENABLE`, `DISABLE` or
    /// `CLRINT`; `None` when rejected (diagnostic pushed).
    fn interrupt_input(
        &mut self,
        what: &str,
        args: &[Option<ast::Expr>],
        span: Span,
    ) -> Option<Value> {
        match args {
            [Some(expr)] => self.interrupt_number("the input", expr, &INPUTS),
            _ => {
                self.diagnostics.push(interrupt_error(
                    format!("`{what}` takes one input, {} given", args.len()),
                    span,
                    "here",
                    "name the input 1…8 in parentheses: `SETINT(3)`, `ENABLE(3)`",
                ));
                None
            }
        }
    }

    /// An input or priority: a constant must be a whole number of `range`;
    /// a computed one is checked when the block runs.
    fn interrupt_number(
        &mut self,
        what: &str,
        expr: &ast::Expr,
        range: &RangeInclusive<u32>,
    ) -> Option<Value> {
        self.check_variables(expr);
        match values::constant(expr) {
            Some(n) if interrupts::in_range(n, range).is_none() => {
                self.diagnostics.push(interrupt_error(
                    format!(
                        "{what} {} is not a whole number {}…{}",
                        values::source_text(expr),
                        range.start(),
                        range.end()
                    ),
                    expr.span,
                    "out of range",
                    "the control has the fast inputs 1…8 and the priorities 1 (highest) … 128",
                ));
                None
            }
            _ => Some(values::value(expr)),
        }
    }
}
