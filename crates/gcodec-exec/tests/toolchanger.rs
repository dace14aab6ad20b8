//! The toolchanger protocol against the traces recorded from LinuxCNC's
//! iov2 (`shared/reference/iov2-traces/`): the same handshakes give the
//! same states and reason codes, except where SPEC §12.3 records a safer
//! decision (each such test says so). Then the decisions themselves, the
//! example scenarios, and the invariants over generated scenarios.
//!
//! The traces' fake changer waited 0.3 s before each of its edges, three
//! cycles of 0.1 s: the scenarios here acknowledge after `ack_cycles = 3`.

use std::path::PathBuf;

use gcodec_exec::toolchanger::*;
use gcodec_profile::{InjectAction, InjectAt, Injection, Profile, Scenario, load_scenario};
use proptest::prelude::*;

fn examples_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/toolchanger")
}

fn example_profile(name: &str) -> Profile {
    let text =
        std::fs::read_to_string(examples_dir().join("profile").join(name)).expect("readable");
    gcodec_profile::load(&text).expect("loads")
}

/// The non-random traces' machine (start-change, tools 1 2 3 20 in
/// pockets 1 2 3 7).
fn iov2() -> Profile {
    example_profile("iov2.toml")
}

/// The random traces' machine (T5 in the spindle, T10 in pocket 3, T20 in
/// pocket 7).
fn random() -> Profile {
    example_profile("random.toml")
}

fn changer(profile: &Profile, scenario: &str) -> SimulatedChanger {
    let scenario = load_scenario(scenario).expect("the scenario loads");
    SimulatedChanger::new(profile, &scenario).expect("the changer is built")
}

fn tool(number: u32) -> Option<ChangerTool> {
    Some(ChangerTool {
        number,
        label: format!("T{number}"),
    })
}

fn spindle(changer: &SimulatedChanger) -> Option<u32> {
    changer.tool_in_spindle().map(|t| t.number)
}

/// The `state` pin as the events show it, repeats dropped: the trace's
/// `io -> state` lines.
fn states(events: &[ToolchangerEvent]) -> Vec<u8> {
    let mut states: Vec<u8> = events.iter().map(|e| e.state.number()).collect();
    states.dedup();
    states
}

fn edges(events: &[ToolchangerEvent]) -> Vec<ToolchangerEdge> {
    events.iter().map(|e| e.edge).collect()
}

fn abort_reasons(events: &[ToolchangerEvent]) -> Vec<i32> {
    events
        .iter()
        .filter(|e| e.edge == ToolchangerEdge::AbortRaised)
        .filter_map(|e| e.abort_reason.map(|r| r.0))
        .collect()
}

use ToolchangerEdge as E;

/// `T<tool>` then the change M on the non-random traces' machine: the
/// changer, the change's report and the change's events.
fn prepare_then_change(
    scenario: &str,
    number: u32,
) -> (
    SimulatedChanger,
    Report<ChangeOutcome>,
    Vec<ToolchangerEvent>,
) {
    let mut c = changer(&iov2(), scenario);
    let mut events = Vec::new();
    prepare(&mut c, tool(number), &mut events);
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    (c, changed, events)
}

// --- trace-nonrandom-faults.txt -----------------------------------------

/// S1: `T1` then `M6`.
#[test]
fn trace_normal_change_prepares_starts_and_commits() {
    let mut c = changer(&iov2(), "ack_cycles = 3");
    let mut events = Vec::new();
    let prepared = prepare(&mut c, tool(1), &mut events);
    assert_eq!(prepared.outcome, PrepareOutcome::Prepared);
    assert_eq!(states(&events), [1, 0]);
    assert_eq!(events[0].pocket, Some(1));
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    assert_eq!(changed.outcome, ChangeOutcome::Committed);
    assert_eq!(changed.spindle, tool(1));
    assert_eq!(states(&events), [2, 3, 0]);
    assert_eq!(
        edges(&events),
        [
            E::StartChangeRequested,
            E::StartChangeAcknowledged,
            E::ChangeRequested,
            E::ChangeAcknowledged,
            E::ChangeCommitted
        ]
    );
    assert_eq!(changed.cycles, 6);
    assert_eq!(c.prepared(), None);
}

