//! The commonest instructions in the JSON of `gcodec lower`, written by
//! hand: a modal change, a constant feed, and a motion to constant end
//! points without circle data or details. They are most of a program's
//! instructions, and serde_json spent most of its time on them escaping
//! every key byte by byte and going through the flattened, internally
//! tagged enum's map (docs/performance.md, "Issue 20: the hot
//! instructions written by hand"). The bytes are those serde_json's
//! pretty printer writes, as an element of the document's `instructions`
//! (tests compare them); every other instruction goes through serde.

use gcodec_ail::{FileJsonText, Instruction, Op, Source, Value, write_json_f64, write_json_string};
use serde_json::ser::{CompactFormatter, Formatter};

/// Writes `instruction` as an element of the `instructions` sequence
/// (after a comma unless `first`) if it is one of the hot kinds; false,
/// writing nothing, otherwise.
/// `file` keeps the text of the last file name written: every instruction
/// names one, mostly the same.
pub(super) fn write_hot(
    instruction: &Instruction,
    first: bool,
    file: &mut FileJsonText,
    out: &mut Vec<u8>,
) -> bool {
    match &instruction.op {
        Op::ModalChange { group, code } => {
            begin(out, first, b"modal_change");
            out.extend_from_slice(b",\n      \"group\": ");
            write_u32(out, u32::from(*group));
            out.extend_from_slice(b",\n      \"code\": ");
            write_json_string(out, code.name());
        }
        Op::Feed {
            value: Value::Const(value),
        } => {
            begin(out, first, b"feed");
            out.extend_from_slice(b",\n      \"value\": ");
            write_json_f64(out, *value);
        }
        Op::Motion {
            motion,
            targets,
            circle: None,
            details: None,
        } if !targets.is_empty() && targets.iter().all(|t| t.plain_constant().is_some()) => {
            begin(out, first, b"motion");
            out.extend_from_slice(b",\n      \"motion\": ");
            write_json_string(out, motion.name());
            out.extend_from_slice(b",\n      \"targets\": [");
            for (k, target) in targets.iter().enumerate() {
                out.extend_from_slice(if k == 0 {
                    b"\n        {\n          \"axis\": ".as_slice()
                } else {
                    b",\n        {\n          \"axis\": ".as_slice()
                });
                write_json_string(out, &target.axis);
                out.extend_from_slice(b",\n          \"value\": ");
                if let Some(value) = target.plain_constant() {
                    write_json_f64(out, value);
                }
                out.extend_from_slice(b",\n          \"mode\": null\n        }");
            }
            out.extend_from_slice(b"\n      ],\n      \"circle\": null");
        }
        _ => return false,
    }
    write_source(out, &instruction.source, file);
    true
}

/// The element's line break and indentation, its `{` and its `kind`.
fn begin(out: &mut Vec<u8>, first: bool, kind: &[u8]) {
    if !first {
        out.push(b',');
    }
    out.extend_from_slice(b"\n    {\n      \"kind\": \"");
    out.extend_from_slice(kind);
    out.push(b'"');
}

/// The text around an instruction's file name: the key before it and
/// the one after.
pub(super) fn source_file_text() -> FileJsonText {
    FileJsonText::between(
        b",\n      \"source\": {\n        \"file\": ",
        b",\n        \"line\": ",
    )
}

/// The `source` field and the element's closing brace; `file` is
/// [`source_file_text`]'s.
fn write_source(out: &mut Vec<u8>, source: &Source, file: &mut FileJsonText) {
    file.write(out, &source.file);
    write_u32(out, source.line);
    out.extend_from_slice(b",\n        \"col\": ");
    write_u32(out, source.col);
    out.extend_from_slice(b",\n        \"span\": {\n          \"start\": ");
    write_u32(out, source.span.start);
    out.extend_from_slice(b",\n          \"end\": ");
    write_u32(out, source.span.end);
    out.extend_from_slice(b"\n        }\n      }\n    }");
}

fn write_u32(out: &mut Vec<u8>, value: u32) {
    // Writing into a vector does not fail.
    let _ = CompactFormatter.write_u32(out, value);
}
