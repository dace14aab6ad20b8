//! A run an application steps: the machine's pending answers pause it,
//! `resume` goes on without asking again, `cancel` stops it cleanly
//! (SPEC §11.10).

mod common;

use common::runs::{diagnostic_codes, in_session, run_against};

use std::sync::Arc;

use gcodec_driver::{Definitions, MemoryLoader};
use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{Event, EventKind, EventQueue, ProgramEndReason, VecSink};
use gcodec_exec::machine::{
    AbortCause, Answer, AuxiliaryFunction, Machine, MachineAction, MachineError, MachineEvents,
    Outcome, PendingToken, Wait,
};
use gcodec_exec::session::{Session, SessionError, Step};
use gcodec_exec::value::RtValue;
use gcodec_profile::Profile;
use gcodec_source::SourceFile;

/// A machine that answers M100, dwells and reads of `$A_DBB` later, and
/// counts what it is asked.
#[derive(Default)]
struct LateMachine {
    calls: Vec<String>,
    aborts: Vec<AbortCause>,
    next: u64,
    /// Answer at once with this instead of pending.
    ready_read: Option<RtValue>,
    fail_m: bool,
}

impl LateMachine {
    fn token(&mut self) -> PendingToken {
        self.next += 1;
        PendingToken(self.next)
    }
}

impl Machine for LateMachine {
    fn auxiliary_function(&mut self, f: &AuxiliaryFunction, _: &mut MachineEvents) -> Answer<()> {
        self.calls.push(format!("{f:?}"));
        match f {
            AuxiliaryFunction::M { value: 100, .. } if self.fail_m => {
                Answer::Error(MachineError::new("the PLC refuses M100"))
            }
            AuxiliaryFunction::M { value: 100, .. } => Answer::Pending(self.token()),
            _ => Answer::Ready(()),
        }
    }

    fn wait(&mut self, wait: &Wait, _: &mut MachineEvents) -> Answer<()> {
        self.calls.push(format!("{wait:?}"));
        Answer::Pending(self.token())
    }

    fn system_variable(&mut self, name: &str, _: &[RtValue]) -> Answer<Option<RtValue>> {
        self.calls.push(name.to_owned());
        match &self.ready_read {
            Some(value) => Answer::Ready(Some(value.clone())),
            None => Answer::Pending(self.token()),
        }
    }

    fn abort(&mut self, cause: AbortCause, _: &mut MachineEvents) {
        self.aborts.push(cause);
    }
}

const PROGRAM: &str = "N10 M100\nN20 G4 F1.5\nN30 R1=$A_DBB[0]+1\nN40 MSG(\"R1=\"<<R1)\nN50 M30\n";

fn main_program(profile: &Profile, text: &str) -> Arc<gcodec_exec::program::Program> {
    let file = Arc::new(SourceFile::new("LATE.MPF", text));
    let loaded = common::runs::compile_main(&file, profile, &Definitions::new());
    assert!(!loaded.has_errors, "{text}: {:?}", loaded.diagnostics);
    loaded.program
}

fn messages(events: &[Event]) -> Vec<String> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Message(m) => Some(m.text.clone()),
            _ => None,
        })
        .collect()
}

fn end_reason(events: &[Event]) -> Option<ProgramEndReason> {
    events.iter().find_map(|e| match &e.kind {
        EventKind::ProgramEnd(end) => Some(end.reason),
        _ => None,
    })
}

/// Steps `session` to its end, answering each pending action with what
/// `answer` gives; the actions in order.
fn step_through(
    session: &mut Session<'_>,
    mut answer: impl FnMut(&MachineAction) -> Outcome,
) -> Vec<MachineAction> {
    let mut actions = Vec::new();
    for _ in 0..1000 {
        match session.step() {
            Step::Events => {}
            Step::Pending(pending) => {
                let outcome = answer(&pending.action);
                actions.push(pending.action);
                session.resume(pending.token, outcome).expect("resumed");
            }
            Step::Ended(outcome) => {
                outcome.expect("events written");
                return actions;
            }
        }
    }
    panic!("the session did not end");
}

