//! Control flow: structures become labels and conditional jumps, and
//! `GOTO…` targets are resolved as the control searches for them.
//!
//! The control finds jump targets at run time: `GOTOF` searches towards
//! the end of the program, `GOTOB` towards its start, `GOTO` and `GOTOC`
//! forward first, then backward; the nearest match wins (reference §8.1).
//! A program's text does not change while it runs, so the search gives the
//! same block every time and is done here, once. Every resolved target is
//! a [`gcodec_ail::Op::Label`] named `<target>@<line>`, unique in the
//! document; structure labels are `<KEYWORD>@<line of the opener>.<part>`.
//! `@` cannot occur in a label of the language, so no name clashes.
//!
//! `REPEAT` sections are found here too: their start as the control
//! searches it, their end label `SECTION@<line of the REPEAT>.end` after
//! the section's last block. A program with a computed jump target
//! (`GOTOF "LBL"<<I`) labels every block with a label or number, since
//! any of them may be the target.

use std::collections::HashMap;

use rustc_hash::FxHashMap;

use gcodec_ail::JumpSearch;
use gcodec_parser::ast::{
    Block, BlockNumber, CaseArm, ControlStructure, GotoKind, Jump, JumpTarget, LabelDef,
    RepeatSection, StatementKind, StructureKind,
};
use gcodec_source::Span;

/// What a block is to the structures around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Role {
    Open,
    Middle,
    Close,
}

/// The control-flow facts of a program, computed before lowering.
pub(crate) struct Flow {
    /// The blocks control flow touches (most blocks are not among them),
    /// by index, in order: lowering, going through the blocks in order,
    /// reads them with a cursor (`Lowering::block_flow`).
    blocks: Vec<(usize, BlockFlow)>,
    /// Blocks by label (upper case) and by block number, in order.
    labels: HashMap<String, Vec<usize>>,
    /// The span of each block's label, for diagnostics.
    label_spans: FxHashMap<usize, Span>,
    numbers: HashMap<u64, Vec<usize>>,
    /// Per `REPEAT` block: its section, or the target that is missing.
    sections: HashMap<usize, Result<Section, String>>,
    /// Where control can go back: see [`Flow::returns`].
    returns: Option<Vec<(usize, usize)>>,
    /// Every resolved jump and `REPEAT` section, as blocks: see
    /// [`Flow::edges`].
    edges: Vec<Edge>,
}

/// A place a block sends control to by name: a jump's target, or the first
/// or last block of the section a `REPEAT` runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Edge {
    pub(crate) from: usize,
    pub(crate) to: usize,
    /// True for a `GOTO…` (a `CASE` arm's too), false for a `REPEAT`.
    pub(crate) is_jump: bool,
}

/// What control flow says about one block.
#[derive(Default)]
pub(crate) struct BlockFlow {
    /// The structures it opens, splits or closes.
    pub(crate) roles: Vec<(usize, Role)>,
    /// The names of the resolved jump targets it carries.
    pub(crate) targets: Vec<String>,
    /// The labels of the `REPEAT` sections that end with it.
    pub(crate) section_ends: Vec<String>,
}

/// Where a jump target is searched from the jump's block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Search {
    Forward,
    Backward,
    ForwardThenBackward,
    /// `REPEATB` and the start of `REPEAT a b`: towards the program
    /// start first.
    BackwardThenForward,
}

impl Search {
    pub(crate) fn of(kind: GotoKind) -> Self {
        match kind {
            GotoKind::GotoF => Search::Forward,
            GotoKind::GotoB => Search::Backward,
            _ => Search::ForwardThenBackward,
        }
    }

    /// As the AIL writes it, for a search at run time.
    pub(crate) fn ail(self) -> JumpSearch {
        match self {
            Search::Forward => JumpSearch::Forward,
            Search::Backward => JumpSearch::Backward,
            _ => JumpSearch::ForwardThenBackward,
        }
    }
}

/// A `REPEAT` section: the labels before its first and after its last
/// instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Section {
    pub(crate) start: String,
    pub(crate) end: String,
}

