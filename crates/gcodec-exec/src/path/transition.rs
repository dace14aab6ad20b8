//! Contour definitions at a corner: the chamfer (`CHF=`, `CHR=`) and the
//! rounding (`RND=`, modal `RNDM=`) that the control inserts between the
//! element that leads into a corner and the one that leaves it (SPEC
//! §11.12).

use super::planar::{
    self, EPS, P2, Segment, add, arc_between, carrier_intersections, cross, distance, dot, nearest,
    scale, sub,
};

/// What is inserted at a corner.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CornerElement {
    /// `CHF=`: a chamfer of this length.
    ChamferLength(f64),
    /// `CHR=`: a chamfer whose legs along the elements have this length.
    ChamferLeg(f64),
    /// `RND=`, `RNDM=`: a tangent arc of this radius.
    Rounding(f64),
}

/// The corner resolved: where the leading element now ends, the inserted
/// element, where the leaving one now starts.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Corner {
    pub lead_end: P2,
    pub inserted: Segment,
    pub leave_start: P2,
    /// The size was reduced to fit elements too short for it.
    pub reduced: bool,
}

/// The corner element between `lead` (ending at the corner) and `leave`
/// (starting there); `None` where there is nothing to insert: the
/// elements meet tangentially, one has no extent, or the value is 0.
pub fn resolve(lead: &Segment, leave: &Segment, element: CornerElement) -> Option<Corner> {
    let a = lead.end_tangent()?;
    let b = leave.start_tangent()?;
    let turn = cross(a, b);
    let along = dot(a, b);
    // Tangent (no corner), or a reversal (no inside to round into).
    if turn.abs() <= 1e-9 {
        return None;
    }
    match element {
        CornerElement::ChamferLength(length) if length > EPS => {
            let half_cos = ((1.0 + along) / 2.0).max(0.0).sqrt();
            if half_cos <= 1e-9 {
                return None;
            }
            chamfer(lead, leave, length / (2.0 * half_cos))
        }
        CornerElement::ChamferLeg(leg) if leg > EPS => chamfer(lead, leave, leg),
        CornerElement::Rounding(radius) if radius > EPS => {
            rounding(lead, leave, radius, turn > 0.0)
        }
        _ => None,
    }
}

/// A chamfer whose ends lie at chord distance `leg` from the corner on
/// either element, reduced to the shorter element's chord.
fn chamfer(lead: &Segment, leave: &Segment, leg: f64) -> Option<Corner> {
    let corner = lead.end();
    let fits = leg
        .min(distance(lead.start(), corner))
        .min(distance(leave.end(), corner));
    let reduced = fits < leg - EPS;
    if fits <= EPS {
        return None;
    }
    let lead_end = at_chord(lead, corner, fits, true)?;
    let leave_start = at_chord(leave, corner, fits, false)?;
    Some(Corner {
        lead_end,
        inserted: Segment::Line {
            start: lead_end,
            end: leave_start,
        },
        leave_start,
        reduced,
    })
}

/// The point of `element` at chord distance `d` from `corner`, its end
/// (`from_end`) or its start.
fn at_chord(element: &Segment, corner: P2, d: f64, from_end: bool) -> Option<P2> {
    match element {
        Segment::Line { start, end } => {
            let u = planar::unit(sub(*end, *start))?;
            Some(if from_end {
                add(corner, scale(u, -d))
            } else {
                add(corner, scale(u, d))
            })
        }
        Segment::Arc { .. } => {
            let circle = Segment::Arc {
                start: add(corner, [d, 0.0]),
                end: add(corner, [-d, 0.0]),
                centre: corner,
                radius: d,
                sweep: std::f64::consts::PI,
            };
            let points = carrier_intersections(element, &circle);
            points
                .into_iter()
                .filter(|p| (-1e-9..=1.0 + 1e-9).contains(&element.position(*p)))
                .min_by(|p, q| {
                    let target = if from_end { 1.0 } else { 0.0 };
                    (element.position(*p) - target)
                        .abs()
                        .total_cmp(&(element.position(*q) - target).abs())
                })
        }
    }
}

/// The arc of `radius` tangent to both elements inside the corner
/// (`left`: the contour turns left there); reduced, by halving the
/// interval, to the largest radius whose tangent points lie on both
/// elements.
fn rounding(lead: &Segment, leave: &Segment, radius: f64, left: bool) -> Option<Corner> {
    if let Some(corner) = tangent_arc(lead, leave, radius, left) {
        return Some(corner);
    }
    let (mut fits, mut too_big) = (0.0, radius);
    let mut best = None;
    for _ in 0..50 {
        let r = (fits + too_big) / 2.0;
        match tangent_arc(lead, leave, r, left) {
            Some(corner) => {
                fits = r;
                best = Some(corner);
            }
            None => too_big = r,
        }
    }
    best.map(|corner| Corner {
        reduced: true,
        ..corner
    })
}

