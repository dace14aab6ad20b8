//! `lint::compensation_left_active`: tool radius compensation (`G41`,
//! `G42`) on, on some path, at a tool change or at the end of a main
//! program. The control wants `G40` first: a change with compensation on
//! moves the equidistant path with the new radius, and the next program
//! starts with compensation on.

use gcodec_ail::{Op, ToolChangeTrigger};
use gcodec_source::{Diagnostic, codes};

use super::facts::Set;
use super::graph::ends_program;
use super::{Context, Findings};
use crate::ProgramKind;

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    for (at, instruction) in cx.document.instructions.iter().enumerate() {
        let place = match &instruction.op {
            Op::ToolChange {
                trigger: ToolChangeTrigger::M6,
            } => "at this tool change",
            // The end of a subprogram hands compensation back to its
            // caller, which may mean it.
            op if ends_program(op) && cx.kind == ProgramKind::Main => {
                if matches!(op, Op::End) {
                    "at the end of the program"
                } else {
                    "at this program end"
                }
            }
            _ => continue,
        };
        if cx.graph.is_reached(at) && cx.facts.may_hold(at, Set::COMPENSATION) {
            let span = if matches!(instruction.op, Op::End) {
                cx.block_span_of(at)
            } else {
                cx.span_of(at)
            };
            out.push(
                Diagnostic::new(
                    codes::lint::COMPENSATION_LEFT_ACTIVE,
                    format!("tool radius compensation (`G41`/`G42`) is still on {place}"),
                )
                .with_label(span, "compensation may be on here")
                .with_help("switch compensation off with `G40` in a motion block before it"),
            );
        }
    }
}
