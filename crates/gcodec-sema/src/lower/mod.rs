//! Lowers a parsed program block by block into AIL, checking each word
//! against the machine profile and tracking the modal state of
//! straight-line code.
//!
//! Within a block, instructions come in the order the control acts on them:
//! work offset and other modal G commands (indirect ones last), feed, spindle
//! speed, tool selection and cutting edge (then `DL`), M functions acting
//! before the motion, `H` functions, declarations and assignments, named
//! addresses (`address`), the dwell, the motion, then `M0 M1 M2 M17 M30` after
//! it (the M-function design). A skipped block (`/`, `/0`…`/9`) has its
//! `skip_block` test after its labels and its `SKIP@<line>.end` label after all
//! of it, before the end of a `REPEAT` section it closes.

use std::borrow::Cow;
use std::sync::Arc;

use gcodec_ail::{
    AxisValue, ByteRange, Circle, Document, Instruction, MTiming, Op, Source, Suppression,
    SuppressionScope, ToolChangeTrigger, Value,
};
use gcodec_lang::addresses::{NamedAddress, letter_str};
use gcodec_lang::ggroups::{self, GCommand};
use gcodec_lang::mfunctions::acts_after_motion;
use gcodec_lang::motion::MOTION_GROUP;
use gcodec_lang::{MotionKind, WorkOffsetCode};
use gcodec_parser::ast::{self, Block, GotoKind, Program};
use gcodec_profile::{DuplicateSuppressionPolicy, Profile};
use gcodec_source::{Diagnostic, Diagnostics, Severity, Span, codes};

use crate::definitions::Definitions;
use crate::flow::BlockFlow;
use crate::mfunc;
use outline::{Outline, ProgramKind};
use parts::{Entry, OpenEntry};

mod addresses;
mod axis_commands;
mod calls;
mod constant_words;
mod control;
mod frames;
mod interrupts;
pub(crate) mod outline;
mod parts;
mod statements;
pub(crate) mod stream;
mod variables;
mod words;

/// The result of lowering: always a document, plus what was wrong.
#[derive(Clone, Debug)]
pub struct Lowered {
    pub document: Document,
    pub diagnostics: Diagnostics,
}

impl Lowered {
    /// True if any diagnostic, kept or not, is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.has_errors()
    }
}

/// Lowers `program` for the machine `profile` describes, without global
/// user data ([`lower_with`]).
pub fn lower(program: &Program, profile: &Profile) -> Lowered {
    lower_with(program, profile, &Definitions::new())
}

/// Lowers `program` for the machine `profile` describes; the program may
/// use the global variables and macros of `definitions`. It is started as
/// its file name says ([`ProgramKind::of_file`]); [`lower_program`] takes
/// the kind.
pub fn lower_with(program: &Program, profile: &Profile, definitions: &Definitions) -> Lowered {
    lower_program(
        program,
        ProgramKind::of_file(&program.file),
        profile,
        definitions,
    )
}

/// Lowers `program`, started as `kind`, for the machine `profile`
/// describes, with the global variables and macros of `definitions`.
pub fn lower_program(
    program: &Program,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
) -> Lowered {
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    // Below this, a thread costs more than it saves.
    const BLOCKS_PER_PART: usize = 50_000;
    let parts = (program.blocks.len() / BLOCKS_PER_PART).clamp(1, threads);
    let outline = outline::outline(program, kind, profile, definitions);
    lower_outlined(program, profile, &outline, parts, true)
}

/// [`lower_with`], the blocks split into `parts` runs lowered on threads of
/// their own. The result is the same for every `parts` (a test checks);
/// public for that test only.
#[doc(hidden)]
pub fn lower_in_parts(
    program: &Program,
    profile: &Profile,
    definitions: &Definitions,
    parts: usize,
) -> Lowered {
    let kind = ProgramKind::of_file(&program.file);
    let outline = outline::outline(program, kind, profile, definitions);
    lower_outlined(program, profile, &outline, parts, true)
}

/// [`lower_with`] in one part, every block by the general path: the
/// reference the direct lowering of constant-word blocks is tested
/// against (`constant_words.rs`). Public for that test only.
#[doc(hidden)]
pub fn lower_by_the_general_path(
    program: &Program,
    profile: &Profile,
    definitions: &Definitions,
) -> Lowered {
    let kind = ProgramKind::of_file(&program.file);
    let outline = outline::outline(program, kind, profile, definitions);
    lower_outlined(program, profile, &outline, 1, false)
}

