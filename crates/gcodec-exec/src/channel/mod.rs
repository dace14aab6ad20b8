//! The channel: runs lowered programs the way a SINUMERIK channel does and
//! hands every event to an [`EventSink`] as it happens (SPEC §11).
//!
//! [`Channel::run`] walks the main program's instructions with a program
//! counter. Subprograms, cycles, modal calls and `REPEAT` sections push a
//! level on a stack (at most [`RunOptions::max_levels`] program
//! levels); jumps go to the instruction index of their label. A block is
//! the run of instructions of one source line; at its end the modal call
//! runs (after a traversing block), and the CSV row is written. Nothing
//! per block or per loop pass is kept, so memory does not grow with the
//! run: events go out, the summary adds up.
//!
//! Module map: `state` (modal groups, positions, frames, tool, spindles,
//! the pole and working-area limits, and the system variables a program
//! reads), `motion` (traversing blocks
//! and arcs), `polar` (end points computed from `AP`/`RP` and `ANG`),
//! `approach` (`G74`/`G75`), `settings` (the group 3 commands whose axis
//! words set values: `G25`/`G26`, the pole, `G58`/`G59`), `calls`
//! (subprograms, parameters, sections), `functions` (M and H functions,
//! spindle, dwell, named addresses, programmable frames), `tools` (tool
//! selection and change, cutting edges), `interrupts` (the
//! routines assigned to inputs), `summary` (the figures after the run).

mod approach;
mod calls;
mod functions;
mod interrupts;
mod machine_calls;
mod motion;
mod polar;
pub mod session;
mod settings;
pub mod state;
mod summary;
mod tool_data;
mod toolpath;
mod tools;

use std::borrow::Cow;
use std::io;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use gcodec_ail::{Instruction, Op};
use gcodec_lang::WorkOffsetCode;
use gcodec_lang::ggroups;
use gcodec_profile::Profile;
use gcodec_source::{Code, Severity, codes};
use rustc_hash::FxHashSet;

pub use state::MachineState;
pub use summary::{RunSummary, ToolSummary};

use crate::eval::{self, Env};
use crate::event::{
    BlockRow, CallKind, DiagnosticEvent, Event, EventKind, EventSink, EventSource, MessageEvent,
    ModalChangeEvent, ProgramEndEvent, ProgramEndReason, StopEvent, StopReason,
};
use crate::geometry::CircleTolerance;
use crate::loader::ProgramLoader;
use crate::machine::{Machine, MachineEvents, SimulatedMachine};
use crate::program::Program;
use crate::tool_resolution::{TableResolver, ToolResolver};
use crate::value::RunError;
use crate::vars::{Global, Scope, Variables};

/// How a run goes.
#[derive(Clone, Debug)]
pub struct RunOptions {
    /// Skip levels switched on (`/0`…`/9`).
    pub skip_levels: [bool; 10],
    /// Stop after this many blocks ([`ProgramEndReason::Limit`]).
    pub max_steps: u64,
    /// Stop before the element operations on variables pass this many
    /// ([`crate::budget::WorkBudget`], `--max-work`): a block can cost
    /// millions of them, which the step limit does not see.
    pub max_work: u64,
    /// Program levels, the main program's included (16 on the control).
    pub max_levels: usize,
    /// `M0` (and `M1` with `optional_stop`) ends the run with a `stop`
    /// event: the simulation cannot wait for NC start. `false` (`--no-stop`)
    /// goes on.
    pub stop_at_m0: bool,
    /// The operator's optional-stop switch: `M1` stops.
    pub optional_stop: bool,
    /// Set from another thread (Ctrl-C) to stop the run cleanly.
    pub interrupt: Option<Arc<AtomicBool>>,
    pub circle_tolerance: CircleTolerance,
    /// Straight motions to constant end points in a plain state (no
    /// frame, offset or tool length acting) skip the general path's
    /// transforms ([`Channel`]'s direct path; on by default), and so do
    /// the workpiece positions of CSV rows and motions in such a state.
    /// `false` runs every motion by the general path: tests hold the two
    /// equal.
    pub direct_motions: bool,
}

impl RunOptions {
    /// The defaults for a machine: its skip levels, `stop_at_m0` and
    /// circle tolerance, 10 million blocks, a billion element operations,
    /// 16 levels, M1 does not stop.
    pub fn for_profile(profile: &Profile) -> Self {
        let mut skip_levels = [false; 10];
        for level in &profile.program.skip_levels {
            if let Some(slot) = skip_levels.get_mut(usize::from(*level.get_ref())) {
                *slot = true;
            }
        }
        Self {
            skip_levels,
            max_steps: 10_000_000,
            max_work: crate::budget::DEFAULT_MAX_WORK,
            max_levels: 16,
            stop_at_m0: profile.program.stop_at_m0,
            optional_stop: false,
            interrupt: None,
            circle_tolerance: CircleTolerance {
                absolute: *profile.program.circle_error_const.get_ref(),
                relative: *profile.program.circle_error_factor.get_ref(),
            },
            direct_motions: true,
        }
    }
}

/// What a run ended with.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOutcome {
    pub reason: ProgramEndReason,
    pub summary: RunSummary,
    /// The number of diagnostic events of severity `error` (alarms).
    pub errors: u64,
    pub warnings: u64,
}

/// Receives the state after each executed block (`--format csv`).
pub trait BlockObserver {
    fn block(&mut self, row: &BlockRow) -> io::Result<()>;
}

/// The CSV trace: the writer takes every block's row and writes those
/// [`crate::event::CsvRows`] selects.
impl<W: io::Write> BlockObserver for crate::event::CsvWriter<W> {
    fn block(&mut self, row: &BlockRow) -> io::Result<()> {
        self.row(row)
    }
}

