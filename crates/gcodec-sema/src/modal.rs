//! The modal state at every block, as far as it is known before the program
//! runs: for each program line with instructions, the command of each of
//! the 64 G groups when the block starts, or "unknown" where the paths that
//! reach the block disagree or a call may have changed it.
//!
//! The analysis is a forward dataflow over the control flow of a lowered
//! AIL [`Document`]: instructions run in order, `label`s are join points,
//! `jump`, `skip_block`, `computed_jump`, `goto_start` and
//! `repeat_section` add edges and `return`, `end` and `M2 M17 M30` end a
//! path. At a join, a group keeps its command only if every path agrees.
//! Each group's value can only rise from "not reached" to a command to
//! "unknown", so the fixed point is reached after at most 66 changes per
//! join point; straight-line code is walked once. See
//! [`ModalStates::analyse`] for the rules.
//!
//! Memory: the state of a line is an id into a table of the distinct
//! states (straight-line code has few), 8 bytes per line with instructions;
//! a state is 65 bytes (one registry index per group, plus whether a modal
//! call is active).

use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::collections::hash_map::Entry;
use std::fmt;

use gcodec_ail::{Document, Instruction, Op, RepeatSection, Value};
use gcodec_lang::modal::GROUP_COUNT;
use gcodec_lang::{MClass, ggroups};
use gcodec_profile::{Profile, reset_defaults};
use rustc_hash::FxHashMap;

/// Where the analysed program starts.
#[derive(Clone, Copy, Debug)]
pub enum Start<'a> {
    /// A main program: every group in its reset state ([`reset_defaults`]).
    Reset(&'a Profile),
    /// A subprogram: it starts in its caller's state, which is not known
    /// here, so every group is unknown.
    Unknown,
}

// Whether a modal call (`MCALL NAME(…)`) is active: it runs `NAME` after
// every traversing block, and `NAME` may change any group.
const CALL_UNKNOWN: u8 = 0;
const CALL_INACTIVE: u8 = 1;
const CALL_ACTIVE: u8 = 2;

/// The modal state at one point of the program: per G group the command in
/// force, or unknown.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct ModalState {
    /// The registry index (1-based, [`ggroups::member`]) of each group's
    /// command, group `n` at `n - 1`; 0 is unknown. Registry indices fit a
    /// byte (the longest group, 64, has 101 members), so a state is 65
    /// bytes.
    groups: [u8; GROUP_COUNT],
    /// One of `CALL_UNKNOWN`, `CALL_INACTIVE`, `CALL_ACTIVE`.
    modal_call: u8,
}

impl ModalState {
    /// The state after a reset of the machine `profile` describes, with no
    /// modal call active.
    pub fn reset(profile: &Profile) -> Self {
        let mut state = Self::unknown();
        for (i, code) in reset_defaults(profile).iter().enumerate() {
            let index = code.and_then(ggroups::lookup).map_or(0, |(_, index)| index);
            state.groups[i] = index;
        }
        state
    }

    /// Every group unknown, no modal call active (see
    /// [`ModalStates::analyse`] for why a subprogram may assume that).
    pub fn unknown() -> Self {
        Self {
            groups: [0; GROUP_COUNT],
            modal_call: CALL_INACTIVE,
        }
    }

