//! What may hold on some path from the program's start to each
//! instruction: no feed set yet, no speed set for a spindle, no tool
//! selected since the last change, no cutting edge since the change,
//! tool radius compensation on.
//!
//! A forward dataflow over the [`Graph`]: each fact is a bit, a path that
//! sets it makes it hold where the paths meet (union), and the facts at an
//! instruction are those of its block's entry, so that a block's own `F`,
//! `S`, `T`, `D` or `G40` counts wherever in the block it is written (the
//! control takes a block's words together).

use gcodec_ail::{Document, Op, ToolChangeTrigger};
use gcodec_profile::Profile;

use super::graph::Graph;
use crate::ProgramKind;

/// A set of facts, one bit each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Set(u64);

impl Set {
    /// No feed `F` set since the start.
    pub(crate) const FEED_UNSET: Set = Set(1);
    /// No tool selected since the start or the last change.
    pub(crate) const NO_SELECTION: Set = Set(1 << 1);
    /// A tool changed in, and no cutting edge `D` since.
    pub(crate) const NO_EDGE: Set = Set(1 << 2);
    /// `G41` or `G42` on.
    pub(crate) const COMPENSATION: Set = Set(1 << 3);
    /// The first spindle's bit; spindle `n` (1…[`SPINDLES`]) is bit
    /// `SPEED_BASE + n - 1`: no speed `S` set for it since the start.
    const SPEED_BASE: u32 = 8;

    const fn union(self, other: Set) -> Set {
        Set(self.0 | other.0)
    }

    pub(crate) const fn contains(self, other: Set) -> bool {
        self.0 & other.0 == other.0
    }

    const fn without(self, other: Set) -> Set {
        Set(self.0 & !other.0)
    }

    /// No speed set for spindle `number`; `None` for a spindle beyond
    /// those followed.
    pub(crate) fn speed_unset(number: u32) -> Option<Set> {
        (1..=SPINDLES)
            .contains(&number)
            .then(|| Set(1 << (Set::SPEED_BASE + number - 1)))
    }

    fn all_speeds() -> Set {
        Set(((1u64 << SPINDLES) - 1) << Set::SPEED_BASE)
    }
}

/// The spindles whose speed is followed, 1…16.
const SPINDLES: u32 = 16;

/// What an instruction does to the facts: those it ends, those it starts.
#[derive(Clone, Copy, Default)]
struct Effect {
    ends: Set,
    starts: Set,
}

/// The facts at the entry of every instruction some path reaches.
pub(crate) struct Facts {
    at: Vec<Set>,
    /// Per instruction, the facts its block ends anywhere in the block.
    block_ends: Vec<Set>,
    /// The machine's master spindle: the one `S` and `M3` address without
    /// a number.
    pub master_spindle: u32,
}

impl Facts {
    pub(crate) fn of(
        document: &Document,
        graph: &Graph,
        kind: ProgramKind,
        profile: &Profile,
    ) -> Self {
        let master_spindle = profile.machine.spindles.first().map_or(1, |s| *s.get_ref());
        // A changed-in tool has an edge unless MD20270 says none.
        let edge_after_change = *profile.tool_change.cutting_edge_default.get_ref() != 0;
        let mut effects: Vec<Effect> = document
            .instructions
            .iter()
            .map(|i| effect(&i.op, master_spindle, edge_after_change))
            .collect();
        let block_ends = block_ends(document, &effects);
        // `T1 M6 D1`: the block's edge counts for the change wherever it is
        // written. A block's `T` is the one its change takes, though: the
        // selection is used up.
        for (effect, ends) in effects.iter_mut().zip(&block_ends) {
            effect.starts = effect.starts.without(ends.without(Set::NO_SELECTION));
        }
        // A subprogram starts in its caller's state, which is not known:
        // nothing is assumed missing.
        let entry = match kind {
            ProgramKind::Main => Set::FEED_UNSET
                .union(Set::NO_SELECTION)
                .union(Set::all_speeds()),
            ProgramKind::Subprogram => Set::default(),
        };
        let at = solve(graph, &effects, entry);
        Facts {
            at,
            block_ends,
            master_spindle,
        }
    }

