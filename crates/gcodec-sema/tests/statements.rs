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