    /// The command of `group` (1…64) as the registry spells it (`G1`,
    /// `G17`, `DIAMON`); `None` when it is unknown, for non-modal and
    /// unassigned groups (no command stays in force) and outside 1…64.
    pub fn get(&self, group: u8) -> Option<&'static str> {
        ggroups::member(group, self.index(group)?)
    }

    /// The registry index of `group`'s command (the value `$P_GG[group]`
    /// returns), or `None` as for [`get`](Self::get).
    pub fn index(&self, group: u8) -> Option<u8> {
        let slot = *self.groups.get(usize::from(group).checked_sub(1)?)?;
        (slot != 0).then_some(slot)
    }

    /// The groups whose command is known, in group order.
    pub fn known(&self) -> impl Iterator<Item = (u8, &'static str)> + '_ {
        (1..=GROUP_COUNT as u8).filter_map(|group| Some((group, self.get(group)?)))
    }

    /// Whether a modal call (`MCALL NAME(…)`) is active: `None` when the
    /// paths reaching this point disagree.
    pub fn modal_call_active(&self) -> Option<bool> {
        match self.modal_call {
            CALL_ACTIVE => Some(true),
            CALL_INACTIVE => Some(false),
            _ => None,
        }
    }

    /// Joins `other` into `self` (what is known on both paths stays known);
    /// true if `self` changed.
    fn join(&mut self, other: &Self) -> bool {
        let mut changed = false;
        for (mine, theirs) in self.groups.iter_mut().zip(&other.groups) {
            if *mine != *theirs && *mine != 0 {
                *mine = 0;
                changed = true;
            }
        }
        if self.modal_call != other.modal_call && self.modal_call != CALL_UNKNOWN {
            self.modal_call = CALL_UNKNOWN;
            changed = true;
        }
        changed
    }

    /// Sets group `group` (1…64) to the registry index `index` (0:
    /// unknown); true if that changed the state.
    fn set(&mut self, group: u8, index: u8) -> bool {
        match usize::from(group)
            .checked_sub(1)
            .and_then(|i| self.groups.get_mut(i))
        {
            Some(slot) if *slot != index => {
                *slot = index;
                true
            }
            _ => false,
        }
    }

    /// Every group unknown (after a call that may change any of them).
    fn forget_groups(&mut self) -> bool {
        let changed = self.groups.iter().any(|&g| g != 0);
        self.groups = [0; GROUP_COUNT];
        changed
    }

    fn set_modal_call(&mut self, value: u8) -> bool {
        let changed = self.modal_call != value;
        self.modal_call = value;
        changed
    }
}

impl fmt::Display for ModalState {
    /// The known commands in group order, separated by blanks.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut first = true;
        for (_, code) in self.known() {
            if !first {
                f.write_str(" ")?;
            }
            f.write_str(code)?;
            first = false;
        }
        Ok(())
    }
}

impl fmt::Debug for ModalState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ModalState")
            .field("known", &self.known().collect::<Vec<_>>())
            .field("modal_call_active", &self.modal_call_active())
            .finish()
    }
}

/// What the analysis says about one line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineState<'a> {
    /// The line has no instructions (it is empty or only a comment) or is
    /// not in the document.
    NoInstructions,
    /// No path from the start reaches the line (e.g. after `M30` or an
    /// unconditional jump, without a label that is jumped to).
    Unreachable,
    /// The state when the block starts.
    Reached(&'a ModalState),
}

/// The line has instructions, but no path reaches it.
const UNREACHED: u32 = u32::MAX;

/// The modal state at the start of every block of a document.
#[derive(Clone, Debug)]
pub struct ModalStates {
    /// The distinct states of reached lines, in the order they first
    /// start a line.
    states: Vec<ModalState>,
    /// The lines with instructions, sorted.
    lines: Vec<u32>,
    /// (index into `lines`, index into `states` or `UNREACHED`): from that
    /// line on, up to the next change, the lines have that state. Sorted;
    /// the first starts at 0 when there are lines. Consecutive lines in
    /// one state (straight-line code that changes no group) share an entry.
    changes: Vec<(u32, u32)>,
}

impl ModalStates {
    /// Analyses `document`, starting in the state `start` gives.
    ///
    /// The state of a line is the state before its first instruction (in
    /// document order); a loop that comes back into the middle of a block
    /// (`FOR` sets its counter before its head label) does not change it.
    ///
    /// - `modal_change` sets its group; a command the registry does not
    ///   place in that group makes the group unknown. Non-modal groups (2,
    ///   3, 9, 11, 62) act in their block only and are never in a state.
    /// - `modal_change_indirect` (`G[8]=KORD`) sets the group when its
    ///   index is a constant member, else makes it unknown.
    /// - `work_offset` sets group 8 to `group8_selected`. With a
    ///   suppression (`G53`, `G153`, `SUPA`) the block may have had no
    ///   Group 8 code, and `group8_selected` is then what lowering tracked
    ///   in line order, not along the control flow: group 8 stays known
    ///   only if it already had that value.
    /// - `call` may change any group (the callee is another file, and
    ///   whether it restores the caller's G codes — `PROC … SAVE` — is not
    ///   known here): after it every group is unknown. `MCALL NAME(…)`
    ///   calls nothing yet but makes every later traversing block (a
    ///   `motion`) such a call, until `MCALL` alone cancels it. A
    ///   subprogram's own `MCALL` is taken to end with it, and a
    ///   subprogram to start without its caller's modal call (the modal
    ///   call does not run inside what it calls).
    /// - `jump` goes to every label of its target name; with a
    ///   `condition` it may also go on. A target that does not exist
    ///   (`X@missing`) is alarm 14080 when the jump runs: that path ends.
    /// - `skip_block` may go to its `end` label (the skip level is on) and
    ///   may go on: a conditional jump.
    /// - `computed_jump` may go to any label; it goes on when it has a
    ///   condition or `continue_if_missing`.
    /// - `goto_start` may go back to the first instruction (the PLC
    ///   decides) and may go on.
    /// - `repeat_section` runs its section, then goes on as the state at
    ///   the section's `end` label leaves it; with more than one pass
    ///   (or a computed count) the end joins into the start again, and
    ///   with a computed count it may also skip the section. When a label
    ///   of the section is missing, nothing is known after it.
    /// - `return`, `end`, and `M2 M17 M30` end the path.
    ///
    /// Never panics, and terminates on any document.
    pub fn analyse(document: &Document, start: Start<'_>) -> Self {
        let initial = match start {
            Start::Reset(profile) => ModalState::reset(profile),
            Start::Unknown => ModalState::unknown(),
        };
        let graph = Graph::new(&document.instructions);
        let mut table = StateTable::new(graph.motions_matter);
        let initial = table.intern(&initial);
        let entries = Solver::solve(&graph, &mut table, initial);
        Self::collect(&graph, &entries, &mut table)
    }

