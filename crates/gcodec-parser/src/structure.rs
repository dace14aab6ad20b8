//! Pairs control-structure openers with their closers.
//!
//! The control runs structures interpretively and only finds a missing
//! `ENDIF` when it gets there; gcodec reports it up front, naming both the
//! opener and where the end was expected.

use gcodec_source::{Diagnostic, Span, codes};

use crate::ast::*;

/// SINUMERIK allows this many nested control structures per program level.
pub const CONTROL_NESTING_LIMIT: usize = 16;

struct Open {
    kind: StructureKind,
    index: usize,
    span: Span,
    /// The first call after the opener that misspells its closer.
    misspelt: Option<Span>,
}

/// The closers, for the help of a structure never closed.
const CLOSERS: [&str; 5] = ["ENDIF", "ENDWHILE", "ENDFOR", "ENDLOOP", "UNTIL"];

/// The closer a call by name misspells (`ENDIFF`, `ENDWHIL`), if any: such
/// a call leaves its structure unclosed, and the diagnostic names it.
/// Only names that begin like a closer are compared, so that reading a
/// plain line stays cheap.
pub(crate) fn near_closer(name: &str) -> Option<&'static str> {
    let begins_like_one = name
        .get(..2)
        .is_some_and(|b| b.eq_ignore_ascii_case("EN") || b.eq_ignore_ascii_case("UN"));
    begins_like_one
        .then(|| gcodec_source::nearest(name, CLOSERS))
        .flatten()
}

/// The closer a statement misspells: a call by a name near a closer.
fn misspelt_closer(kind: &StatementKind) -> Option<&'static str> {
    match kind {
        StatementKind::Call(call) => match &call.target {
            CallTarget::Name { name, .. } => near_closer(name),
            CallTarget::Number { .. } => None,
        },
        _ => None,
    }
}

/// True for the statements pairing must see: those that open, split or
/// close a control structure, and calls that misspell a closer.
pub(crate) fn is_paired_statement(kind: &StatementKind) -> bool {
    is_structure_statement(kind) || misspelt_closer(kind).is_some()
}

/// True for the statements that open, split or close a control structure.
fn is_structure_statement(kind: &StatementKind) -> bool {
    matches!(
        kind,
        StatementKind::If(_)
            | StatementKind::While(_)
            | StatementKind::For(_)
            | StatementKind::Loop
            | StatementKind::Repeat
            | StatementKind::Else
            | StatementKind::EndIf
            | StatementKind::EndWhile
            | StatementKind::EndFor
            | StatementKind::EndLoop
            | StatementKind::Until(_)
    )
}

/// Pairs the structures of `program` and sets every block's depth.
/// `structure_blocks` lists, in order, the indices of the blocks holding a
/// statement pairing must see (see [`is_paired_statement`]); the parser
/// collects them while parsing, in parallel, so this serial pass visits
/// only those blocks' statements.
pub(crate) fn pair(
    program: &mut Program,
    structure_blocks: &[u32],
    diagnostics: &mut Vec<Diagnostic>,
) {
    let mut pairing = Pairing::default();
    pairing.feed(&mut program.blocks, 0, structure_blocks, diagnostics);
    let (structures, unclosed) = pairing.finish();
    diagnostics.extend(unclosed);
    program.structures = structures;
}

/// Structure pairing fed with a program's blocks a run at a time, in
/// order (the streamed run parses a program in chunks): the same
/// structures, depths and diagnostics as pairing the whole program.
#[derive(Default)]
pub struct Pairing {
    stack: Vec<Open>,
    structures: Vec<ControlStructure>,
    /// The end of the last block with content so far, and of the last
    /// block: where an unclosed structure's end is expected.
    content_end: Option<Span>,
    last_end: Option<Span>,
}

