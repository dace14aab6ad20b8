//! Pages rendered to bytes on several threads and written in order: the
//! serialising of a large program's instructions is most of `gcodec
//! lower`'s work, and one thread doing it held the others up.

use std::io::{self, Write};

use rayon::prelude::*;

use super::Page;

/// Pages rendered at a time: enough for every thread to have one.
const BATCH: usize = 4;

/// Renders each of `pages` with `render` (its instructions, whether they
/// are the first of the document, the bytes to append to) on the rayon
/// pool, a few pages at a time, and writes the bytes in the pages'
/// order. True if any page had an instruction.
pub fn write_rendered(
    mut pages: impl Iterator<Item = Page>,
    out: &mut impl Write,
    render: impl Fn(&[gcodec_ail::Instruction], bool, &mut Vec<u8>) -> io::Result<()> + Sync,
) -> io::Result<bool> {
    let mut any = false;
    // Buffers written out come back for the next batch.
    let mut spare: Vec<Vec<u8>> = Vec::new();
    loop {
        let mut batch: Vec<(Page, bool, Vec<u8>)> = Vec::with_capacity(BATCH);
        for page in pages.by_ref().take(BATCH) {
            let first = !any;
            any |= !page.instructions().is_empty();
            batch.push((page, first, spare.pop().unwrap_or_default()));
        }
        if batch.is_empty() {
            return Ok(any);
        }
        let rendered: Vec<io::Result<Vec<u8>>> = batch
            .into_par_iter()
            .map(|(page, first, mut bytes)| {
                bytes.clear();
                render(page.instructions(), first, &mut bytes).map(|()| bytes)
            })
            .collect();
        for bytes in rendered {
            let bytes = bytes?;
            out.write_all(&bytes)?;
            spare.push(bytes);
        }
    }
}