    /// Replays each reached basic block from its entry state and records
    /// the state at the first instruction of every line.
    fn collect(graph: &Graph<'_>, entries: &[u32], table: &mut StateTable) -> Self {
        let mut out = Collector {
            remap: vec![UNREACHED; table.states.len()],
            states: Vec::new(),
            lines: Vec::with_capacity(graph.runs),
            changes: Vec::new(),
            last: None,
        };
        for (block, &entry) in entries.iter().enumerate() {
            let mut id = entry;
            for event in graph.events(block) {
                if event.code == LINE {
                    out.record(event.line, id, table);
                } else if id != UNREACHED {
                    id = table.step(id, event.code);
                }
            }
        }
        let Collector {
            mut states,
            mut lines,
            mut changes,
            ..
        } = out;
        // Lowering writes lines in order; another writer may not. The first
        // run of a line in document order is its block's start.
        if !graph.lines_sorted {
            let mut pairs = Vec::with_capacity(lines.len());
            let mut change = 0;
            let mut current = UNREACHED;
            for (at, &line) in lines.iter().enumerate() {
                while let Some(&(from, id)) = changes.get(change) {
                    if from as usize > at {
                        break;
                    }
                    current = id;
                    change += 1;
                }
                pairs.push((line, current));
            }
            pairs.sort_by_key(|&(line, _)| line);
            pairs.dedup_by_key(|&mut (line, _)| line);
            lines.clear();
            changes.clear();
            for (line, id) in pairs {
                if changes.last().is_none_or(|&(_, last)| last != id) {
                    changes.push((lines.len() as u32, id));
                }
                lines.push(line);
            }
        }
        lines.shrink_to_fit();
        changes.shrink_to_fit();
        states.shrink_to_fit();
        Self {
            states,
            lines,
            changes,
        }
    }

    /// The state id (into `states`, or `UNREACHED`) of the `at`th line
    /// with instructions.
    fn id_of(&self, at: usize) -> u32 {
        let after = self
            .changes
            .partition_point(|&(from, _)| from as usize <= at);
        after
            .checked_sub(1)
            .and_then(|c| self.changes.get(c))
            .map_or(UNREACHED, |&(_, id)| id)
    }

    /// The lines with instructions, in order, with their state ids.
    fn ids(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.changes
            .iter()
            .enumerate()
            .flat_map(move |(c, &(from, id))| {
                let to = self
                    .changes
                    .get(c + 1)
                    .map_or(self.lines.len(), |&(to, _)| to as usize);
                let lines = self.lines.get(from as usize..to).unwrap_or(&[]);
                lines.iter().map(move |&line| (line, id))
            })
    }

