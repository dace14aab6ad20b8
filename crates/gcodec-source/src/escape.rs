//! Control characters made visible in text meant for a terminal.
//!
//! A comment, a string or a file name can hold ESC, BEL or CR; written
//! raw to a terminal they retitle it, clear it or overwrite the line. Every
//! human-readable output shows them as `\x` and two hex digits instead
//! (`\x1b`, `\x07`, `\x0d`); JSON escapes them by its own rules and stays
//! exact.

use std::borrow::Cow;
use std::fmt::Write as _;
use std::io;

/// True for the characters shown escaped: C0 controls but tab and line
/// feed, DEL and the C1 controls (U+0080–U+009F, which some terminals
/// obey as ESC sequences).
pub fn is_escaped(c: char) -> bool {
    c.is_control() && c != '\t' && c != '\n'
}

/// `text` with every [`is_escaped`] character written as `\xNN`.
pub fn escape_controls(text: &str) -> Cow<'_, str> {
    if !text.chars().any(is_escaped) {
        return Cow::Borrowed(text);
    }
    let mut escaped = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        push_escaped(&mut escaped, c);
    }
    Cow::Owned(escaped)
}

/// Pushes `c`, escaped if it [`is_escaped`].
pub(crate) fn push_escaped(out: &mut String, c: char) {
    if is_escaped(c) {
        let _ = write!(out, "\\x{:02x}", c as u32);
    } else {
        out.push(c);
    }
}

/// The lead byte of the UTF-8 form of every C1 control (`C2 80`…`C2 9F`).
const C1_LEAD: u8 = 0xc2;

/// Writes UTF-8 text to `W` with the [`is_escaped`] characters escaped:
/// the terminal side of a text format (a syntax tree, a listing, a run's
/// trace), whatever its writer wrote.
#[derive(Debug)]
pub struct EscapeControls<W: io::Write> {
    inner: W,
    /// A C1 lead byte that ended the last write: whether it starts a C1
    /// control depends on the next byte.
    pending_lead: bool,
}

impl<W: io::Write> EscapeControls<W> {
    pub fn new(inner: W) -> Self {
        Self {
            inner,
            pending_lead: false,
        }
    }

    /// Writes a pending lead byte that no C1 control followed.
    fn release_lead(&mut self) -> io::Result<()> {
        if std::mem::take(&mut self.pending_lead) {
            self.inner.write_all(&[C1_LEAD])?;
        }
        Ok(())
    }
}

impl<W: io::Write> io::Write for EscapeControls<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut plain = 0;
        let mut i = 0;
        if self.pending_lead
            && let Some(&next) = buf.first()
        {
            self.pending_lead = false;
            if (0x80..=0x9f).contains(&next) {
                write!(self.inner, "\\x{next:02x}")?;
                plain = 1;
                i = 1;
            } else {
                self.inner.write_all(&[C1_LEAD])?;
            }
        }
        while i < buf.len() {
            let b = buf[i];
            let c1 = b == C1_LEAD && buf.get(i + 1).is_some_and(|n| (0x80..=0x9f).contains(n));
            if b == C1_LEAD && i + 1 == buf.len() {
                self.inner.write_all(&buf[plain..i])?;
                self.pending_lead = true;
                return Ok(buf.len());
            }
            let c0 = (b < 0x20 && b != b'\t' && b != b'\n') || b == 0x7f;
            if c0 || c1 {
                self.inner.write_all(&buf[plain..i])?;
                let code = if c1 { buf[i + 1] } else { b };
                write!(self.inner, "\\x{code:02x}")?;
                i += if c1 { 2 } else { 1 };
                plain = i;
            } else {
                i += 1;
            }
        }
        self.inner.write_all(&buf[plain..])?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        self.release_lead()?;
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use std::io::Write;

    use super::*;

    const RAW: &str = "ti\u{1b}]0;T\u{7}tle\ra\tb\nc\u{7f}\u{9b}2J é€";
    const SHOWN: &str = "ti\\x1b]0;T\\x07tle\\x0da\tb\nc\\x7f\\x9b2J é€";

    #[test]
    fn controls_but_tab_and_line_feed_are_escaped() {
        assert_eq!(escape_controls(RAW), SHOWN);
        assert!(matches!(escape_controls("G1 X1\tY2\n"), Cow::Borrowed(_)));
    }

    /// The writer escapes what `escape_controls` escapes, however the
    /// text is cut into writes (a C1 control's two bytes split too).
    #[test]
    fn the_writer_escapes_across_any_cut() {
        let bytes = RAW.as_bytes();
        for cut in 0..=bytes.len() {
            let mut out = EscapeControls::new(Vec::new());
            out.write_all(&bytes[..cut]).unwrap();
            out.write_all(&bytes[cut..]).unwrap();
            out.flush().unwrap();
            assert_eq!(String::from_utf8(out.inner).unwrap(), SHOWN, "cut at {cut}");
        }
        // A lead byte at the end is written as it came when flushed.
        let mut out = EscapeControls::new(Vec::new());
        out.write_all(b"x\xc2").unwrap();
        out.flush().unwrap();
        assert_eq!(out.inner, b"x\xc2");
    }
}
