//! Address words beyond G/M/T/D/F/S: named addresses, `H` functions,
//! dwell, spline and thread motion, computed spindle numbers, indirect G
//! commands, the dimension-modifier rules, legacy aliases and the
//! profile's unsupported G commands.

use gcodec_profile::Profile;
use gcodec_sema::{Lowered, lower};
use serde_json::{Value, json};

mod common;

use common::{codes, kinds, lower_with, machine as profile, ops};

/// X Y Z linear, C rotary, spindles 1 and 2.
fn mill() -> Profile {
    profile(
        "spindles = [1, 2]\n\
         [[axes]]\nname = \"X\"\nkind = \"linear\"\ngeometry = true\n\
         [[axes]]\nname = \"Y\"\nkind = \"linear\"\ngeometry = true\n\
         [[axes]]\nname = \"Z\"\nkind = \"linear\"\ngeometry = true\n\
         [[axes]]\nname = \"C\"\nkind = \"rotary\"\n",
    )
}

fn assert_clean(lowered: &Lowered) {
    assert!(lowered.diagnostics.is_empty(), "{:#?}", lowered.diagnostics);
}

#[test]
fn an_unknown_axis_names_the_machines_axes_and_the_nearest() {
    let help = |src: &str| {
        let l = lower_with(&mill(), src);
        assert_eq!(codes(&l), ["gcodec::lower::unknown_address"], "{src}");
        l.diagnostics[0]
            .help
            .as_deref()
            .unwrap_or_default()
            .to_owned()
    };
    let listed = "this machine's axes (the profile's `[[axes]]`) are `X`, `Y`, `Z`, `C`";
    assert_eq!(help("G1 A10 F100\n"), listed);
    assert_eq!(
        help("G1 X1=10 F100\n"),
        format!(
            "did you mean `X`? T{}; `X1` names the machine axis of `X` only with `G74`/`G75`",
            &listed[1..]
        )
    );
    assert_eq!(
        help("G0 AX[Z2]=5\n"),
        format!("did you mean `Z`? T{}", &listed[1..])
    );
}

// ---- named addresses ----

#[test]
fn settings_become_address_instructions() {
    let l = lower_with(
        &mill(),
        "FA[X]=400 FL[Y]=20 ACC[Z]=50 OVR=80 LIMS=3000 FB=100 ADIS=0.5 RNDM=2 SD=3 SF=45\n",
    );
    assert_clean(&l);
    let a = ops(&l, "address");
    assert_eq!(
        a[0],
        json!({"kind": "address", "address": "FA", "axis": "X", "value": 400.0, "scope": "modal"})
    );
    assert_eq!(a[1]["address"], "FL");
    assert_eq!(a[1]["axis"], "Y");
    assert_eq!(a[2]["address"], "ACC");
    assert_eq!(
        a[3],
        json!({"kind": "address", "address": "OVR", "value": 80.0, "scope": "modal"})
    );
    assert_eq!(a[4]["address"], "LIMS");
    assert_eq!(a[5]["address"], "FB");
    assert_eq!(a[5]["scope"], "block");
    let names: Vec<&str> = a.iter().map(|v| v["address"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "FA", "FL", "ACC", "OVR", "LIMS", "FB", "ADIS", "RNDM", "SD", "SF"
        ]
    );
}

