//! The commonest block of large programs lowered directly: `G1 X… Y… F…`,
//! constant words for a straight motion and nothing else.
//!
//! The general path collects every word of a block into a [`BlockPlan`]
//! and then walks all of the plan's parts to emit the block's
//! instructions, which costs several times the three instructions such a
//! block makes. [`Lowering::constant_word_block`] takes a block only when
//! everything the general path would do with it is plain to see: no
//! control flow, skip mark or label; only compactly written constant
//! words; at most one `G`, and that one `G0` or `G1` the machine has with
//! no legacy alias; at most one `F`; each of the machine's single-letter
//! axes at most once, and at least one; the motion command straight
//! (`G0`, `G1`, or not known from the text). It emits what the general
//! path emits, in its order: the modal change, the feed, the motion.
//! Every other block, and every block with anything to report, is left to
//! the general path. `tests/constant_words.rs` holds the two to the same
//! instructions and diagnostics on every fixture and corpus program and on
//! generated blocks.

use std::borrow::Cow;

use gcodec_ail::{AxisValue, Op, Value};
use gcodec_lang::MotionKind;
use gcodec_lang::addresses::letter_str;
use gcodec_lang::ggroups::{self, GCommand};
use gcodec_parser::ast::{Block, StatementKind};
use gcodec_parser::{ConstantWord, WordLine};
use gcodec_source::Span;

use super::Lowering;

/// Most axes a block lowered here may move; more go the general way.
const MAX_TARGETS: usize = 10;

