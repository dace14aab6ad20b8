//! The tool-change design's test matrix, executor and integration rows,
//! one named test each (the parser and AIL rows, and the lowering side of
//! the M-function row, are `gcodec-sema`'s
//! `tool_m_functions_offsets::tool_change_design_matrix`). The golden
//! streams of the modes are the run fixtures `tools.mpf`,
//! `tool_management.mpf`, `tool_change_direct.mpf` and
//! `tool_change_direct_tm.mpf`.

mod common;

use common::tools::{assert_clean, changes, diagnostics, expect, run_tools};
use gcodec_exec::event::{EventKind, MAction, ProgramEndReason, SelectionSource, ToolTiming};
use gcodec_profile::Profile;
use gcodec_source::Severity;

fn machine(tool_change: &str) -> Profile {
    gcodec_testkit::machine(&format!(
        "spindles = [1]\n[tool_change]\n{tool_change}\n\
         [[tools]]\nnumber = 1\nedges = [{{ d = 1, length = 100.0 }}, {{ d = 2, length = 90.0 }}]\n\
         [[tools]]\nnumber = 2\nedges = [{{ d = 1, length = 50.0 }}]\n"
    ))
}

/// Executor: direct-change flow. `T` changes at once (`direct_t_word`),
/// nothing stays pending; `$P_TOOLP` is the last programmed T.
#[test]
fn executor_direct_change_flow() {
    let program = format!(
        "T1\n{}{}T2\n{}M30\n",
        expect("$P_TOOLNO", 1.0),
        expect("$P_TOOLP", 1.0),
        expect("$P_TOOLNO", 2.0)
    );
    let events = run_tools(
        &machine("tool_change_mode = \"direct\""),
        &program,
        &[],
        None,
    );
    assert_clean(&events, "direct");
    let changes: Vec<_> = changes(&events)
        .iter()
        .map(|c| {
            (
                c.previous_tool.clone(),
                c.new_tool.clone(),
                c.selection_source,
            )
        })
        .collect();
    assert_eq!(
        changes,
        [
            (None, Some("T1".into()), SelectionSource::DirectTWord),
            (
                Some("T1".into()),
                Some("T2".into()),
                SelectionSource::DirectTWord
            ),
        ]
    );
    assert!(events.iter().any(|e| matches!(
        &e.kind,
        EventKind::ToolSelect(s) if s.timing == ToolTiming::Immediate
    )));
}

/// Executor: preselect + M6 flow. `T` waits (`$P_TOOLP`), the change M
/// makes it active (`pending_then_m6`); `$P_TOOLP` stays the last
/// programmed T.
#[test]
fn executor_preselect_then_m6_flow() {
    let program = format!(
        "T1\n{}{}M6\n{}{}M30\n",
        expect("$P_TOOLP", 1.0),
        expect("$P_TOOLNO", 0.0),
        expect("$P_TOOLNO", 1.0),
        expect("$P_TOOLP", 1.0)
    );
    let events = run_tools(&machine(""), &program, &[], None);
    assert_clean(&events, "deferred");
    let [change] = changes(&events)[..] else {
        panic!("one change");
    };
    assert_eq!(change.new_tool.as_deref(), Some("T1"));
    assert_eq!(change.selection_source, SelectionSource::PendingThenM6);
    assert!(events.iter().any(|e| matches!(
        &e.kind,
        EventKind::ToolSelect(s) if s.timing == ToolTiming::DeferredUntilM6
    )));
}

/// Executor: M6 without a pending selection under each
/// `m6_without_pending_policy`.
#[test]
fn executor_m6_without_pending_per_policy() {
    let program = "T1 M6\nM6\nM30\n";
    let alarm = run_tools(
        &machine("m6_without_pending_policy = \"error\""),
        program,
        &[],
        None,
    );
    assert_eq!(
        diagnostics(&alarm, Severity::Error),
        (
            vec![("gcodec::run::m6_without_pending", 2)],
            ProgramEndReason::Alarm
        )
    );
    for (policy, warnings) in [
        ("warning", vec![("gcodec::run::m6_without_pending", 2)]),
        ("ignore", vec![]),
    ] {
        let events = run_tools(
            &machine(&format!("m6_without_pending_policy = \"{policy}\"")),
            program,
            &[],
            None,
        );
        assert_eq!(
            diagnostics(&events, Severity::Warning),
            (warnings, ProgramEndReason::M30),
            "{policy}"
        );
        let last = changes(&events)[1];
        assert_eq!(
            (
                last.previous_tool.as_deref(),
                last.new_tool.as_deref(),
                last.selection_source
            ),
            (Some("T1"), Some("T1"), SelectionSource::M6WithoutPending),
            "{policy}: the tool stays"
        );
    }
}

/// Executor: of several selections before the change, the last wins.
#[test]
fn executor_last_selection_wins_before_m6() {
    let program = format!("T1\nT2\n{}M6\nM30\n", expect("$P_TOOLP", 2.0));
    let events = run_tools(&machine(""), &program, &[], None);
    assert_clean(&events, "last wins");
    let new: Vec<_> = changes(&events)
        .iter()
        .map(|c| c.new_tool.clone())
        .collect();
    assert_eq!(new, [Some("T2".to_owned())]);
}

/// Integration: the change M is an M function of class `tool` (its
/// `m_function` event, action `tool_change`) and then the change; a
/// machine with another change M changes with that one.
#[test]
fn integration_change_m_goes_through_the_m_function_path() {
    for (tool_change, program) in [
        ("", "T1\nM6\nM30\n"),
        ("change_m_code = 206", "T1\nM206\nM30\n"),
    ] {
        let events = run_tools(&machine(tool_change), program, &[], None);
        let line2: Vec<&str> = events
            .iter()
            .filter(|e| e.source.line == 2)
            .map(|e| match &e.kind {
                EventKind::MFunction(m) if m.action == MAction::ToolChange => "m_function",
                EventKind::ToolChange(_) => "tool_change",
                _ => "other",
            })
            .filter(|k| *k != "other")
            .collect();
        assert_eq!(line2, ["m_function", "tool_change"], "{program}");
    }
}

/// Integration: tool-offset side effects. After a change the new tool's
/// `D1` (the default `cutting_edge_default`) and its length are active;
/// the length is traversed with the next motion of the infeed axis, `D0`
/// takes it away, and the change to no tool leaves `D0`.
#[test]
fn integration_tool_offset_side_effects() {
    let program = format!(
        "T1 M6\n{}G0 Z0\n{}D2\nG0 X5\n{}G0 Z0\n{}D0\nG0 Z0\n{}T0 M6\n{}{}M30\n",
        expect("$P_TOOL", 1.0),
        expect("$AA_IM[Z]", 100.0),
        expect("$AA_IM[Z]", 100.0),
        expect("$AA_IM[Z]", 90.0),
        expect("$AA_IM[Z]", 0.0),
        expect("$P_TOOL", 0.0),
        expect("$P_TOOLNO", 0.0)
    );
    let events = run_tools(&machine(""), &program, &[], None);
    assert_clean(&events, "offsets");
}