/// [`lower_in_parts`] with the program's `outline` built; `direct`:
/// whether blocks of constant words are lowered directly.
fn lower_outlined(
    program: &Program,
    profile: &Profile,
    outline: &Outline<'_>,
    parts: usize,
    direct: bool,
) -> Lowered {
    let mut diagnostics = outline.diagnostics().clone();
    let subprogram = outline.subprogram;
    let blocks = program.blocks.len();
    let parts = parts.clamp(1, blocks.max(1));
    let ranges: Vec<std::ops::Range<usize>> = (0..parts)
        .map(|k| blocks * k / parts..blocks * (k + 1) / parts)
        .collect();
    // Reserving avoids copying a large vector (`capacity`). The first
    // part reserves for all, since the others are appended to it.
    let statements: Vec<usize> = ranges
        .iter()
        .map(|r| {
            program.blocks[r.clone()]
                .iter()
                .map(|b| b.statements.len())
                .sum()
        })
        .collect();
    let total: usize = statements.iter().sum();
    let lower_part = |k: usize, range: std::ops::Range<usize>| {
        let reserve = if k == 0 { total } else { statements[k] };
        let entry = if k == 0 {
            Entry::ProgramStart
        } else {
            Entry::AfterOpenPart
        };
        let mut lowering = Lowering::new(outline, profile, program.source.bytes(), reserve, entry);
        lowering.direct_constant_words = direct;
        for index in range {
            lowering.block(index, &program.blocks[index]);
        }
        lowering
    };
    let mut lowered: Vec<Lowering> = if parts == 1 {
        vec![lower_part(0, ranges[0].clone())]
    } else {
        std::thread::scope(|scope| {
            let handles: Vec<_> = ranges
                .iter()
                .enumerate()
                .skip(1)
                .map(|(k, range)| {
                    let range = range.clone();
                    scope.spawn(move || lower_part(k, range))
                })
                .collect();
            let mut all = vec![lower_part(0, ranges[0].clone())];
            // A part that panicked is lowered again on this thread, where
            // the panic then surfaces as it would without threads.
            for (k, handle) in handles.into_iter().enumerate() {
                all.push(
                    handle
                        .join()
                        .unwrap_or_else(|_| lower_part(k + 1, ranges[k + 1].clone())),
                );
            }
            all
        })
    };
    if !parts::settle_parts(&mut lowered) {
        // A case the ledger cannot fill in (a modal call in
        // force across a boundary, an inherited thread or OEM command):
        // lower in one run.
        return lower_outlined(program, profile, outline, 1, direct);
    }
    let mut parts = lowered.into_iter();
    let Some(mut first) = parts.next() else {
        // `parts` is at least 1, so this does not happen.
        return Lowered {
            document: Document::new(),
            diagnostics,
        };
    };
    for part in parts {
        let mut instructions = part.document.instructions;
        first.document.instructions.append(&mut instructions);
        first.diagnostics.append(part.diagnostics);
    }
    first.end();
    let mut document = first.document;
    diagnostics.append(first.diagnostics);
    resolve_from_dataflow(&mut document, profile, subprogram);
    Lowered {
        document,
        diagnostics,
    }
}

/// Gives a motion whose command was open the command `kind`, moving its
/// `I J K` to where that command reads them: an arc's circle data, a
/// thread's lead (each empty where the block has none, as lowering under
/// a known command gives them).
fn assign_motion_command(
    motion: &mut MotionKind,
    circle: &mut Option<Box<gcodec_ail::Circle>>,
    details: &mut Option<Box<gcodec_ail::MotionDetails>>,
    kind: MotionKind,
) {
    *motion = kind;
    if is_threaded(kind) {
        details.get_or_insert_default().thread = Some(gcodec_ail::Thread {
            lead: circle.take().map(|c| c.centre).unwrap_or_default(),
            lead_change: None,
        });
    } else if is_arc(kind) {
        circle.get_or_insert_default();
    } else {
        *circle = None;
    }
}

/// Motions with circle data.
fn is_arc(kind: MotionKind) -> bool {
    matches!(
        kind,
        MotionKind::ArcCw
            | MotionKind::ArcCcw
            | MotionKind::ArcThroughPoint
            | MotionKind::ArcTangential
            | MotionKind::InvoluteCw
            | MotionKind::InvoluteCcw
    )
}

/// Motions whose `I J K` are the thread lead.
fn is_threaded(kind: MotionKind) -> bool {
    matches!(
        kind,
        MotionKind::Thread
            | MotionKind::ThreadIncreasingLead
            | MotionKind::ThreadDecreasingLead
            | MotionKind::Tapping
            | MotionKind::TappingRetract
            | MotionKind::ThreadConvexCw
            | MotionKind::ThreadConvexCcw
    )
}

/// Fills in what lowering left to run time because paths meet
/// (`motion: modal`, `group8_selected: null`) where the dataflow over the
/// whole document ([`crate::modal`]) shows every path agrees. Straight-line
/// programs have nothing to fill in and skip the analysis.
#[doc(hidden)]
pub fn resolve_from_dataflow(document: &mut Document, profile: &Profile, subprogram: bool) {
    let open = |op: &Op| match op {
        Op::Motion { motion, .. } => *motion == MotionKind::Modal,
        Op::WorkOffset {
            group8_selected, ..
        } => group8_selected.is_none(),
        _ => false,
    };
    if !document.instructions.iter().any(|i| open(&i.op)) {
        return;
    }
    let start = if subprogram {
        crate::modal::Start::Unknown
    } else {
        crate::modal::Start::Reset(profile)
    };
    let states = crate::modal::ModalStates::analyse(document, start);
    for instruction in &mut document.instructions {
        if !open(&instruction.op) {
            continue;
        }
        // The block programs no command of its own for the group in
        // question (else lowering would know it): its state at the start
        // is the one the instruction runs in.
        let Some(state) = states.state_at_line(instruction.source.line) else {
            continue;
        };
        match &mut instruction.op {
            Op::Motion {
                motion,
                circle,
                details,
                ..
            } => {
                if let Some(kind) = state
                    .index(MOTION_GROUP)
                    .and_then(|index| MotionKind::of_command(MOTION_GROUP, index))
                {
                    assign_motion_command(motion, circle, details, kind);
                }
            }
            Op::WorkOffset {
                group8_selected, ..
            } => *group8_selected = state.get(8).and_then(WorkOffsetCode::parse),
            _ => {}
        }
    }
}

