//! JSON text shared by the hand-written JSON writers (`gcodec lower`'s
//! instructions, the executor's JSONL events), which write the bytes
//! serde_json would.

use std::sync::Arc;

/// Whether serde_json writes `text` as it is, between quotes: printable
/// ASCII but a quote or a backslash. Names (axes, G codes, files) almost
/// always are.
pub(crate) fn needs_no_escape(text: &str) -> bool {
    text.bytes()
        .all(|b| (b.is_ascii_graphic() && b != b'"' && b != b'\\') || b == b' ')
}

/// Writes `text` as serde_json writes a string: a plain one
/// ([`needs_no_escape`]) copied as it is, anything else through
/// serde_json's escaping.
pub fn write_json_string(out: &mut Vec<u8>, text: &str) {
    if needs_no_escape(text) {
        out.push(b'"');
        out.extend_from_slice(text.as_bytes());
        out.push(b'"');
    } else if serde_json::to_writer(&mut *out, text).is_err() {
        // Writing into a vector does not fail; keep the JSON valid anyway.
        out.extend_from_slice(b"\"\"");
    }
}

/// A file name and its JSON text: every event and instruction names its
/// file, mostly the same one, whose text is written once, with the fixed
/// text around it if asked ([`FileJsonText::between`]).
#[derive(Debug, Default)]
pub struct FileJsonText {
    file: Option<Arc<str>>,
    before: &'static [u8],
    after: &'static [u8],
    text: Vec<u8>,
}

impl FileJsonText {
    /// Writes `before`, the file and `after` as one kept text: the key
    /// before the name and the one after it copied with it.
    pub fn between(before: &'static [u8], after: &'static [u8]) -> Self {
        Self {
            before,
            after,
            ..Self::default()
        }
    }

    /// Writes `file` as [`write_json_string`] does, between the texts
    /// given to [`FileJsonText::between`], from the text kept when it is
    /// the file written last.
    pub fn write(&mut self, out: &mut Vec<u8>, file: &Arc<str>) {
        let same = self
            .file
            .as_ref()
            .is_some_and(|last| Arc::ptr_eq(last, file) || **last == **file);
        if !same {
            self.text.clear();
            self.text.extend_from_slice(self.before);
            write_json_string(&mut self.text, file);
            self.text.extend_from_slice(self.after);
            self.file = Some(Arc::clone(file));
        }
        out.extend_from_slice(&self.text);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Plain and not: the bytes serde_json writes.
    #[test]
    fn strings_are_written_as_serde_writes_them() {
        for text in [
            "",
            "X",
            "G1",
            "part one.mpf",
            "dir/\"quoted\".mpf",
            "back\\slash",
            "tab\there",
            "line\nbreak",
            "\u{e9}t\u{e9}",
            "\u{1}",
        ] {
            let mut written = Vec::new();
            write_json_string(&mut written, text);
            assert_eq!(written, serde_json::to_vec(text).unwrap(), "{text:?}");
        }
    }
}
