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

use std::collections::HashMap;

use gcodec_parser::ast::{
    Block, BlockNumber, GotoKind, JumpTarget, Program, StatementKind, StructureKind,
};

/// What a block is to the structures around it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Role {
    Open,
    Middle,
    Close,
}

/// The control-flow facts of a program, computed before lowering.
pub(crate) struct Flow {
    /// Per block: the structures it opens, splits or closes.
    roles: HashMap<usize, Vec<(usize, Role)>>,
    /// Per block: the names of the resolved jump targets it carries.
    targets: HashMap<usize, Vec<String>>,
    /// Blocks by label (upper case) and by block number, in order.
    labels: HashMap<String, Vec<usize>>,
    numbers: HashMap<u64, Vec<usize>>,
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

impl Flow {
    pub(crate) fn new(program: &Program) -> Self {
        let mut roles: HashMap<usize, Vec<(usize, Role)>> = HashMap::new();
        for (i, s) in program.structures.iter().enumerate() {
            roles
                .entry(s.open as usize)
                .or_default()
                .push((i, Role::Open));
            if let Some(m) = s.middle {
                roles.entry(m as usize).or_default().push((i, Role::Middle));
            }
            if let Some(c) = s.close {
                roles.entry(c as usize).or_default().push((i, Role::Close));
            }
        }
        // One walk over the statements finds every jump with a static
        // target.
        let jumps: Vec<(usize, GotoKind, &JumpTarget)> = program
            .blocks
            .iter()
            .enumerate()
            .flat_map(|(i, block)| jumps(block).map(move |(kind, target)| (i, kind, target)))
            .collect();
        // Only the block numbers some jump names are indexed: most blocks
        // of a program have a number, few are jumped to.
        let mut numbers: HashMap<u64, Vec<usize>> = jumps
            .iter()
            .filter_map(|(_, _, target)| match target {
                JumpTarget::BlockNumber { value, .. } => Some((*value, Vec::new())),
                _ => None,
            })
            .collect();
        let mut labels: HashMap<String, Vec<usize>> = HashMap::new();
        for (i, block) in program.blocks.iter().enumerate() {
            if let Some(label) = &block.label {
                labels
                    .entry(label.name.to_ascii_uppercase().to_string())
                    .or_default()
                    .push(i);
            }
            if let Some(BlockNumber { value, .. }) = &block.number {
                if let Some(blocks) = numbers.get_mut(value) {
                    blocks.push(i);
                }
            }
        }
        let mut flow = Self {
            roles,
            targets: HashMap::new(),
            labels,
            numbers,
        };
        // Every jump's target block carries its label.
        for (i, kind, target) in jumps {
            if let Some(to) = flow.search(i, kind, target) {
                let name = label_name(target, to);
                let names = flow.targets.entry(to).or_default();
                if !names.contains(&name) {
                    names.push(name);
                }
            }
        }
        flow
    }

    /// The structures block `index` opens, splits or closes.
    pub(crate) fn roles(&self, index: usize) -> &[(usize, Role)] {
        self.roles.get(&index).map_or(&[], Vec::as_slice)
    }

    /// The jump labels block `index` carries.
    pub(crate) fn targets(&self, index: usize) -> &[String] {
        self.targets.get(&index).map_or(&[], Vec::as_slice)
    }

    /// The labels defined more than once, with their blocks.
    pub(crate) fn duplicate_labels(&self) -> impl Iterator<Item = (&String, &Vec<usize>)> {
        self.labels.iter().filter(|(_, blocks)| blocks.len() > 1)
    }

    /// Resolves the jump `kind` to `target` from block `from`.
    pub(crate) fn resolve(&self, from: usize, kind: GotoKind, target: &JumpTarget) -> Resolved {
        match self.search(from, kind, target) {
            Some(to) => Resolved::Label(label_name(target, to)),
            None if matches!(target, JumpTarget::Expr(_)) => Resolved::Computed,
            None => Resolved::Missing(target_text(target)),
        }
    }

    /// The block a jump lands on, searching as the control does.
    fn search(&self, from: usize, kind: GotoKind, target: &JumpTarget) -> Option<usize> {
        let candidates = match target {
            JumpTarget::Label { name, .. } => {
                self.labels.get(name.to_ascii_uppercase().as_str())?
            }
            JumpTarget::BlockNumber { value, .. } => self.numbers.get(value)?,
            JumpTarget::Expr(_) => return None,
        };
        let forward = || candidates.iter().copied().find(|&b| b > from);
        let backward = || candidates.iter().rev().copied().find(|&b| b < from);
        match kind {
            GotoKind::GotoF => forward(),
            GotoKind::GotoB => backward(),
            GotoKind::Goto | GotoKind::GotoC => forward().or_else(backward),
            GotoKind::GotoS => None,
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
    format!("{keyword}@{open_line}.{part}")
}

/// The label of the jump target in block `to`: `LBL@12`, `N100@40`.
fn label_name(target: &JumpTarget, to: usize) -> String {
    format!("{}@{}", target_text(target), to + 1)
}

fn target_text(target: &JumpTarget) -> String {
    match target {
        JumpTarget::Label { name, .. } => name.to_ascii_uppercase().to_string(),
        JumpTarget::BlockNumber { value, .. } => format!("N{value}"),
        JumpTarget::Expr(_) => "<computed>".to_owned(),
    }
}

/// The jumps of a block with a static target.
fn jumps(block: &Block) -> impl Iterator<Item = (GotoKind, &JumpTarget)> {
    block.statements.iter().filter_map(|st| {
        let jump = match &st.kind {
            StatementKind::Goto(j) => j.as_ref(),
            StatementKind::IfGoto(g) => &g.jump,
            _ => return None,
        };
        Some((jump.goto, jump.target.as_ref()?))
    })
}
