//! The listing of `gcodec lower --format text`, written as the pages
//! come: the lines [`gcodec_ail::write_listing`] writes of the whole
//! document, pages on several threads
//! ([`super::rendered::write_rendered`]).

use std::io::{self, Write};

use gcodec_ail::write_instruction_listing;

use super::Page;
use super::rendered::write_rendered;

/// Writes `pages` as the listing [`gcodec_ail::write_listing`] writes of
/// their document.
pub fn write_listing(pages: impl Iterator<Item = Page>, out: &mut impl Write) -> io::Result<()> {
    write_rendered(pages, out, |instructions, _, bytes| {
        let mut line = String::new();
        for instruction in instructions {
            line.clear();
            // Writing to a `String` does not fail.
            let _ = write_instruction_listing(instruction, &mut line);
            bytes.extend_from_slice(line.as_bytes());
        }
        Ok(())
    })
    .map(|_| ())
}
