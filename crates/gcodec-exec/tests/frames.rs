//! Frames with hand-checked numbers (SPEC §11.x "Frames"; reference §9).
//!
//! The milling machine has the axes X, Y, Z (geometry) and C (rotary),
//! indices 0…3; the lathe X, Z (geometry) and C. A frame maps a point of
//! its inner (workpiece) system to the outer one as `T + R·(S·M·p)`.

use gcodec_exec::frames::{Frame, FrameAxes, chain_values, frame_function};
use gcodec_exec::geometry::Plane;
use gcodec_exec::value::{FrameAxis, FrameValue, RtValue, RunError};
use gcodec_lang::FrameOp;
use gcodec_lang::functions::Function;
use std::sync::Arc;

use gcodec_source::codes;

const X: usize = 0;
const Y: usize = 1;
const Z: usize = 2;
const C: usize = 3;
/// cos 45° = sin 45° = 1/√2.
const H: f64 = std::f64::consts::FRAC_1_SQRT_2;
/// cos 30° = √3/2.
const C30: f64 = 0.866_025_403_784_438_6;

fn mill() -> FrameAxes {
    FrameAxes::new([("X", true), ("Y", true), ("Z", true), ("C", false)])
}

fn lathe() -> FrameAxes {
    FrameAxes::new([("X", true), ("Z", true), ("C", false)])
}

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < 1e-9, "{what}: got {a}, expected {b}");
}

fn close_all(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths");
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        close(*x, *y, &format!("{what} [{k}]"));
    }
}

/// One instruction: the op, (axis index, value) pairs, `RPL=`.
type Step<'a> = (FrameOp, &'a [(usize, f64)], Option<f64>);

/// A frame after a sequence of instructions under `G17`.
fn run(axes: &FrameAxes, steps: &[Step]) -> Frame {
    let mut f = Frame::neutral(axes);
    for (op, values, rpl) in steps {
        f.apply(axes, *op, values, *rpl, Plane::G17)
            .unwrap_or_else(|e| panic!("{op:?} {values:?}: {e}"));
    }
    f
}

fn outer(f: &Frame, p: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; p.len()];
    f.to_outer(p, &mut out);
    out
}

fn inner(f: &Frame, p: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; p.len()];
    f.to_inner(p, &mut out);
    out
}

/// `to_outer` gives `expected`, and `to_inner` brings it back.
fn maps(f: &Frame, p: &[f64], expected: &[f64]) {
    let o = outer(f, p);
    close_all(&o, expected, "to_outer");
    close_all(&inner(f, &o), p, "to_inner");
}

fn apply_err(
    f: &mut Frame,
    axes: &FrameAxes,
    op: FrameOp,
    values: &[(usize, f64)],
    rpl: Option<f64>,
    plane: Plane,
) -> RunError {
    let before = f.clone();
    let e = f
        .apply(axes, op, values, rpl, plane)
        .expect_err("the instruction is rejected");
    assert_eq!(*f, before, "a rejected instruction leaves the frame alone");
    e
}

// ---------------------------------------------------------------------
// Instructions

#[test]
fn solid_angle_rotations_are_not_simulated() {
    let axes = mill();
    let mut f = run(&axes, &[(FrameOp::Trans, &[(X, 10.0)], None)]);
    for op in [FrameOp::Rots, FrameOp::Arots, FrameOp::Crots] {
        let e = apply_err(&mut f, &axes, op, &[(X, 30.0)], None, Plane::G17);
        assert_eq!(e.code, codes::run::FRAME, "{op:?}");
        assert!(e.message.contains(op.keyword()), "{}", e.message);
    }
}

#[test]
fn trans_offsets_the_named_axes() {
    let axes = mill();
    let f = run(&axes, &[(FrameOp::Trans, &[(X, 10.0), (Y, 5.0)], None)]);
    assert!(!f.is_neutral());
    assert_eq!((f.coarse(X), f.coarse(Y), f.coarse(Z)), (10.0, 5.0, 0.0));
    // (1, 2, 3, 0) + (10, 5, 0, 0)
    maps(&f, &[1.0, 2.0, 3.0, 0.0], &[11.0, 7.0, 3.0, 0.0]);
}

#[test]
fn atrans_adds_to_the_translation() {
    // The manual's example: TRANS X10 Y10 Z10, ATRANS X5 Y5 → X15 Y15 Z10.
    let axes = mill();
    let f = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, 10.0), (Y, 10.0), (Z, 10.0)], None),
            (FrameOp::Atrans, &[(X, 5.0), (Y, 5.0)], None),
        ],
    );
    assert_eq!((f.coarse(X), f.coarse(Y), f.coarse(Z)), (15.0, 15.0, 10.0));
    assert_eq!(f.fine(X), 0.0);
}