/// S2: a hard fault (-5) while `T2` prepares; the prepare completes, and
/// the `M6` is aborted at start-change with reason 3; `tool-change` is
/// never raised and T1 stays.
#[test]
fn trace_hard_fault_during_prepare_aborts_the_change_with_reason_3() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 3\ninitial_tool = 1\n[[inject]]\nat = \"prepare\"\nn = 1\naction = \"fault\"\nfault_reason = -5\nhold_cycles = 2\n",
    );
    let mut events = Vec::new();
    assert_eq!(
        prepare(&mut c, tool(2), &mut events).outcome,
        PrepareOutcome::Prepared
    );
    assert_eq!(states(&events), [1, 0]);
    assert!(
        events
            .iter()
            .any(|e| e.edge == E::FaultLatched && e.fault_reason == Some(-5))
    );
    assert_eq!(c.fault(), Some(FaultReason(-5)));
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::MOTION_OR_IO_ERROR,
            fault_reason: Some(FaultReason(-5))
        }
    );
    assert_eq!(states(&events), [2, 4, 0]);
    assert!(!edges(&events).contains(&E::ChangeRequested));
    assert_eq!(abort_reasons(&events), [3]);
    assert_eq!(changed.spindle, tool(1));
}

/// S3: clear-fault drops the latch in one cycle.
#[test]
fn trace_clear_drops_the_latched_fault() {
    let mut c = changer(
        &iov2(),
        "initial_fault = true\ninitial_fault_reason = -5\n[[inject]]\nat = \"block\"\nn = 12\naction = \"clear\"\n",
    );
    let mut events = Vec::new();
    c.block(11, &mut events);
    assert!(events.is_empty());
    c.block(12, &mut events);
    assert_eq!(edges(&events), [E::FaultCleared]);
    assert_eq!(c.fault(), None);
    assert_eq!(c.cycles(), 1);
}

/// S4: a soft fault (+7) before `T3 M6`: the change is raised and the
/// changer aborts it with 101; the program goes on with T1.
#[test]
fn trace_soft_fault_skips_the_change() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 3\ninitial_tool = 1\n[[inject]]\nat = \"block\"\nn = 20\naction = \"fault\"\nfault_reason = 7\nhold_cycles = 1\n",
    );
    let mut events = Vec::new();
    c.block(20, &mut events);
    assert_eq!(edges(&events), [E::FaultLatched]);
    assert_eq!(
        prepare(&mut c, tool(3), &mut events).outcome,
        PrepareOutcome::Prepared
    );
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Skipped {
            fault_reason: FaultReason(7)
        }
    );
    assert_eq!(states(&events), [2, 3, 4, 0]);
    assert_eq!(abort_reasons(&events), [101]);
    assert_eq!(changed.spindle, tool(1));
    assert_eq!(c.fault(), Some(FaultReason(7)));
}

/// S5: the operator aborts (8) while `tool-change` is high. The tool
/// stays. Deliberate difference: iov2 keeps the aborted prepare
/// (`pocket_prepped` 2); gcodec drops it (SPEC §12.3, issue 330).
#[test]
fn trace_abort_during_changing_keeps_the_tool_and_drops_the_prepare() {
    let (c, changed, events) = prepare_then_change(
        "ack_cycles = 3\ninitial_tool = 1\n[[inject]]\nat = \"change\"\nn = 1\nafter_cycles = 1\naction = \"abort\"\nabort_reason = 8\n",
        2,
    );
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::USER_ABORT,
            fault_reason: None
        }
    );
    assert_eq!(states(&events), [2, 3, 4, 0]);
    assert_eq!(abort_reasons(&events), [8]);
    assert_eq!(changed.spindle, tool(1));
    assert_eq!(c.prepared(), None);
    assert_eq!(c.state(), ChangerState::Idle);
}