/// One level of the stack: a program (or a section of one) running.
struct Level {
    program: Arc<Program>,
    /// Where this level goes on (while a deeper level runs: the
    /// instruction after the call).
    pc: usize,
    /// The program level of events (0: main program); a `REPEAT` section
    /// runs at its program's level.
    program_level: u32,
    kind: LevelKind,
}

enum LevelKind {
    Main,
    /// A called program (or a section of one), `pass` of `passes`.
    Call(Box<calls::ActiveCall>),
    /// `REPEAT`: from `start` to the label `end`.
    Repeat {
        target: String,
        start: usize,
        end: usize,
        pass: u32,
        passes: u32,
        /// The `REPEAT` block: every pass's `call` event points there.
        origin: EventSource,
    },
}

/// What an instruction does to the program counter.
enum Flow {
    Next,
    Jump(usize),
    /// A level was pushed (a call) or popped (a return): continue with the
    /// top of the stack.
    Switch,
    End(ProgramEndReason),
    /// The machine is still working on what the instruction asked
    /// (`Channel::pending` says what): the run pauses at it.
    Pending,
}

/// Why the run loop gave control back.
pub(crate) enum Halt {
    /// The run is over.
    End(ProgramEndReason),
    /// A machine action is pending (`Channel::pending`).
    Pending,
    /// A block ended and the sink has events to hand over.
    Yield,
}

/// The block being executed.
#[derive(Default)]
struct BlockState {
    open: bool,
    /// A jump, call or return happened: the next instruction starts a
    /// block even on the same line.
    transferred: bool,
    line: u32,
    had_motion: bool,
    /// The auxiliary-function groups (bit `group − 1`) whose M function
    /// the block has output.
    m_groups: u64,
    /// The `D` the block programmed: a change later in the block (`T1 M6
    /// D2` lowers the `D` first) takes it instead of the default edge.
    edge: Option<u32>,
    /// Where the block came from (for the CSV row).
    file: Option<Arc<str>>,
    level: u32,
    number: Option<u32>,
    /// A motion of the block moved in the working plane.
    moved_in_plane: bool,
    /// The feed before the block's `F`: under `G34`/`G35` a motion
    /// block's `F` is the change of the thread lead, not a feed, and a
    /// block whose motion command lowering could not know (paths meet
    /// there) gives it as a feed (`Channel::lead_change_was_fed`).
    feed_before_f: Option<f64>,
}

/// A running channel.
pub struct Channel<'r> {
    pub state: MachineState,
    pub vars: Variables,
    options: RunOptions,
    loader: &'r mut dyn ProgramLoader,
    sink: Box<dyn EventSink + 'r>,
    machine: Box<dyn Machine + 'r>,
    /// Asked of the machine when the run starts: it is told of every
    /// block.
    machine_watches_blocks: bool,
    /// Asked of the sink when the run starts: it may want the run to
    /// hand over at the end of a block.
    sink_may_yield: bool,
    /// The sink's [`EventSink::takes_motions`], asked when the run starts.
    sink_takes_motions: bool,
    /// What the machine reports with an answer, emitted at once.
    machine_events: MachineEvents,
    /// The machine action the run waits for, and how to go on.
    pending: Option<machine_calls::PendingAction>,
    /// Where the run loop left off at a pause: the line of the
    /// instruction run before (see `advance`).
    paused_previous_line: Option<Option<u32>>,
    observer: Option<&'r mut dyn BlockObserver>,
    /// What a `T` selection names ([`TableResolver`] unless an
    /// application supplies its own).
    tool_resolver: Box<dyn ToolResolver + 'r>,
    stack: Vec<Level>,
    summary: RunSummary,
    block: BlockState,
    /// `MCALL NAME(…)`: the call made after every traversing block.
    /// Things reported once per run (not-simulated addresses).
    reported: FxHashSet<String>,
    motion: motion::MotionScratch,
    row: BlockRow,
    /// What the row's positions were computed from.
    row_positions_from: RowPositionsFrom,
    /// What the row's other state columns were filled from.
    row_columns_from: Option<RowColumnsFrom>,
    /// Whether the last row filled went to the observer as it was (the
    /// path stage was idle): only then can the next say it is the same.
    row_went_as_filled: bool,
    errors: u64,
    warnings: u64,
    output_error: Option<io::Error>,
    /// Where the active tool's figures are in the summary, once looked up
    /// (cleared by a tool change): not searched for every block.
    figures_slot: Option<usize>,
    /// A global variable of the definition files that did not fit the
    /// memory for variables, where it is defined: the run does not start.
    global_error: Option<(EventSource, RunError)>,
    /// Chamfers, roundings and tool radius compensation: the motions and
    /// outputs held for the look-ahead ([`crate::path`]).
    path: toolpath::PathStage,
    /// What the stage released, reused.
    path_ready: Vec<crate::path::Held<toolpath::HeldMotion, toolpath::HeldOutput>>,
    /// Where the tool centre stands after the last motion released under
    /// compensation (workpiece coordinates); `None` without it.
    last_tool_point: Option<Vec<f64>>,
    /// An alarm of the stage at a block's end, raised at the next block.
    path_alarm: Option<RunError>,
    /// A contour definition waiting for its second block.
    pending_contour: Option<toolpath::PendingContour>,
    /// The frame of the last motion the stage took, shared while it holds.
    path_frame: Option<Arc<crate::frames::Frame>>,
    /// The event the stage's released elements are written in, reused.
    path_event: Option<Event>,
}