#[test]
fn substituting_ops_reset_everything_first() {
    let axes = mill();
    let base: &[Step] = &[
        (FrameOp::Trans, &[(X, 10.0), (C, 3.0)], None),
        (FrameOp::Arot, &[], Some(30.0)),
        (FrameOp::Ascale, &[(Y, 2.0)], None),
        (FrameOp::Amirror, &[(Z, 0.0)], None),
    ];
    // SCALE X2 keeps only the scale of X: (1, 1, 1, 1) → (2, 1, 1, 1).
    let mut f = run(&axes, base);
    f.apply(&axes, FrameOp::Scale, &[(X, 2.0)], None, Plane::G17)
        .unwrap();
    maps(&f, &[1.0, 1.0, 1.0, 1.0], &[2.0, 1.0, 1.0, 1.0]);
    // MIRROR Y0 keeps only the mirroring of Y.
    let mut f = run(&axes, base);
    f.apply(&axes, FrameOp::Mirror, &[(Y, 0.0)], None, Plane::G17)
        .unwrap();
    maps(&f, &[1.0, 1.0, 1.0, 1.0], &[1.0, -1.0, 1.0, 1.0]);
    // ROT Z90 keeps only the rotation: (1, 0, 0) → (0, 1, 0).
    let mut f = run(&axes, base);
    f.apply(&axes, FrameOp::Rot, &[(Z, 90.0)], None, Plane::G17)
        .unwrap();
    assert_eq!(f.angles(), [0.0, 0.0, 90.0]);
    maps(&f, &[1.0, 0.0, 0.0, 7.0], &[0.0, 1.0, 0.0, 7.0]);
    // The bare keywords reset.
    for op in [
        FrameOp::Trans,
        FrameOp::Rot,
        FrameOp::Scale,
        FrameOp::Mirror,
    ] {
        let mut f = run(&axes, base);
        f.apply(&axes, op, &[], None, Plane::G17).unwrap();
        assert!(f.is_neutral(), "{op:?}");
        assert_eq!(f, Frame::neutral(&axes), "{op:?}");
    }
}

#[test]
fn additive_ops_without_values_change_nothing() {
    let axes = mill();
    let base: &[Step] = &[
        (FrameOp::Trans, &[(X, 10.0)], None),
        (FrameOp::Arot, &[(Z, 30.0)], None),
    ];
    for op in [
        FrameOp::Atrans,
        FrameOp::Arot,
        FrameOp::Ascale,
        FrameOp::Amirror,
    ] {
        let mut f = run(&axes, base);
        f.apply(&axes, op, &[], None, Plane::G17).unwrap();
        assert_eq!(f, run(&axes, base), "{op:?}");
    }
}

#[test]
fn atrans_after_rot_moves_along_the_rotated_axes() {
    let axes = mill();
    let f = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 45.0)], None),
            (FrameOp::Atrans, &[(X, 10.0)], None),
        ],
    );
    // T = Rz(45)·(10, 0, 0) = (10·cos 45, 10·sin 45, 0) = (7.0711, 7.0711, 0).
    close(f.coarse(X), 10.0 * H, "TR X");
    close(f.coarse(Y), 10.0 * H, "TR Y");
    close(f.coarse(Z), 0.0, "TR Z");
    // Inner (10, 0, 0): T + Rz(45)·(10, 0, 0) = (14.1421, 14.1421, 0).
    maps(&f, &[10.0, 0.0, 0.0, 0.0], &[20.0 * H, 20.0 * H, 0.0, 0.0]);
    // A rotary axis is translated, never rotated.
    let f = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 90.0)], None),
            (FrameOp::Atrans, &[(C, 10.0)], None),
        ],
    );
    assert_eq!((f.coarse(X), f.coarse(Y), f.coarse(C)), (0.0, 0.0, 10.0));
}

#[test]
fn rpl_rotates_in_the_active_plane() {
    let axes = mill();
    let rot = |plane: Plane, angle: f64| {
        let mut f = Frame::neutral(&axes);
        f.apply(&axes, FrameOp::Rot, &[], Some(angle), plane)
            .unwrap();
        f
    };
    // G17, about Z: X → Y; Y → −X.
    let f = rot(Plane::G17, 90.0);
    assert_eq!(f.angles(), [0.0, 0.0, 90.0]);
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[0.0, 1.0, 0.0, 0.0]);
    maps(&f, &[0.0, 1.0, 0.0, 0.0], &[-1.0, 0.0, 0.0, 0.0]);
    // G17 by 30°: (1, 0, 0) → (cos 30, sin 30, 0) = (0.8660, 0.5, 0).
    maps(
        &rot(Plane::G17, 30.0),
        &[1.0, 0.0, 0.0, 0.0],
        &[C30, 0.5, 0.0, 0.0],
    );
    // G18, about Y (the Z/X plane, Z the abscissa): Z → X; X → −Z.
    let f = rot(Plane::G18, 90.0);
    assert_eq!(f.angles(), [0.0, 90.0, 0.0]);
    maps(&f, &[0.0, 0.0, 1.0, 0.0], &[1.0, 0.0, 0.0, 0.0]);
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[0.0, 0.0, -1.0, 0.0]);
    // G19, about X (the Y/Z plane): Y → Z; Z → −Y.
    let f = rot(Plane::G19, 90.0);
    assert_eq!(f.angles(), [90.0, 0.0, 0.0]);
    maps(&f, &[0.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 1.0, 0.0]);
    maps(&f, &[0.0, 0.0, 1.0, 0.0], &[0.0, -1.0, 0.0, 0.0]);
    // AROT RPL= adds in the plane: 30 + 15 = 45 about Y.
    let mut f = rot(Plane::G18, 30.0);
    f.apply(&axes, FrameOp::Arot, &[], Some(15.0), Plane::G18)
        .unwrap();
    assert_eq!(f.angles(), [0.0, 45.0, 0.0]);
    // Ry(45)·(0, 0, 1) = (sin 45, 0, cos 45).
    maps(&f, &[0.0, 0.0, 1.0, 0.0], &[H, 0.0, H, 0.0]);
}

