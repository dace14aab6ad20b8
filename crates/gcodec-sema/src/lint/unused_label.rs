//! `lint::unused_label`: a label no jump, `REPEAT` section or `CASE` arm
//! of the program names. Advice: a label may be a mark for the operator's
//! block search or for a `CALL … BLOCK` of another program.

use gcodec_source::{Diagnostic, codes};
use rustc_hash::FxHashSet;

use super::{Context, Findings};

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    // A computed jump target or a `CALL BLOCK` of the program itself may
    // name any label.
    if cx.flow.returns().is_none() {
        return;
    }
    let targets: FxHashSet<usize> = cx.flow.edges().iter().map(|e| e.to).collect();
    let mut unused: Vec<(usize, &String)> = cx
        .flow
        .labels()
        .iter()
        .flat_map(|(name, blocks)| blocks.iter().map(move |&b| (b, name)))
        .filter(|(block, _)| !targets.contains(block))
        .collect();
    unused.sort_unstable();
    for (block, _) in unused {
        let Some(label) = cx.program.blocks.get(block).and_then(|b| b.label.as_ref()) else {
            continue;
        };
        out.push(
            Diagnostic::new(
                codes::lint::UNUSED_LABEL,
                format!("the label `{}` is never jumped to", label.name),
            )
            .with_label(label.span, "no jump, section or repetition names this")
            .with_help("remove the label, or use a comment to mark the place"),
        );
    }
}
