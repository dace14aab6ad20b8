//! The path stage (chamfers, roundings, tool radius compensation) on
//! random contours: whatever the geometry, the run never panics, every
//! event is in block order, every number it writes is finite, and every
//! block's motion comes out once.

mod common;

use common::runs::events_of_text;
use gcodec_exec::event::{EventKind, MotionEvent};
use proptest::prelude::*;

fn mill() -> gcodec_profile::Profile {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/fixtures/run/mill.toml"
    ))
    .expect("the fixture mill");
    gcodec_profile::load(&text).expect("a valid profile")
}

/// One block of a contour: a move in the plane, with what may come with
/// it.
fn block() -> impl Strategy<Value = String> {
    let coordinate = -40i32..40;
    let motion = prop_oneof![
        (coordinate.clone(), coordinate.clone()).prop_map(|(x, y)| format!("G1 X{x} Y{y}")),
        (
            coordinate.clone(),
            coordinate.clone(),
            5i32..60,
            any::<bool>()
        )
            .prop_map(|(x, y, r, cw)| format!("{} X{x} Y{y} CR={r}", if cw { "G2" } else { "G3" })),
        (-5i32..5).prop_map(|z| format!("G1 Z{z}")),
        Just("M8".to_owned()),
    ];
    let extra = prop_oneof![
        4 => Just(String::new()),
        1 => (1i32..8).prop_map(|r| format!(" RND={r}")),
        1 => (1i32..8).prop_map(|c| format!(" CHF={c}")),
        1 => Just(" G41".to_owned()),
        1 => Just(" G42".to_owned()),
        1 => Just(" G40".to_owned()),
        1 => Just(" G451".to_owned()),
        1 => Just(" G450".to_owned()),
        1 => Just(" CDON".to_owned()),
        1 => Just(" KONT".to_owned()),
        1 => Just(" KONTT".to_owned()),
        1 => (0i32..100).prop_map(|d| format!(" DISC={d}")),
        1 => (-2i32..3).prop_map(|o| format!(" OFFN={o}")),
        1 => (0i32..4).prop_map(|r| format!(" RNDM={r}")),
    ];
    (motion, extra).prop_map(|(m, e)| format!("{m}{e}"))
}

fn finite(motion: &MotionEvent) -> bool {
    let maps = [&motion.from, &motion.to, &motion.to_machine];
    maps.iter().all(|m| m.iter().all(|(_, v)| v.is_finite()))
        && motion.tool.as_ref().is_none_or(|t| {
            t.tool_to.iter().all(|(_, v)| v.is_finite())
                && t.tool_to_machine.iter().all(|(_, v)| v.is_finite())
        })
        && motion.radius.is_none_or(f64::is_finite)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn random_contours_run_to_an_end_in_block_order(blocks in prop::collection::vec(block(), 1..14)) {
        let mut program = String::from("T1 D1 M6\nG17 G90 G54 F300\nG0 X0 Y0 Z2\nG1 Z-1\n");
        for b in &blocks {
            program.push_str(b);
            program.push('\n');
        }
        program.push_str("G40 G1 X-50 Y-50\nM30\n");
        let events = events_of_text(mill(), "PATH.MPF", &program);
        let last = events.last().expect("a program_end");
        prop_assert!(matches!(last.kind, EventKind::ProgramEnd(_)), "{program}");
        let mut line = 0;
        for event in &events {
            if let EventKind::Motion(motion) = &event.kind {
                prop_assert!(finite(motion), "{program}\n{event:?}");
            }
            // The same or a later block, but for the warnings of the end.
            if !matches!(event.kind, EventKind::Diagnostic(_) | EventKind::ProgramEnd(_)) {
                prop_assert!(event.source.line >= line, "{program}\nout of order: {event:?}");
                line = event.source.line;
            }
        }
    }
}