#[test]
fn several_angles_in_one_rot_are_rpy_z_then_y_then_x() {
    let axes = mill();
    // ROT X90 Z90 = Rz(90)·Rx(90) = [[0,0,1],[1,0,0],[0,1,0]]:
    // e1 → Rx: e1 → Rz: e2;  e2 → Rx: e3 → Rz: e3;  e3 → Rx: −e2 → Rz: e1.
    // (The other order, Rx·Rz, would send e1 to e3.)
    for values in [[(X, 90.0), (Z, 90.0)], [(Z, 90.0), (X, 90.0)]] {
        let f = run(&axes, &[(FrameOp::Rot, &values, None)]);
        assert_eq!(f.angles(), [90.0, 0.0, 90.0]);
        assert_eq!(
            f.rotation_matrix(),
            [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        );
        maps(&f, &[1.0, 0.0, 0.0, 0.0], &[0.0, 1.0, 0.0, 0.0]);
        maps(&f, &[0.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 1.0, 0.0]);
        maps(&f, &[0.0, 0.0, 1.0, 0.0], &[1.0, 0.0, 0.0, 0.0]);
    }
    // ROT Y90 Z90 = Rz(90)·Ry(90): e1 → Ry: −e3 → Rz: −e3;
    // e3 → Ry: e1 → Rz: e2.
    let f = run(&axes, &[(FrameOp::Rot, &[(Y, 90.0), (Z, 90.0)], None)]);
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[0.0, 0.0, -1.0, 0.0]);
    maps(&f, &[0.0, 0.0, 1.0, 0.0], &[0.0, 1.0, 0.0, 0.0]);
}

#[test]
fn arot_composes_in_the_rotated_system() {
    let axes = mill();
    // ROT Z90 then AROT X90 turns about the new X'': the same as ROT X90 Z90.
    let a = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 90.0)], None),
            (FrameOp::Arot, &[(X, 90.0)], None),
        ],
    );
    let b = run(&axes, &[(FrameOp::Rot, &[(X, 90.0), (Z, 90.0)], None)]);
    assert_eq!(a.angles(), [90.0, 0.0, 90.0]);
    assert_eq!(a, b);
    // About one axis the angles add: 30 + 20 = 50, and (1, 0, 0) → (cos 50, sin 50, 0).
    let f = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 30.0)], None),
            (FrameOp::Arot, &[(Z, 20.0)], None),
        ],
    );
    assert_eq!(f.angles(), [0.0, 0.0, 50.0]);
    let (s, c) = 50f64.to_radians().sin_cos();
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[c, s, 0.0, 0.0]);
    // … also past 180 (170 + 20 reads 190, as programmed).
    let f = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 170.0)], None),
            (FrameOp::Arot, &[(Z, 20.0)], None),
        ],
    );
    assert_eq!(f.angles(), [0.0, 0.0, 190.0]);
    // A translation before AROT stays where it was: TRANS X10, AROT Z90,
    // inner (1, 0, 0) → (10, 0, 0) + (0, 1, 0).
    let f = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, 10.0)], None),
            (FrameOp::Arot, &[(Z, 90.0)], None),
        ],
    );
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[10.0, 1.0, 0.0, 0.0]);
}

#[test]
fn ascale_multiplies_and_scales_a_later_atrans() {
    let axes = mill();
    // The manual's example: SCALE X2 Y2, ATRANS X2.5 Y18: the offset is
    // scaled too, T = (5, 36).
    let f = run(
        &axes,
        &[
            (FrameOp::Scale, &[(X, 2.0), (Y, 2.0)], None),
            (FrameOp::Atrans, &[(X, 2.5), (Y, 18.0)], None),
            (FrameOp::Ascale, &[(X, 3.0)], None),
        ],
    );
    assert_eq!((f.coarse(X), f.coarse(Y)), (5.0, 36.0));
    // Scales 2·3 = 6 and 2.
    assert_eq!((f.scale(X), f.scale(Y), f.scale(Z)), (6.0, 2.0, 1.0));
    // (1, 1, 0) → (6·1 + 5, 2·1 + 36, 0) = (11, 38, 0).
    maps(&f, &[1.0, 1.0, 0.0, 0.0], &[11.0, 38.0, 0.0, 0.0]);
    // ASCALE after ROT scales the rotated X: ROT Z90, ASCALE X2:
    // (1, 0, 0) → S: (2, 0, 0) → Rz(90): (0, 2, 0).
    let f = run(
        &axes,
        &[
            (FrameOp::Rot, &[(Z, 90.0)], None),
            (FrameOp::Ascale, &[(X, 2.0)], None),
        ],
    );
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[0.0, 2.0, 0.0, 0.0]);
}

