//! The channel's side of the [`Machine`]: asking it, pausing at a pending
//! answer, and going on when the answer comes (SPEC §11.10).
//!
//! A pending answer pauses the run at the instruction that asked: the
//! instruction's work before the machine call is done, its work after is
//! the [`Continuation`], run when the application resumes with the
//! outcome. A system variable read is the one exception: it is asked in
//! the middle of an expression, so the instruction runs again from its
//! start with the answer (an instruction reads before it has any effect).

use std::cell::{Cell, RefCell};
use std::sync::Arc;

use gcodec_ail::Instruction;
use gcodec_source::{Severity, codes};

use super::session::SessionError;
use super::{Channel, Flow};
use gcodec_ail::ToolChangeTrigger;

use crate::event::{Event, EventKind, EventSource, MAction, ProgramEndReason, SelectionSource};
use crate::machine::{
    AbortCause, Answer, AuxiliaryFunction, Machine, MachineAction, MachineError, Outcome,
    PendingToken, Wait,
};
use crate::program::Program;
use crate::tool_resolution::ToolRef;
use crate::value::{RtValue, RunError};

/// A machine action the run waits for.
pub(crate) struct PendingAction {
    pub token: PendingToken,
    pub action: MachineAction,
    pub source: EventSource,
    continuation: Continuation,
    program: Arc<Program>,
    pc: usize,
    instruction: Instruction,
}

/// What the instruction still does once the machine is done.
pub(crate) enum Continuation {
    /// Nothing: the run goes on with the next instruction.
    Next,
    /// The channel's own part of an M function (spindle, stop, end).
    MAction {
        action: MAction,
        value: u32,
        extension: Option<u32>,
    },
    /// The instruction runs again with the value read.
    Reread(UnansweredRead),
    /// The tool change is reported and takes effect as the machine says.
    ToolChange(Box<ChangeInProgress>),
}

/// A tool change the machine is asked to make.
#[derive(Clone, Debug)]
pub(crate) struct ChangeInProgress {
    pub previous: Option<String>,
    pub new: Option<ToolRef>,
    pub source: SelectionSource,
    pub substituted: bool,
    pub trigger: ToolChangeTrigger,
}

/// A read of a system variable that neither the channel nor the profile
/// answered, kept for the machine.
#[derive(Clone, Debug)]
pub(crate) struct UnansweredRead {
    pub name: String,
    pub indices: Vec<RtValue>,
}

impl UnansweredRead {
    fn is(&self, name: &str, indices: &[RtValue]) -> bool {
        self.name == name && self.indices == indices
    }
}

/// The machine's answers to the reads of the instruction running (it
/// runs again with each), and the read none answered yet.
#[derive(Default)]
pub(crate) struct MachineReads {
    answered: RefCell<Vec<(UnansweredRead, RtValue)>>,
    unanswered: RefCell<Option<UnansweredRead>>,
    /// Whether `answered` or `unanswered` holds anything: checked after every
    /// instruction, so that a run the machine answers nothing for pays
    /// one flag.
    any: Cell<bool>,
}

impl MachineReads {
    pub fn lookup(&self, name: &str, indices: &[RtValue]) -> Option<RtValue> {
        if !self.any.get() {
            return None;
        }
        let answered = self.answered.borrow();
        answered
            .iter()
            .find(|(read, _)| read.is(name, indices))
            .map(|(_, v)| v.clone())
    }

    pub fn unanswered(&self, name: &str, indices: &[RtValue]) {
        *self.unanswered.borrow_mut() = Some(UnansweredRead {
            name: name.to_owned(),
            indices: indices.to_vec(),
        });
        self.any.set(true);
    }

    pub fn take_unanswered(&self) -> Option<UnansweredRead> {
        self.unanswered.borrow_mut().take()
    }

    pub fn answer(&self, read: UnansweredRead, value: RtValue) {
        self.answered.borrow_mut().push((read, value));
        self.any.set(true);
    }

    /// The instruction is done: its answers are not kept.
    pub fn instruction_done(&self) {
        if self.any.replace(false) {
            self.answered.borrow_mut().clear();
            *self.unanswered.borrow_mut() = None;
        }
    }
}

