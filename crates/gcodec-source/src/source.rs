use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::encoding::{Encoding, TextEncoding};
use crate::lines::{LineTable, MAX_SOURCE_LEN, line_table};
use crate::read::{DEFAULT_MAX_FILE_SIZE, ReadError, UTF8_BOM, read_program};
use crate::{SourceBytes, Span};

/// One part program as read from disk: its name and its bytes (after a
/// UTF-8 byte-order mark, which is not part of the program: spans count
/// from the byte after it).
#[derive(Clone, Debug)]
pub struct SourceFile {
    name: String,
    path: Option<PathBuf>,
    /// Shared with the parsed program that quotes from it
    /// ([`SourceFile::shared_bytes`]), so the file is held once.
    bytes: Arc<SourceBytes>,
    line_starts: Vec<u32>,
    /// Whether the bytes are valid UTF-8, found once when the file is
    /// made: every choice of [`TextEncoding`] starts from it.
    valid_utf8: bool,
    /// What the bytes of comments and strings are read in: UTF-8 if the
    /// file is valid UTF-8, else Windows-1252, until
    /// [`SourceFile::decoded`] says otherwise.
    encoding: Encoding,
}

impl SourceFile {
    /// A source held in memory, named `name` in diagnostics and dumps; a
    /// leading UTF-8 byte-order mark is dropped, as when a file is read.
    ///
    /// # Panics
    /// Never for files up to [`MAX_SOURCE_LEN`] bytes; callers reading from
    /// disk use [`SourceFile::read`], which reports larger files as an error.
    pub fn new(name: impl Into<String>, bytes: impl Into<Vec<u8>>) -> Self {
        let mut bytes = bytes.into();
        if bytes.starts_with(UTF8_BOM) {
            bytes.drain(..UTF8_BOM.len());
        }
        if bytes.len() > MAX_SOURCE_LEN {
            // Spans are u32: keep the addressable prefix rather than wrap.
            bytes.truncate(MAX_SOURCE_LEN);
        }
        let table = line_table(&bytes);
        Self::of_bytes(name.into(), None, bytes.into(), table)
    }

    /// A file of `bytes` (a byte-order mark dropped), read as UTF-8 where
    /// they are valid UTF-8, else in Windows-1252.
    fn of_bytes(name: String, path: Option<PathBuf>, bytes: SourceBytes, table: LineTable) -> Self {
        let valid_utf8 = table.ascii || std::str::from_utf8(&bytes).is_ok();
        Self {
            name,
            path,
            valid_utf8,
            encoding: TextEncoding::default().given(valid_utf8),
            bytes: Arc::new(bytes),
            line_starts: table.starts,
        }
    }

    /// Reads a program's file from disk, if it is a regular file of at
    /// most [`DEFAULT_MAX_FILE_SIZE`] bytes (see [`SourceFile::read_capped`]).
    pub fn read(path: &Path) -> Result<Self, ReadError> {
        Self::read_capped(path, DEFAULT_MAX_FILE_SIZE)
    }

    /// Reads a program's file from disk: a regular file only (a FIFO or a
    /// device is [`ReadError::NotAFile`], before anything is read from
    /// it) of at most `max_len` bytes (checked before reading, and no
    /// more is read), not UTF-16 text; a leading UTF-8 byte-order mark is
    /// dropped.
    pub fn read_capped(path: &Path, max_len: u64) -> Result<Self, ReadError> {
        let (bytes, table) = read_program(path, max_len)?;
        let name = path.display().to_string();
        Ok(Self::of_bytes(name, Some(path.to_path_buf()), bytes, table))
    }

    /// The same file named by another path that leads to it (a symbolic
    /// link to the file read), in diagnostics and as its path.
    pub fn named(mut self, path: &Path) -> Self {
        self.name = path.display().to_string();
        self.path = Some(path.to_path_buf());
        self
    }

    /// The same file, its text read as `encoding` says: a legacy code
    /// page other than Windows-1252, or one encoding for every file.
    pub fn decoded(mut self, encoding: TextEncoding) -> Self {
        self.encoding = encoding.given(self.valid_utf8);
        self
    }

    /// The encoding the file's comments and strings are read in.
    pub fn encoding(&self) -> Encoding {
        self.encoding
    }

    /// The name used in diagnostics and dumps (the path as given).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The path the file was read from, if it came from disk.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The bytes as stored.
    pub fn bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// The bytes as stored, shared rather than copied.
    pub fn shared_bytes(&self) -> Arc<SourceBytes> {
        Arc::clone(&self.bytes)
    }

    /// Byte offsets at which each line starts (the first is 0).
    pub fn line_starts(&self) -> &[u32] {
        &self.line_starts
    }

    /// 1-based line and byte column of a byte offset.
    pub fn line_col(&self, offset: u32) -> (u32, u32) {
        crate::span::line_col(&self.line_starts, offset)
    }

