//! Toolchanger scenarios: the shipped examples load, every key reads as
//! `docs/toolchanger.md` says, and each kind of bad scenario is a
//! diagnostic with its code and a span on the offending text.

use std::path::PathBuf;

use gcodec_profile::{InjectAction, InjectAt, Injection, Scenario, load_scenario};

/// Each diagnostic of a rejected scenario as its code and the text its
/// first label spans.
fn rejected(text: &str) -> Vec<(&'static str, String)> {
    let diagnostics = load_scenario(text).expect_err("the scenario is rejected");
    diagnostics
        .iter()
        .map(|d| {
            let span = d.span().expect("a labelled span");
            (
                d.code.name(),
                text[span.start as usize..span.end as usize].to_owned(),
            )
        })
        .collect()
}

#[test]
fn an_empty_scenario_is_the_default_changer() {
    let scenario = load_scenario("").expect("loads");
    assert_eq!(scenario, Scenario::default());
    assert_eq!(scenario.ack_cycles, 1);
    assert!(scenario.inject.is_empty());
}

#[test]
fn every_key_is_read() {
    let scenario = load_scenario(
        r#"
ack_cycles = 3
timeout_cycles = 20
initial_tool = 2
initial_fault = true
initial_fault_reason = 7

[[inject]]
at = "prepare"
n = 2
after_cycles = 1
action = "fault"
fault_reason = -5
hold_cycles = 4

[[inject]]
at = "block"
n = 30
pass = 2
action = "clear"

[[inject]]
at = "change"
n = 1
action = "abort"
abort_reason = 8

[[inject]]
at = "start_change"
n = 1
action = "never_ack"

[[inject]]
at = "abort"
n = 1
action = "delay_ack"
hold_cycles = 5
"#,
    )
    .expect("loads");
    assert_eq!(scenario.ack_cycles, 3);
    assert_eq!(scenario.timeout_cycles, Some(20));
    assert_eq!(scenario.initial_tool.map(|t| t.into_inner()), Some(2));
    assert_eq!(scenario.initial_fault, Some(7));
    assert_eq!(
        scenario.inject,
        [
            Injection {
                at: InjectAt::Prepare(2),
                after_cycles: 1,
                action: InjectAction::Fault {
                    reason: -5,
                    hold_cycles: Some(4)
                },
            },
            Injection {
                at: InjectAt::Block { line: 30, pass: 2 },
                after_cycles: 0,
                action: InjectAction::Clear,
            },
            Injection {
                at: InjectAt::Change(1),
                after_cycles: 0,
                action: InjectAction::Abort { reason: 8 },
            },
            Injection {
                at: InjectAt::StartChange(1),
                after_cycles: 0,
                action: InjectAction::NeverAck,
            },
            Injection {
                at: InjectAt::Abort(1),
                after_cycles: 0,
                action: InjectAction::DelayAck { cycles: 5 },
            },
        ]
    );
}

#[test]
fn a_fault_held_until_cleared_has_no_hold_cycles() {
    let scenario =
        load_scenario("[[inject]]\nat = \"block\"\nn = 4\naction = \"fault\"\nfault_reason = 0\n")
            .expect("loads");
    assert_eq!(
        scenario.inject[0].action,
        InjectAction::Fault {
            reason: 0,
            hold_cycles: None
        }
    );
}

#[test]
fn text_that_is_not_toml_is_a_syntax_error() {
    let found = rejected("ack_cycles = \n");
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].0, "gcodec::scenario::syntax");
}

#[test]
fn unknown_keys_names_and_types_are_schema_errors() {
    assert_eq!(
        rejected("ack_cycle = 2\n"),
        [("gcodec::scenario::schema", "ack_cycle".to_owned())]
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"tool_change\"\nn = 1\naction = \"clear\"\n")[0].0,
        "gcodec::scenario::schema"
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\nn = 1\naction = \"explode\"\n")[0].0,
        "gcodec::scenario::schema"
    );
    assert_eq!(
        rejected("initial_tool = \"T3\"\n")[0].0,
        "gcodec::scenario::schema"
    );
    // `at`, `n` and `action` have no default.
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\naction = \"clear\"\n")[0].0,
        "gcodec::scenario::schema"
    );
}

