//! The checked-in JSON Schema is the one the types generate, and the
//! instruction shapes of the tool-change, M-function and work-offset
//! designs read and write exactly as they specify.

use gcodec_ail::*;
use gcodec_lang::addresses::TransitionKind;
use gcodec_lang::{BinaryOp, DimensionMode, MClass, MotionKind, WorkOffsetCode};
use serde_json::json;

const SCHEMA_PATH: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../docs/schema/ail.schema.json"
);

/// Fails when `docs/schema/ail.schema.json` is stale. To regenerate:
/// `GCODEC_UPDATE_SCHEMA=1 cargo test -p gcodec-ail --test schema`.
#[test]
fn the_checked_in_schema_is_current() {
    let generated = json_schema();
    if std::env::var_os("GCODEC_UPDATE_SCHEMA").is_some() {
        std::fs::write(SCHEMA_PATH, &generated).expect("write the schema");
    }
    let checked_in = std::fs::read_to_string(SCHEMA_PATH).unwrap_or_default();
    assert!(
        checked_in == generated,
        "docs/schema/ail.schema.json is stale: run \
         `GCODEC_UPDATE_SCHEMA=1 cargo test -p gcodec-ail --test schema` and commit it"
    );
}

fn source(line: u32) -> Source {
    Source {
        file: "part.mpf".into(),
        line,
        col: 1,
        span: ByteRange { start: 0, end: 2 },
    }
}

/// Serialises one instruction and reads it back.
fn round_trip(op: Op) -> serde_json::Value {
    let instruction = Instruction {
        op,
        source: source(120),
    };
    let value = serde_json::to_value(&instruction).expect("serialises");
    let back: Instruction = serde_json::from_value(value.clone()).expect("reads back");
    assert_eq!(back, instruction);
    value
}

#[test]
fn tool_select_has_the_seed_000_fields() {
    let value = round_trip(Op::ToolSelect(Box::new(ToolSelect {
        selector_kind: SelectorKind::Name,
        selector_value: "DRILL_10".into(),
        selector_expr: None,
        spindle_extension: None,
        timing: ToolTiming::DeferredUntilM6,
        raw: "T=\"DRILL_10\"".into(),
    })));
    assert_eq!(
        value,
        json!({
            "kind": "tool_select",
            "selector_kind": "name",
            "selector_value": "DRILL_10",
            "spindle_extension": null,
            "timing": "deferred_until_m6",
            "raw": "T=\"DRILL_10\"",
            "source": {"file": "part.mpf", "line": 120, "col": 1, "span": {"start": 0, "end": 2}}
        })
    );
}

#[test]
fn tool_change_has_the_seed_000_trigger() {
    let value = round_trip(Op::ToolChange {
        trigger: ToolChangeTrigger::M6,
    });
    assert_eq!(value["kind"], "tool_change");
    assert_eq!(value["trigger"], "m6");
}

#[test]
fn m_function_has_the_seed_001_fields() {
    let value = round_trip(Op::MFunction(Box::new(MFunction {
        m_value: Some(3),
        m_expr: None,
        address_extension: None,
        address_extension_expr: None,
        class: MClass::Spindle,
        timing: MTiming::InBlock,
        raw: "M3".into(),
    })));
    assert_eq!(value["kind"], "m_function");
    assert_eq!(value["m_value"], 3);
    assert_eq!(value["address_extension"], serde_json::Value::Null);
    assert_eq!(value["class"], "spindle");
    assert_eq!(value["timing"], "in_block");
    assert_eq!(value["raw"], "M3");
    assert_eq!(value["source"]["line"], 120);
}

#[test]
fn work_offset_has_the_seed_003_fields() {
    let value = round_trip(Op::WorkOffset {
        group8_selected: Some(WorkOffsetCode::G54),
        suppression: Some(Suppression::G53),
        suppression_scope: Some(SuppressionScope::Block),
    });
    assert_eq!(value["kind"], "work_offset");
    assert_eq!(value["group8_selected"], "g54");
    assert_eq!(value["suppression"], "g53");
    assert_eq!(value["suppression_scope"], "block");
}

