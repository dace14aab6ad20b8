//! The control-flow graph of an AIL document: where each instruction can
//! go next, and which instructions the program's start reaches.
//!
//! Over-approximated where the document cannot say: a computed jump may
//! reach any label, a `REPEAT` section goes back to after its `REPEAT`
//! from its end every time, a jump to a missing target goes on (the run
//! stops there with an alarm lowering already reports). Calls come back.

use gcodec_ail::{Document, Op};
use rustc_hash::FxHashMap;

/// Successors of every instruction: the next one where control can fall
/// through, plus the named targets.
pub(crate) struct Graph {
    falls_through: Vec<bool>,
    /// (from, to) for every edge that is not a fall-through, sorted.
    edges: Vec<(u32, u32)>,
    /// Per instruction, whether it has an edge in `edges` (most have
    /// none: no search for them).
    has_edges: Vec<bool>,
    /// Instructions the start of the program reaches.
    reached: Vec<bool>,
}

/// How an instruction ends the program or the run of a level.
pub(crate) fn ends_program(op: &Op) -> bool {
    match op {
        Op::End | Op::Return { .. } => true,
        Op::MFunction(m) => {
            m.address_extension.is_none()
                && m.address_extension_expr.is_none()
                && matches!(m.m_value, Some(2 | 17 | 30))
        }
        _ => false,
    }
}

impl Graph {
    pub(crate) fn of(document: &Document) -> Self {
        let labels: FxHashMap<&str, u32> = document
            .instructions
            .iter()
            .enumerate()
            .filter_map(|(at, i)| match &i.op {
                Op::Label { name } => Some((name.as_str(), at as u32)),
                _ => None,
            })
            .collect();
        let count = document.instructions.len();
        let mut falls_through = vec![true; count];
        let mut edges = Vec::new();
        let mut computed = Vec::new();
        let mut section_ends = Vec::new();
        for (at, op) in document.instructions.iter().map(|i| &i.op).enumerate() {
            let from = at as u32;
            let mut to = |name: &str| match labels.get(name) {
                Some(&target) => {
                    edges.push((from, target));
                    true
                }
                None => false,
            };
            match op {
                Op::Jump { target, condition } => {
                    // A missing target: the run stops with an alarm that
                    // lowering reports; the rules go on as if it fell
                    // through.
                    let found = to(target);
                    falls_through[at] = condition.is_some() || !found;
                }
                Op::SkipBlock { end, .. } => {
                    to(end);
                }
                Op::GotoStart { .. } => edges.push((from, 0)),
                Op::RepeatSection(section) => {
                    to(&section.start);
                    if let Some(&end) = labels.get(section.end.as_str()) {
                        section_ends.push((end, from + 1));
                    }
                }
                Op::ComputedJump(_) => computed.push(from),
                op if ends_program(op) => falls_through[at] = false,
                _ => {}
            }
        }
        for from in computed {
            edges.extend(labels.values().map(|&to| (from, to)));
        }
        edges.extend(section_ends);
        edges.sort_unstable();
        edges.dedup();
        let mut has_edges = vec![false; count];
        for &(from, _) in &edges {
            has_edges[from as usize] = true;
        }
        let mut graph = Graph {
            falls_through,
            edges,
            has_edges,
            reached: vec![false; count],
        };
        graph.reach();
        graph
    }

    /// The number of instructions.
    pub(crate) fn len(&self) -> usize {
        self.falls_through.len()
    }

    /// Where control can go after instruction `at`.
    pub(crate) fn successors(&self, at: usize) -> impl Iterator<Item = usize> + '_ {
        let next = (self.falls_through[at] && at + 1 < self.len()).then_some(at + 1);
        let from = at as u32;
        let first = if self.has_edges[at] {
            self.edges.partition_point(|&(f, _)| f < from)
        } else {
            self.edges.len()
        };
        let named = self.edges[first..]
            .iter()
            .take_while(move |&&(f, _)| f == from)
            .map(|&(_, to)| to as usize);
        next.into_iter().chain(named)
    }

    /// Whether control can fall through from `at` to the next instruction.
    pub(crate) fn falls_through(&self, at: usize) -> bool {
        self.falls_through[at]
    }

    /// Whether some path from the program's start reaches `at`.
    pub(crate) fn is_reached(&self, at: usize) -> bool {
        self.reached[at]
    }

    fn reach(&mut self) {
        if self.len() == 0 {
            return;
        }
        let mut stack = vec![0usize];
        let mut next = Vec::new();
        self.reached[0] = true;
        while let Some(at) = stack.pop() {
            next.clear();
            next.extend(self.successors(at));
            for &to in &next {
                if !self.reached[to] {
                    self.reached[to] = true;
                    stack.push(to);
                }
            }
        }
    }
}