#[test]
fn pending_actions_pause_the_run_and_resume_without_being_asked_again() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, PROGRAM);
    let mut machine = LateMachine::default();
    let mut actions = Vec::new();
    let events = in_session(&profile, main, &mut machine, |session| {
        actions = step_through(session, |action| match action {
            MachineAction::SystemVariable { .. } => Outcome::Value(Some(RtValue::Int(41))),
            _ => Outcome::Done,
        });
    });
    assert_eq!(
        actions,
        vec![
            MachineAction::AuxiliaryFunction(AuxiliaryFunction::M {
                value: 100,
                extension: None
            }),
            MachineAction::Wait(Wait::Dwell { seconds: 1.5 }),
            MachineAction::SystemVariable {
                name: "$A_DBB".into(),
                indices: vec![RtValue::Int(0)]
            },
        ]
    );
    // Each asked once: the read's instruction ran again with the answer.
    assert_eq!(
        machine.calls,
        vec![
            "M { value: 100, extension: None }",
            "Dwell { seconds: 1.5 }",
            "$A_DBB",
            "M { value: 30, extension: None }",
        ]
    );
    assert_eq!(messages(&events), vec!["R1=42"]);
    let m_events = events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::MFunction(_)))
        .count();
    assert_eq!(m_events, 2, "M100 and M30, each reported once");
    assert_eq!(end_reason(&events), Some(ProgramEndReason::M30));
    assert!(machine.aborts.is_empty());
}

#[test]
fn a_machine_answering_at_once_runs_the_read_again_with_its_value() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, "R1=$A_DBB[3]*2\nMSG(\"R1=\"<<R1)\nM30\n");
    let mut machine = LateMachine {
        ready_read: Some(RtValue::Real(2.5)),
        ..LateMachine::default()
    };
    let (outcome, events) = run_against(&profile, main, &mut machine);
    assert_eq!(outcome.errors, 0);
    assert_eq!(messages(&events), vec!["R1=5"]);
    assert_eq!(machine.calls[0], "$A_DBB");
}

#[test]
fn a_read_no_one_answers_is_the_alarm_it_always_was() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, "R1=$A_DBB[0]\nM30\n");
    let machine = gcodec_exec::machine::SimulatedMachine::new(&profile);
    let (outcome, events) = run_against(&profile, main, machine);
    assert_eq!(outcome.reason, ProgramEndReason::Alarm);
    assert_eq!(
        diagnostic_codes(&events),
        vec!["gcodec::run::system_variable"]
    );
}

#[test]
fn resume_refuses_a_wrong_token_or_outcome_and_keeps_the_action_pending() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, PROGRAM);
    in_session(&profile, main, LateMachine::default(), |session| {
        refuses_wrong_answers(session);
    });
}

fn refuses_wrong_answers(session: &mut Session<'_>) {
    assert_eq!(
        session.resume(PendingToken(1), Outcome::Done),
        Err(SessionError::NothingPending)
    );
    let Step::Pending(pending) = session.step() else {
        panic!("M100 is pending");
    };
    assert_eq!(pending.source.line, 1);
    assert!(matches!(
        session.resume(PendingToken(99), Outcome::Done),
        Err(SessionError::WrongToken { .. })
    ));
    assert!(matches!(
        session.resume(pending.token, Outcome::Value(None)),
        Err(SessionError::WrongOutcome { .. })
    ));
    assert_eq!(session.pending(), Some(pending.clone()));
    assert_eq!(session.resume(pending.token, Outcome::Done), Ok(()));
    let Step::Pending(next) = session.step() else {
        panic!("the dwell is pending");
    };
    assert_eq!(
        next.action,
        MachineAction::Wait(Wait::Dwell { seconds: 1.5 })
    );
}

