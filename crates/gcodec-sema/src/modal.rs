//! The modal state at every block, as far as it is known before the program
//! runs: for each program line with instructions, the command of each of
//! the 64 G groups when the block starts, or "unknown" where the paths that
//! reach the block disagree or a call may have changed it.
//!
//! The analysis is a forward dataflow over the control flow of a lowered
//! AIL [`Document`]: instructions run in order, `label`s are join points,
//! `jump`, `computed_jump`, `goto_start` and `repeat_section` add edges and
//! `return`, `end` and `M2 M17 M30` end a path. At a join, a group keeps
//! its command only if every path agrees. Each group's value can only rise
//! from "not reached" to a command to "unknown", so the fixed point is
//! reached after at most 66 changes per join point; straight-line code is
//! walked once. See [`ModalStates::analyse`] for the rules.
//!
//! Memory: the state of a line is an id into a table of the distinct
//! states (straight-line code has few), 8 bytes per line with instructions;
//! a state is 65 bytes (one registry index per group, plus whether a modal
//! call is active).

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::fmt;

use gcodec_ail::{Document, Instruction, MClass, Op, RepeatSection, Value};
use gcodec_profile::Profile;

use crate::ggroups;

/// The number of G groups (reference §3.2).
pub const GROUP_COUNT: usize = 64;

/// The modal G commands after a reset, group `n` at `n - 1`: the registry's
/// defaults ([`ggroups::default_member`]), overridden by the profile's
/// `modal_defaults`; group 8 is the profile's `default_group8_offset` (the
/// selection lowering starts from for `work_offset`, seed 003) when that is
/// a Group 8 code. `None` for non-modal and unassigned groups.
pub fn reset_defaults(profile: &Profile) -> [Option<&'static str>; GROUP_COUNT] {
    let mut modal = [None; GROUP_COUNT];
    for (i, slot) in modal.iter_mut().enumerate() {
        *slot = ggroups::default_member(i as u8 + 1);
    }
    for (group, code) in &profile.modal_defaults {
        let lookup = ggroups::lookup(code.get_ref());
        if let (Ok(g), Some((found, index))) = (group.get_ref().parse::<u8>(), lookup) {
            if g == found {
                modal[usize::from(g) - 1] = ggroups::member(g, index);
            }
        }
    }
    // Lowering tracks the Group 8 selection from this setting, so the
    // `group8_selected` of its `work_offset` instructions agree with it.
    let group8 = profile.work_offsets.default_group8_offset.get_ref();
    if let Some(uifr) = gcodec_profile::group8_index(group8) {
        modal[7] = ggroups::member(8, uifr + 1);
    }
    modal
}

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
    /// The distinct states of reached lines.
    states: Vec<ModalState>,
    /// (line, index into `states` or `UNREACHED`), one per line with
    /// instructions, sorted by line.
    lines: Vec<(u32, u32)>,
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
        let entries = Solver::solve(&graph, initial);
        Self::collect(&graph, &entries)
    }

    /// Replays each reached basic block from its entry state and records
    /// the state at the first instruction of every line.
    fn collect(graph: &Graph<'_>, entries: &Entries) -> Self {
        let mut states = Interner::default();
        let mut lookups = Lookups::new();
        // Lowering gives every line with instructions a run of them, in
        // order, so the last line is about how many there are.
        let last_line = graph.instructions.last().map_or(0, |i| i.source.line);
        let mut lines: Vec<(u32, u32)> =
            Vec::with_capacity((last_line as usize).min(graph.instructions.len()));
        let mut previous_line = None;
        for block in 0..graph.block_count() {
            let entry = entries.state(block);
            let mut state = entry.cloned();
            // The id of `state` while it has not changed since interned.
            let mut id = None;
            for instruction in graph.block(block) {
                let line = instruction.source.line;
                if previous_line != Some(line) {
                    previous_line = Some(line);
                    let at = match &state {
                        Some(state) => *id.get_or_insert_with(|| states.intern(state)),
                        None => UNREACHED,
                    };
                    lines.push((line, at));
                }
                if let Some(state) = state.as_mut() {
                    if transfer(state, &instruction.op, &mut lookups) {
                        id = None;
                    }
                }
            }
        }
        // Lowering writes lines in order; another writer may not. The first
        // run of a line in document order is its block's start.
        if !lines.windows(2).all(|w| w[0].0 < w[1].0) {
            lines.sort_by_key(|&(line, _)| line);
            lines.dedup_by_key(|&mut (line, _)| line);
        }
        lines.shrink_to_fit();
        let mut states = states.states;
        states.shrink_to_fit();
        Self { states, lines }
    }

    /// What is known about `line` (1-based).
    pub fn line_state(&self, line: u32) -> LineState<'_> {
        let Ok(at) = self.lines.binary_search_by_key(&line, |&(l, _)| l) else {
            return LineState::NoInstructions;
        };
        match self.states.get(self.lines[at].1 as usize) {
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
        self.lines
            .iter()
            .filter_map(|&(line, at)| Some((line, self.states.get(at as usize)?)))
    }

    /// The lines with instructions that no path reaches, in order.
    pub fn unreachable_lines(&self) -> impl Iterator<Item = u32> + '_ {
        self.lines
            .iter()
            .filter(|&&(_, at)| at == UNREACHED)
            .map(|&(line, _)| line)
    }

    /// How many different states the reached lines have.
    pub fn distinct_states(&self) -> usize {
        self.states.len()
    }

    /// The heap memory the result holds, in bytes.
    pub fn heap_bytes(&self) -> usize {
        self.states.capacity() * std::mem::size_of::<ModalState>()
            + self.lines.capacity() * std::mem::size_of::<(u32, u32)>()
    }
}

