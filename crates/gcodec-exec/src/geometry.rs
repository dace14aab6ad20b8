//! Circle geometry: arcs and helices from the forms a part program writes
//! them in (SPEC §11.x "Circles and helices"; reference §2.7, §3.3).
//!
//! Everything here is a pure function of plain numbers: the caller (the
//! channel) resolves `I J K` (incremental by default, `=AC(…)` absolute),
//! `CR=`, `AR=`, `I1= J1= K1=`, `TURN=` and the tangent of the previous
//! path element to numbers first, and turns an [`ArcError`] into a runtime
//! diagnostic with the error's [`code`](ArcError::code).
//!
//! # Conventions
//!
//! * Points are [`Point3`]: the three geometry axes in channel order
//!   (`[X, Y, Z]` with the default names), in the caller's length unit.
//! * A [`Plane`] names its abscissa, ordinate and infeed axis: `G17` X/Y
//!   (infeed Z), `G18` **Z/X** (infeed Y), `G19` Y/Z (infeed X). The three
//!   form a right-handed system in each plane (abscissa × ordinate =
//!   infeed), which is why `G18` is Z/X and not X/Z.
//! * [`Direction`]: `G2` ([`Direction::Cw`]) is clockwise and `G3`
//!   ([`Direction::Ccw`]) counter-clockwise **as seen looking from the
//!   positive infeed axis towards the plane** (against the infeed
//!   direction). For `G18` that is looking from +Y, with Z to the right
//!   and X upwards. (On a lathe whose +Y points into the floor, i.e. X
//!   towards the operator, `G2` therefore looks counter-clockwise to the
//!   operator: the control's definition, not a bug.)
//! * Angles are radians, measured in the arc's basis ([`Arc::u`],
//!   [`Arc::v`]) from `u` towards `v`; for an arc in the working plane `u`
//!   is the abscissa and `v` the ordinate, so angles are the usual polar
//!   angles of the plane and a positive sweep is `G3`.

use gcodec_source::{Code, codes};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use std::fmt;

/// A point or vector of the three geometry axes, in channel order.
pub type Point3 = [f64; 3];

/// The working plane (group 6), as the control spells the command.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
pub enum Plane {
    /// X/Y, infeed along Z.
    #[default]
    G17,
    /// Z/X, infeed along Y.
    G18,
    /// Y/Z, infeed along X.
    G19,
}

impl Plane {
    /// `G17`, `G18`, `G19`.
    pub fn code(self) -> &'static str {
        match self {
            Self::G17 => "G17",
            Self::G18 => "G18",
            Self::G19 => "G19",
        }
    }

    /// Indices into a [`Point3`] of the abscissa, the ordinate and the
    /// infeed axis: `G17` (0, 1, 2), `G18` (2, 0, 1), `G19` (1, 2, 0).
    pub const fn axes(self) -> (usize, usize, usize) {
        match self {
            Plane::G17 => (0, 1, 2),
            Plane::G18 => (2, 0, 1),
            Plane::G19 => (1, 2, 0),
        }
    }

    /// The infeed (third, perpendicular) axis index.
    pub const fn infeed(self) -> usize {
        self.axes().2
    }
}

/// The direction of rotation of `G2`/`G3`, seen from the positive infeed
/// axis (see the module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Direction {
    /// `G2`.
    Cw,
    /// `G3`.
    Ccw,
}

impl Direction {
    /// +1 for counter-clockwise, −1 for clockwise.
    pub const fn sign(self) -> f64 {
        match self {
            Direction::Cw => -1.0,
            Direction::Ccw => 1.0,
        }
    }
}

/// How far an end point may lie off the circle, after MD21000
/// `CIRCLE_ERROR_CONST` and MD21010 `CIRCLE_ERROR_FACTOR`: the radii at
/// the start and at the end may differ by `max(absolute, relative ×
/// radius)`. The same allowance lets a `CR=` slightly smaller than half
/// the chord stand for a half circle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct CircleTolerance {
    /// In the length unit of the points (mm by default).
    pub absolute: f64,
    /// A fraction of the radius.
    pub relative: f64,
}

