//! The AIL document in JSON, written as its pages come: the bytes
//! `serde_json::to_writer_pretty` writes of the whole `Document`, the
//! commonest instructions by hand ([`super::hot_json`]), the others
//! serialised with serde_json, each indented as the pretty printer
//! indents it inside the document, pages on several threads
//! ([`super::rendered::write_rendered`]).

use std::io::{self, Write};

use gcodec_ail::{AIL_VERSION, Instruction};
use serde::Serialize;
use serde_json::ser::Formatter;

use super::Page;
use gcodec_ail::FileJsonText;

use super::hot_json::{source_file_text, write_hot};
use super::rendered::write_rendered;

/// Writes `pages` as the AIL document in JSON, pretty-printed as
/// `serde_json::to_writer_pretty` prints a `Document`, and a newline.
pub fn write_json(pages: impl Iterator<Item = Page>, out: &mut impl Write) -> io::Result<()> {
    // `Document`'s fields in order, as its derived `Serialize` has them.
    write!(
        out,
        "{{\n  \"ail_version\": {AIL_VERSION},\n  \"instructions\": ["
    )?;
    let any = write_rendered(pages, out, |instructions, first, bytes| {
        let mut file = source_file_text();
        for (k, instruction) in instructions.iter().enumerate() {
            element(instruction, first && k == 0, &mut file, bytes)?;
        }
        Ok(())
    })?;
    // The pretty printer breaks the line before the `]` of a sequence
    // that has elements.
    out.write_all(if any { b"\n  ]\n}\n" } else { b"]\n}\n" })
}

/// One element of the `instructions` sequence: the line break and the
/// indentation before it, after a comma unless it is the `first`, and
/// the instruction, two levels in.
fn element(
    instruction: &Instruction,
    first: bool,
    file: &mut FileJsonText,
    bytes: &mut Vec<u8>,
) -> io::Result<()> {
    if write_hot(instruction, first, file, bytes) {
        return Ok(());
    }
    serde_element(instruction, first, bytes)
}

/// [`element`] through serde_json.
fn serde_element(instruction: &Instruction, first: bool, bytes: &mut Vec<u8>) -> io::Result<()> {
    let mut formatter = Pretty {
        current_indent: ELEMENT_LEVEL,
        has_value: false,
    };
    // What the pretty printer writes before an element of the sequence.
    let mut bytes = Bytes(bytes);
    formatter.begin_array_value(&mut bytes, first)?;
    let mut serializer = serde_json::Serializer::with_formatter(bytes, formatter);
    instruction
        .serialize(&mut serializer)
        .map_err(io::Error::from)
}

/// Bytes in memory, written to as the serialiser writes: a few at a time,
/// which a copy each (`Vec`'s `write_all`) made a good part of the cost.
struct Bytes<'a>(&'a mut Vec<u8>);

impl Write for Bytes<'_> {
    #[inline]
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.write_all(buf)?;
        Ok(buf.len())
    }

    #[inline]
    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        if buf.len() <= SHORT {
            // Short pieces byte by byte, without a call to copy them.
            for &byte in buf {
                self.0.push(byte);
            }
        } else {
            self.0.extend_from_slice(buf);
        }
        Ok(())
    }

    fn flush(&mut self) -> io::Result<()> {
        Ok(())
    }
}

/// What [`Bytes`] writes byte by byte.
const SHORT: usize = 8;

/// The level of the instructions in the document: inside the document's
/// object and its `instructions` sequence.
const ELEMENT_LEVEL: usize = 2;

/// A comma, a line break and the indentation of this many levels, at
/// most: `serde_json::ser::PrettyFormatter` writes the indentation a
/// level at a time, which was a good part of the cost.
const LEVELS: usize = 32;

/// `",\n"` and `LEVELS` indentations of two spaces.
static BREAKS: [u8; 2 + 2 * LEVELS] = {
    let mut breaks = [b' '; 2 + 2 * LEVELS];
    breaks[0] = b',';
    breaks[1] = b'\n';
    breaks
};

/// `serde_json::ser::PrettyFormatter::new()` (two spaces a level), its
/// line breaks and indentation written as one slice each.
#[derive(Default)]
struct Pretty {
    /// The level of what is written next.
    current_indent: usize,
    has_value: bool,
}

