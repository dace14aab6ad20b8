//! A source's line table, and reading a large file with it.
//!
//! Reading the file and finding its lines are the steps of a run before
//! any other thread starts (a streamed run cuts its chunks from the line
//! table), so a large file is mapped rather than read (on Unix), and its
//! lines are found on two threads, each in its half of the file.

#[cfg(unix)]
use std::fs::File;
#[cfg(unix)]
use std::io;

#[cfg(unix)]
use crate::SourceBytes;

/// Files larger than this cannot be addressed by 32-bit spans.
pub const MAX_SOURCE_LEN: usize = u32::MAX as usize - 1;

/// Sources from this size on are mapped (on Unix) and have their lines
/// found on two threads.
const PARALLEL_FROM: usize = 1 << 22;

/// The offset of every line's start: 0, then every offset after a `\n`
/// (the table [`crate::SourceFile::line_starts`] holds).
pub fn line_starts(bytes: &[u8]) -> Vec<u32> {
    line_table(bytes).starts
}

/// A source's line table, and whether all its bytes are ASCII, found in
/// the same pass: ASCII text is valid UTF-8 without a second pass over
/// a large file to check it.
#[derive(Debug)]
pub(crate) struct LineTable {
    pub(crate) starts: Vec<u32>,
    pub(crate) ascii: bool,
}

/// The [`LineTable`] of `bytes`.
pub(crate) fn line_table(bytes: &[u8]) -> LineTable {
    let mut starts = Vec::with_capacity(bytes.len() / 24 + 1);
    starts.push(0);
    if bytes.len() < PARALLEL_FROM {
        let ascii = push_line_starts(bytes, 0, &mut starts);
        return LineTable { starts, ascii };
    }
    // The second half's lines on another thread.
    let middle = bytes.len() / 2;
    let (first, second) = bytes.split_at(middle);
    let (first_ascii, (rest, rest_ascii)) = std::thread::scope(|scope| {
        let rest = scope.spawn(|| {
            let mut rest = Vec::with_capacity(second.len() / 24 + 1);
            let ascii = push_line_starts(second, middle, &mut rest);
            (rest, ascii)
        });
        let first_ascii = push_line_starts(first, 0, &mut starts);
        let rest = rest
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (first_ascii, rest)
    });
    starts.extend_from_slice(&rest);
    LineTable {
        starts,
        ascii: first_ascii && rest_ascii,
    }
}

/// The bytes of `file` from `offset` to `len`, mapped rather than read
/// ([`SourceBytes`]), and their line table, found on two threads; `None`
/// for fewer bytes than are worth it (the caller then reads the file).
#[cfg(unix)]
pub(crate) fn map_large(
    file: &File,
    offset: u64,
    len: u64,
) -> io::Result<Option<(SourceBytes, LineTable)>> {
    let (Ok(offset), Ok(len)) = (usize::try_from(offset), usize::try_from(len)) else {
        return Ok(None);
    };
    if len.saturating_sub(offset) < PARALLEL_FROM {
        return Ok(None);
    }
    let bytes = SourceBytes::mapped(file, offset, len)?;
    let table = line_table(&bytes);
    Ok(Some((bytes, table)))
}