impl CircleTolerance {
    /// The control's defaults: 0.01 mm, 0.001 × radius.
    pub const DEFAULT: CircleTolerance = CircleTolerance {
        absolute: 0.01,
        relative: 0.001,
    };

    /// The allowed deviation for a circle of this radius.
    pub fn allowed(&self, radius: f64) -> f64 {
        self.absolute.max(self.relative * radius.abs())
    }

    fn is_valid(&self) -> bool {
        self.absolute.is_finite()
            && self.relative.is_finite()
            && self.absolute >= 0.0
            && self.relative >= 0.0
    }
}

impl Default for CircleTolerance {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The form an arc is programmed in. Centres are absolute (the caller has
/// added the start point to incremental `I J K`); only their plane
/// coordinates are used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ArcForm {
    /// `G2`/`G3` with end point and `I J K`. An end point equal to the
    /// start point gives a full circle.
    Centre {
        direction: Direction,
        centre: Point3,
    },
    /// `G2`/`G3` with end point and `CR=`: positive for at most 180°,
    /// negative for more. Full circles cannot be programmed this way.
    Radius { direction: Direction, radius: f64 },
    /// `G2`/`G3` with end point and `AR=` (degrees, 0 < AR < 360).
    AngleToEnd { direction: Direction, angle: f64 },
    /// `G2`/`G3` with `I J K` and `AR=` (degrees, 0 < AR < 360): the end
    /// point in the plane follows from them; the plane coordinates of the
    /// `end` passed to [`resolve_arc`] are ignored, only its infeed
    /// coordinate is used (helix). [`Arc::end`] holds the computed point.
    AngleFromCentre {
        direction: Direction,
        centre: Point3,
        angle: f64,
    },
    /// `CIP` with `I1= J1= K1=` (absolute): the circle through start,
    /// intermediate and end point, in any orientation in space; the
    /// direction follows from the order of the points.
    Intermediate { point: Point3 },
    /// `CT`: the circle in the working plane that leaves the start point
    /// along `tangent` (the end tangent of the previous path element; only
    /// its plane components are used, its length does not matter).
    Tangent { tangent: Point3 },
}

/// A resolved arc or helix.
///
/// The path is `point_at(t)` for `t` in 0…1:
/// `centre + radius·(cos φ·u + sin φ·v) + t·rise·normal` with
/// `φ = start_angle + t·sweep`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Arc {
    pub plane: Plane,
    /// The start point as given.
    pub start: Point3,
    /// The end point: as given, or computed (`AR=` with a centre).
    pub end: Point3,
    /// The centre, at the start's infeed level for an arc in the plane.
    pub centre: Point3,
    pub radius: f64,
    /// Unit normal of the circle's plane: the infeed axis, except for an
    /// oblique `CIP` circle (then the normal with a positive infeed
    /// component, or, perpendicular to the working plane, with a positive
    /// abscissa or else ordinate component).
    pub normal: Point3,
    /// Unit vector of angle 0 (the abscissa in the working plane; for an
    /// oblique circle the abscissa projected onto its plane, or the
    /// ordinate when the abscissa is perpendicular to it).
    pub u: Point3,
    /// Unit vector of angle 90°: `normal × u`.
    pub v: Point3,
    /// Angle of the start point, in [0, 2π).
    pub start_angle: f64,
    /// Angle of the end point, in [0, 2π).
    pub end_angle: f64,
    /// Signed sweep in radians, positive counter-clockwise about `normal`
    /// (`G3`), including full circles and `TURN=` turns.
    pub sweep: f64,
    /// Displacement along `normal` from start to end (the helix's infeed
    /// travel; 0 for a plane arc).
    pub rise: f64,
    /// Rise per full turn (0 without rise).
    pub lead: f64,
    /// Path length (of the helix when it rises).
    pub length: f64,
    /// How far the end point lies off the circle through the start (the
    /// difference of the radii; only a centre form can have one, within
    /// the tolerance).
    pub end_deviation: f64,
}

/// An axis-aligned bounding box.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct BoundingBox {
    pub min: Point3,
    pub max: Point3,
}

impl BoundingBox {
    /// The box of one point.
    pub fn point(p: Point3) -> Self {
        BoundingBox { min: p, max: p }
    }