    /// What is known about `line` (1-based).
    pub fn line_state(&self, line: u32) -> LineState<'_> {
        let Ok(at) = self.lines.binary_search(&line) else {
            return LineState::NoInstructions;
        };
        match self.states.get(self.id_of(at) as usize) {
            Some(state) => LineState::Reached(state),
            None => LineState::Unreachable,
        }
    }

    /// The state when the block on `line` starts; `None` when the line has
    /// no instructions or is never reached ([`line_state`](Self::line_state)
    /// tells which).
    pub fn state_at_line(&self, line: u32) -> Option<&ModalState> {
        match self.line_state(line) {
            LineState::Reached(state) => Some(state),
            LineState::NoInstructions | LineState::Unreachable => None,
        }
    }

    /// The reached lines with their states, in line order.
    pub fn iter(&self) -> impl Iterator<Item = (u32, &ModalState)> + '_ {
        self.ids()
            .filter_map(|(line, at)| Some((line, self.states.get(at as usize)?)))
    }

    /// The lines with instructions that no path reaches, in order.
    pub fn unreachable_lines(&self) -> impl Iterator<Item = u32> + '_ {
        self.ids()
            .filter(|&(_, at)| at == UNREACHED)
            .map(|(line, _)| line)
    }

    /// How many different states the reached lines have.
    pub fn distinct_states(&self) -> usize {
        self.states.len()
    }

    /// The heap memory the result holds, in bytes.
    pub fn heap_bytes(&self) -> usize {
        self.states.capacity() * std::mem::size_of::<ModalState>()
            + self.lines.capacity() * std::mem::size_of::<u32>()
            + self.changes.capacity() * std::mem::size_of::<(u32, u32)>()
    }
}

/// Builds the result of [`ModalStates::collect`].
struct Collector {
    /// The result's id of each state of the table (`UNREACHED`: none yet).
    remap: Vec<u32>,
    states: Vec<ModalState>,
    lines: Vec<u32>,
    changes: Vec<(u32, u32)>,
    /// The result id of the last line recorded.
    last: Option<u32>,
}

impl Collector {
    /// The line `line` starts in the table's state `id` (or `UNREACHED`).
    fn record(&mut self, line: u32, id: u32, table: &StateTable) {
        let at = match self.remap.get_mut(id as usize) {
            Some(slot) if *slot != UNREACHED => *slot,
            Some(slot) => {
                let at = self.states.len() as u32;
                *slot = at;
                self.states.push(table.states[id as usize].clone());
                at
            }
            None => UNREACHED,
        };
        if self.last != Some(at) {
            self.last = Some(at);
            self.changes.push((self.lines.len() as u32, at));
        }
        self.lines.push(line);
    }
}

/// Line-start pseudo event: the line of the instruction is in `line`.
const LINE: u32 = 0;
// State-changing events, `kind << 16 | group << 8 | index`.
/// Sets group `group` to `index`.
const SET: u32 = 1;
/// A `work_offset` with a suppression selecting `index`: group 8 stays
/// known only if it already is `index`.
const SUPPRESSED: u32 = 2;
const MODAL_CALL: u32 = 3;
const CANCEL_MODAL_CALL: u32 = 4;
/// A call: every group unknown.
const FORGET: u32 = 5;
/// A traversing block: a call if a modal call may be active.
const MOTION: u32 = 6;

const fn code(kind: u32, group: u8, index: u8) -> u32 {
    kind << 16 | (group as u32) << 8 | index as u32
}

/// Applies the event `code` to `state`; true if the state changed.
fn apply(state: &mut ModalState, code: u32) -> bool {
    let group = (code >> 8) as u8;
    let index = code as u8;
    match code >> 16 {
        SET => state.set(group, index),
        SUPPRESSED if state.index(8) == Some(index) => false,
        SUPPRESSED => state.set(8, 0),
        MODAL_CALL => state.set_modal_call(CALL_ACTIVE),
        CANCEL_MODAL_CALL => state.set_modal_call(CALL_INACTIVE),
        FORGET => state.forget_groups(),
        MOTION if state.modal_call != CALL_INACTIVE => state.forget_groups(),
        _ => false,
    }
}

/// Distinct states by dense id, with the effect of events and joins on ids
/// memoised: the analysis works on ids and builds a state only the first
/// time an event or a join leads to it.
struct StateTable {
    states: Vec<ModalState>,
    ids: FxHashMap<ModalState, u32>,
    /// Direct-mapped cache of `(id << 32 | event code) → id`; key
    /// `u64::MAX` is empty (no event code is `u32::MAX`).
    steps: Box<[(u64, u32)]>,
    /// Whether `MOTION` can change anything: only if the document has a
    /// modal call or a `repeat_section` (the only ways a modal call gets
    /// active or unknown); else every motion is a no-op.
    motions_matter: bool,
}

