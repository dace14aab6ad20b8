//! Tool resolution as a policy (an application's own resolver through
//! the public API, each outcome under each `on_unresolved_tool`), the
//! pending selection per program level, and the cutting edge after a
//! change (MD20270, MD22562 bit 2); `$P_TOOLNO`, `$P_TOOLP` and `$P_TOOL`
//! read in the programs after each case.

mod common;

use common::tools::{assert_clean, changes, diagnostics, expect, jsonl, run_tools};
use gcodec_exec::event::{EventKind, ProgramEndReason, SelectorKind};
use gcodec_exec::tool_resolution::{
    ResolutionContext, TableResolver, ToolRef, ToolResolution, ToolResolver, ToolSelector,
};
use gcodec_profile::Profile;
use gcodec_source::Severity;

fn tool(label: &str, number: u32) -> ToolRef {
    ToolRef {
        label: label.to_owned(),
        number,
    }
}

/// A resolver that gives the same answer to every selection.
struct Answer(ToolResolution);

impl ToolResolver for Answer {
    fn resolve_selection(
        &self,
        _: &ToolSelector,
        _: &Profile,
        _: &ResolutionContext<'_>,
    ) -> ToolResolution {
        self.0.clone()
    }
}

/// A tool-management database that holds two tools for every name and no
/// rule to choose; it gives them out of number order.
fn two_of_each() -> Option<Box<dyn ToolResolver>> {
    Some(Box::new(Answer(ToolResolution::Ambiguous {
        candidates: vec![tool("T5", 5), tool("T3", 3)],
    })))
}

/// A resolver that replaces every selection by the sister tool T9.
fn always_t9() -> Option<Box<dyn ToolResolver>> {
    Some(Box::new(Answer(ToolResolution::Resolved {
        tool: tool("T9", 9),
        substituted: true,
    })))
}

fn machine(tool_change: &str) -> Profile {
    gcodec_testkit::machine(&format!("spindles = [1]\n[tool_change]\n{tool_change}\n"))
}

/// The machine with two tools of several edges each.
fn with_tools(tool_change: &str) -> Profile {
    gcodec_testkit::machine(&format!(
        "spindles = [1]\n[tool_change]\n{tool_change}\n\
         [[tools]]\nnumber = 1\nedges = [{{ d = 1, length = 100.0 }}, {{ d = 2, length = 90.0 }}]\n\
         [[tools]]\nnumber = 2\nedges = [{{ d = 1, length = 50.0 }}, {{ d = 2, length = 40.0 }}]\n"
    ))
}

fn policy(name: &str) -> String {
    format!("on_unresolved_tool = \"{name}\"")
}

// ---- resolution ----

/// The ambiguous outcome under each policy, as golden streams: `error`
/// is the alarm `ambiguous_tool` listing the candidates by number,
/// `warning` warns and goes on with the selection as written, `fallback`
/// takes the first candidate of that order silently.
#[test]
fn an_ambiguous_selection_follows_on_unresolved_tool() {
    for name in ["error", "warning", "fallback"] {
        let events = run_tools(
            &machine(&policy(name)),
            "N10 T7\nN20 M6\nN30 M30\n",
            &[],
            two_of_each(),
        );
        insta::assert_snapshot!(format!("ambiguous_{name}"), jsonl(&events));
    }
}

#[test]
fn the_ambiguous_alarm_lists_the_candidates_by_number() {
    let events = run_tools(&machine(""), "T7\nM30\n", &[], two_of_each());
    let message = events
        .iter()
        .find_map(|e| match &e.kind {
            EventKind::Diagnostic(d) => Some(d.message.to_string()),
            _ => None,
        })
        .expect("an alarm");
    assert_eq!(
        message,
        "the tool `7` is ambiguous: T3, T5 fit, and the tool resolver has no rule to choose"
    );
}