#[test]
fn an_axial_address_needs_a_known_axis() {
    let l = lower_with(&mill(), "FA[B]=400\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
    assert!(ops(&l, "address").is_empty());
    let l = lower_with(&mill(), "ACC=50\n");
    assert_eq!(codes(&l), ["gcodec::lower::missing_axis"]);
    // A variable names the axis when the block runs.
    let l = lower_with(&mill(), "DEF AXIS AXN\nFA[AXN]=400\n");
    assert!(!codes(&l).contains(&"gcodec::lower::unknown_address"));
    let a = ops(&l, "address");
    assert_eq!(a[0]["axis_expr"]["name"], "AXN");
    assert!(a[0].get("axis").is_none());
}

#[test]
fn spos_checks_the_spindle_and_takes_rotary_modifiers() {
    let l = lower_with(
        &mill(),
        "SPOS=90\nSPOS[2]=DC(10)\nSPOSA[1]=ACP(5)\nSPOS=ACN(1)\n",
    );
    assert_clean(&l);
    let a = ops(&l, "address");
    assert_eq!(
        a[0],
        json!({"kind": "address", "address": "SPOS", "value": 90.0, "scope": "block"})
    );
    assert_eq!(
        a[1],
        json!({"kind": "address", "address": "SPOS", "extension": 2, "value": 10.0, "mode": "DC", "scope": "block"})
    );
    assert_eq!(a[2]["address"], "SPOSA");
    assert_eq!(a[2]["mode"], "ACP");
    assert_eq!(a[3]["mode"], "ACN");
    let l = lower_with(&mill(), "SPOS[3]=90\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_spindle"]);
    // A computed spindle number is left for run time.
    let l = lower_with(&mill(), "DEF INT SPI=2\nSPOS[SPI]=IC(90)\n");
    assert!(codes(&l).is_empty(), "{:?}", codes(&l));
    assert_eq!(ops(&l, "address")[0]["extension_expr"]["name"], "SPI");
    // `SPOS2=` is read by the parser as an assignment.
    let l = lower_with(&mill(), "SPOS2=DC(45)\nSPOS3=1\n");
    let a = ops(&l, "address");
    assert_eq!(a[0]["extension"], 2);
    assert_eq!(a[0]["mode"], "DC");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_spindle"]);
}

#[test]
fn fad_is_an_address_not_a_variable() {
    let l = lower_with(&mill(), "G1 G41 G147 DISR=5 FAD=200 X10 Y10\n");
    assert_clean(&l);
    let names: Vec<Value> = ops(&l, "address")
        .iter()
        .map(|a| a["address"].clone())
        .collect();
    assert_eq!(names, [json!("DISR"), json!("FAD")]);
    assert!(ops(&l, "assign").is_empty());
}

#[test]
fn an_address_twice_in_a_block_is_an_error() {
    let l = lower_with(&mill(), "OVR=50 OVR=60\n");
    assert_eq!(codes(&l), ["gcodec::lower::address_repeated"]);
    let l = lower_with(&mill(), "DL=1 DL=2\n");
    assert_eq!(codes(&l), ["gcodec::lower::address_repeated"]);
    // Different axes are different addresses.
    let l = lower_with(&mill(), "FA[X]=1 FA[Y]=2\n");
    assert_clean(&l);
}