#[test]
fn mirror_and_amirror() {
    let axes = mill();
    // MIRROR X0: the value is ignored, X changes sign.
    let f = run(&axes, &[(FrameOp::Mirror, &[(X, 0.0)], None)]);
    assert!(f.mirrored(X) && !f.mirrored(Y));
    maps(&f, &[3.0, 4.0, 5.0, 0.0], &[-3.0, 4.0, 5.0, 0.0]);
    let f = run(&axes, &[(FrameOp::Mirror, &[(X, 25.0)], None)]);
    maps(&f, &[3.0, 4.0, 5.0, 0.0], &[-3.0, 4.0, 5.0, 0.0]);
    // ATRANS in the mirrored system: ATRANS X10 → T X = −10;
    // inner X 1 → −1 − 10 = −11.
    let f = run(
        &axes,
        &[
            (FrameOp::Mirror, &[(X, 0.0)], None),
            (FrameOp::Atrans, &[(X, 10.0)], None),
        ],
    );
    assert_eq!(f.coarse(X), -10.0);
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[-11.0, 0.0, 0.0, 0.0]);
    // AMIRROR toggles: X back, Y mirrored.
    let f = run(
        &axes,
        &[
            (FrameOp::Mirror, &[(X, 0.0)], None),
            (FrameOp::Amirror, &[(X, 0.0), (Y, 0.0)], None),
        ],
    );
    assert!(!f.mirrored(X) && f.mirrored(Y));
    maps(&f, &[3.0, 4.0, 5.0, 0.0], &[3.0, -4.0, 5.0, 0.0]);
    // A rotary axis mirrors too.
    let f = run(&axes, &[(FrameOp::Mirror, &[(C, 0.0)], None)]);
    maps(&f, &[0.0, 0.0, 0.0, 90.0], &[0.0, 0.0, 0.0, -90.0]);
}

#[test]
fn arot_in_a_mirrored_system_turns_the_other_way() {
    let axes = mill();
    // MIRROR X0, AROT Z30: inner (1, 0, 0) → Rz(30): (cos 30, sin 30, 0)
    // → mirrored X: (−0.8660, 0.5, 0). Seen from outside that is a
    // rotation by −30 of the mirrored point (−1, 0, 0): Rz(−30)·(−1, 0, 0)
    // = (−cos 30, sin 30, 0).
    let f = run(
        &axes,
        &[
            (FrameOp::Mirror, &[(X, 0.0)], None),
            (FrameOp::Arot, &[(Z, 30.0)], None),
        ],
    );
    assert_eq!(f.angles(), [0.0, 0.0, -30.0]);
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[-C30, 0.5, 0.0, 0.0]);
}

#[test]
fn scale_translation_rotation_order_within_one_frame() {
    let axes = mill();
    // TRANS X10 Y20, AROT Z90, ASCALE X2, AMIRROR Y0:
    // outer = T + Rz(90)·(S·M·p); p = (1, 1, 0):
    // S·M·p = (2, −1, 0); Rz(90)·(2, −1, 0) = (1, 2, 0); + (10, 20, 0) = (11, 22, 0).
    let f = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, 10.0), (Y, 20.0)], None),
            (FrameOp::Arot, &[(Z, 90.0)], None),
            (FrameOp::Ascale, &[(X, 2.0)], None),
            (FrameOp::Amirror, &[(Y, 0.0)], None),
        ],
    );
    maps(&f, &[1.0, 1.0, 0.0, 0.0], &[11.0, 22.0, 0.0, 0.0]);
}

