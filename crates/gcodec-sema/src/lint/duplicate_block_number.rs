//! `lint::duplicate_block_number`: a block number given to more than one
//! block. The control accepts it (a jump goes to the nearest in its
//! direction), but the operator's block search and a reader cannot tell
//! the blocks apart.

use std::collections::HashMap;

use gcodec_source::{Diagnostic, Span, codes};

use super::Context;

pub(super) fn check(cx: &Context<'_>, out: &mut Vec<Diagnostic>) {
    let mut first: HashMap<(bool, u64), Span> = HashMap::new();
    for block in &cx.program.blocks {
        let Some(number) = &block.number else {
            continue;
        };
        match first.get(&(number.main, number.value)) {
            Some(&earlier) => {
                let written = if number.main { ":" } else { "N" };
                out.push(
                    Diagnostic::new(
                        codes::lint::DUPLICATE_BLOCK_NUMBER,
                        format!(
                            "the block number `{written}{}` is given twice",
                            number.value
                        ),
                    )
                    .with_label(number.span, "given again here")
                    .with_label(earlier, "first given here")
                    .with_help("number the blocks in order, each number once"),
                );
            }
            None => {
                first.insert((number.main, number.value), number.span);
            }
        }
    }
}
