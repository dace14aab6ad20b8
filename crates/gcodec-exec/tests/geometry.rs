//! Circle geometry with hand-checked numbers (SPEC §11.x "Circles and
//! helices"). Points are `[X, Y, Z]`; angles in the assertions are degrees.

use gcodec_exec::geometry::{
    Arc, ArcError, ArcForm, CircleTolerance, Direction, MAX_TURNS, Plane, Point3, arc_length,
    arc_points, resolve_arc,
};
use std::f64::consts::PI;

const TOL: CircleTolerance = CircleTolerance::DEFAULT;
const R3: f64 = 8.660_254_037_844_386; // √75 = 5·√3
const S2: f64 = 7.071_067_811_865_475; // 10/√2 = 5·√2

fn close(a: f64, b: f64, what: &str) {
    assert!((a - b).abs() < 1e-9, "{what}: got {a}, expected {b}");
}

fn close_pt(a: Point3, b: Point3, what: &str) {
    for k in 0..3 {
        close(a[k], b[k], what);
    }
}

fn centre(direction: Direction, c: Point3) -> ArcForm {
    ArcForm::Centre {
        direction,
        centre: c,
    }
}

fn radius(direction: Direction, r: f64) -> ArcForm {
    ArcForm::Radius {
        direction,
        radius: r,
    }
}

fn ok(plane: Plane, s: Point3, e: Point3, form: ArcForm) -> Arc {
    resolve_arc(plane, s, e, &form, 0.0, &TOL).expect("arc resolves")
}

fn err(plane: Plane, s: Point3, e: Point3, form: ArcForm, turns: f64) -> ArcError {
    resolve_arc(plane, s, e, &form, turns, &TOL).expect_err("arc is rejected")
}

/// Centre, radius, start angle, end angle, sweep (degrees).
fn check(arc: &Arc, c: Point3, r: f64, a0: f64, a1: f64, sweep: f64) {
    close_pt(arc.centre, c, "centre");
    close(arc.radius, r, "radius");
    close(arc.start_angle_degrees(), a0, "start angle");
    close(arc.end_angle_degrees(), a1, "end angle");
    close(arc.sweep_degrees(), sweep, "sweep");
    // The path ends where it should.
    close_pt(arc.point_at(0.0), arc.start, "point_at(0)");
    close_pt(arc.point_at(1.0), arc.end, "point_at(1)");
}

fn bbox(arc: &Arc, min: Point3, max: Point3) {
    let b = arc.bounding_box();
    close_pt(b.min, min, "bbox min");
    close_pt(b.max, max, "bbox max");
}

// --- G17 --------------------------------------------------------------------

#[test]
fn g17_quarter_ccw() {
    // G17 G3 X0 Y10 I-10 J0 from (10,0): centre (0,0), 0° → 90°, +90°.
    // Length 10·π/2 = 15.707963.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        centre(Direction::Ccw, [0.0, 0.0, 0.0]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 90.0, 90.0);
    close(a.length, 15.707_963_267_948_966, "length");
    assert_eq!(a.direction(), Direction::Ccw);
    // Midpoint at 45°: (7.071, 7.071).
    close_pt(a.point_at(0.5), [S2, S2, 0.0], "midpoint");
    bbox(&a, [0.0, 0.0, 0.0], [10.0, 10.0, 0.0]);
}

#[test]
fn g17_quarter_cw() {
    // G2 from (0,10) to (10,0) about (0,0): 90° → 0°, −90°.
    let a = ok(
        Plane::G17,
        [0.0, 10.0, 0.0],
        [10.0, 0.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 90.0, 0.0, -90.0);
    close_pt(a.point_at(0.5), [S2, S2, 0.0], "midpoint");
    assert_eq!(a.direction(), Direction::Cw);
}

#[test]
fn g17_three_quarters_cw_and_its_bounding_box() {
    // G2 from (10,0) to (0,10) about (0,0): clockwise 0° → −90° → −180° →
    // −270° (= 90°): sweep −270°, through (0,−10) and (−10,0).
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 90.0, -270.0);
    close(a.length, 10.0 * 1.5 * PI, "length 10·3π/2");
    bbox(&a, [-10.0, -10.0, 0.0], [10.0, 10.0, 0.0]);
}

