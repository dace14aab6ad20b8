//! Circles as the picture needs them: the sweep of an arc from its end
//! points, points along it, and its extremes in its own plane.

use std::f64::consts::{FRAC_PI_2, TAU};

use gcodec_exec::event::Plane;

/// A point of the three geometry axes X, Y, Z, in mm.
pub type Point3 = [f64; 3];

/// How far a chord of a polyline may deviate from the circle it stands
/// for, in mm.
pub const CHORD_TOLERANCE: f64 = 0.01;

/// At most this many chords for one arc or helix: a guard against a
/// huge radius, not a limit a machining path meets.
const MAX_CHORDS: usize = 65_536;

/// An arc or helix of a working plane, resolved for drawing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ArcPath {
    pub plane: Plane,
    /// The start point.
    pub from: Point3,
    /// The centre's abscissa and ordinate in the plane.
    pub centre: (f64, f64),
    pub radius: f64,
    /// The start angle in radians, from the abscissa towards the ordinate.
    pub start_angle: f64,
    /// Signed: positive counter-clockwise (`G3`), full turns included.
    pub sweep: f64,
    /// The travel along the infeed axis from start to end (a helix).
    pub rise: f64,
}

impl ArcPath {
    /// The arc from `from` to `to` about `centre` (the plane's abscissa
    /// and ordinate) in the direction given, with `turns` full turns more.
    /// An end point equal to the start point is a full circle.
    pub fn new(
        plane: Plane,
        from: Point3,
        to: Point3,
        centre: (f64, f64),
        clockwise: bool,
        turns: u32,
    ) -> Self {
        let (h, v, infeed) = plane.axes();
        let start_angle = (from[v] - centre.1).atan2(from[h] - centre.0);
        let end_angle = (to[v] - centre.1).atan2(to[h] - centre.0);
        let closed = from[h] == to[h] && from[v] == to[v];
        let turning = if closed {
            TAU
        } else if clockwise {
            (start_angle - end_angle).rem_euclid(TAU)
        } else {
            (end_angle - start_angle).rem_euclid(TAU)
        };
        let turning = turning + f64::from(turns) * TAU;
        Self {
            plane,
            from,
            centre,
            radius: (from[h] - centre.0).hypot(from[v] - centre.1),
            start_angle,
            sweep: if clockwise { -turning } else { turning },
            rise: to[infeed] - from[infeed],
        }
    }

    /// The point at `t` (0 at the start, 1 at the end).
    pub fn point_at(&self, t: f64) -> Point3 {
        let (h, v, infeed) = self.plane.axes();
        let angle = self.start_angle + self.sweep * t;
        let mut p = self.from;
        p[h] = self.centre.0 + self.radius * angle.cos();
        p[v] = self.centre.1 + self.radius * angle.sin();
        p[infeed] = self.from[infeed] + self.rise * t;
        p
    }

    /// The length of the path: √((r·sweep)² + rise²).
    pub fn length(&self) -> f64 {
        (self.radius * self.sweep).hypot(self.rise)
    }

    /// Whether it stays in one plane parallel to its working plane and
    /// turns less than a full circle more than once (a helix does not).
    pub fn is_flat(&self) -> bool {
        self.rise == 0.0 && self.sweep.abs() <= TAU
    }

    /// How many chords keep within [`CHORD_TOLERANCE`] of the circle: at
    /// least one per quarter turn.
    pub fn chords(&self) -> usize {
        let step = if self.radius > CHORD_TOLERANCE {
            (2.0 * (1.0 - CHORD_TOLERANCE / self.radius).acos()).min(FRAC_PI_2)
        } else {
            FRAC_PI_2
        };
        let chords = (self.sweep.abs() / step).ceil();
        if chords.is_finite() {
            (chords as usize).clamp(1, MAX_CHORDS)
        } else {
            1
        }
    }

    /// The points of the polyline, the start and end included.
    pub fn polyline(&self) -> impl Iterator<Item = Point3> + '_ {
        let chords = self.chords();
        (0..=chords).map(move |i| self.point_at(i as f64 / chords as f64))
    }

    /// The points whose hull bounds the arc: its end points and the
    /// quarter points of the circle (0°, 90°, 180°, 270°) that lie on its
    /// sweep. Exact for a flat arc; a helix's rise is spread between.
    pub fn extremes(&self) -> impl Iterator<Item = Point3> + '_ {
        let (low, high) = if self.sweep >= 0.0 {
            (self.start_angle, self.start_angle + self.sweep)
        } else {
            (self.start_angle + self.sweep, self.start_angle)
        };
        let first = (low / FRAC_PI_2).ceil() as i64;
        // A sweep beyond one turn has every quarter point; a degenerate
        // one (no sweep) none.
        let last = if self.sweep == 0.0 {
            first - 1
        } else {
            ((high / FRAC_PI_2).floor() as i64).min(first + 3)
        };
        let quarters = (first..=last).map(move |k| {
            let angle = k as f64 * FRAC_PI_2;
            self.point_at(((angle - self.start_angle) / self.sweep).clamp(0.0, 1.0))
        });
        [self.point_at(0.0), self.point_at(1.0)]
            .into_iter()
            .chain(quarters)
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use super::*;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn the_sweep_follows_the_direction_and_the_turns() {
        let from = [0.0, 0.0, 0.0];
        let to = [20.0, 0.0, 0.0];
        let cw = ArcPath::new(Plane::G17, from, to, (10.0, 0.0), true, 0);
        assert!(close(cw.sweep, -PI), "{cw:?}");
        // Clockwise from 180° passes 90°: over the top.
        assert!(close(cw.point_at(0.5)[1], 10.0));
        let ccw = ArcPath::new(Plane::G17, from, to, (10.0, 0.0), false, 2);
        assert!(close(ccw.sweep, 5.0 * PI));
        let full = ArcPath::new(Plane::G17, from, from, (10.0, 0.0), true, 0);
        assert!(close(full.sweep, -TAU));
        assert!(close(full.length(), TAU * 10.0));
    }

    #[test]
    fn a_helix_rises_along_the_infeed_and_is_not_flat() {
        let helix = ArcPath::new(
            Plane::G18,
            [0.0, 0.0, 10.0],
            [0.0, -4.0, 10.0],
            (0.0, 0.0),
            false,
            1,
        );
        // G18: Z is the abscissa, X the ordinate, Y the infeed.
        assert!(close(helix.point_at(0.5)[1], -2.0));
        assert!(!helix.is_flat());
        assert!(close(helix.length(), (10.0 * 4.0 * PI).hypot(4.0)));
    }

    #[test]
    fn the_extremes_bound_a_three_quarter_arc() {
        // Counter-clockwise from 180° to 90° about the origin, radius 10.
        let arc = ArcPath::new(
            Plane::G17,
            [-10.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
            (0.0, 0.0),
            false,
            0,
        );
        let xs: Vec<f64> = arc.extremes().map(|p| p[0]).collect();
        let ys: Vec<f64> = arc.extremes().map(|p| p[1]).collect();
        let max = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max);
        let min = |v: &[f64]| v.iter().copied().fold(f64::MAX, f64::min);
        assert!(close(max(&xs), 10.0) && close(min(&xs), -10.0));
        assert!(close(max(&ys), 10.0) && close(min(&ys), -10.0));
        assert!(arc.chords() >= 3);
    }
}