/// Distinct states, each stored once, by dense id.
#[derive(Default)]
struct Interner {
    states: Vec<ModalState>,
    ids: HashMap<ModalState, u32>,
}

impl Interner {
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
}

/// How an instruction affects the control flow.
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

/// Every `Op` is listed so that a new kind does not slip through as
/// "no effect on the control flow".
fn control(op: &Op) -> Control<'_> {
    match op {
        Op::Jump { target, condition } => Control::Jump {
            target,
            conditional: condition.is_some(),
        },
        Op::ComputedJump(jump) => Control::Computed {
            goes_on: jump.condition.is_some() || jump.continue_if_missing,
        },
        Op::GotoStart { .. } => Control::Start,
        Op::RepeatSection(section) => Control::Repeat(section),
        Op::Return { .. } | Op::End => Control::Stop,
        Op::MFunction(m) => {
            // The program-flow class: the profile may not reclassify these
            // values (the extension is forbidden for them), but a machine
            // could map one to a custom function; then it does not end.
            let ends = m.class == MClass::ProgramFlow
                && m.address_extension.is_none()
                && m.address_extension_expr.is_none()
                && matches!(m.m_value, Some(2 | 17 | 30));
            if ends { Control::Stop } else { Control::Next }
        }
        Op::ToolSelect(_)
        | Op::ToolChange { .. }
        | Op::CuttingEdge { .. }
        | Op::WorkOffset { .. }
        | Op::ModalChange { .. }
        | Op::Motion { .. }
        | Op::Feed { .. }
        | Op::SpindleSpeed { .. }
        | Op::Dwell { .. }
        | Op::Address(_)
        | Op::HFunction(_)
        | Op::ModalChangeIndirect { .. }
        | Op::Frame { .. }
        | Op::Declare(_)
        | Op::Assign { .. }
        | Op::AssignList(_)
        | Op::Label { .. }
        | Op::Call(_)
        | Op::CancelModalCall
        | Op::Procedure(_)
        | Op::External(_)
        | Op::Message { .. }
        | Op::Stop { .. } => Control::Next,
    }
}

