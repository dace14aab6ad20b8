//! `lint::unreachable_code`: blocks no path from the program's start
//! reaches: after `M30`, `M2`, `M17` or `RET` with no jump to them, or
//! after an unconditional jump. One finding per run of such blocks.

use gcodec_ail::Op;
use gcodec_parser::ast::StatementKind;
use gcodec_source::{Diagnostic, codes};

use super::{Context, Findings};

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    let instructions = &cx.document.instructions;
    let mut at = 0;
    while at < instructions.len() {
        if cx.graph.is_reached(at) || !is_code(cx, at) {
            at += 1;
            continue;
        }
        // A run of instructions none of which is reached; the blocks
        // between them that lower to nothing (comments) belong to it.
        let first = at;
        let mut last = at;
        while at < instructions.len() && !cx.graph.is_reached(at) {
            if is_code(cx, at) {
                last = at;
            }
            at += 1;
        }
        let span = cx.block_span_of(first).cover(cx.block_span_of(last));
        // The nearest reached instruction before: where control stops.
        let stop = (0..first)
            .rev()
            .find(|&i| cx.graph.is_reached(i))
            .filter(|&i| !cx.graph.falls_through(i));
        let mut d = Diagnostic::new(codes::lint::UNREACHABLE_CODE, message(cx, stop))
            .with_label(span, "no path reaches this");
        if let Some(stop) = stop {
            d = d.with_label(cx.span_of(stop), "control does not go on after this");
        }
        out.push(d.with_help(
            "remove the blocks, or jump to them (a label and a `GOTO`) if they are meant to run",
        ));
    }
}

/// What the program does before the unreached code, in words.
fn message(cx: &Context<'_>, stop: Option<usize>) -> String {
    match stop.map(|i| &cx.document.instructions[i].op) {
        Some(Op::MFunction(m)) => format!("code after `{}` that no jump reaches", m.raw),
        Some(Op::Return { .. }) => "code after the return that no jump reaches".to_owned(),
        Some(Op::Jump { .. }) => "code after an unconditional jump that no jump reaches".to_owned(),
        _ => "code that no path through the program reaches".to_owned(),
    }
}

/// Whether instruction `at` is code a user wrote: not one of the labels
/// and jumps a control structure lowers to, nor the end of the text.
fn is_code(cx: &Context<'_>, at: usize) -> bool {
    match &cx.document.instructions[at].op {
        Op::End | Op::Label { .. } | Op::SkipBlock { .. } => false,
        Op::Jump { .. } => {
            let line = cx.document.instructions[at].source.line as usize;
            cx.program
                .blocks
                .get(line.wrapping_sub(1))
                .is_some_and(|b| {
                    b.statements.iter().any(|s| {
                        matches!(s.kind, StatementKind::Goto(_) | StatementKind::IfGoto(_))
                    })
                })
        }
        _ => true,
    }
}