#[test]
fn g17_half_circles_both_directions() {
    // (0,0) → (10,0) about (5,0). G2: 180° → 0° clockwise passes 90°,
    // the top (5,5). G3: passes 270°, the bottom (5,−5).
    let s = [0.0, 0.0, 0.0];
    let e = [10.0, 0.0, 0.0];
    let cw = ok(Plane::G17, s, e, centre(Direction::Cw, [5.0, 0.0, 0.0]));
    check(&cw, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, -180.0);
    close_pt(cw.point_at(0.5), [5.0, 5.0, 0.0], "G2 top");
    bbox(&cw, [0.0, 0.0, 0.0], [10.0, 5.0, 0.0]);
    let ccw = ok(Plane::G17, s, e, centre(Direction::Ccw, [5.0, 0.0, 0.0]));
    check(&ccw, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, 180.0);
    close_pt(ccw.point_at(0.5), [5.0, -5.0, 0.0], "G3 bottom");
    bbox(&ccw, [0.0, -5.0, 0.0], [10.0, 0.0, 0.0]);
    close(ccw.length, 5.0 * PI, "half circle length 5π");
}

// --- G18: Z/X, seen from +Y (Z to the right, X up) -------------------------

#[test]
fn g18_quarter_ccw_goes_from_z_to_x() {
    // G18 G3 from Z10 X0 to Z0 X10 about the origin. Angles are measured
    // in (Z, X): start atan2(X=0, Z=10) = 0°, end atan2(10, 0) = 90°,
    // sweep +90°; midpoint Z = X = 7.071.
    let a = ok(
        Plane::G18,
        [0.0, 0.0, 10.0],
        [10.0, 0.0, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 90.0, 90.0);
    close_pt(a.point_at(0.5), [S2, 0.0, S2], "midpoint");
    close_pt(a.normal, [0.0, 1.0, 0.0], "normal +Y");
    close_pt(a.u, [0.0, 0.0, 1.0], "u = Z");
    close_pt(a.v, [1.0, 0.0, 0.0], "v = X");
}

#[test]
fn g18_cw_between_the_same_points_goes_the_long_way() {
    // G2 from Z10 X0 to Z0 X10: clockwise 0° → −270°; at t = 0.5 the angle
    // is −135°: Z = 10·cos(−135°) = −7.071, X = 10·sin(−135°) = −7.071.
    let a = ok(
        Plane::G18,
        [0.0, 0.0, 10.0],
        [10.0, 0.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 90.0, -270.0);
    close_pt(a.point_at(0.5), [-S2, 0.0, -S2], "midpoint");
}

#[test]
fn g18_quarter_cw() {
    // G2 from X10 Z0 (angle 90°) to Z10 X0 (angle 0°): −90°, midpoint at 45°.
    let a = ok(
        Plane::G18,
        [10.0, 0.0, 0.0],
        [0.0, 0.0, 10.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 90.0, 0.0, -90.0);
    close_pt(a.point_at(0.5), [S2, 0.0, S2], "midpoint");
}

#[test]
fn g18_half_circle_in_both_directions() {
    // Z0 X0 → Z10 X0 about Z5 X0. In (Z, X) that is (0,0) → (10,0):
    // G2 passes 90° in (Z, X), i.e. X = +5; G3 passes X = −5.
    let s = [0.0, 0.0, 0.0];
    let e = [0.0, 0.0, 10.0];
    let cw = ok(Plane::G18, s, e, centre(Direction::Cw, [0.0, 0.0, 5.0]));
    check(&cw, [0.0, 0.0, 5.0], 5.0, 180.0, 0.0, -180.0);
    close_pt(cw.point_at(0.5), [5.0, 0.0, 5.0], "G2 passes X+5");
    bbox(&cw, [0.0, 0.0, 0.0], [5.0, 0.0, 10.0]);
    let ccw = ok(Plane::G18, s, e, centre(Direction::Ccw, [0.0, 0.0, 5.0]));
    check(&ccw, [0.0, 0.0, 5.0], 5.0, 180.0, 0.0, 180.0);
    close_pt(ccw.point_at(0.5), [-5.0, 0.0, 5.0], "G3 passes X−5");
}

// --- G19: Y/Z, infeed X -----------------------------------------------------

#[test]
fn g19_quarters_both_directions() {
    // G19 G3 from Y10 Z0 (angle 0° in (Y, Z)) to Y0 Z10 (90°): +90°.
    let a = ok(
        Plane::G19,
        [0.0, 10.0, 0.0],
        [0.0, 0.0, 10.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 90.0, 90.0);
    close_pt(a.point_at(0.5), [0.0, S2, S2], "midpoint");
    close_pt(a.normal, [1.0, 0.0, 0.0], "normal +X");
    // G2 back: 90° → 0°, −90°.
    let b = ok(
        Plane::G19,
        [0.0, 0.0, 10.0],
        [0.0, 10.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&b, [0.0; 3], 10.0, 90.0, 0.0, -90.0);
}

#[test]
fn g19_half_circle_ccw_passes_positive_z() {
    // Y10 → Y−10 about the origin, G3: 0° → 180° via 90° = Z+10.
    let a = ok(
        Plane::G19,
        [0.0, 10.0, 0.0],
        [0.0, -10.0, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 180.0, 180.0);
    bbox(&a, [0.0, -10.0, 0.0], [0.0, 10.0, 10.0]);
    // G2 passes Z−10.
    let b = ok(
        Plane::G19,
        [0.0, 10.0, 0.0],
        [0.0, -10.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    close_pt(b.point_at(0.5), [0.0, 0.0, -10.0], "G2 passes Z−10");
}

#[test]
fn the_centre_infeed_coordinate_is_ignored() {
    // K in G17 does not move the centre off the start's level.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 3.0],
        [0.0, 10.0, 3.0],
        centre(Direction::Ccw, [0.0, 0.0, 99.0]),
    );
    close_pt(a.centre, [0.0, 0.0, 3.0], "centre at Z3");
    close(a.rise, 0.0, "no rise");
}

// --- CR= --------------------------------------------------------------------

#[test]
fn cr_equal_to_half_the_chord_is_a_half_circle() {
    // (0,0) → (10,0), CR=±5: half chord 5 = r, so h = √(25−25) = 0 and the
    // centre is (5,0) whatever the sign; ±180°.
    let s = [0.0, 0.0, 0.0];
    let e = [10.0, 0.0, 0.0];
    for r in [5.0, -5.0] {
        let cw = ok(Plane::G17, s, e, radius(Direction::Cw, r));
        check(&cw, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, -180.0);
        let ccw = ok(Plane::G17, s, e, radius(Direction::Ccw, r));
        check(&ccw, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, 180.0);
    }
}

#[test]
fn cr_ten_short_and_long_arcs() {
    // (0,0) → (10,0), |CR| = 10: h = √(100 − 25) = 8.660254.
    let s = [0.0, 0.0, 0.0];
    let e = [10.0, 0.0, 0.0];

    // G2 CR=10: short clockwise arc, centre right of the chord (−Y):
    // (5, −8.66). Start angle atan2(8.66, −5) = 120°, end atan2(8.66, 5)
    // = 60°, sweep −60°, length 10·π/3 = 10.471976.
    let a = ok(Plane::G17, s, e, radius(Direction::Cw, 10.0));
    check(&a, [5.0, -R3, 0.0], 10.0, 120.0, 60.0, -60.0);
    close(a.length, 10.0 * PI / 3.0, "length");

    // G2 CR=−10: long arc, centre (5, 8.66); 240° → 300° clockwise is
    // −300°, length 10·5π/3 = 52.359878.
    let b = ok(Plane::G17, s, e, radius(Direction::Cw, -10.0));
    check(&b, [5.0, R3, 0.0], 10.0, 240.0, 300.0, -300.0);
    close(b.length, 50.0 * PI / 3.0, "length");
    // Clockwise from 240° it passes 180°, 90°, 0°: x from 5−10 = −5 to
    // 5+10 = 15, y up to 8.66+10 = 18.66; the lowest points are the ends.
    bbox(&b, [-5.0, 0.0, 0.0], [15.0, R3 + 10.0, 0.0]);

    // G3 CR=10: centre left (5, 8.66), 240° → 300°, +60°.
    let c = ok(Plane::G17, s, e, radius(Direction::Ccw, 10.0));
    check(&c, [5.0, R3, 0.0], 10.0, 240.0, 300.0, 60.0);

    // G3 CR=−10: centre (5, −8.66), 120° → 60° counter-clockwise, +300°.
    let d = ok(Plane::G17, s, e, radius(Direction::Ccw, -10.0));
    check(&d, [5.0, -R3, 0.0], 10.0, 120.0, 60.0, 300.0);
}

#[test]
fn cr_in_g18_uses_z_x() {
    // G18 from Z0 X0 to Z10 X0, G2 CR=10. In (Z, X) this is the G17 case
    // above: centre (Z5, X−8.66), sweep −60°.
    let a = ok(
        Plane::G18,
        [0.0, 0.0, 0.0],
        [0.0, 0.0, 10.0],
        radius(Direction::Cw, 10.0),
    );
    check(&a, [-R3, 0.0, 5.0], 10.0, 120.0, 60.0, -60.0);
}

#[test]
fn cr_too_small() {
    // Half chord 5 > 4 by 1 ≫ 0.01: rejected.
    let e = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        radius(Direction::Cw, 4.0),
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_radius_too_small");
    assert_eq!(
        e,
        ArcError::RadiusTooSmall {
            radius: 4.0,
            half_chord: 5.0
        }
    );
    // 5 − 4.999 = 0.001 ≤ max(0.01, 0.001·4.999): a half circle of r 5.
    let a = ok(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        radius(Direction::Cw, 4.999),
    );
    check(&a, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, -180.0);
}

#[test]
fn cr_needs_a_chord_and_a_radius() {
    let e = err(
        Plane::G17,
        [1.0, 2.0, 0.0],
        [1.0, 2.0, 5.0],
        radius(Direction::Cw, 5.0),
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_zero_chord");
    let e = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        radius(Direction::Cw, 0.0),
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_zero_radius");
}

// --- AR= --------------------------------------------------------------------

#[test]
fn ar_with_end_point() {
    let s = [0.0, 0.0, 0.0];
    let e = [10.0, 0.0, 0.0];
    // G3 AR=90: r = 5 / sin 45° = 7.071, h = 5·cos45°/sin45° = 5 to the
    // left: centre (5,5); 225° → 315°, +90°.
    let a = ok(
        Plane::G17,
        s,
        e,
        ArcForm::AngleToEnd {
            direction: Direction::Ccw,
            angle: 90.0,
        },
    );
    check(&a, [5.0, 5.0, 0.0], S2, 225.0, 315.0, 90.0);
    // G2 AR=90: centre (5,−5); 135° → 45°, −90°.
    let b = ok(
        Plane::G17,
        s,
        e,
        ArcForm::AngleToEnd {
            direction: Direction::Cw,
            angle: 90.0,
        },
    );
    check(&b, [5.0, -5.0, 0.0], S2, 135.0, 45.0, -90.0);
    // G3 AR=270: h = 5·cos135°/sin135° = −5: centre (5,−5); 135° → 45°
    // counter-clockwise, +270°.
    let c = ok(
        Plane::G17,
        s,
        e,
        ArcForm::AngleToEnd {
            direction: Direction::Ccw,
            angle: 270.0,
        },
    );
    check(&c, [5.0, -5.0, 0.0], S2, 135.0, 45.0, 270.0);
    // AR=180: r = 5/sin 90° = 5, centre (5,0).
    let d = ok(
        Plane::G17,
        s,
        e,
        ArcForm::AngleToEnd {
            direction: Direction::Cw,
            angle: 180.0,
        },
    );
    check(&d, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, -180.0);
}

#[test]
fn ar_with_centre_computes_the_end_point() {
    // G3 I-10 J0 AR=90 from (10,0,2) with Z2: centre (0,0), end at 90°:
    // (0,10,2). G2: end at −90°: (0,−10,2). The end's plane coordinates
    // passed in are ignored.
    let s = [10.0, 0.0, 2.0];
    let form = |direction| ArcForm::AngleFromCentre {
        direction,
        centre: [0.0, 0.0, 0.0],
        angle: 90.0,
    };
    let a = ok(Plane::G17, s, [10.0, 0.0, 2.0], form(Direction::Ccw));
    close_pt(a.end, [0.0, 10.0, 2.0], "G3 end");
    check(&a, [0.0, 0.0, 2.0], 10.0, 0.0, 90.0, 90.0);
    let b = ok(Plane::G17, s, [10.0, 0.0, 2.0], form(Direction::Cw));
    close_pt(b.end, [0.0, -10.0, 2.0], "G2 end");
    check(&b, [0.0, 0.0, 2.0], 10.0, 0.0, 270.0, -90.0);
}

#[test]
fn ar_out_of_range() {
    for angle in [0.0, -10.0, 360.0, 400.0] {
        let e = err(
            Plane::G17,
            [0.0; 3],
            [10.0, 0.0, 0.0],
            ArcForm::AngleToEnd {
                direction: Direction::Cw,
                angle,
            },
            0.0,
        );
        assert_eq!(e.code(), "gcodec::run::circle_opening_angle", "AR={angle}");
    }
    let e = err(
        Plane::G17,
        [3.0, 4.0, 0.0],
        [3.0, 4.0, 0.0],
        ArcForm::AngleToEnd {
            direction: Direction::Cw,
            angle: 90.0,
        },
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_zero_chord");
}

// --- CIP --------------------------------------------------------------------

#[test]
fn cip_through_5_5_is_clockwise() {
    // (0,0) → (10,0) through (5,5): centre (5,0), r 5. a = P−S = (5,5),
    // b = E−S = (10,0), (a×b)_z = 5·0 − 5·10 = −50 < 0: clockwise (G2),
    // 180° → 0°, −180°.
    let a = ok(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        ArcForm::Intermediate {
            point: [5.0, 5.0, 0.0],
        },
    );
    check(&a, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, -180.0);
    close_pt(
        a.point_at(0.5),
        [5.0, 5.0, 0.0],
        "passes the intermediate point",
    );
    // Through (5,−5): counter-clockwise.
    let b = ok(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        ArcForm::Intermediate {
            point: [5.0, -5.0, 0.0],
        },
    );
    check(&b, [5.0, 0.0, 0.0], 5.0, 180.0, 0.0, 180.0);
}

#[test]
fn cip_three_quarters() {
    // (10,0) → (0,−10) through (−10,0): a = (−20,0), b = (−10,−10),
    // (a×b)_z = (−20)(−10) − 0 = 200 > 0: counter-clockwise, 0° → 270°.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, -10.0, 0.0],
        ArcForm::Intermediate {
            point: [-10.0, 0.0, 0.0],
        },
    );
    check(&a, [0.0; 3], 10.0, 0.0, 270.0, 270.0);
    close(a.length, 15.0 * PI, "length 10·3π/2");
}

#[test]
fn cip_in_g18_and_g19() {
    // G18: Z0 X0 → Z10 X0 through Z5 X5. In (Z, X): (0,0) → (10,0)
    // through (5,5), clockwise as in G17: centre Z5 X0, −180°.
    let a = ok(
        Plane::G18,
        [0.0; 3],
        [0.0, 0.0, 10.0],
        ArcForm::Intermediate {
            point: [5.0, 0.0, 5.0],
        },
    );
    check(&a, [0.0, 0.0, 5.0], 5.0, 180.0, 0.0, -180.0);
    // G19: Y0 Z0 → Y10 Z0 through Y5 Z−5: counter-clockwise, +180°.
    let b = ok(
        Plane::G19,
        [0.0; 3],
        [0.0, 10.0, 0.0],
        ArcForm::Intermediate {
            point: [0.0, 5.0, -5.0],
        },
    );
    check(&b, [0.0, 5.0, 0.0], 5.0, 180.0, 0.0, 180.0);
}

#[test]
fn cip_oblique_circle_in_space() {
    // G17 CIP from (10,0,0) through (0,0,10) to (−10,0,0): a circle in the
    // X/Z plane, centre 0, r 10. a = (−10,0,10), b = (−20,0,0),
    // a×b = (0, −200, 0): travel about −Y. No Z component, no X component,
    // so the normal is turned to +Y; u = X, v = Y×X = −Z; travel is
    // clockwise about +Y: −180°, and the midpoint (angle −90°) is
    // −10·v = (0,0,10).
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [-10.0, 0.0, 0.0],
        ArcForm::Intermediate {
            point: [0.0, 0.0, 10.0],
        },
    );
    close_pt(a.normal, [0.0, 1.0, 0.0], "normal");
    close_pt(a.u, [1.0, 0.0, 0.0], "u");
    close_pt(a.v, [0.0, 0.0, -1.0], "v");
    check(&a, [0.0; 3], 10.0, 0.0, 180.0, -180.0);
    close_pt(a.point_at(0.5), [0.0, 0.0, 10.0], "midpoint");
    close(a.rise, 0.0, "no rise");
    close(a.length, 10.0 * PI, "length");
    bbox(&a, [-10.0, 0.0, 0.0], [10.0, 0.0, 10.0]);
}

#[test]
fn cip_errors() {
    let cip = |p| ArcForm::Intermediate { point: p };
    // Collinear.
    let e = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        cip([5.0, 0.0, 0.0]),
        0.0,
    );
    assert_eq!(e, ArcError::CollinearPoints);
    assert_eq!(e.code(), "gcodec::run::circle_collinear");
    // Also beyond the end point, and an intermediate point on the start.
    let e = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        cip([20.0, 0.0, 0.0]),
        0.0,
    );
    assert_eq!(e, ArcError::CollinearPoints);
    let e = err(Plane::G17, [0.0; 3], [10.0, 0.0, 0.0], cip([0.0; 3]), 0.0);
    assert_eq!(e, ArcError::CollinearPoints);
    // End = start: no full circle through CIP.
    let e = err(Plane::G17, [0.0; 3], [0.0; 3], cip([5.0, 5.0, 0.0]), 0.0);
    assert_eq!(e.code(), "gcodec::run::circle_zero_chord");
    // TURN= with CIP.
    let e = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        cip([5.0, 5.0, 0.0]),
        1.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_turns_cip");
}

// --- CT ---------------------------------------------------------------------

#[test]
fn ct_turns_left_and_right() {
    // Previous motion along +X ending at (0,0). CT X10 Y10: d = (10,10),
    // left normal n = (0,1), n·d = 10, ρ = |d|²/(2 n·d) = 200/20 = 10 > 0:
    // centre (0,10), counter-clockwise, 270° → 0°, +90°.
    let a = ok(
        Plane::G17,
        [0.0; 3],
        [10.0, 10.0, 0.0],
        ArcForm::Tangent {
            tangent: [1.0, 0.0, 0.0],
        },
    );
    check(&a, [0.0, 10.0, 0.0], 10.0, 270.0, 0.0, 90.0);
    // CT X10 Y−10: n·d = −10, ρ = −10: centre (0,−10), clockwise,
    // 90° → 0°, −90°. The tangent's length and infeed part do not matter.
    let b = ok(
        Plane::G17,
        [0.0; 3],
        [10.0, -10.0, 0.0],
        ArcForm::Tangent {
            tangent: [5.0, 0.0, 3.0],
        },
    );
    check(&b, [0.0, -10.0, 0.0], 10.0, 90.0, 0.0, -90.0);
    // CT X0 Y20: d = (0,20), ρ = 400/40 = 10: centre (0,10), a half circle.
    let c = ok(
        Plane::G17,
        [0.0; 3],
        [0.0, 20.0, 0.0],
        ArcForm::Tangent {
            tangent: [1.0, 0.0, 0.0],
        },
    );
    check(&c, [0.0, 10.0, 0.0], 10.0, 270.0, 90.0, 180.0);
    // The arc leaves tangentially: just after the start it moves along +X.
    let p = c.point_at(1e-6);
    assert!(p[0] > 0.0 && p[1].abs() < 1e-6 * p[0].max(1e-12) * 1e3);
}

#[test]
fn ct_errors() {
    // End on the tangent's line, ahead or behind.
    for e in [[10.0, 0.0, 0.0], [-10.0, 0.0, 0.0]] {
        let x = err(
            Plane::G17,
            [0.0; 3],
            e,
            ArcForm::Tangent {
                tangent: [1.0, 0.0, 0.0],
            },
            0.0,
        );
        assert_eq!(x.code(), "gcodec::run::circle_tangent_straight");
    }
    // A tangent along the infeed axis (previous motion in Z only).
    let x = err(
        Plane::G17,
        [0.0; 3],
        [10.0, 10.0, 0.0],
        ArcForm::Tangent {
            tangent: [0.0, 0.0, -1.0],
        },
        0.0,
    );
    assert_eq!(x.code(), "gcodec::run::circle_tangent_missing");
}

// --- Helices, full circles, TURN= -----------------------------------------

#[test]
fn full_circle_by_centre() {
    // G2 from (10,0) back to (10,0) about (0,0): −360°, length 20π.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [10.0, 0.0, 0.0],
        centre(Direction::Cw, [0.0; 3]),
    );
    check(&a, [0.0; 3], 10.0, 0.0, 0.0, -360.0);
    close(a.length, 20.0 * PI, "length");
    bbox(&a, [-10.0, -10.0, 0.0], [10.0, 10.0, 0.0]);
}

#[test]
fn helix_full_circle_with_turn_2() {
    // G3 X10 Y0 Z−6 I−10 J0 TURN=2 from (10,0,0): a full circle plus two
    // turns = 3 turns, 1080°; rise −6, lead −6/3 = −2 per turn; length
    // √((10·6π)² + 6²) = √(35530.5758 + 36) = 188.591.
    let a = resolve_arc(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [10.0, 0.0, -6.0],
        &centre(Direction::Ccw, [0.0; 3]),
        2.0,
        &TOL,
    )
    .unwrap();
    close(a.sweep_degrees(), 1080.0, "sweep");
    close(a.rise, -6.0, "rise");
    close(a.lead, -2.0, "lead");
    close(
        a.length,
        ((60.0 * PI).powi(2) + 36.0).sqrt(),
        "helix length",
    );
    assert!((a.length - 188.591).abs() < 1e-3);
    close_pt(a.point_at(1.0), [10.0, 0.0, -6.0], "end");
    // After one turn (t = 1/3): back at (10,0), two millimetres down.
    close_pt(a.point_at(1.0 / 3.0), [10.0, 0.0, -2.0], "one turn");
    bbox(&a, [-10.0, -10.0, -6.0], [10.0, 10.0, 0.0]);
}

#[test]
fn helix_quarter_cw_with_turn_2() {
    // G2 X0 Y10 Z−5 I−10 J0 TURN=2 from (10,0,0): clockwise 0° → −270°
    // plus 720° = −990°; 2.75 turns, lead −5/2.75 = −1.818182.
    // At t = 0.5: angle −495° ≡ −135° → (−7.071, −7.071), Z −2.5.
    let a = resolve_arc(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.0, -5.0],
        &centre(Direction::Cw, [0.0; 3]),
        2.0,
        &TOL,
    )
    .unwrap();
    close(a.sweep_degrees(), -990.0, "sweep");
    close(a.lead, -5.0 / 2.75, "lead");
    close_pt(a.point_at(0.5), [-S2, -S2, -2.5], "half way");
    close(a.end_angle_degrees(), 90.0, "end angle");
}

#[test]
fn helix_in_g18_rises_along_y() {
    // G18 G3 Z0 X10 Y4 K−10 I0 from Z10 X0 Y0: +90° about +Y, rise 4
    // along Y, lead 4/(1/4) = 16.
    let a = ok(
        Plane::G18,
        [0.0, 0.0, 10.0],
        [10.0, 4.0, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    close(a.rise, 4.0, "rise");
    close(a.lead, 16.0, "lead");
    close_pt(a.point_at(0.5), [S2, 2.0, S2], "half way");
}

#[test]
fn cr_with_turns() {
    // (0,0) → (10,0) G2 CR=5 TURN=1: −180° − 360° = −540°.
    let a = resolve_arc(
        Plane::G17,
        [0.0; 3],
        [10.0, 0.0, 0.0],
        &radius(Direction::Cw, 5.0),
        1.0,
        &TOL,
    )
    .unwrap();
    close(a.sweep_degrees(), -540.0, "sweep");
    close(a.length, 15.0 * PI, "length 5·3π");
}

#[test]
fn bad_turns() {
    for turns in [-1.0, 0.5, MAX_TURNS + 1.0] {
        let e = err(
            Plane::G17,
            [10.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            centre(Direction::Cw, [0.0; 3]),
            turns,
        );
        assert_eq!(e, ArcError::Turns { turns });
        assert_eq!(e.code(), "gcodec::run::circle_turns");
    }
}

// --- End point off the circle ------------------------------------------------

#[test]
fn end_point_off_the_circle() {
    // Start radius 10, end radius 10.5: 0.5 > max(0.01, 0.001·10) = 0.01.
    let e = err(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.5, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_end_point");
    match e {
        ArcError::EndPointNotOnCircle {
            start_radius,
            end_radius,
            allowed,
        } => {
            close(start_radius, 10.0, "start radius");
            close(end_radius, 10.5, "end radius");
            close(allowed, 0.01, "allowed");
        }
        other => panic!("unexpected {other:?}"),
    }
    assert!(e.to_string().contains("end point not on the circle"));
    // 0.005 off is within 0.01 and reported as the deviation.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.005, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    close(a.end_deviation, 0.005, "deviation");
    close(a.sweep_degrees(), 90.0, "sweep");
}

#[test]
fn the_tolerance_grows_with_the_radius() {
    // r = 100: allowed max(0.01, 0.001·100) = 0.1. 0.05 off passes, 0.2
    // fails; a caller's tighter tolerance (0.01, 0) rejects the 0.05.
    let s = [100.0, 0.0, 0.0];
    let c = centre(Direction::Ccw, [0.0; 3]);
    assert!(resolve_arc(Plane::G17, s, [0.0, 100.05, 0.0], &c, 0.0, &TOL).is_ok());
    let e = resolve_arc(Plane::G17, s, [0.0, 100.2, 0.0], &c, 0.0, &TOL).unwrap_err();
    assert_eq!(e.code(), "gcodec::run::circle_end_point");
    let tight = CircleTolerance {
        absolute: 0.01,
        relative: 0.0,
    };
    let e = resolve_arc(Plane::G17, s, [0.0, 100.05, 0.0], &c, 0.0, &tight).unwrap_err();
    assert_eq!(e.code(), "gcodec::run::circle_end_point");
}

#[test]
fn centre_on_the_start_point() {
    let e = err(
        Plane::G17,
        [5.0, 5.0, 0.0],
        [5.0, 5.0, 0.0],
        centre(Direction::Cw, [5.0, 5.0, 0.0]),
        0.0,
    );
    assert_eq!(e.code(), "gcodec::run::circle_zero_radius");
}

// --- Inputs ------------------------------------------------------------------

#[test]
fn non_finite_inputs_and_bad_tolerance_are_errors() {
    let s = [10.0, 0.0, 0.0];
    let e = [0.0, 10.0, 0.0];
    let c = centre(Direction::Ccw, [0.0; 3]);
    let x = resolve_arc(Plane::G17, [f64::NAN, 0.0, 0.0], e, &c, 0.0, &TOL).unwrap_err();
    assert_eq!(
        x,
        ArcError::NonFinite {
            what: "start point"
        }
    );
    assert_eq!(x.code(), "gcodec::run::circle_non_finite");
    let x = resolve_arc(
        Plane::G17,
        s,
        e,
        &radius(Direction::Cw, f64::INFINITY),
        0.0,
        &TOL,
    )
    .unwrap_err();
    assert_eq!(x, ArcError::NonFinite { what: "radius" });
    let x = resolve_arc(
        Plane::G17,
        s,
        e,
        &centre(Direction::Cw, [f64::NEG_INFINITY, 0.0, 0.0]),
        0.0,
        &TOL,
    )
    .unwrap_err();
    assert_eq!(x, ArcError::NonFinite { what: "centre" });
    let x = resolve_arc(Plane::G17, s, e, &c, f64::NAN, &TOL).unwrap_err();
    assert_eq!(x, ArcError::NonFinite { what: "TURN" });
    let bad = CircleTolerance {
        absolute: -1.0,
        relative: 0.0,
    };
    let x = resolve_arc(Plane::G17, s, e, &c, 0.0, &bad).unwrap_err();
    assert_eq!(x.code(), "gcodec::run::circle_tolerance");
}

#[test]
fn huge_but_finite_inputs_give_finite_results_or_errors() {
    let big = 1e300;
    // CR=1e300 over a chord of 1.4e300: the centre's distance from the
    // chord overflows; an error, not NaN.
    let x = resolve_arc(
        Plane::G17,
        [big, 0.0, 0.0],
        [0.0, big, 0.0],
        &radius(Direction::Cw, big),
        0.0,
        &TOL,
    )
    .unwrap_err();
    assert_eq!(x.code(), "gcodec::run::circle_out_of_range");
    let forms = [
        centre(Direction::Cw, [0.0; 3]),
        radius(Direction::Cw, big),
        radius(Direction::Cw, -1e-300),
        ArcForm::AngleToEnd {
            direction: Direction::Ccw,
            angle: 1e-12,
        },
        ArcForm::Intermediate {
            point: [big, -big, 1.0],
        },
        ArcForm::Tangent {
            tangent: [1e-300, 1e-300, 0.0],
        },
    ];
    for form in forms {
        if let Ok(a) = resolve_arc(
            Plane::G17,
            [big, 0.0, 0.0],
            [0.0, big, 0.0],
            &form,
            0.0,
            &TOL,
        ) {
            assert!(a.is_finite(), "{form:?} gave a non-finite arc: {a:?}");
            let p = a.point_at(0.5);
            assert!(p.iter().all(|x| !x.is_nan()), "{form:?}: {p:?}");
        }
    }
}

#[test]
fn error_codes_are_distinct() {
    let all = [
        ArcError::NonFinite { what: "x" },
        ArcError::InvalidTolerance,
        ArcError::EndPointNotOnCircle {
            start_radius: 1.0,
            end_radius: 2.0,
            allowed: 0.01,
        },
        ArcError::ZeroRadius,
        ArcError::RadiusTooSmall {
            radius: 1.0,
            half_chord: 2.0,
        },
        ArcError::ZeroChord,
        ArcError::OpeningAngle { angle: 0.0 },
        ArcError::CollinearPoints,
        ArcError::TangentMissing,
        ArcError::TangentStraight,
        ArcError::Turns { turns: -1.0 },
        ArcError::TurnsWithIntermediate,
        ArcError::OutOfRange,
    ];
    let mut codes: Vec<_> = all.iter().map(|e| e.code().name()).collect();
    assert!(codes.iter().all(|c| c.starts_with("gcodec::run::circle_")));
    assert!(all.iter().all(|e| !e.to_string().is_empty()));
    codes.sort();
    codes.dedup();
    assert_eq!(codes.len(), all.len());
}

// --- Polylines and lengths -----------------------------------------------------

#[test]
fn arc_length_helper() {
    // r 10, a quarter turn, no rise: 15.707963; with rise 3 on a full
    // turn: √((20π)² + 9) = √(3947.8418 + 9) = 62.90342.
    close(arc_length(10.0, PI / 2.0, 0.0), 5.0 * PI, "quarter");
    close(arc_length(10.0, -PI / 2.0, 0.0), 5.0 * PI, "sign ignored");
    close(
        arc_length(10.0, 2.0 * PI, 3.0),
        ((20.0 * PI).powi(2) + 9.0).sqrt(),
        "helix",
    );
    assert!((arc_length(10.0, 2.0 * PI, 3.0) - 62.90342).abs() < 1e-4);
}

#[test]
fn arc_points_respect_the_chord_error() {
    // Quarter circle r 10, chord error 0.01: a chord of angle α deviates
    // 10·(1 − cos(α/2)); α = 2·acos(0.999) = 0.089450 rad; (π/2)/α =
    // 17.56 → 18 segments, 19 points.
    let a = ok(
        Plane::G17,
        [10.0, 0.0, 0.0],
        [0.0, 10.0, 0.0],
        centre(Direction::Ccw, [0.0; 3]),
    );
    let pts = arc_points(&a, 0.01);
    assert_eq!(pts.len(), 19);
    close_pt(pts[0], a.start, "first");
    close_pt(pts[18], a.end, "last");
    for w in pts.windows(2) {
        let mid = [(w[0][0] + w[1][0]) / 2.0, (w[0][1] + w[1][1]) / 2.0];
        let sagitta = 10.0 - mid[0].hypot(mid[1]);
        assert!(sagitta <= 0.01 + 1e-12, "sagitta {sagitta}");
        close(w[0][0].hypot(w[0][1]), 10.0, "on the circle");
    }
    // Without a usable chord error: one segment per quarter.
    assert_eq!(arc_points(&a, 0.0).len(), 2);
    assert_eq!(arc_points(&a, f64::NAN).len(), 2);
    // A chord error above the radius: still one per quarter.
    assert_eq!(arc_points(&a, 50.0).len(), 2);
}