impl Pairing {
    /// Pairs the structures of `blocks`, the blocks from index `first` on,
    /// and sets their depths. `structure_blocks` lists the absolute indices
    /// of those among them holding a structure statement, in order.
    pub fn feed(
        &mut self,
        blocks: &mut [Block],
        first: usize,
        structure_blocks: &[u32],
        diagnostics: &mut Vec<Diagnostic>,
    ) {
        let stack = &mut self.stack;
        let structures = &mut self.structures;
        let mut unvisited = 0;
        for &index in structure_blocks {
            let Some(bi) = (index as usize).checked_sub(first) else {
                continue;
            };
            let Some(before) = blocks.get_mut(unvisited..bi) else {
                continue;
            };
            for block in before {
                block.depth = stack.len() as u32;
            }
            unvisited = bi + 1;
            let index = index as usize;
            let block = &mut blocks[bi];
            let mut depth = stack.len();
            for st in &block.statements {
                let opens = match &st.kind {
                    StatementKind::If(_) => Some(StructureKind::If),
                    StatementKind::While(_) => Some(StructureKind::While),
                    StatementKind::For(_) => Some(StructureKind::For),
                    StatementKind::Loop => Some(StructureKind::Loop),
                    StatementKind::Repeat => Some(StructureKind::Repeat),
                    _ => None,
                };
                if let Some(kind) = opens {
                    structures.push(ControlStructure {
                        kind,
                        open: index as u32,
                        middle: None,
                        close: None,
                    });
                    stack.push(Open {
                        kind,
                        index: structures.len() - 1,
                        span: st.span,
                        misspelt: None,
                    });
                    if stack.len() == CONTROL_NESTING_LIMIT + 1 {
                        diagnostics.push(
                            Diagnostic::new(
                                codes::parse::DEEP_NESTING,
                                format!(
                                    "control structures nested more than {CONTROL_NESTING_LIMIT} deep"
                                ),
                            )
                            .with_label(st.span, "this structure is too deep for the control")
                            .with_help("SINUMERIK allows 16 nested control structures per program level; move inner parts into a subprogram"),
                        );
                    }
                    continue;
                }
                if let Some(closer) = misspelt_closer(&st.kind) {
                    let open = stack
                        .iter_mut()
                        .rev()
                        .find(|o| closer_word(o.kind) == closer);
                    if let Some(open) = open {
                        open.misspelt.get_or_insert(st.span);
                    }
                    continue;
                }
                let closes = match &st.kind {
                    StatementKind::EndIf => Some((StructureKind::If, "ENDIF")),
                    StatementKind::EndWhile => Some((StructureKind::While, "ENDWHILE")),
                    StatementKind::EndFor => Some((StructureKind::For, "ENDFOR")),
                    StatementKind::EndLoop => Some((StructureKind::Loop, "ENDLOOP")),
                    StatementKind::Until(_) => Some((StructureKind::Repeat, "UNTIL")),
                    _ => None,
                };
                if let StatementKind::Else = st.kind {
                    match stack.last() {
                        Some(top)
                            if top.kind == StructureKind::If
                                && structures[top.index].middle.is_none() =>
                        {
                            structures[top.index].middle = Some(index as u32);
                            depth = stack.len() - 1;
                        }
                        _ => diagnostics.push(
                            Diagnostic::new(
                                codes::parse::UNMATCHED_END,
                                "`ELSE` without an open `IF`",
                            )
                            .with_label(st.span, "no IF to belong to")
                            .with_help("ELSE stands between `IF cond` and `ENDIF`, once per IF"),
                        ),
                    }
                    continue;
                }
                let Some((kind, word)) = closes else { continue };
                match stack.iter().rposition(|o| o.kind == kind) {
                    Some(pos) => {
                        // Everything opened after the match is left unclosed.
                        for inner in stack.drain(pos + 1..).rev() {
                            diagnostics.push(unclosed(&inner, st.span, "before this"));
                        }
                        if let Some(open) = stack.pop() {
                            structures[open.index].close = Some(index as u32);
                        }
                        depth = depth.min(stack.len());
                    }
                    None => diagnostics.push(
                        Diagnostic::new(
                            codes::parse::UNMATCHED_END,
                            format!("`{word}` without an open `{}`", opener_word(kind)),
                        )
                        .with_label(st.span, "nothing to close")
                        .with_help(format!(
                            "remove it, or add the `{}` it should close",
                            opener_word(kind)
                        )),
                    ),
                }
            }
            block.depth = depth as u32;
        }
        for block in blocks.get_mut(unvisited..).unwrap_or_default() {
            block.depth = stack.len() as u32;
        }
        // The end is expected at the end of the last block that has content
        // (of the last block, if none has).
        let end = |b: &Block| Span::new(b.span.end, b.span.end);
        if let Some(block) = blocks.iter().rev().find(|b| !b.span.is_empty()) {
            self.content_end = Some(end(block));
        }
        if let Some(block) = blocks.last() {
            self.last_end = Some(end(block));
        }
    }

    /// The structures, and a diagnostic for each one never closed.
    pub fn finish(self) -> (Vec<ControlStructure>, Vec<Diagnostic>) {
        let eof = self.content_end.or(self.last_end).unwrap_or_default();
        let unclosed = self
            .stack
            .iter()
            .rev()
            .map(|open| unclosed(open, eof, "by the end of the program"))
            .collect();
        (self.structures, unclosed)
    }
}

fn opener_word(kind: StructureKind) -> &'static str {
    match kind {
        StructureKind::If => "IF",
        StructureKind::While => "WHILE",
        StructureKind::For => "FOR",
        StructureKind::Loop => "LOOP",
        StructureKind::Repeat => "REPEAT",
    }
}

fn closer_word(kind: StructureKind) -> &'static str {
    match kind {
        StructureKind::If => "ENDIF",
        StructureKind::While => "ENDWHILE",
        StructureKind::For => "ENDFOR",
        StructureKind::Loop => "ENDLOOP",
        StructureKind::Repeat => "UNTIL",
    }
}

fn unclosed(open: &Open, expected_at: Span, where_: &'static str) -> Diagnostic {
    let opener = opener_word(open.kind);
    let closer = closer_word(open.kind);
    let d = Diagnostic::new(
        codes::parse::UNCLOSED_STRUCTURE,
        format!("`{opener}` is never closed by `{closer}`"),
    )
    .with_label(open.span, format!("`{opener}` opened here"))
    .with_label(expected_at, format!("`{closer}` expected {where_}"));
    match open.misspelt {
        Some(at) => d
            .with_label(at, format!("did you mean `{closer}`?"))
            .with_help(format!(
                "this is read as a call of a subprogram, not as `{closer}`; write `{closer}`"
            )),
        None => d.with_help(format!(
            "add `{closer}` in a block of its own where the structure ends"
        )),
    }
}