impl<'r> Channel<'r> {
    pub fn new(
        profile: Arc<Profile>,
        options: RunOptions,
        loader: &'r mut dyn ProgramLoader,
        sink: impl EventSink + 'r,
    ) -> Self {
        // The profile has no key for MD28050 (the number of R parameters).
        let max_memory = *profile.program.max_variable_memory.get_ref();
        let vars = Variables::default().with_budgets(options.max_work, max_memory);
        let machine = Box::new(SimulatedMachine::new(&profile));
        let max_dummy_blocks = *profile.program.cutcom_max_dummy_blocks.get_ref();
        let max_check_blocks = *profile.program.cutcom_check_blocks.get_ref();
        let state = MachineState::new(profile);
        let motion = motion::MotionScratch::new(&state, options.direct_motions);
        Self {
            state,
            vars,
            options,
            loader,
            sink: Box::new(sink),
            machine,
            machine_watches_blocks: false,
            sink_may_yield: false,
            sink_takes_motions: true,
            machine_events: MachineEvents::new(),
            pending: None,
            paused_previous_line: None,
            observer: None,
            tool_resolver: Box::new(TableResolver),
            stack: Vec::new(),
            summary: RunSummary::default(),
            block: BlockState::default(),
            reported: FxHashSet::default(),
            motion,
            row: BlockRow::default(),
            row_positions_from: RowPositionsFrom::default(),
            row_columns_from: None,
            row_went_as_filled: false,
            errors: 0,
            warnings: 0,
            output_error: None,
            figures_slot: None,
            global_error: None,
            path: toolpath::PathStage::new(max_dummy_blocks, max_check_blocks),
            path_ready: Vec::new(),
            last_tool_point: None,
            path_alarm: None,
            pending_contour: None,
            path_frame: None,
            path_event: None,
        }
    }

    /// Runs against `machine` instead of the [`SimulatedMachine`] of the
    /// profile.
    pub fn with_machine(mut self, machine: impl Machine + 'r) -> Self {
        self.machine = Box::new(machine);
        self
    }

    /// Also hands the state after each block to `observer`.
    pub fn with_observer(mut self, observer: &'r mut dyn BlockObserver) -> Self {
        self.observer = Some(observer);
        self
    }

    /// Resolves tool selections with `resolver` instead of the profile's
    /// tool table.
    pub fn with_tool_resolver(mut self, resolver: Box<dyn ToolResolver + 'r>) -> Self {
        self.tool_resolver = resolver;
        self
    }

