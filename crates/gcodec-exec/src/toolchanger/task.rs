//! The executor's rules over any [`Toolchanger`] (LinuxCNC's "task"
//! side): [`prepare`], [`change`] and [`abort`] request, cycle until the
//! changer answers, and decide what a fault, an abort or a missing
//! acknowledgement does. Each wait is bounded by the changer's
//! `timeout_cycles`, so every operation ends; each ends with the changer
//! idle and nothing waiting (LinuxCNC issue 3675), and its [`Report`] says
//! which tool is in the spindle.

use super::reason::{AbortReason, FaultReason};
use super::{Answer, ChangerState, ChangerTool, Status, Toolchanger, ToolchangerEvent};

/// How an operation ended, the tool in the spindle afterwards and the
/// cycles it took (its time is `cycles × cycle_time`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Report<O> {
    pub outcome: O,
    pub spindle: Option<ChangerTool>,
    pub cycles: u64,
}

/// How a prepare ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrepareOutcome {
    /// The changer acknowledged: the tool is ready for the change. A fault
    /// latched meanwhile does not stop a prepare; the change meets it.
    Prepared,
    /// A random changer with the tool in the spindle: no handshake, and
    /// the next change keeps the tool.
    AlreadyInSpindle,
    /// An abort (an operator's, or the timeout's) ended it.
    Aborted {
        abort_reason: AbortReason,
        fault_reason: Option<FaultReason>,
    },
}

/// How a change ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ChangeOutcome {
    /// The prepared tool is in the spindle.
    Committed,
    /// The prepared tool was in the spindle: no change handshake.
    AlreadyInSpindle,
    /// Nothing was prepared (or an abort dropped the prepare): no
    /// handshake, the tool stays.
    NotPrepared,
    /// A soft fault: the change is skipped, the tool stays, the program
    /// goes on.
    Skipped { fault_reason: FaultReason },
    /// A hard fault, an abort or a timeout: the tool stays, the program
    /// aborts.
    Aborted {
        abort_reason: AbortReason,
        fault_reason: Option<FaultReason>,
    },
}

/// How an abort ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AbortOutcome {
    /// The changer acknowledged the abort with this reason (the first
    /// one, when an abort was pending already).
    Acknowledged { abort_reason: AbortReason },
    /// No acknowledgement within the timeout: gcodec withdrew the abort,
    /// so that nothing waits.
    Unacknowledged { abort_reason: AbortReason },
}

/// How a wait for an answer ended.
enum Waited {
    Done,
    Failed,
    TimedOut,
}

/// Cycles until the changer answers, at most `timeout_cycles`.
fn wait(changer: &mut dyn Toolchanger, events: &mut Vec<ToolchangerEvent>) -> Waited {
    for _ in 0..changer.timeout_cycles().max(1) {
        match changer.cycle(events) {
            Status::Busy => {}
            Status::Done => return Waited::Done,
            Status::Failed => return Waited::Failed,
        }
    }
    Waited::TimedOut
}

fn report<O>(changer: &dyn Toolchanger, outcome: O, start: u64) -> Report<O> {
    Report {
        outcome,
        spindle: changer.tool_in_spindle().cloned(),
        cycles: changer.cycles().saturating_sub(start),
    }
}

/// Raises an abort with `reason` (or keeps the one pending) and waits for
/// its acknowledgement; withdraws it when none comes. The reason the
/// changer saw.
fn abort_and_wait(
    changer: &mut dyn Toolchanger,
    reason: AbortReason,
    events: &mut Vec<ToolchangerEvent>,
) -> AbortOutcome {
    let reason = match changer.request_abort(reason, events) {
        Answer::AbortPending(pending) => pending,
        _ => reason,
    };
    finish_abort(changer, reason, events)
}

/// Waits for the pending abort's acknowledgement; withdraws it when none
/// comes.
fn finish_abort(
    changer: &mut dyn Toolchanger,
    reason: AbortReason,
    events: &mut Vec<ToolchangerEvent>,
) -> AbortOutcome {
    if changer.state() != ChangerState::WaitingForAbortAck {
        return AbortOutcome::Acknowledged {
            abort_reason: reason,
        };
    }
    match wait(changer, events) {
        Waited::Done | Waited::Failed if changer.state() != ChangerState::WaitingForAbortAck => {
            AbortOutcome::Acknowledged {
                abort_reason: reason,
            }
        }
        _ => {
            changer.withdraw_abort();
            AbortOutcome::Unacknowledged {
                abort_reason: reason,
            }
        }
    }
}

/// An abort still pending from before is acknowledged (or withdrawn)
/// before anything new starts.
fn settle(changer: &mut dyn Toolchanger, events: &mut Vec<ToolchangerEvent>) {
    if let Some(reason) = changer.pending_abort() {
        finish_abort(changer, reason, events);
    }
}