/// A resolver's substitution counts only where the profile allows it;
/// elsewhere it is unresolved.
#[test]
fn a_resolver_substitutes_only_with_allow_substitution() {
    let allowed = run_tools(
        &machine("allow_substitution = true"),
        &format!(
            "T7\n{}M6\n{}M30\n",
            expect("$P_TOOLP", 9.0),
            expect("$P_TOOLNO", 9.0)
        ),
        &[],
        always_t9(),
    );
    assert_clean(&allowed, "allowed");
    let change = changes(&allowed)[0];
    assert_eq!(
        (change.new_tool.as_deref(), change.substituted),
        (Some("T9"), true)
    );

    let refused = run_tools(&machine(""), "T7\nM6\nM30\n", &[], always_t9());
    assert_eq!(
        diagnostics(&refused, Severity::Error),
        (
            vec![("gcodec::run::unresolved_tool", 1)],
            ProgramEndReason::Alarm
        )
    );
}

/// The table resolver, asked directly: the first enabled sister tool by
/// duplo number, a substitution only when allowed, never ambiguous.
#[test]
fn the_table_resolver_takes_the_first_enabled_sister_tool() {
    let profile = |substitution: bool| {
        gcodec_testkit::machine(&format!(
            "[tool_change]\ntool_management_enabled = true\nallow_substitution = {substitution}\n\
             [[tools]]\nnumber = 4\nname = \"DRILL\"\nduplo = 3\n\
             [[tools]]\nnumber = 1\nname = \"DRILL\"\nstate = \"locked\"\n\
             [[tools]]\nnumber = 2\nname = \"DRILL\"\nduplo = 2\n"
        ))
    };
    let selector = ToolSelector {
        kind: SelectorKind::Name,
        value: "drill".into(),
    };
    let resolve = |profile: &Profile| {
        let context = ResolutionContext {
            active_tool: None,
            tools: &profile.tools,
            tool_management: true,
        };
        TableResolver.resolve_selection(&selector, profile, &context)
    };
    assert_eq!(
        resolve(&profile(true)),
        ToolResolution::Resolved {
            tool: tool("DRILL", 2),
            substituted: true
        }
    );
    assert!(matches!(
        resolve(&profile(false)),
        ToolResolution::Unresolved { .. }
    ));
}

/// Resolution sees the run's tool table: a tool the program made by
/// writing its data is selected, where the profile has a table.
#[test]
fn a_tool_the_program_writes_resolves() {
    let events = run_tools(
        &with_tools(""),
        &format!(
            "R1=5\n$TC_DP3[5,1]=20\nT=R1\nM6\n{}M30\n",
            expect("$P_TOOLNO", 5.0)
        ),
        &[],
        None,
    );
    assert_clean(&events, "written tool");
}

// ---- the pending selection per program level ----

/// `main` calling `SUB` (`sub`) under `pending_selection_scope = scope`.
fn run_with_sub(scope: &str, main: &str, sub: &str) -> Vec<gcodec_exec::event::Event> {
    run_tools(
        &machine(&format!("pending_selection_scope = \"{scope}\"")),
        main,
        &[("SUB.SPF", sub)],
        None,
    )
}

/// A selection before a call and the change in the subprogram: with the
/// channel scope the subprogram changes to it; per program level the
/// subprogram has none (its change keeps the tool) and the caller's comes
/// back at the return. `$P_TOOLP` is the last programmed T either way.
#[test]
fn a_selection_before_a_call_is_changed_in_it_per_scope() {
    for (scope, sub_tool, pending_after, new_tools) in [
        ("channel", 1.0, 1.0, vec![Some("T1"), Some("T1")]),
        ("program_level", 0.0, 1.0, vec![None, Some("T1")]),
    ] {
        let main = format!("T1\nSUB\n{}M6\nM30\n", expect("$P_TOOLP", pending_after));
        let sub = format!("M6\n{}M17\n", expect("$P_TOOLNO", sub_tool));
        let events = run_with_sub(scope, &main, &sub);
        assert_clean(&events, scope);
        let new: Vec<_> = changes(&events)
            .iter()
            .map(|c| c.new_tool.as_deref())
            .collect();
        assert_eq!(new, new_tools, "{scope}");
    }
}