const STEP_BITS: u32 = 12;

/// The multiplier of FxHash: it spreads the keys of the direct-mapped
/// step cache over its slots.
const FX_SEED: u64 = 0x51_7c_c1_b7_27_22_0a_95;

impl StateTable {
    fn new(motions_matter: bool) -> Self {
        Self {
            states: Vec::new(),
            ids: FxHashMap::default(),
            steps: vec![(u64::MAX, 0); 1 << STEP_BITS].into_boxed_slice(),
            motions_matter,
        }
    }

    fn intern(&mut self, state: &ModalState) -> u32 {
        if let Some(&id) = self.ids.get(state) {
            return id;
        }
        // Ids stay below `UNREACHED`: a document has fewer than 2^32 - 1
        // join points times 66 states.
        let id = self.states.len() as u32;
        self.states.push(state.clone());
        self.ids.insert(state.clone(), id);
        id
    }

    /// The state after the event `code` in the state `id`.
    fn step(&mut self, id: u32, code: u32) -> u32 {
        if code >> 16 == MOTION && !self.motions_matter {
            return id;
        }
        let key = u64::from(id) << 32 | u64::from(code);
        let slot = (key.wrapping_mul(FX_SEED) >> (64 - STEP_BITS)) as usize;
        if let Some(&(k, to)) = self.steps.get(slot)
            && k == key
        {
            return to;
        }
        let Some(mut state) = self.states.get(id as usize).cloned() else {
            return id;
        };
        let to = if apply(&mut state, code) {
            self.intern(&state)
        } else {
            id
        };
        if let Some(entry) = self.steps.get_mut(slot) {
            *entry = (key, to);
        }
        to
    }

    /// The join of the states `a` and `b`.
    fn join(&mut self, a: u32, b: u32) -> u32 {
        if a == b {
            return a;
        }
        let (Some(mine), Some(theirs)) = (self.states.get(a as usize), self.states.get(b as usize))
        else {
            return a;
        };
        let mut joined = mine.clone();
        if joined.join(theirs) {
            self.intern(&joined)
        } else {
            a
        }
    }
}

/// How an instruction affects the control flow.
#[derive(Clone, Copy)]
enum Control<'d> {
    /// On with the next instruction.
    Next,
    /// The path ends: `return`, `end`, `M2 M17 M30`.
    Stop,
    Jump {
        target: &'d str,
        conditional: bool,
    },
    /// To any label; `goes_on` when it may also continue.
    Computed {
        goes_on: bool,
    },
    /// `goto_start`: to the first instruction or on.
    Start,
    Repeat(&'d RepeatSection),
}

/// One entry of [`Graph::events`]: a line starts (`code` `LINE`), or an
/// instruction that may change the state (`code` from [`code`]).
#[derive(Clone, Copy)]
struct Event {
    code: u32,
    line: u32,
}

/// A basic block: it starts at the first instruction, at every label and
/// after every instruction that does not simply go on.
struct Block<'d> {
    /// Its first event in [`Graph::events`].
    first_event: u32,
    /// The label it starts with.
    label: Option<&'d str>,
    /// What its last instruction does.
    control: Control<'d>,
}

/// The document cut into basic blocks, each reduced to the events that
/// matter to the state: line starts and state changes, in order.
struct Graph<'d> {
    events: Vec<Event>,
    blocks: Vec<Block<'d>>,
    /// The block of every label, in order.
    labels: Vec<u32>,
    /// The next label of the same name, by index into `labels`
    /// (`u32::MAX`: none).
    label_next: Vec<u32>,
    /// The first and last label (index into `labels`) of each name.
    label_names: FxHashMap<&'d str, (u32, u32)>,
    /// (end label, block ending in the `repeat_section`, the section),
    /// sorted by the end label.
    repeats: Vec<(&'d str, u32, &'d RepeatSection)>,
    /// The number of line runs (maximal runs of instructions on one line).
    runs: usize,
    /// Whether each run's line is greater than the one before.
    lines_sorted: bool,
    /// See [`StateTable::motions_matter`].
    motions_matter: bool,
}