    /// Grows the box to include `p`.
    pub fn include(&mut self, p: Point3) {
        for (k, x) in p.into_iter().enumerate() {
            self.min[k] = self.min[k].min(x);
            self.max[k] = self.max[k].max(x);
        }
    }

    /// The smallest box holding both.
    pub fn union(&self, other: &BoundingBox) -> BoundingBox {
        let mut b = *self;
        b.include(other.min);
        b.include(other.max);
        b
    }
}

/// Why an arc cannot be resolved. Each variant has a stable diagnostic
/// code ([`code`](Self::code)) in `gcodec::run::`.
#[derive(Clone, Debug, PartialEq)]
pub enum ArcError {
    /// An input (named) is NaN or infinite.
    NonFinite { what: &'static str },
    /// The tolerance is negative or not finite (a caller error).
    InvalidTolerance,
    /// The end point does not lie on the circle (alarm 14040).
    EndPointNotOnCircle {
        start_radius: f64,
        end_radius: f64,
        allowed: f64,
    },
    /// The radius is zero: `CR=0`, or the centre is the start point.
    ZeroRadius,
    /// `|CR|` is smaller than half the chord beyond the tolerance.
    RadiusTooSmall { radius: f64, half_chord: f64 },
    /// End point equals start point for a form that needs a chord
    /// (`CR=`, `AR=` with end point, `CT`, `CIP`).
    ZeroChord,
    /// `AR=` outside 0 < AR < 360.
    OpeningAngle { angle: f64 },
    /// `CIP`: the three points lie on one line (or two coincide).
    CollinearPoints,
    /// `CT`: the tangent has no component in the working plane.
    TangentMissing,
    /// `CT`: the end point lies on the tangent's line, so no circle.
    TangentStraight,
    /// `TURN=` is negative, not a whole number or above 999.
    Turns { turns: f64 },
    /// `TURN=` with `CIP` (a circle through three points has no helix).
    TurnsWithIntermediate,
    /// The numbers are too large for the arc to be computed (an
    /// intermediate result overflowed).
    OutOfRange,
}

impl ArcError {
    /// The stable diagnostic code.
    pub const fn code(&self) -> &'static Code {
        match self {
            ArcError::NonFinite { .. } => codes::run::CIRCLE_NON_FINITE,
            ArcError::InvalidTolerance => codes::run::CIRCLE_TOLERANCE,
            ArcError::EndPointNotOnCircle { .. } => codes::run::CIRCLE_END_POINT,
            ArcError::ZeroRadius => codes::run::CIRCLE_ZERO_RADIUS,
            ArcError::RadiusTooSmall { .. } => codes::run::CIRCLE_RADIUS_TOO_SMALL,
            ArcError::ZeroChord => codes::run::CIRCLE_ZERO_CHORD,
            ArcError::OpeningAngle { .. } => codes::run::CIRCLE_OPENING_ANGLE,
            ArcError::CollinearPoints => codes::run::CIRCLE_COLLINEAR,
            ArcError::TangentMissing => codes::run::CIRCLE_TANGENT_MISSING,
            ArcError::TangentStraight => codes::run::CIRCLE_TANGENT_STRAIGHT,
            ArcError::Turns { .. } => codes::run::CIRCLE_TURNS,
            ArcError::TurnsWithIntermediate => codes::run::CIRCLE_TURNS_CIP,
            ArcError::OutOfRange => codes::run::CIRCLE_OUT_OF_RANGE,
        }
    }
}

