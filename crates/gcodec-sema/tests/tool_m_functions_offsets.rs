//! The test-matrix rows of the tool-change, M-function and work-offset
//! designs that belong to parsing, lowering and the modal engine, one
//! named test each (the executor rows are `gcodec-exec`'s
//! `tool_change_design_matrix`).

use serde_json::{Value, json};

mod common;

use common::{codes, errors, kinds, lower_with, machine as profile, ops};

// ---- tool change ----

/// The parser and AIL rows of the tool-change design's test matrix, and
/// the lowering side of its M-function row; the executor and integration
/// rows are `gcodec-exec`'s `tests/tool_change_design_matrix.rs`.
mod tool_change_design_matrix {
    use super::*;

    /// Tool-change matrix, parser tests: accepted/rejected selector forms by
    /// management mode.
    #[test]
    fn parser_selector_forms_by_management_mode() {
        let plain = profile("");
        for accepted in ["T5", "T=5", "T1=5", "T0"] {
            let l = lower_with(&plain, accepted);
            assert_eq!(
                errors(&l),
                [] as [&str; 0],
                "{accepted} without tool management"
            );
            assert_eq!(
                ops(&l, "tool_select")[0]["selector_kind"],
                "number",
                "{accepted}"
            );
        }
        for rejected in ["T=\"DRILL\"", "T1=\"DRILL\""] {
            let l = lower_with(&plain, rejected);
            assert_eq!(
                errors(&l),
                ["gcodec::lower::tool_selector_form"],
                "{rejected}"
            );
            assert!(ops(&l, "tool_select").is_empty());
        }
        let managed = profile("[tool_change]\ntool_management_enabled = true\n");
        for (accepted, kind) in [
            ("T=\"DRILL\"", "name"),
            ("T1=\"DRILL\"", "name"),
            ("T=5", "location"),
            ("T1=5", "location"),
        ] {
            let l = lower_with(&managed, accepted);
            assert_eq!(
                errors(&l),
                [] as [&str; 0],
                "{accepted} with tool management"
            );
            assert_eq!(
                ops(&l, "tool_select")[0]["selector_kind"],
                kind,
                "{accepted}"
            );
        }
        let l = lower_with(&managed, "T5");
        assert_eq!(errors(&l), ["gcodec::lower::tool_selector_form"]);
    }

    /// Tool-change matrix, AIL tests: normalized instruction shape + timing
    /// metadata.
    #[test]
    fn ail_normalized_instruction_shape_and_timing() {
        let deferred = lower_with(&profile(""), "T1=7");
        assert_eq!(
            ops(&deferred, "tool_select"),
            [json!({
                "kind": "tool_select",
                "selector_kind": "number",
                "selector_value": "7",
                "spindle_extension": 1,
                "timing": "deferred_until_m6",
                "raw": "T1=7"
            })]
        );
        assert!(
            ops(&deferred, "tool_change").is_empty(),
            "T only preselects"
        );

        let direct = lower_with(
            &profile("[tool_change]\ntool_change_mode = \"direct\"\n"),
            "T7",
        );
        assert_eq!(ops(&direct, "tool_select")[0]["timing"], "immediate");
        assert_eq!(
            ops(&direct, "tool_change"),
            [json!({"kind": "tool_change", "trigger": "t_word"})]
        );
    }

    /// Tool-change matrix, integration (lowering; the run is
    /// `gcodec-exec`'s `tool_change_design_matrix`): M6 goes through the M-code path (class
    /// `tool`) and triggers the change; the cutting edge follows the tool.
    #[test]
    fn integration_change_m_lowers_through_the_m_code_path() {
        let l = lower_with(&profile(""), "T5 M6 D1");
        let kinds = kinds(&l);
        assert_eq!(
            kinds,
            [
                "tool_select",
                "cutting_edge",
                "m_function",
                "tool_change",
                "end"
            ]
        );
        assert_eq!(ops(&l, "m_function")[0]["class"], "tool");
        assert_eq!(ops(&l, "tool_change")[0]["trigger"], "m6");
        // A machine that changes with another M code.
        let l = lower_with(&profile("[tool_change]\nchange_m_code = 206\n"), "T5 M206");
        assert_eq!(ops(&l, "m_function")[0]["class"], "tool");
        assert_eq!(ops(&l, "tool_change").len(), 1);
    }
}