    /// Whether `fact` may hold at instruction `at` (reached by some path),
    /// its own block's words counted.
    pub(crate) fn may_hold(&self, at: usize, fact: Set) -> bool {
        let here = self.at[at].without(self.block_ends[at]);
        here.contains(fact) && fact != Set::default()
    }

    /// The spindle an `S` or `M3` without a number addresses.
    pub(crate) fn spindle(&self, number: Option<u32>) -> u32 {
        number.unwrap_or(self.master_spindle)
    }
}

fn effect(op: &Op, master: u32, edge_after_change: bool) -> Effect {
    let ends = |set: Set| Effect {
        ends: set,
        starts: Set::default(),
    };
    match op {
        Op::Feed { .. } => ends(Set::FEED_UNSET),
        Op::SpindleSpeed {
            spindle,
            spindle_expr,
            ..
        } => match spindle_expr {
            Some(_) => ends(Set::all_speeds()),
            None => ends(Set::speed_unset(spindle.unwrap_or(master)).unwrap_or_default()),
        },
        Op::ToolSelect(_) => ends(Set::NO_SELECTION),
        Op::ToolChange { trigger } => Effect {
            ends: Set::default(),
            starts: match (trigger, edge_after_change) {
                (ToolChangeTrigger::M6, true) => Set::NO_SELECTION,
                (ToolChangeTrigger::M6, false) => Set::NO_SELECTION.union(Set::NO_EDGE),
                (ToolChangeTrigger::TWord, true) => Set::default(),
                (ToolChangeTrigger::TWord, false) => Set::NO_EDGE,
            },
        },
        Op::CuttingEdge { .. } => ends(Set::NO_EDGE),
        Op::ModalChange { group: 7, code } => match code.name() {
            "G41" | "G42" => Effect {
                ends: Set::default(),
                starts: Set::COMPENSATION,
            },
            "G40" => ends(Set::COMPENSATION),
            _ => Effect::default(),
        },
        // A computed group-7 command may switch compensation off.
        Op::ModalChangeIndirect { group: 7, .. } => ends(Set::COMPENSATION),
        // A called program may set the feed, the speeds, select a tool
        // and an edge: what is missing before is not known after.
        Op::Call(_) => ends(
            Set::FEED_UNSET
                .union(Set::NO_SELECTION)
                .union(Set::NO_EDGE)
                .union(Set::all_speeds()),
        ),
        _ => Effect::default(),
    }
}

/// Per instruction, the facts ended anywhere in its block (the
/// instructions of one source line in a row).
fn block_ends(document: &Document, effects: &[Effect]) -> Vec<Set> {
    let mut out = vec![Set::default(); effects.len()];
    let lines: Vec<u32> = document
        .instructions
        .iter()
        .map(|i| i.source.line)
        .collect();
    let mut first = 0;
    while first < lines.len() {
        let mut last = first;
        while last + 1 < lines.len() && lines[last + 1] == lines[first] {
            last += 1;
        }
        let ends = effects[first..=last]
            .iter()
            .fold(Set::default(), |set, e| set.union(e.ends));
        out[first..=last].fill(ends);
        first = last + 1;
    }
    out
}

/// The facts at each instruction's entry: a worklist to the fixpoint
/// (each fact only ever added, so every instruction is revisited at most
/// once per fact).
fn solve(graph: &Graph, effects: &[Effect], entry: Set) -> Vec<Set> {
    let mut at = vec![Set::default(); graph.len()];
    if graph.len() == 0 {
        return at;
    }
    let mut queued = vec![false; graph.len()];
    let mut work = vec![0usize];
    at[0] = entry;
    queued[0] = true;
    while let Some(here) = work.pop() {
        queued[here] = false;
        let effect = effects[here];
        let out = at[here].without(effect.ends).union(effect.starts);
        for next in graph.successors(here) {
            let joined = at[next].union(out);
            if joined != at[next] {
                at[next] = joined;
                if !queued[next] {
                    queued[next] = true;
                    work.push(next);
                }
            }
        }
    }
    at
}