/// Whether `group` (1…64) keeps its command after its block.
fn is_modal_group(group: u8) -> bool {
    ggroups::group(group).is_some_and(|g| g.effect == ggroups::Effect::Modal)
}

/// The registry index of `code` if it is a member of `group`, else 0.
fn member_index(group: u8, code: &str) -> u8 {
    match ggroups::lookup(code) {
        Some((found, index)) if found == group => index,
        _ => 0,
    }
}

/// [`member_index`] behind a small direct-mapped cache keyed by the
/// string's address and length. Lowering writes the registry's own
/// `&'static str`s, so a document's codes are a few distinct strings and
/// the cache skips nearly every lookup (a third of the analysis' time
/// without it). Keying by address is sound while the document is borrowed:
/// two live strings at one address with one length are the same string.
struct Lookups {
    /// (address, length, group, index); length `usize::MAX` is empty.
    slots: Box<[(usize, usize, u8, u8); LOOKUP_SLOTS]>,
}

const LOOKUP_SLOTS: usize = 256;

impl Lookups {
    fn new() -> Self {
        Self {
            slots: Box::new([(0, usize::MAX, 0, 0); LOOKUP_SLOTS]),
        }
    }

    fn member_index(&mut self, group: u8, code: &str) -> u8 {
        let (address, len) = (code.as_ptr() as usize, code.len());
        let slot = &mut self.slots[(address ^ (address >> 8) ^ usize::from(group)) % LOOKUP_SLOTS];
        if (slot.0, slot.1, slot.2) == (address, len, group) {
            return slot.3;
        }
        let index = member_index(group, code);
        *slot = (address, len, group, index);
        index
    }
}

/// Applies one instruction to `state`; true if the state changed. Every
/// `Op` is listed so that a new kind is a compile error here.
fn transfer(state: &mut ModalState, op: &Op, lookups: &mut Lookups) -> bool {
    match op {
        Op::ModalChange { group, code } => {
            is_modal_group(*group) && state.set(*group, lookups.member_index(*group, code))
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
            is_modal_group(*group) && state.set(*group, index)
        }
        Op::WorkOffset {
            group8_selected,
            suppression,
            ..
        } => {
            // `null`: a suppression alone, the selection unknown to
            // lowering; a suppression never changes the selection.
            let Some(group8_selected) = group8_selected else {
                return false;
            };
            let selected = lookups.member_index(8, group8_selected);
            match suppression {
                None => state.set(8, selected),
                Some(_) if state.index(8) == Some(selected) => false,
                Some(_) => state.set(8, 0),
            }
        }
        Op::Call(call) if call.modal => state.set_modal_call(CALL_ACTIVE),
        Op::Call(_) => state.forget_groups(),
        Op::CancelModalCall => state.set_modal_call(CALL_INACTIVE),
        // A modal call runs after the block (or may: unknown).
        Op::Motion { .. } if state.modal_call != CALL_INACTIVE => state.forget_groups(),
        Op::Motion { .. }
        | Op::ToolSelect(_)
        | Op::ToolChange { .. }
        | Op::CuttingEdge { .. }
        | Op::MFunction(_)
        | Op::Feed { .. }
        | Op::SpindleSpeed { .. }
        | Op::Dwell { .. }
        | Op::Address(_)
        | Op::HFunction(_)
        | Op::Frame { .. }
        | Op::Declare(_)
        | Op::Assign { .. }
        | Op::AssignList(_)
        | Op::Label { .. }
        | Op::Jump { .. }
        | Op::RepeatSection(_)
        | Op::ComputedJump(_)
        | Op::GotoStart { .. }
        | Op::Procedure(_)
        | Op::External(_)
        | Op::Return { .. }
        | Op::Message { .. }
        | Op::Stop { .. }
        | Op::End => false,
    }
}

