//! Skip marks (`/`, `/0`…`/9`): a skipped block lowers to a `skip_block`
//! test after the labels it starts with and a `SKIP@<line>.end` label after
//! its instructions, before the end of a `REPEAT` section it closes.

use gcodec_ail::Op;
use gcodec_lang::MotionKind;
use gcodec_sema::Lowered;

mod common;

use common::{codes, motions, selections};

fn lower_src(src: &str) -> Lowered {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    common::lower_named("skip.mpf", &profile, src)
}

/// The listing of line `line`, one instruction an entry, without line and
/// column.
fn line(l: &Lowered, line: u32) -> Vec<String> {
    let mut out = String::new();
    gcodec_ail::write_listing(&l.document, &mut out).unwrap();
    out.lines()
        .filter_map(|text| {
            let (at, rest) = text.trim_start().split_once(':')?;
            (at.parse() == Ok(line)).then(|| rest.trim_start_matches(|c: char| c.is_ascii_digit()))
        })
        .map(|rest| rest.trim().to_owned())
        .collect()
}

/// The `skip_block` tests: line, level, end label.
fn skips(l: &Lowered) -> Vec<(u32, u8, String)> {
    l.document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::SkipBlock { level, end } => Some((i.source.line, *level, end.clone())),
            _ => None,
        })
        .collect()
}

/// Every `skip_block`'s end label exists once, after it, on its line; no
/// two labels share a name.
fn assert_skips_land(l: &Lowered) {
    let instructions = &l.document.instructions;
    let mut names: Vec<&str> = instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Label { name } => Some(name.as_str()),
            _ => None,
        })
        .collect();
    let count = names.len();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), count, "labels named twice: {names:?}");
    for (at, instruction) in instructions.iter().enumerate() {
        let Op::SkipBlock { end, .. } = &instruction.op else {
            continue;
        };
        let target = instructions
            .iter()
            .position(|i| matches!(&i.op, Op::Label { name } if name == end))
            .unwrap_or_else(|| panic!("no label {end}"));
        assert!(target > at + 1, "{end}: nothing skipped");
        assert_eq!(instructions[target].source.line, instruction.source.line);
    }
}