/// Unknown tools follow `on_unresolved_tool` once the profile has a table.
#[test]
fn tool_change_unresolved_tools_follow_the_policy() {
    let table = "[[tools]]\nnumber = 1\n";
    let l = lower_with(&profile(table), "T2");
    assert_eq!(errors(&l), ["gcodec::lower::unresolved_tool"]);
    let l = lower_with(
        &profile(&format!(
            "[tool_change]\non_unresolved_tool = \"warning\"\n{table}"
        )),
        "T2",
    );
    assert_eq!(codes(&l), ["gcodec::lower::unresolved_tool"]);
    assert_eq!(errors(&l), [] as [&str; 0]);
    let l = lower_with(
        &profile(&format!(
            "[tool_change]\non_unresolved_tool = \"fallback\"\n{table}"
        )),
        "T2",
    );
    assert_eq!(codes(&l), [] as [&str; 0]);
}

// ---- M functions ----

/// M-function matrix, parser tests: valid/invalid forms, range, extension
/// restrictions, per-block count.
#[test]
fn m_functions_forms_range_extensions_and_count() {
    let p = profile("");
    for valid in ["M3", "M1=3", "M0", "M30", "M2147483647"] {
        assert_eq!(errors(&lower_with(&p, valid)), [] as [&str; 0], "{valid}");
    }
    assert_eq!(
        errors(&lower_with(&p, "M2147483648")),
        ["gcodec::lower::invalid_value"]
    );
    // A computed value is checked when the block runs.
    let computed = lower_with(&p, "M=R1");
    assert_eq!(errors(&computed), [] as [&str; 0]);
    assert_eq!(ops(&computed, "m_function")[0]["m_value"], Value::Null);
    assert_eq!(
        errors(&lower_with(&p, "M=-1")),
        ["gcodec::lower::invalid_value"]
    );
    assert_eq!(
        errors(&lower_with(&p, "M3.5")),
        ["gcodec::lower::invalid_value"]
    );
    for forbidden in ["M1=0", "M1=1", "M1=2", "M1=17", "M1=30"] {
        assert_eq!(
            errors(&lower_with(&p, forbidden)),
            ["gcodec::lower::m_extension_forbidden"],
            "{forbidden}"
        );
    }
    assert_eq!(
        errors(&lower_with(&p, "M2=3")),
        ["gcodec::lower::unknown_spindle"]
    );
    let no_ext = profile("[m_functions]\nenable_extended_m_address = false\n");
    assert_eq!(
        errors(&lower_with(&no_ext, "M1=3")),
        ["gcodec::lower::m_extension_forbidden"]
    );
    // Five of different auxiliary-function groups (`M3 M5` share one).
    assert_eq!(errors(&lower_with(&p, "M3 M7 M8 M9 M40")), [] as [&str; 0]);
    assert_eq!(
        errors(&lower_with(&p, "M3 M7 M8 M9 M40 M41")),
        ["gcodec::lower::too_many_m_functions"]
    );
    let two = profile("[m_functions]\nmax_m_per_block = 2\n");
    assert_eq!(
        errors(&lower_with(&two, "M3 M8 M9")),
        ["gcodec::lower::too_many_m_functions"]
    );
}

