//! `lint::duplicate_block_number`: a block number given to more than one
//! block. The control accepts it (a jump goes to the nearest in its
//! direction), but the operator's block search and a reader cannot tell
//! the blocks apart.

use gcodec_source::{Diagnostic, codes};

use super::{Context, Findings};

pub(super) fn check(cx: &Context<'_>, out: &mut Findings) {
    // (main block, number, block): sorted, equal numbers side by side with
    // their first block first. Block numbers mostly rise through a
    // program, so the sort has little to do (a hash map cost the check a
    // tenth of its time on numbered programs).
    let mut numbers: Vec<(bool, u64, usize)> = cx
        .program
        .blocks
        .iter()
        .enumerate()
        .filter_map(|(at, b)| b.number.as_ref().map(|n| (n.main, n.value, at)))
        .collect();
    numbers.sort_unstable();
    for pair in numbers.windows(2) {
        let [(main, value, _), (next_main, next_value, again)] = pair else {
            continue;
        };
        if (main, value) != (next_main, next_value) {
            continue;
        }
        let first = numbers.partition_point(|n| (n.0, n.1) < (*main, *value));
        let blocks = &cx.program.blocks;
        let (Some(earlier), Some(again)) = (
            blocks[numbers[first].2].number.as_ref(),
            blocks[*again].number.as_ref(),
        ) else {
            continue;
        };
        let written = if *main { ":" } else { "N" };
        out.push(
            Diagnostic::new(
                codes::lint::DUPLICATE_BLOCK_NUMBER,
                format!("the block number `{written}{value}` is given twice"),
            )
            .with_label(again.span, "given again here")
            .with_label(earlier.span, "first given here")
            .with_help("number the blocks in order, each number once"),
        );
    }
}