impl fmt::Display for ArcError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ArcError::NonFinite { what } => write!(f, "the circle's {what} is not a finite number"),
            ArcError::InvalidTolerance => {
                write!(f, "the circle tolerance is negative or not finite")
            }
            ArcError::EndPointNotOnCircle {
                start_radius,
                end_radius,
                allowed,
            } => write!(
                f,
                "end point not on the circle: radius {start_radius} at the start, \
                 {end_radius} at the end (allowed difference {allowed})"
            ),
            ArcError::ZeroRadius => write!(f, "the circle has radius zero"),
            ArcError::RadiusTooSmall { radius, half_chord } => write!(
                f,
                "radius {radius} is smaller than half the distance to the end point ({half_chord})"
            ),
            ArcError::ZeroChord => write!(
                f,
                "the end point equals the start point, which this circle form cannot program \
                 (a full circle needs the centre)"
            ),
            ArcError::OpeningAngle { angle } => {
                write!(
                    f,
                    "opening angle AR={angle} is not between 0 and 360 degrees"
                )
            }
            ArcError::CollinearPoints => write!(
                f,
                "start, intermediate and end point of CIP lie on a straight line"
            ),
            ArcError::TangentMissing => write!(
                f,
                "CT: the previous path element has no tangent in the working plane"
            ),
            ArcError::TangentStraight => write!(
                f,
                "CT: the end point lies on the tangent, no circle leaves it tangentially"
            ),
            ArcError::Turns { turns } => {
                write!(f, "TURN={turns} is not a whole number from 0 to 999")
            }
            ArcError::TurnsWithIntermediate => write!(f, "TURN= is not possible with CIP"),
            ArcError::OutOfRange => {
                write!(f, "the circle's numbers are too large to compute it")
            }
        }
    }
}

impl std::error::Error for ArcError {}

/// The largest `TURN=`.
pub const MAX_TURNS: f64 = 999.0;

/// Relative size below which lengths count as zero (numerical degeneracy,
/// not a machining tolerance).
const EPS: f64 = 1e-9;

/// Resolves an arc or helix.
///
/// `start` and `end` are absolute points of the geometry axes; `turns` is
/// `TURN=` (0 when not written). For the forms in the working plane the
/// infeed coordinates of start and end make a helix when they differ.
pub fn resolve_arc(
    plane: Plane,
    start: Point3,
    end: Point3,
    form: &ArcForm,
    turns: f64,
    tolerance: &CircleTolerance,
) -> Result<Arc, ArcError> {
    finite3(start, "start point")?;
    finite3(end, "end point")?;
    finite(turns, "TURN")?;
    if !tolerance.is_valid() {
        return Err(ArcError::InvalidTolerance);
    }
    if turns < 0.0 || turns.fract() != 0.0 || turns > MAX_TURNS {
        return Err(ArcError::Turns { turns });
    }
    let arc = match *form {
        ArcForm::Centre { direction, centre } => {
            finite3(centre, "centre")?;
            centre_form(plane, start, end, direction, centre, turns, tolerance)
        }
        ArcForm::Radius { direction, radius } => {
            finite(radius, "radius")?;
            radius_form(plane, start, end, direction, radius, turns, tolerance)
        }
        ArcForm::AngleToEnd { direction, angle } => {
            finite(angle, "opening angle")?;
            check_angle(angle)?;
            angle_to_end(plane, start, end, direction, angle.to_radians(), turns)
        }
        ArcForm::AngleFromCentre {
            direction,
            centre,
            angle,
        } => {
            finite3(centre, "centre")?;
            finite(angle, "opening angle")?;
            check_angle(angle)?;
            angle_from_centre(
                plane,
                start,
                end,
                direction,
                centre,
                angle.to_radians(),
                turns,
            )
        }
        ArcForm::Intermediate { point } => {
            finite3(point, "intermediate point")?;
            if turns != 0.0 {
                return Err(ArcError::TurnsWithIntermediate);
            }
            intermediate(plane, start, point, end)
        }
        ArcForm::Tangent { tangent } => {
            finite3(tangent, "tangent")?;
            tangent_form(plane, start, end, tangent, turns)
        }
    }?;
    if arc.is_finite() {
        Ok(arc)
    } else {
        Err(ArcError::OutOfRange)
    }
}

/// Path length of an arc or helix of this radius, signed sweep (radians)
/// and rise: `sqrt((r·|sweep|)² + rise²)`.
pub fn arc_length(radius: f64, sweep: f64, rise: f64) -> f64 {
    (radius * sweep).hypot(rise)
}