#[test]
fn cancel_abandons_the_pending_action_and_ends_the_run_there() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, PROGRAM);
    let mut machine = LateMachine::default();
    let events = in_session(&profile, main, &mut machine, cancel_at_the_dwell);
    assert_eq!(machine.aborts, vec![AbortCause::Cancelled]);
    let cancelled = events
        .iter()
        .find(|e| matches!(&e.kind, EventKind::Diagnostic(d) if d.code == gcodec_source::codes::run::CANCELLED))
        .expect("the cancel is reported");
    assert_eq!(cancelled.source.line, 2, "at the dwell that was pending");
    assert_eq!(end_reason(&events), Some(ProgramEndReason::Cancelled));
    assert!(messages(&events).is_empty(), "nothing after the dwell ran");
}

fn cancel_at_the_dwell(session: &mut Session<'_>) {
    let Step::Pending(pending) = session.step() else {
        panic!("M100 is pending");
    };
    session
        .resume(pending.token, Outcome::Done)
        .expect("resumed");
    let Step::Pending(dwell) = session.step() else {
        panic!("the dwell is pending");
    };
    session.cancel();
    let Step::Ended(outcome) = session.step() else {
        panic!("the run ends");
    };
    let outcome = outcome.expect("events written");
    assert_eq!(outcome.reason, ProgramEndReason::Cancelled);
    assert_eq!(outcome.errors, 1);
    // Over: stepping again says so, resuming finds nothing.
    assert!(matches!(session.step(), Step::Ended(Ok(_))));
    assert_eq!(
        session.resume(dwell.token, Outcome::Done),
        Err(SessionError::NothingPending)
    );
}

#[test]
fn a_failed_action_is_an_alarm_and_the_machine_is_told_the_run_aborts() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, PROGRAM);
    let mut machine = LateMachine {
        fail_m: true,
        ..LateMachine::default()
    };
    let (outcome, events) = run_against(&profile, main, &mut machine);
    assert_eq!(outcome.reason, ProgramEndReason::Alarm);
    assert_eq!(
        diagnostic_codes(&events),
        vec!["gcodec::run::machine_error"]
    );
    assert_eq!(machine.aborts, vec![AbortCause::Alarm]);
}

#[test]
fn a_run_that_cannot_wait_ends_with_an_alarm_at_the_pending_action() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let main = main_program(&profile, PROGRAM);
    let (outcome, events) = run_against(&profile, main, LateMachine::default());
    assert_eq!(outcome.reason, ProgramEndReason::Alarm);
    assert_eq!(
        diagnostic_codes(&events),
        vec!["gcodec::run::machine_action_unanswered"]
    );
}

#[test]
fn an_event_queue_hands_events_over_block_by_block_and_loses_none() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let text = "G0 X10\nG1 X20 F100\nM3 S1000\nG4 F1\nX30\nM30\n";
    let main = main_program(&profile, text);
    let mut loader = MemoryLoader::new(Arc::clone(&profile), Definitions::new());
    let mut whole = VecSink::new();
    let options = RunOptions::for_profile(&profile);
    Channel::new(
        Arc::clone(&profile),
        options.clone(),
        &mut loader,
        &mut whole,
    )
    .run(Arc::clone(&main))
    .expect("events written");
    let queue = EventQueue::new();
    let channel = Channel::new(Arc::clone(&profile), options, &mut loader, queue.clone());
    let mut session = Session::new(channel, main);
    let mut batches = Vec::new();
    loop {
        match session.step() {
            Step::Events => batches.push(queue.take()),
            Step::Pending(pending) => panic!("the simulated machine answers at once: {pending:?}"),
            Step::Ended(outcome) => {
                outcome.expect("events written");
                batches.push(queue.take());
                break;
            }
        }
    }
    assert!(batches.len() >= 6, "a batch per block: {}", batches.len());
    let stepped: Vec<Event> = batches.into_iter().flatten().collect();
    assert_eq!(stepped, whole.events);
}

/// A machine whose tool changes take a while.
#[derive(Default)]
struct SlowChanger {
    prepares: Vec<Option<String>>,
    changes: Vec<(Option<String>, Option<String>)>,
}

impl Machine for SlowChanger {
    fn prepare_tool(
        &mut self,
        request: &gcodec_exec::machine::ToolRequest<'_>,
        _: &mut MachineEvents,
    ) -> Answer<()> {
        self.prepares.push(request.tool.map(str::to_owned));
        Answer::Ready(())
    }