/// A selection in a subprogram and the change after its return: kept
/// with the channel scope, dropped per program level.
#[test]
fn a_selection_in_a_subprogram_is_changed_after_its_return_per_scope() {
    for (scope, pending_after, new_tool) in
        [("channel", 2.0, Some("T2")), ("program_level", 0.0, None)]
    {
        let main = format!("SUB\n{}M6\nM30\n", expect("$P_TOOLP", pending_after));
        let sub = format!("T2\n{}M17\n", expect("$P_TOOLP", 2.0));
        let events = run_with_sub(scope, &main, &sub);
        assert_clean(&events, scope);
        assert_eq!(changes(&events)[0].new_tool.as_deref(), new_tool, "{scope}");
    }
}

/// Per program level, each pass of a call starts with none, and the
/// caller's selection comes back after the last.
#[test]
fn every_pass_of_a_call_starts_without_a_selection_per_program_level() {
    let main = format!("T1\nSUB P3\n{}M30\n", expect("$P_TOOLP", 1.0));
    let sub = format!("{}T2\nM17\n", expect("$P_TOOLP", 0.0));
    let events = run_with_sub("program_level", &main, &sub);
    assert_clean(&events, "passes");
}

// ---- the cutting edge after a change ----

/// `cutting_edge_default` 0, n, −1 and −2 after `T1 M6 D2` and a change to
/// T2 without a `D`; the edge (`$P_TOOL`) and the length traversed by the
/// next motion of Z (`$AA_IM[Z]`).
#[test]
fn the_edge_after_a_change_follows_cutting_edge_default() {
    for (default, edge, length) in [
        (0, 0.0, 0.0),
        (1, 1.0, 50.0),
        (2, 2.0, 40.0),
        (-1, 2.0, 40.0),
        (-2, 2.0, 90.0),
    ] {
        let program = format!(
            "T1 M6 D2\nT2 M6\n{}G0 Z0\n{}{}M30\n",
            expect("$P_TOOL", edge),
            expect("$AA_IM[Z]", length),
            expect("$P_TOOLNO", 2.0)
        );
        let events = run_tools(
            &with_tools(&format!("cutting_edge_default = {default}")),
            &program,
            &[],
            None,
        );
        assert_clean(&events, &format!("cutting_edge_default = {default}"));
    }
}

/// With −2 the old tool's offset stays only until a `D` is programmed: the
/// `D` then selects the new tool's edge.
#[test]
fn the_old_offset_stays_until_a_d_is_programmed() {
    let program = format!(
        "T1 M6 D1\nT2 M6\nD1\nG0 Z0\n{}M30\n",
        expect("$AA_IM[Z]", 50.0)
    );
    let events = run_tools(
        &with_tools("cutting_edge_default = -2"),
        &program,
        &[],
        None,
    );
    assert_clean(&events, "-2 then D1");
}

/// A `D` in the change's block wins over the default.
#[test]
fn a_d_in_the_change_block_wins_over_the_default() {
    let program = format!("T1 M6 D2\n{}M30\n", expect("$P_TOOL", 2.0));
    let events = run_tools(&with_tools("cutting_edge_default = 0"), &program, &[], None);
    assert_clean(&events, "D in the block");
}

/// `D1` with no tool: no offset (MD22562 bit 2 = 0, the default) or the
/// alarm `edge_without_tool`.
#[test]
fn an_edge_without_a_tool_follows_edge_without_tool() {
    let program = format!(
        "D1\nG0 Z0\n{}{}M30\n",
        expect("$P_TOOL", 1.0),
        expect("$AA_IM[Z]", 0.0)
    );
    assert_clean(
        &run_tools(&with_tools(""), &program, &[], None),
        "no offset",
    );
    let alarm = run_tools(
        &with_tools("edge_without_tool = \"alarm\""),
        "T0 M6\nD1\nM30\n",
        &[],
        None,
    );
    assert_eq!(
        diagnostics(&alarm, Severity::Error),
        (
            vec![("gcodec::run::edge_without_tool", 2)],
            ProgramEndReason::Alarm
        )
    );
}