/// Pushes the offset after each `\n` of `part`, which starts at `base`;
/// whether every byte of `part` is ASCII.
///
/// Sixteen bytes at a time (SSE2, part of every x86_64 target): a search
/// for each line end (`memchr`) starts anew for every line, and lines of
/// large programs are short.
#[cfg(target_arch = "x86_64")]
fn push_line_starts(part: &[u8], base: usize, starts: &mut Vec<u32>) -> bool {
    use std::arch::x86_64::{
        __m128i, _mm_cmpeq_epi8, _mm_loadu_si128, _mm_movemask_epi8, _mm_set1_epi8,
    };
    const LANES: usize = 16;
    let mut blocks = part.chunks_exact(LANES);
    let mut at = base;
    // The bytes' high bits, gathered: none set in ASCII.
    let mut high = 0;
    for block in blocks.by_ref() {
        // SAFETY: SSE2 is there on every x86_64 target; the load reads the
        // sixteen bytes of `block`, unaligned loads allowed.
        let (mut newlines, high_bits) = unsafe {
            let v = _mm_loadu_si128(block.as_ptr().cast::<__m128i>());
            let newline = _mm_cmpeq_epi8(v, _mm_set1_epi8(b'\n' as i8));
            (_mm_movemask_epi8(newline) as u32, _mm_movemask_epi8(v))
        };
        high |= high_bits;
        while newlines != 0 {
            starts.push((at + newlines.trailing_zeros() as usize) as u32 + 1);
            newlines &= newlines - 1;
        }
        at += LANES;
    }
    let rest = blocks.remainder();
    starts.extend(memchr::memchr_iter(b'\n', rest).map(|i| (at + i) as u32 + 1));
    high == 0 && rest.is_ascii()
}

/// [`push_line_starts`] where SSE2 is not there.
#[cfg(not(target_arch = "x86_64"))]
fn push_line_starts(part: &[u8], base: usize, starts: &mut Vec<u32>) -> bool {
    starts.extend(memchr::memchr_iter(b'\n', part).map(|i| (base + i) as u32 + 1));
    part.is_ascii()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A large source, with a line end just before, at or after the
    /// middle where it is split.
    pub(crate) fn large_sources() -> Vec<Vec<u8>> {
        let mut base = Vec::new();
        while base.len() < PARALLEL_FROM + 100 {
            base.extend_from_slice(b"N10 G1 X1 Y2\r\n");
        }
        base.push(b'Z');
        let middle = base.len() / 2;
        [middle - 1, middle, middle + 1]
            .into_iter()
            .map(|at| {
                let mut bytes = base.clone();
                bytes[at] = b'\n';
                bytes
            })
            .collect()
    }

    /// The line table of `bytes`, by the plainest scan.
    pub(crate) fn one_scan(bytes: &[u8]) -> Vec<u32> {
        let mut expected = vec![0];
        expected.extend(
            (0..bytes.len())
                .filter(|&i| bytes[i] == b'\n')
                .map(|i| i as u32 + 1),
        );
        expected
    }

    /// The table found on two threads is the one a plain scan gives.
    #[test]
    fn line_starts_of_a_large_source_are_those_of_one_scan() {
        for bytes in large_sources() {
            assert_eq!(line_starts(&bytes), one_scan(&bytes));
        }
    }

    /// Short sources of every length around the blocks the scan reads, with
    /// line ends and a byte beyond ASCII at every place: the table of a
    /// plain scan, and ASCII exactly when every byte is.
    #[test]
    fn line_tables_are_those_of_one_scan() {
        for len in 0..70 {
            for at in 0..len {
                for byte in [b'\n', 0xC3, 0x80, 0xFF] {
                    let mut bytes: Vec<u8> = (0..len).map(|i| b"G1 X5\n"[i % 6]).collect();
                    bytes[at] = byte;
                    let table = line_table(&bytes);
                    assert_eq!(table.starts, one_scan(&bytes), "{len} {at} {byte}");
                    assert_eq!(table.ascii, bytes.is_ascii(), "{len} {at} {byte}");
                }
            }
        }
    }

    /// A large source is ASCII unless a byte of either half is not.
    #[test]
    fn a_large_source_is_ascii_unless_a_byte_is_not() {
        let bytes = &large_sources()[0];
        assert!(line_table(bytes).ascii);
        for at in [0, bytes.len() / 2 - 1, bytes.len() / 2, bytes.len() - 1] {
            let mut other = bytes.clone();
            other[at] = 0xE9;
            let table = line_table(&other);
            assert!(!table.ascii, "byte {at}");
            assert_eq!(table.starts, one_scan(&other), "byte {at}");
        }
    }
}
