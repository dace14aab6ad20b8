//! Programs run with the simulated toolchanger (SPEC §11.10, §12): the
//! example scenarios as golden text traces, the interpreter-side errors
//! iov2 aborts with reason 10, and runs without a toolchanger unchanged.

mod common;

use common::runs::diagnostic_codes;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_driver::{RunSetup, run_main};
use gcodec_exec::event::{Event, EventKind, ProgramEndReason, TextSink, VecSink};
use gcodec_profile::Profile;
use gcodec_source::SourceFile;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn example_profile(name: &str) -> Profile {
    let path = repo().join("examples/toolchanger/profile").join(name);
    let text = std::fs::read_to_string(&path).expect("the example profile");
    gcodec_profile::load(&text).expect("a valid profile")
}

/// The run set up as `gcodec run --profile … --toolchanger SCENARIO`.
fn setup(profile: Profile, scenario: Option<&str>) -> RunSetup {
    let mut setup = RunSetup::new(profile);
    if let Some(name) = scenario {
        let path = repo().join("examples/toolchanger").join(name);
        let file = SourceFile::new(name, std::fs::read(&path).expect("the scenario"));
        let changer = gcodec_driver::load_toolchanger(&file, &setup.profile)
            .unwrap_or_else(|e| panic!("{name}: {:?}", e.diagnostics));
        setup.toolchanger = Some(changer);
    }
    setup
}

fn example_program(name: &str) -> Arc<SourceFile> {
    let path = repo().join("examples/toolchanger").join(name);
    let bytes = std::fs::read(&path).expect("the example program");
    Arc::new(SourceFile::new(
        format!("examples/toolchanger/{name}"),
        bytes,
    ))
}

/// The text trace of `program` run as `setup` says.
fn text_trace(program: Arc<SourceFile>, setup: &RunSetup) -> String {
    let mut out = Vec::new();
    {
        let mut sink = TextSink::new(&mut out);
        let report = run_main(program, setup, &mut sink, None);
        assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics);
    }
    String::from_utf8(out).expect("text")
}

fn events(program: &str, setup: &RunSetup) -> Vec<Event> {
    common::runs::events_of_text_with(setup, "CHANGER.MPF", program)
}

fn toolchanger_edges(events: &[Event]) -> usize {
    events
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Toolchanger(_)))
        .count()
}

#[test]
fn every_example_scenario_runs_as_its_golden_trace() {
    let mut scenarios: Vec<String> = std::fs::read_dir(repo().join("examples/toolchanger"))
        .expect("the examples")
        .filter_map(|entry| {
            let name = entry.ok()?.file_name().into_string().ok()?;
            name.ends_with(".toml").then_some(name)
        })
        .collect();
    scenarios.sort();
    assert!(scenarios.len() >= 7, "{scenarios:?}");
    for scenario in &scenarios {
        let (profile, program) = if scenario.starts_with("random") {
            ("random.toml", "random_changes.mpf")
        } else {
            ("iov2.toml", "tool_changes.mpf")
        };
        let setup = setup(example_profile(profile), Some(scenario));
        let trace = text_trace(example_program(program), &setup);
        let name = scenario.trim_end_matches(".toml");
        insta::assert_snapshot!(format!("scenario_{name}"), trace);
    }
}

#[test]
fn the_profile_s_toolchanger_runs_without_a_scenario() {
    let setup = setup(example_profile("random.toml"), None);
    let trace = text_trace(example_program("random_changes.mpf"), &setup);
    insta::assert_snapshot!("random_changer_without_a_scenario", trace);
}

/// iov2 lets the interpreter catch a change M with nothing selected and
/// an unknown tool, and aborts with reason 10; gcodec's policies decide,
/// and the toolchanger is not involved (SPEC §12).
#[test]
fn a_bare_change_m_and_an_unknown_tool_are_policies_not_abort_reason_10() {
    let mut profile = example_profile("iov2.toml");
    profile.tool_change.m6_without_pending_policy = gcodec_profile::Policy::Error;
    profile.tool_change.on_unresolved_tool = gcodec_profile::UnresolvedToolPolicy::Error;
    let setup = setup(profile, None);
    let bare = events("N10 M6\nN20 M30\n", &setup);
    assert_eq!(
        diagnostic_codes(&bare),
        vec!["gcodec::run::m6_without_pending"]
    );
    assert_eq!(toolchanger_edges(&bare), 0);
    // A constant `T99` is lowering's `unresolved_tool` already; a computed
    // one is found when the run selects it.
    let unknown = events("N10 R1=99\nN20 T=R1\nN30 M6\nN40 M30\n", &setup);
    assert_eq!(
        diagnostic_codes(&unknown),
        vec!["gcodec::run::unresolved_tool"]
    );
    assert_eq!(toolchanger_edges(&unknown), 0);
    // After a completed change a second bare M6 has nothing pending
    // either (iov2 resets its prepared pocket after every change).
    let again = events("N10 T1 M6\nN20 M6\nN30 M30\n", &setup);
    assert_eq!(
        diagnostic_codes(&again),
        vec!["gcodec::run::m6_without_pending"]
    );
}

