//! Reading a program's file from disk, defensively: only a regular file is
//! opened for its bytes, its size is checked before a byte is read and no
//! more than the cap is ever read, a UTF-8 byte-order mark is dropped and
//! UTF-16 text is named for what it is (SPEC §1).
//!
//! A FIFO would block the reader until something writes to it and a
//! device such as `/dev/zero` never ends, so the file is opened without
//! blocking and its type is checked on the opened file (not only on the
//! path, which could be swapped meanwhile).

use std::fmt;
use std::fs::{self, File, Metadata};
use std::io::{self, Read};
use std::path::Path;

use crate::SourceBytes;
use crate::lines::{LineTable, MAX_SOURCE_LEN, line_table};
use crate::{Code, codes};

/// The size above which a program's file is not read unless the profile
/// allows more (`[program] max_file_size`): 1 GiB, four times the largest
/// programs seen (CAM output of about 256 MB), while a file read whole
/// stays well inside a workstation's memory.
pub const DEFAULT_MAX_FILE_SIZE: u64 = 1 << 30;

/// The UTF-8 byte-order mark, which some Windows editors put at the start
/// of a file. It is not part of the program: [`SourceFile`] drops it, and
/// so does every parse of bytes, so that spans count from the byte after
/// it wherever the bytes came from.
///
/// [`SourceFile`]: crate::SourceFile
pub const UTF8_BOM: &[u8] = b"\xEF\xBB\xBF";

/// How many bytes at the start of a file are looked at for UTF-16 text
/// without a byte-order mark.
const UTF16_SAMPLE: usize = 512;

/// Why a file could not be read as a program.
#[derive(Debug)]
pub enum ReadError {
    /// Opening or reading it failed: it does not exist, is a directory or
    /// may not be read.
    Io(io::Error),
    /// It is no regular file: a FIFO, a device, a socket (`what` says
    /// which, "a FIFO").
    NotAFile { what: &'static str },
    /// It holds more than `max_len` bytes (`len`, as far as it is known).
    TooLarge { len: u64, max_len: u64 },
    /// It is UTF-16 text, in the byte order named (`little-endian`), with a
    /// byte-order mark or without.
    Utf16 { byte_order: &'static str, bom: bool },
}

impl ReadError {
    /// The registry code of this error, for a file named on the command
    /// line (a called program's read error is the run's own code).
    pub fn code(&self) -> &'static Code {
        match self {
            Self::Io(_) => codes::io::READ,
            Self::NotAFile { .. } => codes::io::NOT_A_FILE,
            Self::TooLarge { .. } => codes::io::TOO_LARGE,
            Self::Utf16 { .. } => codes::io::UTF16,
        }
    }

    /// How to mend it.
    pub fn help(&self) -> &'static str {
        match self {
            Self::Io(_) => "check the path and that the file is readable",
            Self::NotAFile { .. } => {
                "give a regular file: FIFOs, devices and sockets are not read as programs"
            }
            Self::TooLarge { .. } => {
                "split the program, or raise `[program] max_file_size` in the machine profile"
            }
            Self::Utf16 { .. } => {
                "save the file as UTF-8 or in the control's 8-bit code page (ANSI, Windows-1252)"
            }
        }
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io(e) => e.fmt(f),
            Self::NotAFile { what } => write!(f, "it is {what}, not a regular file"),
            Self::TooLarge { len, max_len } => {
                write!(f, "it holds {len} bytes, more than the {max_len} allowed")
            }
            Self::Utf16 { byte_order, bom } => {
                let mark = if *bom {
                    "with a byte-order mark"
                } else {
                    "without a byte-order mark"
                };
                write!(
                    f,
                    "it is UTF-16 text ({byte_order}, {mark}); programs are 8-bit text"
                )
            }
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Io(e) => Some(e),
            _ => None,
        }
    }
}

impl From<io::Error> for ReadError {
    fn from(e: io::Error) -> Self {
        Self::Io(e)
    }
}