/// The document cut into basic blocks: a block starts at the first
/// instruction, at every label and after every instruction that does not
/// simply go on.
struct Graph<'d> {
    instructions: &'d [Instruction],
    /// The first instruction of each block.
    starts: Vec<u32>,
    /// (name, block) of every label, sorted by name.
    labels: Vec<(&'d str, u32)>,
    /// (end label, block ending in the `repeat_section`, the section),
    /// sorted by the end label.
    repeats: Vec<(&'d str, u32, &'d RepeatSection)>,
}

impl<'d> Graph<'d> {
    fn new(instructions: &'d [Instruction]) -> Self {
        let mut starts = Vec::new();
        let mut labels = Vec::new();
        let mut repeats = Vec::new();
        let mut starts_block = true;
        for (at, instruction) in instructions.iter().enumerate() {
            if starts_block || matches!(instruction.op, Op::Label { .. }) {
                starts.push(at as u32);
            }
            let block = starts.len() as u32 - 1;
            if let Op::Label { name } = &instruction.op {
                labels.push((name.as_str(), block));
            }
            let control = control(&instruction.op);
            if let Control::Repeat(section) = control {
                repeats.push((section.end.as_str(), block, section));
            }
            starts_block = !matches!(control, Control::Next);
        }
        labels.sort_unstable();
        repeats.sort_unstable_by_key(|&(end, block, _)| (end, block));
        Self {
            instructions,
            starts,
            labels,
            repeats,
        }
    }

    fn block_count(&self) -> usize {
        self.starts.len()
    }