/// Points along the arc, start and end included, such that the chords
/// deviate from the circle by at most `chord_error` (at least one segment
/// per 90°, at most [`MAX_SEGMENTS`] segments). A `chord_error` that is
/// not a positive finite number gives one segment per 90°.
pub fn arc_points(arc: &Arc, chord_error: f64) -> Vec<Point3> {
    let quarter_steps = (arc.sweep.abs() / FRAC_PI_2).ceil();
    let mut steps = quarter_steps.max(1.0);
    if chord_error.is_finite() && chord_error > 0.0 && chord_error < arc.radius {
        // A chord of angle α deviates r·(1 − cos(α/2)) from the circle.
        let alpha = 2.0 * (1.0 - chord_error / arc.radius).acos();
        if alpha > 0.0 {
            steps = steps.max((arc.sweep.abs() / alpha).ceil());
        }
    }
    let n = if steps.is_finite() {
        (steps as usize).clamp(1, MAX_SEGMENTS)
    } else {
        MAX_SEGMENTS
    };
    arc.points(n)
}

/// The most segments [`arc_points`] makes of one arc.
pub const MAX_SEGMENTS: usize = 1 << 16;

impl Arc {
    /// Whether every number of the arc is finite ([`resolve_arc`] only
    /// returns such arcs).
    pub fn is_finite(&self) -> bool {
        let scalars = [
            self.radius,
            self.start_angle,
            self.end_angle,
            self.sweep,
            self.rise,
            self.lead,
            self.length,
            self.end_deviation,
        ];
        scalars.iter().all(|x| x.is_finite())
            && [self.end, self.centre, self.normal, self.u, self.v]
                .iter()
                .all(|p| p.iter().all(|x| x.is_finite()))
    }

    /// The point at parameter `t` (0 = start, 1 = end of the arc).
    pub fn point_at(&self, t: f64) -> Point3 {
        let phi = self.start_angle + t * self.sweep;
        let (s, c) = phi.sin_cos();
        let mut p = [0.0; 3];
        for (k, x) in p.iter_mut().enumerate() {
            *x = self.centre[k]
                + self.radius * (c * self.u[k] + s * self.v[k])
                + t * self.rise * self.normal[k];
        }
        p
    }

    /// `segments + 1` equally spaced points, start and end included
    /// (`segments` at least 1).
    pub fn points(&self, segments: usize) -> Vec<Point3> {
        let n = segments.max(1);
        (0..=n)
            .map(|i| self.point_at(i as f64 / n as f64))
            .collect()
    }

    /// The sweep in degrees.
    pub fn sweep_degrees(&self) -> f64 {
        self.sweep.to_degrees()
    }

    /// The start angle in degrees, in [0, 360).
    pub fn start_angle_degrees(&self) -> f64 {
        self.start_angle.to_degrees()
    }

    /// The end angle in degrees, in [0, 360).
    pub fn end_angle_degrees(&self) -> f64 {
        self.end_angle.to_degrees()
    }

    /// Whether the arc is programmed as clockwise about its normal.
    pub fn direction(&self) -> Direction {
        if self.sweep < 0.0 {
            Direction::Cw
        } else {
            Direction::Ccw
        }
    }

    /// The exact bounding box of the path: start, end and, per axis, the
    /// extreme points of the circle (for an arc in the working plane those
    /// at 0°, 90°, 180° and 270°) that lie on the sweep.
    pub fn bounding_box(&self) -> BoundingBox {
        let mut bb = BoundingBox::point(self.point_at(0.0));
        bb.include(self.point_at(1.0));
        let span = self.sweep.abs();
        if span == 0.0 {
            return bb;
        }
        let dir = self.sweep.signum();
        for k in 0..3 {
            if self.u[k] == 0.0 && self.v[k] == 0.0 {
                continue;
            }
            // cos φ·u_k + sin φ·v_k is extreme at φ = atan2(v_k, u_k) (+π).
            let peak = self.v[k].atan2(self.u[k]);
            for phi in [peak, peak + PI] {
                let delta = ((phi - self.start_angle) * dir).rem_euclid(TAU);
                if delta <= span {
                    bb.include(self.point_at(delta / span));
                }
            }
        }
        bb
    }
}

// ---------------------------------------------------------------------------
// The forms.