impl<'d> Graph<'d> {
    /// One pass over the instructions. Every `Op` is listed so that a new
    /// kind is a compile error here.
    fn new(instructions: &'d [Instruction]) -> Self {
        let mut events = Vec::with_capacity(instructions.len());
        let mut blocks: Vec<Block<'d>> = Vec::new();
        let mut labels = Vec::new();
        let mut label_list: Vec<&'d str> = Vec::new();
        let mut repeats = Vec::new();
        let mut runs = 0;
        let mut lines_sorted = true;
        let mut motions_matter = false;
        let mut previous_line = None;
        let mut starts_block = true;
        // Whether the last state event of this block is a `MOTION`: a
        // motion after it changes nothing more (after the first, either
        // no modal call is active or every group is already unknown).
        let mut after_motion = false;
        for instruction in instructions {
            let op = &instruction.op;
            if starts_block || matches!(op, Op::Label { .. }) {
                blocks.push(Block {
                    first_event: events.len() as u32,
                    label: None,
                    control: Control::Next,
                });
                after_motion = false;
            }
            let line = instruction.source.line;
            if previous_line != Some(line) {
                if previous_line.is_some_and(|previous| previous >= line) {
                    lines_sorted = false;
                }
                previous_line = Some(line);
                runs += 1;
                events.push(Event { code: LINE, line });
            }
            let block = blocks.len() as u32 - 1;
            let mut control = Control::Next;
            let mut event = None;
            match op {
                Op::ModalChange {
                    group,
                    code: command,
                } => {
                    if ggroups::is_modal(*group) {
                        // A command of another group (in a document read
                        // from JSON) makes the group's command unknown.
                        let index = if command.group() == *group {
                            command.index()
                        } else {
                            0
                        };
                        event = Some(code(SET, *group, index));
                    }
                }
                Op::ModalChangeIndirect { group, index } => {
                    let index = match index {
                        Value::Const(v) if v.fract() == 0.0 && (1.0..=255.0).contains(v) => {
                            let v = *v as u8;
                            if ggroups::member(*group, v).is_some() {
                                v
                            } else {
                                0
                            }
                        }
                        _ => 0,
                    };
                    if ggroups::is_modal(*group) {
                        event = Some(code(SET, *group, index));
                    }
                }
                Op::WorkOffset {
                    group8_selected,
                    suppression,
                    ..
                } => {
                    // `null`: a suppression alone, the selection unknown to
                    // lowering; a suppression never changes the selection.
                    if let Some(selected) = group8_selected {
                        // The registry lists group 8 in `$P_UIFR` order
                        // from index 1.
                        let selected = selected.index().map_or(0, |uifr| uifr + 1);
                        let kind = if suppression.is_some() {
                            SUPPRESSED
                        } else {
                            SET
                        };
                        event = Some(code(kind, 8, selected));
                    }
                }
                Op::Call(call) if call.modal => {
                    motions_matter = true;
                    event = Some(code(MODAL_CALL, 0, 0));
                }
                Op::Call(_) => event = Some(code(FORGET, 0, 0)),
                Op::CancelModalCall => event = Some(code(CANCEL_MODAL_CALL, 0, 0)),
                // A modal call runs after the block (or may: unknown).
                Op::Motion { .. } => {
                    if !after_motion {
                        events.push(Event {
                            code: code(MOTION, 0, 0),
                            line,
                        });
                        after_motion = true;
                    }
                }
                Op::Label { name } => {
                    labels.push(block);
                    label_list.push(name.as_str());
                    if let Some(last) = blocks.last_mut() {
                        last.label = Some(name.as_str());
                    }
                }
                Op::Jump { target, condition } => {
                    control = Control::Jump {
                        target,
                        conditional: condition.is_some(),
                    };
                }
                // A skipped block continues at its end label.
                Op::SkipBlock { end, .. } => {
                    control = Control::Jump {
                        target: end,
                        conditional: true,
                    };
                }
                Op::ComputedJump(jump) => {
                    control = Control::Computed {
                        goes_on: jump.condition.is_some() || jump.continue_if_missing,
                    };
                }
                Op::GotoStart { .. } => control = Control::Start,
                Op::RepeatSection(section) => {
                    motions_matter = true;
                    repeats.push((section.end.as_str(), block, &**section));
                    control = Control::Repeat(section);
                }
                Op::Return { .. } | Op::End => control = Control::Stop,
                Op::MFunction(m) => {
                    // The program-flow class: the profile may not
                    // reclassify these values (the extension is forbidden
                    // for them), but a machine could map one to a custom
                    // function; then it does not end.
                    let ends = m.class == MClass::ProgramFlow
                        && m.address_extension.is_none()
                        && m.address_extension_expr.is_none()
                        && matches!(m.m_value, Some(2 | 17 | 30));
                    if ends {
                        control = Control::Stop;
                    }
                }
                Op::ToolSelect(_)
                | Op::ToolChange { .. }
                | Op::CuttingEdge { .. }
                | Op::Feed { .. }
                | Op::SpindleSpeed { .. }
                | Op::Dwell { .. }
                | Op::Address(_)
                | Op::HFunction(_)
                | Op::Frame(_)
                | Op::AxisSetting(_)
                | Op::ApproachPoint(_)
                | Op::Declare(_)
                | Op::Assign { .. }
                | Op::AssignList(_)
                | Op::Procedure(_)
                | Op::External(_)
                | Op::Message { .. }
                | Op::Stop { .. }
                | Op::InterruptAssign(_)
                | Op::InterruptControl { .. } => {}
            }
            if let Some(code) = event {
                events.push(Event { code, line });
                after_motion = false;
            }
            starts_block = !matches!(control, Control::Next);
            if starts_block && let Some(last) = blocks.last_mut() {
                last.control = control;
            }
        }
        let mut label_next = vec![u32::MAX; label_list.len()];
        let mut label_names: FxHashMap<&'d str, (u32, u32)> =
            FxHashMap::with_capacity_and_hasher(label_list.len(), Default::default());
        for (at, name) in label_list.into_iter().enumerate() {
            let at = at as u32;
            match label_names.entry(name) {
                Entry::Occupied(mut chain) => {
                    let (_, last) = chain.get_mut();
                    if let Some(next) = label_next.get_mut(*last as usize) {
                        *next = at;
                    }
                    *last = at;
                }
                Entry::Vacant(chain) => {
                    chain.insert((at, at));
                }
            }
        }
        repeats.sort_unstable_by_key(|&(end, block, _)| (end, block));
        Self {
            events,
            blocks,
            labels,
            label_next,
            label_names,
            repeats,
            runs,
            lines_sorted,
            motions_matter,
        }
    }