/// S6: the operator aborts (8) while `tool-prepare` is high.
#[test]
fn trace_abort_during_preparing() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 3\ninitial_tool = 1\n[[inject]]\nat = \"prepare\"\nn = 1\nafter_cycles = 1\naction = \"abort\"\nabort_reason = 8\n",
    );
    let mut events = Vec::new();
    let prepared = prepare(&mut c, tool(3), &mut events);
    assert_eq!(
        prepared.outcome,
        PrepareOutcome::Aborted {
            abort_reason: AbortReason::USER_ABORT,
            fault_reason: None
        }
    );
    assert_eq!(states(&events), [1, 4, 0]);
    assert_eq!(prepared.spindle, tool(1));
    assert_eq!(c.prepared(), None);
}

/// S7: `T0 M6` unloads: the full handshake runs and the spindle is empty.
#[test]
fn trace_t0_unloads_with_the_full_handshake() {
    let mut c = changer(&iov2(), "ack_cycles = 3\ninitial_tool = 2");
    let mut events = Vec::new();
    assert_eq!(
        prepare(&mut c, None, &mut events).outcome,
        PrepareOutcome::Prepared
    );
    assert_eq!(events[0].tool, None);
    let changed = change(&mut c, &mut events);
    assert_eq!(changed.outcome, ChangeOutcome::Committed);
    assert_eq!(changed.spindle, None);
    assert_eq!(states(&events), [1, 0, 2, 3, 0]);
}

/// S9: a hard fault (-9) while `tool-change` is high: the changer aborts
/// with 101. Deliberate difference: LinuxCNC's task then sends reason 3,
/// which overwrites 101 while the abort is pending; gcodec keeps 101
/// (SPEC §12.3).
#[test]
fn trace_fault_while_changing_aborts_with_101_and_keeps_it() {
    let (_, changed, events) = prepare_then_change(
        "ack_cycles = 3\ninitial_tool = 2\n[[inject]]\nat = \"change\"\nn = 1\nafter_cycles = 1\naction = \"fault\"\nfault_reason = -9\n",
        1,
    );
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::TOOLCHANGER_FAULT,
            fault_reason: Some(FaultReason(-9))
        }
    );
    assert_eq!(states(&events), [2, 3, 4, 0]);
    assert_eq!(abort_reasons(&events), [101]);
    let ack = events
        .iter()
        .find(|e| e.edge == E::AbortAcknowledged)
        .expect("acknowledged");
    assert_eq!(ack.abort_reason, Some(AbortReason::TOOLCHANGER_FAULT));
    assert_eq!(changed.spindle, tool(2));
}

// --- trace-nonrandom-misc.txt -------------------------------------------

/// `T20 M6` with T20 in the spindle (non-random): the prepare handshake
/// runs (pocket 7, the tool's own), the start-change too, and the change
/// completes without `tool-change`.
#[test]
fn trace_tool_already_in_the_spindle_changes_without_the_change_handshake() {
    let mut c = changer(&iov2(), "ack_cycles = 3\ninitial_tool = 20");
    let mut events = Vec::new();
    assert_eq!(
        prepare(&mut c, tool(20), &mut events).outcome,
        PrepareOutcome::Prepared
    );
    assert_eq!(events[0].pocket, Some(7));
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    assert_eq!(changed.outcome, ChangeOutcome::AlreadyInSpindle);
    assert_eq!(states(&events), [2]);
    assert_eq!(
        edges(&events),
        [E::StartChangeRequested, E::StartChangeAcknowledged]
    );
    assert_eq!(changed.spindle, tool(20));
}

// --- trace-random.txt and trace-random-precall-bug330.txt ---------------