    /// Declares the global user data of definition files (GUD), each with
    /// its type's initial value, in the order given. A declaration the
    /// store rejects as too large stays undeclared: reading it is an error
    /// naming it. One that does not fit the memory for variables is the
    /// run's alarm, at its line of its definition file, and the run does
    /// not start (as the control does not activate the definitions).
    pub fn with_globals<'g>(mut self, globals: impl IntoIterator<Item = &'g Global>) -> Self {
        for global in globals {
            let declared = self.vars.declare(
                Scope::Global,
                &global.name,
                global.data_type,
                &global.dims,
                crate::vars::Init::None,
            );
            if let Err(error) = declared
                && error.code == codes::run::VARIABLE_MEMORY
            {
                let source = EventSource {
                    file: global.file.clone(),
                    line: global.line,
                    col: global.col,
                    level: 0,
                };
                self.global_error = Some((source, error));
                break;
            }
        }
        self
    }

    /// Runs `main` to its end and writes the final `program_end` event.
    /// An error writing events ends the run and is returned. A machine
    /// action left pending ends the run with an alarm: nothing here can
    /// answer it (a [`crate::session::Session`] can).
    pub fn run(self, main: Arc<Program>) -> io::Result<RunOutcome> {
        session::Session::new(self, main).run_to_end()
    }

    /// Starts the run of `main`: its level, the definitions' globals, its
    /// parameters. `Some`: the run ends before its first block.
    pub(crate) fn begin(&mut self, main: Arc<Program>) -> Option<ProgramEndReason> {
        self.machine_watches_blocks = self.machine.watches_blocks();
        if let Some(tool) = self.machine.initial_tool() {
            self.state.active_tool = Some(crate::tool_resolution::ToolRef {
                label: tool.label,
                number: tool.number,
            });
        }
        self.sink_may_yield = self.sink.may_yield();
        self.sink_takes_motions = self.sink.takes_motions();
        self.stack.push(Level {
            program: Arc::clone(&main),
            pc: 0,
            program_level: 0,
            kind: LevelKind::Main,
        });
        if let Some((source, error)) = self.global_error.take() {
            return Some(self.alarm_in_definitions(source, error));
        }
        match self.bind_main(&main) {
            Ok(()) => None,
            Err(error) => Some(match main.instruction(0) {
                Some(first) => self.alarm(&main, &first, error),
                None => ProgramEndReason::Alarm,
            }),
        }
    }

    /// Ends the run: the machine abandons what it was doing if the run
    /// ends in an alarm, the `program_end` event, the outcome.
    pub(crate) fn finish(&mut self, mut reason: ProgramEndReason) -> io::Result<RunOutcome> {
        self.end_block();
        if let Some(error) = self.path_alarm.take() {
            self.alarm_in_definitions(self.last_source(), error);
            reason = ProgramEndReason::Alarm;
        }
        self.release_path(true);
        if reason == ProgramEndReason::Alarm {
            self.abort_machine(crate::machine::AbortCause::Alarm);
        }
        let end = Event {
            kind: EventKind::ProgramEnd(ProgramEndEvent {
                reason,
                blocks: self.summary.blocks,
            }),
            source: self.last_source(),
        };
        self.emit(&end);
        if let Some(error) = self.output_error.take() {
            return Err(error);
        }
        self.sink.finish()?;
        Ok(RunOutcome {
            reason,
            summary: std::mem::take(&mut self.summary),
            errors: self.errors,
            warnings: self.warnings,
        })
    }

    /// A global variable did not fit: its alarm at its definition.
    fn alarm_in_definitions(&mut self, source: EventSource, error: RunError) -> ProgramEndReason {
        self.count(Severity::Error);
        let event = Event {
            kind: EventKind::Diagnostic(DiagnosticEvent::new(error.code, error.message)),
            source,
        };
        self.emit(&event);
        ProgramEndReason::Alarm
    }

    /// Runs on until the end, a pending machine action or a pause for
    /// the sink; called again, goes on from where it stopped.
    pub(crate) fn advance(&mut self) -> Halt {
        loop {
            let Some(top) = self.stack.last() else {
                return Halt::End(ProgramEndReason::EndOfText);
            };
            let program = Arc::clone(&top.program);
            let mut pc = top.pc;
            let repeat_end = match &top.kind {
                LevelKind::Repeat { end, .. } => Some(*end),
                _ => None,
            };
            let section_end = match &top.kind {
                LevelKind::Call(call) => call.section_end_line,
                _ => None,
            };
            // The page of `pc`, fetched when the run leaves it (a streamed
            // program arrives and is forgotten page by page).
            let mut page = Program::no_page();
            // The line of the instruction run before `pc` in sequence (0:
            // none, at the program's start): blocks with errors between
            // it and `pc` are reached.
            let mut previous_line = self
                .paused_previous_line
                .take()
                .unwrap_or((pc == 0).then_some(0));
            loop {
                if repeat_end == Some(pc) {
                    match self.repeat_pass_done() {
                        Some(reason) => return Halt::End(reason),
                        None => break,
                    }
                }
                if page.get(pc).is_none() {
                    match program.page(pc) {
                        Some(next) => page = next,
                        None if program.is_forgotten(pc) => {
                            return Halt::End(self.forgotten(&program, pc));
                        }
                        // Past the last instruction (lowering always ends
                        // with `end`; a hand-made document may not).
                        None => {
                            match self.return_from_call(&program, pc.saturating_sub(1), false) {
                                Flow::End(reason) => return Halt::End(reason),
                                _ => break,
                            }
                        }
                    }
                }
                let Some(instruction) = page.get(pc) else {
                    break;
                };
                let line = instruction.source.line;
                if section_end.is_some_and(|end| line > end) {
                    match self.return_from_call(&program, pc, true) {
                        Flow::End(reason) => return Halt::End(reason),
                        _ => break,
                    }
                }
                if !self.block.open || self.block.transferred || line != self.block.line {
                    if self.block.open {
                        self.end_block();
                        if self.modal_call_due() {
                            if let Some(top) = self.stack.last_mut() {
                                top.pc = pc;
                            }
                            match self.run_modal_call(&program, pc) {
                                Flow::End(reason) => return Halt::End(reason),
                                _ => break,
                            }
                        }
                    }
                    let after = previous_line.filter(|_| !self.block.transferred);
                    if let Some(error) = page.error_reached(after, line) {
                        let error = error.clone();
                        return Halt::End(self.block_with_errors(&program, instruction, error));
                    }
                    if self.sink_may_yield && self.sink.wants_yield() {
                        if let Some(top) = self.stack.last_mut() {
                            top.pc = pc;
                        }
                        self.paused_previous_line = Some(previous_line);
                        return Halt::Yield;
                    }
                    if let Some(reason) = self.start_block(&program, instruction) {
                        return Halt::End(reason);
                    }
                }
                previous_line = Some(line);
                if let Some(top) = self.stack.last_mut() {
                    top.pc = pc;
                }
                match self.execute(&program, pc, instruction) {
                    Flow::Next => pc += 1,
                    Flow::Jump(target) => {
                        pc = target;
                        self.block.transferred = true;
                    }
                    Flow::Switch => {
                        self.block.transferred = true;
                        break;
                    }
                    Flow::End(reason) => return Halt::End(reason),
                    Flow::Pending => {
                        self.paused_previous_line = Some(previous_line);
                        return Halt::Pending;
                    }
                }
                if self.output_error.is_some() {
                    return Halt::End(ProgramEndReason::Alarm);
                }
            }
        }
    }

    /// A block the program's lowering found errors in is reached: the
    /// control stops there with an alarm (SPEC §11.9).
    fn block_with_errors(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        at: gcodec_ail::Source,
    ) -> ProgramEndReason {
        let mut there = instruction.clone();
        there.source = at;
        let error = RunError::new(
            codes::run::BLOCK_WITH_ERRORS,
            "the run reaches a block with errors (reported with the program's diagnostics)",
        );
        self.alarm(program, &there, error)
    }

    /// The run comes back to an instruction of a streamed program that
    /// was forgotten: the outline missed a way back (a bug in gcodec).
    fn forgotten(&mut self, program: &Arc<Program>, pc: usize) -> ProgramEndReason {
        if let Some(last) = program.last_instruction() {
            let error = RunError::new(
                codes::run::FORGOTTEN_INSTRUCTION,
                format!(
                    "the run comes back to instruction {pc}, which the streamed run \
                     had forgotten; please report this program to gcodec"
                ),
            );
            return self.alarm(program, &last, error);
        }
        ProgramEndReason::Alarm
    }

    /// The start of a block: counts it, checks the limits.
    fn start_block(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
    ) -> Option<ProgramEndReason> {
        if let Some(error) = self.path_alarm.take() {
            return Some(self.alarm(program, instruction, error));
        }
        let level = self.program_level();
        // The file stays from block to block: no count of its references
        // changes.
        let file = match self.block.file.take() {
            Some(file) if Arc::ptr_eq(&file, &program.file) => Some(file),
            _ => self.observer.is_some().then(|| program.file.clone()),
        };
        self.block = BlockState {
            open: true,
            transferred: false,
            line: instruction.source.line,
            had_motion: false,
            m_groups: 0,
            edge: None,
            file,
            level,
            number: None,
            moved_in_plane: false,
            feed_before_f: None,
        };
        if self.observer.is_some() {
            self.block.number = program.block_number(instruction.source.line);
        }
        self.summary.blocks += 1;
        self.figures().blocks += 1;
        if self.machine_watches_blocks {
            self.machine_block(program, instruction);
        }
        if self.summary.blocks > self.options.max_steps {
            let message = format!(
                "the run stopped after {} blocks (--max-steps): an endless loop, or a longer program than expected",
                self.options.max_steps
            );
            self.diagnostic_at(
                program,
                instruction,
                codes::run::STEP_LIMIT,
                Severity::Error,
                message,
                Some("raise the limit with --max-steps N if the program is meant to run this long"),
            );
            return Some(ProgramEndReason::Limit);
        }
        if self
            .options
            .interrupt
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::Relaxed))
        {
            self.diagnostic_at(
                program,
                instruction,
                codes::run::INTERRUPTED,
                Severity::Error,
                "the run was interrupted (Ctrl-C)".into(),
                None,
            );
            return Some(ProgramEndReason::Limit);
        }
        None
    }

    /// The end of a block: the block-scope suppression ends, the CSV row.
    fn end_block(&mut self) {
        if !self.block.open {
            return;
        }
        self.block.open = false;
        self.state.suppression = None;
        self.path_block_ended();
        if self.observer.is_some() {
            self.fill_row();
            if !self.hold_row()
                && let Some(observer) = self.observer.as_mut()
                && let Err(error) = observer.block(&self.row)
            {
                self.output_error.get_or_insert(error);
            }
        }
    }

    /// Sends `event` unless it is a motion and the sink takes none.
    fn send_if_taken(&mut self, event: &Event) {
        send_if_taken(
            &mut *self.sink,
            self.sink_takes_motions,
            &mut self.output_error,
            event,
        );
    }

    /// Fills the row of the block just ended.
    fn fill_row(&mut self) {
        // The row goes to the observer as it is unless the stage holds it.
        let as_filled = self.path.is_idle();
        let state = &self.state;
        let row = &mut self.row;
        row.block_number = self.block.number;
        if let Some(file) = &self.block.file {
            keep_file(&mut row.file, file);
        }
        row.line = self.block.line;
        row.level = self.block.level;
        row.blocks = self.summary.blocks;
        row.moved = self.block.had_motion;
        // A block without motion mostly leaves them as they were: the
        // frame transform is the costliest part of a row. A block that
        // moved mostly changed them: computing them is cheaper than
        // asking whether what they come from changed (the writer compares
        // the values anyway), and what they come from is forgotten, since
        // it was not noted.
        let positions_changed = if self.block.had_motion {
            self.row_positions_from.forget();
            true
        } else {
            self.row_positions_from.refresh(state)
        };
        if positions_changed {
            self.motion.workpiece_position(state);
            motion::fill_map(&mut row.positions, state, &self.motion.wcs, true);
        }
        // Most blocks of a loop change no column: the writer need not
        // compare them (a sixth of a CSV run without motion).
        let columns_from = RowColumnsFrom::of(state);
        let tool = state.active_tool.as_ref().map(|t| t.label.as_str());
        let columns_same =
            self.row_columns_from == Some(columns_from) && row.tool.as_deref() == tool;
        row.columns_unchanged = columns_same && self.row_went_as_filled && as_filled;
        row.unchanged = row.columns_unchanged && !positions_changed;
        self.row_went_as_filled = as_filled;
        if columns_same {
            return;
        }
        self.row_columns_from = Some(columns_from);
        match (&mut row.tool, &state.active_tool) {
            (Some(label), Some(tool)) => label.clone_from(&tool.label),
            (label, tool) => *label = tool.as_ref().map(|t| t.label.clone()),
        }
        row.edge = columns_from.edge;
        row.feed = f64::from_bits(columns_from.feed);
        row.spindle_speed = f64::from_bits(columns_from.spindle_speed);
        row.spindle = columns_from.spindle;
        for (slot, column) in row.modal.iter_mut().zip(crate::event::MAIN_MODAL_GROUPS) {
            *slot = Cow::Borrowed(state.modal(column.group).unwrap_or(""));
        }
    }

    /// The figures of the active tool.
    fn figures(&mut self) -> &mut ToolSummary {
        let slot = match self.figures_slot {
            Some(slot) => slot,
            None => {
                let tool = self.state.active_tool.as_ref().map(|t| t.label.as_str());
                let slot = self.summary.slot(tool);
                self.figures_slot = Some(slot);
                slot
            }
        };
        self.summary.at(slot)
    }

    fn program_level(&self) -> u32 {
        self.stack.last().map_or(0, |l| l.program_level)
    }

    /// Runs one instruction.
    ///
    /// The three instructions of a flood's block (`G1 X… Y… F…`) are run
    /// here, every other by [`Self::execute_op`]: entering the one large
    /// function with its every case cost more than a small one's work.
    fn execute(&mut self, program: &Arc<Program>, pc: usize, instruction: &Instruction) -> Flow {
        let result = match &instruction.op {
            Op::Motion { .. } => self.motion(program, instruction).map(|()| Flow::Next),
            Op::ModalChange { group, code } => {
                self.modal_change(program, instruction, *group, code.index());
                Ok(Flow::Next)
            }
            Op::Feed { value } => self.feed(value),
            _ => {
                let flow = self.execute_op(program, pc, instruction);
                return self.instruction_done(flow);
            }
        };
        let flow = match result {
            Ok(flow) => flow,
            Err(error) => self.failed(program, pc, instruction, error),
        };
        self.instruction_done(flow)
    }

    /// The system variables read from the machine are forgotten after
    /// each instruction that does not wait for one.
    fn instruction_done(&mut self, flow: Flow) -> Flow {
        if !matches!(flow, Flow::Pending) {
            self.state.machine_reads.instruction_done();
        }
        flow
    }

    /// `F…`: the feed.
    fn feed(&mut self, value: &gcodec_ail::Value) -> Result<Flow, RunError> {
        let feed = self.real_of(value)?;
        self.block.feed_before_f.get_or_insert(self.state.feed);
        self.state.feed = feed;
        Ok(Flow::Next)
    }

    /// A modal command programmed: put in force if its group is modal.
    fn modal_change(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        group: u8,
        index: u8,
    ) {
        if ggroups::is_modal(group) {
            self.set_modal(program, instruction, group, index);
        }
    }

    /// What an instruction that failed with `error` leads to: the machine
    /// asked for a system variable it answers, or an alarm.
    #[cold]
    fn failed(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        error: RunError,
    ) -> Flow {
        if error.code == codes::run::SYSTEM_VARIABLE
            && let Some(read) = self.state.machine_reads.take_unanswered()
        {
            return self.read_from_machine(program, pc, instruction, read, error);
        }
        Flow::End(self.alarm(program, instruction, error))
    }

    /// Runs an instruction other than [`Self::execute`]'s three.
    #[inline(never)]
    fn execute_op(&mut self, program: &Arc<Program>, pc: usize, instruction: &Instruction) -> Flow {
        let result = match &instruction.op {
            Op::Label { .. } | Op::External(_) | Op::Procedure(_) => Ok(Flow::Next),
            Op::SkipBlock { level, end } => {
                let on = self
                    .options
                    .skip_levels
                    .get(usize::from(*level))
                    .copied()
                    .unwrap_or(false);
                if on {
                    self.jump_to_label(program, pc, end)
                } else {
                    Ok(Flow::Next)
                }
            }
            Op::Jump { target, condition } => {
                let jump = match condition {
                    None => Ok(true),
                    Some(c) => eval::eval_bool(&self.env(), c),
                };
                match jump {
                    Ok(true) => self.jump_to_label(program, pc, target),
                    Ok(false) => Ok(Flow::Next),
                    Err(e) => Err(e),
                }
            }
            Op::ComputedJump(jump) => self.computed_jump(program, pc, jump),
            // The PLC never asks for the restart in the simulation.
            Op::GotoStart { condition } => match condition {
                Some(c) => eval::eval_bool(&self.env(), c).map(|_| Flow::Next),
                None => Ok(Flow::Next),
            },
            Op::ModalChange { group, code } => {
                self.modal_change(program, instruction, *group, code.index());
                Ok(Flow::Next)
            }
            Op::ModalChangeIndirect { group, index } => {
                self.modal_change_indirect(program, instruction, *group, index)
            }
            Op::WorkOffset {
                group8_selected,
                suppression,
                ..
            } => {
                if let Some(code) = *group8_selected {
                    self.select_work_offset(program, instruction, code);
                }
                self.state.suppression = *suppression;
                Ok(Flow::Next)
            }
            Op::Motion { .. } => self.motion(program, instruction).map(|()| Flow::Next),
            Op::Frame(frame) => self.frame(frame).map(|()| Flow::Next),
            Op::AxisSetting(setting) => self.axis_setting(setting).map(|()| Flow::Next),
            Op::ApproachPoint(approach) => self
                .approach_point(program, instruction, approach)
                .map(|()| Flow::Next),
            Op::Feed { value } => self.feed(value),
            Op::SpindleSpeed {
                spindle,
                speed,
                spindle_expr,
            } => self
                .spindle_speed(
                    program,
                    instruction,
                    *spindle,
                    speed,
                    spindle_expr.as_deref(),
                )
                .map(|()| Flow::Next),
            Op::Dwell {
                seconds,
                revolutions,
            } => self.dwell(
                program,
                pc,
                instruction,
                seconds.as_ref(),
                revolutions.as_ref(),
            ),
            Op::Address(address) => self
                .address(program, instruction, address)
                .map(|()| Flow::Next),
            Op::HFunction(h) => self.h_function(program, pc, instruction, h),
            Op::MFunction(m) => self.m_function(program, pc, instruction, m),
            Op::ToolSelect(select) => self.tool_select(program, pc, instruction, select),
            Op::ToolChange { trigger } => self.tool_change(program, pc, instruction, *trigger),
            Op::CuttingEdge { edge } => self
                .cutting_edge(program, instruction, edge)
                .map(|()| Flow::Next),
            Op::Declare(declare) => {
                eval::declare(&mut self.vars, &self.state, declare, Scope::Local)
                    .map(|()| Flow::Next)
            }
            Op::Assign { target, value } => {
                let programs = self
                    .stack
                    .last()
                    .map(|level| (&*self.loader as &dyn ProgramLoader, &*level.program.file));
                eval::assign_in(&mut self.vars, &mut self.state, programs, target, value)
                    .map(|()| Flow::Next)
            }
            Op::AssignList(list) => {
                eval::assign_list(&mut self.vars, &self.state, list).map(|()| Flow::Next)
            }
            Op::Message { text } => eval::eval_value(&self.env(), text).and_then(|v| {
                let text = v.to_text()?;
                let event = EventKind::Message(MessageEvent { text });
                self.emit_at(program, instruction, event);
                Ok(Flow::Next)
            }),
            Op::Stop { reason } => {
                let event = EventKind::Stop(StopEvent {
                    reason: StopReason::PreprocessingStop,
                    detail: Some(reason.clone()),
                });
                self.emit_at(program, instruction, event);
                Ok(Flow::Next)
            }
            Op::InterruptAssign(assign) => self
                .interrupt_assign(program, instruction, assign)
                .map(|()| Flow::Next),
            Op::InterruptControl { action, input } => self
                .interrupt_control(program, instruction, *action, input)
                .map(|()| Flow::Next),
            Op::Call(call) => self.call(program, pc, instruction, call),
            Op::CancelModalCall => {
                self.state.modal_call = None;
                Ok(Flow::Next)
            }
            Op::RepeatSection(section) => self.repeat_section(program, pc, instruction, section),
            Op::Return { .. } => Ok(self.return_from_call(program, pc, false)),
            Op::End => Ok(self.return_from_call(program, pc, false)),
        };
        match result {
            Ok(flow) => flow,
            Err(error) => self.failed(program, pc, instruction, error),
        }
    }

    /// `value` evaluated to a REAL. A constant needs no environment to
    /// evaluate in: making one was most of what a flood block's `F1000`
    /// cost.
    fn real_of(&self, value: &gcodec_ail::Value) -> Result<f64, RunError> {
        match value {
            gcodec_ail::Value::Const(n) => Ok(*n),
            gcodec_ail::Value::Expr(_) => eval::eval_real(&self.env(), value),
        }
    }

    fn env(&self) -> Env<'_> {
        let env = Env::new(&self.vars, &self.state);
        match self.stack.last() {
            Some(level) => env.with_programs(&*self.loader, &level.program.file),
            None => env,
        }
    }

    fn jump_to_label(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        target: &str,
    ) -> Result<Flow, RunError> {
        match program.jump_target(pc).or_else(|| program.label(target)) {
            Some(index) => Ok(Flow::Jump(index)),
            None => Err(RunError::new(
                codes::run::JUMP_TARGET_NOT_FOUND,
                format!(
                    "the jump target `{}` is not in the program",
                    crate::program::written_label(target)
                ),
            )),
        }
    }

    fn computed_jump(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        jump: &gcodec_ail::ComputedJump,
    ) -> Result<Flow, RunError> {
        if let Some(c) = &jump.condition
            && !eval::eval_bool(&self.env(), c)?
        {
            return Ok(Flow::Next);
        }
        let target = match eval::eval(&self.env(), &jump.target)? {
            // `GOTOF 90`: a number names the block number `N90` (as the
            // CEAD interpreter reads it; the manuals write `N90`).
            value if value.is_numeric() => format!("N{}", value.to_int()?),
            value => value.to_text()?,
        };
        match program.search_label(&target, pc, jump.search) {
            Some(index) => Ok(Flow::Jump(index)),
            None if jump.continue_if_missing => Ok(Flow::Next),
            None => Err(RunError::new(
                codes::run::JUMP_TARGET_NOT_FOUND,
                format!("the jump target `{target}` is not in the program"),
            )),
        }
    }

    /// Puts the command at `index` of `group` in force; an index the
    /// registry does not assign changes nothing.
    #[inline]
    fn set_modal(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        group: u8,
        index: u8,
    ) {
        // The command in force programmed again (the `G1` of every block
        // of a flood): the same index is the same command, and nothing
        // changes, known without a call or a name (`KONTC`, which is
        // warned of each time, aside).
        let in_force = self.state.modal_index(group) == Some(index);
        if !in_force || group == 17 {
            self.change_modal(program, instruction, group, index, in_force);
        }
    }

    /// [`Self::set_modal`] of a command not in force, or of group 17.
    fn change_modal(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        group: u8,
        index: u8,
        in_force: bool,
    ) {
        let Some(code) = ggroups::member(group, index) else {
            return;
        };
        if group == 17 && code == "KONTC" {
            self.not_simulated(program, instruction, "approach-mode", || {
                "`KONTC`: the curvature-continuous approach and retraction is not simulated: the tool approaches and leaves on a tangent circle as under `KONTT`".into()
            });
        }
        if in_force {
            return;
        }
        let previous = self.state.modal(group);
        if previous == Some(code) {
            return;
        }
        if group == 6 {
            // A new working plane starts the polar angle anew (reference §2.7).
            self.state.polar.angle = 0.0;
        }
        self.state.modal[usize::from(group) - 1] = index;
        let event = EventKind::ModalChange(ModalChangeEvent {
            group,
            code: Cow::Borrowed(code),
            previous: previous.map(Cow::Borrowed),
        });
        self.emit_at(program, instruction, event);
    }

    fn modal_change_indirect(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        group: u8,
        index: &gcodec_ail::Value,
    ) -> Result<Flow, RunError> {
        let n = eval::eval_value(&self.env(), index)?.to_int()?;
        let member = u8::try_from(n)
            .ok()
            .filter(|&n| ggroups::member(group, n).is_some());
        let Some(index) = member else {
            return Err(RunError::new(
                codes::run::INDEX_OUT_OF_RANGE,
                format!("`G[{group}]={n}`: group {group} has no command at index {n}"),
            ));
        };
        if group == 8 {
            // The registry lists group 8 in `$P_UIFR` order from index 1.
            if let Some(selected) = index.checked_sub(1).and_then(WorkOffsetCode::of_index) {
                self.select_work_offset(program, instruction, selected);
            }
        } else if ggroups::is_modal(group) {
            self.set_modal(program, instruction, group, index);
        }
        Ok(Flow::Next)
    }

    fn select_work_offset(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        code: WorkOffsetCode,
    ) {
        self.state.group8 = code;
        // The registry lists group 8 in `$P_UIFR` order from index 1.
        if let Some(uifr) = code.index() {
            self.set_modal(program, instruction, 8, uifr + 1);
        }
    }

    /// Reports `error` as an alarm: a diagnostic event of severity error.
    /// Returns why the run ends: a limit for the work budget (a guard of
    /// the simulation, as the step limit is), an alarm for the rest.
    fn alarm(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        error: RunError,
    ) -> ProgramEndReason {
        let code = error.code;
        let reason = if code == codes::run::WORK_LIMIT {
            ProgramEndReason::Limit
        } else {
            ProgramEndReason::Alarm
        };
        self.diagnostic_at(
            program,
            instruction,
            code,
            Severity::Error,
            error.message,
            error.help,
        );
        reason
    }

    fn diagnostic_at(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        code: &'static Code,
        severity: Severity,
        message: String,
        help: Option<&'static str>,
    ) {
        let mut diagnostic = DiagnosticEvent::new(code, message);
        diagnostic.severity = severity;
        diagnostic.help = help.map(Cow::Borrowed);
        self.count(severity);
        self.emit_at(program, instruction, EventKind::Diagnostic(diagnostic));
    }

    /// Counts a diagnostic the run reports.
    fn count(&mut self, severity: Severity) {
        match severity {
            Severity::Error => self.errors += 1,
            Severity::Warning => self.warnings += 1,
            Severity::Advice => {}
        }
    }

    /// Advice, once per run for `key`, that a construct is not simulated.
    fn not_simulated(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        key: &str,
        message: impl FnOnce() -> String,
    ) {
        let code = codes::run::NOT_SIMULATED;
        self.once(program, instruction, key, code, Severity::Advice, message);
    }

    /// A diagnostic reported once per run for `key`; its message is only
    /// made then (the blocks that would report it again are many).
    fn once(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        key: &str,
        code: &'static Code,
        severity: Severity,
        message: impl FnOnce() -> String,
    ) {
        if !self.reported.contains(key) {
            self.reported.insert(key.to_owned());
            self.diagnostic_at(program, instruction, code, severity, message(), None);
        }
    }

    fn source(&self, program: &Program, instruction: &Instruction) -> EventSource {
        EventSource {
            file: program.file.clone(),
            line: instruction.source.line,
            col: instruction.source.col,
            level: self.program_level(),
        }
    }

    fn last_source(&self) -> EventSource {
        let level = self.stack.last();
        let file = level.map_or_else(|| Arc::from(""), |l| l.program.file.clone());
        let line = level
            .and_then(|l| {
                l.program
                    .instruction(l.pc)
                    .or_else(|| l.program.last_instruction())
                    .map(|i| (i.source.line, i.source.col))
            })
            .unwrap_or((1, 1));
        EventSource {
            file,
            line: line.0,
            col: line.1,
            level: self.program_level(),
        }
    }

    fn emit_at(&mut self, program: &Program, instruction: &Instruction, kind: EventKind) {
        let event = Event {
            kind,
            source: self.source(program, instruction),
        };
        self.emit(&event);
    }

    fn emit(&mut self, event: &Event) {
        self.emit_in_order(event);
    }

    /// Whether the block just ended calls the modal call: it traversed, a
    /// modal call is active, and no modal call is running already (the
    /// called program's own motions do not call it again).
    fn modal_call_due(&self) -> bool {
        self.block.had_motion
            && self.state.modal_call.is_some()
            && !self.stack.iter().any(|l| match &l.kind {
                LevelKind::Call(call) => call.kind == CallKind::Modal,
                _ => false,
            })
    }
}

