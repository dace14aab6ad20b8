//! The lint rules of `gcodec check`: findings about programs that lower
//! without an error but would surprise on the machine (a change M with no
//! tool selected, compensation left on at the end, code no path reaches).
//!
//! Lowering stays as it is: `gcodec lower` and `gcodec run` report what
//! the control would reject; the rules here are opinions about programs
//! the control accepts, asked for by `gcodec check` ([`lint`]). Each rule
//! is a module of its own with a code of the registry's `lint` area, which
//! says whether it looks at the program's text or at every path through
//! it ([`gcodec_source::codes::Scope`]):
//!
//! - the text, from the syntax tree and its resolved jumps
//!   ([`crate::flow`]): [`unused_label`], [`jump_into_structure`],
//!   [`duplicate_block_number`];
//! - every path, from the AIL's control-flow graph ([`graph`]) and the
//!   facts that may hold on some path to each instruction ([`facts`]):
//!   [`unreachable_code`], [`missing_program_end`],
//!   [`change_without_tool`], [`tool_without_edge`],
//!   [`compensation_left_active`], [`spindle_without_speed`],
//!   [`motion_without_feed`].
//!
//! Where a rule cannot know (a call that may set the feed, a computed
//! jump target that may reach any label), it assumes the program right:
//! a finding is something the program does on a path the rule can follow.

mod facts;
mod graph;

mod change_without_tool;
mod compensation_left_active;
mod duplicate_block_number;
mod jump_into_structure;
mod missing_program_end;
mod motion_without_feed;
mod spindle_without_speed;
mod tool_without_edge;
mod unreachable_code;
mod unused_label;

use gcodec_ail::{ByteRange, Document};
use gcodec_parser::ast::Program;
use gcodec_profile::Profile;
use gcodec_source::{Diagnostic, Diagnostics, MAX_KEPT_PER_FILE, Span};

use crate::ProgramKind;
use crate::flow::{Flow, FlowBuilder};

use facts::Facts;
use graph::Graph;

/// What the rules look at: the program as parsed and as lowered, how it
/// is started, and the machine.
pub(crate) struct Context<'a> {
    pub program: &'a Program,
    pub document: &'a Document,
    pub kind: ProgramKind,
    pub flow: Flow,
    pub graph: Graph,
    pub facts: Facts,
}

/// The findings of every lint rule on `program`, parsed and lowered to
/// `document`, started as `kind` on the machine `profile` describes, in
/// source order.
pub fn lint(
    program: &Program,
    document: &Document,
    kind: ProgramKind,
    profile: &Profile,
) -> Diagnostics {
    let mut builder = FlowBuilder::default();
    builder.reserve(program.blocks.len());
    for (index, block) in program.blocks.iter().enumerate() {
        builder.block(index, block);
    }
    let flow = builder.finish(&program.structures);
    let graph = Graph::of(document);
    let facts = Facts::of(document, &graph, kind, profile);
    let cx = Context {
        program,
        document,
        kind,
        flow,
        graph,
        facts,
    };
    let mut found = Findings::default();
    let rules: [fn(&Context<'_>, &mut Findings); 10] = [
        unused_label::check,
        jump_into_structure::check,
        duplicate_block_number::check,
        unreachable_code::check,
        missing_program_end::check,
        change_without_tool::check,
        tool_without_edge::check,
        compensation_left_active::check,
        spindle_without_speed::check,
        motion_without_feed::check,
    ];
    for rule in rules {
        rule(&cx, &mut found);
    }
    // `push` keeps every one: `Findings` already kept no more than a file
    // may.
    let mut diagnostics = found.omitted;
    for d in found.kept {
        diagnostics.push(d);
    }
    diagnostics.sort_by_start();
    diagnostics
}

/// What the rules find: kept up to the number a file may keep
/// ([`MAX_KEPT_PER_FILE`]), counted beyond, so that a program with a
/// finding in every block (block numbers that wrap round in a
/// million-block program) does not hold them all.
#[derive(Default)]
pub(crate) struct Findings {
    kept: Vec<Diagnostic>,
    omitted: Diagnostics,
}

impl Findings {
    pub(crate) fn push(&mut self, diagnostic: Diagnostic) {
        if self.kept.len() < MAX_KEPT_PER_FILE {
            self.kept.push(diagnostic);
        } else {
            self.omitted
                .count_omitted(diagnostic.code, diagnostic.severity);
        }
    }
}

/// The span of an instruction's source.
fn span(range: ByteRange) -> Span {
    Span::new(range.start, range.end)
}

impl Context<'_> {
    /// The span of instruction `at`.
    fn span_of(&self, at: usize) -> Span {
        span(self.document.instructions[at].source.span)
    }

    /// The span of the block instruction `at` comes from: its line.
    fn block_span_of(&self, at: usize) -> Span {
        let line = self.document.instructions[at].source.line as usize;
        self.program
            .blocks
            .get(line.wrapping_sub(1))
            .map_or_else(|| self.span_of(at), |b| b.span)
    }
}
