//! A run an application steps (SPEC §11.10): it executes until it has
//! events to hand over, a pending machine action, or the end.
//!
//! ```text
//! let queue = EventQueue::new();
//! let channel = Channel::new(profile, options, &mut loader, queue.clone())
//!     .with_machine(my_machine);
//! let mut session = Session::new(channel, main);
//! loop {
//!     match session.step() {
//!         Step::Events => for event in queue.take() { /* show it */ },
//!         Step::Pending(pending) => { /* start the machine; later: */
//!             session.resume(pending.token, Outcome::Done)?; }
//!         Step::Ended(outcome) => break,
//!     }
//! }
//! ```
//!
//! `Channel::run` and `gcodec run` step a session to its end with the
//! simulated machine, which never leaves an action pending.

use std::io;
use std::sync::Arc;

use super::{Channel, Halt, RunOutcome};
use crate::event::{EventSource, ProgramEndReason};
use crate::machine::{Machine, MachineAction, Outcome, PendingToken};
use crate::program::Program;

/// A steppable run of one main program.
pub struct Session<'r> {
    channel: Channel<'r>,
    phase: Phase,
}

enum Phase {
    /// Not started: the main program to start with.
    Ready(Arc<Program>),
    Running,
    /// Waiting for the application to answer the channel's pending
    /// action.
    Waiting,
    /// Over: the reason, the outcome not yet handed over.
    Ending(ProgramEndReason),
    /// Over, with its outcome (`None`: writing its events failed).
    Ended(Option<RunOutcome>),
}

/// What a [`Session::step`] stopped at.
#[derive(Debug)]
pub enum Step {
    /// A block ended and the channel's sink has events to hand over (its
    /// `wants_yield`, as an [`crate::event::EventQueue`] does when it
    /// holds any).
    Events,
    /// The machine is working on an action: answer it with
    /// [`Session::resume`] (or [`Session::cancel`] the run).
    Pending(Pending),
    /// The run is over; its `program_end` event is the sink's last. Every
    /// later step says so again.
    Ended(io::Result<RunOutcome>),
}

/// A machine action the run waits for.
#[derive(Clone, Debug, PartialEq)]
pub struct Pending {
    pub token: PendingToken,
    pub action: MachineAction,
    /// The instruction that asked.
    pub source: EventSource,
}

/// Why [`Session::resume`] refused an answer; the session is unchanged.
#[derive(Clone, Debug, PartialEq)]
pub enum SessionError {
    /// No action is pending.
    NothingPending,
    /// The token is not the pending action's.
    WrongToken {
        pending: PendingToken,
        given: PendingToken,
    },
    /// The outcome does not answer the action (a value for a tool change).
    WrongOutcome {
        action: MachineAction,
        outcome: Outcome,
    },
}

impl std::fmt::Display for SessionError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::NothingPending => write!(f, "no machine action is pending"),
            Self::WrongToken { pending, given } => write!(
                f,
                "token {} is not the pending action's ({})",
                given.0, pending.0
            ),
            Self::WrongOutcome { action, outcome } => {
                write!(f, "{outcome:?} does not answer {action:?}")
            }
        }
    }
}

impl std::error::Error for SessionError {}

impl<'r> Session<'r> {
    /// A session that runs `main` on `channel` (its profile, options,
    /// loader, sink and machine) when first stepped.
    pub fn new(channel: Channel<'r>, main: Arc<Program>) -> Self {
        Self {
            channel,
            phase: Phase::Ready(main),
        }
    }

    /// Runs until the sink has events to hand over, the machine leaves an
    /// action pending, or the run ends.
    pub fn step(&mut self) -> Step {
        loop {
            match std::mem::replace(&mut self.phase, Phase::Running) {
                Phase::Ready(main) => {
                    if let Some(reason) = self.channel.begin(main) {
                        self.phase = Phase::Ending(reason);
                    }
                }
                Phase::Running => match self.channel.advance() {
                    Halt::End(reason) => self.phase = Phase::Ending(reason),
                    Halt::Yield => return Step::Events,
                    Halt::Pending => self.phase = Phase::Waiting,
                },
                // Waiting with nothing pending cannot happen; were it to,
                // the run would go on rather than wait for ever.
                Phase::Waiting => {
                    if let Some(pending) = self.pending() {
                        self.phase = Phase::Waiting;
                        return Step::Pending(pending);
                    }
                }
                Phase::Ending(reason) => {
                    let outcome = self.channel.finish(reason);
                    self.phase = Phase::Ended(outcome.as_ref().ok().cloned());
                    return Step::Ended(outcome);
                }
                Phase::Ended(outcome) => {
                    let again = match &outcome {
                        Some(outcome) => Ok(outcome.clone()),
                        None => Err(io::Error::other("writing the run's events failed")),
                    };
                    self.phase = Phase::Ended(outcome);
                    return Step::Ended(again);
                }
            }
        }
    }

    /// Answers the pending action with `outcome`; the next
    /// [`Session::step`] goes on from there. The action is not asked of
    /// the machine again.
    pub fn resume(&mut self, token: PendingToken, outcome: Outcome) -> Result<(), SessionError> {
        if !matches!(self.phase, Phase::Waiting) {
            return Err(SessionError::NothingPending);
        }
        match self.channel.resume_pending(token, outcome)? {
            Some(reason) => self.phase = Phase::Ending(reason),
            None if self.channel.pending().is_some() => self.phase = Phase::Waiting,
            None => self.phase = Phase::Running,
        }
        Ok(())
    }

    /// Stops the run where it is: the machine abandons a pending action
    /// (a toolchanger aborts with reason 8, user abort), a
    /// `gcodec::run::cancelled` diagnostic names the place, and the next
    /// step ends the run. Cancelling a run that is over does nothing.
    pub fn cancel(&mut self) {
        match self.phase {
            Phase::Ready(_) | Phase::Running | Phase::Waiting => {
                let reason = self.channel.cancel();
                self.phase = Phase::Ending(reason);
            }
            Phase::Ending(_) | Phase::Ended(_) => {}
        }
    }

    /// Steps to the end, for a run nothing answers: a pending action ends
    /// it with the alarm `gcodec::run::machine_action_unanswered`.
    pub fn run_to_end(mut self) -> io::Result<RunOutcome> {
        loop {
            match self.step() {
                Step::Events => {}
                Step::Pending(_) => {
                    let reason = self.channel.unanswered();
                    self.phase = Phase::Ending(reason);
                }
                Step::Ended(outcome) => return outcome,
            }
        }
    }

    /// What the run waits for, if anything.
    pub fn pending(&self) -> Option<Pending> {
        self.channel.pending().map(|p| Pending {
            token: p.token,
            action: p.action.clone(),
            source: p.source.clone(),
        })
    }

    /// The machine the run talks to (its toolchanger's latched fault).
    pub fn machine(&self) -> &dyn Machine {
        self.channel.machine()
    }

    /// The channel: its state and variables between steps.
    pub fn channel(&self) -> &Channel<'r> {
        &self.channel
    }
}
