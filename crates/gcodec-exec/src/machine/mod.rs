//! The machine behind the channel: what takes time or can fail outside
//! the NC program (SPEC §11.10).
//!
//! The channel hands a [`Machine`] the tool prepare and the tool change,
//! the M and H functions a PLC receives, the dwell it waits for, and the
//! reads of system variables that neither the channel nor the machine
//! profile answers. Each call answers [`Answer::Ready`] with its result,
//! [`Answer::Pending`] with a token (the machine is still working: a
//! [`crate::session::Session`] hands the token to the application, which
//! resumes the run with the outcome when the machine is done), or
//! [`Answer::Error`] with a reason (the run ends with an alarm).
//!
//! [`SimulatedMachine`] is the machine `gcodec run` runs against: it
//! answers every call at once, and drives the simulated toolchanger when
//! the profile has one.

mod simulated;

pub use simulated::SimulatedMachine;

use crate::event::EventKind;
use crate::toolchanger::Toolchanger;
use crate::value::RtValue;

/// Names one pending machine action of a run: the application answers it
/// with [`crate::session::Session::resume`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PendingToken(pub u64);

/// What a machine call answers.
#[derive(Clone, Debug, PartialEq)]
pub enum Answer<T> {
    /// Done, with the result.
    Ready(T),
    /// Still working: the run pauses until the token is resumed.
    Pending(PendingToken),
    /// Failed: the run ends with an alarm giving the reason.
    Error(MachineError),
}

/// Why a machine action failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MachineError {
    /// Said in the run's alarm (`gcodec::run::machine_error`).
    pub message: String,
}

impl MachineError {
    pub fn new(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
        }
    }
}

/// A tool the channel asks the machine to prepare or change to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ToolRequest<'a> {
    /// The tool as `tool_change` events name it (`T3`, a name with tool
    /// management); `None`: no tool (`T0`, an empty spindle).
    pub tool: Option<&'a str>,
    /// Its number in the tool table (0 for no tool).
    pub number: u32,
    /// The tool in the spindle before.
    pub previous: Option<&'a str>,
}

/// A tool as the machine names it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MachineTool {
    /// As `tool_change` events name it (`T3`, or its name).
    pub label: String,
    pub number: u32,
}

/// What a tool change did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ChangeResult {
    /// The new tool is in the spindle. `false`: a soft fault of the
    /// toolchanger skipped the change, the old tool stays and the program
    /// goes on.
    pub committed: bool,
    /// The toolchanger's fault reason when the change was skipped.
    pub fault_reason: Option<i32>,
}

impl ChangeResult {
    /// The change was made.
    pub const COMMITTED: Self = Self {
        committed: true,
        fault_reason: None,
    };
}

/// An auxiliary function output to the PLC.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AuxiliaryFunction {
    M { value: u32, extension: Option<u32> },
    H { value: f64, extension: Option<u32> },
}

/// Something the channel waits for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wait {
    /// `G4`: this long, seconds (revolutions already turned into time).
    Dwell { seconds: f64 },
}

/// Why the run stops a machine action in progress.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbortCause {
    /// The application cancelled the run (toolchanger abort reason 8,
    /// user abort).
    Cancelled,
    /// The run ended in an alarm (toolchanger abort reason 1).
    Alarm,
}

/// Events a machine reports with an answer (toolchanger protocol edges):
/// the channel gives them the position of the instruction that asked.
pub type MachineEvents = Vec<EventKind>;

/// The machine behind a channel. Every method has a default that answers
/// at once as a machine with no PLC and an instant tool change would; a
/// machine overrides what it does itself.
pub trait Machine {
    /// `T` with the change deferred to the change M: the tool is brought
    /// to the change position while the program goes on.
    fn prepare_tool(
        &mut self,
        _request: &ToolRequest<'_>,
        _events: &mut MachineEvents,
    ) -> Answer<()> {
        Answer::Ready(())
    }

    /// The change M (or `T` in direct mode): the tool goes into the
    /// spindle.
    fn change_tool(
        &mut self,
        _request: &ToolRequest<'_>,
        _events: &mut MachineEvents,
    ) -> Answer<ChangeResult> {
        Answer::Ready(ChangeResult::COMMITTED)
    }

    /// An M or H function output to the PLC (the change M excepted: that
    /// is [`Machine::change_tool`]).
    fn auxiliary_function(
        &mut self,
        _function: &AuxiliaryFunction,
        _events: &mut MachineEvents,
    ) -> Answer<()> {
        Answer::Ready(())
    }

    /// A system variable neither the channel nor the profile answers
    /// (upper-case name with its `$`, evaluated indices). `Ready(None)`:
    /// the machine does not know it either, the run's alarm
    /// `gcodec::run::system_variable` says so.
    fn system_variable(&mut self, _name: &str, _indices: &[RtValue]) -> Answer<Option<RtValue>> {
        Answer::Ready(None)
    }