    fn change_tool(
        &mut self,
        request: &gcodec_exec::machine::ToolRequest<'_>,
        _: &mut MachineEvents,
    ) -> Answer<gcodec_exec::machine::ChangeResult> {
        self.changes.push((
            request.previous.map(str::to_owned),
            request.tool.map(str::to_owned),
        ));
        Answer::Pending(PendingToken(self.changes.len() as u64))
    }
}

fn tool_changes(events: &[Event]) -> Vec<(Option<String>, bool, Option<i32>)> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::ToolChange(c) => Some((c.new_tool.clone(), c.committed, c.fault_reason)),
            _ => None,
        })
        .collect()
}

#[test]
fn a_tool_change_answered_late_takes_effect_as_the_machine_says() {
    let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
    let text = "T1\nM6\nMSG(\"T=\"<<$P_TOOLNO)\nT2\nM6\nMSG(\"T=\"<<$P_TOOLNO)\nM30\n";
    let main = main_program(&profile, text);
    let mut machine = SlowChanger::default();
    let mut answers = vec![
        gcodec_exec::machine::ChangeResult::COMMITTED,
        // A soft fault: the change is skipped, the program goes on.
        gcodec_exec::machine::ChangeResult {
            committed: false,
            fault_reason: Some(7),
        },
    ]
    .into_iter();
    let mut actions = Vec::new();
    let events = in_session(&profile, main, &mut machine, |session| {
        actions = step_through(session, |_| {
            Outcome::ToolChanged(answers.next().expect("two changes"))
        });
    });
    assert_eq!(
        actions,
        vec![
            MachineAction::ChangeTool {
                tool: Some("T1".into()),
                previous: None
            },
            MachineAction::ChangeTool {
                tool: Some("T2".into()),
                previous: Some("T1".into())
            },
        ]
    );
    assert_eq!(machine.prepares, vec![Some("T1".into()), Some("T2".into())]);
    assert_eq!(
        tool_changes(&events),
        vec![
            (Some("T1".into()), true, None),
            (Some("T2".into()), false, Some(7))
        ]
    );
    assert_eq!(messages(&events), vec!["T=1", "T=1"]);
}

/// A machine that answers each call as a script says: at once, later, or
/// with an error.
struct ScriptedMachine {
    answers: Vec<u8>,
    at: usize,
    tokens: u64,
}

impl ScriptedMachine {
    /// 0: ready, 1: pending, 2: error; cycling through the script.
    fn next<T>(&mut self, ready: T) -> Answer<T> {
        let answer = self
            .answers
            .get(self.at % self.answers.len().max(1))
            .copied();
        self.at += 1;
        match answer.unwrap_or(0) {
            1 => {
                self.tokens += 1;
                Answer::Pending(PendingToken(self.tokens))
            }
            2 => Answer::Error(MachineError::new("scripted")),
            _ => Answer::Ready(ready),
        }
    }
}

impl Machine for ScriptedMachine {
    fn prepare_tool(
        &mut self,
        _: &gcodec_exec::machine::ToolRequest<'_>,
        _: &mut MachineEvents,
    ) -> Answer<()> {
        self.next(())
    }

    fn change_tool(
        &mut self,
        _: &gcodec_exec::machine::ToolRequest<'_>,
        _: &mut MachineEvents,
    ) -> Answer<gcodec_exec::machine::ChangeResult> {
        self.next(gcodec_exec::machine::ChangeResult::COMMITTED)
    }

    fn auxiliary_function(&mut self, _: &AuxiliaryFunction, _: &mut MachineEvents) -> Answer<()> {
        self.next(())
    }

    fn wait(&mut self, _: &Wait, _: &mut MachineEvents) -> Answer<()> {
        self.next(())
    }

    fn system_variable(&mut self, _: &str, _: &[RtValue]) -> Answer<Option<RtValue>> {
        self.next(Some(RtValue::Int(3)))
    }
}

/// What the application does at a pending action.
#[derive(Clone, Copy, Debug)]
enum Reply {
    Answer,
    Fail,
    WrongToken,
    WrongOutcome,
    Cancel,
}

