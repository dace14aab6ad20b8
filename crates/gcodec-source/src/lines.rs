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
    let mut starts = Vec::with_capacity(bytes.len() / 24 + 1);
    starts.push(0);
    if bytes.len() < PARALLEL_FROM {
        push_line_starts(bytes, 0, &mut starts);
        return starts;
    }
    // The second half's lines on another thread.
    let middle = bytes.len() / 2;
    let (first, second) = bytes.split_at(middle);
    let rest = std::thread::scope(|scope| {
        let rest = scope.spawn(|| {
            let mut rest = Vec::with_capacity(second.len() / 24 + 1);
            push_line_starts(second, middle, &mut rest);
            rest
        });
        push_line_starts(first, 0, &mut starts);
        rest.join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    });
    starts.extend_from_slice(&rest);
    starts
}

/// The bytes of `file` from `offset` to `len`, mapped rather than read
/// ([`SourceBytes`]), and their line table, found on two threads; `None`
/// for fewer bytes than are worth it (the caller then reads the file).
#[cfg(unix)]
pub(crate) fn map_large(
    file: &File,
    offset: u64,
    len: u64,
) -> io::Result<Option<(SourceBytes, Vec<u32>)>> {
    let (Ok(offset), Ok(len)) = (usize::try_from(offset), usize::try_from(len)) else {
        return Ok(None);
    };
    if len.saturating_sub(offset) < PARALLEL_FROM {
        return Ok(None);
    }
    let bytes = SourceBytes::mapped(file, offset, len)?;
    let starts = line_starts(&bytes);
    Ok(Some((bytes, starts)))
}

/// Pushes the offset after each `\n` of `part`, which starts at `base`.
fn push_line_starts(part: &[u8], base: usize, starts: &mut Vec<u32>) {
    starts.extend(memchr::memchr_iter(b'\n', part).map(|i| (base + i) as u32 + 1));
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
}