/// Hands `event` to the sink unless writing failed before; keeps the
/// first error.
fn send(sink: &mut dyn EventSink, error: &mut Option<io::Error>, event: &Event) {
    if error.is_some() {
        return;
    }
    if let Err(e) = sink.event(event) {
        *error = Some(e);
    }
}

/// Makes `kept` name `file`, counting a reference only when it is
/// another file: the file mostly stays from one block or motion to the
/// next.
fn keep_file(kept: &mut Arc<str>, file: &Arc<str>) {
    if !Arc::ptr_eq(kept, file) {
        *kept = Arc::clone(file);
    }
}

/// [`send`], but a motion only to a sink that takes motions
/// ([`EventSink::takes_motions`]).
fn send_if_taken(
    sink: &mut dyn EventSink,
    takes_motions: bool,
    error: &mut Option<io::Error>,
    event: &Event,
) {
    if takes_motions || !matches!(event.kind, EventKind::Motion(_)) {
        send(sink, error, event);
    }
}

/// What a CSV row's state columns other than the positions and the tool
/// are a function of: the same values, the same columns.
#[derive(Clone, Copy, PartialEq)]
struct RowColumnsFrom {
    edge: u32,
    feed: u64,
    spindle_speed: u64,
    spindle: crate::event::SpindleState,
    /// The registry index of each group of `MAIN_MODAL_GROUPS`.
    modal: [u8; crate::event::MAIN_MODAL_GROUPS.len()],
}