    fn block_count(&self) -> usize {
        self.blocks.len()
    }

    /// The events of `block`.
    fn events(&self, block: usize) -> &[Event] {
        let start = self.blocks.get(block).map_or(0, |b| b.first_event as usize);
        let end = self
            .blocks
            .get(block + 1)
            .map_or(self.events.len(), |b| b.first_event as usize);
        self.events.get(start..end).unwrap_or(&[])
    }

    /// The blocks of the labels named `name` (several if it is defined
    /// more than once; none if it does not exist).
    fn labelled<'a>(&'a self, name: &'a str) -> impl Iterator<Item = u32> + 'a {
        let first = self
            .label_names
            .get(name)
            .map_or(u32::MAX, |&(first, _)| first);
        std::iter::successors(Some(first), |&at| self.label_next.get(at as usize).copied())
            .map_while(|at| self.labels.get(at as usize).copied())
    }

    /// The `repeat_section`s whose section ends at the label `name`.
    fn repeats_ending_at<'a>(
        &'a self,
        name: &'a str,
    ) -> impl Iterator<Item = (u32, &'d RepeatSection)> + 'a {
        let from = self.repeats.partition_point(|&(n, _, _)| n < name);
        self.repeats[from..]
            .iter()
            .take_while(move |&&(n, _, _)| n == name)
            .map(|&(_, block, section)| (block, section))
    }
}

/// The worklist iteration to the fixed point.
struct Solver<'g, 'd, 't> {
    graph: &'g Graph<'d>,
    table: &'t mut StateTable,
    /// The entry state of every block (`UNREACHED` or an id).
    entries: Vec<u32>,
    /// Blocks to (re)visit, lowest first, so straight-line code is walked
    /// in order and each block once.
    queue: BinaryHeap<Reverse<u32>>,
    queued: Vec<bool>,
    /// What `computed_jump`s bring to every label.
    computed: Option<u32>,
}

impl<'g, 'd, 't> Solver<'g, 'd, 't> {
    fn solve(graph: &'g Graph<'d>, table: &'t mut StateTable, initial: u32) -> Vec<u32> {
        let count = graph.block_count();
        let mut solver = Solver {
            graph,
            table,
            entries: vec![UNREACHED; count],
            queue: BinaryHeap::new(),
            queued: vec![false; count],
            computed: None,
        };
        solver.flow_into(0, initial);
        while let Some(Reverse(block)) = solver.queue.pop() {
            solver.queued[block as usize] = false;
            solver.visit(block);
        }
        solver.entries
    }

