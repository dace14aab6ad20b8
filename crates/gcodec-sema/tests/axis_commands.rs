//! G commands whose axis words do not traverse (SPEC §10.2): group 3
//! settings lower to `axis_setting`, `G74`/`G75` to `approach_point` with
//! machine-axis names; polar end points without circle data are arcs
//! about the pole.

use serde_json::json;

mod common;

use common::{codes, ops};

fn lowered(src: &str) -> gcodec_sema::Lowered {
    let profile = gcodec_profile::builtin().expect("the built-in profile");
    common::lower_with(&profile, src)
}

#[test]
fn group_three_commands_take_the_blocks_axis_words_as_values() {
    let l = lowered(
        "G1 X1 Y1 F100\nG26 X300 Y300\nG25 X-10 S100\nG111 X0 Y0\nG110 AP=45 RP=IC(2)\nG58 X5\nG59 Z1\nM30\n",
    );
    assert_eq!(codes(&l), [] as [&str; 0]);
    let settings = ops(&l, "axis_setting");
    let commands: Vec<&str> = settings
        .iter()
        .map(|s| s["command"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(commands, ["G26", "G25", "G111", "G110", "G58", "G59"]);
    assert_eq!(
        settings[0]["values"],
        json!([{"axis": "X", "value": 300.0, "mode": null}, {"axis": "Y", "value": 300.0, "mode": null}])
    );
    assert_eq!(
        settings[1]["spindle_limits"],
        json!([{"spindle": null, "speed": 100.0}])
    );
    assert_eq!(settings[3]["values"][1]["mode"], "IC");
    assert_eq!(ops(&l, "motion").len(), 1, "only the G1 block traverses");
    assert!(ops(&l, "spindle_speed").is_empty(), "`G25 S` is a limit");
}

#[test]
fn g74_and_g75_name_machine_axes() {
    let l = lowered("G75 FP=2 X1=0 Y1=0\nG74 Z1=0\nG75 Z=0\nM30\n");
    assert_eq!(codes(&l), [] as [&str; 0]);
    let approaches = ops(&l, "approach_point");
    assert_eq!(
        approaches,
        [
            json!({"kind": "approach_point", "command": "G75", "fixed_point": 2.0, "axes": ["X", "Y"]}),
            json!({"kind": "approach_point", "command": "G74", "fixed_point": null, "axes": ["Z"]}),
            json!({"kind": "approach_point", "command": "G75", "fixed_point": 1.0, "axes": ["Z"]}),
        ]
    );
    assert!(ops(&l, "motion").is_empty());
    assert!(ops(&l, "address").is_empty(), "FP belongs to G75");
}

#[test]
fn machine_axis_names_outside_g74_and_g75_are_unknown_addresses() {
    let l = lowered("G0 Z1=0\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
    let help = l.diagnostics.iter().next().and_then(|d| d.help.clone());
    assert!(
        help.is_some_and(|h| h.contains("machine axis of `Z`")),
        "{:?}",
        l.diagnostics
    );
}

#[test]
fn polar_arcs_need_no_circle_data() {
    let l = lowered("G111 X0 Y0\nG2 AP=90 RP=10 F100\nM30\n");
    assert_eq!(codes(&l), [] as [&str; 0]);
    let l = lowered("G2 X10 Y0 F100\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::missing_circle_data"]);
}