impl Channel<'_> {
    /// Takes the machine's answer to what `instruction` asked: the events
    /// it reported are emitted there; `Ready` gives the result, `Pending`
    /// keeps `action` and `continuation` for the application (and gives
    /// `None`), `Error` is the alarm [`codes::run::MACHINE_ERROR`].
    pub(super) fn machine_answer<T>(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        answer: Answer<T>,
        action: impl FnOnce() -> MachineAction,
        continuation: Continuation,
    ) -> Result<Option<T>, RunError> {
        self.emit_machine_events(program, instruction);
        self.book_machine_time();
        match answer {
            Answer::Ready(result) => Ok(Some(result)),
            Answer::Pending(token) => {
                self.pending = Some(PendingAction {
                    token,
                    action: action(),
                    source: self.source(program, instruction),
                    continuation,
                    program: Arc::clone(program),
                    pc,
                    instruction: instruction.clone(),
                });
                Ok(None)
            }
            Answer::Error(error) => Err(machine_error(error)),
        }
    }

    /// The seconds the machine's own work took, to the active tool.
    fn book_machine_time(&mut self) {
        let elapsed = self.machine.take_elapsed();
        if elapsed > 0.0 {
            self.figures().machine_time += elapsed;
        }
    }

    /// Takes the machine's answer to an action with no result and nothing
    /// left to do after it: the next instruction, or a pause.
    pub(super) fn machine_done(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        answer: Answer<()>,
        action: impl FnOnce() -> MachineAction,
    ) -> Result<Flow, RunError> {
        let ready =
            self.machine_answer(program, pc, instruction, answer, action, Continuation::Next)?;
        Ok(if ready.is_some() {
            Flow::Next
        } else {
            Flow::Pending
        })
    }

    /// The events the machine reported, at `instruction`.
    fn emit_machine_events(&mut self, program: &Program, instruction: &Instruction) {
        if self.machine_events.is_empty() {
            return;
        }
        let source = self.source(program, instruction);
        self.emit_reported(&source);
    }

    /// Emits the events the machine reported at `source`.
    fn emit_reported(&mut self, source: &EventSource) {
        let mut events = std::mem::take(&mut self.machine_events);
        for kind in events.drain(..) {
            let event = Event {
                kind,
                source: source.clone(),
            };
            self.emit(&event);
        }
        self.machine_events = events;
    }

    /// A read the channel and the profile could not answer: the machine
    /// is asked. Its value runs the instruction again; `None` is the
    /// original alarm.
    pub(super) fn read_from_machine(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        read: UnansweredRead,
        unanswered: RunError,
    ) -> Flow {
        let answer = self.machine.system_variable(&read.name, &read.indices);
        let action = || MachineAction::SystemVariable {
            name: read.name.clone(),
            indices: read.indices.clone(),
        };
        let continuation = Continuation::Reread(read.clone());
        match self.machine_answer(program, pc, instruction, answer, action, continuation) {
            Ok(Some(Some(value))) => {
                self.state.machine_reads.answer(read, value);
                self.execute(program, pc, instruction)
            }
            Ok(Some(None)) => Flow::End(self.alarm(program, instruction, unanswered)),
            Ok(None) => Flow::Pending,
            Err(error) => Flow::End(self.alarm(program, instruction, error)),
        }
    }

    /// The application answers the pending action: the instruction's
    /// rest runs. `Some`: the run ended.
    pub(crate) fn resume_pending(
        &mut self,
        token: PendingToken,
        outcome: Outcome,
    ) -> Result<Option<ProgramEndReason>, SessionError> {
        let pending = self.pending.as_ref().ok_or(SessionError::NothingPending)?;
        if pending.token != token {
            return Err(SessionError::WrongToken {
                pending: pending.token,
                given: token,
            });
        }
        if !pending.action.is_answered_by(&outcome) {
            return Err(SessionError::WrongOutcome {
                action: pending.action.clone(),
                outcome,
            });
        }
        let pending = self.pending.take().ok_or(SessionError::NothingPending)?;
        let PendingAction {
            continuation,
            program,
            pc,
            instruction,
            ..
        } = pending;
        self.machine.resumed(token, &mut self.machine_events);
        self.emit_machine_events(&program, &instruction);
        self.book_machine_time();
        let flow = match (continuation, outcome) {
            (_, Outcome::Failed(error)) => {
                Flow::End(self.alarm(&program, &instruction, machine_error(error)))
            }
            // The instruction runs again, in its block, with the answer:
            // the program counter stays at it.
            (Continuation::Reread(read), Outcome::Value(Some(value))) => {
                self.state.machine_reads.answer(read, value);
                return Ok(None);
            }
            (Continuation::ToolChange(change), outcome) => {
                // `is_answered_by` let only a change's outcome through.
                let Outcome::ToolChanged(result) = outcome else {
                    return Err(SessionError::NothingPending);
                };
                match self.finish_change(&program, &instruction, *change, result) {
                    Ok(()) => Flow::Next,
                    Err(error) => Flow::End(self.alarm(&program, &instruction, error)),
                }
            }
            (Continuation::Reread(_), _) => {
                let error = RunError::new(
                    codes::run::SYSTEM_VARIABLE,
                    "the machine has no value for the system variable either",
                );
                Flow::End(self.alarm(&program, &instruction, error))
            }
            (
                Continuation::MAction {
                    action,
                    value,
                    extension,
                },
                _,
            ) => match self.m_action(&program, pc, &instruction, action, value, extension) {
                Ok(flow) => flow,
                Err(error) => Flow::End(self.alarm(&program, &instruction, error)),
            },
            (Continuation::Next, _) => Flow::Next,
        };
        Ok(self.go_on(pc, flow))
    }

    /// Sets the stack's program counter after the instruction at `pc`
    /// finished with `flow`. `Some`: the run ended.
    fn go_on(&mut self, pc: usize, flow: Flow) -> Option<ProgramEndReason> {
        match flow {
            Flow::Next => {
                if let Some(top) = self.stack.last_mut() {
                    top.pc = pc + 1;
                }
            }
            Flow::Jump(target) => {
                if let Some(top) = self.stack.last_mut() {
                    top.pc = target;
                }
                self.block.transferred = true;
            }
            Flow::Switch => self.block.transferred = true,
            Flow::End(reason) => return Some(reason),
            Flow::Pending => {}
        }
        None
    }

    /// The application cancels the run: the machine abandons what it was
    /// doing, the diagnostic names where the run stopped.
    pub(crate) fn cancel(&mut self) -> ProgramEndReason {
        let source = match self.pending.take() {
            Some(pending) => pending.source,
            None => self.last_source(),
        };
        self.machine
            .abort(AbortCause::Cancelled, &mut self.machine_events);
        self.emit_reported(&source);
        self.count(Severity::Error);
        let mut diagnostic = crate::event::DiagnosticEvent::new(
            codes::run::CANCELLED,
            "the run was cancelled".to_owned(),
        );
        diagnostic.severity = Severity::Error;
        let event = Event {
            kind: EventKind::Diagnostic(diagnostic),
            source,
        };
        self.emit(&event);
        ProgramEndReason::Cancelled
    }

    /// The run ends in an alarm: the machine abandons a change in
    /// progress.
    pub(super) fn abort_machine(&mut self, cause: AbortCause) {
        self.machine.abort(cause, &mut self.machine_events);
        if !self.machine_events.is_empty() {
            let source = self.last_source();
            self.emit_reported(&source);
        }
    }

    /// A run that cannot wait: the pending action ends it with an alarm.
    pub(crate) fn unanswered(&mut self) -> ProgramEndReason {
        let Some(pending) = self.pending.take() else {
            return ProgramEndReason::Alarm;
        };
        let error = RunError::new(
            codes::run::MACHINE_ACTION_UNANSWERED,
            format!(
                "the machine left {} pending, and this run cannot wait for it",
                describe(&pending.action)
            ),
        )
        .with_help("step the run with a Session, which resumes pending machine actions");
        self.alarm(&pending.program, &pending.instruction, error)
    }

    /// Tells the machine a block starts, if it watches blocks.
    pub(super) fn machine_block(&mut self, program: &Program, instruction: &Instruction) {
        let level = self.program_level();
        self.machine
            .block_started(instruction.source.line, level, &mut self.machine_events);
        self.emit_machine_events(program, instruction);
    }

    /// The machine the run talks to.
    pub fn machine(&self) -> &dyn Machine {
        &*self.machine
    }

    /// What the run waits for, if anything.
    pub(crate) fn pending(&self) -> Option<&PendingAction> {
        self.pending.as_ref()
    }
}

/// The alarm of a machine action that failed.
fn machine_error(error: MachineError) -> RunError {
    RunError::new(
        codes::run::MACHINE_ERROR,
        format!("the machine reports: {}", error.message),
    )
}

/// The action in words, for messages.
fn describe(action: &MachineAction) -> String {
    match action {
        MachineAction::PrepareTool { tool } => {
            format!("the prepare of {}", tool.as_deref().unwrap_or("no tool"))
        }
        MachineAction::ChangeTool { tool, .. } => {
            format!("the change to {}", tool.as_deref().unwrap_or("no tool"))
        }
        MachineAction::AuxiliaryFunction(AuxiliaryFunction::M { value, .. }) => {
            format!("the output of M{value}")
        }
        MachineAction::AuxiliaryFunction(AuxiliaryFunction::H { value, .. }) => {
            format!("the output of H{value}")
        }
        MachineAction::Wait(Wait::Dwell { seconds }) => format!("a dwell of {seconds} s"),
        MachineAction::SystemVariable { name, .. } => format!("the read of `{name}`"),
    }
}