#[test]
fn trace_random_changer_swaps_pockets_on_each_change() {
    let mut c = changer(&random(), "ack_cycles = 3");
    assert_eq!(spindle(&c), Some(5));
    let pockets = |c: &SimulatedChanger| [5, 10, 20].map(|t| c.pocket_of(t));
    let mut events = Vec::new();
    for (next, expected) in [
        (10, [Some(3), Some(0), Some(7)]),
        (20, [Some(3), Some(7), Some(0)]),
        (5, [Some(0), Some(7), Some(3)]),
    ] {
        assert_eq!(
            prepare(&mut c, tool(next), &mut events).outcome,
            PrepareOutcome::Prepared
        );
        let changed = change(&mut c, &mut events);
        assert_eq!(changed.outcome, ChangeOutcome::Committed);
        assert_eq!(changed.spindle, tool(next));
        assert_eq!(pockets(&c), expected, "after T{next} M6");
    }
    let committed: Vec<_> = events
        .iter()
        .filter(|e| e.edge == E::ChangeCommitted)
        .map(|e| (e.tool.clone().unwrap_or_default(), e.pocket))
        .collect();
    assert_eq!(
        committed,
        [
            ("T10".to_owned(), Some(3)),
            ("T20".to_owned(), Some(7)),
            ("T5".to_owned(), Some(3))
        ]
    );
}

/// `T10 M6; T20; T10 M6`: iov2 ignores the second `T10` (the tool is in
/// the spindle) and keeps the stale prepare of T20, which the `M6` loads
/// (LinuxCNC issue 330). Deliberate difference: gcodec's prepare of the
/// tool in the spindle replaces the stale one, and T10 stays.
#[test]
fn trace_random_precall_bug_330_keeps_the_tool_in_the_spindle() {
    let mut c = changer(&random(), "ack_cycles = 3");
    let mut events = Vec::new();
    prepare(&mut c, tool(10), &mut events);
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Committed
    );
    assert_eq!(
        prepare(&mut c, tool(20), &mut events).outcome,
        PrepareOutcome::Prepared
    );
    let mut again = Vec::new();
    assert_eq!(
        prepare(&mut c, tool(10), &mut again).outcome,
        PrepareOutcome::AlreadyInSpindle
    );
    assert!(again.is_empty(), "no handshake, as in iov2");
    let changed = change(&mut c, &mut again);
    assert_eq!(changed.outcome, ChangeOutcome::AlreadyInSpindle);
    assert_eq!(changed.spindle, tool(10));
    assert_eq!(c.pocket_of(20), Some(7));
}

// --- the decisions of SPEC §12.3 ----------------------------------------

/// Every trace starts with LinuxCNC's start-up abort (reason 5). A run
/// does not raise it (the changer starts idle, as the scenario says); an
/// application that resets its machine can, and the handshake runs.
#[test]
fn the_start_up_abort_is_not_raised_by_a_run_but_runs_when_asked() {
    let mut c = changer(&iov2(), "");
    assert_eq!(
        (c.state(), c.cycles(), c.pending_abort()),
        (ChangerState::Idle, 0, None)
    );
    let mut events = Vec::new();
    let report = abort(&mut c, AbortReason::ESTOP_RESET, &mut events);
    assert_eq!(
        report.outcome,
        AbortOutcome::Acknowledged {
            abort_reason: AbortReason::ESTOP_RESET
        }
    );
    assert_eq!(states(&events), [4, 0]);
    assert_eq!(edges(&events), [E::AbortRaised, E::AbortAcknowledged]);
}