#[test]
fn a_hard_fault_ends_the_run_with_the_old_tool_in_the_spindle() {
    let setup = setup(
        example_profile("iov2.toml"),
        Some("fault_while_changing.toml"),
    );
    let events = events("N10 T1 M6\nN20 G0 X1\nN30 M30\n", &setup);
    let changes: Vec<(Option<String>, Option<String>, bool)> = events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::ToolChange(c) => {
                Some((c.previous_tool.clone(), c.new_tool.clone(), c.committed))
            }
            _ => None,
        })
        .collect();
    assert_eq!(changes, vec![(None, Some("T1".into()), false)]);
    assert_eq!(
        diagnostic_codes(&events),
        vec!["gcodec::run::machine_error"]
    );
    let end = events.last().expect("program_end");
    assert!(matches!(&end.kind, EventKind::ProgramEnd(e) if e.reason == ProgramEndReason::Alarm));
}

/// Without a `[toolchanger]` table and without a scenario, a run and its
/// events are those of a channel with no machine behind it.
#[test]
fn without_a_toolchanger_a_run_has_no_toolchanger_events_or_time() {
    let profile = gcodec_profile::builtin().expect("the built-in profile");
    assert!(profile.toolchanger.is_none());
    let setup = setup(profile, None);
    let file = Arc::new(SourceFile::new("PLAIN.MPF", "T1 M6\nG0 X10\nT2 M6\nM30\n"));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    let outcome = report.outcome.expect("events written");
    assert_eq!(toolchanger_edges(&sink.events), 0);
    assert!(
        outcome
            .summary
            .tools()
            .iter()
            .all(|t| t.machine_time == 0.0)
    );
    let json = serde_json::to_string(&outcome.summary).expect("json");
    assert!(!json.contains("machine_time"), "{json}");
}

#[test]
fn toolchanger_cycles_count_in_the_run_s_time() {
    let setup = setup(example_profile("iov2.toml"), Some("normal.toml"));
    let file = Arc::new(SourceFile::new("TIMED.MPF", "T1 M6\nM30\n"));
    let mut sink = VecSink::new();
    let outcome = run_main(file, &setup, &mut sink, None)
        .outcome
        .expect("events written");
    let total = outcome.summary.total();
    // Prepare 3 cycles, start-change 3, change 3: 0.9 s at 0.1 s a cycle.
    assert!(
        (total.machine_time - 0.9).abs() < 1e-9,
        "{}",
        total.machine_time
    );
}

/// A machine that starts a change on its simulated changer and leaves it
/// pending, as an application stepping the changer itself does.
struct StartedChange {
    changer: gcodec_exec::toolchanger::SimulatedChanger,
    edges: Vec<gcodec_exec::toolchanger::ToolchangerEvent>,
}

impl gcodec_exec::machine::Machine for StartedChange {
    fn change_tool(
        &mut self,
        request: &gcodec_exec::machine::ToolRequest<'_>,
        events: &mut gcodec_exec::machine::MachineEvents,
    ) -> gcodec_exec::machine::Answer<gcodec_exec::machine::ChangeResult> {
        use gcodec_exec::toolchanger::{ChangerTool, Toolchanger};
        let tool = request.tool.map(|label| ChangerTool {
            number: request.number,
            label: label.to_owned(),
        });
        gcodec_exec::toolchanger::prepare(&mut self.changer, tool, &mut self.edges);
        self.changer.request_change(&mut self.edges);
        self.changer.cycle(&mut self.edges);
        events.extend(self.edges.drain(..).map(EventKind::Toolchanger));
        gcodec_exec::machine::Answer::Pending(gcodec_exec::machine::PendingToken(1))
    }

    fn abort(
        &mut self,
        cause: gcodec_exec::machine::AbortCause,
        events: &mut gcodec_exec::machine::MachineEvents,
    ) {
        use gcodec_exec::toolchanger::AbortReason;
        let reason = match cause {
            gcodec_exec::machine::AbortCause::Cancelled => AbortReason::USER_ABORT,
            gcodec_exec::machine::AbortCause::Alarm => AbortReason::TASK_EXEC_ERROR,
        };
        gcodec_exec::toolchanger::abort(&mut self.changer, reason, &mut self.edges);
        events.extend(self.edges.drain(..).map(EventKind::Toolchanger));
    }
}

/// The abort reasons of the run's toolchanger events, and the state the
/// last one leaves.
fn abort_reasons(events: &[Event]) -> (Vec<i32>, Option<String>) {
    let toolchanger: Vec<_> = events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Toolchanger(t) => Some(t),
            _ => None,
        })
        .collect();
    let reasons = toolchanger
        .iter()
        .filter_map(|t| t.abort_reason.map(|r| r.0))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let last = toolchanger.last().map(|t| t.state.name().to_owned());
    (reasons, last)
}

