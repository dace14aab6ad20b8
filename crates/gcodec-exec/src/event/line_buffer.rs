//! [`LineBuffer`]: where the JSONL and CSV writers build their lines, in
//! place, before they go to the writer in blocks.

use std::io::{self, Write};

/// The size at which a [`LineBuffer`] hands its lines to the writer.
const BLOCK: usize = 1 << 16;

/// Lines built straight into one buffer, which goes to the writer in
/// blocks of about 64 KiB: a line built apart and then copied into a
/// `BufWriter` was a second copy of every byte, and a call for each
/// line. [`LineBuffer::flush`], [`LineBuffer::into_inner`] or dropping
/// the buffer writes the rest.
pub(super) struct LineBuffer<W: Write> {
    /// `None` only after [`LineBuffer::into_inner`].
    out: Option<W>,
    /// Lines not yet written; a writer appends to it.
    pub(super) lines: Vec<u8>,
}

impl<W: Write> LineBuffer<W> {
    pub(super) fn new(writer: W) -> Self {
        Self {
            out: Some(writer),
            lines: Vec::with_capacity(BLOCK + 4096),
        }
    }

    /// Hands the lines to the writer once they fill a block: called after
    /// each line (or event).
    pub(super) fn line_done(&mut self) -> io::Result<()> {
        if self.lines.len() >= BLOCK {
            self.write_lines()?;
        }
        Ok(())
    }

    /// Writes every line and flushes the writer.
    pub(super) fn flush(&mut self) -> io::Result<()> {
        self.write_lines()?;
        self.out.as_mut().ok_or_else(taken)?.flush()
    }

    /// Writes every line, flushes, and gives the writer back.
    pub(super) fn into_inner(mut self) -> io::Result<W> {
        self.write_lines()?;
        let mut out = self.out.take().ok_or_else(taken)?;
        out.flush()?;
        Ok(out)
    }

    fn write_lines(&mut self) -> io::Result<()> {
        if self.lines.is_empty() {
            return Ok(());
        }
        let out = self.out.as_mut().ok_or_else(taken)?;
        let result = out.write_all(&self.lines);
        self.lines.clear();
        result
    }
}

/// The writer was given back (not reachable through the writers' API).
fn taken() -> io::Error {
    io::Error::other("the writer was given back")
}

impl<W: Write> Drop for LineBuffer<W> {
    /// Writes what is buffered, as a `BufWriter` does when dropped.
    fn drop(&mut self) {
        let _ = self.write_lines();
    }
}