/// iov2 processes commands while an abort waits for its acknowledgement
/// and overwrites the state; gcodec refuses them, and the helpers wait
/// for the acknowledgement first.
#[test]
fn a_pending_abort_blocks_further_commands() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 4\n[[inject]]\nat = \"block\"\nn = 3\naction = \"abort\"\nabort_reason = 8\n",
    );
    let mut events = Vec::new();
    c.block(3, &mut events);
    assert_eq!(c.pending_abort(), Some(AbortReason::USER_ABORT));
    assert_eq!(
        c.request_prepare(tool(1), &mut events),
        Answer::AbortPending(AbortReason::USER_ABORT)
    );
    assert_eq!(c.state(), ChangerState::WaitingForAbortAck);
    let mut events = Vec::new();
    assert_eq!(
        prepare(&mut c, tool(1), &mut events).outcome,
        PrepareOutcome::Prepared
    );
    assert_eq!(
        edges(&events)[..2],
        [E::AbortAcknowledged, E::PrepareRequested]
    );
}

/// iov2 clears the latch even while the fault line is high (and latches
/// it again a cycle later); gcodec clears only a fault whose line is low.
#[test]
fn clear_fault_while_the_fault_line_is_high_keeps_the_fault() {
    let mut c = changer(
        &iov2(),
        "[[inject]]\nat = \"block\"\nn = 1\naction = \"fault\"\nfault_reason = -5\nhold_cycles = 3\n[[inject]]\nat = \"block\"\nn = 2\naction = \"clear\"\n[[inject]]\nat = \"block\"\nn = 9\naction = \"clear\"\n",
    );
    let mut events = Vec::new();
    c.block(1, &mut events);
    c.block(2, &mut events);
    assert_eq!(edges(&events), [E::FaultLatched]);
    assert_eq!(c.fault(), Some(FaultReason(-5)));
    c.cycle(&mut events);
    c.cycle(&mut events);
    c.block(9, &mut events);
    assert_eq!(edges(&events), [E::FaultLatched, E::FaultCleared]);
}

/// A second abort while one is pending does not overwrite its reason.
#[test]
fn a_later_abort_keeps_the_first_reason() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 3\n[[inject]]\nat = \"abort\"\nn = 1\naction = \"abort\"\nabort_reason = 6\n",
    );
    let mut events = Vec::new();
    let report = abort(&mut c, AbortReason::USER_ABORT, &mut events);
    assert_eq!(
        report.outcome,
        AbortOutcome::Acknowledged {
            abort_reason: AbortReason::USER_ABORT
        }
    );
    assert_eq!(abort_reasons(&events), [8]);
    let ack = events.last().expect("acknowledged");
    assert_eq!(
        (ack.edge, ack.abort_reason),
        (E::AbortAcknowledged, Some(AbortReason::USER_ABORT))
    );
}

fn without_start_change() -> Profile {
    gcodec_profile::load(
        "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n[toolchanger]\n[[tools]]\nnumber = 20\nlocation = 7\n",
    )
    .expect("loads")
}

/// A change to the tool in the spindle still meets a latched fault: it
/// is raised so that the fault aborts it. iov2 completes it without a
/// handshake when the changer has no start-change, and the fault passes.
#[test]
fn a_change_to_the_tool_in_the_spindle_still_meets_a_latched_fault() {
    let scenario = "initial_tool = 20\ninitial_fault = true\ninitial_fault_reason = -2\n";
    let mut c = changer(&without_start_change(), scenario);
    let mut events = Vec::new();
    prepare(&mut c, tool(20), &mut events);
    let changed = change(&mut c, &mut events);
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::TOOLCHANGER_FAULT,
            fault_reason: Some(FaultReason(-2))
        }
    );
    assert_eq!(changed.spindle, tool(20));
    let mut c = changer(&iov2(), scenario);
    prepare(&mut c, tool(20), &mut events);
    assert!(matches!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::MOTION_OR_IO_ERROR,
            ..
        }
    ));
}

