//! The character encoding a program's text is read in.
//!
//! Spans are byte offsets into the file as stored, whatever its
//! encoding; the encoding only turns the bytes of comments, strings and
//! quoted text into characters. A file that is valid UTF-8 is read as
//! UTF-8; any other in a legacy code page: the profile's
//! `[program] code_page` (Windows-1252 by default, the control's own),
//! unless `--encoding` names one for every file (SPEC §1).

use std::borrow::Cow;

/// An encoding of program text, by its WHATWG label (`windows-1252`,
/// `windows-1251`, `utf-8`, `iso-8859-2`, …; `encoding_rs` does the work).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Encoding(&'static encoding_rs::Encoding);

impl Encoding {
    pub const UTF_8: Self = Self(encoding_rs::UTF_8);
    /// The control's code page, and the default for files that are not
    /// UTF-8.
    pub const WINDOWS_1252: Self = Self(encoding_rs::WINDOWS_1252);

    /// The encoding a label names (case-insensitive, as WHATWG defines
    /// the labels: `cp1251` and `windows-1251` are one encoding). `None`
    /// for an unknown label, and for the encodings that are not single
    /// bytes or ASCII-compatible multi-byte ones (UTF-16, `replacement`),
    /// in which program text cannot be stored: its keywords are ASCII.
    pub fn for_label(label: &str) -> Option<Self> {
        let encoding = encoding_rs::Encoding::for_label_no_replacement(label.trim().as_bytes())?;
        encoding.is_ascii_compatible().then_some(Self(encoding))
    }

    /// The encoding's canonical name (`windows-1251`).
    pub fn name(self) -> &'static str {
        self.0.name()
    }

    /// UTF-8 when `bytes` are valid UTF-8, else `fallback`.
    pub fn detect(bytes: &[u8], fallback: Self) -> Self {
        TextEncoding::Detect {
            code_page: fallback,
        }
        .of(bytes)
    }

    /// The characters of `bytes`; a byte sequence the encoding has no
    /// character for becomes U+FFFD (only UTF-8 and a few multi-byte code
    /// pages have such sequences: every byte is a character of a
    /// single-byte code page).
    pub fn decode(self, bytes: &[u8]) -> Cow<'_, str> {
        self.0.decode_without_bom_handling(bytes).0
    }

    /// The character of one byte of a single-byte code page (U+FFFD for a
    /// byte that is only part of a character, in UTF-8 or a multi-byte
    /// code page): text shown byte by byte keeps a point per byte.
    pub fn decode_byte(self, byte: u8) -> char {
        self.decode(&[byte]).chars().next().unwrap_or('\u{fffd}')
    }
}

impl Default for Encoding {
    fn default() -> Self {
        Self::WINDOWS_1252
    }
}

/// How the files of a run or a lowering are decoded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextEncoding {
    /// UTF-8 where a file is valid UTF-8, else this code page (the
    /// profile's `[program] code_page`).
    Detect { code_page: Encoding },
    /// Every file in this encoding (`--encoding`).
    Fixed(Encoding),
}

impl TextEncoding {
    /// The encoding of a file of `bytes`.
    pub fn of(self, bytes: &[u8]) -> Encoding {
        self.given(std::str::from_utf8(bytes).is_ok())
    }

    /// The encoding of a file whose bytes are valid UTF-8 or not.
    pub fn given(self, valid_utf8: bool) -> Encoding {
        match self {
            Self::Detect { .. } if valid_utf8 => Encoding::UTF_8,
            Self::Detect { code_page } => code_page,
            Self::Fixed(encoding) => encoding,
        }
    }
}

impl Default for TextEncoding {
    fn default() -> Self {
        Self::Detect {
            code_page: Encoding::WINDOWS_1252,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Encoding;

    #[test]
    fn a_legacy_code_page_decodes_its_letters() {
        let cyrillic = Encoding::for_label("windows-1251").expect("a code page");
        // "Привет" in Windows-1251.
        let bytes = [0xcf, 0xf0, 0xe8, 0xe2, 0xe5, 0xf2];
        assert_eq!(cyrillic.decode(&bytes), "Привет");
        assert_eq!(Encoding::WINDOWS_1252.decode(&bytes), "Ïðèâåò");
        assert_eq!(Encoding::for_label("CP1251"), Some(cyrillic));
    }

    #[test]
    fn valid_utf8_is_read_as_utf8_and_anything_else_in_the_fallback() {
        assert_eq!(
            Encoding::detect("Ä".as_bytes(), Encoding::WINDOWS_1252),
            Encoding::UTF_8
        );
        assert_eq!(
            Encoding::detect(&[0xc4], Encoding::WINDOWS_1252),
            Encoding::WINDOWS_1252
        );
    }

    #[test]
    fn labels_of_encodings_program_text_cannot_use_are_refused() {
        assert_eq!(Encoding::for_label("utf-16le"), None);
        assert_eq!(Encoding::for_label("no-such-encoding"), None);
        assert_eq!(Encoding::for_label("utf8"), Some(Encoding::UTF_8));
    }
}
