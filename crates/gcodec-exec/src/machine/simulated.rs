//! The machine `gcodec run` runs against.

use gcodec_profile::{Profile, Scenario};
use gcodec_source::Diagnostic;

use super::{
    AbortCause, Answer, ChangeResult, Machine, MachineError, MachineEvents, MachineTool,
    ToolRequest,
};
use crate::event::{EventKind, MessageEvent};
use crate::toolchanger::{
    self, AbortReason, ChangeOutcome, ChangerState, ChangerTool, FaultReason, PrepareOutcome,
    SimulatedChanger, Toolchanger, ToolchangerEvent,
};

/// A machine that answers every call at once: M and H functions are
/// taken, waits take their time in the estimate only. Tool prepares and
/// changes go through a toolchanger when the machine has one (the
/// profile's `[toolchanger]` table, or a scenario), stepped cycle by
/// cycle until it answers; without one a change is made at once, and a
/// run against it is the run of a channel with no machine behind it.
pub struct SimulatedMachine {
    changer: Option<Box<dyn Toolchanger>>,
    /// The changer's edges of one operation, reused.
    edges: Vec<ToolchangerEvent>,
    /// Seconds of toolchanger cycles not yet handed to the run.
    elapsed: f64,
}

impl SimulatedMachine {
    /// The machine of `profile`: with the simulated toolchanger of its
    /// `[toolchanger]` table (acknowledging every handshake after one
    /// cycle), or without a toolchanger.
    pub fn new(profile: &Profile) -> Self {
        // The default scenario names no tool, the one thing that can fail.
        let changer = profile
            .toolchanger
            .as_ref()
            .and_then(|_| SimulatedChanger::new(profile, &Scenario::default()).ok());
        Self::with_changer(changer.map(|c| Box::new(c) as Box<dyn Toolchanger>))
    }

    /// The machine of `profile` with the simulated toolchanger behaving as
    /// `scenario` says (a toolchanger with the `[toolchanger]` table's
    /// settings, or its defaults). A scenario's `initial_tool` the tool
    /// table lacks is `gcodec::scenario::unknown_tool`.
    pub fn with_scenario(profile: &Profile, scenario: &Scenario) -> Result<Self, Diagnostic> {
        let changer = SimulatedChanger::new(profile, scenario)?;
        Ok(Self::with_changer(Some(Box::new(changer))))
    }

    /// The machine with `changer` (an application's own), or none.
    pub fn with_changer(changer: Option<Box<dyn Toolchanger>>) -> Self {
        Self {
            changer,
            edges: Vec::new(),
            elapsed: 0.0,
        }
    }

    /// Hands the changer's edges over as events, and counts its cycles.
    fn report(&mut self, cycles: u64, cycle_time: f64, events: &mut MachineEvents) {
        self.elapsed += cycles as f64 * cycle_time;
        self.hand_over(events);
    }

    fn hand_over(&mut self, events: &mut MachineEvents) {
        events.extend(self.edges.drain(..).map(EventKind::Toolchanger));
    }
}

/// The alarm's reason for an operation the changer aborted.
fn aborted(
    what: &str,
    tool: Option<&str>,
    abort: AbortReason,
    fault: Option<FaultReason>,
) -> MachineError {
    let tool = tool.unwrap_or("no tool");
    let fault = match fault {
        Some(FaultReason(reason)) => format!(", toolchanger fault {reason}"),
        None => String::new(),
    };
    MachineError::new(format!(
        "the toolchanger aborted the {what} of {tool} (abort reason {}: {}{fault})",
        abort.0,
        abort.describe()
    ))
}

/// A hard fault with a reason below 0 shows the operator a message before
/// the alarm, as LinuxCNC's `[TASK]IO_ERROR` (`toolchanger error %d`)
/// does; a reason of 0 aborts without one.
fn operator_message(fault: Option<FaultReason>, events: &mut MachineEvents) {
    if let Some(FaultReason(reason)) = fault.filter(|f| f.0 < 0) {
        events.push(EventKind::Message(MessageEvent {
            text: format!("toolchanger error {reason}"),
        }));
    }
}