#[test]
fn suppressions_order_by_strength() {
    assert!(Suppression::Supa > Suppression::G153);
    assert!(Suppression::G153 > Suppression::G53);
}

#[test]
fn constants_are_plain_numbers_and_expressions_are_trees() {
    let value = round_trip(Op::Motion {
        motion: MotionKind::Linear,
        targets: vec![
            AxisValue {
                axis: "X".into(),
                value: Value::Const(10.5),
                mode: None,
            },
            AxisValue {
                axis: "Y".into(),
                value: Value::Expr(Box::new(Expr::Binary {
                    operator: BinaryOp::Add,
                    lhs: Box::new(Expr::Var {
                        var_kind: VarKind::RParameter,
                        name: VarName::Text("R".into()),
                        indices: vec![Expr::Number { value: 1.0 }],
                    }),
                    rhs: Box::new(Expr::Number { value: 5.0 }),
                })),
                mode: Some(DimensionMode::Ic),
            },
        ],
        circle: None,
        details: None,
    });
    assert_eq!(value["targets"][0]["value"], 10.5);
    assert_eq!(value["targets"][1]["value"]["op"], "binary");
    assert_eq!(value["targets"][1]["value"]["lhs"]["name"], "R");
}

#[test]
fn documents_carry_their_version() {
    let doc = Document {
        ail_version: AIL_VERSION,
        instructions: vec![Instruction {
            op: Op::End,
            source: source(3),
        }],
    };
    let value = serde_json::to_value(&doc).expect("serialises");
    assert_eq!(value["ail_version"], 1);
    assert_eq!(value["instructions"][0]["kind"], "end");
    let back: Document = serde_json::from_value(value).expect("reads back");
    assert_eq!(back, doc);
}

#[test]
fn motion_details_are_fields_of_the_motion() {
    let value = round_trip(Op::Motion {
        motion: MotionKind::Thread,
        targets: vec![AxisValue {
            axis: "Z".into(),
            value: Value::Const(-10.0),
            mode: None,
        }],
        circle: None,
        details: Some(Box::new(MotionDetails {
            thread: Some(Thread {
                lead: vec![AxisValue {
                    axis: "K".into(),
                    value: Value::Const(2.0),
                    mode: None,
                }],
                lead_change: None,
            }),
            transition: Some(Transition {
                kind: TransitionKind::Chamfer,
                value: Value::Const(1.0),
            }),
            ..MotionDetails::default()
        })),
    });
    assert_eq!(value["thread"]["lead"][0]["axis"], "K");
    assert_eq!(value["transition"]["kind"], "chamfer");
    // Absent details are absent fields, not nulls, and read back as none.
    assert!(value.get("spline").is_none() && value.get("indirect_targets").is_none());
    let plain = round_trip(Op::Motion {
        motion: MotionKind::Linear,
        targets: Vec::new(),
        circle: None,
        details: None,
    });
    assert!(plain.get("thread").is_none());
    assert!(plain["circle"].is_null());
}

#[test]
fn an_instruction_stays_small() {
    // The commonest instructions are motions; a document of a large
    // program holds millions.
    assert!(std::mem::size_of::<Instruction>() <= 88);
}

#[test]
fn skip_block_names_its_level_and_end_label() {
    let value = round_trip(Op::SkipBlock {
        level: 3,
        end: "SKIP@120.end".into(),
    });
    assert_eq!(
        value,
        json!({
            "kind": "skip_block",
            "level": 3,
            "end": "SKIP@120.end",
            "source": {"file": "part.mpf", "line": 120, "col": 1, "span": {"start": 0, "end": 2}}
        })
    );
    // The schema allows the control's levels only.
    let schema: serde_json::Value = serde_json::from_str(&json_schema()).unwrap();
    let skip = schema["$defs"]["Instruction"]["oneOf"]
        .as_array()
        .and_then(|kinds| {
            kinds
                .iter()
                .find(|k| k["properties"]["kind"]["const"] == "skip_block")
        })
        .expect("skip_block in the schema");
    assert_eq!(skip["properties"]["level"]["maximum"], 9);
}
