//! Commands of issue 16 whose axis words do not simply traverse (SPEC
//! §11.5, §11.6): group 3 settings (`G25`/`G26`, `G58`/`G59`, the pole of
//! `G110`…`G112`), polar end points (`AP`, `RP`) and the one-block `ANG=`,
//! the approach of machine-data points (`G74`, `G75`), and increments
//! after a change of frame or offset (SD42440).

use std::sync::Arc;

use gcodec_driver::{RunSetup, run_main};
use gcodec_exec::event::{EventKind, MotionEvent, ProgramEndReason, VecSink};
use gcodec_lang::MotionKind;
use gcodec_profile::Profile;
use gcodec_source::{Severity, SourceFile};

/// What a run shows: its motions, its error codes, how it ended.
struct Run {
    motions: Vec<MotionEvent>,
    errors: Vec<&'static str>,
    end: ProgramEndReason,
}

impl Run {
    /// The end point of the last motion, workpiece (`to`) or machine
    /// coordinates, on `axes`.
    fn last(&self, machine: bool, axes: &[&str]) -> Vec<f64> {
        let motion = self.motions.last().expect("a motion");
        let map = if machine {
            &motion.to_machine
        } else {
            &motion.to
        };
        axes.iter().map(|a| map.get(a).expect("the axis")).collect()
    }
}

fn run_on(profile: Profile, program: &str) -> Run {
    let setup = RunSetup::new(profile);
    let file = Arc::new(SourceFile::new("GEOMETRY.MPF", program));
    let mut sink = VecSink::new();
    let report = run_main(file, &setup, &mut sink, None);
    assert!(
        !report.diagnostics.iter().any(|d| d.is_error()),
        "{program}: {:?}",
        report.diagnostics
    );
    let mut run = Run {
        motions: Vec::new(),
        errors: Vec::new(),
        end: ProgramEndReason::EndOfText,
    };
    for event in sink.events {
        match event.kind {
            EventKind::Motion(m) => run.motions.push(m),
            EventKind::Diagnostic(d) if d.severity == Severity::Error => {
                run.errors.push(d.code.name())
            }
            EventKind::ProgramEnd(e) => run.end = e.reason,
            _ => {}
        }
    }
    run
}

fn run(program: &str) -> Run {
    run_on(
        gcodec_profile::builtin().expect("the built-in profile"),
        program,
    )
}

fn profile(text: &str) -> Profile {
    gcodec_profile::load(text).unwrap_or_else(|e| panic!("{text}: {e:?}"))
}

fn close(got: &[f64], expected: &[f64]) {
    assert_eq!(got.len(), expected.len());
    for (g, e) in got.iter().zip(expected) {
        assert!((g - e).abs() < 1e-9, "got {got:?}, expected {expected:?}");
    }
}

#[test]
fn working_area_limits_do_not_traverse() {
    let r = run("G1 X1 Y1 F100\nG26 X300 Y300\nG25 X-10 Y-10 S100\nG26 S2000\nG1 X5\nM30\n");
    assert_eq!(r.errors, [] as [&str; 0]);
    assert_eq!(r.motions.len(), 2, "only the two G1 blocks move");
    close(&r.last(true, &["X", "Y"]), &[5.0, 1.0]);
}

#[test]
fn g58_replaces_the_coarse_and_g59_the_fine_translation_of_an_axis() {
    let r = run("TRANS X10 Y5\nG58 X20\nG0 X0 Y0\nM30\n");
    close(&r.last(true, &["X", "Y"]), &[20.0, 5.0]);
    // G59 adds the fine translation; G58 keeps it.
    let r = run("TRANS X10 Y5\nG59 X1\nG58 X20\nG0 X0 Y0\nM30\n");
    close(&r.last(true, &["X", "Y"]), &[21.0, 5.0]);
    assert_eq!(r.motions.len(), 1);
}

#[test]
fn g58_as_a_legacy_alias_selects_the_settable_offset() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../profiles/mill_g505_g599.toml"
    ))
    .expect("the shipped profile");
    let r = run_on(profile(&text), "G58\nG0 X0\nM30\n");
    let motion = r.motions.last().expect("a motion");
    assert_eq!(
        motion.work_offset.effective_work_offset_selected,
        gcodec_lang::WorkOffsetCode(505)
    );
}

#[test]
fn polar_end_points_go_about_the_pole_of_g111() {
    let r = run("G111 X0 Y0\nG1 AP=45 RP=10 F100\nM30\n");
    assert_eq!(r.errors, [] as [&str; 0]);
    assert_eq!(r.motions.len(), 1, "G111 itself does not move");
    let h = 10.0 * std::f64::consts::FRAC_1_SQRT_2;
    close(&r.last(false, &["X", "Y"]), &[h, h]);
}