/// Runs `T1 M6 …` against a change left pending, then `finish` decides.
fn pending_change(
    finish: impl FnOnce(&mut gcodec_exec::session::Session<'_>, gcodec_exec::machine::PendingToken),
) -> Vec<Event> {
    use gcodec_exec::session::Step;
    let profile = Arc::new(example_profile("iov2.toml"));
    let scenario = gcodec_profile::load_scenario("ack_cycles = 5").expect("scenario");
    let machine = StartedChange {
        changer: gcodec_exec::toolchanger::SimulatedChanger::new(&profile, &scenario)
            .expect("changer"),
        edges: Vec::new(),
    };
    let file = Arc::new(SourceFile::new(
        "LATE.MPF",
        "N10 T1 M6\nN20 G0 X1\nN30 M30\n",
    ));
    let main = common::runs::compile_main(&file, &profile, &gcodec_driver::Definitions::new());
    common::runs::in_session(&profile, main.program, machine, |session| {
        let Step::Pending(pending) = session.step() else {
            panic!("the change is pending");
        };
        finish(session, pending.token);
        assert!(matches!(session.step(), Step::Ended(Ok(_))));
    })
}

#[test]
fn a_run_cancelled_in_the_middle_of_a_change_aborts_it_with_reason_8() {
    let events = pending_change(|session, _| session.cancel());
    assert_eq!(abort_reasons(&events), (vec![8], Some("idle".into())));
    assert_eq!(diagnostic_codes(&events), vec!["gcodec::run::cancelled"]);
    assert!(
        !events
            .iter()
            .any(|e| matches!(e.kind, EventKind::ToolChange(_))),
        "no change is reported made"
    );
}

#[test]
fn a_run_ending_in_an_alarm_during_a_change_aborts_it_with_reason_1() {
    let events = pending_change(|session, token| {
        let failed = gcodec_exec::machine::Outcome::Failed(
            gcodec_exec::machine::MachineError::new("the spindle did not stop"),
        );
        session.resume(token, failed).expect("an answer");
    });
    assert_eq!(abort_reasons(&events), (vec![1], Some("idle".into())));
    assert_eq!(
        diagnostic_codes(&events),
        vec!["gcodec::run::machine_error"]
    );
}

/// The application reads the latched fault through the session's
/// machine; the program cannot.
#[test]
fn the_latched_fault_is_read_through_the_session_not_the_program() {
    use gcodec_exec::session::Step;
    let profile = Arc::new(example_profile("iov2.toml"));
    let scenario =
        gcodec_profile::load_scenario("initial_fault = true\ninitial_fault_reason = 7\n")
            .expect("scenario");
    let machine = gcodec_exec::machine::SimulatedMachine::with_scenario(&profile, &scenario)
        .expect("machine");
    let file = Arc::new(SourceFile::new("FAULT.MPF", "N10 T1 M6\nN20 M30\n"));
    let main = common::runs::compile_main(&file, &profile, &gcodec_driver::Definitions::new());
    common::runs::in_session(&profile, main.program, machine, |session| {
        assert!(matches!(session.step(), Step::Ended(Ok(_))));
        let changer = session.machine().toolchanger().expect("a toolchanger");
        assert_eq!(changer.fault().map(|f| f.0), Some(7));
        assert_eq!(changer.state().name(), "idle");
    });
}

/// A hard fault below 0 shows the operator a message before the alarm;
/// one of 0 aborts without (LinuxCNC's `[TASK]IO_ERROR` rule).
#[test]
fn a_hard_fault_below_zero_shows_an_operator_message_and_zero_does_not() {
    for (reason, message) in [(-5, Some("toolchanger error -5")), (0, None)] {
        let mut setup = setup(example_profile("iov2.toml"), None);
        let text = format!(
            "[[inject]]\nat = \"prepare\"\nn = 1\nafter_cycles = 1\naction = \"fault\"\nfault_reason = {reason}\n"
        );
        let file = SourceFile::new("FAULT.TOML", text);
        setup.toolchanger =
            Some(gcodec_driver::load_toolchanger(&file, &setup.profile).expect("a scenario"));
        let events = events("N10 T1 M6\nN20 M30\n", &setup);
        let messages: Vec<&str> = events
            .iter()
            .filter_map(|e| match &e.kind {
                EventKind::Message(m) => Some(m.text.as_str()),
                _ => None,
            })
            .collect();
        assert_eq!(
            messages,
            message.into_iter().collect::<Vec<_>>(),
            "{reason}"
        );
        assert_eq!(
            diagnostic_codes(&events),
            vec!["gcodec::run::machine_error"]
        );
    }
}