/// What a block of constant words says, read before anything is emitted.
#[derive(Default)]
struct ConstantWords {
    /// `G0` or `G1`, its name and where it is written.
    g: Option<(GCommand, &'static str, Span)>,
    feed: Option<(f64, Span)>,
    /// The axes' targets, the first `count` of them.
    targets: [(&'static str, f64, Span); MAX_TARGETS],
    count: usize,
}

impl Lowering<'_> {
    /// Lowers `block` (the program's block `index`, with no control-flow
    /// facts) if it is a straight motion of constant words; `false`, with
    /// nothing emitted or changed, if the general path must lower it.
    pub(super) fn constant_word_block(&mut self, index: usize, block: &Block) -> bool {
        if block.skip.is_some() || block.label.is_some() {
            return false;
        }
        let words = block
            .statements
            .iter()
            .map(|statement| match &statement.kind {
                StatementKind::Word(word) => {
                    word.letter_constant()
                        .map(|(letter, value, integer)| ConstantWord {
                            letter,
                            value,
                            integer,
                            span: statement.span,
                        })
                }
                _ => None,
            });
        let mut read = ConstantWords::default();
        let Some(motion) = self.straight_constant_words(words, &mut read) else {
            return false;
        };
        self.emit_constant_words(index, &read, motion);
        true
    }

    /// Lowers `line` (the program's block `index`) as
    /// [`Self::constant_word_block`] lowers its block, without the block:
    /// a streamed run reads most lines of large programs this way.
    /// `false`, with nothing emitted or changed, if the line's block must
    /// be lowered ([`Lowering::block`]): it has control-flow facts, is
    /// longer than the machine takes, or is no straight motion of
    /// constant words.
    pub(super) fn word_line(&mut self, index: usize, line: &WordLine) -> bool {
        let span = line.span();
        if !self.direct_constant_words
            || span.len() > *self.profile.program.max_block_length.get_ref()
            || self.block_flow(index).is_some()
        {
            return false;
        }
        let words = line.words().iter().copied().map(Some);
        let mut read = ConstantWords::default();
        let Some(motion) = self.straight_constant_words(words, &mut read) else {
            return false;
        };
        self.begin_block(span);
        self.emit_constant_words(index, &read, motion);
        true
    }

    /// Reads the constant words of a block into `words` (filled in place:
    /// moving them was a copy call a line); their motion if they are a
    /// straight motion [`Self::constant_word_block`] lowers (`None` stands
    /// for any other statement).
    fn straight_constant_words(
        &self,
        statements: impl Iterator<Item = Option<ConstantWord>>,
        words: &mut ConstantWords,
    ) -> Option<MotionKind> {
        if !self.read_constant_words(statements, words) {
            return None;
        }
        let motion_command = words.g.map_or(self.modal[0], |(_, name, _)| Some(name));
        straight_motion(motion_command)
    }

    /// Emits the instructions of `words`, the block `index`'s, a
    /// `motion`.
    fn emit_constant_words(&mut self, index: usize, words: &ConstantWords, motion: MotionKind) {
        let targets = &words.targets[..words.count];
        // At least one target (`read_constant_words`).
        let Some(&(_, _, first)) = targets.first() else {
            return;
        };
        if let Some((command, name, span)) = words.g {
            self.emit_named_modal_change(index, command, name, span);
        }
        if let Some((value, span)) = words.feed {
            self.emit(
                index,
                span,
                Op::Feed {
                    value: Value::Const(value),
                },
            );
        }
        let targets: Vec<AxisValue> = targets
            .iter()
            .map(|&(axis, value, _)| AxisValue {
                axis: Cow::Borrowed(axis),
                value: Value::Const(value),
                mode: None,
            })
            .collect();
        self.emit_motion_op(index, first, motion, targets, None, None);
    }

    /// Reads the constant words of a block into `words` (as they were
    /// made); whether they are all of the kinds
    /// [`Self::constant_word_block`] lowers, each as often as it may.
    fn read_constant_words(
        &self,
        statements: impl Iterator<Item = Option<ConstantWord>>,
        words: &mut ConstantWords,
    ) -> bool {
        for statement in statements {
            let Some(ConstantWord {
                letter,
                value,
                integer,
                span,
            }) = statement
            else {
                return false;
            };
            match letter {
                b'G' if words.g.is_none() && integer && (value == 0.0 || value == 1.0) => {
                    let Some((command, name)) = self.straight_commands[usize::from(value == 1.0)]
                    else {
                        return false;
                    };
                    words.g = Some((command, name, span));
                }
                b'F' if words.feed.is_none() => words.feed = Some((value, span)),
                b'A' | b'B' | b'C' | b'Q' | b'U' | b'V' | b'W' | b'X' | b'Y' | b'Z' => {
                    let axis = letter_str(letter);
                    let repeated = words.targets[..words.count]
                        .iter()
                        .any(|(a, _, _)| *a == axis);
                    let Some(slot) = words.targets.get_mut(words.count) else {
                        return false;
                    };
                    if repeated || !self.is_axis(axis) {
                        return false;
                    }
                    *slot = (axis, value, span);
                    words.count += 1;
                }
                _ => return false,
            }
        }
        words.count > 0
    }

    /// `G0` or `G1` (`value`), where the machine has it under that name:
    /// no legacy alias stands for it and the profile does not rule it out
    /// (kept in [`Lowering::straight_commands`]).
    pub(super) fn straight_motion_command(&self, value: f64) -> Option<GCommand> {
        if self.legacy_alias(value).is_some() {
            return None;
        }
        let (group, index) = ggroups::lookup_g(value as u64)?;
        let command = GCommand::new(group, index)?;
        (group == 1 && self.g_unsupported(group, command.name()).is_none()).then_some(command)
    }
}

/// The motion under the motion command `code` as the text knows it, if
/// straight: `G0`, `G1`, or not known (`modal`). Names compared, not
/// looked up: the per-block lookup cost a tenth of this path.
fn straight_motion(code: Option<&str>) -> Option<MotionKind> {
    match code {
        None => Some(MotionKind::Modal),
        Some("G0") => Some(MotionKind::Rapid),
        Some("G1") => Some(MotionKind::Linear),
        Some(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::straight_motion;
    use crate::lower::motion_of;

    /// The names compared are the commands the general path looks up.
    #[test]
    fn straight_motions_are_the_general_paths() {
        for code in ["G0", "G1"] {
            assert_eq!(straight_motion(Some(code)), motion_of(code), "{code}");
        }
        for code in ["G2", "G3", "G33", "ASPLINE", "CIP", "G01"] {
            assert_eq!(straight_motion(Some(code)), None, "{code}");
        }
    }
}
