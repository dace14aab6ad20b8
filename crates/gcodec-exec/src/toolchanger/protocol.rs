//! The executor's side of the toolchanger protocol (iocontrol v2's io
//! side), pure: the state, the latched fault, the output and input pins,
//! and [`Protocol::cycle`], which applies the per-cycle rules in iov2's
//! order and reports the edges it saw. Which tool is prepared or in the
//! spindle is not a pin matter; the changer that owns the protocol keeps
//! it (`simulated.rs`).
//!
//! Where iov2's code and documentation disagree, this follows the safer
//! reading (SPEC §12.3): a pending abort refuses new requests, clear-fault
//! acts only while the fault line is low, and a second abort does not
//! overwrite the reason of the one pending.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::ToolchangerEdge;
use super::reason::{AbortReason, FaultReason};

/// The protocol's state, numbered as iov2's `state` pin.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ChangerState {
    #[default]
    Idle = 0,
    Preparing = 1,
    /// Start-change raised, or acknowledged and the change not yet raised
    /// (iov2 keeps the pin at 2 until the change).
    StartChange = 2,
    Changing = 3,
    WaitingForAbortAck = 4,
}

impl ChangerState {
    /// The number of iov2's `state` pin.
    pub fn number(self) -> u8 {
        self as u8
    }

    /// The JSON name (`waiting_for_abort_ack`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Idle => "idle",
            Self::Preparing => "preparing",
            Self::StartChange => "start_change",
            Self::Changing => "changing",
            Self::WaitingForAbortAck => "waiting_for_abort_ack",
        }
    }
}

/// The pins the executor's side drives.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Outputs {
    /// `tool-prepare`.
    pub prepare: bool,
    /// `tool-prep-number`: the tool being prepared, 0 for none.
    pub prep_number: u32,
    /// `tool-prep-pocket`.
    pub prep_pocket: u32,
    /// `start-change`.
    pub start_change: bool,
    /// `tool-change`.
    pub change: bool,
    /// `emc-abort`.
    pub abort: bool,
    /// `emc-reason`, valid while `abort` is high.
    pub abort_reason: AbortReason,
    /// `toolchanger-fault-ack`: follows the fault line once it is read.
    pub fault_ack: bool,
}

/// The pins the changer drives.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Inputs {
    /// `tool-prepared`.
    pub prepared: bool,
    /// `start-change-ack`.
    pub start_change_ack: bool,
    /// `tool-changed`.
    pub changed: bool,
    /// `emc-abort-ack`.
    pub abort_ack: bool,
    /// `toolchanger-fault`.
    pub fault: bool,
    /// `toolchanger-reason`, read while `fault` is high.
    pub fault_reason: i32,
    /// `toolchanger-clear-fault`.
    pub clear_fault: bool,
}

/// A request the protocol refused: an abort waits for its
/// acknowledgement, and nothing starts before it comes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct AbortPending(pub AbortReason);

/// The executor's side of the protocol.
#[derive(Clone, Debug, Default)]
pub struct Protocol {
    state: ChangerState,
    outputs: Outputs,
    /// `toolchanger-faulted` and the reason read with it.
    fault: Option<FaultReason>,
}

impl Protocol {
    /// Idle, with `fault` latched (a session's state carried into a run).
    pub fn new(fault: Option<FaultReason>) -> Self {
        Self {
            fault,
            ..Self::default()
        }
    }

    pub fn state(&self) -> ChangerState {
        self.state
    }

    pub fn outputs(&self) -> &Outputs {
        &self.outputs
    }

    /// The latched fault, `toolchanger-faulted` with its reason.
    pub fn fault(&self) -> Option<FaultReason> {
        self.fault
    }

    /// The reason of the abort pending, if one is.
    pub fn pending_abort(&self) -> Option<AbortReason> {
        self.outputs.abort.then_some(self.outputs.abort_reason)
    }

    fn refuse_while_aborting(&self) -> Result<(), AbortPending> {
        match self.pending_abort() {
            Some(reason) => Err(AbortPending(reason)),
            None => Ok(()),
        }
    }

    /// Raises `tool-prepare` for `number` (0: no tool) in `pocket`.
    pub fn prepare(&mut self, number: u32, pocket: u32) -> Result<(), AbortPending> {
        self.refuse_while_aborting()?;
        self.outputs.prep_number = number;
        self.outputs.prep_pocket = pocket;
        self.outputs.prepare = true;
        self.state = ChangerState::Preparing;
        Ok(())
    }