    fn block(&self, block: usize) -> &'d [Instruction] {
        let start = self.starts[block] as usize;
        let end = self
            .starts
            .get(block + 1)
            .map_or(self.instructions.len(), |&s| s as usize);
        &self.instructions[start..end]
    }

    /// The blocks of the labels named `name` (several if it is defined
    /// more than once; none if it does not exist).
    fn labelled<'a>(&'a self, name: &'a str) -> impl Iterator<Item = u32> + 'a {
        let from = self.labels.partition_point(|&(n, _)| n < name);
        self.labels[from..]
            .iter()
            .take_while(move |&&(n, _)| n == name)
            .map(|&(_, block)| block)
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

/// The entry state of every basic block (`UNREACHED` or an interned id).
struct Entries {
    ids: Vec<u32>,
    interner: Interner,
}

impl Entries {
    fn state(&self, block: usize) -> Option<&ModalState> {
        self.interner.states.get(*self.ids.get(block)? as usize)
    }
}

/// The worklist iteration to the fixed point.
struct Solver<'g, 'd> {
    graph: &'g Graph<'d>,
    entries: Entries,
    /// Blocks to (re)visit, lowest first, so straight-line code is walked
    /// in order and each block once.
    queue: BinaryHeap<Reverse<u32>>,
    queued: Vec<bool>,
    /// What `computed_jump`s bring to every label.
    computed: Option<ModalState>,
    lookups: Lookups,
}

impl<'g, 'd> Solver<'g, 'd> {
    fn solve(graph: &'g Graph<'d>, initial: ModalState) -> Entries {
        let count = graph.block_count();
        let mut solver = Solver {
            graph,
            entries: Entries {
                ids: vec![UNREACHED; count],
                interner: Interner::default(),
            },
            queue: BinaryHeap::new(),
            queued: vec![false; count],
            computed: None,
            lookups: Lookups::new(),
        };
        solver.flow_into(0, &initial);
        while let Some(Reverse(block)) = solver.queue.pop() {
            solver.queued[block as usize] = false;
            solver.visit(block);
        }
        solver.entries
    }

    /// Joins `state` into the entry of `block`, queueing it if that
    /// changed. Each entry rises at most 66 times (reached, then each
    /// group and the modal call unknown), which bounds the iteration.
    fn flow_into(&mut self, block: u32, state: &ModalState) {
        let Some(&id) = self.entries.ids.get(block as usize) else {
            return;
        };
        let joined = if id == UNREACHED {
            state.clone()
        } else {
            let mut joined = self.entries.interner.states[id as usize].clone();
            if !joined.join(state) {
                return;
            }
            joined
        };
        self.entries.ids[block as usize] = self.entries.interner.intern(&joined);
        if !std::mem::replace(&mut self.queued[block as usize], true) {
            self.queue.push(Reverse(block));
        }
    }

    fn visit(&mut self, block: u32) {
        let graph = self.graph;
        let Some(entry) = self.entries.state(block as usize).cloned() else {
            return;
        };
        let instructions = graph.block(block as usize);
        let Some((last, _)) = instructions.split_last() else {
            return;
        };
        if let Some(Instruction {
            op: Op::Label { name },
            ..
        }) = instructions.first()
        {
            self.section_ends_at(name, &entry);
        }
        let mut state = entry;
        for instruction in instructions {
            transfer(&mut state, &instruction.op, &mut self.lookups);
        }
        let next = block + 1;
        match control(&last.op) {
            Control::Next => self.flow_into(next, &state),
            Control::Stop => {}
            Control::Jump {
                target,
                conditional,
            } => {
                for to in graph.labelled(target) {
                    self.flow_into(to, &state);
                }
                if conditional {
                    self.flow_into(next, &state);
                }
            }
            Control::Computed { goes_on } => {
                self.computed_jump(&state);
                if goes_on {
                    self.flow_into(next, &state);
                }
            }
            Control::Start => {
                self.flow_into(0, &state);
                self.flow_into(next, &state);
            }
            Control::Repeat(section) => self.repeat(block, section, &state),
        }
    }

    /// A `repeat_section` in the last instruction of `block`, reached in
    /// `state`.
    fn repeat(&mut self, block: u32, section: &'d RepeatSection, state: &ModalState) {
        let graph = self.graph;
        let next = block + 1;
        let at_end: Vec<u32> = graph.labelled(&section.end).collect();
        if graph.labelled(&section.start).next().is_none() || at_end.is_empty() {
            // What runs instead is the executor's business.
            let mut unknown = ModalState::unknown();
            unknown.modal_call = CALL_UNKNOWN;
            self.flow_into(next, &unknown);
            return;
        }
        let starts: Vec<u32> = graph.labelled(&section.start).collect();
        for &to in &starts {
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
            if let Some(at) = self.entries.state(end as usize).cloned() {
                self.section_end(block, section, &at);
            }
        }
    }

    /// The label `name` starts a block reached in `state`: the sections
    /// ending there return to after their `repeat_section`s.
    fn section_ends_at(&mut self, name: &str, state: &ModalState) {
        let graph = self.graph;
        for (block, section) in graph.repeats_ending_at(name) {
            if self.entries.ids[block as usize] != UNREACHED {
                self.section_end(block, section, state);
            }
        }
    }

    /// The section of the `repeat_section` ending `block` reaches its end
    /// in `state`.
    fn section_end(&mut self, block: u32, section: &'d RepeatSection, state: &ModalState) {
        let graph = self.graph;
        if graph.labelled(&section.start).next().is_none() {
            return;
        }
        self.flow_into(block + 1, state);
        if !matches!(section.passes, Value::Const(p) if p == 1.0) {
            // The next pass starts where this one ended.
            let starts: Vec<u32> = graph.labelled(&section.start).collect();
            for to in starts {
                self.flow_into(to, state);
            }
        }
    }

    /// A `computed_jump` reached in `state` may go to any label.
    fn computed_jump(&mut self, state: &ModalState) {
        let changed = match &mut self.computed {
            Some(computed) => computed.join(state),
            None => {
                self.computed = Some(state.clone());
                true
            }
        };
        if let (true, Some(computed)) = (changed, self.computed.clone()) {
            let graph = self.graph;
            for &(_, block) in &graph.labels {
                self.flow_into(block, &computed);
            }
        }
    }
}