/// The warning for a construct lowering does not translate yet: it is
/// named, never dropped in silence.
pub(crate) fn not_lowered(span: Span, what: &str) -> Diagnostic {
    Diagnostic::new(
        codes::lower::NOT_LOWERED,
        format!("{what} is not lowered yet"),
    )
    .with_label(span, "left out of the instruction list")
    .with_help("gcodec does not translate this construct yet; the program cannot be run as written")
}

/// The motion of a group 1 command as the registry spells it (`G1`,
/// `CIP`); `None` for another command.
fn motion_of(code: &str) -> Option<MotionKind> {
    ggroups::lookup(code).and_then(|(group, index)| MotionKind::of_command(group, index))
}

/// An address as an AIL axis name: single letters without allocating.
fn axis_name(address: &str) -> Cow<'static, str> {
    match address.as_bytes() {
        [b @ b'A'..=b'Z'] => Cow::Borrowed(letter_str(*b)),
        _ => Cow::Owned(address.to_owned()),
    }
}

/// Where a jump searches, for messages.
fn direction(kind: GotoKind) -> &'static str {
    match kind {
        GotoKind::GotoF => "forward (towards the program end)",
        GotoKind::GotoB => "backward (towards the program start)",
        _ => "forward or backward",
    }
}

/// Room for the instructions of about `statements` statements: about one
/// instruction per statement, plus labels, jumps and modal changes.
fn capacity(statements: usize) -> usize {
    statements * 5 / 4 + 16
}

