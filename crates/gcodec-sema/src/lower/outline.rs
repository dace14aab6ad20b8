//! What lowering reads about the whole program before its first block:
//! control flow (structures, jump targets, `REPEAT` sections), the names
//! of each section, the `PROC`/`EXTERN` signatures. It owns all of it, so
//! a program can be outlined chunk by chunk and its syntax trees dropped
//! (a streamed run, `crate::ChunkLowering`), or outlined whole.

use std::collections::HashMap;
use std::sync::Arc;

use gcodec_lang::MClass;
use gcodec_parser::ast::{self, Block, ControlStructure, StatementKind};
use gcodec_profile::Profile;
use gcodec_source::{Diagnostic, Diagnostics, SourceFile, Span, codes};
use rustc_hash::FxHashMap;

use crate::definitions::Definitions;
use crate::flow::{Flow, FlowBuilder};
use crate::{mfunc, values};

use super::{calls, variables};

/// The whole-program facts lowering reads, computed before the blocks.
pub struct Outline<'d> {
    pub(super) file: Arc<str>,
    pub(super) structures: Vec<ControlStructure>,
    /// The loop variable of each `FOR`, by the block that opens it: the
    /// `ENDFOR` block counts it up.
    pub(super) for_variables: FxHashMap<u32, gcodec_ail::Expr>,
    pub(super) flow: Flow,
    /// The names the program may use, by section (`variables.rs`).
    pub(super) names: variables::Names<'d>,
    /// The `PROC` and `EXTERN` signatures of the program, by name.
    pub(super) signatures: HashMap<String, calls::Signature>,
    /// `mcode_class_overrides` by M value.
    pub(super) m_overrides: HashMap<u32, MClass>,
    /// It starts in its caller's modal state (see [`OutlineBuilder`]).
    pub(super) subprogram: bool,
    /// Where the program's first statement is (`PROC` must be it).
    pub(super) first_statement: Option<Span>,
    /// The index, start and end of its last block (0s for a program
    /// without blocks): the program's end instruction sits there.
    pub(super) last_block: (usize, u32, u32),
    /// What outlining found wrong (names defined twice or too late) and
    /// advice on labels defined twice.
    diagnostics: Diagnostics,
}

impl Outline<'_> {
    /// Outlining's diagnostics: report them with the lowering's.
    pub fn diagnostics(&self) -> &Diagnostics {
        &self.diagnostics
    }

    /// The macros of the definitions, which the program's chunks are
    /// parsed with.
    pub fn macros(&self) -> &gcodec_parser::Macros {
        self.names.macros()
    }

    /// Whether the program starts in its caller's modal state: a
    /// [`ProgramKind::Subprogram`], or one opening with `PROC`.
    pub fn is_subprogram(&self) -> bool {
        self.subprogram
    }

    /// Where control can go back in the program, as spans of lines
    /// (first, last), sorted: a loop from its end to its start, a jump to
    /// a block at or before its own, a `REPEAT` section with its `REPEAT`.
    /// A run at line `l` comes back to a line before `l` only inside a
    /// span holding `l`, so a streamed run may forget the instructions
    /// before the first such span (or before `l`). `None` when control
    /// can go back anywhere: a computed jump target, a `CALL BLOCK`
    /// section of the program itself.
    pub fn returns(&self) -> Option<Vec<(u32, u32)>> {
        // Block `b` is line `b + 1`.
        let line = |b: usize| u32::try_from(b + 1).unwrap_or(u32::MAX);
        let returns = self.flow.returns()?;
        Some(returns.iter().map(|&(a, b)| (line(a), line(b))).collect())
    }
}

/// How a program starts: as the main program of a run or as one that a
/// running program calls.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgramKind {
    /// Started by the operator: it starts in the machine's reset state
    /// (the profile's modal defaults), unless it opens with `PROC`.
    Main,
    /// Called by another program: it starts in its caller's modal state,
    /// which lowering cannot know.
    Subprogram,
}

impl ProgramKind {
    /// What `gcodec lower FILE` assumes: a subprogram for an `.SPF` file,
    /// else a main program.
    pub fn of_file(file: &str) -> Self {
        let spf = std::path::Path::new(file)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("spf"));
        if spf { Self::Subprogram } else { Self::Main }
    }
}

/// Builds an [`Outline`] from a program's blocks, fed in order (their
/// depths set by the structure pairing), a run at a time.
pub struct OutlineBuilder<'d> {
    file: Arc<str>,
    kind: ProgramKind,
    m_overrides: HashMap<u32, MClass>,
    flow: FlowBuilder,
    names: variables::NameCollector<'d>,
    signatures: HashMap<String, calls::Signature>,
    for_variables: FxHashMap<u32, gcodec_ail::Expr>,
    /// The first statement of the program, once seen, and whether it is
    /// `PROC`.
    first_statement: Option<(Span, bool)>,
    last_block: (usize, u32, u32),
}

impl<'d> OutlineBuilder<'d> {
    /// An outline of the program in `file`, started as `kind`, for the
    /// machine `profile` describes, with the global names of
    /// `definitions`.
    pub fn new(
        file: &str,
        kind: ProgramKind,
        profile: &Profile,
        definitions: &'d Definitions,
    ) -> Self {
        Self {
            file: Arc::from(file),
            kind,
            m_overrides: mfunc::overrides(profile),
            flow: FlowBuilder::default(),
            names: variables::NameCollector::new(profile, definitions),
            signatures: HashMap::new(),
            for_variables: FxHashMap::default(),
            first_statement: None,
            last_block: (0, 0, 0),
        }
    }

