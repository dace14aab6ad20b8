//! `lint::change_without_tool`: the change M function of a main program
//! on a path where no tool has been selected since the start or since the
//! last change. The change then finds no pending selection
//! (`run::m6_without_pending` when it runs).

use gcodec_ail::{Op, ToolChangeTrigger};
use gcodec_source::{Diagnostic, codes};

use super::facts::Set;
use super::{Context, Findings};
use crate::ProgramKind;

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    // A subprogram changes the tool its caller selected.
    if cx.kind != ProgramKind::Main {
        return;
    }
    for (at, instruction) in cx.document.instructions.iter().enumerate() {
        let Op::ToolChange {
            trigger: ToolChangeTrigger::M6,
        } = instruction.op
        else {
            continue;
        };
        if cx.graph.is_reached(at) && cx.facts.may_hold(at, Set::NO_SELECTION) {
            out.push(
                Diagnostic::new(
                    codes::lint::CHANGE_WITHOUT_TOOL,
                    "a tool change with no tool selected before it on some path",
                )
                .with_label(cx.span_of(at), "this change finds no selected tool")
                .with_help(
                    "select the tool to change to with `T` before the change, or in its block",
                ),
            );
        }
    }
}