#[test]
fn poles_of_g110_and_g112_are_relative_to_the_position_and_the_last_pole() {
    // G110: from the last programmed position (10, 10).
    let r = run("G0 X10 Y10\nG110 X5\nG1 AP=0 RP=2 F100\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[17.0, 10.0]);
    // G112: from the pole before, in polar form.
    let r = run("G111 X10 Y0\nG112 AP=90 RP=5\nG0 AP=0 RP=1\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[11.0, 5.0]);
    // The pole is set in the workpiece system: TRANS moves it along.
    let r = run("TRANS X100\nG111 X10 Y0\nG0 AP=180 RP=10\nM30\n");
    close(&r.last(true, &["X", "Y"]), &[100.0, 0.0]);
}

#[test]
fn polar_values_are_incremental_by_ic_and_under_g91_and_modal() {
    let r = run("G111 X0 Y0\nG0 AP=30 RP=10\nG0 AP=IC(60)\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[0.0, 10.0]);
    let r = run("G111 X0 Y0\nG0 AP=90 RP=10\nG0 RP=IC(-4)\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[0.0, 6.0]);
    let r = run("G111 X0 Y0\nG0 AP=90 RP=10 Z5\nG91 G0 AP=90 RP=2 Z1\nM30\n");
    close(&r.last(false, &["X", "Y", "Z"]), &[-12.0, 0.0, 6.0]);
    // A new pole starts the angle at 0; the radius stays.
    let r = run("G111 X0 Y0\nG0 AP=90 RP=10\nG111 X50 Y0\nG0 RP=10\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[60.0, 0.0]);
}

#[test]
fn polar_end_points_work_in_every_plane() {
    // G18: Z is the abscissa, X the ordinate.
    let r = run("G18 G111 Z0 X0\nG0 AP=90 RP=4 Y7\nM30\n");
    close(&r.last(false, &["X", "Y", "Z"]), &[4.0, 7.0, 0.0]);
    // G19: Y is the abscissa, Z the ordinate.
    let r = run("G19 G111 Y0 Z0\nG0 AP=90 RP=4\nM30\n");
    close(&r.last(false, &["X", "Y", "Z"]), &[0.0, 0.0, 4.0]);
}

#[test]
fn a_pole_on_the_diameter_axis_is_programmed_as_a_diameter() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../profiles/lathe_828d.toml"
    ))
    .expect("the shipped profile");
    // G18: Z is the abscissa, X (a diameter under DIAMON) the ordinate.
    let r = run_on(
        profile(&text),
        "G18 DIAMON G111 Z0 X20\nG0 AP=0 RP=5\nM30\n",
    );
    assert_eq!(r.errors, [] as [&str; 0]);
    close(&r.last(false, &["X", "Z"]), &[20.0, 5.0]);
    close(&r.last(true, &["X"]), &[10.0]);
}

#[test]
fn polar_arcs_go_about_the_pole() {
    let r = run("G111 X0 Y0\nG0 AP=0 RP=10\nG3 AP=90 F100\nG2 AP=0 RP=10\nM30\n");
    assert_eq!(r.errors, [] as [&str; 0]);
    let arc = &r.motions[1];
    assert_eq!(arc.motion, MotionKind::ArcCcw);
    assert_eq!(arc.radius, Some(10.0));
    close(
        &[arc
            .centre
            .as_ref()
            .and_then(|c| c.get("X"))
            .expect("a centre")],
        &[0.0],
    );
    close(&r.last(false, &["X", "Y"]), &[10.0, 0.0]);
}

#[test]
fn polar_and_cartesian_in_the_plane_is_an_error() {
    let r = run("G111 X0 Y0\nG1 AP=45 RP=10 X5 F100\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::polar_end_point"]);
    assert_eq!(r.end, ProgramEndReason::Alarm);
    let r = run("G111 X0 Y0\nG1 AP=45 RP=-1 F100\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::polar_end_point"]);
    let r = run("G111 X0 Y0\nG1 AP=45 RP=1 ANG=30 F100\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::contour_angle"]);
    let r = run("G111 X0 ANG=30\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::polar_end_point"]);
}

#[test]
fn one_block_contour_angle_gives_the_other_coordinate() {
    let r = run("G0 X10 Y0\nG1 X20 ANG=45 F100\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[20.0, 10.0]);
    let r = run("G0 X10 Y0\nG1 Y-5 ANG=135 F100\nM30\n");
    close(&r.last(false, &["X", "Y"]), &[15.0, -5.0]);
    let r = run("G0 X10 Y0\nG1 X20 ANG=90 F100\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::contour_angle"]);
    // Several blocks make the contour: not built yet, and said so (not
    // "no axis `ANG`": `ANG` is an address, not an axis).
    let r = run("G0 X10 Y0\nG1 ANG=45 F100\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::contour_angle"]);
}