/// A resolved jump: the label of the target block, or why there is none.
pub(crate) enum Resolved {
    Label(String),
    /// Not found in the search direction: the control stops with alarm
    /// 14080 when the jump runs (`GOTOC` continues instead).
    Missing(String),
    /// A computed target (`GOTOF "LBL"<<I`): searched when it runs.
    Computed,
}

/// Collects the control-flow facts of a program fed block by block in
/// order; [`FlowBuilder::finish`] resolves them into a [`Flow`].
#[derive(Default)]
pub(crate) struct FlowBuilder {
    jumps: Vec<(usize, Search, JumpTarget)>,
    repeats: Vec<(usize, RepeatSection)>,
    /// Blocks by label (upper case), in order, and each label's span.
    labels: HashMap<String, Vec<usize>>,
    label_spans: FxHashMap<usize, Span>,
    /// Every block number with its block, in order: which of them jumps
    /// name is known only at the end.
    numbers: Vec<(u64, u32)>,
    /// A `CALL BLOCK` section of the program itself: it may start at any
    /// block.
    calls_own_section: bool,
    /// The blocks with a `GOTOS`.
    restarts: Vec<usize>,
}

impl FlowBuilder {
    /// Makes room for the block numbers of `blocks` more blocks.
    pub(crate) fn reserve(&mut self, blocks: usize) {
        self.numbers.reserve(blocks);
    }

    /// Takes in block `index` of the program. Inlined, the rest apart:
    /// pass 1 hands it every block of a flood, most with neither
    /// statement nor label (skimmed), and entering the whole function
    /// cost more than that.
    #[inline]
    pub(crate) fn block(&mut self, index: usize, block: &Block) {
        if !block.statements.is_empty() {
            self.statements(index, block);
        }
        if let Some(label) = &block.label {
            self.label(index, label);
        }
        if let Some(BlockNumber { value, .. }) = &block.number {
            self.numbers.push((*value, index as u32));
        }
    }

    /// The jumps, repeats and calls of block `index`'s statements.
    #[inline(never)]
    fn statements(&mut self, index: usize, block: &Block) {
        for statement in block.statements.iter() {
            let (single, arms, default): (Option<&Jump>, &[CaseArm], Option<&Jump>) =
                match &statement.kind {
                    StatementKind::Goto(j) => (Some(j.as_ref()), &[], None),
                    StatementKind::IfGoto(g) => (Some(&g.jump), &[], None),
                    StatementKind::Case(c) => (None, &c.arms, c.default.as_ref()),
                    StatementKind::RepeatSection(r) => {
                        self.repeats.push((index, r.as_ref().clone()));
                        continue;
                    }
                    StatementKind::IndirectCall(call) => {
                        self.calls_own_section |= call.section.is_some() && call.program.is_none();
                        continue;
                    }
                    _ => continue,
                };
            let all = single.into_iter().chain(arms.iter().map(|arm| &arm.jump));
            for jump in all.chain(default) {
                match &jump.target {
                    Some(target) => self
                        .jumps
                        .push((index, Search::of(jump.goto), target.clone())),
                    // `GOTOS`: back to the program's start.
                    None => self.restarts.push(index),
                }
            }
        }
    }

    /// Block `index`'s label.
    #[inline(never)]
    fn label(&mut self, index: usize, label: &LabelDef) {
        self.labels
            .entry(label.name.to_ascii_uppercase().to_string())
            .or_default()
            .push(index);
        self.label_spans.insert(index, label.span);
    }