/// M-function matrix, AIL tests: normalized instruction metadata for
/// class/timing/raw/source.
#[test]
fn m_functions_instruction_metadata() {
    let l = lower_with(&profile(""), "N10 G1 X10 M3 M1=4 M40 M30");
    let m = ops(&l, "m_function");
    let summary: Vec<(Value, Value, Value, Value)> = m
        .iter()
        .map(|v| {
            (
                v["m_value"].clone(),
                v["class"].clone(),
                v["timing"].clone(),
                v["raw"].clone(),
            )
        })
        .collect();
    assert_eq!(
        summary,
        [
            (json!(3), json!("spindle"), json!("in_block"), json!("M3")),
            (json!(4), json!("spindle"), json!("in_block"), json!("M1=4")),
            (json!(40), json!("gearbox"), json!("in_block"), json!("M40")),
            (
                json!(30),
                json!("program_flow"),
                json!("post_motion"),
                json!("M30")
            ),
        ]
    );
    assert_eq!(m[1]["address_extension"], 1);
    // M30 comes after the motion it waits for; its source is its own word.
    let instructions = &l.document.instructions;
    let motion = instructions
        .iter()
        .position(|i| matches!(i.op, gcodec_ail::Op::Motion { .. }))
        .unwrap();
    let m30 = instructions
        .iter()
        .position(|i| matches!(&i.op, gcodec_ail::Op::MFunction(m) if m.m_value == Some(30)))
        .unwrap();
    assert!(m30 > motion);
    assert_eq!(
        (instructions[m30].source.line, instructions[m30].source.col),
        (1, 24)
    );
    // Without motion in the block, M30 acts in the block.
    let l = lower_with(&profile(""), "M30");
    assert_eq!(ops(&l, "m_function")[0]["timing"], "in_block");
}

/// Unknown M functions follow `unknown_mcode_policy`; overrides classify.
#[test]
fn m_functions_unknown_codes_follow_the_policy() {
    let l = lower_with(&profile(""), "M123");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_m_function"]);
    assert_eq!(errors(&l), [] as [&str; 0]);
    assert_eq!(ops(&l, "m_function")[0]["class"], "custom");
    let strict = profile("[m_functions]\nunknown_mcode_policy = \"error\"\n");
    assert_eq!(
        errors(&lower_with(&strict, "M123")),
        ["gcodec::lower::unknown_m_function"]
    );
    let quiet = profile("[m_functions]\nunknown_mcode_policy = \"ignore\"\n");
    assert_eq!(codes(&lower_with(&quiet, "M123")), [] as [&str; 0]);
    let known = profile(
        "[m_functions]\nunknown_mcode_policy = \"error\"\nmcode_class_overrides = { 123 = \"gearbox\" }\n",
    );
    let l = lower_with(&known, "M123");
    assert_eq!(codes(&l), [] as [&str; 0]);
    assert_eq!(ops(&l, "m_function")[0]["class"], "gearbox");
}

// ---- work offsets ----

/// Work-offset matrix, parser tests: Group 8 syntax acceptance/rejection with
/// profile range variants.
#[test]
fn work_offsets_group8_acceptance_with_profile_ranges() {
    let standard = profile("");
    for accepted in ["G500", "G54", "G57"] {
        assert_eq!(
            errors(&lower_with(&standard, accepted)),
            [] as [&str; 0],
            "{accepted}"
        );
    }
    for rejected in ["G505", "G599"] {
        assert_eq!(
            errors(&lower_with(&standard, rejected)),
            ["gcodec::lower::unsupported_offset"],
            "{rejected}"
        );
    }
    let wide = profile(
        "[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\n",
    );
    for accepted in ["G505", "G599", "G54"] {
        assert_eq!(
            errors(&lower_with(&wide, accepted)),
            [] as [&str; 0],
            "{accepted}"
        );
    }
    let narrow = profile("[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G55\"]\n");
    assert_eq!(
        errors(&lower_with(&narrow, "G56")),
        ["gcodec::lower::unsupported_offset"]
    );
}

/// Work-offset matrix, parser tests: suppression command parse coverage.
#[test]
fn work_offsets_suppression_commands() {
    for (src, suppression) in [
        ("G53", "g53"),
        ("G153", "g153"),
        ("SUPA", "supa"),
        ("supa", "supa"),
    ] {
        let l = lower_with(&profile(""), src);
        assert_eq!(errors(&l), [] as [&str; 0], "{src}");
        let w = ops(&l, "work_offset");
        assert_eq!(w[0]["suppression"], suppression, "{src}");
        assert_eq!(w[0]["suppression_scope"], "block", "{src}");
    }
}

