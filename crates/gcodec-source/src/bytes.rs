//! [`SourceBytes`]: a program's bytes, in memory or mapped from its file.

use std::ops::Deref;

/// A program's bytes: a vector, or on Unix a large file mapped into
/// memory.
///
/// A file read into a fresh buffer costs the kernel's copy and a page
/// fault for every 4 KiB of the buffer, which on the benchmark machine
/// (docs/performance.md, "Issue 20: writers, numbers and mapped files")
/// took 25 ms
/// for a 27 MB program, before any other thread starts; mapped, the
/// page cache's pages are the bytes: 2.5 ms. The mapping is private and
/// read-only. A mapped file that another process shortens while gcodec
/// reads it ends gcodec with `SIGBUS`, as for any program that maps its
/// input (SPEC §1); one that is rewritten in place shows the new bytes.
pub struct SourceBytes {
    storage: Storage,
}

enum Storage {
    Owned(Vec<u8>),
    /// The file's bytes from `start` on (after a byte-order mark).
    #[cfg(unix)]
    Mapped {
        map: memmap2::Mmap,
        start: usize,
    },
}

impl SourceBytes {
    /// The bytes of `file` from `start` to its end (`len` bytes when it
    /// was opened), mapped.
    #[cfg(unix)]
    pub(crate) fn mapped(file: &std::fs::File, start: usize, len: usize) -> std::io::Result<Self> {
        // SAFETY: a mapping is unsafe because the file may change under
        // it. gcodec maps it private and read-only and never writes it;
        // what another process's change does is documented (SPEC §1):
        // rewritten bytes are read as they then are (every reader takes
        // the bytes as bytes and checks UTF-8 where it needs text), and a
        // read past a new end is `SIGBUS`.
        let map = unsafe { memmap2::MmapOptions::new().len(len).map(file)? };
        // A file not in the page cache yet is read ahead whole: its bytes
        // are read three times (the line table, pass 1, pass 2).
        let _ = map.advise(memmap2::Advice::WillNeed);
        Ok(Self {
            storage: Storage::Mapped { map, start },
        })
    }
}

impl Deref for SourceBytes {
    type Target = [u8];

    fn deref(&self) -> &[u8] {
        match &self.storage {
            Storage::Owned(bytes) => bytes,
            #[cfg(unix)]
            Storage::Mapped { map, start } => &map[*start..],
        }
    }
}

impl From<Vec<u8>> for SourceBytes {
    fn from(bytes: Vec<u8>) -> Self {
        Self {
            storage: Storage::Owned(bytes),
        }
    }
}

impl Default for SourceBytes {
    fn default() -> Self {
        Vec::new().into()
    }
}

impl PartialEq for SourceBytes {
    fn eq(&self, other: &Self) -> bool {
        **self == **other
    }
}

impl std::fmt::Debug for SourceBytes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let how = match &self.storage {
            Storage::Owned(_) => "in memory",
            #[cfg(unix)]
            Storage::Mapped { .. } => "mapped",
        };
        write!(f, "SourceBytes({} bytes, {how})", self.len())
    }
}