fn centre_form(
    plane: Plane,
    start: Point3,
    end: Point3,
    direction: Direction,
    centre: Point3,
    turns: f64,
    tolerance: &CircleTolerance,
) -> Result<Arc, ArcError> {
    let s = in_plane(plane, start);
    let e = in_plane(plane, end);
    let c = in_plane(plane, centre);
    let rs = dist2(s, c);
    let re = dist2(e, c);
    if rs <= EPS * scale2(&[s, c]) {
        return Err(ArcError::ZeroRadius);
    }
    let allowed = tolerance.allowed(rs);
    if (rs - re).abs() > allowed {
        return Err(ArcError::EndPointNotOnCircle {
            start_radius: rs,
            end_radius: re,
            allowed,
        });
    }
    let a0 = angle2(s, c);
    // The same point, or (within the tolerance) the same angle: a full
    // circle.
    let base = match directed(angle2(e, c) - a0, direction) {
        _ if coincident2(s, e) => TAU,
        b if b * rs <= EPS * scale2(&[s, c]) => TAU,
        b => b,
    };
    Ok(plane_arc(
        plane,
        start,
        end,
        c,
        rs,
        a0,
        direction,
        base,
        turns,
        (rs - re).abs(),
    ))
}

fn radius_form(
    plane: Plane,
    start: Point3,
    end: Point3,
    direction: Direction,
    radius: f64,
    turns: f64,
    tolerance: &CircleTolerance,
) -> Result<Arc, ArcError> {
    let s = in_plane(plane, start);
    let e = in_plane(plane, end);
    if coincident2(s, e) {
        return Err(ArcError::ZeroChord);
    }
    let r = radius.abs();
    if r <= EPS * scale2(&[s, e]) {
        return Err(ArcError::ZeroRadius);
    }
    let chord = dist2(s, e);
    let half = chord / 2.0;
    let h = if r >= half {
        ((r - half) * (r + half)).sqrt()
    } else if half - r <= tolerance.allowed(r) {
        0.0
    } else {
        return Err(ArcError::RadiusTooSmall {
            radius,
            half_chord: half,
        });
    };
    let r = r.max(half);
    // Centre left of the chord S→E for a short counter-clockwise arc and
    // for a long clockwise one.
    let large = radius < 0.0;
    let side = if (direction == Direction::Ccw) != large {
        1.0
    } else {
        -1.0
    };
    let c = chord_centre(s, e, chord, side * h);
    let a0 = angle2(s, c);
    let base = directed(angle2(e, c) - a0, direction);
    Ok(plane_arc(
        plane, start, end, c, r, a0, direction, base, turns, 0.0,
    ))
}

fn angle_to_end(
    plane: Plane,
    start: Point3,
    end: Point3,
    direction: Direction,
    angle: f64,
    turns: f64,
) -> Result<Arc, ArcError> {
    let s = in_plane(plane, start);
    let e = in_plane(plane, end);
    if coincident2(s, e) {
        return Err(ArcError::ZeroChord);
    }
    let chord = dist2(s, e);
    let half = chord / 2.0;
    let (sin, cos) = (angle / 2.0).sin_cos();
    let r = half / sin;
    // Signed distance of the centre from the chord's midpoint, to the left
    // for counter-clockwise; negative (the other side) above 180°.
    let h = half * cos / sin * direction.sign();
    let c = chord_centre(s, e, chord, h);
    let a0 = angle2(s, c);
    Ok(plane_arc(
        plane, start, end, c, r, a0, direction, angle, turns, 0.0,
    ))
}

fn angle_from_centre(
    plane: Plane,
    start: Point3,
    end: Point3,
    direction: Direction,
    centre: Point3,
    angle: f64,
    turns: f64,
) -> Result<Arc, ArcError> {
    let s = in_plane(plane, start);
    let c = in_plane(plane, centre);
    let r = dist2(s, c);
    if r <= EPS * scale2(&[s, c]) {
        return Err(ArcError::ZeroRadius);
    }
    let a0 = angle2(s, c);
    let a1 = a0 + direction.sign() * angle;
    let (ia, io, _) = plane.axes();
    let mut computed = end;
    computed[ia] = c[0] + r * a1.cos();
    computed[io] = c[1] + r * a1.sin();
    Ok(plane_arc(
        plane, start, computed, c, r, a0, direction, angle, turns, 0.0,
    ))
}

