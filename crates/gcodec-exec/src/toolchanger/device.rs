//! The changer's side of the pins, scripted by a [`Scenario`]: it
//! acknowledges each handshake `ack_cycles` after it sees the request
//! (and holds the acknowledgement while the request stays high, as the
//! fake changer of the recorded traces did), and fires the scenario's
//! injections at the operations and blocks they name.

use gcodec_profile::{InjectAction, InjectAt, Scenario};
use rustc_hash::FxHashMap;

use super::protocol::{Inputs, Outputs};
use super::reason::AbortReason;

/// The four handshakes; an operation of the run is one of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Handshake {
    Prepare,
    StartChange,
    Change,
    Abort,
}

const HANDSHAKES: usize = 4;

/// How the changer acknowledges one handshake.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Ack {
    Normal,
    Never,
    Late(u32),
}

/// One handshake as the changer follows it.
#[derive(Clone, Copy, Debug, Default)]
struct Tracker {
    /// The cycle the changer first saw the request, while it is high.
    seen_at: Option<u64>,
    /// The cycle from which it acknowledges; `None`: never.
    ack_from: Option<u64>,
    /// How the next request of this handshake is acknowledged.
    next: Option<Ack>,
}

/// An injection and whether it is armed (its operation or block has
/// started, at that cycle) or done.
#[derive(Clone, Debug)]
struct Armed {
    at: InjectAt,
    after_cycles: u32,
    action: InjectAction,
    armed_at: Option<u64>,
    done: bool,
}

/// The changer's fault line.
#[derive(Clone, Copy, Debug)]
struct FaultLine {
    reason: i32,
    /// The last cycle it is high; `None`: until a clear.
    until: Option<u64>,
}

#[derive(Clone, Debug)]
pub(crate) struct Device {
    ack_cycles: u32,
    trackers: [Tracker; HANDSHAKES],
    injections: Vec<Armed>,
    /// Operations of each handshake so far.
    counts: [u32; HANDSHAKES],
    /// Runs of each line of the main program so far.
    passes: FxHashMap<u32, u32>,
    fault: Option<FaultLine>,
    /// How the next handshake of any kind is acknowledged (an
    /// acknowledgement injection at a block).
    next_any: Option<Ack>,
}

/// What the changer's side does in one cycle.
pub(crate) struct Drive {
    pub(crate) inputs: Inputs,
    /// An abort the scenario raises on the executor's side now.
    pub(crate) abort: Option<AbortReason>,
}

impl Device {
    pub(crate) fn new(scenario: &Scenario) -> Self {
        Self {
            ack_cycles: scenario.ack_cycles.max(1),
            trackers: [Tracker::default(); HANDSHAKES],
            injections: scenario
                .inject
                .iter()
                .map(|i| Armed {
                    at: i.at,
                    after_cycles: i.after_cycles,
                    action: i.action,
                    armed_at: None,
                    done: false,
                })
                .collect(),
            counts: [0; HANDSHAKES],
            passes: FxHashMap::default(),
            fault: None,
            next_any: None,
        }
    }

    /// An operation starts (its request is raised) after cycle `cycle`:
    /// the injections for it are armed.
    pub(crate) fn operation(&mut self, handshake: Handshake, cycle: u64) {
        // A new request is a new rising edge, even when the pin was
        // dropped and raised again between two cycles.
        self.trackers[handshake as usize].seen_at = None;
        let count = &mut self.counts[handshake as usize];
        *count = count.saturating_add(1);
        let n = *count;
        for injection in &mut self.injections {
            let hit = match (injection.at, handshake) {
                (InjectAt::Prepare(k), Handshake::Prepare)
                | (InjectAt::StartChange(k), Handshake::StartChange)
                | (InjectAt::Change(k), Handshake::Change)
                | (InjectAt::Abort(k), Handshake::Abort) => k == n,
                _ => false,
            };
            if hit && injection.armed_at.is_none() {
                injection.armed_at = Some(cycle);
                if let Some(ack) = ack_of(injection.action) {
                    self.trackers[handshake as usize].next = Some(ack);
                    injection.done = true;
                }
            }
        }
    }