#[test]
fn counts_start_at_one() {
    assert_eq!(
        rejected(
            "ack_cycles = 0\n[[inject]]\nat = \"block\"\nn = 0\npass = 0\naction = \"fault\"\nfault_reason = 1\nhold_cycles = 0\n"
        ),
        [
            ("gcodec::scenario::out_of_range", "0".to_owned()),
            ("gcodec::scenario::out_of_range", "0".to_owned()),
            ("gcodec::scenario::out_of_range", "0".to_owned()),
            ("gcodec::scenario::out_of_range", "0".to_owned()),
        ]
    );
    assert_eq!(
        rejected("timeout_cycles = 0\n"),
        [("gcodec::scenario::out_of_range", "0".to_owned())]
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\nn = 1\naction = \"abort\"\nabort_reason = 0\n"),
        [("gcodec::scenario::out_of_range", "0".to_owned())]
    );
}

#[test]
fn an_action_without_its_value_is_missing_value() {
    assert_eq!(
        rejected("[[inject]]\nat = \"prepare\"\nn = 1\naction = \"fault\"\n"),
        [("gcodec::scenario::missing_value", "\"fault\"".to_owned())]
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\nn = 1\naction = \"abort\"\n"),
        [("gcodec::scenario::missing_value", "\"abort\"".to_owned())]
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\nn = 1\naction = \"delay_ack\"\n"),
        [(
            "gcodec::scenario::missing_value",
            "\"delay_ack\"".to_owned()
        )]
    );
    assert_eq!(
        rejected("initial_fault = true\n"),
        [("gcodec::scenario::missing_value", "true".to_owned())]
    );
}

#[test]
fn a_key_the_entry_does_not_use_is_rejected() {
    assert_eq!(
        rejected(
            "[[inject]]\nat = \"change\"\nn = 1\npass = 2\naction = \"clear\"\nfault_reason = 3\nabort_reason = 8\nhold_cycles = 2\n"
        ),
        [
            ("gcodec::scenario::key_not_applicable", "2".to_owned()),
            ("gcodec::scenario::key_not_applicable", "3".to_owned()),
            ("gcodec::scenario::key_not_applicable", "8".to_owned()),
            ("gcodec::scenario::key_not_applicable", "2".to_owned()),
        ]
    );
    assert_eq!(
        rejected("[[inject]]\nat = \"change\"\nn = 1\nafter_cycles = 3\naction = \"never_ack\"\n"),
        [("gcodec::scenario::key_not_applicable", "3".to_owned())]
    );
    assert_eq!(
        rejected("initial_fault = false\ninitial_fault_reason = -2\n"),
        [("gcodec::scenario::key_not_applicable", "-2".to_owned())]
    );
}

fn examples_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/toolchanger")
}

/// One scenario a case, each with a comment header saying what it shows.
#[test]
fn every_example_scenario_loads() {
    let mut names: Vec<String> = std::fs::read_dir(examples_dir())
        .expect("examples/toolchanger/")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "fault_while_changing.toml",
            "hard_fault_at_prepare.toml",
            "never_ack_timeout.toml",
            "normal.toml",
            "operator_abort.toml",
            "random_changer.toml",
            "soft_fault.toml",
        ]
    );
    for name in &names {
        let text = std::fs::read_to_string(examples_dir().join(name)).expect("readable");
        assert!(text.starts_with("# "), "{name}: no comment header");
        if let Err(d) = load_scenario(&text) {
            panic!("{name}: {d:#?}");
        }
    }
}

/// The machines the examples run on: the recorded traces' changers.
#[test]
fn the_example_profiles_load_with_their_toolchanger() {
    for (name, random) in [("iov2.toml", false), ("random.toml", true)] {
        let text =
            std::fs::read_to_string(examples_dir().join("profile").join(name)).expect("readable");
        let profile = gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"));
        let toolchanger = profile.toolchanger.expect("a [toolchanger] table");
        assert!(toolchanger.support_start_change, "{name}");
        assert_eq!(toolchanger.random, random, "{name}");
    }
}
