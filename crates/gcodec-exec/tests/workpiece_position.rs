//! The workpiece position a motion starts from (SPEC §11.5, "Positions"):
//! the end point the last motion was programmed to, bit for bit, while
//! the frame, the tool length and its infeed axis stay; the frame's image
//! of the machine position once one of them changed, after a block with
//! its frames suppressed and under tool radius compensation.
//!
//! The machining centre's `G54` is X −412.5, Y −220, Z −515.3: through
//! its arithmetic there and back `X100.037` comes back as
//! `100.03700000000003`.

mod common;

use common::runs::events_of_text_with;
use gcodec_driver::RunSetup;
use gcodec_exec::event::{EventKind, MotionEvent};
use gcodec_source::Severity;
use gcodec_testkit::profile;

/// The motions of `program` on the machining centre, run on the direct
/// path or the general one; panics on an error.
fn motions(program: &str, direct: bool) -> Vec<MotionEvent> {
    let mut setup = RunSetup::new(profile("mill_tool_management.toml"));
    setup.options.direct_motions = direct;
    let mut motions = Vec::new();
    for event in events_of_text_with(&setup, "POSITIONS.MPF", program) {
        match event.kind {
            EventKind::Motion(m) => motions.push(m),
            EventKind::Diagnostic(d) if d.severity == Severity::Error => {
                panic!("{program}: {}: {}", d.code.name(), d.message)
            }
            _ => {}
        }
    }
    motions
}

/// The bits of each axis of `from` and `to`.
fn bits(map: &gcodec_exec::event::AxisMap) -> Vec<(String, u64)> {
    map.iter()
        .map(|(axis, value)| (axis.to_owned(), value.to_bits()))
        .collect()
}

#[test]
fn each_motion_starts_where_the_last_was_programmed_to_under_an_offset() {
    let mut program = String::from("G54 G1 F1000\n");
    for i in 0..200 {
        let (x, y) = (100.0 + f64::from(i) * 0.037, 200.0 - f64::from(i) * 0.053);
        program.push_str(&format!("X{x:.3} Y{y:.3}\n"));
    }
    program.push_str("G91 X0.1 Y-0.1\nX0.1\nM30\n");
    for direct in [true, false] {
        let motions = motions(&program, direct);
        assert_eq!(motions.len(), 202);
        for pair in motions.windows(2) {
            assert_eq!(
                bits(&pair[1].from),
                bits(&pair[0].to),
                "direct path {direct}: {:?} after {:?}",
                pair[1].from,
                pair[0].to
            );
        }
        // The axes not programmed stay as they were, bit for bit.
        assert!(motions.iter().skip(1).all(|m| m.to.get("Z") == Some(515.3)));
        assert_eq!(motions[1].to.get("X"), Some(100.037));
    }
}

#[test]
fn the_programmed_end_point_and_the_actual_position_read_it() {
    // A comparison has a tolerance: the values go to a motion instead.
    let program = "G54 G1 X100.037 Y200.053 F1000\n\
                   G1 X=$P_EP[X] Y=$AA_IW[Y]\n\
                   M30\n";
    for direct in [true, false] {
        let motions = motions(program, direct);
        assert_eq!(bits(&motions[1].to), bits(&motions[0].to));
    }
}

#[test]
fn a_new_frame_a_suppressed_block_or_a_tool_length_starts_from_the_machine_position() {
    let x = |motion: &MotionEvent| motion.from.get("X").expect("X");
    let z = |motion: &MotionEvent| motion.from.get("Z").expect("Z");
    // A programmable frame: the position in it, X 10 − 3.
    let m = motions("G54 G1 X10 F1000\nTRANS X3\nG1 Y5\nM30\n", true);
    assert!((x(&m[1]) - 7.0).abs() < 1e-9, "{:?}", m[1].from);
    // `G53` programs machine positions: the next block starts from the
    // image of machine X 0 in `G54`, not from the X 10 of the block before.
    let m = motions("G54 G1 X10 F1000\nG53 G1 X0\nG1 Y5\nM30\n", true);
    assert!((x(&m[2]) - 412.5).abs() < 1e-9, "{:?}", m[2].from);
    // A tool length along Z (the face mill's D1: 95.2 mm) moves the
    // workpiece position of the same machine position down by it.
    let m = motions(
        "G54 G1 Z10 F1000\nT=\"FACEMILL_63\" M6 D1\nG1 X5\nM30\n",
        true,
    );
    let last = m.last().expect("a motion");
    assert!((z(last) - (10.0 - 95.2)).abs() < 1e-9, "{:?}", last.from);
    // Another plane, another infeed axis: under `G18` the length acts
    // along Y, and Z is the machine's again.
    let m = motions(
        "G54 T=\"FACEMILL_63\" M6 D1\nG1 Y20 Z10 F1000\nG18\nG1 X5\nM30\n",
        true,
    );
    let last = m.last().expect("a motion");
    let y = last.from.get("Y").expect("Y");
    assert!((y - (20.0 - 95.2)).abs() < 1e-9, "{:?}", last.from);
    assert!((z(last) - (10.0 + 95.2)).abs() < 1e-9, "{:?}", last.from);
}
