//! JSON text shared by the hand-written JSON writers (`gcodec lower`'s
//! instructions, the executor's JSONL events), which write the bytes
//! serde_json would.

/// Writes `text` as serde_json writes a string. Names (axes, G codes,
/// files) need no escaping almost always and are copied as they are;
/// anything else goes through serde_json's escaping.
pub fn write_json_string(out: &mut Vec<u8>, text: &str) {
    let plain = text
        .bytes()
        .all(|b| (b.is_ascii_graphic() && b != b'"' && b != b'\\') || b == b' ');
    if plain {
        out.push(b'"');
        out.extend_from_slice(text.as_bytes());
        out.push(b'"');
    } else if serde_json::to_writer(&mut *out, text).is_err() {
        // Writing into a vector does not fail; keep the JSON valid anyway.
        out.extend_from_slice(b"\"\"");
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