#[test]
fn ax_names_an_axis_directly_or_when_the_block_runs() {
    let l = lower_with(&mill(), "DEF AXIS _Z\nG0 AX[X]=5 AX[_Z]=IC(3)\n");
    assert!(!codes(&l).iter().any(|c| c.contains("address")));
    let m = &ops(&l, "motion")[0];
    assert_eq!(m["motion"], "rapid");
    assert_eq!(
        m["targets"],
        json!([{"axis": "X", "value": 5.0, "mode": null}])
    );
    assert_eq!(m["indirect_targets"][0]["axis"]["name"], "_Z");
    assert_eq!(m["indirect_targets"][0]["mode"], "IC");
    let l = lower_with(&mill(), "AX[B]=5\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
    // A block of indirect targets only is still a motion.
    let l = lower_with(&mill(), "DEF AXIS _Z\nAX[_Z]=1\n");
    assert_eq!(ops(&l, "motion").len(), 1);
}

#[test]
fn transitions_and_polar_values_belong_to_the_motion() {
    let l = lower_with(
        &mill(),
        "G1 X10 Y5 CHF=2\nX20 RND=1.5\nG1 AP=IC(30) RP=50\n",
    );
    assert_clean(&l);
    let m = ops(&l, "motion");
    assert_eq!(m[0]["transition"], json!({"kind": "chamfer", "value": 2.0}));
    assert_eq!(
        m[1]["transition"],
        json!({"kind": "rounding", "value": 1.5})
    );
    assert_eq!(
        m[2]["targets"],
        json!([{"axis": "AP", "value": 30.0, "mode": "IC"}, {"axis": "RP", "value": 50.0, "mode": null}])
    );
    let l = lower_with(&mill(), "G1 X10 CHF=2 RND=1\n");
    assert_eq!(codes(&l), ["gcodec::lower::address_repeated"]);
}

#[test]
fn dl_follows_the_cutting_edge() {
    let l = lower_with(&mill(), "D1 DL=2\n");
    assert_clean(&l);
    assert_eq!(kinds(&l), ["cutting_edge", "address", "end"]);
    assert_eq!(ops(&l, "address")[0]["address"], "DL");
    let l = lower_with(&mill(), "DL=1.5\n");
    assert_eq!(codes(&l), ["gcodec::lower::invalid_value"]);
}

#[test]
fn extensions_only_where_the_control_takes_them() {
    let l = lower_with(&mill(), "OVR[X]=5\n");
    assert_eq!(codes(&l), ["gcodec::lower::extension_not_allowed"]);
    let l = lower_with(&mill(), "X[1]=5\n");
    assert_eq!(codes(&l), ["gcodec::lower::extension_not_allowed"]);
}

#[test]
fn numbered_axes_and_unknown_axis_letters() {
    let l = lower_with(
        &profile("[[axes]]\nname = \"X1\"\nkind = \"linear\"\n"),
        "G1 X1=10\nQ5\n",
    );
    assert_eq!(ops(&l, "motion")[0]["targets"][0]["axis"], "X1");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
}

#[test]
fn e_is_reserved_unless_the_machine_has_an_axis_e() {
    let l = lower_with(&mill(), "G1 X1 E=IC(0.5)\nACC[E]=50\n");
    assert_eq!(
        codes(&l),
        [
            "gcodec::lower::reserved_address",
            "gcodec::lower::reserved_address"
        ]
    );
    assert!(l.diagnostics.iter().all(|d| !d.is_error()));
    let printer = profile(
        "[[axes]]\nname = \"X\"\nkind = \"linear\"\n[[axes]]\nname = \"E\"\nkind = \"linear\"\n",
    );
    let l = lower_with(&printer, "G1 X1 E=IC(0.5)\nACC[E]=50\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "motion")[0]["targets"][1]["axis"], "E");
    assert_eq!(ops(&l, "address")[0]["axis"], "E");
}

#[test]
fn an_axis_named_by_a_number_is_reported() {
    let l = lower_with(&mill(), "ACC[4]=4\n");
    assert_eq!(codes(&l), ["gcodec::lower::axis_number"]);
    assert!(!l.has_errors());
}

// ---- H functions ----

#[test]
fn h_functions_are_output_like_m_functions() {
    let l = lower_with(&mill(), "DEF INT II=1\nH5 H2=7 H[II]=R1 H=QU(9) M3\n");
    assert_clean(&l);
    let h = ops(&l, "h_function");
    assert_eq!(
        h[0],
        json!({"kind": "h_function", "h_value": 5.0, "address_extension": null, "quick": false, "timing": "in_block", "raw": "H5"})
    );
    assert_eq!(h[1]["address_extension"], 2);
    assert_eq!(h[1]["raw"], "H2=7");
    assert_eq!(h[2]["address_extension_expr"]["name"], "II");
    assert_eq!(h[2]["h_value"], Value::Null);
    assert_eq!(h[2]["h_expr"]["var_kind"], "r_parameter");
    assert_eq!(h[3]["quick"], true);
    assert_eq!(h[3]["h_value"], 9.0);
    // After the M functions acting in the block.
    let k = kinds(&l);
    let m = k.iter().position(|k| k == "m_function").unwrap();
    let first_h = k.iter().position(|k| k == "h_function").unwrap();
    assert!(m < first_h);
}

#[test]
fn h_takes_no_modifier() {
    let l = lower_with(&mill(), "H=AC(1)\n");
    assert_eq!(codes(&l), ["gcodec::lower::modifier_not_allowed"]);
}

// ---- dwell ----

#[test]
fn g4_dwells_instead_of_setting_feed_or_speed() {
    let l = lower_with(&mill(), "N10 G4 F2.5\nG4 S30\n");
    assert_clean(&l);
    let d = ops(&l, "dwell");
    assert_eq!(
        d[0],
        json!({"kind": "dwell", "seconds": 2.5, "revolutions": null})
    );
    assert_eq!(
        d[1],
        json!({"kind": "dwell", "seconds": null, "revolutions": 30.0})
    );
    assert!(ops(&l, "feed").is_empty());
    assert!(ops(&l, "spindle_speed").is_empty());
    assert!(ops(&l, "modal_change").is_empty());
}

#[test]
fn g4_needs_a_block_of_its_own_and_a_time() {
    let l = lower_with(&mill(), "G4 F2 X10\n");
    assert_eq!(codes(&l), ["gcodec::lower::dwell_not_alone"]);
    let l = lower_with(&mill(), "G4\n");
    assert_eq!(codes(&l), ["gcodec::lower::dwell_without_time"]);
    // A computed time is fine.
    let l = lower_with(&mill(), "DEF REAL DTB=2\nN5 G4 F=DTB\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "dwell")[0]["seconds"]["name"], "DTB");
}

// ---- motion kinds ----

#[test]
fn spline_motion_carries_its_data() {
    let l = lower_with(
        &mill(),
        "BSPLINE SD=2\nX10 Y20 PW=2\nX30 Y40 PL=1.5\nASPLINE\nX70 Y30\nCSPLINE X1\nPOLY X2\n",
    );
    assert_clean(&l);
    let m = ops(&l, "motion");
    assert_eq!(m[0]["motion"], "bspline");
    assert_eq!(m[0]["spline"], json!({"weight": 2.0, "interval": null}));
    assert_eq!(m[1]["spline"], json!({"weight": null, "interval": 1.5}));
    assert_eq!(m[2]["motion"], "aspline");
    assert!(m[2].get("spline").is_none());
    assert_eq!(m[3]["motion"], "cspline");
    assert_eq!(m[4]["motion"], "poly");
    assert_eq!(ops(&l, "address")[0]["address"], "SD");
}

#[test]
fn thread_motion_takes_the_lead() {
    let l = lower_with(
        &mill(),
        "G33 Z-20 K2\nG331 Z-10 K1\nG332 Z0 K1\nG34 Z-30 K2 F0.1\n",
    );
    assert_clean(&l);
    let m = ops(&l, "motion");
    assert_eq!(m[0]["motion"], "thread");
    assert_eq!(
        m[0]["thread"]["lead"],
        json!([{"axis": "K", "value": 2.0, "mode": null}])
    );
    assert_eq!(m[0]["circle"], Value::Null);
    assert_eq!(m[1]["motion"], "tapping");
    assert_eq!(m[2]["motion"], "tapping_retract");
    assert_eq!(m[3]["motion"], "thread_increasing_lead");
    assert_eq!(m[3]["thread"]["lead_change"], 0.1);
    assert!(ops(&l, "feed").is_empty());
}

// ---- computed spindle numbers ----

#[test]
fn m_and_s_with_a_computed_spindle() {
    let l = lower_with(&mill(), "DEF INT SPINU=2\nM[SPINU]=3 S[SPINU]=1000\n");
    assert_clean(&l);
    let m = &ops(&l, "m_function")[0];
    assert_eq!(m["m_value"], 3);
    assert_eq!(m["address_extension"], Value::Null);
    assert_eq!(m["address_extension_expr"]["name"], "SPINU");
    assert_eq!(m["class"], "spindle");
    assert_eq!(m["timing"], "in_block");
    assert_eq!(m["raw"], "M[SPINU]=3");
    let s = &ops(&l, "spindle_speed")[0];
    assert_eq!(s["spindle"], Value::Null);
    assert_eq!(s["spindle_expr"]["name"], "SPINU");
    assert_eq!(s["speed"], 1000.0);
    // Constant brackets are checked like `M2=`.
    let l = lower_with(&mill(), "M[2]=3 S[2]=100\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "m_function")[0]["address_extension"], 2);
    assert_eq!(ops(&l, "spindle_speed")[0]["spindle"], 2);
    let l = lower_with(&mill(), "M[5]=3\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_spindle"]);
    // No extension keeps the M-function design's shape without the new field.
    let l = lower_with(&mill(), "M3\n");
    assert!(
        ops(&l, "m_function")[0]
            .get("address_extension_expr")
            .is_none()
    );
    assert!(ops(&l, "m_function")[0].get("address_extension").is_some());
    let l = lower_with(&mill(), "DEF INT SPINU=2\nM[SPINU]=30\n");
    assert_eq!(codes(&l), ["gcodec::lower::m_extension_forbidden"]);
}

// ---- indirect G ----

#[test]
fn indirect_g_with_a_constant_is_the_plain_command() {
    let l = lower_with(&mill(), "G[8]=2\nG[6]=2\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "work_offset")[0]["group8_selected"], "g54");
    assert_eq!(
        ops(&l, "modal_change")[0],
        json!({"kind": "modal_change", "group": 6, "code": "G18"})
    );
    let l = lower_with(&mill(), "G[8]=7\n");
    assert_eq!(codes(&l), ["gcodec::lower::unsupported_offset"]);
}

#[test]
fn indirect_g_with_a_variable_is_computed_when_the_block_runs() {
    let l = lower_with(&mill(), "DEF INT KORD=2\nG[8]=KORD\n");
    assert_clean(&l);
    assert_eq!(
        ops(&l, "modal_change_indirect")[0],
        json!({"kind": "modal_change_indirect", "group": 8, "index": {"op": "var", "var_kind": "user", "name": "KORD", "indices": []}})
    );
    let l = lower_with(&mill(), "DEF INT KORD=2\nG54 G[8]=KORD\n");
    assert_eq!(codes(&l), ["gcodec::lower::g_group_conflict"]);
}

#[test]
fn indirect_g_rules() {
    for (src, code) in [
        ("G[8]=R1+1\n", "gcodec::lower::invalid_indirect_g"),
        ("G[2]=1\n", "gcodec::lower::invalid_indirect_g"),
        ("G[1]=5\n", "gcodec::lower::invalid_indirect_g"),
        ("G[5]=1\n", "gcodec::lower::invalid_indirect_g"),
        ("G[65]=1\n", "gcodec::lower::invalid_indirect_g"),
        ("G[6]=9\n", "gcodec::lower::invalid_indirect_g"),
        ("G=R1\n", "gcodec::lower::computed_g"),
    ] {
        let l = lower_with(&mill(), src);
        assert_eq!(codes(&l), [code], "{src}");
    }
    let l = lower_with(&mill(), "G[1]=1 X1\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "motion")[0]["motion"], "rapid");
}

// ---- dimension modifiers ----

#[test]
fn modifiers_are_checked_per_address() {
    for src in [
        "F=AC(3)\n",
        "S=IC(100)\n",
        "M=AC(3)\n",
        "T=IC(1)\n",
        "D=AC(1)\n",
        "CR=AC(5)\n",
        "OVR=IC(5)\n",
        "X=DC(5)\n",
        "X=ACP(5)\n",
        "C=DAC(5)\n",
        "I=DC(5)\n",
        "SPOS=CAC(5)\n",
    ] {
        let l = lower_with(&mill(), src);
        assert_eq!(codes(&l), ["gcodec::lower::modifier_not_allowed"], "{src}");
        let d = &l.diagnostics[0];
        let at = d.span().unwrap();
        // The label is on the modifier, just after `=`.
        assert!(src[..at.start as usize].ends_with('='), "{src}");
        assert!(src[at.start as usize..].contains('('), "{src}");
        assert!(d.help.is_some(), "{src}");
    }
    for src in [
        "G1 X=AC(5)\n",
        "G1 X=IC(5)\n",
        "G1 C=DC(90)\n",
        "G1 C=ACP(90)\n",
        "G1 C=ACN(90)\n",
        "G2 X1 Y1 I=AC(5) J=IC(0)\n",
        "SPOS=DC(5)\n",
        "POS[C]=ACN(10)\n",
        "POSA[X]=IC(10)\n",
        "G1 X=DAC(10)\n",
    ] {
        let l = lower_with(&mill(), src);
        assert_clean(&l);
    }
    let l = lower_with(&mill(), "POS[X]=DC(10)\n");
    assert_eq!(codes(&l), ["gcodec::lower::modifier_not_allowed"]);
}

// ---- profile: legacy aliases and unsupported G ----

#[test]
fn a_legacy_alias_lowers_as_its_group8_target() {
    let p = common::profile("mill_g505_g599.toml");
    let l = lower_with(&p, "G58\nG1 X1\n");
    assert_clean(&l);
    assert_eq!(ops(&l, "work_offset")[0]["group8_selected"], "g505");
    assert!(ops(&l, "modal_change").iter().all(|m| m["code"] != "G58"));
    // It is a Group 8 command: a second one in the block conflicts.
    let l = lower_with(&p, "G54 G58\n");
    assert_eq!(codes(&l), ["gcodec::lower::g_group_conflict"]);
    // Without an alias, G58 is the axial offset of group 3.
    let l = lower_with(&mill(), "G58 X5\n");
    assert_eq!(ops(&l, "axis_setting")[0]["command"], "G58");
    assert!(ops(&l, "work_offset").is_empty());
}

#[test]
fn g_commands_the_profile_rules_out() {
    let p = profile("[g_codes]\nunsupported = [\"G33\", \"cip\"]\nunsupported_groups = [35]\n");
    for src in ["G33 Z1 K1\n", "CIP X1 Y1 I1=1 J1=1\n", "SON\n"] {
        let l = lower_with(&p, src);
        assert_eq!(codes(&l), ["gcodec::lower::unsupported_g"], "{src}");
        assert!(
            l.diagnostics[0]
                .help
                .as_deref()
                .unwrap()
                .contains("[g_codes]")
        );
    }
    let l = lower_with(&p, "G1 X1\n");
    assert_clean(&l);
    // The shipped 828D lathe rules out punching and nibbling.
    let lathe = common::profile("lathe_828d.toml");
    let l = lower_with(&lathe, "SPOF\n");
    assert_eq!(codes(&l), ["gcodec::lower::unsupported_g"]);
}

/// Profile G names are checked by `gcodec_sema::check_profile`
/// (tests/profile_check.rs), not by lowering; with an unchecked profile a
/// name the registry lacks simply matches nothing.
#[test]
fn unchecked_profile_g_names_match_nothing() {
    let p = profile("[g_codes]\nunsupported = [\"G999\", \"NOSUCH\", \"G33\"]\n");
    assert_clean(&lower_with(&p, "G1 X1\n"));
    assert_eq!(
        codes(&lower_with(&p, "G33 Z1 K1\n")),
        ["gcodec::lower::unsupported_g"]
    );
    let p = profile(
        "[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\nlegacy_aliases = { G1 = \"G505\" }\n",
    );
    assert!(!gcodec_sema::check_profile(&p).is_empty());
    let l = lower_with(&p, "X1\nG1 X2\n");
    assert!(!l.has_errors(), "{:#?}", l.diagnostics);
}

#[test]
fn no_panic_on_odd_addresses() {
    for src in [
        "G[R1]=1\n",
        "AX[1+2]=3\n",
        "H[200]=1\n",
        "H2=1E40\n",
        "SPOS[1.5]=3\n",
        "S[0]=100\n",
        "PW=1\n",
        "CHF=1\n",
        "FA[X]=1 FA[X]=2\n",
        "G4 S2=5\n",
    ] {
        let parsed = gcodec_parser::parse_bytes("t.mpf", src.as_bytes());
        let _ = lower(&parsed.program, &mill());
    }
}

#[test]
fn an_axis_with_a_longer_name_is_a_target_not_a_variable() {
    // The parser reads `XV=…` as an assignment: it knows no axes.
    let profile = common::profile("grinder_fb422.toml");
    let parsed =
        gcodec_parser::parse_bytes("xv.mpf", b"G1 XV=10 F100\nXV=IC(2.5)\nXV=ACP(5)\nM30\n");
    let l = gcodec_sema::lower(&parsed.program, &profile);
    let codes: Vec<&str> = l.diagnostics.iter().map(|d| d.code.name()).collect();
    assert_eq!(codes, ["gcodec::lower::modifier_not_allowed"]);
    let targets: Vec<(String, Option<gcodec_lang::DimensionMode>)> = l
        .document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            gcodec_ail::Op::Motion { targets, .. } => Some(targets),
            _ => None,
        })
        .flatten()
        .map(|t| (t.axis.to_string(), t.mode))
        .collect();
    assert_eq!(
        targets,
        [
            ("XV".to_owned(), None),
            ("XV".to_owned(), Some(gcodec_lang::DimensionMode::Ic))
        ]
    );
    assert!(
        !l.document
            .instructions
            .iter()
            .any(|i| matches!(i.op, gcodec_ail::Op::Assign { .. }))
    );
}

// ---- axes written twice, circles without data ----

#[test]
fn an_axis_written_twice_is_an_error() {
    let l = lower_with(&mill(), "G1 X1 Y2 X=3 F100\nG1 X1 Y2 Z3 C4\n");
    assert_eq!(codes(&l), ["gcodec::lower::repeated_axis"]);
    let d = &l.diagnostics[0];
    assert!(d.message.contains("`X`"), "{}", d.message);
    // The label is on the second `X`.
    assert_eq!(d.span().map(|s| s.start), Some(9));
}

#[test]
fn a_circle_needs_a_centre_radius_or_angle() {
    let l = lower_with(
        &mill(),
        "G17 G2 X10 Y0 F100\nG3 X0 Y10 I-10\nG2 X10 Y0 CR=10\nG3 X0 Y10 AR=90\nCIP X5 Y5 I1=2 J1=3\nG1 X0\n",
    );
    assert_eq!(codes(&l), ["gcodec::lower::missing_circle_data"]);
    assert!(l.diagnostics[0].message.contains("`G2`"));
    // Under a motion command lowering does not know (after a label a jump
    // reaches), the executor decides.
    let l = lower_with(&mill(), "G2 X1 Y1 CR=5\nLBL: X2 Y2\nGOTOB LBL\n");
    assert!(
        !codes(&l).contains(&"gcodec::lower::missing_circle_data"),
        "{:?}",
        codes(&l)
    );
}

// ---- diameter programming ----

/// `DIAMON`/`DIAM90` need a transverse axis (`diameter = true`); `DIAMOF`
/// and `DIAMCYCOF` are accepted on any machine.
#[test]
fn diameter_programming_needs_a_transverse_axis() {
    for command in ["DIAMON", "DIAM90"] {
        let l = lower_with(&mill(), &format!("G18 {command}\nG0 X10\n"));
        assert_eq!(
            codes(&l),
            ["gcodec::lower::no_transverse_axis"],
            "{command}"
        );
    }
    assert_clean(&lower_with(&mill(), "G18 DIAMOF\nDIAMCYCOF\n"));
    let lathe = profile(
        "[[axes]]\nname = \"X\"\nkind = \"linear\"\ngeometry = true\ndiameter = true\n\
         [[axes]]\nname = \"Z\"\nkind = \"linear\"\ngeometry = true\n",
    );
    assert_clean(&lower_with(&lathe, "G18 DIAMON\nG0 X10\nDIAM90\n"));
}