    fn entry(&self, block: u32) -> Option<u32> {
        self.entries
            .get(block as usize)
            .copied()
            .filter(|&id| id != UNREACHED)
    }

    /// Joins `state` into the entry of `block`, queueing it if that
    /// changed. Each entry rises at most 66 times (reached, then each
    /// group and the modal call unknown), which bounds the iteration.
    fn flow_into(&mut self, block: u32, state: u32) {
        let Some(&id) = self.entries.get(block as usize) else {
            return;
        };
        let joined = if id == UNREACHED {
            state
        } else {
            self.table.join(id, state)
        };
        if joined == id {
            return;
        }
        self.entries[block as usize] = joined;
        if !std::mem::replace(&mut self.queued[block as usize], true) {
            self.queue.push(Reverse(block));
        }
    }

    fn visit(&mut self, block: u32) {
        let graph = self.graph;
        let Some(entry) = self.entry(block) else {
            return;
        };
        let Some(info) = graph.blocks.get(block as usize) else {
            return;
        };
        if let Some(name) = info.label {
            self.section_ends_at(name, entry);
        }
        let mut state = entry;
        for event in graph.events(block as usize) {
            if event.code != LINE {
                state = self.table.step(state, event.code);
            }
        }
        let next = block + 1;
        match info.control {
            Control::Next => self.flow_into(next, state),
            Control::Stop => {}
            Control::Jump {
                target,
                conditional,
            } => {
                for to in graph.labelled(target) {
                    self.flow_into(to, state);
                }
                if conditional {
                    self.flow_into(next, state);
                }
            }
            Control::Computed { goes_on } => {
                self.computed_jump(state);
                if goes_on {
                    self.flow_into(next, state);
                }
            }
            Control::Start => {
                self.flow_into(0, state);
                self.flow_into(next, state);
            }
            Control::Repeat(section) => self.repeat(block, section, state),
        }
    }

    /// A `repeat_section` in the last instruction of `block`, reached in
    /// `state`.
    fn repeat(&mut self, block: u32, section: &'d RepeatSection, state: u32) {
        let graph = self.graph;
        let next = block + 1;
        let at_end: Vec<u32> = graph.labelled(&section.end).collect();
        if graph.labelled(&section.start).next().is_none() || at_end.is_empty() {
            // What runs instead is the executor's business.
            let mut unknown = ModalState::unknown();
            unknown.modal_call = CALL_UNKNOWN;
            let unknown = self.table.intern(&unknown);
            self.flow_into(next, unknown);
            return;
        }
        for to in graph.labelled(&section.start) {
            self.flow_into(to, state);
        }
        if !matches!(section.passes, Value::Const(p) if p >= 1.0) {
            // A computed count may be 0.
            self.flow_into(next, state);
        }
        // The end label may have been reached before this `repeat_section`
        // was: take what is already known there (`section_ends_at` does
        // the rest when it changes).
        for end in at_end {
            if let Some(at) = self.entry(end) {
                self.section_end(block, section, at);
            }
        }
    }

    /// The label `name` starts a block reached in `state`: the sections
    /// ending there return to after their `repeat_section`s.
    fn section_ends_at(&mut self, name: &str, state: u32) {
        let graph = self.graph;
        for (block, section) in graph.repeats_ending_at(name) {
            if self.entry(block).is_some() {
                self.section_end(block, section, state);
            }
        }
    }

    /// The section of the `repeat_section` ending `block` reaches its end
    /// in `state`.
    fn section_end(&mut self, block: u32, section: &'d RepeatSection, state: u32) {
        let graph = self.graph;
        if graph.labelled(&section.start).next().is_none() {
            return;
        }
        self.flow_into(block + 1, state);
        if !matches!(section.passes, Value::Const(p) if p == 1.0) {
            // The next pass starts where this one ended.
            for to in graph.labelled(&section.start) {
                self.flow_into(to, state);
            }
        }
    }

    /// A `computed_jump` reached in `state` may go to any label.
    fn computed_jump(&mut self, state: u32) {
        let computed = match self.computed {
            Some(computed) => self.table.join(computed, state),
            None => state,
        };
        if self.computed != Some(computed) {
            self.computed = Some(computed);
            let graph = self.graph;
            for &block in &graph.labels {
                self.flow_into(block, computed);
            }
        }
    }
}