fn changer_tool(request: &ToolRequest<'_>) -> Option<ChangerTool> {
    request.tool.map(|label| ChangerTool {
        number: request.number,
        label: label.to_owned(),
    })
}

impl Machine for SimulatedMachine {
    fn prepare_tool(
        &mut self,
        request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<()> {
        let Some(changer) = self.changer.as_deref_mut() else {
            return Answer::Ready(());
        };
        let report = toolchanger::prepare(changer, changer_tool(request), &mut self.edges);
        let cycle_time = changer.cycle_time();
        self.report(report.cycles, cycle_time, events);
        match report.outcome {
            PrepareOutcome::Prepared | PrepareOutcome::AlreadyInSpindle => Answer::Ready(()),
            PrepareOutcome::Aborted {
                abort_reason,
                fault_reason,
            } => {
                operator_message(fault_reason, events);
                Answer::Error(aborted("prepare", request.tool, abort_reason, fault_reason))
            }
        }
    }

    fn change_tool(
        &mut self,
        request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<ChangeResult> {
        let Some(changer) = self.changer.as_deref_mut() else {
            return Answer::Ready(ChangeResult::COMMITTED);
        };
        let report = toolchanger::change(changer, &mut self.edges);
        let cycle_time = changer.cycle_time();
        self.report(report.cycles, cycle_time, events);
        match report.outcome {
            ChangeOutcome::Committed | ChangeOutcome::AlreadyInSpindle => {
                Answer::Ready(ChangeResult::COMMITTED)
            }
            // An abort dropped the prepare: the tool stays.
            ChangeOutcome::NotPrepared => Answer::Ready(ChangeResult {
                committed: false,
                fault_reason: None,
            }),
            ChangeOutcome::Skipped { fault_reason } => Answer::Ready(ChangeResult {
                committed: false,
                fault_reason: Some(fault_reason.0),
            }),
            ChangeOutcome::Aborted {
                abort_reason,
                fault_reason,
            } => {
                operator_message(fault_reason, events);
                Answer::Error(aborted("change", request.tool, abort_reason, fault_reason))
            }
        }
    }

    /// An operation in progress is aborted (reason 8 for a cancelled run,
    /// 1 for an alarm); an idle changer is left alone (no abort is raised
    /// for nothing, SPEC §12).
    fn abort(&mut self, cause: AbortCause, events: &mut MachineEvents) {
        let Some(changer) = self.changer.as_deref_mut() else {
            return;
        };
        if changer.state() == ChangerState::Idle && changer.pending_abort().is_none() {
            return;
        }
        let reason = match cause {
            AbortCause::Cancelled => AbortReason::USER_ABORT,
            AbortCause::Alarm => AbortReason::TASK_EXEC_ERROR,
        };
        let report = toolchanger::abort(changer, reason, &mut self.edges);
        let cycle_time = changer.cycle_time();
        self.report(report.cycles, cycle_time, events);
    }

    fn watches_blocks(&self) -> bool {
        self.changer.is_some()
    }

    /// A block of the main program: the scenario's `"block"` injections.
    fn block_started(&mut self, line: u32, level: u32, events: &mut MachineEvents) {
        if level != 0 {
            return;
        }
        if let Some(changer) = self.changer.as_deref_mut() {
            changer.block(line, &mut self.edges);
            self.hand_over(events);
        }
    }

    fn take_elapsed(&mut self) -> f64 {
        std::mem::take(&mut self.elapsed)
    }

    fn toolchanger(&self) -> Option<&dyn Toolchanger> {
        self.changer.as_deref()
    }

    fn initial_tool(&self) -> Option<MachineTool> {
        let tool = self.changer.as_deref()?.tool_in_spindle()?;
        Some(MachineTool {
            label: tool.label.clone(),
            number: tool.number,
        })
    }
}