#[test]
fn rejected_instructions() {
    let axes = mill();
    let mut f = run(&axes, &[(FrameOp::Trans, &[(X, 1.0)], None)]);
    let g17 = Plane::G17;
    // A rotation of a rotary axis.
    let e = apply_err(&mut f, &axes, FrameOp::Rot, &[(C, 30.0)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    assert!(e.message.contains("C is not a geometry axis"), "{e}");
    let e = apply_err(&mut f, &axes, FrameOp::Arot, &[(C, 30.0)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    // Scale 0.
    let e = apply_err(&mut f, &axes, FrameOp::Scale, &[(Y, 0.0)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    assert!(e.message.contains("must not be 0"), "{e}");
    let e = apply_err(&mut f, &axes, FrameOp::Ascale, &[(X, -0.0)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    // Not a number.
    for v in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        for op in [
            FrameOp::Trans,
            FrameOp::Atrans,
            FrameOp::Rot,
            FrameOp::Ascale,
        ] {
            let e = apply_err(&mut f, &axes, op, &[(X, v)], None, g17);
            assert_eq!(e.code, codes::run::FRAME);
        }
        let e = apply_err(&mut f, &axes, FrameOp::Rot, &[], Some(v), g17);
        assert_eq!(e.code, codes::run::FRAME);
    }
    // An index that is no axis.
    let e = apply_err(&mut f, &axes, FrameOp::Trans, &[(4, 1.0)], None, g17);
    assert_eq!(e.code, codes::run::UNKNOWN_AXIS);
    // RPL= with TRANS, or together with axis angles.
    let e = apply_err(&mut f, &axes, FrameOp::Trans, &[], Some(10.0), g17);
    assert_eq!(e.code, codes::run::FRAME);
    let e = apply_err(&mut f, &axes, FrameOp::Rot, &[(Z, 5.0)], Some(10.0), g17);
    assert_eq!(e.code, codes::run::FRAME);
    // Overflow: 1e300 · 1e300 and 1e308 + 1e308 are infinite; 1e-200 · 1e-200 is 0.
    let mut f = run(&axes, &[(FrameOp::Scale, &[(X, 1e300)], None)]);
    let e = apply_err(&mut f, &axes, FrameOp::Ascale, &[(X, 1e300)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    let mut f = run(&axes, &[(FrameOp::Trans, &[(Y, 1e308)], None)]);
    let e = apply_err(&mut f, &axes, FrameOp::Atrans, &[(Y, 1e308)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
    let mut f = run(&axes, &[(FrameOp::Scale, &[(Z, 1e-200)], None)]);
    let e = apply_err(&mut f, &axes, FrameOp::Ascale, &[(Z, 1e-200)], None, g17);
    assert_eq!(e.code, codes::run::FRAME);
}

#[test]
fn a_lathe_rotates_only_in_its_z_x_plane() {
    let axes = lathe();
    // X is slot X, Z slot Z; there is no Y.
    assert_eq!(axes.geometry_slot(0), Some(0));
    assert_eq!(axes.geometry_slot(1), Some(2));
    assert_eq!(axes.geometry_axis(1), None);
    let mut f = Frame::neutral(&axes);
    f.apply(&axes, FrameOp::Rot, &[], Some(90.0), Plane::G18)
        .unwrap();
    // Ry(90): Z → X, X → −Z. Points are (X, Z, C).
    maps(&f, &[0.0, 1.0, 0.0], &[1.0, 0.0, 0.0]);
    maps(&f, &[1.0, 0.0, 5.0], &[0.0, -1.0, 5.0]);
    // G17 would turn X into the missing Y.
    let e = apply_err(&mut f, &axes, FrameOp::Arot, &[], Some(30.0), Plane::G17);
    assert_eq!(e.code, codes::run::FRAME);
    assert!(e.message.contains("geometry axis Y"), "{e}");
    // ROT about X (G19) too: Z would turn into Y.
    let e = apply_err(&mut f, &axes, FrameOp::Rot, &[(0, 10.0)], None, Plane::G18);
    assert_eq!(e.code, codes::run::FRAME);
    // A half turn about Z keeps Y out of it: X → −X.
    f.apply(&axes, FrameOp::Rot, &[(1, 180.0)], None, Plane::G18)
        .unwrap();
    maps(&f, &[2.0, 3.0, 0.0], &[-2.0, 3.0, 0.0]);
    // TRANS of the rotary C.
    let f = run(&axes, &[(FrameOp::Trans, &[(2, 45.0)], None)]);
    maps(&f, &[1.0, 2.0, 10.0], &[1.0, 2.0, 55.0]);
}

// ---------------------------------------------------------------------
// Inverse, chain

/// A frame with every component: TRANS X10 Y−5 Z3 C45, AROT X20 Y−35 Z70,
/// ASCALE X1.5 Y1.5 Z1.5 C2, AMIRROR Y0, ATRANS X1 Y2 Z3.
fn busy(axes: &FrameAxes) -> Frame {
    run(
        axes,
        &[
            (
                FrameOp::Trans,
                &[(X, 10.0), (Y, -5.0), (Z, 3.0), (C, 45.0)],
                None,
            ),
            (FrameOp::Arot, &[(X, 20.0), (Y, -35.0), (Z, 70.0)], None),
            (
                FrameOp::Ascale,
                &[(X, 1.5), (Y, 1.5), (Z, 1.5), (C, 2.0)],
                None,
            ),
            (FrameOp::Amirror, &[(Y, 0.0)], None),
            (FrameOp::Atrans, &[(X, 1.0), (Y, 2.0), (Z, 3.0)], None),
        ],
    )
}

/// Deterministic points spread over ±1000.
fn points() -> impl Iterator<Item = [f64; 4]> {
    (0..200).map(|k| {
        let k = f64::from(k);
        [
            (k * 1.3).sin() * 1000.0,
            (k * 0.7).cos() * 500.0,
            (k * 2.1).sin() * 250.0 - 100.0,
            k * 3.6 - 360.0,
        ]
    })
}

#[test]
fn to_inner_inverts_to_outer() {
    let axes = mill();
    let mut frames = vec![busy(&axes), Frame::neutral(&axes)];
    // Unequal scales under a rotation still invert exactly point by point.
    frames.push(run(
        &axes,
        &[
            (FrameOp::Rot, &[(X, 10.0), (Y, 20.0), (Z, 30.0)], None),
            (FrameOp::Ascale, &[(X, 2.0), (Y, -0.5), (Z, 3.0)], None),
            (FrameOp::Atrans, &[(X, 7.0), (C, -1.0)], None),
        ],
    ));
    for f in &frames {
        for p in points() {
            let o = outer(f, &p);
            close_all(&inner(f, &o), &p, "inner(outer(p))");
            let i = inner(f, &p);
            close_all(&outer(f, &i), &p, "outer(inner(p))");
        }
    }
}

#[test]
fn chain_is_composition_and_inverse_undoes_it() {
    let axes = mill();
    let a = busy(&axes);
    let b = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, -3.0), (C, 10.0)], None),
            (FrameOp::Arot, &[], Some(-15.0)),
            (FrameOp::Amirror, &[(X, 0.0)], None),
        ],
    );
    let ab = a.chain(&b);
    for p in points() {
        let direct = outer(&ab, &p);
        let stepwise = outer(&a, &outer(&b, &p));
        close_all(&direct, &stepwise, "(a:b)(p) = a(b(p))");
    }
    for f in [&a, &b, &ab] {
        let id = f.chain(&f.inverse());
        let id2 = f.inverse().chain(f);
        for p in points().take(20) {
            close_all(&outer(&id, &p), &p, "f : f⁻¹");
            close_all(&outer(&id2, &p), &p, "f⁻¹ : f");
        }
    }
    // TRANS X10 inverted: X −10.
    let t = run(&axes, &[(FrameOp::Trans, &[(X, 10.0)], None)]);
    assert_eq!(t.inverse().coarse(X), -10.0);
}

#[test]
fn g54_chained_with_a_programmable_trans_and_rot() {
    let axes = mill();
    // G54 = X100 Y50 Z−20; programmable TRANS X10, AROT RPL=90.
    let g54 = Frame::translation(&axes, &[(X, 100.0), (Y, 50.0), (Z, -20.0)]).unwrap();
    let prog = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, 10.0)], None),
            (FrameOp::Arot, &[], Some(90.0)),
        ],
    );
    let total = g54.chain(&prog);
    // Inner (5, 0, 0): Rz(90) → (0, 5, 0); + (10, 0, 0) → (10, 5, 0);
    // + G54 → (110, 55, −20).
    maps(&total, &[5.0, 0.0, 0.0, 0.0], &[110.0, 55.0, -20.0, 0.0]);
    let v = total.to_value(&axes);
    assert_eq!(v.component("X", "TR"), Some(110.0));
    assert_eq!(v.component("Y", "TR"), Some(50.0));
    assert_eq!(v.component("Z", "TR"), Some(-20.0));
    assert_eq!(v.component("Z", "RT"), Some(90.0));
    // A rotated outer frame turns the inner translation: G54 rotated by 90
    // about Z, inner TRANS X10: T = (100, 50, −20) + Rz(90)·(10, 0, 0) = (100, 60, −20).
    let mut rotated = FrameValue::default();
    rotated.axes.push(FrameAxis {
        translation: 100.0,
        ..FrameAxis::neutral("X")
    });
    rotated.axes.push(FrameAxis {
        translation: 50.0,
        ..FrameAxis::neutral("Y")
    });
    rotated.axes.push(FrameAxis {
        translation: -20.0,
        rotation: 90.0,
        ..FrameAxis::neutral("Z")
    });
    let g54 = Frame::from_value(&axes, &rotated).unwrap();
    let t = g54.chain(&run(&axes, &[(FrameOp::Trans, &[(X, 10.0)], None)]));
    assert_eq!(
        (t.coarse(X), t.coarse(Y), t.coarse(Z)),
        (100.0, 60.0, -20.0)
    );
    // Translation frames reject what is no number or no axis.
    assert_eq!(
        Frame::translation(&axes, &[(X, f64::NAN)])
            .unwrap_err()
            .code,
        codes::run::FRAME
    );
    assert_eq!(
        Frame::translation(&axes, &[(9, 1.0)]).unwrap_err().code,
        codes::run::UNKNOWN_AXIS
    );
}

// ---------------------------------------------------------------------
// Values and functions

#[test]
fn frame_value_round_trip() {
    let axes = mill();
    // TRANS X10, AROT RPL=45, ASCALE C2, AMIRROR Y0.
    let f = run(
        &axes,
        &[
            (FrameOp::Trans, &[(X, 10.0)], None),
            (FrameOp::Arot, &[], Some(45.0)),
            (FrameOp::Ascale, &[(C, 2.0)], None),
            (FrameOp::Amirror, &[(Y, 0.0)], None),
        ],
    );
    let v = f.to_value(&axes);
    let names: Vec<&str> = v.axes.iter().map(|a| &*a.axis).collect();
    assert_eq!(names, ["X", "Y", "Z", "C"]);
    assert_eq!(v.component("X", "TR"), Some(10.0));
    assert_eq!(v.component("X", "FI"), Some(0.0));
    assert_eq!(v.component("Y", "MI"), Some(1.0));
    assert_eq!(v.component("Z", "RT"), Some(45.0));
    assert_eq!(v.component("C", "SC"), Some(2.0));
    assert_eq!(v.component("C", "RT"), Some(0.0));
    assert_eq!(Frame::from_value(&axes, &v).unwrap(), f);
    // Neutral axes are left out; the neutral frame is the empty value.
    let t = run(&axes, &[(FrameOp::Trans, &[(Y, -2.5)], None)]);
    let names: Vec<String> = t
        .to_value(&axes)
        .axes
        .iter()
        .map(|a| a.axis.to_string())
        .collect();
    assert_eq!(names, ["Y"]);
    assert_eq!(Frame::neutral(&axes).to_value(&axes), FrameValue::default());
    // Every frame of the busy sequence survives the round trip.
    let b = busy(&axes);
    let back = Frame::from_value(&axes, &b.to_value(&axes)).unwrap();
    for p in points().take(20) {
        close_all(&outer(&back, &p), &outer(&b, &p), "round trip");
    }
}

#[test]
fn from_value_rejects_what_no_frame_holds() {
    let axes = mill();
    let one = |fa: FrameAxis| FrameValue { axes: vec![fa] };
    let q = one(FrameAxis {
        translation: 1.0,
        ..FrameAxis::neutral("Q")
    });
    assert_eq!(
        Frame::from_value(&axes, &q).unwrap_err().code,
        codes::run::UNKNOWN_AXIS
    );
    // A neutral unknown axis does no harm; names are case-insensitive.
    assert!(
        Frame::from_value(&axes, &one(FrameAxis::neutral("Q")))
            .unwrap()
            .is_neutral()
    );
    let x = Frame::from_value(
        &axes,
        &one(FrameAxis {
            fine: 0.5,
            ..FrameAxis::neutral("x")
        }),
    )
    .unwrap();
    assert_eq!(x.fine(X), 0.5);
    let bad = [
        FrameAxis {
            rotation: 10.0,
            ..FrameAxis::neutral("C")
        },
        FrameAxis {
            scale: 0.0,
            ..FrameAxis::neutral("X")
        },
        FrameAxis {
            translation: f64::NAN,
            ..FrameAxis::neutral("X")
        },
        FrameAxis {
            rotation: f64::INFINITY,
            ..FrameAxis::neutral("Z")
        },
    ];
    for fa in bad {
        let e = Frame::from_value(&axes, &one(fa.clone())).unwrap_err();
        assert_eq!(e.code, codes::run::FRAME, "{fa:?}");
    }
}

/// The frame function named `name` (any case, as lowering reads it).
fn call(axes: &FrameAxes, name: &str, args: &[Option<RtValue>]) -> Result<FrameValue, RunError> {
    let function = Function::named(name).expect("a predefined function");
    match frame_function(axes, function, args).expect("a frame function") {
        Ok(RtValue::Frame(f)) => Ok((*f).clone()),
        Ok(other) => panic!("{name}: not a frame: {other:?}"),
        Err(e) => Err(e),
    }
}

fn ax(name: &str) -> Option<RtValue> {
    Some(RtValue::axis(name))
}

fn num(v: f64) -> Option<RtValue> {
    Some(RtValue::Real(v))
}

#[test]
fn ctrans_crot_and_chaining() {
    let axes = mill();
    let ctrans = call(&axes, "CTRANS", &[ax("X"), num(10.0)]).unwrap();
    let crot = call(&axes, "CROT", &[ax("Z"), Some(RtValue::Int(45))]).unwrap();
    // CTRANS(X,10) : CROT(Z,45): the rotation acts inside the translation.
    let v = chain_values(&axes, &ctrans, &crot).unwrap();
    assert_eq!(v.component("X", "TR"), Some(10.0));
    assert_eq!(v.component("Y", "TR"), Some(0.0));
    assert_eq!(v.component("Z", "RT"), Some(45.0));
    // Inner (1, 0, 0) → Rz(45): (0.7071, 0.7071, 0) → + (10, 0, 0).
    let f = Frame::from_value(&axes, &v).unwrap();
    maps(&f, &[1.0, 0.0, 0.0, 0.0], &[10.0 + H, H, 0.0, 0.0]);
    // CROT(Z,45) : CTRANS(X,10): the translation is rotated,
    // T = Rz(45)·(10, 0, 0) = (7.0711, 7.0711, 0).
    let v = chain_values(&axes, &crot, &ctrans).unwrap();
    close(v.component("X", "TR").unwrap(), 10.0 * H, "TR X");
    close(v.component("Y", "TR").unwrap(), 10.0 * H, "TR Y");
    assert_eq!(v.component("Z", "RT"), Some(45.0));
    // CROT with several axes is RPY, like ROT.
    let v = call(&axes, "CROT", &[ax("X"), num(90.0), ax("Z"), num(90.0)]).unwrap();
    assert_eq!(
        Frame::from_value(&axes, &v).unwrap().rotation_matrix(),
        [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
    );
}

#[test]
fn the_other_frame_functions() {
    let axes = mill();
    // CTRANS(X,10): coarse 10, fine 0; CFINE(X,10): coarse 0, fine 10.
    let v = call(&axes, "ctrans", &[ax("X"), num(10.0), ax("C"), num(5.0)]).unwrap();
    assert_eq!(v.component("X", "TR"), Some(10.0));
    assert_eq!(v.component("X", "FI"), Some(0.0));
    assert_eq!(v.component("C", "TR"), Some(5.0));
    let v = call(&axes, "CFINE", &[ax("X"), num(10.0)]).unwrap();
    assert_eq!(v.component("X", "TR"), Some(0.0));
    assert_eq!(v.component("X", "FI"), Some(10.0));
    // The fine offset counts in the transformation: X 1 → 11.
    maps(
        &Frame::from_value(&axes, &v).unwrap(),
        &[1.0, 0.0, 0.0, 0.0],
        &[11.0, 0.0, 0.0, 0.0],
    );
    // CTRANS() and the other bare functions: the neutral frame.
    for name in ["CTRANS", "CFINE", "CROT", "CSCALE", "CMIRROR"] {
        assert_eq!(
            call(&axes, name, &[]).unwrap(),
            FrameValue::default(),
            "{name}"
        );
    }
    let v = call(&axes, "CSCALE", &[ax("X"), num(2.0), ax("Y"), num(3.0)]).unwrap();
    assert_eq!(
        (v.component("X", "SC"), v.component("Y", "SC")),
        (Some(2.0), Some(3.0))
    );
    let v = call(&axes, "CMIRROR", &[ax("X"), ax("Z")]).unwrap();
    assert_eq!(
        (
            v.component("X", "MI"),
            v.component("Y", "MI"),
            v.component("Z", "MI")
        ),
        (Some(1.0), Some(0.0), Some(1.0))
    );
    // INVFRAME(CTRANS(X,10)) = CTRANS(X,−10).
    let t = call(&axes, "CTRANS", &[ax("X"), num(10.0)]).unwrap();
    let inv = call(&axes, "INVFRAME", &[Some(RtValue::Frame(Arc::new(t)))]).unwrap();
    assert_eq!(inv.component("X", "TR"), Some(-10.0));
    // Chaining with a CFINE keeps coarse and fine apart:
    // CTRANS(X,10) : CFINE(X,1) → TR 10, FI 1.
    let fine = call(&axes, "CFINE", &[ax("X"), num(1.0)]).unwrap();
    let t = call(&axes, "CTRANS", &[ax("X"), num(10.0)]).unwrap();
    let v = chain_values(&axes, &t, &fine).unwrap();
    assert_eq!(
        (v.component("X", "TR"), v.component("X", "FI")),
        (Some(10.0), Some(1.0))
    );
}

#[test]
fn frame_function_errors() {
    let axes = mill();
    let code = |name: &str, args: &[Option<RtValue>]| call(&axes, name, args).unwrap_err().code;
    assert_eq!(code("CTRANS", &[ax("X")]), codes::run::ARGUMENT_COUNT);
    assert_eq!(code("CTRANS", &[ax("X"), None]), codes::run::ARGUMENT_COUNT);
    assert_eq!(
        code("CTRANS", &[None, num(1.0)]),
        codes::run::ARGUMENT_COUNT
    );
    assert_eq!(
        code("CTRANS", &[num(1.0), num(1.0)]),
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        code("CTRANS", &[ax("X"), Some(RtValue::string("a"))]),
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        code("CTRANS", &[ax("Q"), num(1.0)]),
        codes::run::UNKNOWN_AXIS
    );
    assert_eq!(code("CTRANS", &[ax("X"), num(f64::NAN)]), codes::run::FRAME);
    assert_eq!(code("CROT", &[ax("C"), num(10.0)]), codes::run::FRAME);
    assert_eq!(code("CSCALE", &[ax("X"), num(0.0)]), codes::run::FRAME);
    assert_eq!(code("CMIRROR", &[num(1.0)]), codes::run::TYPE_MISMATCH);
    assert_eq!(code("INVFRAME", &[]), codes::run::ARGUMENT_COUNT);
    assert_eq!(code("INVFRAME", &[num(1.0)]), codes::run::TYPE_MISMATCH);
    for name in ["CRPL", "CROTS", "MEAFRAME"] {
        assert!(
            frame_function(&axes, Function::named(name).unwrap(), &[]).is_none(),
            "{name}"
        );
    }
    assert!(frame_function(&axes, Function::Sin, &[num(1.0)]).is_none());
    // A value naming an axis the channel does not have.
    let q = FrameValue {
        axes: vec![FrameAxis {
            translation: 1.0,
            ..FrameAxis::neutral("Q")
        }],
    };
    assert_eq!(
        chain_values(&axes, &q, &FrameValue::default())
            .unwrap_err()
            .code,
        codes::run::UNKNOWN_AXIS
    );
    // 1e300 · 1e300 overflows in a chain.
    let big = call(&axes, "CSCALE", &[ax("X"), num(1e300)]).unwrap();
    assert_eq!(
        chain_values(&axes, &big, &big).unwrap_err().code,
        codes::run::FRAME
    );
}

// ---------------------------------------------------------------------
// Robustness

#[test]
fn slices_of_other_lengths_do_not_panic() {
    let axes = mill();
    let f = busy(&axes);
    let mut out = [0.0; 2];
    f.to_outer(&[1.0, 2.0, 3.0, 4.0], &mut out);
    f.to_inner(&[1.0, 2.0], &mut out);
    // Entries past the frame's axes are copied.
    let t = run(&axes, &[(FrameOp::Trans, &[(X, 1.0)], None)]);
    let mut out = [0.0; 6];
    t.to_outer(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0], &mut out);
    assert_eq!(out, [2.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    f.to_outer(&[], &mut []);
    // A frame over no axes.
    let none = FrameAxes::new(Vec::<(&str, bool)>::new());
    assert!(none.is_empty());
    let mut n = Frame::neutral(&none);
    let e = n
        .apply(&none, FrameOp::Rot, &[], Some(10.0), Plane::G17)
        .unwrap_err();
    assert_eq!(e.code, codes::run::FRAME);
}

#[test]
fn odd_inputs_never_panic() {
    let axes = mill();
    let odd = [
        0.0,
        -0.0,
        1.0,
        -1.0,
        1e-320,
        1e300,
        -1e300,
        f64::MAX,
        f64::MIN_POSITIVE,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        359.999_999_999,
        -720.0,
    ];
    let ops = FrameOp::ALL;
    let planes = [Plane::G17, Plane::G18, Plane::G19];
    let mut f = busy(&axes);
    for (k, &v) in odd.iter().enumerate() {
        for (j, &op) in ops.iter().enumerate() {
            let axis = (k + j) % 4;
            let rpl = (op.is_rotation() && k % 2 == 0).then_some(v);
            let values: &[(usize, f64)] = if rpl.is_some() { &[] } else { &[(axis, v)] };
            let before = f.clone();
            if f.apply(&axes, op, values, rpl, planes[k % 3]).is_err() {
                assert_eq!(f, before);
            }
            let mut out = [0.0; 4];
            f.to_outer(&[v, 1.0, -v, 2.0], &mut out);
            f.to_inner(&[v, 1.0, -v, 2.0], &mut out);
            let _ = f.to_value(&axes);
            let _ = f.inverse().chain(&f);
        }
    }
}