    /// Raises `start-change`.
    pub fn start_change(&mut self) -> Result<(), AbortPending> {
        self.refuse_while_aborting()?;
        self.outputs.start_change = true;
        self.state = ChangerState::StartChange;
        Ok(())
    }

    /// Raises `tool-change`. A start-change still unacknowledged is
    /// withdrawn: the change supersedes it, and no request is left
    /// waiting.
    pub fn change(&mut self) -> Result<(), AbortPending> {
        self.refuse_while_aborting()?;
        self.outputs.start_change = false;
        self.outputs.change = true;
        self.state = ChangerState::Changing;
        Ok(())
    }

    /// Ends a start-change that no change follows (the prepared tool is
    /// in the spindle): iov2 leaves the state at 2 until the next command;
    /// gcodec returns to idle, so that nothing looks under way.
    pub fn end_start_change(&mut self) {
        if self.state == ChangerState::StartChange {
            self.outputs.start_change = false;
            self.state = ChangerState::Idle;
        }
    }

    /// Raises `emc-abort` with `reason` and drops every request (the
    /// reason first, as iov2 orders it). With an abort already pending,
    /// nothing changes and `false` is returned: the changer latched the
    /// first reason on the rising edge, and a later one would not reach
    /// it.
    pub fn abort(&mut self, reason: AbortReason) -> bool {
        if self.outputs.abort {
            return false;
        }
        self.outputs.abort_reason = reason;
        self.outputs.abort = true;
        self.outputs.change = false;
        self.outputs.prepare = false;
        self.outputs.start_change = false;
        self.state = ChangerState::WaitingForAbortAck;
        true
    }

    /// Drops an abort the changer never acknowledged, so that nothing
    /// stays waiting (LinuxCNC issue 3675).
    pub fn withdraw_abort(&mut self) {
        self.outputs.abort = false;
        self.state = ChangerState::Idle;
    }