    /// The facts, given the program's paired `structures`.
    pub(crate) fn finish(self, structures: &[ControlStructure]) -> Flow {
        let mut blocks = Marks(Vec::with_capacity(structures.len() * 3));
        for (i, s) in structures.iter().enumerate() {
            let parts = [
                (Some(s.open), Role::Open),
                (s.middle, Role::Middle),
                (s.close, Role::Close),
            ];
            for (block, role) in parts {
                if let Some(block) = block {
                    blocks.0.push((block as usize, Mark::Role(i, role)));
                }
            }
        }
        let FlowBuilder {
            jumps,
            repeats,
            labels,
            label_spans,
            numbers: all_numbers,
            calls_own_section,
            restarts,
        } = self;
        // A label no block carries may be a STRING variable that names the
        // label (`GOTOF ZIEL`): searched when it runs, like an expression.
        let computed_jumps = jumps.iter().any(|(_, _, target)| match target {
            JumpTarget::Expr(_) => true,
            JumpTarget::Label { name, .. } => {
                !labels.contains_key(name.to_ascii_uppercase().as_str())
            }
            JumpTarget::BlockNumber { .. } => false,
        });
        // Only the block numbers some jump or section names are indexed:
        // most blocks of a program have a number, few are jumped to.
        let named = jumps.iter().map(|(_, _, t)| t).chain(
            repeats
                .iter()
                .flat_map(|(_, r)| std::iter::once(&r.start).chain(r.end.as_ref())),
        );
        let mut numbers: HashMap<u64, Vec<usize>> = named
            .filter_map(|target| match target {
                JumpTarget::BlockNumber { value, .. } => Some((*value, Vec::new())),
                _ => None,
            })
            .collect();
        for &(value, block) in &all_numbers {
            if let Some(blocks) = numbers.get_mut(&value) {
                blocks.push(block as usize);
            } else if computed_jumps {
                numbers.insert(value, vec![block as usize]);
            }
        }
        let mut flow = Flow {
            blocks: Vec::new(),
            labels,
            label_spans,
            numbers,
            sections: HashMap::new(),
            returns: None,
            edges: Vec::new(),
        };
        let mut returns: Vec<(usize, usize)> = structures
            .iter()
            .filter(|s| s.kind != StructureKind::If)
            .filter_map(|s| Some((s.open as usize, s.close? as usize)))
            .chain(restarts.iter().map(|&at| (0, at)))
            .collect();
        // Every jump's target block carries its label.
        for (i, kind, target) in &jumps {
            if let Some(to) = flow.search(*i, *kind, target) {
                flow.edges.push(Edge {
                    from: *i,
                    to,
                    is_jump: true,
                });
                blocks.0.push((to, Mark::Target(label_name(target, to))));
                if to <= *i {
                    returns.push((to, *i));
                }
            }
        }
        for (i, repeat) in &repeats {
            let section = flow.section(*i, repeat);
            if let Ok((start, end)) = &section {
                // The section's passes go back to its start, and back to
                // the `REPEAT` after them.
                returns.push(((*start).min(*i), (*end).max(*i)));
                for to in [*start, *end] {
                    flow.edges.push(Edge {
                        from: *i,
                        to,
                        is_jump: false,
                    });
                }
                let start_label = label_name(&repeat.start, *start);
                blocks.0.push((*start, Mark::Target(start_label)));
                blocks
                    .0
                    .push((*end, Mark::SectionEnd(section_end_label(*i))));
            }
            flow.sections.insert(
                *i,
                section.map(|(start, _)| Section {
                    start: label_name(&repeat.start, start),
                    end: section_end_label(*i),
                }),
            );
        }
        // A computed target can be any label or block number: each is
        // a label instruction for the executor's search.
        if computed_jumps {
            // In block order, a block's label before its number.
            let mut named: Vec<(usize, bool, String)> = flow
                .labels
                .iter()
                .flat_map(|(name, blocks)| {
                    blocks
                        .iter()
                        .map(move |&b| (b, false, line_label(name, b + 1, "")))
                })
                .chain(all_numbers.iter().map(|&(value, b)| {
                    (
                        b as usize,
                        true,
                        line_label(&number_text(value), b as usize + 1, ""),
                    )
                }))
                .collect();
            named.sort_by_key(|(block, is_number, _)| (*block, *is_number));
            blocks.0.extend(
                named
                    .into_iter()
                    .map(|(block, _, name)| (block, Mark::Target(name))),
            );
        }
        if !computed_jumps && !calls_own_section {
            returns.sort_unstable();
            flow.returns = Some(returns);
        }
        flow.blocks = blocks.by_block();
        flow
    }
}

/// What control flow says about blocks, one fact at a time, in the order
/// found; [`Marks::by_block`] gathers them per block. (A hash map from
/// block to [`BlockFlow`] cost a serial tenth of a second's pass 1 on the
/// 1,000,000-block benchmark.)
struct Marks(Vec<(usize, Mark)>);

enum Mark {
    Role(usize, Role),
    Target(String),
    SectionEnd(String),
}