    /// Line `line` of the main program starts after cycle `cycle`; whether
    /// an injection is due in the next cycle.
    pub(crate) fn block(&mut self, line: u32, cycle: u64) -> bool {
        let pass = self.passes.entry(line).or_insert(0);
        *pass = pass.saturating_add(1);
        let pass = *pass;
        let mut due = false;
        for injection in &mut self.injections {
            if injection.at == (InjectAt::Block { line, pass }) && injection.armed_at.is_none() {
                injection.armed_at = Some(cycle);
                match ack_of(injection.action) {
                    Some(ack) => {
                        self.next_any = Some(ack);
                        injection.done = true;
                    }
                    None => due |= injection.after_cycles == 0,
                }
            }
        }
        due
    }

    /// The changer's side in cycle `cycle`: the injections due fire, then
    /// the inputs follow the outputs of the executor's side.
    pub(crate) fn drive(&mut self, outputs: &Outputs, cycle: u64) -> Drive {
        let mut clear = false;
        let mut abort = None;
        for injection in &mut self.injections {
            let due = !injection.done
                && injection
                    .armed_at
                    .is_some_and(|at| cycle > at.saturating_add(u64::from(injection.after_cycles)));
            if !due {
                continue;
            }
            injection.done = true;
            match injection.action {
                InjectAction::Fault {
                    reason,
                    hold_cycles,
                } => {
                    self.fault = Some(FaultLine {
                        reason,
                        until: hold_cycles
                            .map(|h| cycle.saturating_add(u64::from(h)).saturating_sub(1)),
                    });
                }
                InjectAction::Clear => {
                    clear = true;
                    if self.fault.is_some_and(|f| f.until.is_none()) {
                        self.fault = None;
                    }
                }
                InjectAction::Abort { reason } => abort = Some(AbortReason(reason)),
                InjectAction::NeverAck | InjectAction::DelayAck { .. } => {}
            }
        }
        let fault = self.fault;
        if self
            .fault
            .is_some_and(|f| f.until.is_some_and(|u| cycle >= u))
        {
            self.fault = None;
        }
        let requests = [
            outputs.prepare,
            outputs.start_change,
            outputs.change,
            outputs.abort,
        ];
        let mut acks = [false; HANDSHAKES];
        for (index, high) in requests.into_iter().enumerate() {
            acks[index] = self.follow(index, high, cycle);
        }
        Drive {
            inputs: Inputs {
                prepared: acks[Handshake::Prepare as usize],
                start_change_ack: acks[Handshake::StartChange as usize],
                changed: acks[Handshake::Change as usize],
                abort_ack: acks[Handshake::Abort as usize],
                fault: fault.is_some(),
                fault_reason: fault.map_or(0, |f| f.reason),
                clear_fault: clear,
            },
            abort,
        }
    }

    /// Follows one request pin; whether the changer acknowledges it now.
    fn follow(&mut self, index: usize, high: bool, cycle: u64) -> bool {
        let ack_cycles = u64::from(self.ack_cycles);
        let tracker = &mut self.trackers[index];
        if !high {
            tracker.seen_at = None;
            return false;
        }
        if tracker.seen_at.is_none() {
            tracker.seen_at = Some(cycle);
            let ack = tracker
                .next
                .take()
                .or_else(|| self.next_any.take())
                .unwrap_or(Ack::Normal);
            let normal = cycle.saturating_add(ack_cycles - 1);
            tracker.ack_from = match ack {
                Ack::Normal => Some(normal),
                Ack::Late(delay) => Some(normal.saturating_add(u64::from(delay))),
                Ack::Never => None,
            };
        }
        tracker.ack_from.is_some_and(|from| cycle >= from)
    }
}

/// The acknowledgement an injection's action sets, if it is one.
fn ack_of(action: InjectAction) -> Option<Ack> {
    match action {
        InjectAction::NeverAck => Some(Ack::Never),
        InjectAction::DelayAck { cycles } => Some(Ack::Late(cycles)),
        _ => None,
    }
}