impl Pretty {
    /// A line break (after a comma unless `first`) and the indentation.
    fn break_line<W: ?Sized + Write>(&self, writer: &mut W, comma: bool) -> io::Result<()> {
        let start = usize::from(!comma);
        let levels = self.current_indent.min(LEVELS);
        writer.write_all(&BREAKS[start..2 + 2 * levels])?;
        for _ in LEVELS..self.current_indent {
            writer.write_all(b"  ")?;
        }
        Ok(())
    }

    /// `[` or `{`: one level deeper, nothing in it yet.
    fn open<W: ?Sized + Write>(&mut self, writer: &mut W, bracket: &[u8]) -> io::Result<()> {
        self.current_indent += 1;
        self.has_value = false;
        writer.write_all(bracket)
    }

    /// `]` or `}`: on a line of its own after a value, as serde_json's
    /// pretty printer puts it.
    fn close<W: ?Sized + Write>(&mut self, writer: &mut W, bracket: &[u8]) -> io::Result<()> {
        self.current_indent -= 1;
        if self.has_value {
            self.break_line(writer, false)?;
        }
        writer.write_all(bracket)
    }
}

impl Formatter for Pretty {
    #[inline]
    fn begin_array<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.open(writer, b"[")
    }

    #[inline]
    fn end_array<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.close(writer, b"]")
    }

    #[inline]
    fn begin_array_value<W: ?Sized + Write>(
        &mut self,
        writer: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.break_line(writer, !first)
    }

    #[inline]
    fn end_array_value<W: ?Sized + Write>(&mut self, _writer: &mut W) -> io::Result<()> {
        self.has_value = true;
        Ok(())
    }

    #[inline]
    fn begin_object<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.open(writer, b"{")
    }

    #[inline]
    fn end_object<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        self.close(writer, b"}")
    }

    #[inline]
    fn begin_object_key<W: ?Sized + Write>(
        &mut self,
        writer: &mut W,
        first: bool,
    ) -> io::Result<()> {
        self.break_line(writer, !first)
    }

    #[inline]
    fn begin_object_value<W: ?Sized + Write>(&mut self, writer: &mut W) -> io::Result<()> {
        writer.write_all(b": ")
    }

    #[inline]
    fn end_object_value<W: ?Sized + Write>(&mut self, _writer: &mut W) -> io::Result<()> {
        self.has_value = true;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Nested deeper than `LEVELS`, empty and not: the bytes of serde_json's
    /// own pretty printer.
    #[test]
    fn pretty_writes_what_serde_jsons_pretty_printer_writes() {
        let mut deep = serde_json::json!({"leaf": [1, 2.5, "x\ny", null, {}, []]});
        for level in 0..40 {
            deep = serde_json::json!({"level": level, "inner": [deep, {"a": true}]});
        }
        for value in [deep, serde_json::json!([]), serde_json::json!({})] {
            let expected = serde_json::to_vec_pretty(&value).unwrap();
            let mut written = Vec::new();
            let mut serializer =
                serde_json::Serializer::with_formatter(&mut written, Pretty::default());
            value.serialize(&mut serializer).unwrap();
            assert_eq!(
                String::from_utf8(written).unwrap(),
                String::from_utf8(expected).unwrap()
            );
        }
    }

    /// The instructions written by hand are the bytes serde writes: those
    /// of programs with every hot shape and its near misses, and motions
    /// with numbers, axis names and file names that need care.
    #[test]
    fn hot_instructions_are_written_as_serde_writes_them() {
        use std::borrow::Cow;
        use std::sync::Arc;

        use gcodec_ail::{AxisValue, ByteRange, Op, Source, Value};
        use gcodec_lang::MotionKind;

        let program = "G0 X0 Y0 Z5\nG1 Z-1 F200\nX10 Y=AC(5) F=R1\nG2 X20 Y0 CR=5\n\
                       G3 X0 Y0 I-10 J0 TURN=1\nG91 X1\nG90 G17 G64 F1.5 X-0.0001\n\
                       R1=3 X=R1 Y=R1*2\nCIP X1 Y1 I1=0.5 J1=0.5\nG1 X1E3 Y.5\nM30\n";
        let profile = gcodec_profile::builtin().unwrap();
        let compiled = crate::compile_text(
            "dir/part \"one\" \u{e9}.mpf",
            program,
            gcodec_sema::ProgramKind::Main,
            &profile,
            &gcodec_sema::Definitions::new(),
        );
        let mut instructions = compiled.document.instructions;
        let numbers = [
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1.0 / 3.0,
            123.4567,
            1e-7,
            1e16,
            1e300,
            5e-324,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
        ];
        let files = [
            "plain.mpf",
            "with space.mpf",
            "back\\slash.mpf",
            "tab\there.mpf",
        ];
        for (k, pair) in numbers.windows(2).enumerate() {
            let target = |axis: Cow<'static, str>, value| AxisValue {
                axis,
                value: Value::Const(value),
                mode: None,
            };
            instructions.push(Instruction {
                op: Op::Motion {
                    motion: [MotionKind::Linear, MotionKind::Rapid, MotionKind::Modal][k % 3],
                    targets: vec![
                        target(Cow::Borrowed("X"), pair[0]),
                        target(Cow::Owned(format!("C\"{k}")), pair[1]),
                    ],
                    circle: None,
                    details: None,
                },
                source: Source {
                    file: Arc::from(files[k % files.len()]),
                    line: k as u32,
                    col: u32::MAX,
                    span: ByteRange {
                        start: 0,
                        end: u32::MAX,
                    },
                },
            });
            let source = instructions[instructions.len() - 1].source.clone();
            instructions.push(Instruction {
                op: Op::Feed {
                    value: Value::Const(pair[0]),
                },
                source,
            });
        }
        let mut hot = 0;
        // One file text for all, as for a page: file names change between
        // the programs' instructions and the ones made here.
        let mut file = source_file_text();
        for instruction in &instructions {
            for first in [true, false] {
                let mut by_hand = Vec::new();
                if !write_hot(instruction, first, &mut file, &mut by_hand) {
                    assert!(by_hand.is_empty());
                    continue;
                }
                hot += 1;
                let mut by_serde = Vec::new();
                serde_element(instruction, first, &mut by_serde).unwrap();
                assert_eq!(
                    String::from_utf8(by_hand).unwrap(),
                    String::from_utf8(by_serde).unwrap(),
                    "{instruction:?}"
                );
            }
        }
        // The programs' hot instructions and the 26 made here, twice each.
        assert!(hot >= 2 * (26 + 12), "{hot} hot instructions");
        // Near misses go through serde: an expression, AC, circle data.
        let serde_only = instructions
            .iter()
            .filter(|i| !write_hot(i, true, &mut source_file_text(), &mut Vec::new()))
            .count();
        assert!(serde_only >= 5, "{serde_only} instructions through serde");
    }

    /// The document of no, one and several pages, some empty: the bytes
    /// of the pretty printer's whole document.
    #[test]
    fn pages_make_the_document_the_pretty_printer_writes() {
        let program = "G1 X1 F100\nX2\nR1=R1*2+3\nM30\n";
        let compiled = crate::compile_text(
            "pages.mpf",
            program,
            gcodec_sema::ProgramKind::Main,
            &gcodec_profile::builtin().unwrap(),
            &gcodec_sema::Definitions::new(),
        );
        let all = compiled.document.instructions;
        assert!(all.len() > 4, "{all:#?}");
        let page = |range: std::ops::Range<usize>| Page {
            instructions: all[range].to_vec(),
            spent: None,
        };
        let n = all.len();
        // Pages as (start, end) of the instructions.
        let cuts: [&[(usize, usize)]; 4] = [
            &[],
            &[(0, 0)],
            &[(0, n)],
            &[(0, 0), (0, 1), (1, 1), (1, 3), (3, n), (n, n)],
        ];
        for cut in cuts {
            let cut: Vec<std::ops::Range<usize>> = cut.iter().map(|&(a, b)| a..b).collect();
            let instructions: Vec<Instruction> =
                cut.iter().flat_map(|r| all[r.clone()].to_vec()).collect();
            let document = gcodec_ail::Document {
                ail_version: AIL_VERSION,
                instructions,
            };
            let mut expected = serde_json::to_vec_pretty(&document).unwrap();
            expected.push(b'\n');
            let mut written = Vec::new();
            write_json(cut.iter().map(|r| page(r.clone())), &mut written).unwrap();
            assert_eq!(
                String::from_utf8(written).unwrap(),
                String::from_utf8(expected).unwrap(),
                "{cut:?}"
            );
        }
    }
}