    /// A wait of the channel.
    fn wait(&mut self, _wait: &Wait, _events: &mut MachineEvents) -> Answer<()> {
        Answer::Ready(())
    }

    /// The run stops while a machine action may be in progress: the
    /// machine abandons it safely (a toolchanger aborts with the cause's
    /// reason).
    fn abort(&mut self, _cause: AbortCause, _events: &mut MachineEvents) {}

    /// The application answered the pending action `token`: the machine
    /// reports the events of its work meanwhile (a toolchanger's edges),
    /// which the run emits at the instruction that asked, before it goes
    /// on.
    fn resumed(&mut self, _token: PendingToken, _events: &mut MachineEvents) {}

    /// Whether [`Machine::block_started`] is wanted: asked once, when the
    /// run starts, so that a machine that does not watch blocks costs
    /// nothing per block.
    fn watches_blocks(&self) -> bool {
        false
    }

    /// A block of the main program (`level` 0) or of a called one starts,
    /// at `line` of its file.
    fn block_started(&mut self, _line: u32, _level: u32, _events: &mut MachineEvents) {}

    /// Seconds the machine's own actions took since last asked (a tool
    /// change's cycles): the run adds them to its time estimate.
    fn take_elapsed(&mut self) -> f64 {
        0.0
    }

    /// The tool in the spindle when the run starts (`None`: none, as the
    /// channel assumes).
    fn initial_tool(&self) -> Option<MachineTool> {
        None
    }

    /// The machine's toolchanger, for the application to read its state
    /// and its latched fault and reason between steps (a program cannot
    /// read them, SPEC §12).
    fn toolchanger(&self) -> Option<&dyn Toolchanger> {
        None
    }
}

/// What a pending machine action is, for the application that answers it.
#[derive(Clone, Debug, PartialEq)]
pub enum MachineAction {
    PrepareTool {
        tool: Option<String>,
    },
    ChangeTool {
        tool: Option<String>,
        previous: Option<String>,
    },
    AuxiliaryFunction(AuxiliaryFunction),
    Wait(Wait),
    SystemVariable {
        name: String,
        indices: Vec<RtValue>,
    },
}

/// How the application answers a pending action: the result the machine
/// call would have given when ready.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// A prepare, an M or H function, a wait: done.
    Done,
    /// A tool change: done, with what it did.
    ToolChanged(ChangeResult),
    /// A system variable read: its value (`None`: the machine does not
    /// know it either).
    Value(Option<RtValue>),
    /// The action failed: the run ends with an alarm.
    Failed(MachineError),
}

impl MachineAction {
    /// Whether `outcome` answers this action.
    pub fn is_answered_by(&self, outcome: &Outcome) -> bool {
        matches!(
            (self, outcome),
            (_, Outcome::Failed(_))
                | (Self::ChangeTool { .. }, Outcome::ToolChanged(_))
                | (Self::SystemVariable { .. }, Outcome::Value(_))
                | (
                    Self::PrepareTool { .. } | Self::AuxiliaryFunction(_) | Self::Wait(_),
                    Outcome::Done
                )
        )
    }
}

/// A machine lent to a run: the application keeps it, and reads it when
/// the run is over.
impl<M: Machine + ?Sized> Machine for &mut M {
    fn prepare_tool(
        &mut self,
        request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<()> {
        (**self).prepare_tool(request, events)
    }

    fn change_tool(
        &mut self,
        request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<ChangeResult> {
        (**self).change_tool(request, events)
    }

    fn auxiliary_function(
        &mut self,
        function: &AuxiliaryFunction,
        events: &mut MachineEvents,
    ) -> Answer<()> {
        (**self).auxiliary_function(function, events)
    }

    fn system_variable(&mut self, name: &str, indices: &[RtValue]) -> Answer<Option<RtValue>> {
        (**self).system_variable(name, indices)
    }

    fn wait(&mut self, wait: &Wait, events: &mut MachineEvents) -> Answer<()> {
        (**self).wait(wait, events)
    }

    fn abort(&mut self, cause: AbortCause, events: &mut MachineEvents) {
        (**self).abort(cause, events);
    }

    fn resumed(&mut self, token: PendingToken, events: &mut MachineEvents) {
        (**self).resumed(token, events);
    }

    fn watches_blocks(&self) -> bool {
        (**self).watches_blocks()
    }

    fn block_started(&mut self, line: u32, level: u32, events: &mut MachineEvents) {
        (**self).block_started(line, level, events);
    }

    fn take_elapsed(&mut self) -> f64 {
        (**self).take_elapsed()
    }

    fn initial_tool(&self) -> Option<MachineTool> {
        (**self).initial_tool()
    }

    fn toolchanger(&self) -> Option<&dyn Toolchanger> {
        (**self).toolchanger()
    }
}
