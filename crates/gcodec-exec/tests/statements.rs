//! Statements that were read as something else (issue 16), run:
//! interrupt assignments, named addresses, M functions of one
//! auxiliary-function group, computed M values, `T0`, `EXTCALL`, a jump
//! to the label a STRING variable names.

use gcodec_exec::event::{Event, EventKind, ProgramEndReason};
use gcodec_source::Severity;

mod common;

/// The events of running `program` (which must compile cleanly) on
/// `profile`.
fn events_on(profile: gcodec_profile::Profile, program: &str) -> Vec<Event> {
    common::runs::events_of_text(profile, "STATEMENTS.MPF", program)
}

fn events(program: &str) -> Vec<Event> {
    events_on(
        gcodec_profile::builtin().expect("built-in profile"),
        program,
    )
}

/// The run's error diagnostics (code, line) and how it ended.
fn errors(events: &[Event]) -> (Vec<(&'static str, u32)>, ProgramEndReason) {
    let mut errors = Vec::new();
    let mut end = None;
    for event in events {
        match &event.kind {
            EventKind::Diagnostic(d) if d.severity == Severity::Error => {
                errors.push((d.code.name(), event.source.line))
            }
            EventKind::ProgramEnd(e) => end = Some(e.reason),
            _ => {}
        }
    }
    (errors, end.expect("the program ends"))
}

#[test]
fn enable_of_an_input_without_a_routine_is_an_alarm() {
    let (errors, end) = errors(&events(
        "N10 SETINT(3) PRIO=1 LIFT_Z\nN20 CLRINT(3)\nN30 ENABLE(3)\nM30\n",
    ));
    assert_eq!(errors, [("gcodec::run::interrupt", 3)]);
    assert_eq!(end, ProgramEndReason::Alarm);
}

#[test]
fn computed_interrupt_inputs_and_priorities_are_checked_when_they_run() {
    for program in [
        "R1=9\nSETINT(R1) PRIO=1 LIFT_Z\nM30\n",
        "R1=200\nSETINT(3) PRIO=R1 LIFT_Z\nM30\n",
        "R1=0\nDISABLE(R1)\nM30\n",
    ] {
        let (errors, end) = errors(&events(program));
        assert_eq!(errors, [("gcodec::run::interrupt", 2)], "{program}");
        assert_eq!(end, ProgramEndReason::Alarm, "{program}");
    }
}

/// The messages of the `not_simulated` advice of a run.
fn advice(events: &[Event]) -> Vec<String> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Diagnostic(d) if d.code.name() == "gcodec::run::not_simulated" => {
                Some(d.message.to_string())
            }
            _ => None,
        })
        .collect()
}

#[test]
fn named_addresses_run_as_not_simulated_advice() {
    let events = events_on(
        gcodec_testkit::profile("mill_5axis.toml"),
        "G1 X5 F100 MEAS=1\nOS[X]=1\nFMA[2,X]=100\nCPSETTYPE[X]=\"CP\"\nCPLA[X]=Y\nM30\n",
    );
    assert_eq!(errors(&events), (vec![], ProgramEndReason::M30));
    assert_eq!(
        advice(&events),
        [
            "`MEAS=` has no effect in the simulation",
            "`OS=` has no effect in the simulation",
            "`FMA=` has no effect in the simulation",
            "`CPSETTYPE=` has no effect in the simulation",
            "`CPLA=` has no effect in the simulation",
        ]
    );
}

#[test]
fn a_computed_m_value_ends_the_program_after_the_blocks_motion() {
    let events = events("G0 X10 M=2*15\nG0 X20\nM30\n");
    let kinds: Vec<&str> = events.iter().map(|e| e.kind_name()).collect();
    assert_eq!(
        kinds,
        ["modal_change", "motion", "m_function", "program_end"]
    );
    assert_eq!(errors(&events), (vec![], ProgramEndReason::M30));
}