/// A hard fault is caught at start-change (reason 3) where the changer
/// has it, at the change (101) where it has not, as in iov2.
#[test]
fn without_start_change_a_latched_hard_fault_aborts_with_101() {
    let mut c = changer(
        &without_start_change(),
        "initial_fault = true\ninitial_fault_reason = 0\n",
    );
    let mut events = Vec::new();
    prepare(&mut c, tool(20), &mut events);
    let mut events = Vec::new();
    let changed = change(&mut c, &mut events);
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::TOOLCHANGER_FAULT,
            fault_reason: Some(FaultReason(0))
        }
    );
    assert_eq!(states(&events), [3, 4, 0]);
    assert_eq!(changed.spindle, None);
}

/// LinuxCNC issue 3675: an abort during a pending change wedged the
/// controller. After gcodec's abort nothing waits: the next change runs.
#[test]
fn an_abort_during_a_change_leaves_nothing_waiting() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 5\n[[inject]]\nat = \"change\"\nn = 1\nafter_cycles = 2\naction = \"abort\"\nabort_reason = 8\n",
    );
    let mut events = Vec::new();
    prepare(&mut c, tool(2), &mut events);
    assert!(matches!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Aborted { .. }
    ));
    assert_eq!((c.state(), c.pending_abort()), (ChangerState::Idle, None));
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::NotPrepared
    );
    prepare(&mut c, tool(2), &mut events);
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Committed
    );
    assert_eq!(spindle(&c), Some(2));
}

// --- timeouts and acknowledgements --------------------------------------

#[test]
fn a_change_never_acknowledged_aborts_with_reason_102_after_the_timeout() {
    let text =
        std::fs::read_to_string(examples_dir().join("never_ack_timeout.toml")).expect("readable");
    let mut c = changer(&iov2(), &text);
    let mut events = Vec::new();
    prepare(&mut c, tool(3), &mut events);
    let changed = change(&mut c, &mut events);
    assert_eq!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::ACK_TIMEOUT,
            fault_reason: None
        }
    );
    // One cycle of start-change, 20 of waiting, one for the abort.
    assert_eq!(changed.cycles, 22);
    assert_eq!(c.state(), ChangerState::Idle);
}

#[test]
fn an_abort_never_acknowledged_is_withdrawn() {
    let mut c = changer(
        &iov2(),
        "timeout_cycles = 5\n[[inject]]\nat = \"abort\"\nn = 1\naction = \"never_ack\"\n",
    );
    let mut events = Vec::new();
    let report = abort(&mut c, AbortReason::USER_ABORT, &mut events);
    assert_eq!(
        report.outcome,
        AbortOutcome::Unacknowledged {
            abort_reason: AbortReason::USER_ABORT
        }
    );
    assert_eq!(report.cycles, 5);
    assert_eq!((c.state(), c.pending_abort()), (ChangerState::Idle, None));
}

#[test]
fn a_delayed_acknowledgement_takes_its_cycles() {
    let mut c = changer(
        &iov2(),
        "ack_cycles = 2\n[[inject]]\nat = \"prepare\"\nn = 2\naction = \"delay_ack\"\nhold_cycles = 4\n",
    );
    let mut events = Vec::new();
    assert_eq!(prepare(&mut c, tool(1), &mut events).cycles, 2);
    assert_eq!(prepare(&mut c, tool(2), &mut events).cycles, 6);
    assert_eq!(prepare(&mut c, tool(3), &mut events).cycles, 2);
    assert_eq!(c.cycle_time(), 0.1);
}

#[test]
fn an_initial_tool_the_table_lacks_is_a_diagnostic_into_the_scenario() {
    let text = "ack_cycles = 2\ninitial_tool = 99\n";
    let scenario = load_scenario(text).expect("loads");
    let diagnostic = SimulatedChanger::new(&iov2(), &scenario).expect_err("rejected");
    assert_eq!(diagnostic.code.name(), "gcodec::scenario::unknown_tool");
    let span = diagnostic.span().expect("a span");
    assert_eq!(&text[span.start as usize..span.end as usize], "99");
}

// --- the example scenarios do what their headers say ---------------------

