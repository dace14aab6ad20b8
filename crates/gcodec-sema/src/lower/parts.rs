//! Lowering a program in parts: runs of blocks lowered at the same time,
//! on threads of their own ([`super::lower_in_parts`]) or a chunk at a time
//! in a streamed run ([`super::stream::lower_chunks`]).
//!
//! A part after the first is lowered before the part before it has ended,
//! so it starts in a state it does not know ([`Entry::AfterOpenPart`]).
//! Lowering then leaves what reads that state open and notes where
//! ([`OpenEntry`]); the [`PartLedger`] takes the parts in order and fills
//! in what each left open from the exit state of the part before it, or
//! says that the part must be lowered again from that state.

use gcodec_ail::{Document, Op};
use gcodec_lang::{MotionKind, WorkOffsetCode};

use super::{Lowering, assign_motion_command, motion_of};

/// The state lowering passes from a part to the part after it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct BoundaryState {
    /// The motion command (group 1), `None` where unknown.
    pub(super) group1: Option<&'static str>,
    /// The Group 8 selection, `None` where unknown.
    pub(super) group8: Option<u8>,
    /// `MCALL NAME` is in force.
    pub(super) modal_call: bool,
}

/// Where a lowering starts.
#[derive(Clone, Copy, Debug)]
pub(super) enum Entry {
    /// At the start of the program (of a subprogram: in its caller's
    /// state, unknown).
    ProgramStart,
    /// After a part whose exit state is not known yet: what reads it is
    /// left open for the [`PartLedger`].
    AfterOpenPart,
    /// After a part that ended in this state.
    After(BoundaryState),
}

/// What a part that started after an open part ([`Entry::AfterOpenPart`])
/// left open: the instructions that read the state it started in, until
/// the part sets that state or forgets it.
#[derive(Debug, Default)]
pub(super) struct OpenEntry {
    /// The part started after an open part: there may be something to
    /// fill in.
    after_open_part: bool,
    /// The motion command is still the one the part started with.
    group1: bool,
    /// The Group 8 selection is still the one the part started with.
    group8: bool,
    /// Motions under the command the part started with (indices into the
    /// part's instructions).
    motions: Vec<usize>,
    /// Work offsets under the selection the part started with.
    offsets: Vec<usize>,
}

impl OpenEntry {
    /// What a lowering from `entry` has open before its first block.
    pub(super) fn at(entry: Entry) -> Self {
        let open = matches!(entry, Entry::AfterOpenPart);
        Self {
            after_open_part: open,
            group1: open,
            group8: open,
            ..Self::default()
        }
    }

    /// The motion command is the one the part started with, not known.
    pub(super) fn group1_is_entry(&self) -> bool {
        self.group1
    }

    /// The Group 8 selection is the one the part started with, not known.
    pub(super) fn group8_is_entry(&self) -> bool {
        self.group8
    }

    /// The part sets its own motion command.
    pub(super) fn set_group1(&mut self) {
        self.group1 = false;
    }

    /// The part sets its own Group 8 selection.
    pub(super) fn set_group8(&mut self) {
        self.group8 = false;
    }

    /// The part forgets the state (paths meet): nothing after this reads
    /// the state it started with.
    pub(super) fn forget(&mut self) {
        self.group1 = false;
        self.group8 = false;
    }

    /// The motion at `at` moves under the command the part started with.
    pub(super) fn read_by_motion(&mut self, at: usize) {
        self.motions.push(at);
    }

    /// The work offset at `at` is under the selection the part started
    /// with.
    pub(super) fn read_by_work_offset(&mut self, at: usize) {
        self.offsets.push(at);
    }

    /// Fills in the motions and work offsets of `document` that read the
    /// state the part started in, which is `entry`. False where that is
    /// not all a lowering from `entry` would have done differently: a
    /// modal call in force at the entry, a motion under a command that is
    /// not lowered, a thread reading `F` as its lead change, or an arc
    /// without circle data (a lowering from `entry` reports it).
    fn fill_in(&self, document: &mut Document, entry: BoundaryState) -> bool {
        if !self.after_open_part {
            return true;
        }
        if entry.modal_call {
            return false;
        }
        if let (false, Some(code)) = (self.motions.is_empty(), entry.group1) {
            let Some(kind) = motion_of(code).filter(|_| !matches!(code, "G34" | "G35")) else {
                return false;
            };
            for &i in &self.motions {
                if let Op::Motion {
                    motion,
                    circle,
                    details,
                    ..
                } = &mut document.instructions[i].op
                {
                    let no_circle = circle.as_ref().is_none_or(|c| {
                        c.centre.is_empty() && c.radius.is_none() && c.opening_angle.is_none()
                    });
                    if matches!(kind, MotionKind::ArcCw | MotionKind::ArcCcw) && no_circle {
                        return false;
                    }
                    assign_motion_command(motion, circle, details, kind);
                }
            }
        }
        let selected = entry.group8.and_then(WorkOffsetCode::of_index);
        for &i in &self.offsets {
            if let Op::WorkOffset {
                group8_selected, ..
            } = &mut document.instructions[i].op
            {
                *group8_selected = selected;
            }
        }
        true
    }
}

/// Takes the parts of a lowering in order and fills in what each left
/// open from the exit state of the part before it.
#[derive(Debug, Default)]
pub(super) struct PartLedger {
    /// The exit state of the last part taken; `None` before the first.
    exit: Option<BoundaryState>,
}

impl PartLedger {
    /// Takes `part`, the part after those taken: fills in what it left
    /// open and records its exit state. False if the part needs more than
    /// filling in: it must be lowered again from [`Self::entry`] and
    /// taken then.
    pub(super) fn take(&mut self, part: &mut Lowering<'_>) -> bool {
        let entry = self.exit.unwrap_or_default();
        if !part.open.fill_in(&mut part.document, entry) {
            return false;
        }
        self.exit = Some(part.exit_state(entry));
        true
    }

    /// Where the part after those taken starts.
    pub(super) fn entry(&self) -> Entry {
        self.exit.map_or(Entry::ProgramStart, Entry::After)
    }
}

/// Takes `parts` in order ([`PartLedger::take`]); false if one of them
/// must be lowered again.
pub(super) fn settle_parts(parts: &mut [Lowering<'_>]) -> bool {
    let mut ledger = PartLedger::default();
    parts.iter_mut().all(|part| ledger.take(part))
}

impl Lowering<'_> {
    /// The state after this part, given `entry`, the state it started in.
    pub(super) fn exit_state(&self, entry: BoundaryState) -> BoundaryState {
        BoundaryState {
            group1: if self.open.group1_is_entry() {
                entry.group1
            } else {
                self.modal[0]
            },
            group8: if self.open.group8_is_entry() {
                entry.group8
            } else {
                self.group8
            },
            modal_call: self.modal_call,
        }
    }
}
