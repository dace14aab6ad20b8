//! Chunks: runs of whole lines, the unit a streamed run parses, lowers
//! and runs at a time.

/// A run of whole lines of a source: the unit a streamed run parses,
/// lowers and runs at a time (no token crosses a line end).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Chunk {
    /// The bytes of its lines, line ends included.
    pub bytes: std::ops::Range<usize>,
    /// The index of its first block (line) in the program.
    pub first_block: usize,
    /// How many blocks (lines) it holds.
    pub blocks: usize,
}

/// Cuts `src` into chunks of `lines` lines each (the last may be
/// shorter). A source without lines is one empty chunk.
pub fn chunks(src: &[u8], lines: usize) -> Vec<Chunk> {
    chunks_at(&gcodec_source::line_starts(src), src.len(), lines)
}

/// [`chunks`] of a source of `len` bytes whose lines start at
/// `line_starts` (0, then every offset after a `\n`, as
/// [`gcodec_source::SourceFile::line_starts`] gives them): no second scan
/// of the bytes, which on large files is a serial step before any thread
/// starts.
pub fn chunks_at(line_starts: &[u32], len: usize, lines: usize) -> Vec<Chunk> {
    let lines = lines.max(1);
    // The offsets after each line end; the first line starts at 0.
    let ends = line_starts.get(1..).unwrap_or_default();
    let mut chunks = Vec::with_capacity(ends.len() / lines + 1);
    let mut start = 0;
    let mut first_block = 0;
    for full in ends.chunks_exact(lines) {
        let end = full[lines - 1] as usize;
        chunks.push(Chunk {
            bytes: start..end,
            first_block,
            blocks: lines,
        });
        first_block += lines;
        start = end;
    }
    // The last lines, the last without a line end; a source without
    // lines is one empty chunk.
    if start < len || chunks.is_empty() {
        let ended = ends.len() % lines;
        let unended = ends.last().map_or(0, |&e| e as usize) < len;
        chunks.push(Chunk {
            bytes: start..len,
            first_block,
            blocks: ended + usize::from(unended),
        });
    }
    chunks
}
