//! `lint::jump_into_structure`: a `GOTO…` from outside a loop or `IF` to a
//! block inside its body. The control checks the nesting of structures
//! only as it runs them: entering a body sideways skips its opening, so
//! the closing keyword finds no structure to close (the manuals: do not
//! mix control structures with jumps).

use gcodec_parser::ast::{ControlStructure, StructureKind};
use gcodec_source::{Diagnostic, codes};

use super::{Context, Findings};

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    let structures: Vec<(&ControlStructure, usize)> = cx
        .program
        .structures
        .iter()
        .filter_map(|s| Some((s, s.close? as usize)))
        .collect();
    if structures.is_empty() {
        return;
    }
    let mut jumps: Vec<_> = cx.flow.edges().iter().filter(|e| e.is_jump).collect();
    // Structures by their opening block, the open ones swept in order of
    // the jumps' targets: a target is inside the few structures open at
    // it (nesting is at most 16 deep), not inside all of them.
    let mut by_open: Vec<usize> = (0..structures.len()).collect();
    by_open.sort_by_key(|&i| structures[i].0.open);
    jumps.sort_by_key(|e| e.to);
    let mut next = 0;
    let mut open: Vec<usize> = Vec::new();
    for jump in jumps {
        while next < by_open.len() && (structures[by_open[next]].0.open as usize) < jump.to {
            open.push(by_open[next]);
            next += 1;
        }
        open.retain(|&i| structures[i].1 >= jump.to);
        let entered = open.iter().map(|&i| structures[i]).find(|(s, close)| {
            let from = jump.from;
            from < s.open as usize || from > *close
        });
        let Some((structure, _)) = entered else {
            continue;
        };
        let (Some(from), Some(opener)) = (
            cx.program.blocks.get(jump.from),
            cx.program.blocks.get(structure.open as usize),
        ) else {
            continue;
        };
        let what = match structure.kind {
            StructureKind::If => "an `IF` body",
            StructureKind::While => "a `WHILE` loop",
            StructureKind::For => "a `FOR` loop",
            StructureKind::Loop => "a `LOOP`",
            StructureKind::Repeat => "a `REPEAT` loop",
        };
        out.push(
            Diagnostic::new(
                codes::lint::JUMP_INTO_STRUCTURE,
                format!("a jump into {what} from outside it"),
            )
            .with_label(from.span, "this jump")
            .with_label(
                cx.program.blocks.get(jump.to).map_or(from.span, |b| b.span),
                "lands inside the body",
            )
            .with_label(opener.span, "the structure opens here")
            .with_help("jump to the block that opens the structure, or out of it, not into it"),
        );
    }
}
