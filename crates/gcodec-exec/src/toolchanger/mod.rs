//! The toolchanger: the toolchanger protocol (LinuxCNC's iocontrol v2)
//! between the executor and the machine's changer, stepping in cycles
//! (SPEC §12, `docs/toolchanger.md`).
//!
//! [`Toolchanger`] is what the executor's machine asks of a changer, one
//! request or one cycle at a time, so that an application can step it or
//! answer late. [`SimulatedChanger`] is the default: the protocol
//! (`protocol.rs`) with a changer scripted by a scenario (`device.rs`)
//! and the pocket bookkeeping (`pockets.rs`). The blocking helpers
//! [`prepare`], [`change`] and [`abort`] (`task.rs`) are the executor's
//! rules over any changer: what a fault, an abort or a missing
//! acknowledgement does to the operation, and which tool is in the
//! spindle afterwards.
//!
//! Every protocol edge is a [`ToolchangerEvent`] (`event.rs`; the runtime
//! event kind `toolchanger`) appended to the vector the caller passes; the caller adds the source position when it emits
//! them as runtime events.

mod device;
mod event;
mod pockets;
mod protocol;
mod reason;
mod simulated;
mod task;

pub use protocol::{AbortPending, ChangerState, Inputs, Outputs, Protocol};
pub use reason::{AbortReason, FaultReason};
pub use simulated::SimulatedChanger;
pub use task::{AbortOutcome, ChangeOutcome, PrepareOutcome, Report, abort, change, prepare};

pub use event::{ToolchangerEdge, ToolchangerEvent};

/// A tool as the changer knows it: its number and its name as the run's
/// `tool_change` event gives it (`T3`, or the tool's name with tool
/// management).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct ChangerTool {
    pub number: u32,
    pub label: String,
}

/// What a prepare left for the next change: a tool, or none (an unload,
/// `T0`), and its pocket.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Prepared {
    pub tool: Option<ChangerTool>,
    pub pocket: Option<u32>,
}

/// How a changer answers a request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Answer {
    /// The request is raised; cycle until it is answered.
    Raised,
    /// The tool asked for is in the spindle already: no handshake.
    AlreadyInSpindle,
    /// A change with nothing prepared: no handshake.
    NothingPrepared,
    /// A start-change on a changer without it.
    NotSupported,
    /// An abort is pending: nothing starts before its acknowledgement (for
    /// an abort: the pending one keeps its reason).
    AbortPending(AbortReason),
}

/// Where the requested operation stands after a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Not answered yet.
    Busy,
    /// Acknowledged (or nothing was requested).
    Done,
    /// A fault or an abort stopped it: a fault is latched at start-change
    /// or an abort is pending (cycle on until it is acknowledged).
    Failed,
}

/// What the executor's machine asks of a toolchanger. Object-safe: a run
/// holds a `Box<dyn Toolchanger>`.
pub trait Toolchanger {
    /// Whether a change starts with the start-change handshake.
    fn supports_start_change(&self) -> bool;

    /// Cycles an acknowledgement may take before the operation aborts
    /// with reason 102.
    fn timeout_cycles(&self) -> u32;

    /// Seconds a cycle takes, for the run's time estimate.
    fn cycle_time(&self) -> f64;

    /// Prepares `tool` (`None`: no tool, an unload).
    fn request_prepare(
        &mut self,
        tool: Option<ChangerTool>,
        events: &mut Vec<ToolchangerEvent>,
    ) -> Answer;

    /// Raises the start-change handshake.
    fn request_start_change(&mut self, events: &mut Vec<ToolchangerEvent>) -> Answer;

    /// Raises the change to the prepared tool.
    fn request_change(&mut self, events: &mut Vec<ToolchangerEvent>) -> Answer;

    /// Aborts whatever is requested, with `reason`.
    fn request_abort(&mut self, reason: AbortReason, events: &mut Vec<ToolchangerEvent>) -> Answer;

    /// Drops an abort the changer never acknowledged: the changer is idle
    /// and nothing waits.
    fn withdraw_abort(&mut self);

    /// Advances one cycle.
    fn cycle(&mut self, events: &mut Vec<ToolchangerEvent>) -> Status;

    /// Line `line` of the main program starts (the changer counts the
    /// passes itself), for what is to happen at a block.
    fn block(&mut self, line: u32, events: &mut Vec<ToolchangerEvent>);

    fn state(&self) -> ChangerState;

    /// The latched fault and its reason.
    fn fault(&self) -> Option<FaultReason>;

    /// The reason of the abort pending, if one is.
    fn pending_abort(&self) -> Option<AbortReason>;

    /// What the last prepare left for the next change.
    fn prepared(&self) -> Option<&Prepared>;

    /// The tool in the spindle; `None` for none.
    fn tool_in_spindle(&self) -> Option<&ChangerTool>;

    /// The pocket of tool `number` (0 for the spindle's on a random
    /// changer).
    fn pocket_of(&self, number: u32) -> Option<u32>;

    /// Cycles since the changer started.
    fn cycles(&self) -> u64;
}