fn tangent_arc(lead: &Segment, leave: &Segment, radius: f64, left: bool) -> Option<Corner> {
    let side = if left { radius } else { -radius };
    let a = lead.offset(side)?;
    let b = leave.offset(side)?;
    let corner = lead.end();
    let centre = nearest(&carrier_intersections(&a, &b), corner)?;
    let lead_end = foot(lead, centre)?;
    let leave_start = foot(leave, centre)?;
    let on = |e: &Segment, p: P2| (-1e-9..=1.0 + 1e-9).contains(&e.position(p));
    if !on(lead, lead_end) || !on(leave, leave_start) {
        return None;
    }
    Some(Corner {
        lead_end,
        inserted: arc_between(centre, lead_end, leave_start, left),
        leave_start,
        reduced: false,
    })
}

/// The point of `element`'s carrier nearest `p` (where a circle about `p`
/// touches it).
fn foot(element: &Segment, p: P2) -> Option<P2> {
    match element {
        Segment::Line { start, end } => {
            let u = planar::unit(sub(*end, *start))?;
            Some(add(*start, scale(u, dot(sub(p, *start), u))))
        }
        Segment::Arc { centre, radius, .. } => {
            let u = planar::unit(sub(p, *centre))?;
            Some(add(*centre, scale(u, *radius)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn line(start: P2, end: P2) -> Segment {
        Segment::Line { start, end }
    }

    fn close(a: P2, b: P2) -> bool {
        distance(a, b) < 1e-7
    }

    #[test]
    fn a_rounding_between_two_lines_is_tangent_to_both() {
        // Up the Y axis, then right along Y=80: a right turn.
        let up = line([0.0, 0.0], [0.0, 80.0]);
        let right = line([0.0, 80.0], [100.0, 80.0]);
        let c = resolve(&up, &right, CornerElement::Rounding(5.0)).unwrap();
        assert!(close(c.lead_end, [0.0, 75.0]), "{c:?}");
        assert!(close(c.leave_start, [5.0, 80.0]), "{c:?}");
        let Segment::Arc { centre, sweep, .. } = c.inserted else {
            panic!("{c:?}")
        };
        assert!(close(centre, [5.0, 75.0]));
        assert!(
            (sweep + PI / 2.0).abs() < 1e-9,
            "clockwise quarter: {sweep}"
        );
        assert!(!c.reduced);
    }

    #[test]
    fn a_chamfer_by_length_and_by_leg() {
        let up = line([0.0, 0.0], [0.0, 80.0]);
        let right = line([0.0, 80.0], [100.0, 80.0]);
        // A 90° corner: a chamfer of length 2 has legs of 2/√2.
        let c = resolve(&up, &right, CornerElement::ChamferLength(2.0)).unwrap();
        assert!((distance(c.lead_end, c.leave_start) - 2.0).abs() < 1e-9);
        let c = resolve(&up, &right, CornerElement::ChamferLeg(2.0)).unwrap();
        assert!(close(c.lead_end, [0.0, 78.0]) && close(c.leave_start, [2.0, 80.0]));
    }

    #[test]
    fn a_rounding_too_big_for_a_short_element_is_reduced() {
        let up = line([0.0, 0.0], [0.0, 3.0]);
        let right = line([0.0, 3.0], [100.0, 3.0]);
        let c = resolve(&up, &right, CornerElement::Rounding(5.0)).unwrap();
        assert!(c.reduced);
        assert!(close(c.lead_end, [0.0, 0.0]), "{c:?}");
        let Segment::Arc { radius, .. } = c.inserted else {
            panic!()
        };
        assert!((radius - 3.0).abs() < 1e-6, "{radius}");
    }

    #[test]
    fn a_rounding_between_a_line_and_an_arc() {
        // Right along Y=0 to (10,0), then a counter-clockwise half circle
        // about (10,10) of radius 10: the line leaves tangentially, so
        // take one that does not: a quarter about (20,0) from (10,0).
        let lead = line([0.0, 0.0], [10.0, 0.0]);
        let leave = Segment::Arc {
            start: [10.0, 0.0],
            end: [20.0, 10.0],
            centre: [20.0, 0.0],
            radius: 10.0,
            sweep: -PI / 2.0,
        };
        let c = resolve(&lead, &leave, CornerElement::Rounding(2.0)).unwrap();
        let Segment::Arc { centre, radius, .. } = c.inserted else {
            panic!()
        };
        assert!((radius - 2.0).abs() < 1e-9);
        // Tangent to the line: 2 above it; to the circle: 12 from its centre.
        assert!((centre[1] - 2.0).abs() < 1e-9, "{centre:?}");
        assert!(
            (distance(centre, [20.0, 0.0]) - 12.0).abs() < 1e-9,
            "{centre:?}"
        );
    }

    #[test]
    fn nothing_is_inserted_between_tangent_elements() {
        let a = line([0.0, 0.0], [10.0, 0.0]);
        let b = line([10.0, 0.0], [20.0, 0.0]);
        assert!(resolve(&a, &b, CornerElement::Rounding(2.0)).is_none());
    }
}