const FIXED_POINTS: &str = r#"
[machine]
name = "mill with fixed points"
control = "840d_sl"

[[axes]]
name = "X"
kind = "linear"
geometry = true
fixed_points = [-10.0, -250.0]
reference_point = 5.0

[[axes]]
name = "Y"
kind = "linear"
geometry = true

[[axes]]
name = "Z"
kind = "linear"
geometry = true
fixed_points = [-1.0, -2.0, -3.0]

[work_offsets.values.G54]
X = 100.0
Z = 50.0
"#;

#[test]
fn g75_goes_to_the_fixed_point_of_the_machine_axes_outside_every_frame() {
    let r = run_on(
        profile(FIXED_POINTS),
        "G54 G0 X1 Y2 Z3\nTRANS X7\nG75 FP=2 X1=0 Z1=0\nM30\n",
    );
    assert_eq!(r.errors, [] as [&str; 0]);
    let motion = r.motions.last().expect("a motion");
    assert_eq!(motion.motion, MotionKind::Rapid);
    close(&r.last(true, &["X", "Y", "Z"]), &[-250.0, 2.0, -2.0]);
    // Workpiece coordinates of that point in the frame in force.
    close(&r.last(false, &["X", "Z"]), &[-357.0, -52.0]);
    // FP=1 when not written.
    let r = run_on(profile(FIXED_POINTS), "G75 Z1=0\nM30\n");
    close(&r.last(true, &["Z"]), &[-1.0]);
}

#[test]
fn g74_goes_to_the_reference_point() {
    let r = run_on(profile(FIXED_POINTS), "G0 X30 Z30\nG74 X1=0 Z1=0\nM30\n");
    close(&r.last(true, &["X", "Z"]), &[5.0, 0.0]);
    // The built-in profile: machine zero; `Z1` names the machine axis.
    let r = run("G0 X30 Z30\nG74 Z1=0\nM30\n");
    assert_eq!(r.errors, [] as [&str; 0]);
    close(&r.last(true, &["X", "Z"]), &[30.0, 0.0]);
}

#[test]
fn a_fixed_point_the_profile_lacks_is_an_error() {
    let r = run_on(profile(FIXED_POINTS), "G75 FP=3 X1=0\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::fixed_point"]);
    let r = run_on(profile(FIXED_POINTS), "G75 FP=5 Z1=0\nM30\n");
    assert_eq!(r.errors, ["gcodec::run::fixed_point"]);
}

/// A mill with `G505` (X 5), increments after an offset change as
/// SD42440 = `traverses` says.
fn settable_g505(traverses: bool) -> Profile {
    profile(&format!(
        "[machine]\nname = \"mill with G505\"\ncontrol = \"840d_sl\"\n\n[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505\"]\nincremental_traverses_offset_change = {traverses}\n\n[work_offsets.values.G505]\nX = 5.0\n"
    ))
}

#[test]
fn an_increment_after_a_frame_or_offset_change_traverses_the_change() {
    for program in [
        "G0 X10\nTRANS X5\nG91 X1\nM30\n",
        "G0 X10\nTRANS X5\nX=IC(1)\nM30\n",
    ] {
        let r = run(program);
        close(&r.last(true, &["X"]), &[16.0]);
        close(&r.last(false, &["X"]), &[11.0]);
    }
    let r = run_on(settable_g505(true), "G0 X10\nG505\nG91 X1\nM30\n");
    close(&r.last(true, &["X"]), &[16.0]);
    // Once traversed, increments go on from the new position.
    let r = run("G0 X10\nTRANS X5\nG91 X1\nX1\nM30\n");
    close(&r.last(true, &["X"]), &[17.0]);
    // A suppressed block programs the machine position: its increment
    // counts from there, and it changes no frame for the next block.
    let r = run_on(settable_g505(true), "G505 G0 X10\nG53 G91 X1\nX1\nM30\n");
    assert_eq!(r.motions[1].to_machine.get("X"), Some(16.0));
    close(&r.last(true, &["X"]), &[17.0]);
}

#[test]
fn the_profile_can_make_increments_follow_only_the_programmed_path() {
    let r = run_on(settable_g505(false), "G0 X10\nG505\nG91 X1\nM30\n");
    close(&r.last(true, &["X"]), &[11.0]);
}