/// The bytes of the regular file at `path` without a leading UTF-8
/// byte-order mark (mapped if the file is large), and their line table; at most `max_len` bytes in the
/// file (and never more than [`MAX_SOURCE_LEN`], the spans' limit).
pub(crate) fn read_program(
    path: &Path,
    max_len: u64,
) -> Result<(SourceBytes, LineTable), ReadError> {
    let max_len = max_len.min(MAX_SOURCE_LEN as u64);
    // The path first, so that a device is not even opened…
    regular(&fs::metadata(path)?)?;
    let mut file = open_without_blocking(path)?;
    // …and the opened file, which is what is read.
    let metadata = file.metadata()?;
    regular(&metadata)?;
    let len = metadata.len();
    if len > max_len {
        return Err(ReadError::TooLarge { len, max_len });
    }
    let mut head = [0; 3];
    let head_len = read_head(&mut file, &mut head)?;
    let head = &head[..head_len];
    if let Some(byte_order) = utf16_mark(head) {
        return Err(ReadError::Utf16 {
            byte_order,
            bom: true,
        });
    }
    let skip = if head == UTF8_BOM { UTF8_BOM.len() } else { 0 };
    let (bytes, starts) = read_rest(&mut file, head, skip, len, max_len)?;
    if let Some(byte_order) = utf16_without_mark(&bytes) {
        return Err(ReadError::Utf16 {
            byte_order,
            bom: false,
        });
    }
    Ok((bytes, starts))
}

/// `Ok` for a regular file; a directory is the IO error reading it gives.
fn regular(metadata: &Metadata) -> Result<(), ReadError> {
    let file_type = metadata.file_type();
    if file_type.is_file() {
        Ok(())
    } else if file_type.is_dir() {
        Err(ReadError::Io(io::ErrorKind::IsADirectory.into()))
    } else {
        Err(ReadError::NotAFile {
            what: special_file(&file_type),
        })
    }
}

#[cfg(unix)]
fn special_file(file_type: &fs::FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if file_type.is_fifo() {
        "a FIFO (named pipe)"
    } else if file_type.is_char_device() {
        "a character device"
    } else if file_type.is_block_device() {
        "a block device"
    } else if file_type.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special_file(_: &fs::FileType) -> &'static str {
    "a special file"
}

/// Opens `path` for reading; a FIFO swapped in after the path was checked
/// does not block the open (its type is checked next).
#[cfg(unix)]
fn open_without_blocking(path: &Path) -> io::Result<File> {
    use std::os::unix::fs::OpenOptionsExt;
    fs::OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NONBLOCK)
        .open(path)
}

#[cfg(not(unix))]
fn open_without_blocking(path: &Path) -> io::Result<File> {
    File::open(path)
}