fn example(name: &str, profile: &Profile) -> SimulatedChanger {
    let text = std::fs::read_to_string(examples_dir().join(name)).expect("readable");
    changer(profile, &text)
}

#[test]
fn the_example_scenarios_do_what_they_say() {
    let mut events = Vec::new();
    let mut c = example("normal.toml", &iov2());
    prepare(&mut c, tool(1), &mut events);
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Committed
    );

    let mut c = example("hard_fault_at_prepare.toml", &iov2());
    prepare(&mut c, tool(1), &mut events);
    assert!(matches!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::MOTION_OR_IO_ERROR,
            ..
        }
    ));
    let mut c = example("hard_fault_at_prepare.toml", &without_start_change());
    prepare(&mut c, tool(20), &mut events);
    assert!(matches!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::TOOLCHANGER_FAULT,
            ..
        }
    ));

    let mut c = example("soft_fault.toml", &iov2());
    prepare(&mut c, tool(1), &mut events);
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Skipped {
            fault_reason: FaultReason(7)
        }
    );
    c.block(10, &mut events);
    assert_eq!(c.fault(), None);

    let mut c = example("fault_while_changing.toml", &iov2());
    prepare(&mut c, tool(2), &mut events);
    let changed = change(&mut c, &mut events);
    assert!(matches!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::TOOLCHANGER_FAULT,
            ..
        }
    ));
    assert_eq!(changed.spindle, None);
    c.block(15, &mut events);
    assert_eq!(c.fault(), None);

    let mut c = example("operator_abort.toml", &iov2());
    prepare(&mut c, tool(1), &mut events);
    assert_eq!(
        change(&mut c, &mut events).outcome,
        ChangeOutcome::Committed
    );
    prepare(&mut c, tool(2), &mut events);
    let changed = change(&mut c, &mut events);
    assert!(matches!(
        changed.outcome,
        ChangeOutcome::Aborted {
            abort_reason: AbortReason::USER_ABORT,
            ..
        }
    ));
    assert_eq!((changed.spindle, c.prepared()), (tool(1), None));

    let mut c = example("random_changer.toml", &random());
    prepare(&mut c, tool(10), &mut events);
    change(&mut c, &mut events);
    assert_eq!(prepare(&mut c, tool(20), &mut events).cycles, 3);
    change(&mut c, &mut events);
    assert_eq!((c.pocket_of(5), c.pocket_of(10)), (Some(3), Some(7)));
}

// --- invariants over generated scenarios --------------------------------

#[derive(Clone, Debug)]
enum Op {
    Prepare(Option<u32>),
    Change,
    Abort(i32),
    Block(u32),
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        prop::option::weighted(0.85, 1u32..=3).prop_map(Op::Prepare),
        Just(Op::Change),
        (1i32..=10).prop_map(Op::Abort),
        (1u32..=4).prop_map(Op::Block),
    ]
}

fn injection() -> impl Strategy<Value = Injection> {
    let at = prop_oneof![
        (1u32..=3).prop_map(InjectAt::Prepare),
        (1u32..=3).prop_map(InjectAt::StartChange),
        (1u32..=3).prop_map(InjectAt::Change),
        (1u32..=2).prop_map(InjectAt::Abort),
        ((1u32..=4), (1u32..=2)).prop_map(|(line, pass)| InjectAt::Block { line, pass }),
    ];
    let action = prop_oneof![
        ((-3i32..=3), prop::option::of(1u32..=4)).prop_map(|(reason, hold_cycles)| {
            InjectAction::Fault {
                reason,
                hold_cycles,
            }
        }),
        Just(InjectAction::Clear),
        (1i32..=10).prop_map(|reason| InjectAction::Abort { reason }),
        Just(InjectAction::NeverAck),
        (1u32..=6).prop_map(|cycles| InjectAction::DelayAck { cycles }),
    ];
    (at, 0u32..=4, action).prop_map(|(at, after_cycles, action)| Injection {
        at,
        after_cycles,
        action,
    })
}