#[test]
fn a_computed_m_value_gets_the_checks_of_a_constant() {
    let profile = gcodec_testkit::machine("spindles = [1, 2]\n");
    for (program, code) in [
        (
            "R1=5\nS1000 M3 M=R1\nM30\n",
            "gcodec::run::m_group_conflict",
        ),
        ("R1=30\nM2=R1\nM30\n", "gcodec::run::m_extension_forbidden"),
        ("R1=2147483648\nM=R1\nM30\n", "gcodec::run::overflow"),
        ("R1=-1\nM=R1\nM30\n", "gcodec::run::overflow"),
    ] {
        let (errors, end) = errors(&events_on(profile.clone(), program));
        assert_eq!(errors, [(code, 2)], "{program}");
        assert_eq!(end, ProgramEndReason::Alarm, "{program}");
    }
    // Another spindle's M5 is not in the master spindle's group.
    let (errors, end) = errors(&events_on(profile, "R1=5\nS1000 M3 M2=R1\nM30\n"));
    assert_eq!((errors, end), (vec![], ProgramEndReason::M30));
}

/// The `new_tool` of every tool change of a run.
fn changes(events: &[Event]) -> Vec<Option<String>> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::ToolChange(c) => Some(c.new_tool.clone()),
            _ => None,
        })
        .collect()
}

#[test]
fn t0_empties_the_spindle_with_and_without_tool_management() {
    for (mode, management, program) in [
        ("deferred_m6", false, "T1 M6\nT0\nM6\nM30\n"),
        ("deferred_m6", true, "T=\"DRILL\" M6\nT0\nM6\nM30\n"),
        ("direct", false, "T1\nT0\nM30\n"),
        ("direct", true, "T=\"DRILL\"\nT0\nM30\n"),
    ] {
        let profile = gcodec_testkit::machine(&format!(
            "spindles = [1]\n[tool_change]\ntool_change_mode = \"{mode}\"\ntool_management_enabled = {management}\n"
        ));
        let events = events_on(profile, program);
        let first = if management { "DRILL" } else { "T1" };
        assert_eq!(
            changes(&events),
            [Some(first.to_owned()), None],
            "{mode} {management}"
        );
        assert_eq!(
            errors(&events),
            (vec![], ProgramEndReason::M30),
            "{mode} {management}"
        );
    }
}

/// `GOTOF ZIEL` with `DEF STRING[8] ZIEL="MARKE"` jumps to the label the
/// string names (it was lowered as a jump to a label `ZIEL` and stopped
/// with alarm 14080); a name that is neither stays a missing target.
#[test]
fn a_jump_to_a_string_variable_goes_to_the_label_it_names() {
    let ran =
        events("DEF STRING[8] ZIEL=\"MARKE\"\nGOTOF ZIEL\nG1 X99 F100\nMARKE:\nG1 X1 F100\nM30\n");
    assert_eq!(errors(&ran), (Vec::new(), ProgramEndReason::M30));
    let reached: Vec<u32> = ran
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Motion(_)))
        .map(|e| e.source.line)
        .collect();
    assert_eq!(reached, [5], "the block after the jump is skipped");
    let (codes, end) = errors(&events("GOTOF NOWHERE\nM30\n"));
    assert_eq!(codes, [("gcodec::run::jump_target_not_found", 1)]);
    assert_eq!(end, ProgramEndReason::Alarm);
}

/// Under `G34`/`G35` a motion block's `F` is the change of the thread
/// lead, not a feed: also in a block after a label, where lowering cannot
/// know the motion command and gives the `F` as a feed.
#[test]
fn a_thread_lead_change_after_a_label_leaves_the_feed() {
    let events = events(
        "G95 S100 M3 F0.2\nG34 Z-10 K2 F0.1\nLBL: Z-20 K2 F0.3\nR1=R1+1\nIF R1<2 GOTOB LBL\nG1 X1\nM30\n",
    );
    let feeds: Vec<Option<f64>> = events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Motion(m) => Some(m.feed),
            _ => None,
        })
        .collect();
    assert_eq!(feeds, [Some(0.2); 4]);
}