/// Work-offset matrix, modal-engine tests: Group 8 persistence across blocks.
#[test]
fn work_offsets_group8_persists_across_blocks() {
    let l = lower_with(&profile(""), "G54\nG0 X1\nG53 X2\nX3\nG500\n");
    let selected: Vec<Value> = ops(&l, "work_offset")
        .iter()
        .map(|w| w["group8_selected"].clone())
        .collect();
    assert_eq!(selected, [json!("g54"), json!("g54"), json!("g500")]);
    // An unsupported code leaves the selection as it was.
    let l = lower_with(&profile(""), "G55\nG505\nG53\n");
    let selected: Vec<Value> = ops(&l, "work_offset")
        .iter()
        .map(|w| w["group8_selected"].clone())
        .collect();
    assert_eq!(selected, [json!("g55"), json!("g55")]);
}

/// Work-offset matrix, modal-engine tests: block-local suppression precedence
/// and non-mutation of the modal selection.
#[test]
fn work_offsets_suppression_is_block_local_and_keeps_the_selection() {
    let l = lower_with(&profile(""), "G54\nG53 G0 X1\nG0 X2\n");
    let w = ops(&l, "work_offset");
    assert_eq!(
        w.len(),
        2,
        "no work_offset for the block without suppression"
    );
    assert_eq!(
        w[1],
        json!({"kind": "work_offset", "group8_selected": "g54", "suppression": "g53", "suppression_scope": "block"})
    );
    // Strongest wins: SUPA > G153 > G53.
    let l = lower_with(&profile(""), "G53 SUPA G153\n");
    assert_eq!(ops(&l, "work_offset")[0]["suppression"], "supa");
}

/// Work-offset matrix, AIL tests: selected/effective work-offset metadata
/// stability.
#[test]
fn work_offsets_metadata_is_stable() {
    let l = lower_with(&profile(""), "G55 G153\n");
    assert_eq!(
        ops(&l, "work_offset"),
        [
            json!({"kind": "work_offset", "group8_selected": "g55", "suppression": "g153", "suppression_scope": "block"})
        ]
    );
    let again = lower_with(&profile(""), "G55 G153\n");
    assert_eq!(l.document, again.document);
}

/// Work-offset matrix, AIL tests: policy behavior for duplicate suppression
/// words.
#[test]
fn work_offsets_duplicate_suppression_policy() {
    let src = "G53 SUPA\n";
    let warn = lower_with(&profile(""), src);
    assert_eq!(codes(&warn), ["gcodec::lower::duplicate_suppression"]);
    assert_eq!(errors(&warn), [] as [&str; 0]);
    assert_eq!(ops(&warn, "work_offset")[0]["suppression"], "supa");
    let error = lower_with(
        &profile("[work_offsets]\nduplicate_suppression_policy = \"error\"\n"),
        src,
    );
    assert_eq!(errors(&error), ["gcodec::lower::duplicate_suppression"]);
    let first = lower_with(
        &profile("[work_offsets]\nduplicate_suppression_policy = \"first_wins\"\n"),
        src,
    );
    assert_eq!(codes(&first), [] as [&str; 0]);
    assert_eq!(ops(&first, "work_offset")[0]["suppression"], "g53");
}

/// Computed values (`T=NAMES[IDX]`, `M1=DIR`, `D=EDGES[IDX]`) are lowered to
/// expressions the executor evaluates, not rejected.
#[test]
fn computed_tool_m_and_edge_values_are_expressions() {
    let managed = profile("[tool_change]\ntool_management_enabled = true\n");
    let l = lower_with(
        &managed,
        "DEF STRING[32] NAMES[4]\nDEF INT IDX, EDGES[4], DIR\nT=NAMES[IDX] D=EDGES[IDX] M1=DIR",
    );
    assert_eq!(errors(&l), [] as [&str; 0]);
    let t = &ops(&l, "tool_select")[0];
    assert_eq!(t["selector_kind"], "computed");
    assert_eq!(t["selector_expr"]["name"], "NAMES");
    let m = &ops(&l, "m_function")[0];
    assert_eq!(m["m_value"], Value::Null);
    assert_eq!(m["m_expr"]["name"], "DIR");
    assert_eq!(m["address_extension"], 1);
    assert_eq!(ops(&l, "cutting_edge")[0]["edge"]["name"], "EDGES");
    // Constant values stay constants.
    let l = lower_with(&profile(""), "T5 D2 M3");
    assert_eq!(ops(&l, "cutting_edge")[0]["edge"], 2.0);
    assert!(ops(&l, "tool_select")[0].get("selector_expr").is_none());
}
