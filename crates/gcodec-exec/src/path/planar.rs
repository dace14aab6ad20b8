//! Geometry in the working plane: the contour's straight and circular
//! elements, their tangents, their equidistants (offset paths) and where
//! those meet. Coordinates are the plane's abscissa and ordinate in mm;
//! angles are counter-clockwise seen from the positive infeed axis.

use std::f64::consts::{PI, TAU};

/// A point (or vector) in the plane.
pub type P2 = [f64; 2];

/// Lengths below this are zero (mm).
pub const EPS: f64 = 1e-9;

/// A contour element in the working plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    Line {
        start: P2,
        end: P2,
    },
    /// `sweep` is signed: positive counter-clockwise (`G3`); its size may
    /// exceed a turn (a full circle, `TURN=`).
    Arc {
        start: P2,
        end: P2,
        centre: P2,
        radius: f64,
        sweep: f64,
    },
}

pub fn sub(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

pub fn add(a: P2, b: P2) -> P2 {
    [a[0] + b[0], a[1] + b[1]]
}

pub fn scale(a: P2, s: f64) -> P2 {
    [a[0] * s, a[1] * s]
}

pub fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// The z component of `a × b`: positive when `b` turns left of `a`.
pub fn cross(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

pub fn norm(a: P2) -> f64 {
    a[0].hypot(a[1])
}

pub fn distance(a: P2, b: P2) -> f64 {
    norm(sub(a, b))
}

/// `a` turned 90° to the left.
pub fn left(a: P2) -> P2 {
    [-a[1], a[0]]
}

pub fn unit(a: P2) -> Option<P2> {
    let n = norm(a);
    (n > EPS).then(|| scale(a, 1.0 / n))
}

/// The angle of `a`, in (-π, π].
pub fn angle(a: P2) -> f64 {
    a[1].atan2(a[0])
}

/// `a` wrapped into (-π, π].
pub fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(TAU);
    if w > PI { w - TAU } else { w }
}

impl Segment {
    pub fn start(&self) -> P2 {
        match *self {
            Self::Line { start, .. } | Self::Arc { start, .. } => start,
        }
    }

    pub fn end(&self) -> P2 {
        match *self {
            Self::Line { end, .. } | Self::Arc { end, .. } => end,
        }
    }

    pub fn length(&self) -> f64 {
        match *self {
            Self::Line { start, end } => distance(start, end),
            Self::Arc { radius, sweep, .. } => radius * sweep.abs(),
        }
    }

    /// The element moved by `d`.
    pub fn translated(&self, d: P2) -> Segment {
        match *self {
            Self::Line { start, end } => Self::Line {
                start: add(start, d),
                end: add(end, d),
            },
            Self::Arc {
                start,
                end,
                centre,
                radius,
                sweep,
            } => Self::Arc {
                start: add(start, d),
                end: add(end, d),
                centre: add(centre, d),
                radius,
                sweep,
            },
        }
    }

    /// The element traversed the other way.
    pub fn reversed(&self) -> Segment {
        match *self {
            Self::Line { start, end } => Self::Line {
                start: end,
                end: start,
            },
            Self::Arc {
                start,
                end,
                centre,
                radius,
                sweep,
            } => Self::Arc {
                start: end,
                end: start,
                centre,
                radius,
                sweep: -sweep,
            },
        }
    }

    /// Whether the element has no extent in the plane.
    pub fn is_point(&self) -> bool {
        self.length() <= EPS
    }

    /// The unit tangent at `p`, a point of the element (its direction of
    /// travel); `None` for a line of no length.
    fn tangent_at(&self, p: P2) -> Option<P2> {
        match *self {
            Self::Line { start, end } => unit(sub(end, start)),
            Self::Arc { centre, sweep, .. } => {
                let radial = unit(sub(p, centre))?;
                Some(if sweep >= 0.0 {
                    left(radial)
                } else {
                    scale(left(radial), -1.0)
                })
            }
        }
    }

    pub fn start_tangent(&self) -> Option<P2> {
        self.tangent_at(self.start())
    }

    pub fn end_tangent(&self) -> Option<P2> {
        self.tangent_at(self.end())
    }

    /// The equidistant at `offset` to the left of the direction of travel
    /// (negative: to the right); `None` where an arc's equidistant
    /// vanishes or turns inside out (the offset reaches its centre).
    pub fn offset(&self, offset: f64) -> Option<Segment> {
        match *self {
            Self::Line { start, end } => {
                let n = left(unit(sub(end, start))?);
                Some(Self::Line {
                    start: add(start, scale(n, offset)),
                    end: add(end, scale(n, offset)),
                })
            }
            Self::Arc {
                start,
                end,
                centre,
                radius,
                sweep,
            } => {
                // Counter-clockwise, the left is towards the centre.
                let r = if sweep >= 0.0 {
                    radius - offset
                } else {
                    radius + offset
                };
                if r <= EPS {
                    return None;
                }
                let at = |p: P2| add(centre, scale(sub(p, centre), r / radius));
                Some(Self::Arc {
                    start: at(start),
                    end: at(end),
                    centre,
                    radius: r,
                    sweep,
                })
            }
        }
    }

    /// Where `p`, a point of the element's carrier (its line or circle),
    /// lies along it: 0 at the start, 1 at the end, less than 0 before
    /// the start and more than 1 beyond the end. An arc's position is
    /// counted from the nearer end, so that a point just beyond either end
    /// is just outside 0…1.
    pub fn position(&self, p: P2) -> f64 {
        match *self {
            Self::Line { start, end } => {
                let d = sub(end, start);
                let l2 = dot(d, d);
                if l2 <= EPS * EPS {
                    return 0.0;
                }
                dot(sub(p, start), d) / l2
            }
            Self::Arc {
                start,
                end,
                centre,
                sweep,
                ..
            } => {
                let s = sweep.signum();
                let a = angle(sub(p, centre));
                let from_start = wrap(s * (a - angle(sub(start, centre))));
                let from_end = wrap(s * (a - angle(sub(end, centre))));
                if from_start.abs() <= from_end.abs() {
                    from_start / sweep.abs()
                } else {
                    1.0 + from_end / sweep.abs()
                }
            }
        }
    }

    /// The same carrier from `start` to `end` (points of it), in the same
    /// direction; an arc keeps its sense of rotation and takes the sweep
    /// that is nearest its old one.
    pub fn with_ends(&self, new_start: P2, new_end: P2) -> Segment {
        match *self {
            Self::Line { .. } => Self::Line {
                start: new_start,
                end: new_end,
            },
            Self::Arc {
                start,
                end,
                centre,
                radius,
                sweep,
            } => {
                let s = sweep.signum();
                let grow_start =
                    wrap(s * (angle(sub(start, centre)) - angle(sub(new_start, centre))));
                let grow_end = wrap(s * (angle(sub(new_end, centre)) - angle(sub(end, centre))));
                Self::Arc {
                    start: new_start,
                    end: new_end,
                    centre,
                    radius,
                    sweep: sweep + s * (grow_start + grow_end),
                }
            }
        }
    }

    /// Whether the element, trimmed or extended to `start` and `end`, still
    /// runs forward (neither end passed the other).
    pub fn runs_forward_between(&self, start: P2, end: P2) -> bool {
        let trimmed = self.with_ends(start, end);
        match trimmed {
            Self::Line { start: s, end: e } => match self {
                Self::Line { start, end } => dot(sub(e, s), sub(*end, *start)) >= -EPS,
                Self::Arc { .. } => true,
            },
            Self::Arc { sweep, .. } => match self {
                Self::Arc { sweep: old, .. } => sweep * old.signum() >= -EPS,
                Self::Line { .. } => true,
            },
        }
    }
}

/// The points where the carriers of `a` and `b` (their infinite lines and
/// full circles) meet: none, one or two.
pub fn carrier_intersections(a: &Segment, b: &Segment) -> Vec<P2> {
    match (a, b) {
        (Segment::Line { start: a0, end: a1 }, Segment::Line { start: b0, end: b1 }) => {
            line_line(*a0, sub(*a1, *a0), *b0, sub(*b1, *b0))
                .into_iter()
                .collect()
        }
        (Segment::Line { start, end }, Segment::Arc { centre, radius, .. })
        | (Segment::Arc { centre, radius, .. }, Segment::Line { start, end }) => {
            line_circle(*start, sub(*end, *start), *centre, *radius)
        }
        (
            Segment::Arc {
                centre: c0,
                radius: r0,
                ..
            },
            Segment::Arc {
                centre: c1,
                radius: r1,
                ..
            },
        ) => circle_circle(*c0, *r0, *c1, *r1),
    }
}

/// The intersection of the lines through `p` along `d` and through `q`
/// along `e`; `None` when they are parallel.
pub fn line_line(p: P2, d: P2, q: P2, e: P2) -> Option<P2> {
    let denominator = cross(d, e);
    let scale_of = norm(d) * norm(e);
    if scale_of <= EPS || denominator.abs() <= 1e-12 * scale_of {
        return None;
    }
    let t = cross(sub(q, p), e) / denominator;
    Some(add(p, scale(d, t)))
}

fn line_circle(p: P2, d: P2, centre: P2, radius: f64) -> Vec<P2> {
    let Some(u) = unit(d) else {
        return Vec::new();
    };
    // The foot of the perpendicular from the centre, and half the chord.
    let foot = add(p, scale(u, dot(sub(centre, p), u)));
    let h2 = radius * radius - dot(sub(foot, centre), sub(foot, centre));
    if h2 < -1e-9 * radius.max(1.0) {
        return Vec::new();
    }
    let h = h2.max(0.0).sqrt();
    if h <= EPS {
        return vec![foot];
    }
    vec![add(foot, scale(u, -h)), add(foot, scale(u, h))]
}

fn circle_circle(c0: P2, r0: f64, c1: P2, r1: f64) -> Vec<P2> {
    let d = distance(c0, c1);
    if d <= EPS || d > r0 + r1 + 1e-9 || d < (r0 - r1).abs() - 1e-9 {
        return Vec::new();
    }
    let a = (r0 * r0 - r1 * r1 + d * d) / (2.0 * d);
    let h = (r0 * r0 - a * a).max(0.0).sqrt();
    let u = scale(sub(c1, c0), 1.0 / d);
    let mid = add(c0, scale(u, a));
    if h <= EPS {
        return vec![mid];
    }
    vec![add(mid, scale(left(u), h)), add(mid, scale(left(u), -h))]
}

/// Of `points`, the one nearest `to`.
pub fn nearest(points: &[P2], to: P2) -> Option<P2> {
    points
        .iter()
        .copied()
        .min_by(|a, b| distance(*a, to).total_cmp(&distance(*b, to)))
}

/// The arc about `centre` from `start` to `end` (both at `radius` from it),
/// turning counter-clockwise when `ccw`, less than a full turn.
pub fn arc_between(centre: P2, start: P2, end: P2, ccw: bool) -> Segment {
    let radius = distance(start, centre);
    let a0 = angle(sub(start, centre));
    let a1 = angle(sub(end, centre));
    let sweep = if ccw {
        (a1 - a0).rem_euclid(TAU)
    } else {
        -(a0 - a1).rem_euclid(TAU)
    };
    Segment::Arc {
        start,
        end,
        centre,
        radius,
        sweep,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: P2, b: P2) -> bool {
        distance(a, b) < 1e-9
    }

    /// A quarter circle of radius 10 about the origin, counter-clockwise
    /// from the abscissa.
    fn quarter() -> Segment {
        Segment::Arc {
            start: [10.0, 0.0],
            end: [0.0, 10.0],
            centre: [0.0, 0.0],
            radius: 10.0,
            sweep: PI / 2.0,
        }
    }

    #[test]
    fn a_line_offsets_to_its_left_and_right() {
        let line = Segment::Line {
            start: [0.0, 0.0],
            end: [10.0, 0.0],
        };
        let left = line.offset(2.0).unwrap();
        assert!(close(left.start(), [0.0, 2.0]) && close(left.end(), [10.0, 2.0]));
        let right = line.offset(-2.0).unwrap();
        assert!(close(right.start(), [0.0, -2.0]));
    }

    #[test]
    fn an_arc_offsets_towards_or_away_from_its_centre() {
        // A quarter counter-clockwise: the left is inside.
        let arc = quarter();
        let inside = arc.offset(3.0).unwrap();
        assert!(close(inside.start(), [7.0, 0.0]) && close(inside.end(), [0.0, 7.0]));
        let outside = arc.offset(-3.0).unwrap();
        assert!(close(outside.end(), [0.0, 13.0]));
        assert!(arc.offset(10.0).is_none(), "the equidistant vanishes");
    }

    #[test]
    fn positions_along_an_arc_count_from_the_nearer_end() {
        let arc = quarter();
        let beyond_end = [-10.0 * 0.1f64.sin(), 10.0 * 0.1f64.cos()];
        assert!((arc.position(beyond_end) - (1.0 + 0.1 / (PI / 2.0))).abs() < 1e-9);
        let before_start = [10.0 * 0.1f64.cos(), -10.0 * 0.1f64.sin()];
        assert!((arc.position(before_start) + 0.1 / (PI / 2.0)).abs() < 1e-9);
    }

    #[test]
    fn trimming_keeps_the_sense_of_rotation() {
        let arc = quarter();
        let p = [10.0 * (PI / 8.0).cos(), 10.0 * (PI / 8.0).sin()];
        let Segment::Arc { sweep, .. } = arc.with_ends(p, arc.end()) else {
            unreachable!()
        };
        assert!((sweep - 3.0 * PI / 8.0).abs() < 1e-9);
        assert!(arc.runs_forward_between(p, arc.end()));
        assert!(!arc.runs_forward_between(arc.end(), p));
    }

    #[test]
    fn carriers_meet_where_they_should() {
        let a = Segment::Line {
            start: [0.0, 0.0],
            end: [1.0, 0.0],
        };
        let b = Segment::Line {
            start: [5.0, -1.0],
            end: [5.0, 1.0],
        };
        assert_eq!(carrier_intersections(&a, &b), vec![[5.0, 0.0]]);
        let circle = Segment::Arc {
            start: [3.0, 0.0],
            end: [-3.0, 0.0],
            centre: [0.0, 0.0],
            radius: 3.0,
            sweep: PI,
        };
        let points = carrier_intersections(&a, &circle);
        assert_eq!(points.len(), 2);
        assert!(close(nearest(&points, [2.0, 0.0]).unwrap(), [3.0, 0.0]));
        let other = Segment::Arc {
            start: [7.0, 0.0],
            end: [1.0, 0.0],
            centre: [4.0, 0.0],
            radius: 3.0,
            sweep: PI,
        };
        let points = carrier_intersections(&circle, &other);
        assert_eq!(points.len(), 2);
        assert!(points.iter().all(|p| (p[0] - 2.0).abs() < 1e-9));
    }

    #[test]
    fn the_arc_between_two_points_turns_as_asked() {
        let Segment::Arc { sweep, .. } = arc_between([0.0, 0.0], [1.0, 0.0], [0.0, 1.0], false)
        else {
            unreachable!()
        };
        assert!((sweep + 1.5 * PI).abs() < 1e-9);
    }
}
