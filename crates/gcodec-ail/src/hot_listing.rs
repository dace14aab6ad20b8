//! The lines of the commonest instructions in the listing of `gcodec
//! lower`, written directly: a modal change, a constant feed, and a
//! motion to constant end points without circle data or details. The
//! general path turns each instruction into a `serde_json::Value` and
//! formats its fields as strings, most of the time of a large listing
//! (docs/performance.md, "Issue 20: the hot instructions written by
//! hand"). The text is the general path's; tests compare them.

use std::fmt::{self, Write};
use std::io::Cursor;

use serde_json::ser::{CompactFormatter, Formatter};

use crate::json_text::needs_no_escape;
use crate::{Instruction, Op, Value};

/// Writes the listing line of `instruction`, newline included, if it is
/// one of the hot kinds with finite numbers; `None`, writing nothing,
/// otherwise.
pub(crate) fn write_hot(instruction: &Instruction, out: &mut impl Write) -> Option<fmt::Result> {
    let hot = match &instruction.op {
        Op::ModalChange { .. } => true,
        Op::Feed {
            value: Value::Const(value),
        } => value.is_finite(),
        Op::Motion {
            targets,
            circle: None,
            details: None,
            ..
        } => {
            !targets.is_empty()
                && targets
                    .iter()
                    .all(|target| target.plain_constant().is_some_and(f64::is_finite))
        }
        _ => false,
    };
    hot.then(|| write_line(instruction, out))
}

fn write_line(instruction: &Instruction, out: &mut impl Write) -> fmt::Result {
    let source = &instruction.source;
    write!(out, "{:>6}:{:<4} ", source.line, source.col)?;
    // The fields in the general path's order: by name.
    match &instruction.op {
        Op::ModalChange { group, code } => {
            out.write_str("modal_change code=")?;
            write_string(out, code.name())?;
            write!(out, " group={group}")?;
        }
        Op::Feed {
            value: Value::Const(value),
        } => {
            out.write_str("feed value=")?;
            write_number(out, *value)?;
        }
        Op::Motion {
            motion, targets, ..
        } => {
            out.write_str("motion motion=")?;
            write_string(out, motion.name())?;
            out.write_str(" targets=[")?;
            for (k, target) in targets.iter().enumerate() {
                out.write_str(if k == 0 { "{axis=" } else { ", {axis=" })?;
                write_string(out, &target.axis)?;
                out.write_str(" value=")?;
                if let Some(value) = target.plain_constant() {
                    write_number(out, value)?;
                }
                out.write_char('}')?;
            }
            out.write_char(']')?;
        }
        _ => {}
    }
    out.write_char('\n')
}

/// A string as compact JSON: quoted, escaped where it must be.
fn write_string(out: &mut impl Write, text: &str) -> fmt::Result {
    if needs_no_escape(text) {
        out.write_char('"')?;
        out.write_str(text)?;
        out.write_char('"')
    } else {
        out.write_str(&serde_json::to_string(text).map_err(|_| fmt::Error)?)
    }
}

/// A finite number as the listing writes it: a whole number below 1e15
/// as an integer (`R1`, not `R1.0`), any other as JSON writes it.
fn write_number(out: &mut impl Write, value: f64) -> fmt::Result {
    if value.fract() == 0.0 && value.abs() < 1e15 {
        return write!(out, "{}", value as i64);
    }
    let mut text = Cursor::new([0u8; 40]);
    CompactFormatter
        .write_f64(&mut text, value)
        .map_err(|_| fmt::Error)?;
    let len = usize::try_from(text.position()).map_err(|_| fmt::Error)?;
    let bytes = &text.get_ref()[..len];
    out.write_str(std::str::from_utf8(bytes).map_err(|_| fmt::Error)?)
}

#[cfg(test)]
mod tests {
    use std::borrow::Cow;
    use std::sync::Arc;

    use gcodec_lang::ggroups::GCommand;
    use gcodec_lang::{DimensionMode, MotionKind};

    use super::*;
    use crate::{AxisValue, ByteRange, Circle, Source, write_general_listing};

    fn source(k: usize) -> Source {
        Source {
            file: Arc::from("part.mpf"),
            line: [1, 42, 999_999, 1_234_567, u32::MAX][k % 5],
            col: [1, 4, 1234, 99_999][k % 4],
            span: ByteRange { start: 0, end: 1 },
        }
    }

    /// Every hot line is the general path's, and what is not hot is left
    /// to it: numbers whole and not, tiny, huge, signed zero, not finite;
    /// plain and quoted axis names; several motion kinds; modal changes of
    /// several groups; near misses (an `AC`, circle data, an expression).
    #[test]
    fn hot_lines_are_the_general_paths() {
        let numbers = [
            0.0,
            -0.0,
            1.0,
            -7.0,
            0.5,
            100.037,
            -123.4567,
            1.0 / 3.0,
            1e-7,
            5e-324,
            999_999_999_999_999.0,
            1e15,
            -1e15,
            1e16,
            1e300,
            f64::MAX,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        let kinds = [
            MotionKind::Linear,
            MotionKind::Rapid,
            MotionKind::Modal,
            MotionKind::ArcCw,
            MotionKind::InvoluteCcw,
        ];
        let mut instructions = Vec::new();
        for code in ["G1", "G0", "G17", "G64", "DIAMON", "G91", "CFTCP"] {
            let code = GCommand::named(code).expect("a G command");
            instructions.push(Instruction {
                op: Op::ModalChange {
                    group: code.group(),
                    code,
                },
                source: source(instructions.len()),
            });
        }
        for (k, pair) in numbers.windows(2).enumerate() {
            let target = |axis: Cow<'static, str>, value, mode| AxisValue {
                axis,
                value: Value::Const(value),
                mode,
            };
            let near_miss = k % 7 == 3;
            instructions.push(Instruction {
                op: Op::Motion {
                    motion: kinds[k % kinds.len()],
                    targets: vec![
                        target(Cow::Borrowed("X"), pair[0], None),
                        target(
                            Cow::Owned(format!("C\"{k}")),
                            pair[1],
                            near_miss.then_some(DimensionMode::Ac),
                        ),
                    ],
                    circle: (k % 7 == 5).then(|| Box::new(Circle::default())),
                    details: None,
                },
                source: source(k),
            });
            instructions.push(Instruction {
                op: Op::Feed {
                    value: Value::Const(pair[0]),
                },
                source: source(k + 1),
            });
        }
        instructions.push(Instruction {
            op: Op::Feed {
                value: Value::Expr(Box::new(crate::Expr::Number { value: 2.5 })),
            },
            source: source(0),
        });
        let (mut hot, mut general) = (0, 0);
        for instruction in &instructions {
            let mut by_hand = String::new();
            let mut expected = String::new();
            write_general_listing(instruction, &mut expected).unwrap();
            match write_hot(instruction, &mut by_hand) {
                Some(written) => {
                    written.unwrap();
                    hot += 1;
                    assert_eq!(by_hand, expected, "{instruction:?}");
                }
                None => {
                    assert!(by_hand.is_empty());
                    general += 1;
                }
            }
        }
        assert!(hot >= 30 && general >= 6, "{hot} hot, {general} general");
    }
}