fn scenario() -> impl Strategy<Value = Scenario> {
    (
        1u32..=4,
        prop::option::of(1u32..=12),
        prop::option::of(-2i32..=2),
        prop::collection::vec(injection(), 0..5),
    )
        .prop_map(
            |(ack_cycles, timeout_cycles, initial_fault, inject)| Scenario {
                ack_cycles,
                timeout_cycles,
                initial_tool: None,
                initial_fault,
                inject,
            },
        )
}

fn generated_profile(random: bool, support_start_change: bool) -> Profile {
    let pockets = if random { [0, 3, 7] } else { [1, 2, 3] };
    let mut text = format!(
        "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n[toolchanger]\nrandom = {random}\nsupport_start_change = {support_start_change}\n"
    );
    for (number, pocket) in (1..=3).zip(pockets) {
        text.push_str(&format!(
            "[[tools]]\nnumber = {number}\nlocation = {pocket}\n"
        ));
    }
    gcodec_profile::load(&text).expect("loads")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, ..ProptestConfig::default() })]

    /// After every operation, faulted or aborted or not: the changer is
    /// idle with nothing pending, the report's spindle tool is the one
    /// the events say, no change is committed without its
    /// acknowledgement, and the operation ended within a bound of cycles.
    #[test]
    fn faults_and_aborts_never_leave_the_spindle_ambiguous(
        scenario in scenario(),
        ops in prop::collection::vec(op(), 1..10),
        random in any::<bool>(),
        support_start_change in any::<bool>(),
    ) {
        let profile = generated_profile(random, support_start_change);
        let mut c = SimulatedChanger::new(&profile, &scenario).expect("built");
        let bound = 6 * (u64::from(c.timeout_cycles()) + 1);
        let mut by_events: Option<String> = c.tool_in_spindle().map(|t| t.label.clone());
        for op in ops {
            let mut events = Vec::new();
            let before = c.tool_in_spindle().cloned();
            let (spindle, cycles, aborted) = match op {
                Op::Prepare(number) => {
                    let r = prepare(&mut c, number.and_then(tool), &mut events);
                    (r.spindle, r.cycles, matches!(r.outcome, PrepareOutcome::Aborted { .. }))
                }
                Op::Change => {
                    let r = change(&mut c, &mut events);
                    let unchanged = !matches!(r.outcome, ChangeOutcome::Committed);
                    if unchanged {
                        prop_assert_eq!(&r.spindle, &before, "{:?}", r.outcome);
                    }
                    (r.spindle, r.cycles, matches!(r.outcome, ChangeOutcome::Aborted { .. }))
                }
                Op::Abort(reason) => {
                    let r = abort(&mut c, AbortReason(reason), &mut events);
                    (r.spindle, r.cycles, true)
                }
                Op::Block(line) => {
                    c.block(line, &mut events);
                    // An abort raised at a block is the run's: settle it.
                    if let Some(reason) = c.pending_abort() {
                        abort(&mut c, reason, &mut events);
                    }
                    (c.tool_in_spindle().cloned(), 0, false)
                }
            };
            prop_assert!(cycles <= bound, "{} cycles", cycles);
            prop_assert_eq!(c.state(), ChangerState::Idle);
            prop_assert_eq!(c.pending_abort(), None);
            if aborted {
                prop_assert_eq!(c.prepared(), None);
                prop_assert_eq!(&spindle, &before);
            }
            for (i, event) in events.iter().enumerate() {
                if event.edge == E::ChangeCommitted {
                    prop_assert!(i > 0 && events[i - 1].edge == E::ChangeAcknowledged);
                    by_events = event.tool.clone();
                }
            }
            prop_assert_eq!(spindle.as_ref().map(|t| t.label.clone()), by_events.clone());
            prop_assert_eq!(c.tool_in_spindle(), spindle.as_ref());
        }
    }
}
