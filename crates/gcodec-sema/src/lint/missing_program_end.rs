//! `lint::missing_program_end`: a main program that some path runs past
//! its last block without `M2`, `M30` (or `M17`): the program end is not
//! signalled, the modal state is not reset for the next program.

use gcodec_ail::Op;
use gcodec_source::{Diagnostic, codes};

use super::{Context, Findings};
use crate::ProgramKind;

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    if cx.kind != ProgramKind::Main {
        return;
    }
    let instructions = &cx.document.instructions;
    let Some(end) = instructions.iter().rposition(|i| matches!(i.op, Op::End)) else {
        return;
    };
    if !cx.graph.is_reached(end) {
        return;
    }
    // Point at the last block that does something; the end of the text
    // for a program without one.
    let last = (0..end)
        .rev()
        .find(|&i| !matches!(instructions[i].op, Op::Label { .. }));
    let span = last.map_or_else(|| cx.span_of(end), |i| cx.block_span_of(i));
    out.push(
        Diagnostic::new(
            codes::lint::MISSING_PROGRAM_END,
            "the main program can run past its last block without `M30` or `M2`",
        )
        .with_label(
            span,
            "the run goes on past this block to the end of the file",
        )
        .with_help("end the main program with `M30` (or `M2`)"),
    );
}