/// The state carried from block to block.
struct Lowering<'a> {
    outline: &'a Outline<'a>,
    profile: &'a Profile,
    /// The program's text, to name values as written ([`crate::values::written`]).
    source: &'a [u8],
    /// The file name every instruction's source holds: a copy of the
    /// outline's per lowering, and per chunk in a streamed run
    /// ([`stream::ChunkLowering`]). The run drops a chunk's instructions
    /// on another thread, and counting references to one shared name
    /// from several threads at once cost more than lowering the
    /// instructions.
    file: Arc<str>,
    /// Where the block being lowered starts (columns count from there).
    block_start: u32,
    document: Document,
    /// Bounded per block ([`Diagnostics::begin_block`]).
    diagnostics: Diagnostics,
    /// Modal code of each G group (index = group − 1) as far as the
    /// program text tells: group 1 is `None` where paths with different
    /// motion commands meet (see [`Self::forget_modal_state`]).
    modal: [Option<&'static str>; 64],
    /// The Group 8 selection (index per `$P_UIFR`), `None` where unknown.
    group8: Option<u8>,
    /// `MCALL NAME` is in force: the subprogram runs after every motion.
    modal_call: bool,
    /// What reads the state a part started in where that is not known
    /// yet, for the [`parts::PartLedger`].
    open: OpenEntry,
    /// The Group 8 indices the machine has.
    group8_supported: [bool; 100],
    /// The plan of the block before, emptied ([`BlockPlan::reset`]): one
    /// plan serves every block, so that its room is reused and the large
    /// struct is not built and moved per block.
    plan: Option<Box<BlockPlan>>,
    /// Where in the flow facts (`Flow::blocks`) the next block's are, at
    /// the earliest: blocks are lowered in order.
    flow_at: usize,
    /// Blocks of constant words for a straight motion are lowered
    /// directly ([`Self::constant_word_block`]); off only to test that
    /// path against the general one.
    direct_constant_words: bool,
    /// `G0` and `G1` with their names where the machine has them under
    /// those names ([`Self::straight_motion_command`]), looked up once
    /// rather than for every block that writes one.
    straight_commands: [Option<(GCommand, &'static str)>; 2],
}

/// An `S` word: spindle number, computed spindle number (`S[SPINU]=`),
/// speed, span.
type SpindleWord = (Option<u32>, Option<Box<gcodec_ail::Expr>>, Value, Span);

/// A named address as written: address, axis, spindle.
type AddressKey = (NamedAddress, Option<String>, Option<u32>);

/// A `skip_block` emitted before a block's instructions, waiting for its
/// end label.
struct OpenSkip {
    /// The index of the `skip_block` instruction.
    at: usize,
    /// The skip mark.
    span: Span,
    /// Whether a modal call was in force before the block.
    modal_call: bool,
}

/// The label after the instructions of the skipped block `index`:
/// `SKIP@<line>.end`, like the other labels lowering makes up (`@` and `.`
/// keep it apart from the program's own labels, `SKIP@12` for `SKIP:`).
fn skip_label(index: usize) -> String {
    crate::flow::line_label("SKIP", index + 1, "end")
}

/// What one block says, collected before instructions are emitted.
#[derive(Default)]
struct BlockPlan {
    g_codes: Vec<(GCommand, Span)>,
    suppressions: Vec<(Suppression, Span)>,
    feed: Option<(Value, Span)>,
    spindle: Vec<SpindleWord>,
    tools: Vec<(Op, Span)>,
    edge: Option<(Value, Span)>,
    m_functions: Vec<mfunc::MWord>,
    targets: Vec<AxisValue>,
    /// Where the first target is written.
    target_span: Option<Span>,
    circle: Circle,
    circle_span: Option<Span>,
    other: Vec<(Op, Span)>,
    /// Subprogram and cycle calls: they run after the block's motion.
    calls: Vec<(Op, Span)>,
    /// Labels and jumps that act when the block is entered, before
    /// anything else in it.
    head: Vec<(Op, Span)>,
    /// Jumps and labels that act after everything else in the block.
    tail: Vec<(Op, Span)>,
    /// `G[8]=KORD`: group, computed index, span.
    indirect_g: Vec<(u8, Value, Span)>,
    /// `H` functions, output with the M functions acting in the block.
    h_functions: Vec<(Op, Span)>,
    /// `DL=`: after the cutting edge.
    after_edge: Vec<(Op, Span)>,
    /// Named addresses (`address` instructions), just before the motion.
    addresses: Vec<(Op, Span)>,
    /// Address, axis, extension of the addresses written, to find
    /// repetitions.
    address_keys: Vec<(AddressKey, Span)>,
    /// `AX[_Z]=…`: targets whose axis is named when the block runs.
    indirect_targets: Vec<gcodec_ail::IndirectAxisValue>,
    /// Where the first indirect target is written.
    motion_span: Option<Span>,
    /// `PW=`, `PL=`.
    spline: gcodec_ail::SplineData,
    spline_span: Option<Span>,
    /// `CHF=`, `CHR=`, `RND=`.
    transition: Option<(gcodec_ail::Transition, Span)>,
    /// Axes written a second time in the block, where (alarm 12010).
    repeated_axes: Vec<(Cow<'static, str>, Span)>,
    /// `X1=0`: machine axes, which only `G74`/`G75` name.
    machine_axis_words: Vec<axis_commands::MachineAxisWord>,
}

impl BlockPlan {
    /// Empties the plan for the next block, field by field: the vectors
    /// keep their room, and the large struct is not built anew.
    fn reset(&mut self) {
        // Every field is named, so that a new one cannot be forgotten.
        let Self {
            g_codes,
            suppressions,
            feed,
            spindle,
            tools,
            edge,
            m_functions,
            targets,
            target_span,
            circle,
            circle_span,
            other,
            calls,
            head,
            tail,
            indirect_g,
            h_functions,
            after_edge,
            addresses,
            address_keys,
            indirect_targets,
            motion_span,
            spline,
            spline_span,
            transition,
            repeated_axes,
            machine_axis_words,
        } = self;
        g_codes.clear();
        suppressions.clear();
        *feed = None;
        spindle.clear();
        tools.clear();
        *edge = None;
        m_functions.clear();
        targets.clear();
        *target_span = None;
        *circle = Circle::default();
        *circle_span = None;
        other.clear();
        calls.clear();
        head.clear();
        tail.clear();
        indirect_g.clear();
        h_functions.clear();
        after_edge.clear();
        addresses.clear();
        address_keys.clear();
        indirect_targets.clear();
        *motion_span = None;
        *spline = gcodec_ail::SplineData::default();
        *spline_span = None;
        *transition = None;
        repeated_axes.clear();
        machine_axis_words.clear();
    }

    fn add_target(&mut self, target: AxisValue, span: Span) {
        self.target_span.get_or_insert(span);
        if self.targets.iter().any(|t| t.axis == target.axis) {
            self.repeated_axes.push((target.axis.clone(), span));
        }
        self.targets.push(target);
    }
}

impl<'a> Lowering<'a> {
    /// The lowering of a part of `program`, starting at `entry`, with
    /// room for the instructions of about `statements` statements.
    fn new(
        outline: &'a Outline<'a>,
        profile: &'a Profile,
        source: &'a [u8],
        statements: usize,
        entry: Entry,
    ) -> Self {
        let mut modal = gcodec_profile::reset_defaults(profile);
        let mut group8 =
            gcodec_profile::group8_index(profile.work_offsets.default_group8_offset.get_ref());
        let mut modal_call = false;
        match entry {
            // A subprogram starts in its caller's state: the motion
            // command and the Group 8 selection are not known here.
            Entry::ProgramStart if outline.subprogram => {
                modal[0] = None;
                group8 = None;
            }
            Entry::ProgramStart => {}
            Entry::AfterOpenPart => {
                modal[0] = None;
                group8 = None;
            }
            Entry::After(state) => {
                modal[0] = state.group1;
                group8 = state.group8;
                modal_call = state.modal_call;
            }
        }
        let mut lowering = Self {
            outline,
            profile,
            source,
            file: Arc::from(&*outline.file),
            block_start: 0,
            document: Document {
                instructions: Vec::with_capacity(capacity(statements)),
                ..Document::new()
            },
            diagnostics: Diagnostics::new(),
            modal,
            group8,
            modal_call,
            open: OpenEntry::at(entry),
            group8_supported: profile.work_offsets.supported_group8(),
            plan: None,
            flow_at: 0,
            direct_constant_words: true,
            straight_commands: [None; 2],
        };
        lowering.straight_commands = [0.0, 1.0].map(|g| {
            lowering
                .straight_motion_command(g)
                .map(|command| (command, command.name()))
        });
        lowering
    }

    /// What control flow says about block `index`, found from where the
    /// block before's was: a step, where a hash lookup per block missed
    /// the cache (a tenth of lowering).
    fn block_flow(&mut self, index: usize) -> Option<&'a BlockFlow> {
        let facts = self.outline.flow.blocks();
        let before = |at: usize| facts.get(at).is_some_and(|(i, _)| *i < index);
        if before(self.flow_at) {
            self.flow_at += 1;
        }
        // A part starting elsewhere, or a block out of order: search.
        let after = |at: usize| at > 0 && facts[at - 1].0 >= index;
        if before(self.flow_at) || after(self.flow_at) {
            self.flow_at = facts.partition_point(|(i, _)| *i < index);
        }
        facts
            .get(self.flow_at)
            .filter(|(i, _)| *i == index)
            .map(|(_, f)| f)
    }

    /// What every block's lowering starts with: columns count from the
    /// block's start (`span`), and its diagnostics are its own.
    fn begin_block(&mut self, span: Span) {
        self.block_start = span.start;
        self.diagnostics.begin_block();
    }

    fn source_at(&self, block: usize, span: Span) -> Source {
        Source {
            file: Arc::clone(&self.file),
            line: block as u32 + 1,
            col: span.start.saturating_sub(self.block_start) + 1,
            span: ByteRange {
                start: span.start,
                end: span.end,
            },
        }
    }

    /// Appends the instruction of `op`, written at `span` of block
    /// `block`. Inlined: the constant-word path emits three a line, and
    /// the match below folds away where the op is known.
    #[inline]
    fn emit(&mut self, block: usize, span: Span, op: Op) {
        match &op {
            // A jump target, or a return from code that may change the
            // state: what follows may be reached in another state.
            Op::Label { .. } | Op::RepeatSection(_) => self.forget_modal_state(),
            Op::Call(call) if call.modal => self.modal_call = true,
            Op::Call(_) => self.forget_modal_state(),
            Op::CancelModalCall => self.modal_call = false,
            // The modal call runs after the motion (which is already
            // lowered): what follows may be in another state.
            Op::Motion { .. } if self.modal_call => self.forget_modal_state(),
            _ => {}
        }
        let source = self.source_at(block, span);
        self.document.instructions.push(Instruction { op, source });
    }

    /// From here on the motion command and the Group 8 selection are not
    /// known from the text alone; [`resolve_from_dataflow`] recovers what the dataflow
    /// over the whole document knows.
    fn forget_modal_state(&mut self) {
        self.modal[0] = None;
        self.group8 = None;
        self.open.forget();
    }

    /// The program's end, after its last block.
    fn end(&mut self) {
        let (index, start, end) = self.outline.last_block;
        self.block_start = start;
        let source = self.source_at(index, Span::new(end, end));
        self.document.instructions.push(Instruction {
            op: Op::End,
            source,
        });
    }

    fn block(&mut self, index: usize, block: &Block) {
        self.begin_block(block.span);
        let max = *self.profile.program.max_block_length.get_ref();
        if block.span.len() > max {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::BLOCK_TOO_LONG,
                    format!(
                        "the block is {} characters long; the control accepts {max}",
                        block.span.len()
                    ),
                )
                .with_label(block.span, "this block")
                .with_help("split the block; the limit is `max_block_length` in the profile"),
            );
        }
        // Most blocks play no part in control flow: one lookup says so.
        let facts = self.block_flow(index);
        if facts.is_none() && self.direct_constant_words && self.constant_word_block(index, block) {
            return;
        }
        let mut plan = self.plan.take().unwrap_or_default();
        if let Some(facts) = facts {
            self.check_structure_block(facts, block);
            self.structure_parts(facts, block, &mut plan);
        }
        let interrupt = self.interrupt_assignment(block, &mut plan);
        for (at, statement) in block.statements.iter().enumerate() {
            if !interrupt.contains(&at) {
                self.statement(block, index, statement, &mut plan);
            }
        }
        // Jump targets and structure labels come first: a jump to a skipped
        // block lands before its skip test.
        for (op, span) in std::mem::take(&mut plan.head) {
            self.emit(index, span, op);
        }
        // A structure block cannot be skipped (`check_structure_block`
        // says so): its mark is ignored.
        let skip = block
            .skip
            .as_deref()
            .filter(|_| facts.is_none_or(|f| f.roles.is_empty()))
            .map(|skip| self.begin_skip(index, skip));
        self.emit_block(index, block, &mut plan);
        plan.reset();
        self.plan = Some(plan);
        if let Some(skip) = skip {
            self.end_skip(index, skip);
        }
        // The end of a `REPEAT` section comes after all of its last block,
        // also when that block is skipped.
        for name in facts.iter().flat_map(|f| &f.section_ends) {
            self.emit(index, block.span, Op::Label { name: name.clone() });
        }
    }

    /// `/`, `/0`…`/9`: the skip test before the block's instructions.
    fn begin_skip(&mut self, index: usize, skip: &ast::SkipLevel) -> OpenSkip {
        let at = self.document.instructions.len();
        self.emit(
            index,
            skip.span,
            Op::SkipBlock {
                level: skip.level,
                end: skip_label(index),
            },
        );
        OpenSkip {
            at,
            span: skip.span,
            modal_call: self.modal_call,
        }
    }

    /// The label a skipped block continues at, after its instructions. A
    /// block with no instruction of its own (a label only, or words that
    /// lowered to nothing) has nothing to skip: its test is taken back.
    fn end_skip(&mut self, index: usize, skip: OpenSkip) {
        if self.document.instructions.len() == skip.at + 1 {
            self.document.instructions.pop();
            return;
        }
        // Two paths meet: the label forgets what the block set (the motion
        // command, the Group 8 selection); a modal call is in force after
        // it if it is on either path.
        self.emit(
            index,
            skip.span,
            Op::Label {
                name: skip_label(index),
            },
        );
        self.modal_call |= skip.modal_call;
    }

    fn not_lowered(&mut self, span: Span, what: &str) {
        self.diagnostics.push(not_lowered(span, what));
    }

    /// Emits a block's instructions in the order the control acts on
    /// them: the work offset, the G commands, feed, spindles and tools,
    /// the M functions that act in the block, H functions and the other
    /// addresses, a dwell, the motion, the M functions that act after it,
    /// calls, and what must come last (the block's `tail`).
    fn emit_block(&mut self, index: usize, block: &Block, plan: &mut BlockPlan) {
        let tail = std::mem::take(&mut plan.tail);
        self.emit_work_offset(index, block, plan);
        let dwell = self.emit_g_commands(index, block, plan);
        let lead_change = self.emit_feed(index, plan);
        self.emit_spindles_and_tools(index, plan);
        let has_motion = !plan.targets.is_empty() || !plan.indirect_targets.is_empty();
        let deferred =
            self.profile.tool_change.tool_change_mode == gcodec_profile::ToolChangeMode::DeferredM6;
        let after = self.emit_m_functions_in_block(index, plan, has_motion, deferred);
        self.emit_auxiliaries(index, plan);
        let mut spline = Some(std::mem::take(&mut plan.spline));
        if !has_motion {
            // Spline data and transitions without a motion: as addresses.
            self.unattached_motion_data(
                index,
                plan.spline_span,
                plan.transition.take(),
                spline.take(),
            );
        }
        if let Some((op, span)) = dwell {
            self.emit(index, span, op);
        }
        if has_motion || plan.circle_span.is_some() {
            self.emit_motion(index, block, plan, spline, lead_change);
        }
        for m in after {
            self.emit_m(index, m, MTiming::PostMotion, deferred);
        }
        for (op, span) in std::mem::take(&mut plan.calls) {
            self.emit(index, span, op);
        }
        for (op, span) in tail {
            self.emit(index, span, op);
        }
    }

    /// The Group 8 selection and the block's suppression, as one
    /// `work_offset`.
    fn emit_work_offset(&mut self, index: usize, block: &Block, plan: &BlockPlan) {
        // Work offset: the Group 8 selection and the block's suppression.
        let group8 = plan.g_codes.iter().find(|(c, _)| c.group() == 8);
        let suppression = self.suppression(&plan.suppressions);
        if let Some((code, _)) = group8
            && let Some(selected) = gcodec_profile::group8_index(code.name())
        {
            self.group8 = Some(selected);
            self.open.set_group8();
        }
        if group8.is_some() || suppression.is_some() {
            let span = group8
                .map(|(_, s)| *s)
                .or(plan.suppressions.first().map(|(_, s)| *s))
                .unwrap_or(block.span);
            let selected = self.group8.and_then(WorkOffsetCode::of_index);
            if selected.is_none() && self.open.group8_is_entry() {
                self.open
                    .read_by_work_offset(self.document.instructions.len());
            }
            self.emit(
                index,
                span,
                Op::WorkOffset {
                    group8_selected: selected,
                    suppression,
                    suppression_scope: suppression.map(|_| SuppressionScope::Block),
                },
            );
        }
    }

    /// The block's G commands (but Group 8) as modal changes; a `G4` is
    /// the dwell, returned to go after the addresses.
    fn emit_g_commands(
        &mut self,
        index: usize,
        block: &Block,
        plan: &mut BlockPlan,
    ) -> Option<(Op, Span)> {
        // `G4 F…` / `G4 S…`: the dwell takes the block's F and S.
        let dwell = plan
            .g_codes
            .iter()
            .find(|(c, _)| c.group() == 2 && c.name() == "G4")
            .map(|(_, s)| *s)
            .map(|g4| (self.dwell(block, g4, plan), g4));
        let g_codes = std::mem::take(&mut plan.g_codes);
        for &(command, span) in &g_codes {
            let (group, code) = (command.group(), command.name());
            if group == 8 || dwell.is_some() && code == "G4" {
                continue;
            }
            if self.emit_axis_command(index, command, span, plan) {
                continue;
            }
            self.emit_modal_change(index, command, span);
        }
        plan.g_codes = g_codes;
        self.unknown_machine_axes(plan);
        for (group, index_value, span) in std::mem::take(&mut plan.indirect_g) {
            self.emit(
                index,
                span,
                Op::ModalChangeIndirect {
                    group,
                    index: index_value,
                },
            );
        }
        dwell
    }

    /// The feed; under `G34`/`G35` with a motion, `F` is the change of the
    /// thread lead instead, returned for the motion.
    fn emit_feed(&mut self, index: usize, plan: &mut BlockPlan) -> Option<gcodec_ail::Value> {
        let modal_group1 = self.modal[0];
        let thread_kind = matches!(modal_group1, Some("G34" | "G35"));
        // Under G34/G35 `F` is the change of the thread lead.
        let lead_change = if thread_kind && !plan.targets.is_empty() {
            plan.feed.take().map(|(v, _)| v)
        } else {
            None
        };
        if let Some((value, span)) = plan.feed.take() {
            self.emit(index, span, Op::Feed { value });
        }
        lead_change
    }

    /// Spindle speeds, tool selections (with the change of a direct `T`),
    /// the cutting edge and what follows it.
    fn emit_spindles_and_tools(&mut self, index: usize, plan: &mut BlockPlan) {
        for (spindle, spindle_expr, speed, span) in std::mem::take(&mut plan.spindle) {
            self.emit(
                index,
                span,
                Op::SpindleSpeed {
                    spindle,
                    speed,
                    spindle_expr,
                },
            );
        }
        for (op, span) in std::mem::take(&mut plan.tools) {
            let direct = matches!(
                op,
                Op::ToolSelect(ref t) if t.timing == gcodec_ail::ToolTiming::Immediate
            );
            self.emit(index, span, op);
            if direct {
                self.emit(
                    index,
                    span,
                    Op::ToolChange {
                        trigger: ToolChangeTrigger::TWord,
                    },
                );
            }
        }
        if let Some((edge, span)) = plan.edge.take() {
            self.emit(index, span, Op::CuttingEdge { edge });
        }
        for (op, span) in std::mem::take(&mut plan.after_edge) {
            self.emit(index, span, op);
        }
    }

    /// The M functions that act in the block; those that act after its
    /// motion are returned.
    fn emit_m_functions_in_block(
        &mut self,
        index: usize,
        plan: &mut BlockPlan,
        has_motion: bool,
        deferred: bool,
    ) -> Vec<mfunc::MWord> {
        mfunc::check_count(&plan.m_functions, self.profile, &mut self.diagnostics);
        mfunc::check_groups(&plan.m_functions, self.profile, &mut self.diagnostics);
        // Only blocks with motion and M0/M1/M2/M17/M30 allocate here.
        let mut after = Vec::new();
        for m in std::mem::take(&mut plan.m_functions) {
            // A computed value (`M=2*15`) may be a program-flow function,
            // which acts after the motion: it waits for the motion, so
            // that a stop or end never drops it (SPEC §10.3).
            if has_motion && m.value.is_none_or(acts_after_motion) {
                after.push(m);
            } else {
                self.emit_m(index, m, MTiming::InBlock, deferred);
            }
        }
        after
    }

    /// H functions, the other instructions and the addresses.
    fn emit_auxiliaries(&mut self, index: usize, plan: &mut BlockPlan) {
        for (op, span) in std::mem::take(&mut plan.h_functions) {
            self.emit(index, span, op);
        }
        for (op, span) in std::mem::take(&mut plan.other) {
            self.emit(index, span, op);
        }
        for (op, span) in std::mem::take(&mut plan.addresses) {
            self.emit(index, span, op);
        }
    }

    /// The block's motion, with its circle, thread and spline data.
    fn emit_motion(
        &mut self,
        index: usize,
        block: &Block,
        plan: &mut BlockPlan,
        spline: Option<gcodec_ail::SplineData>,
        lead_change: Option<gcodec_ail::Value>,
    ) {
        let first = plan
            .target_span
            .or(plan.motion_span)
            .or(plan.circle_span)
            .unwrap_or(block.span);
        let motion = match self.modal[0] {
            None => MotionKind::Modal,
            Some(code) => motion_of(code).unwrap_or_else(|| {
                self.not_lowered(first, &format!("motion under `{code}`"));
                MotionKind::Linear
            }),
        };
        // Under an unknown command the circle data go with the motion
        // as written; the executor reads them by the command then.
        self.report_repeated_axes(plan);
        let circle_missing = matches!(motion, MotionKind::ArcCw | MotionKind::ArcCcw)
            && plan.circle.centre.is_empty()
            && plan.circle.radius.is_none()
            && plan.circle.opening_angle.is_none()
            // A polar end point: the circle is about the pole.
            && !plan
                .targets
                .iter()
                .any(|t| matches!(t.axis.as_ref(), "AP" | "RP"));
        if circle_missing {
            let code = self.modal[0].unwrap_or("G2");
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::MISSING_CIRCLE_DATA,
                    format!("`{code}` is active, but the block gives no centre, radius or opening angle"),
                )
                .with_label(first, "circle end point")
                .with_help("program the centre (`I J K`), the radius (`CR=`) or the opening angle (`AR=`), or change to `G0`/`G1` for a straight line"),
            );
        }
        let arc = is_arc(motion) || motion == MotionKind::Modal && plan.circle_span.is_some();
        let threaded = is_threaded(motion);
        let circle_data = std::mem::take(&mut plan.circle);
        // Under a thread or tapping command `I J K` are the lead.
        let thread = threaded.then(|| gcodec_ail::Thread {
            lead: circle_data.centre.clone(),
            lead_change: lead_change.clone(),
        });
        let circle = arc.then(|| Box::new(circle_data));
        let details = gcodec_ail::MotionDetails {
            indirect_targets: std::mem::take(&mut plan.indirect_targets),
            spline: spline.filter(|s| s.weight.is_some() || s.interval.is_some()),
            thread,
            transition: plan.transition.take().map(|(t, _)| t),
        };
        let details = (!details.is_empty()).then(|| Box::new(details));
        // Exactly as long as needed: the plan's vector grew to room for
        // four axes, and a large program keeps hundreds of thousands of
        // these.
        let targets = plan.targets.drain(..).collect();
        self.emit_motion_op(index, first, motion, targets, circle, details);
    }

    /// Emits the change to the G command `command`, which the state known
    /// from the text then holds if its group is modal.
    fn emit_modal_change(&mut self, index: usize, command: GCommand, span: Span) {
        self.emit_named_modal_change(index, command, command.name(), span);
    }

    /// [`Self::emit_modal_change`] of a command whose `name` is known.
    fn emit_named_modal_change(
        &mut self,
        index: usize,
        command: GCommand,
        name: &'static str,
        span: Span,
    ) {
        let group = command.group();
        if ggroups::is_modal(group) {
            self.modal[usize::from(group) - 1] = Some(name);
            if group == 1 {
                self.open.set_group1();
            }
        }
        self.emit(
            index,
            span,
            Op::ModalChange {
                group,
                code: command,
            },
        );
    }

    /// Emits a block's motion; one of the modal motion command (`motion`
    /// is [`MotionKind::Modal`]) reads the group-1 command the block
    /// entered with.
    fn emit_motion_op(
        &mut self,
        index: usize,
        first: Span,
        motion: MotionKind,
        targets: Vec<AxisValue>,
        circle: Option<Box<gcodec_ail::Circle>>,
        details: Option<Box<gcodec_ail::MotionDetails>>,
    ) {
        if motion == MotionKind::Modal && self.open.group1_is_entry() {
            self.open.read_by_motion(self.document.instructions.len());
        }
        self.emit(
            index,
            first,
            Op::Motion {
                motion,
                targets,
                circle,
                details,
            },
        );
    }

    /// Axes written twice in the block (alarm 12010).
    fn report_repeated_axes(&mut self, plan: &mut BlockPlan) {
        for (axis, span) in std::mem::take(&mut plan.repeated_axes) {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::REPEATED_AXIS,
                    format!("`{axis}` is programmed twice in this block"),
                )
                .with_label(span, "again")
                .with_help("the control rejects the block (alarm 12010); program each axis once"),
            );
        }
    }

    fn emit_m(&mut self, index: usize, m: mfunc::MWord, timing: MTiming, deferred: bool) {
        let is_change = deferred
            && m.value == Some(*self.profile.tool_change.change_m_code.get_ref())
            && m.extension.is_none();
        let span = m.span;
        self.emit(index, span, m.into_op(timing));
        if is_change {
            self.emit(
                index,
                span,
                Op::ToolChange {
                    trigger: ToolChangeTrigger::M6,
                },
            );
        }
    }

    /// The strongest suppression of a block, per the profile's policy for
    /// several in one block (the work-offset design).
    fn suppression(&mut self, found: &[(Suppression, Span)]) -> Option<Suppression> {
        let (first, first_span) = *found.first()?;
        if found.len() == 1 {
            return Some(first);
        }
        let strongest = found.iter().map(|(s, _)| *s).max().unwrap_or(first);
        let policy = self.profile.work_offsets.duplicate_suppression_policy;
        let message = "several of G53, G153 and SUPA in one block";
        let diagnostic = match policy {
            DuplicateSuppressionPolicy::FirstWins => return Some(first),
            DuplicateSuppressionPolicy::Warn => Diagnostic::new(codes::lower::DUPLICATE_SUPPRESSION, message)
                .with_help("the strongest one acts (SUPA > G153 > G53); write only that one"),
            DuplicateSuppressionPolicy::Error => Diagnostic::new(codes::lower::DUPLICATE_SUPPRESSION, message).with_severity(Severity::Error)
                .with_help("the profile forbids this (`duplicate_suppression_policy = \"error\"`); write only one"),
        };
        let mut diagnostic = diagnostic.with_label(first_span, "first");
        for (_, span) in &found[1..] {
            diagnostic = diagnostic.with_label(*span, "again");
        }
        self.diagnostics.push(diagnostic);
        Some(strongest)
    }
}