    /// Makes room for what `blocks` more blocks may bring (most blocks
    /// have a number, which the outline keeps): fed a chunk at a time,
    /// the vectors would grow and be copied over and over.
    pub fn reserve(&mut self, blocks: usize) {
        self.flow.reserve(blocks);
    }

    /// Takes in the next blocks of the program, the first of them block
    /// `first` (0-based).
    pub fn feed(&mut self, first: usize, blocks: &[Block]) {
        for (offset, block) in blocks.iter().enumerate() {
            let index = first + offset;
            self.flow.block(index, block);
            self.names.block(block);
            if block.statements.is_empty() {
                continue;
            }
            self.first_statement.get_or_insert_with(|| {
                let first = &block.statements[0];
                (first.span, matches!(first.kind, StatementKind::Proc(_)))
            });
            for statement in &block.statements {
                calls::add_signature(statement, &mut self.signatures);
                // The loop variable of the block's first `FOR`.
                if let StatementKind::For(f) = &statement.kind {
                    self.for_variables
                        .entry(index as u32)
                        .or_insert_with(|| values::variable(&f.var));
                }
            }
        }
        if let Some(last) = blocks.last() {
            self.last_block = (first + blocks.len() - 1, last.span.start, last.span.end);
        }
    }

    /// The outline, given the program's paired `structures`.
    pub fn finish(self, structures: Vec<ControlStructure>) -> Outline<'d> {
        let flow = self.flow.finish(&structures);
        let (names, mut diagnostics) = self.names.finish();
        diagnostics.extend(duplicate_labels(&flow));
        let called = self.kind == ProgramKind::Subprogram;
        Outline {
            subprogram: called || self.first_statement.is_some_and(|(_, proc)| proc),
            first_statement: self.first_statement.map(|(span, _)| span),
            file: self.file,
            structures,
            for_variables: self.for_variables,
            flow,
            names,
            signatures: self.signatures,
            m_overrides: self.m_overrides,
            last_block: self.last_block,
            diagnostics,
        }
    }
}

/// The outline of a whole parsed program.
pub fn outline<'d>(
    program: &ast::Program,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &'d Definitions,
) -> Outline<'d> {
    let mut builder = OutlineBuilder::new(&program.file, kind, profile, definitions);
    builder.feed(0, &program.blocks);
    builder.finish(program.structures.clone())
}

/// The outline of the program in `file`, read chunk by chunk
/// on `workers` threads with each chunk's tree dropped after it (pass 1
/// of a streamed run), and the diagnostics of pairing its structures, in
/// source order (the outline's own are in [`Outline::diagnostics`]).
///
/// The chunks are skimmed ([`gcodec_parser::skim_chunk`]): most blocks
/// are not parsed, since none of what the outline reads is in them. So
/// the lexical and syntax diagnostics are not found here: pass 2
/// ([`super::stream::lower_chunks`]) gives them.
pub fn outline_chunks<'d>(
    file: &SourceFile,
    kind: ProgramKind,
    chunks: &[gcodec_stream::Chunk],
    workers: usize,
    profile: &Profile,
    definitions: &'d Definitions,
) -> (Outline<'d>, Vec<Diagnostic>) {
    let mut builder = OutlineBuilder::new(file.name(), kind, profile, definitions);
    builder.reserve(chunks.iter().map(|c| c.blocks).sum());
    let mut pairing = gcodec_parser::Pairing::default();
    let mut diagnostics = Vec::new();
    let (src, encoding) = (file.bytes(), file.encoding());
    let macros = definitions.macros();
    gcodec_parser::skim_chunks(src, encoding, chunks, workers, macros, |mut parsed| {
        pairing.feed(
            &mut parsed.blocks,
            parsed.first_block,
            &parsed.structure_blocks,
            &mut diagnostics,
        );
        builder.feed(parsed.first_block, &parsed.blocks);
    });
    let (structures, unclosed) = pairing.finish();
    diagnostics.extend(unclosed);
    diagnostics.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    (builder.finish(structures), diagnostics)
}

/// Labels defined twice: allowed (jumps find the nearest in their
/// direction), but rarely meant.
fn duplicate_labels(flow: &Flow) -> Vec<Diagnostic> {
    let mut duplicates: Vec<(&String, &Vec<usize>)> = flow.duplicate_labels().collect();
    duplicates.sort_by_key(|(_, blocks)| blocks[0]);
    let span = |b: usize| flow.label_span(b).unwrap_or_default();
    duplicates
        .into_iter()
        .map(|(name, blocks)| {
            // The control does not check this (reference §1.7): advice.
            let mut diagnostic = Diagnostic::new(
                codes::lower::DUPLICATE_LABEL,
                format!("label `{name}` is defined {} times", blocks.len()),
            )
            .with_label(span(blocks[0]), "first")
            .with_help("a jump goes to the nearest one in its search direction");
            for &b in &blocks[1..] {
                diagnostic = diagnostic.with_label(span(b), "again");
            }
            diagnostic
        })
        .collect()
}