/// Aborts with `reason`, or waits for the abort pending (the one that
/// failed the operation: the changer's for a fault, or one from outside);
/// the reason the changer saw.
fn aborted_with(
    changer: &mut dyn Toolchanger,
    reason: AbortReason,
    events: &mut Vec<ToolchangerEvent>,
) -> AbortReason {
    match abort_and_wait(changer, reason, events) {
        AbortOutcome::Acknowledged { abort_reason }
        | AbortOutcome::Unacknowledged { abort_reason } => abort_reason,
    }
}

/// The abort that failed an operation: the one pending.
fn failed(changer: &mut dyn Toolchanger, events: &mut Vec<ToolchangerEvent>) -> AbortReason {
    let pending = changer
        .pending_abort()
        .unwrap_or(AbortReason::MOTION_OR_IO_ERROR);
    aborted_with(changer, pending, events)
}

/// Waits for the answer to a request; when an abort fails it (or the
/// wait times out: reason 102), waits for that abort, and gives its
/// reason.
fn wait_or_abort(
    changer: &mut dyn Toolchanger,
    events: &mut Vec<ToolchangerEvent>,
) -> Option<AbortReason> {
    match wait(changer, events) {
        Waited::Done => None,
        Waited::Failed => Some(failed(changer, events)),
        Waited::TimedOut => Some(aborted_with(changer, AbortReason::ACK_TIMEOUT, events)),
    }
}

/// `T`: prepares `tool` (`None`: no tool, an unload) and waits until the
/// changer has it ready.
pub fn prepare(
    changer: &mut dyn Toolchanger,
    tool: Option<ChangerTool>,
    events: &mut Vec<ToolchangerEvent>,
) -> Report<PrepareOutcome> {
    let start = changer.cycles();
    settle(changer, events);
    let aborted = |changer: &dyn Toolchanger, abort_reason| PrepareOutcome::Aborted {
        abort_reason,
        fault_reason: changer.fault(),
    };
    let outcome = match changer.request_prepare(tool, events) {
        Answer::AlreadyInSpindle => PrepareOutcome::AlreadyInSpindle,
        Answer::AbortPending(reason) => aborted(changer, reason),
        _ => match wait_or_abort(changer, events) {
            None => PrepareOutcome::Prepared,
            Some(reason) => aborted(changer, reason),
        },
    };
    report(changer, outcome, start)
}

/// The change M: start-change first where the changer supports it, then
/// the change to the prepared tool. A latched fault is met at the
/// start-change (a hard one aborts with reason 3) or at the change (the
/// changer aborts it with reason 101: hard, the program aborts; soft, the
/// change is skipped).
pub fn change(
    changer: &mut dyn Toolchanger,
    events: &mut Vec<ToolchangerEvent>,
) -> Report<ChangeOutcome> {
    let start = changer.cycles();
    settle(changer, events);
    if changer.prepared().is_none() {
        return report(changer, ChangeOutcome::NotPrepared, start);
    }
    let aborted = |changer: &dyn Toolchanger, abort_reason| ChangeOutcome::Aborted {
        abort_reason,
        fault_reason: changer.fault(),
    };
    if changer.supports_start_change() {
        match changer.request_start_change(events) {
            Answer::Raised => match wait(changer, events) {
                Waited::Done => {}
                Waited::Failed if changer.pending_abort().is_some() => {
                    let reason = failed(changer, events);
                    return report(changer, aborted(changer, reason), start);
                }
                Waited::Failed => {
                    if changer.fault().is_some_and(FaultReason::is_hard) {
                        let reason = aborted_with(changer, AbortReason::MOTION_OR_IO_ERROR, events);
                        return report(changer, aborted(changer, reason), start);
                    }
                }
                Waited::TimedOut => {
                    let reason = aborted_with(changer, AbortReason::ACK_TIMEOUT, events);
                    return report(changer, aborted(changer, reason), start);
                }
            },
            Answer::AbortPending(reason) => {
                return report(changer, aborted(changer, reason), start);
            }
            _ => {}
        }
    }
    let outcome = match changer.request_change(events) {
        Answer::AlreadyInSpindle => ChangeOutcome::AlreadyInSpindle,
        Answer::NothingPrepared => ChangeOutcome::NotPrepared,
        Answer::AbortPending(reason) => aborted(changer, reason),
        _ => match wait_or_abort(changer, events) {
            None => ChangeOutcome::Committed,
            Some(reason) => match changer.fault() {
                Some(fault) if reason == AbortReason::TOOLCHANGER_FAULT && !fault.is_hard() => {
                    ChangeOutcome::Skipped {
                        fault_reason: fault,
                    }
                }
                _ => aborted(changer, reason),
            },
        },
    };
    report(changer, outcome, start)
}

/// Aborts whatever the changer does, with `reason`, and waits for the
/// acknowledgement: afterwards the changer is idle and nothing is
/// prepared.
pub fn abort(
    changer: &mut dyn Toolchanger,
    reason: AbortReason,
    events: &mut Vec<ToolchangerEvent>,
) -> Report<AbortOutcome> {
    let start = changer.cycles();
    let outcome = abort_and_wait(changer, reason, events);
    report(changer, outcome, start)
}