impl Marks {
    /// The flow of each block with a mark, by block index; each block's
    /// facts in the order found, a target name once.
    fn by_block(self) -> Vec<(usize, BlockFlow)> {
        // Sorting (block, place found) is several times quicker than
        // moving the marks themselves, and keeps a block's facts in order.
        let mut order: Vec<(usize, u32)> = self
            .0
            .iter()
            .enumerate()
            .map(|(at, (block, _))| (*block, at as u32))
            .collect();
        order.sort_unstable();
        let mut blocks: Vec<(usize, BlockFlow)> = Vec::with_capacity(order.len());
        for (block, at) in order {
            if blocks.last().is_none_or(|(last, _)| *last != block) {
                blocks.push((block, BlockFlow::default()));
            }
            let (Some((_, flow)), Some((_, mark))) = (blocks.last_mut(), self.0.get(at as usize))
            else {
                continue;
            };
            match mark {
                Mark::Role(structure, role) => flow.roles.push((*structure, *role)),
                Mark::Target(name) => {
                    if !flow.targets.contains(name) {
                        flow.targets.push(name.clone());
                    }
                }
                Mark::SectionEnd(label) => flow.section_ends.push(label.clone()),
            }
        }
        blocks
    }
}

impl Flow {
    /// Every way control can go back in the program, as (first, last)
    /// block: a loop from its end to its start, a jump to a target at or
    /// before it, a `REPEAT` section and its `REPEAT`; sorted. A run that
    /// is past a block no span covering the run's block starts at or
    /// before it never comes back to it. `None` when the program can go
    /// back anywhere (a computed jump target, a `CALL BLOCK` section of
    /// the program itself).
    pub(crate) fn returns(&self) -> Option<&[(usize, usize)]> {
        self.returns.as_deref()
    }

    /// Every jump whose target is found and every `REPEAT` section's
    /// first and last block, in the order of the program.
    pub(crate) fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The blocks with a label, by label (upper case).
    pub(crate) fn labels(&self) -> &HashMap<String, Vec<usize>> {
        &self.labels
    }

    /// The span of the label of block `index`.
    pub(crate) fn label_span(&self, index: usize) -> Option<Span> {
        self.label_spans.get(&index).copied()
    }

    /// The first and last block of the section `REPEAT` in block `at`
    /// repeats (language reference §8.3; the search rules are gcodec's
    /// reading, SPEC §10.7): `REPEATB L` the block labelled `L`, searched
    /// backward first; `REPEAT A B` from `A` (backward first) to the next
    /// `B` from there; `REPEAT L` from `L` (backward) to the first
    /// `ENDLABEL` after it, or to the block before the `REPEAT`.
    fn section(&self, at: usize, repeat: &RepeatSection) -> Result<(usize, usize), String> {
        let start_search = if repeat.single_block || repeat.end.is_some() {
            Search::BackwardThenForward
        } else {
            Search::Backward
        };
        let start = self
            .search(at, start_search, &repeat.start)
            .ok_or_else(|| target_text(&repeat.start))?;
        if repeat.single_block {
            return Ok((start, start));
        }
        if let Some(end) = &repeat.end {
            // The end may be the start block itself.
            let end = self
                .search(start.wrapping_sub(1), Search::Forward, end)
                .filter(|&e| e >= start)
                .ok_or_else(|| target_text(end))?;
            return Ok((start, end));
        }
        let end = self
            .labels
            .get("ENDLABEL")
            .and_then(|blocks| blocks.iter().copied().find(|&b| b > start && b < at))
            .unwrap_or(at.saturating_sub(1).max(start));
        Ok((start, end))
    }

    /// The section of the `REPEAT` in block `at`, or the name of its
    /// missing target.
    pub(crate) fn repeat_section(&self, at: usize) -> Option<&Result<Section, String>> {
        self.sections.get(&at)
    }

    /// What control flow says about block `index`; `None` for most
    /// blocks.
    pub(crate) fn block(&self, index: usize) -> Option<&BlockFlow> {
        let at = self.blocks.partition_point(|(i, _)| *i < index);
        self.blocks
            .get(at)
            .filter(|(i, _)| *i == index)
            .map(|(_, f)| f)
    }