    /// The span from 1-based `line` and byte `col` to the end of that
    /// line (its line end left out): where a position reported without a
    /// span (a run-time event's) is labelled. `None` for a position the
    /// file does not have.
    pub fn line_span(&self, line: u32, col: u32) -> Option<Span> {
        let index = usize::try_from(line.checked_sub(1)?).ok()?;
        let start = *self.line_starts.get(index)?;
        let end = self
            .line_starts
            .get(index + 1)
            .map_or(self.bytes.len() as u32, |next| next - 1);
        let mut end = end.max(start);
        if end > start && self.bytes.get(end as usize - 1) == Some(&b'\r') {
            end -= 1;
        }
        let at = start.checked_add(col.checked_sub(1)?)?;
        (at <= end).then(|| Span::new(at, end))
    }

    /// The text of a span, in the file's encoding.
    pub fn text(&self, span: Span) -> String {
        let end = (span.end as usize).min(self.bytes.len());
        let start = (span.start as usize).min(end);
        self.encoding.decode(&self.bytes[start..end]).into_owned()
    }
}

/// The characters of the bytes 0x80…0x9F in Windows-1252 (the other
/// bytes are the Latin-1 character of the same code).
const CP1252_HIGH: [char; 32] = [
    '€', '\u{81}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{8d}', 'Ž', '\u{8f}',
    '\u{90}', '‘', '’', '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{9d}', 'ž', 'Ÿ',
];

/// The Windows-1252 character of one byte: the control's 8-bit code page,
/// in which a `CHAR` is one byte and a `STRING` one byte per character.
pub fn cp1252(b: u8) -> char {
    match b {
        0x80..=0x9f => CP1252_HIGH[usize::from(b - 0x80)],
        _ => char::from(b),
    }
}

/// The byte of `c` in Windows-1252 ([`cp1252`] backwards); `None` for a
/// character the code page does not have (`Ж`, `😀`, the C1 controls that
/// 0x80…0x9F do not stand for).
pub fn cp1252_byte(c: char) -> Option<u8> {
    if let Some(at) = CP1252_HIGH.iter().position(|&h| h == c) {
        return u8::try_from(0x80 + at).ok();
    }
    u8::try_from(u32::from(c))
        .ok()
        .filter(|b| !(0x80..=0x9f).contains(b))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_span_runs_from_the_column_to_the_line_end() {
        let file = SourceFile::new("t.mpf", "G0 X1\r\nN20 X2\nM30");
        let text = |span: Option<Span>| span.map(|s| file.text(s));
        assert_eq!(text(file.line_span(1, 1)), Some("G0 X1".into()));
        assert_eq!(text(file.line_span(2, 5)), Some("X2".into()));
        assert_eq!(text(file.line_span(3, 1)), Some("M30".into()));
        assert_eq!(text(file.line_span(3, 4)), Some(String::new()));
        assert_eq!(file.line_span(3, 5), None);
        assert_eq!(file.line_span(4, 1), None);
        assert_eq!(file.line_span(0, 1), None);
        assert_eq!(file.line_span(1, 0), None);
    }

    #[test]
    fn line_col_is_one_based() {
        let f = SourceFile::new("t", "G0\nX1\n\nY2");
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(1), (1, 2));
        assert_eq!(f.line_col(3), (2, 1));
        assert_eq!(f.line_col(7), (4, 1));
        assert_eq!(f.line_col(9), (4, 3));
    }

    #[test]
    fn a_byte_order_mark_is_no_part_of_the_text() {
        let file = SourceFile::new("t.mpf", "\u{feff}G0 X1\nM30");
        assert_eq!(file.bytes(), b"G0 X1\nM30");
        assert_eq!(file.line_starts(), [0, 6]);
        assert_eq!(file.line_col(0), (1, 1));
        // Only at the start.
        let file = SourceFile::new("t.mpf", "G0\n\u{feff}M30");
        assert_eq!(file.bytes().len(), 9);
    }

    #[test]
    fn a_file_is_read_in_utf8_where_valid_else_in_its_code_page() {
        let span = Span::new(0, 7);
        let file = SourceFile::new("t.mpf", "Grüße");
        assert_eq!(file.encoding(), Encoding::UTF_8);
        assert_eq!(file.text(span), "Grüße");
        let file = SourceFile::new("t.mpf", b"Gr\xfc\xdfe \x80".to_vec());
        assert_eq!(file.encoding(), Encoding::WINDOWS_1252);
        assert_eq!(file.text(Span::new(0, 7)), "Grüße €");
        let cyrillic = Encoding::for_label("windows-1251").expect("a code page");
        let file = file.decoded(TextEncoding::Detect {
            code_page: cyrillic,
        });
        assert_eq!(file.text(Span::new(0, 2)), "Gr");
        assert_eq!(file.encoding(), cyrillic);
        let file = SourceFile::new("t.mpf", "Grüße").decoded(TextEncoding::Detect {
            code_page: cyrillic,
        });
        assert_eq!(file.encoding(), Encoding::UTF_8, "valid UTF-8 stays UTF-8");
    }

    #[test]
    fn every_cp1252_byte_comes_back_from_its_character() {
        for b in 0..=u8::MAX {
            assert_eq!(cp1252_byte(cp1252(b)), Some(b), "{b:#x}");
        }
        assert_eq!(cp1252_byte('\u{80}'), None);
        assert_eq!(cp1252_byte('Ж'), None);
    }
}
