//! Control structures lower to labels and conditional jumps; `GOTO…`
//! targets are found as the control searches for them.

use gcodec_ail::Op;
use gcodec_sema::{Lowered, lower};

fn lower_src(src: &str) -> Lowered {
    let parsed = gcodec_parser::parse_bytes("flow.mpf", src.as_bytes());
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    let profile = gcodec_profile::builtin().expect("built-in profile");
    lower(&parsed.program, &profile)
}

fn listing(l: &Lowered) -> String {
    let mut out = String::new();
    gcodec_ail::write_listing(&l.document, &mut out).unwrap();
    out
}

fn labels(l: &Lowered) -> Vec<String> {
    l.document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Label { name } => Some(name.clone()),
            _ => None,
        })
        .collect()
}

fn jump_targets(l: &Lowered) -> Vec<String> {
    l.document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Jump { target, .. } => Some(target.clone()),
            _ => None,
        })
        .collect()
}

const STRUCTURES: &str = "N10 R1=0
N20 WHILE R1<3
N30   IF R1==1
N40     G1 X1
N50   ELSE
N60     G1 X2
N70   ENDIF
N80   R1=R1+1
N90 ENDWHILE
N100 FOR R2=1 TO 3
N110 ENDFOR
N120 LOOP
N130   IF R2>3 GOTOF DONE
N140 ENDLOOP
N150 REPEAT
N160 UNTIL R1>5
DONE: M30
";

#[test]
fn every_structure_becomes_labels_and_jumps() {
    let l = lower_src(STRUCTURES);
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    // Every jump lands on a label of the document.
    let labels = labels(&l);
    for target in jump_targets(&l) {
        assert!(labels.contains(&target), "{target} in {labels:?}");
    }
    insta::assert_snapshot!(listing(&l));
}

#[test]
fn jumps_search_as_the_control_does() {
    // Two labels `LB`: GOTOF finds the next one, GOTOB the previous one.
    let l = lower_src("LB: X1\nGOTOF LB\nLB: X2\nGOTOB LB\n");
    assert_eq!(jump_targets(&l), ["LB@3", "LB@3"]);
    let l = lower_src("LB: X1\nX2\nGOTOB LB\nLB: X3\n");
    assert_eq!(jump_targets(&l), ["LB@1"]);
    // GOTO searches forward first, then backward.
    let l = lower_src("N10 X1\nGOTO N10\n");
    assert_eq!(jump_targets(&l), ["N10@1"]);
    let codes: Vec<_> = l.diagnostics.iter().map(|d| d.code.name()).collect();
    assert!(codes.is_empty(), "{codes:?}");
}

#[test]
fn labels_defined_twice_are_advice() {
    // The control accepts them (the nearest one wins), so neither an
    // error nor a warning.
    let l = lower_src("LB: X1\nLB: X2\n");
    let codes: Vec<_> = l
        .diagnostics
        .iter()
        .map(|d| (d.code.name(), d.severity))
        .collect();
    assert_eq!(
        codes,
        [(
            "gcodec::lower::duplicate_label",
            gcodec_source::Severity::Advice
        )]
    );
}

/// A missing target fails only when the jump runs (alarm 14080); GOTOC
/// goes on with the next block.
#[test]
fn missing_targets_warn_and_gotoc_goes_on() {
    let l = lower_src("GOTOF NOWHERE\n");
    let codes: Vec<_> = l
        .diagnostics
        .iter()
        .map(|d| (d.code.name(), d.is_error()))
        .collect();
    assert_eq!(codes, [("gcodec::lower::missing_jump_target", false)]);
    assert_eq!(jump_targets(&l), ["NOWHERE@missing"]);
    // GOTOB does not look forward.
    let l = lower_src("GOTOB LB\nLB: X1\n");
    assert_eq!(l.diagnostics.len(), 1);
    let l = lower_src("GOTOC NOWHERE\nX1\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert!(jump_targets(&l).is_empty());
}

#[test]
fn declarations_lower_per_variable() {
    let l = lower_src("DEF REAL AA=1.5, BB[3]=(1,2,3)\nDEF INT NN\n");
    let declared: Vec<_> = l
        .document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Declare(d) => Some((d.name.clone(), d.data_type.describe(), d.init.len())),
            _ => None,
        })
        .collect();
    assert_eq!(
        declared,
        [
            ("AA".to_owned(), "REAL".to_owned(), 1),
            ("BB".to_owned(), "REAL".to_owned(), 3),
            ("NN".to_owned(), "INT".to_owned(), 0)
        ]
    );
}

/// Calls by name or number lower to `call`, after the block's motion, with
/// their arguments and pass count; `RET` to `return`.
#[test]
fn calls_and_returns() {
    let l = lower_src("G1 X1 CYCLE81(10,0,2,,-5)\nL123 P3\nRET\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let ops: Vec<serde_json::Value> = l
        .document
        .instructions
        .iter()
        .map(|i| {
            let mut v = serde_json::to_value(&i.op).unwrap();
            v.as_object_mut().unwrap().retain(|k, _| k != "source");
            v
        })
        .collect();
    let kinds: Vec<&str> = ops.iter().map(|v| v["kind"].as_str().unwrap()).collect();
    assert_eq!(
        kinds,
        ["modal_change", "motion", "call", "call", "return", "end"]
    );
    assert_eq!(ops[2]["target"], "CYCLE81");
    assert_eq!(
        ops[2]["args"],
        serde_json::json!([10.0, 0.0, 2.0, null, -5.0])
    );
    assert_eq!(ops[3]["target"], "L123");
    assert_eq!(ops[3]["passes"], 3.0);
}

/// Frame instructions lower to `frame` with their values; the bare
/// keyword (no values) resets.
#[test]
fn frames() {
    let l = lower_src("TRANS X10 Y=R1\nAROT RPL=45\nMIRROR X0\nTRANS\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let frames: Vec<(String, Vec<String>)> = l
        .document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Frame(f) => Some((
                f.op.keyword().to_owned(),
                f.values.iter().map(|v| v.axis.to_string()).collect(),
            )),
            _ => None,
        })
        .collect();
    let expected: Vec<(String, Vec<String>)> = vec![
        ("TRANS".into(), vec!["X".into(), "Y".into()]),
        ("AROT".into(), vec!["RPL".into()]),
        ("MIRROR".into(), vec!["X".into()]),
        ("TRANS".into(), vec![]),
    ];
    assert_eq!(frames, expected);
}