#[test]
fn a_skipped_block_is_jumped_over_at_its_level() {
    let l = lower_src("N10 G0 X0\n/N20 G1 X10\n/3 X10\nN40 X20\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_skips_land(&l);
    assert_eq!(
        line(&l, 2),
        [
            r#"skip_block end="SKIP@2.end" level=0"#,
            r#"modal_change code="G1" group=1"#,
            r#"motion motion="linear" targets=[{axis="X" value=10}]"#,
            r#"label name="SKIP@2.end""#,
        ]
    );
    assert_eq!(
        line(&l, 3),
        [
            r#"skip_block end="SKIP@3.end" level=3"#,
            r#"motion motion="modal" targets=[{axis="X" value=10}]"#,
            r#"label name="SKIP@3.end""#,
        ]
    );
    // The test carries the skip mark's place.
    let skip = &l.document.instructions[2];
    let json = serde_json::to_value(skip).unwrap();
    assert_eq!(
        json,
        serde_json::json!({
            "kind": "skip_block",
            "level": 0,
            "end": "SKIP@2.end",
            "source": {"file": "skip.mpf", "line": 2, "col": 1, "span": {"start": 10, "end": 11}}
        })
    );
    // Every level of the control.
    let src: String = (0..=9).map(|n| format!("/{n} X{n}\n")).collect();
    let l = lower_src(&src);
    let levels: Vec<u8> = skips(&l).iter().map(|(_, level, _)| *level).collect();
    assert_eq!(levels, (0..=9).collect::<Vec<u8>>());
    assert_skips_land(&l);
}

#[test]
fn everything_of_the_block_is_skipped_its_jumps_and_calls_too() {
    let l = lower_src("R1=1\n/2 G1 X1 F100 M8 R2=3 L100 GOTOF END\nEND: M30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_skips_land(&l);
    let block = line(&l, 2);
    assert_eq!(
        block.first().unwrap(),
        r#"skip_block end="SKIP@2.end" level=2"#
    );
    assert_eq!(block.last().unwrap(), r#"label name="SKIP@2.end""#);
    let kinds: Vec<&str> = block
        .iter()
        .map(|i| i.split_once(' ').map_or(i.as_str(), |(k, _)| k))
        .collect();
    assert_eq!(
        kinds,
        [
            "skip_block",
            "modal_change",
            "feed",
            "m_function",
            "assign",
            "motion",
            "call",
            "jump",
            "label"
        ]
    );
}

#[test]
fn a_jump_to_a_skipped_block_lands_before_its_test() {
    let l = lower_src("G0 X0\n/LBL: X10\n/N30 X20\nIF R1<2 GOTOB LBL\nIF R1<3 GOTOB N30\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_skips_land(&l);
    assert_eq!(
        line(&l, 2),
        [
            r#"label name="LBL@2""#,
            r#"skip_block end="SKIP@2.end" level=0"#,
            r#"motion motion="rapid" targets=[{axis="X" value=10}]"#,
            r#"label name="SKIP@2.end""#,
        ]
    );
    assert_eq!(
        line(&l, 3)[..2],
        [
            r#"label name="N30@3""#,
            r#"skip_block end="SKIP@3.end" level=0"#
        ]
    );
    // A label of the program named `SKIP` keeps its own name.
    let l = lower_src("/SKIP: X5\nIF R1<2 GOTOB SKIP\nM30\n");
    assert_skips_land(&l);
    assert_eq!(
        line(&l, 1)[..2],
        [
            r#"label name="SKIP@1""#,
            r#"skip_block end="SKIP@1.end" level=0"#
        ]
    );
    // So does every label searched by a computed jump.
    let l = lower_src("/LA1: X5\nGOTOB \"LA\"<<R1\n");
    assert_skips_land(&l);
    assert_eq!(
        line(&l, 1)[..2],
        [
            r#"label name="LA1@1""#,
            r#"skip_block end="SKIP@1.end" level=0"#
        ]
    );
}

#[test]
fn a_skipped_last_block_of_a_section_still_ends_it() {
    let l = lower_src("G1 X0\nSTART: X1\n/X2\nREPEAT START P=2\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_skips_land(&l);
    assert_eq!(
        line(&l, 3),
        [
            r#"skip_block end="SKIP@3.end" level=0"#,
            r#"motion motion="linear" targets=[{axis="X" value=2}]"#,
            r#"label name="SKIP@3.end""#,
            r#"label name="SECTION@4.end""#,
        ]
    );
    // A section of one skipped block: its start label before the test,
    // its end after the skip label.
    let l = lower_src("G1 X0\n/4 LBL: X1\nREPEATB LBL P=2\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(
        line(&l, 2),
        [
            r#"label name="LBL@2""#,
            r#"skip_block end="SKIP@2.end" level=4"#,
            r#"motion motion="linear" targets=[{axis="X" value=1}]"#,
            r#"label name="SKIP@2.end""#,
            r#"label name="SECTION@3.end""#,
        ]
    );
    // A skipped `REPEAT` is skipped with its block.
    let l = lower_src("G1 X0\nSTART: X1\n/REPEAT START P=2\nM30\n");
    assert_eq!(
        line(&l, 3),
        [
            r#"skip_block end="SKIP@3.end" level=0"#,
            r#"repeat_section end="SECTION@3.end" passes=2 start="START@2""#,
            r#"label name="SKIP@3.end""#,
        ]
    );
}

#[test]
fn what_a_skipped_block_sets_is_unknown_after_it() {
    // `/G0`: the next motion runs under G0 or G1.
    let l = lower_src("G1 X0\n/G0\nX10\nM30\n");
    assert_eq!(motions(&l), [MotionKind::Linear, MotionKind::Modal]);
    // The skipped block's own motion knows its command.
    let l = lower_src("G1 X0\n/G0 X5\nX10\nG1 X20\nX30\nM30\n");
    assert_eq!(
        motions(&l),
        [
            MotionKind::Linear,
            MotionKind::Rapid,
            MotionKind::Modal,
            MotionKind::Linear,
            MotionKind::Linear
        ]
    );
    // A skipped block that changes no command: both paths agree, the
    // motion after it is settled again.
    let l = lower_src("G1 X0\n/M8\nX10\n/G1 X15\nX20\nM30\n");
    assert_eq!(
        motions(&l),
        [
            MotionKind::Linear,
            MotionKind::Linear,
            MotionKind::Linear,
            MotionKind::Linear
        ]
    );
    // The Group 8 selection likewise.
    let l = lower_src("G54 X0\n/G55\nG53 X1\nM30\n");
    assert_eq!(
        selections(&l),
        [Some("g54".to_owned()), Some("g55".to_owned()), None]
    );
    let l = lower_src("G54 X0\n/M8\nG53 X1\nM30\n");
    assert_eq!(
        selections(&l),
        [Some("g54".to_owned()), Some("g54".to_owned())]
    );
    // A skipped `MCALL` may leave the modal call in force: the cycle may
    // run after `X1` and change the motion command.
    let l = lower_src("MCALL CYCLE81(1,2,3)\n/MCALL\nG1 X1\nX2\nMCALL\nG1 X3\nX4\nM30\n");
    assert_eq!(
        motions(&l),
        [
            MotionKind::Linear,
            MotionKind::Modal,
            MotionKind::Linear,
            MotionKind::Linear
        ]
    );
}

#[test]
fn a_skipped_structure_block_only_diagnoses() {
    let l = lower_src("R1=0\n/WHILE R1<2\nR1=R1+1\nENDWHILE\n/3 IF R1>0\nX1\nENDIF\nM30\n");
    assert_eq!(
        codes(&l),
        [
            "gcodec::lower::skipped_structure_block",
            "gcodec::lower::skipped_structure_block"
        ]
    );
    assert!(skips(&l).is_empty(), "{:?}", skips(&l));
    assert!(
        !line(&l, 2).iter().any(|i| i.contains("SKIP@")),
        "{:?}",
        line(&l, 2)
    );
    // Skipped blocks inside a structure are tested as any other.
    let l = lower_src("R1=0\nWHILE R1<2\n/R1=R1+1\nENDWHILE\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(skips(&l), [(3, 0, "SKIP@3.end".to_owned())]);
    assert_skips_land(&l);
}

#[test]
fn a_block_with_nothing_to_skip_gets_no_test() {
    // A label alone, a mark alone, a block number alone, a comment: the
    // block does nothing whether it is skipped or not.
    let l = lower_src("G1 X0\n/LBL:\n/\n/N30\n/3 ; comment\nIF R1<2 GOTOB LBL\nX1\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert!(skips(&l).is_empty(), "{:?}", skips(&l));
    assert_eq!(line(&l, 2), [r#"label name="LBL@2""#]);
    // Nothing forgotten either: the motion after them is settled.
    assert_eq!(motions(&l), [MotionKind::Linear, MotionKind::Linear]);
    // The end of a section on such a block stays.
    let l = lower_src("START: X1\n/ENDLABEL:\nREPEAT START P=2\nM30\n");
    assert!(skips(&l).is_empty(), "{:?}", skips(&l));
    assert_eq!(line(&l, 2), [r#"label name="SECTION@3.end""#]);
}