    /// One cycle: the rules of iov2's `read_inputs`, in its order. The
    /// edges seen are appended to `edges`, each with the state after it.
    pub fn cycle(&mut self, inputs: &Inputs, edges: &mut Vec<(ToolchangerEdge, ChangerState)>) {
        // 1. The fault latch: a fault line read sets it (and a new reason
        // replaces the old one).
        if inputs.fault {
            let reason = FaultReason(inputs.fault_reason);
            if self.fault != Some(reason) {
                edges.push((ToolchangerEdge::FaultLatched, self.state));
            }
            self.fault = Some(reason);
            self.outputs.fault_ack = true;
        } else {
            self.outputs.fault_ack = false;
        }
        // 2. Clear, only while the fault line is low: iov2 clears
        // regardless and latches again a cycle later, so that for a cycle
        // the next change would not see a fault that is still there.
        if inputs.clear_fault && !inputs.fault && self.fault.take().is_some() {
            edges.push((ToolchangerEdge::FaultCleared, self.state));
        }
        // 3. The abort handshake.
        if self.outputs.abort && inputs.abort_ack {
            self.outputs.abort = false;
            self.state = ChangerState::Idle;
            edges.push((ToolchangerEdge::AbortAcknowledged, self.state));
        }
        // 4. Start-change: the state stays until the change is raised.
        if self.outputs.start_change && inputs.start_change_ack {
            self.outputs.start_change = false;
            edges.push((ToolchangerEdge::StartChangeAcknowledged, self.state));
        }
        // 5. Prepare.
        if self.outputs.prepare && inputs.prepared {
            self.outputs.prepare = false;
            self.state = ChangerState::Idle;
            edges.push((ToolchangerEdge::PrepareAcknowledged, self.state));
        }
        // 6. Change: a latched fault aborts it (reason 101), else the
        // acknowledgement commits it.
        if self.outputs.change {
            if self.fault.is_some() {
                self.outputs.change = false;
                self.outputs.abort_reason = AbortReason::TOOLCHANGER_FAULT;
                self.outputs.abort = true;
                self.state = ChangerState::WaitingForAbortAck;
                edges.push((ToolchangerEdge::AbortRaised, self.state));
            } else if inputs.changed {
                self.outputs.change = false;
                self.outputs.prep_number = 0;
                self.outputs.prep_pocket = 0;
                self.state = ChangerState::Idle;
                edges.push((ToolchangerEdge::ChangeAcknowledged, self.state));
                edges.push((ToolchangerEdge::ChangeCommitted, self.state));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ToolchangerEdge as E;

    fn cycle(protocol: &mut Protocol, inputs: Inputs) -> Vec<ToolchangerEdge> {
        let mut edges = Vec::new();
        protocol.cycle(&inputs, &mut edges);
        edges.into_iter().map(|(edge, _)| edge).collect()
    }

    #[test]
    fn states_are_numbered_as_iov2_s_state_pin() {
        let numbers = [
            ChangerState::Idle,
            ChangerState::Preparing,
            ChangerState::StartChange,
            ChangerState::Changing,
            ChangerState::WaitingForAbortAck,
        ]
        .map(ChangerState::number);
        assert_eq!(numbers, [0, 1, 2, 3, 4]);
    }

    #[test]
    fn a_pending_abort_refuses_further_requests() {
        let mut p = Protocol::default();
        assert!(p.abort(AbortReason::ESTOP_RESET));
        assert_eq!(p.prepare(1, 1), Err(AbortPending(AbortReason::ESTOP_RESET)));
        assert_eq!(
            p.start_change(),
            Err(AbortPending(AbortReason::ESTOP_RESET))
        );
        assert_eq!(p.change(), Err(AbortPending(AbortReason::ESTOP_RESET)));
        // iov2 would have overwritten the state with 1 here.
        assert_eq!(p.state(), ChangerState::WaitingForAbortAck);
        let acked = cycle(
            &mut p,
            Inputs {
                abort_ack: true,
                ..Inputs::default()
            },
        );
        assert_eq!(acked, [E::AbortAcknowledged]);
        assert_eq!(p.prepare(1, 1), Ok(()));
    }

    #[test]
    fn clear_fault_while_the_fault_line_is_high_does_nothing() {
        let mut p = Protocol::default();
        let fault = Inputs {
            fault: true,
            fault_reason: -5,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, fault), [E::FaultLatched]);
        let both = Inputs {
            clear_fault: true,
            ..fault
        };
        assert_eq!(cycle(&mut p, both), []);
        assert_eq!(p.fault(), Some(FaultReason(-5)));
        let cleared = Inputs {
            clear_fault: true,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, cleared), [E::FaultCleared]);
        assert_eq!(p.fault(), None);
        assert!(!p.outputs().fault_ack);
    }

    #[test]
    fn a_later_abort_does_not_overwrite_the_pending_reason() {
        let mut p = Protocol::default();
        p.change().expect("idle");
        let fault = Inputs {
            fault: true,
            fault_reason: -9,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, fault), [E::FaultLatched, E::AbortRaised]);
        assert_eq!(p.pending_abort(), Some(AbortReason::TOOLCHANGER_FAULT));
        // LinuxCNC's task sends reason 3 now, and iov2 overwrites 101.
        assert!(!p.abort(AbortReason::MOTION_OR_IO_ERROR));
        assert_eq!(p.outputs().abort_reason, AbortReason::TOOLCHANGER_FAULT);
    }

    #[test]
    fn a_change_acknowledged_is_committed_in_the_same_cycle() {
        let mut p = Protocol::default();
        p.prepare(3, 3).expect("idle");
        let prepared = Inputs {
            prepared: true,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, prepared), [E::PrepareAcknowledged]);
        p.start_change().expect("idle");
        let acked = Inputs {
            start_change_ack: true,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, acked), [E::StartChangeAcknowledged]);
        assert_eq!(p.state(), ChangerState::StartChange);
        p.change().expect("idle");
        let changed = Inputs {
            changed: true,
            ..Inputs::default()
        };
        assert_eq!(
            cycle(&mut p, changed),
            [E::ChangeAcknowledged, E::ChangeCommitted]
        );
        assert_eq!(p.state(), ChangerState::Idle);
        assert_eq!(p.outputs().prep_number, 0);
    }

    #[test]
    fn a_latched_fault_aborts_a_change_even_when_the_changer_acknowledges() {
        let mut p = Protocol::new(Some(FaultReason(7)));
        p.change().expect("idle");
        let changed = Inputs {
            changed: true,
            ..Inputs::default()
        };
        assert_eq!(cycle(&mut p, changed), [E::AbortRaised]);
        assert_eq!(p.state(), ChangerState::WaitingForAbortAck);
    }

    #[test]
    fn an_abort_never_acknowledged_can_be_withdrawn() {
        let mut p = Protocol::default();
        p.prepare(1, 1).expect("idle");
        p.abort(AbortReason::USER_ABORT);
        assert!(!p.outputs().prepare);
        p.withdraw_abort();
        assert_eq!(p.state(), ChangerState::Idle);
        assert_eq!(p.pending_abort(), None);
    }
}