fn tangent_form(
    plane: Plane,
    start: Point3,
    end: Point3,
    tangent: Point3,
    turns: f64,
) -> Result<Arc, ArcError> {
    let s = in_plane(plane, start);
    let e = in_plane(plane, end);
    let t = in_plane(plane, tangent);
    let tl = t[0].hypot(t[1]);
    if tl == 0.0 || tl <= EPS * tangent.iter().fold(0.0f64, |m, x| m.max(x.abs())) {
        return Err(ArcError::TangentMissing);
    }
    if coincident2(s, e) {
        return Err(ArcError::ZeroChord);
    }
    let t = [t[0] / tl, t[1] / tl];
    let n = [-t[1], t[0]]; // left normal
    let d = [e[0] - s[0], e[1] - s[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    let nd = n[0] * d[0] + n[1] * d[1];
    // |S + ρn − E| = |ρ|  ⇒  ρ = |d|² / (2 n·d).
    if nd.abs() <= EPS * dd.sqrt() {
        return Err(ArcError::TangentStraight);
    }
    let rho = dd / (2.0 * nd);
    let c = [s[0] + rho * n[0], s[1] + rho * n[1]];
    let direction = if rho > 0.0 {
        Direction::Ccw
    } else {
        Direction::Cw
    };
    let r = rho.abs();
    let a0 = angle2(s, c);
    let base = directed(angle2(e, c) - a0, direction);
    Ok(plane_arc(
        plane, start, end, c, r, a0, direction, base, turns, 0.0,
    ))
}

fn intermediate(plane: Plane, start: Point3, point: Point3, end: Point3) -> Result<Arc, ArcError> {
    let scale = scale3(&[start, point, end]);
    let a = sub(point, start);
    let b = sub(end, start);
    if norm(b) <= EPS * scale {
        return Err(ArcError::ZeroChord);
    }
    let n = cross(a, b);
    let nn = norm(n);
    // Distance of the intermediate point from the line start–end.
    if nn / norm(b) <= EPS * scale || norm(a) <= EPS * scale || norm(sub(end, point)) <= EPS * scale
    {
        return Err(ArcError::CollinearPoints);
    }
    // Circumcentre: S + ((|a|² b − |b|² a) × (a × b)) / (2 |a × b|²).
    let w = sub(scale_v(b, dot(a, a)), scale_v(a, dot(b, b)));
    let centre = add(start, scale_v(cross(w, n), 1.0 / (2.0 * nn * nn)));
    let radius = norm(sub(start, centre));
    // Travel is counter-clockwise about a × b.
    let travel = scale_v(n, 1.0 / nn);
    let (ia, io, ii) = plane.axes();
    let in_working_plane = travel[ia].abs() <= EPS && travel[io].abs() <= EPS;
    let (normal, u, v) = if in_working_plane {
        let mut normal = [0.0; 3];
        normal[ii] = 1.0;
        (normal, unit(ia), unit(io))
    } else {
        let flip = if travel[ii].abs() > EPS {
            travel[ii] < 0.0
        } else if travel[ia].abs() > EPS {
            travel[ia] < 0.0
        } else {
            travel[io] < 0.0
        };
        let normal = if flip { scale_v(travel, -1.0) } else { travel };
        let mut u = project(unit(ia), normal);
        if norm(u) <= 1e-6 {
            u = project(unit(io), normal);
        }
        let u = scale_v(u, 1.0 / norm(u));
        (normal, u, cross(normal, u))
    };
    let ccw = dot(travel, normal) > 0.0;
    let direction = if ccw { Direction::Ccw } else { Direction::Cw };
    let angle_of = |p: Point3| {
        let d = sub(p, centre);
        dot(d, v).atan2(dot(d, u))
    };
    let a0 = clean_angle(angle_of(start).rem_euclid(TAU));
    let sweep = directed(angle_of(end) - a0, direction) * direction.sign();
    let rise = dot(sub(end, start), normal);
    // The three points lie in the circle's plane, so the rise is zero up
    // to rounding; keep the path exact at the end point anyway.
    Ok(Arc {
        plane,
        start,
        end,
        centre,
        radius,
        normal,
        u,
        v,
        start_angle: a0,
        end_angle: clean_angle((a0 + sweep).rem_euclid(TAU)),
        sweep,
        rise,
        lead: lead(rise, sweep),
        length: arc_length(radius, sweep, rise),
        end_deviation: 0.0,
    })
}

// ---------------------------------------------------------------------------
// Helpers.

/// Builds an arc in the working plane from its centre (plane coordinates),
/// radius, start angle and the unsigned sweep without turns.
#[allow(clippy::too_many_arguments)]
fn plane_arc(
    plane: Plane,
    start: Point3,
    end: Point3,
    c: [f64; 2],
    radius: f64,
    a0: f64,
    direction: Direction,
    base: f64,
    turns: f64,
    end_deviation: f64,
) -> Arc {
    let (ia, io, ii) = plane.axes();
    let sweep = direction.sign() * (base + turns * TAU);
    let rise = end[ii] - start[ii];
    let mut centre = [0.0; 3];
    centre[ia] = c[0];
    centre[io] = c[1];
    centre[ii] = start[ii];
    let start_angle = clean_angle(a0.rem_euclid(TAU));
    Arc {
        plane,
        start,
        end,
        centre,
        radius,
        normal: unit(ii),
        u: unit(ia),
        v: unit(io),
        start_angle,
        end_angle: clean_angle((start_angle + sweep).rem_euclid(TAU)),
        sweep,
        rise,
        lead: lead(rise, sweep),
        length: arc_length(radius, sweep, rise),
        end_deviation,
    }
}

/// `rem_euclid` can return 2π itself for a tiny negative input.
fn clean_angle(a: f64) -> f64 {
    if a >= TAU { 0.0 } else { a }
}

fn lead(rise: f64, sweep: f64) -> f64 {
    if rise == 0.0 || sweep == 0.0 {
        0.0
    } else {
        rise * TAU / sweep.abs()
    }
}

/// The unsigned sweep from an angle difference in the given direction,
/// in (0, 2π] (0 only when the difference is a whole number of turns).
fn directed(diff: f64, direction: Direction) -> f64 {
    (diff * direction.sign()).rem_euclid(TAU)
}

fn check_angle(angle: f64) -> Result<(), ArcError> {
    if angle > 0.0 && angle < 360.0 {
        Ok(())
    } else {
        Err(ArcError::OpeningAngle { angle })
    }
}

/// The point at signed distance `h` left of the midpoint of S→E.
fn chord_centre(s: [f64; 2], e: [f64; 2], chord: f64, h: f64) -> [f64; 2] {
    let m = [(s[0] + e[0]) / 2.0, (s[1] + e[1]) / 2.0];
    let n = [-(e[1] - s[1]) / chord, (e[0] - s[0]) / chord];
    [m[0] + h * n[0], m[1] + h * n[1]]
}

fn finite(x: f64, what: &'static str) -> Result<(), ArcError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(ArcError::NonFinite { what })
    }
}

fn finite3(p: Point3, what: &'static str) -> Result<(), ArcError> {
    if p.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(ArcError::NonFinite { what })
    }
}

