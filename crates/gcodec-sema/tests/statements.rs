//! Statements that were read as something else (issue 16): interrupt
//! assignments, named addresses read as variables, M functions of one
//! auxiliary-function group, `T0`, `EXTCALL`.

use gcodec_sema::Lowered;
use serde_json::json;

mod common;

use common::{errors, kinds, ops};

fn lower(src: &str) -> Lowered {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    common::lower_with(&profile, src)
}

#[test]
fn setint_assigns_the_routine_without_calling_it() {
    let l = lower("N10 SETINT(3) PRIO=1 LIFT_Z\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(kinds(&l), ["interrupt_assign", "m_function", "end"]);
    assert_eq!(
        ops(&l, "interrupt_assign"),
        [
            json!({"kind": "interrupt_assign", "input": 3.0, "priority": 1.0,
                "routine": "LIFT_Z", "lift_fast": false, "block_sync": false})
        ]
    );
}

#[test]
fn setint_takes_liftfast_and_blsync_and_lowers_the_rest_of_its_block() {
    let l = lower(
        "SETINT(2) PRIO=5 LIFTFAST\nSETINT(R1) PRIO=R2 AL600 LIFTFAST BLSYNC G1 X5 F100\nM30\n",
    );
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let assigns = ops(&l, "interrupt_assign");
    assert_eq!(assigns[0]["routine"], json!(null));
    assert_eq!(assigns[0]["lift_fast"], json!(true));
    assert_eq!(assigns[1]["routine"], json!("AL600"));
    assert_eq!(assigns[1]["block_sync"], json!(true));
    assert_eq!(assigns[1]["input"]["op"], json!("var"), "{assigns:?}");
    assert_eq!(ops(&l, "motion").len(), 1);
    assert!(ops(&l, "call").is_empty());
}

#[test]
fn enable_disable_and_clrint_act_on_an_input() {
    let l = lower("ENABLE(3)\nDISABLE(3)\nCLRINT(8)\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let actions: Vec<_> = ops(&l, "interrupt_control")
        .iter()
        .map(|o| (o["action"].clone(), o["input"].clone()))
        .collect();
    assert_eq!(
        actions,
        [
            (json!("enable"), json!(3.0)),
            (json!("disable"), json!(3.0)),
            (json!("clear"), json!(8.0))
        ]
    );
}

#[test]
fn interrupt_inputs_priorities_and_routines_out_of_the_rules_are_errors() {
    for src in [
        "SETINT(9) PRIO=1 LIFT_Z\n",
        "SETINT(0) PRIO=1 LIFT_Z\n",
        "SETINT(3) PRIO=129 LIFT_Z\n",
        "SETINT(3) PRIO=0 LIFT_Z\n",
        "SETINT(3) LIFT_Z\n",
        "SETINT(3) PRIO=1\n",
        "SETINT(3) PRIO=1 ONE TWO\n",
        "SETINT() PRIO=1 LIFT_Z\n",
        "ENABLE(2.5)\n",
        "DISABLE(3,4)\n",
        "CLRINT()\n",
    ] {
        let l = lower(src);
        assert_eq!(errors(&l), ["gcodec::lower::interrupt"], "{src}");
        assert!(ops(&l, "call").is_empty(), "{src}");
    }
}

fn lower_5axis(src: &str) -> Lowered {
    common::lower_with(&common::profile("mill_5axis.toml"), src)
}

#[test]
fn addresses_written_like_variables_lower_as_addresses() {
    let l = lower_5axis(
        "G1 X5 F100 MEAS=1\nMEAW=1\nOS[X]=1\nREPOSA RMIBL DISPR=5\nFGREF[A]=10\nJERKLIM[X]=50\nVELOLIM[X]=50\nFMA[2,X]=100\nOST1[X]=2\nCPLNUM[X,Y]=2\nTOFFL[1]=3\nM30\n",
    );
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert!(ops(&l, "assign").is_empty());
    let written: Vec<String> = ops(&l, "address")
        .iter()
        .map(|a| {
            let mut w = a["address"].as_str().unwrap().to_owned();
            for key in ["extension", "axis", "leading_axis"] {
                if let Some(part) = a.get(key) {
                    w.push_str(&format!(" {key}={part}"));
                }
            }
            format!("{w} {} {}", a["scope"], a["value"])
        })
        .collect();
    assert_eq!(
        written,
        [
            "MEAS \"block\" 1.0",
            "MEAW \"block\" 1.0",
            "OS axis=\"X\" \"modal\" 1.0",
            "DISPR \"block\" 5.0",
            "FGREF axis=\"A\" \"modal\" 10.0",
            "JERKLIM axis=\"X\" \"modal\" 50.0",
            "VELOLIM axis=\"X\" \"modal\" 50.0",
            "FMA extension=2 axis=\"X\" \"block\" 100.0",
            "OST1 axis=\"X\" \"modal\" 2.0",
            "CPLNUM axis=\"X\" leading_axis=\"Y\" \"modal\" 2.0",
            "TOFFL extension=1 \"modal\" 3.0",
        ]
    );
}

#[test]
fn a_variable_named_like_an_address_stays_a_variable() {
    let l = lower("DEF REAL OSE\nOSE=5\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(ops(&l, "assign").len(), 1);
    assert!(ops(&l, "address").is_empty());
}

#[test]
fn named_addresses_with_the_wrong_brackets_are_errors() {
    for (src, code) in [
        ("OS=1\n", "gcodec::lower::missing_axis"),
        ("FMA[X]=1\n", "gcodec::lower::missing_axis"),
        ("MEAS[X]=1\n", "gcodec::lower::extension_not_allowed"),
        ("OS[X,Y]=1\n", "gcodec::lower::extension_not_allowed"),
        ("FMA[-1,X]=1\n", "gcodec::lower::invalid_value"),
        ("VELOLIM[Q]=1\n", "gcodec::lower::unknown_address"),
    ] {
        assert_eq!(errors(&lower(src)), [code], "{src}");
    }
}

#[test]
fn two_m_functions_of_one_auxiliary_group_are_alarm_14760() {
    for src in ["S1000 M3 M5\n", "M0 M30\n", "M1=3 M1=70\n", "M0=4 M5\n"] {
        let l = lower(src);
        assert_eq!(errors(&l), ["gcodec::lower::m_group_conflict"], "{src}");
    }
    // Other groups, another spindle than the master, computed values: not
    // here (the run checks computed ones).
    let profile = common::machine("spindles = [1, 2]\n");
    for src in ["S1000 M3 M8\n", "M3 M2=5\n", "M3 M=R1\n", "M0\nM30\n"] {
        let l = common::lower_with(&profile, src);
        assert_eq!(errors(&l), Vec::<&str>::new(), "{src}");
    }
}

#[test]
fn auxiliary_groups_are_the_profiles() {
    let profile =
        common::machine("spindles = [1]\n[m_functions]\nauxiliary_groups = { 7 = [8, 9] }\n");
    assert_eq!(
        errors(&common::lower_with(&profile, "M8 M9\n")),
        ["gcodec::lower::m_group_conflict"]
    );
    assert_eq!(
        errors(&common::lower_with(&profile, "S100 M3 M5\n")),
        Vec::<&str>::new()
    );
}

#[test]
fn a_computed_m_value_acts_after_the_blocks_motion() {
    let l = lower("G0 X10 M=2*15\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(
        kinds(&l),
        ["modal_change", "motion", "m_function", "m_function", "end"]
    );
    assert_eq!(ops(&l, "m_function")[0]["timing"], json!("post_motion"));
    // Without a motion it acts in the block, as constants do.
    let l = lower("M=2*15\n");
    assert_eq!(ops(&l, "m_function")[0]["timing"], json!("in_block"));
}

#[test]
fn t0_is_accepted_under_tool_management() {
    let tm = common::machine("spindles = [1]\n[tool_change]\ntool_management_enabled = true\n");
    let l = common::lower_with(&tm, "T0\nM6\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(ops(&l, "tool_select")[0]["selector_value"], json!("0"));
    // Any other plain number still names no tool there.
    assert_eq!(
        errors(&common::lower_with(&tm, "T5\n")),
        ["gcodec::lower::tool_selector_form"]
    );
}

#[test]
fn extcall_with_and_without_parentheses_calls_an_external_program() {
    let l = lower("EXTCALL \"SUB\"\nEXTCALL(\"/_N_EXT_DIR/SUB\")\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let calls = ops(&l, "call");
    assert_eq!(calls.len(), 2);
    for (call, name) in calls.iter().zip(["SUB", "/_N_EXT_DIR/SUB"]) {
        assert_eq!(call["target"], json!(""));
        assert_eq!(call["target_expr"], json!({"op": "string", "value": name}));
        assert_eq!(call["external"], json!(true));
    }
    assert_eq!(
        errors(&lower("EXTCALL(\"A\",\"B\")\n")),
        ["gcodec::lower::invalid_value"]
    );
}

#[test]
fn a_number_after_an_axial_address_is_an_extension_it_does_not_take() {
    // Not "`FA2` is not defined": `FA` takes its axis in brackets.
    assert_eq!(
        errors(&lower("FA2=400\n")),
        ["gcodec::lower::extension_not_allowed"]
    );
    assert_eq!(
        errors(&lower("OS1=1\n")),
        ["gcodec::lower::extension_not_allowed"]
    );
}

#[test]
fn extension_0_is_the_master_spindle_for_s_as_for_m_and_spos() {
    let l = lower("S0=1000 M0=3\nS[0]=500\nSPOS0=90\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let spindles: Vec<_> = ops(&l, "spindle_speed")
        .iter()
        .map(|s| s["spindle"].clone())
        .collect();
    assert_eq!(spindles, [json!(0), json!(0)]);
    assert_eq!(
        errors(&lower("S2=1000\n")),
        ["gcodec::lower::unknown_spindle"]
    );
}