    /// What control flow says about the blocks it touches, by index, in
    /// order.
    pub(crate) fn blocks(&self) -> &[(usize, BlockFlow)] {
        &self.blocks
    }

    /// The structures block `index` opens, splits or closes.
    pub(crate) fn roles(&self, index: usize) -> &[(usize, Role)] {
        self.block(index).map_or(&[], |b| b.roles.as_slice())
    }

    /// The labels defined more than once, with their blocks.
    pub(crate) fn duplicate_labels(&self) -> impl Iterator<Item = (&String, &Vec<usize>)> {
        self.labels.iter().filter(|(_, blocks)| blocks.len() > 1)
    }

    /// Resolves a jump to `target` from block `from`.
    pub(crate) fn resolve(&self, from: usize, search: Search, target: &JumpTarget) -> Resolved {
        match self.search(from, search, target) {
            Some(to) => Resolved::Label(label_name(target, to)),
            None if matches!(target, JumpTarget::Expr(_)) => Resolved::Computed,
            None => Resolved::Missing(target_text(target)),
        }
    }

    /// The block a jump lands on, searching as the control does.
    fn search(&self, from: usize, search: Search, target: &JumpTarget) -> Option<usize> {
        let candidates = match target {
            JumpTarget::Label { name, .. } => {
                self.labels.get(name.to_ascii_uppercase().as_str())?
            }
            JumpTarget::BlockNumber { value, .. } => self.numbers.get(value)?,
            JumpTarget::Expr(_) => return None,
        };
        // `from` is `usize::MAX` for a search that includes block 0.
        let forward = || {
            candidates
                .iter()
                .copied()
                .find(|&b| from == usize::MAX || b > from)
        };
        let backward = || candidates.iter().rev().copied().find(|&b| b < from);
        match search {
            Search::Forward => forward(),
            Search::Backward => backward(),
            Search::ForwardThenBackward => forward().or_else(backward),
            Search::BackwardThenForward => backward().or_else(forward),
        }
    }
}

/// The label of a structure part: `IF@12.else`.
pub(crate) fn structure_label(kind: StructureKind, open_line: usize, part: &str) -> String {
    let keyword = match kind {
        StructureKind::If => "IF",
        StructureKind::While => "WHILE",
        StructureKind::For => "FOR",
        StructureKind::Loop => "LOOP",
        StructureKind::Repeat => "REPEAT",
    };
    line_label(keyword, open_line, part)
}

/// `{name}@{line}`, then `.{part}` unless `part` is empty. Built by hand:
/// lowering names a label or a jump for every structure part, and
/// `format!` cost more than the rest of such a block.
pub(crate) fn line_label(name: &str, line: usize, part: &str) -> String {
    let mut label = String::with_capacity(name.len() + part.len() + 12);
    label.push_str(name);
    push_line(&mut label, line, part);
    label
}

/// `@{line}`, then `.{part}` unless `part` is empty.
fn push_line(label: &mut String, line: usize, part: &str) {
    label.push('@');
    label.push_str(itoa::Buffer::new().format(line));
    if !part.is_empty() {
        label.push('.');
        label.push_str(part);
    }
}

/// The label of the jump target in block `to`: `LBL@12`, `N100@40`.
fn label_name(target: &JumpTarget, to: usize) -> String {
    let mut label = target_text(target);
    push_line(&mut label, to + 1, "");
    label
}

fn target_text(target: &JumpTarget) -> String {
    match target {
        JumpTarget::Label { name, .. } => name.to_ascii_uppercase().to_string(),
        JumpTarget::BlockNumber { value, .. } => number_text(*value),
        JumpTarget::Expr(_) => "<computed>".to_owned(),
    }
}

/// `N{value}`.
pub(crate) fn number_text(value: u64) -> String {
    let mut digits = itoa::Buffer::new();
    let digits = digits.format(value);
    // Room for the `@{line}` a label adds.
    let mut text = String::with_capacity(digits.len() + 13);
    text.push('N');
    text.push_str(digits);
    text
}

/// The label after the last block of the section of the `REPEAT` in
/// block `at`.
fn section_end_label(at: usize) -> String {
    line_label("SECTION", at + 1, "end")
}