impl RowColumnsFrom {
    fn of(state: &MachineState) -> Self {
        let master = state.master_spindle();
        Self {
            edge: state.edge,
            feed: state.feed.to_bits(),
            spindle_speed: master.map_or(0.0, |s| s.speed).to_bits(),
            spindle: master.map(|s| s.state).unwrap_or_default(),
            modal: crate::event::MAIN_MODAL_GROUPS
                .map(|column| state.modal_index(column.group).unwrap_or(0)),
        }
    }
}

/// What a CSV row's positions are a function of: the machine position,
/// the total frame, the tool length on the infeed axis, and the units and
/// diameter mode they are written in.
#[derive(Default)]
struct RowPositionsFrom {
    /// `None` before the first row.
    frame_generation: Option<u64>,
    machine: Vec<u64>,
    tool_length: u64,
    infeed_axis: Option<usize>,
    inch: bool,
    diameter_mode: (bool, bool),
}

impl RowPositionsFrom {
    /// Makes the next [`RowPositionsFrom::refresh`] say the positions
    /// must be computed again: the row's positions were computed from
    /// inputs it did not note.
    fn forget(&mut self) {
        self.frame_generation = None;
    }

    /// Whether the positions must be computed again for `state`; takes
    /// `state`'s inputs as the new ones.
    fn refresh(&mut self, state: &MachineState) -> bool {
        let frame_generation = Some(state.total_frame_generation());
        let tool_length = state.tool_length.to_bits();
        let infeed_axis = state.infeed_axis();
        let inch = state.inch();
        let diameter_mode = state.diameter_mode();
        let same = self.frame_generation == frame_generation
            && self.tool_length == tool_length
            && self.infeed_axis == infeed_axis
            && self.inch == inch
            && self.diameter_mode == diameter_mode
            && self.machine.len() == state.machine.len()
            && self
                .machine
                .iter()
                .zip(&state.machine)
                .all(|(bits, value)| *bits == value.to_bits());
        if !same {
            self.frame_generation = frame_generation;
            self.tool_length = tool_length;
            self.infeed_axis = infeed_axis;
            self.inch = inch;
            self.diameter_mode = diameter_mode;
            self.machine.clear();
            self.machine
                .extend(state.machine.iter().map(|v| v.to_bits()));
        }
        !same
    }
}