mod stepped {
    use super::*;
    use proptest::prelude::*;

    const BLOCKS: &[&str] = &[
        "T1",
        "M6",
        "T2 M6",
        "M3 S100",
        "G4 F0.5",
        "H2",
        "R1=$A_DBB[1]+R1",
        "G0 X1",
        "M100",
        "D1",
        "MSG(\"x\")",
    ];

    fn reply() -> impl Strategy<Value = Reply> {
        prop_oneof![
            6 => Just(Reply::Answer),
            1 => Just(Reply::Fail),
            1 => Just(Reply::WrongToken),
            1 => Just(Reply::WrongOutcome),
            1 => Just(Reply::Cancel),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

        /// Whatever the machine answers and the application replies, a
        /// stepped run never panics, ends within its steps with exactly
        /// one `program_end` as its last event, and stays ended.
        #[test]
        fn a_stepped_run_always_ends_once(
            blocks in prop::collection::vec(0..BLOCKS.len(), 1..12),
            answers in prop::collection::vec(0u8..3, 1..6),
            replies in prop::collection::vec(reply(), 1..8),
        ) {
            let profile = Arc::new(gcodec_profile::builtin().expect("the built-in profile"));
            let mut text: String = blocks.iter().map(|b| format!("{}\n", BLOCKS[*b])).collect();
            text.push_str("M30\n");
            let main = main_program(&profile, &text);
            let mut loader = MemoryLoader::new(Arc::clone(&profile), Definitions::new());
            let mut sink = VecSink::new();
            let machine = ScriptedMachine { answers, at: 0, tokens: 0 };
            let options = RunOptions::for_profile(&profile);
            let channel = Channel::new(Arc::clone(&profile), options, &mut loader, &mut sink)
                .with_machine(machine);
            let mut session = Session::new(channel, main);
            let mut replies = replies.into_iter().cycle();
            let mut ended = false;
            for _ in 0..200 {
                match session.step() {
                    Step::Events => {}
                    Step::Pending(pending) => {
                        let outcome = match pending.action {
                            MachineAction::ChangeTool { .. } => Outcome::ToolChanged(
                                gcodec_exec::machine::ChangeResult::COMMITTED,
                            ),
                            MachineAction::SystemVariable { .. } => {
                                Outcome::Value(Some(RtValue::Int(1)))
                            }
                            _ => Outcome::Done,
                        };
                        match replies.next().unwrap_or(Reply::Answer) {
                            Reply::Answer => session.resume(pending.token, outcome).expect("fits"),
                            Reply::Fail => session
                                .resume(pending.token, Outcome::Failed(MachineError::new("no")))
                                .expect("fits"),
                            // A refused answer leaves the action pending:
                            // the right one still goes through.
                            Reply::WrongToken => {
                                let refused = session.resume(PendingToken(u64::MAX), outcome.clone());
                                prop_assert!(refused.is_err());
                                session.resume(pending.token, outcome).expect("fits");
                            }
                            Reply::WrongOutcome => {
                                let wrong = match pending.action {
                                    MachineAction::SystemVariable { .. } => Outcome::Done,
                                    _ => Outcome::Value(None),
                                };
                                prop_assert!(session.resume(pending.token, wrong).is_err());
                                session.resume(pending.token, outcome).expect("fits");
                            }
                            Reply::Cancel => session.cancel(),
                        }
                    }
                    Step::Ended(outcome) => {
                        prop_assert!(outcome.is_ok());
                        ended = true;
                        break;
                    }
                }
            }
            prop_assert!(ended, "the run ended");
            prop_assert!(matches!(session.step(), Step::Ended(Ok(_))));
            session.cancel();
            prop_assert!(matches!(session.step(), Step::Ended(Ok(_))));
            drop(session);
            let ends = sink
                .events
                .iter()
                .filter(|e| matches!(e.kind, EventKind::ProgramEnd(_)))
                .count();
            prop_assert_eq!(ends, 1);
            prop_assert!(matches!(
                sink.events.last().map(|e| &e.kind),
                Some(EventKind::ProgramEnd(_))
            ));
        }
    }
}