fn in_plane(plane: Plane, p: Point3) -> [f64; 2] {
    let (ia, io, _) = plane.axes();
    [p[ia], p[io]]
}

fn dist2(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn angle2(p: [f64; 2], c: [f64; 2]) -> f64 {
    (p[1] - c[1]).atan2(p[0] - c[0])
}

fn scale2(ps: &[[f64; 2]]) -> f64 {
    ps.iter()
        .flat_map(|p| p.iter())
        .fold(1.0f64, |m, x| m.max(x.abs()))
}

fn scale3(ps: &[Point3]) -> f64 {
    ps.iter()
        .flat_map(|p| p.iter())
        .fold(1.0f64, |m, x| m.max(x.abs()))
}

fn coincident2(a: [f64; 2], b: [f64; 2]) -> bool {
    dist2(a, b) <= EPS * scale2(&[a, b])
}

fn unit(k: usize) -> Point3 {
    let mut p = [0.0; 3];
    p[k] = 1.0;
    p
}

fn add(a: Point3, b: Point3) -> Point3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: Point3, b: Point3) -> Point3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale_v(a: Point3, s: f64) -> Point3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

fn dot(a: Point3, b: Point3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: Point3, b: Point3) -> Point3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: Point3) -> f64 {
    dot(a, a).sqrt()
}

/// `a` minus its component along the unit vector `n`.
fn project(a: Point3, n: Point3) -> Point3 {
    sub(a, scale_v(n, dot(a, n)))
}