/// Reads up to `head.len()` bytes from the start of `file`; how many.
fn read_head(file: &mut File, head: &mut [u8]) -> io::Result<usize> {
    let mut filled = 0;
    while filled < head.len() {
        match file.read(&mut head[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(filled)
}

/// The file's bytes from `skip` on, `head` (its first bytes) already read;
/// `len` is its size when it was opened. More than `max_len` bytes in all
/// (a file that grew) is [`ReadError::TooLarge`].
fn read_rest(
    file: &mut File,
    head: &[u8],
    skip: usize,
    len: u64,
    max_len: u64,
) -> Result<(SourceBytes, LineTable), ReadError> {
    // `len` is within `max_len`: `read_program` checked it at the open.
    #[cfg(unix)]
    if let Some(mapped) = crate::lines::map_large(file, skip as u64, len)? {
        return Ok(mapped);
    }
    let mut bytes = Vec::with_capacity(usize::try_from(len).unwrap_or(0));
    bytes.extend_from_slice(&head[skip..]);
    // One byte beyond the cap tells a file that grew past it.
    let rest = (max_len + 1).saturating_sub(head.len() as u64);
    file.take(rest).read_to_end(&mut bytes)?;
    let total = (bytes.len() + skip) as u64;
    if total > max_len {
        return Err(ReadError::TooLarge {
            len: total,
            max_len,
        });
    }
    let table = line_table(&bytes);
    Ok((bytes.into(), table))
}

/// The byte order a UTF-16 byte-order mark at the start of `head` gives.
fn utf16_mark(head: &[u8]) -> Option<&'static str> {
    match head {
        [0xFF, 0xFE, ..] => Some("little-endian"),
        [0xFE, 0xFF, ..] => Some("big-endian"),
        _ => None,
    }
}

/// The byte order of UTF-16 text without a mark: a program holds no NUL
/// bytes, while UTF-16 text of the ASCII a program is written in has one
/// in every other byte. At least half the bytes of one parity in the
/// sample are NUL and almost none of the other.
fn utf16_without_mark(bytes: &[u8]) -> Option<&'static str> {
    let sample = &bytes[..bytes.len().min(UTF16_SAMPLE)];
    let pairs = sample.len() / 2;
    if pairs == 0 {
        return None;
    }
    let nul_at = |parity: usize| {
        sample
            .iter()
            .skip(parity)
            .step_by(2)
            .filter(|&&b| b == 0)
            .count()
    };
    let (even, odd) = (nul_at(0), nul_at(1));
    let mostly = |count: usize| count * 2 >= pairs;
    let hardly = |count: usize| count * 8 < pairs;
    if mostly(odd) && hardly(even) {
        Some("little-endian")
    } else if mostly(even) && hardly(odd) {
        Some("big-endian")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lines::tests::{large_sources, one_scan};

    /// A directory of its own under the system's temporary directory.
    struct TempDir(std::path::PathBuf);

    impl TempDir {
        fn new(name: &str) -> Self {
            let dir =
                std::env::temp_dir().join(format!("gcodec-read-{name}-{}", std::process::id()));
            let _ = fs::remove_dir_all(&dir);
            fs::create_dir_all(&dir).expect("temporary directory");
            Self(dir)
        }

        fn file(&self, name: &str, bytes: &[u8]) -> std::path::PathBuf {
            let path = self.0.join(name);
            fs::write(&path, bytes).expect("write");
            path
        }
    }

    impl Drop for TempDir {
        fn drop(&mut self) {
            let _ = fs::remove_dir_all(&self.0);
        }
    }

    /// A large file (mapped on Unix, its lines found in halves) has its
    /// bytes and the table of one scan, with or without a byte-order mark,
    /// a line end just before, at or after the middle where it is split; a
    /// file over the limit is refused.
    #[test]
    fn a_large_file_is_read_whole_with_its_lines() {
        let temp = TempDir::new("large");
        for (i, text) in large_sources().into_iter().enumerate() {
            for bom in [&b""[..], UTF8_BOM] {
                let stored = [bom, &text].concat();
                let path = temp.file(&format!("large{i}.mpf"), &stored);
                let (read, table) = read_program(&path, u64::MAX).unwrap();
                assert!(*read == *text, "the bytes of {}", path.display());
                #[cfg(unix)]
                assert!(format!("{read:?}").ends_with("mapped)"), "{read:?}");
                assert_eq!(table.starts, one_scan(&text));
                assert!(table.ascii);
                let limit = stored.len() as u64 - 1;
                let refused = read_program(&path, limit).unwrap_err();
                assert!(
                    matches!(refused, ReadError::TooLarge { len, max_len }
                        if len == stored.len() as u64 && max_len == limit),
                    "{refused:?}"
                );
            }
        }
    }

    #[test]
    fn a_byte_order_mark_is_dropped_and_utf16_is_named() {
        let temp = TempDir::new("encoding");
        let path = temp.file("bom.mpf", b"\xEF\xBB\xBFG0 X1\nM30\n");
        let (bytes, table) = read_program(&path, 100).unwrap();
        assert_eq!(
            (&bytes[..], &table.starts[..]),
            (&b"G0 X1\nM30\n"[..], &[0, 6, 10][..])
        );
        // The cap counts the file as stored, the mark too.
        assert!(matches!(
            read_program(&path, 12),
            Err(ReadError::TooLarge { len: 13, .. })
        ));
        for (stored, expected) in [
            (&b"\xEF\xBB\xBF"[..], &b""[..]),
            (b"\xEF\xBB", b"\xEF\xBB"),
            (b"", b""),
            (b"G", b"G"),
        ] {
            let path = temp.file("short.mpf", stored);
            assert_eq!(
                *read_program(&path, 100).unwrap().0,
                *expected,
                "{stored:?}"
            );
        }
        let program = "G0 X1\r\nM30\r\n";
        for (stored, order, bom) in [
            (
                [&b"\xFF\xFE"[..], &utf16le(program)].concat(),
                "little-endian",
                true,
            ),
            (
                [&b"\xFE\xFF"[..], &utf16be(program)].concat(),
                "big-endian",
                true,
            ),
            (utf16le(program), "little-endian", false),
            (utf16be(program), "big-endian", false),
        ] {
            let path = temp.file("wide.mpf", &stored);
            let error = read_program(&path, 100).unwrap_err();
            assert!(
                matches!(error, ReadError::Utf16 { byte_order, bom: b } if byte_order == order && b == bom),
                "{error:?}"
            );
            assert_eq!(error.code(), codes::io::UTF16);
        }
    }

    #[test]
    fn a_file_that_grows_past_the_cap_is_not_read_past_it() {
        let temp = TempDir::new("grows");
        let path = temp.file("grows.mpf", b"G0 X1\n");
        let mut file = File::open(&path).unwrap();
        let mut head = [0; 3];
        let head_len = read_head(&mut file, &mut head).unwrap();
        // The file grows after its size was taken (6 bytes).
        fs::write(&path, b"G0 X1\nG0 X2\nG0 X3\n").unwrap();
        let error = read_rest(&mut file, &head[..head_len], 0, 6, 10).unwrap_err();
        assert!(
            matches!(
                error,
                ReadError::TooLarge {
                    len: 11,
                    max_len: 10
                }
            ),
            "{error:?}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn only_regular_files_are_read() {
        let temp = TempDir::new("special");
        // A FIFO with no writer: opening it for reading would block.
        let fifo = temp.0.join("FIFO.SPF");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        let error = read_program(&fifo, 100).unwrap_err();
        assert!(
            matches!(
                error,
                ReadError::NotAFile {
                    what: "a FIFO (named pipe)"
                }
            ),
            "{error:?}"
        );
        assert_eq!(error.code(), codes::io::NOT_A_FILE);
        // Endless: refused before a byte is read.
        let error = read_program(Path::new("/dev/zero"), u64::MAX).unwrap_err();
        assert!(
            matches!(
                error,
                ReadError::NotAFile {
                    what: "a character device"
                }
            ),
            "{error:?}"
        );
        // Through a link too.
        let link = temp.0.join("ZERO.SPF");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        assert!(matches!(
            read_program(&link, 100),
            Err(ReadError::NotAFile { .. })
        ));
        // The opened file is checked, not only the path.
        let opened = open_without_blocking(&fifo).unwrap();
        assert!(matches!(
            regular(&opened.metadata().unwrap()),
            Err(ReadError::NotAFile { .. })
        ));
        // A directory is the IO error it was.
        let error = read_program(&temp.0, 100).unwrap_err();
        assert!(
            matches!(&error, ReadError::Io(e) if e.kind() == io::ErrorKind::IsADirectory),
            "{error:?}"
        );
        assert_eq!(error.code(), codes::io::READ);
    }

    fn utf16le(text: &str) -> Vec<u8> {
        text.encode_utf16().flat_map(u16::to_le_bytes).collect()
    }

    fn utf16be(text: &str) -> Vec<u8> {
        text.encode_utf16().flat_map(u16::to_be_bytes).collect()
    }

    #[test]
    fn utf16_text_is_told_by_its_nul_bytes() {
        let program = "N10 G1 X10 ; Grüße\r\nM30\r\n";
        assert_eq!(utf16_without_mark(&utf16le(program)), Some("little-endian"));
        assert_eq!(utf16_without_mark(&utf16be(program)), Some("big-endian"));
        assert_eq!(utf16_without_mark(program.as_bytes()), None);
        assert_eq!(utf16_without_mark(b""), None);
        assert_eq!(utf16_without_mark(b"G"), None);
        // A stray NUL in 8-bit text is an invalid character, not UTF-16.
        assert_eq!(utf16_without_mark(b"G1 X1\0\nM30\n"), None);
        assert_eq!(utf16_mark(b"\xFF\xFEN"), Some("little-endian"));
        assert_eq!(utf16_mark(b"\xFE\xFF"), Some("big-endian"));
        assert_eq!(utf16_mark(UTF8_BOM), None);
    }
}
