//! Tool radius compensation in the working plane (`G41`/`G42`, SPEC
//! §11.12): the tool centre on the contour's equidistant at the radius of
//! the active cutting edge plus `OFFN`, joined at each corner as the
//! control joins it:
//!
//! - an inside corner: both equidistants end where they meet;
//! - an outside corner under `G450`: a transition circle about the corner;
//!   under `G451`: the equidistants extended to where they meet (lines),
//!   or their end tangents (arcs);
//! - the block that selects compensation (`NORM`): a straight line to
//!   the point perpendicular to the next element's start; the block that
//!   ends it: from the point perpendicular to the last element's end;
//! - a change of side or of radius while on: the old equidistant ends
//!   perpendicular to its element's end, the new one starts perpendicular
//!   to its element's start, a straight line joins them.

use super::planar::{
    self, EPS, P2, Segment, add, arc_between, carrier_intersections, cross, dot, left, nearest,
    scale,
};
use super::{Approach, Element, Held, PathDiagnostic, PathStage, Piece, ToolTrack};
use crate::event::InsertedElement;
use gcodec_source::codes;

/// The side of the contour the tool is on, seen in the direction of
/// travel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// `G41`.
    Left,
    /// `G42`.
    Right,
}

/// What joins the equidistants at an outside corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CornerMode {
    /// `G450`: a transition circle about the corner; with `DISC=` above 0
    /// (percent, to 100) a transition curve drawn towards where the
    /// equidistants meet.
    Circle { disc: u8 },
    /// `G451`: the intersection of the equidistants.
    Intersection,
}

/// The point perpendicular to the end of `contour` at `offset` (to its
/// left when positive).
pub fn normal_end(contour: &Segment, offset: f64) -> P2 {
    match contour.end_tangent() {
        Some(t) => add(contour.end(), scale(left(t), offset)),
        None => contour.end(),
    }
}

/// The point perpendicular to the start of `contour` at `offset`.
pub fn normal_start(contour: &Segment, offset: f64) -> P2 {
    match contour.start_tangent() {
        Some(t) => add(contour.start(), scale(left(t), offset)),
        None => contour.start(),
    }
}

fn selection_error(what: &str) -> PathDiagnostic {
    PathDiagnostic {
        code: codes::run::COMPENSATION_SELECTION,
        message: format!(
            "tool radius compensation is {what} only in a straight block (`G0`, `G1`), not in a circle"
        ),
    }
}

fn collision(message: impl Into<String>) -> PathDiagnostic {
    PathDiagnostic {
        code: codes::run::COMPENSATION_COLLISION,
        message: message.into(),
    }
}

/// An element in the plane after one without compensation: it selects
/// compensation, or there is none.
pub fn start<M>(element: &mut Element<M>) -> Result<(), PathDiagnostic> {
    if element.compensation.side.is_none() {
        return Ok(());
    }
    let Some(contour) = element.contour else {
        return Ok(());
    };
    if !matches!(contour, Segment::Line { .. }) {
        return Err(selection_error("selected"));
    }
    element.tool = Some(ToolTrack {
        start: Some(contour.start()),
        approach: true,
        ..ToolTrack::default()
    });
    Ok(())
}

/// An element in the plane after the compensated one held at `lead`:
/// resolves the corner between them.
pub fn join<M: Clone, O>(
    stage: &mut PathStage<M, O>,
    lead: usize,
    element: &mut Element<M>,
) -> Result<(), PathDiagnostic> {
    let Held::Element(q) = &mut stage.held[lead] else {
        return Ok(());
    };
    let (Some(a), Some(b)) = (q.contour, element.contour) else {
        return Ok(());
    };
    let q_offset = q.compensation.offset();
    let approach = q.tool.as_ref().is_some_and(|t| t.approach);
    let mut track = ToolTrack::default();
    let lead_end;
    if element.compensation.side.is_none() {
        if !matches!(b, Segment::Line { .. }) {
            return Err(selection_error("ended"));
        }
        if approach {
            // `G40` right after `G41`/`G42`: nothing was selected.
            q.tool = None;
            return Ok(());
        }
        lead_end = normal_end(&a, q_offset);
        track.start = Some(lead_end);
        track.end = Some(b.end());
        match element.compensation.approach {
            // `KONT`, ending behind the contour: round its end point.
            Approach::AroundEnds => {
                if let Some((start, pieces)) = around(&a, &b, q_offset, q.compensation.corner) {
                    track.start = Some(start);
                    track.before = pieces;
                }
            }
            // `KONTT`: leave on a circle tangent to the equidistant.
            Approach::Tangent => {
                if let Some(t) = a.end_tangent() {
                    track.curve = tangent_arc(lead_end, t, b.end());
                }
            }
            Approach::Normal => {}
        }
    } else if approach {
        lead_end = normal_start(&b, element.compensation.offset());
        track.start = Some(lead_end);
        // `KONTT`: arrive on a circle tangent to the equidistant.
        if q.compensation.approach == Approach::Tangent
            && let Some(t) = b.start_tangent()
            && let Some(tool) = &mut q.tool
        {
            // Leaving the start backwards through the start point, turned
            // round: it arrives along the equidistant.
            tool.curve = tangent_arc(lead_end, scale(t, -1.0), a.start()).map(|arc| arc.reversed());
        }
        // `KONT`, starting behind the contour: round its start point.
        if q.compensation.approach == Approach::AroundEnds {
            let offset = element.compensation.offset();
            if let Some((start, pieces)) = around(&a, &b, offset, q.compensation.corner) {
                let end = normal_end(&a, offset);
                track.start = Some(start);
                track.before = pieces;
                finish_lead(stage, lead, end);
                element.tool = Some(track);
                return Ok(());
            }
        }
    } else if q.compensation.side != element.compensation.side
        || (q.compensation.radius - element.compensation.radius).abs() > EPS
    {
        lead_end = normal_end(&a, q_offset);
        let start = normal_start(&b, element.compensation.offset());
        track.start = Some(start);
        if planar::distance(lead_end, start) > EPS {
            track.before.push(Piece {
                kind: InsertedElement::CornerLine,
                path: Segment::Line {
                    start: lead_end,
                    end: start,
                },
                corner: b.start(),
            });
        }
    } else {
        let detect = q.compensation.collision_detection;
        let mode = q.compensation.corner;
        let (at, end, start, pieces) = join_leaving_out(stage, lead, &b, q_offset, mode, detect)?;
        lead_end = end;
        track.start = Some(start);
        track.before = pieces;
        finish_lead(stage, at, lead_end);
        element.tool = Some(track);
        return Ok(());
    }
    finish_lead(stage, lead, lead_end);
    element.tool = Some(track);
    Ok(())
}

/// `KONT`: where the straight approach or retraction `a`–`b` (one of
/// them the contour's first or last element) makes an outside corner at
/// the contour's end point, the tool goes round it as round any outside
/// corner: where `b`'s equidistant starts and the pieces before it.
/// `None` where the corner is inside or tangent: then as under `NORM`.
fn around(a: &Segment, b: &Segment, offset: f64, mode: CornerMode) -> Option<(P2, Vec<Piece>)> {
    let (ta, tb) = (a.end_tangent()?, b.start_tangent()?);
    let turn = cross(ta, tb);
    let outside = offset * turn < 0.0 || (turn.abs() <= 1e-7 && dot(ta, tb) < 0.0);
    if !outside {
        return None;
    }
    match corner(a, a.start(), b, offset, mode, false, true) {
        Ok((end, start, mut pieces)) => {
            // Under `G451` two lines meet at a point: the approach ends
            // there, a corner line leads on.
            if planar::distance(end, normal_end(a, offset)) > EPS {
                pieces.insert(0, corner_line(normal_end(a, offset), end, a.end()));
            }
            Some((start, pieces))
        }
        Err(_) => None,
    }
}

/// The circle that touches direction `t` at `at` and passes through
/// `through`, from `at` to `through`; `None` where `through` lies on the
/// tangent (a straight line does).
fn tangent_arc(at: P2, t: P2, through: P2) -> Option<Segment> {
    let n = left(t);
    let chord = planar::sub(at, through);
    let across = dot(n, chord);
    if across.abs() <= 1e-9 * dot(chord, chord).sqrt().max(1.0) {
        return None;
    }
    // The centre on the normal at `at`, as far from `through` as from `at`.
    let lambda = -dot(chord, chord) / (2.0 * across);
    let centre = add(at, scale(n, lambda));
    // Counter-clockwise when the centre is on the left of `t`.
    Some(arc_between(centre, at, through, lambda > 0.0))
}

/// Ends the element at `lead` at `end`; the motions after it without
/// extent in the plane, and the elements left out, keep the tool there.
fn finish_lead<M, O>(stage: &mut PathStage<M, O>, lead: usize, end: P2) {
    if let Some(Held::Element(q)) = stage.held.get_mut(lead)
        && let Some(tool) = &mut q.tool
    {
        tool.end = Some(end);
    }
    for held in stage.held.range_mut(lead + 1..) {
        if let Held::Element(e) = held
            && let Some(tool) = &mut e.tool
            && (e.contour.is_none() || tool.left_out)
        {
            tool.start = Some(end);
            tool.end = Some(end);
            tool.before.clear();
        }
    }
}

/// The corner between the compensated element at `lead` and `b`; with
/// collision detection (`CDON`), an element whose equidistant would run
/// backwards is left out (warning 10763) and the corner is made with the
/// one before it, up to the profile's `cutcom_check_blocks` elements.
/// Returns the element that now leads into the corner, where its
/// equidistant ends, where `b`'s starts, and the pieces between.
fn join_leaving_out<M: Clone, O>(
    stage: &mut PathStage<M, O>,
    lead: usize,
    b: &Segment,
    offset: f64,
    mode: CornerMode,
    detect: bool,
) -> Result<(usize, P2, P2, Vec<Piece>), PathDiagnostic> {
    let mut at = lead;
    let mut left_out = 0;
    loop {
        let Some(Held::Element(q)) = stage.held.get(at) else {
            return Err(collision("no element to join"));
        };
        let Some(a) = q.contour else {
            return Err(collision("no element to join"));
        };
        let approach = q.tool.as_ref().is_some_and(|t| t.approach);
        if approach {
            // Everything after the approach was left out: it ends where
            // `b` starts.
            let start = normal_start(b, offset);
            return Ok((at, start, start, Vec::new()));
        }
        let a_start = q.tool.as_ref().and_then(|t| t.start).unwrap_or(a.start());
        let adjacent = left_out == 0;
        match corner(&a, a_start, b, offset, mode, detect, adjacent) {
            Ok((end, start, pieces)) => return Ok((at, end, start, pieces)),
            Err(CornerFailure::LeadReversed) if detect => {
                if left_out >= stage.max_check_blocks {
                    return Err(collision(format!(
                        "no intersection of the equidistants within {} elements (MD20240 CUTCOM_MAXNUM_CHECK_BLOCKS): the tool cannot follow the contour",
                        stage.max_check_blocks
                    )));
                }
                let previous = stage.held.range(..at).rposition(|h| match h {
                    Held::Element(e) => {
                        e.contour.is_some() && e.tool.as_ref().is_some_and(|t| !t.left_out)
                    }
                    Held::Output(_) => false,
                });
                let Some(previous) = previous else {
                    return Err(collision(
                        "an element is too short for the tool radius and no element before it is held: the tool cannot follow the contour",
                    ));
                };
                if let Some(Held::Element(q)) = stage.held.get_mut(at)
                    && let Some(tool) = &mut q.tool
                {
                    tool.left_out = true;
                }
                left_out += 1;
                at = previous;
            }
            Err(CornerFailure::LeadReversed) => {
                return Err(collision(
                    "an element is too short for the tool radius at an inside corner: the tool would cut into the contour (`CDON` would leave it out)",
                ));
            }
            Err(CornerFailure::Alarm(error)) => return Err(error),
        }
    }
}

/// Why a corner cannot be joined.
#[derive(Debug)]
enum CornerFailure {
    /// The leading element's equidistant would run backwards to it.
    LeadReversed,
    Alarm(PathDiagnostic),
}

/// The corner between `a` (its tool path starting at `a_start`) and `b`
/// on the same side at the same `offset`: where `a`'s equidistant ends,
/// where `b`'s starts, and the pieces between.
fn corner(
    a: &Segment,
    a_start: P2,
    b: &Segment,
    offset: f64,
    mode: CornerMode,
    detect: bool,
    adjacent: bool,
) -> Result<(P2, P2, Vec<Piece>), CornerFailure> {
    let at = a.end();
    if offset.abs() <= EPS {
        return Ok((at, at, Vec::new()));
    }
    let too_small = || {
        collision(
            "the tool radius is larger than the radius of an inside circle: the tool cannot follow the contour",
        )
    };
    let oa = a
        .offset(offset)
        .ok_or_else(too_small)
        .map_err(CornerFailure::Alarm)?;
    let ob = b
        .offset(offset)
        .ok_or_else(too_small)
        .map_err(CornerFailure::Alarm)?;
    let (Some(ta), Some(tb)) = (a.end_tangent(), b.start_tangent()) else {
        return Ok((oa.end(), ob.start(), Vec::new()));
    };
    let turn = cross(ta, tb);
    let along = dot(ta, tb);
    let side = offset.signum();
    if !adjacent {
        // Elements left out between them: the equidistants must meet,
        // whatever the tangents say, or more is left out.
        let near = planar::scale(add(at, b.start()), 0.5);
        return match nearest(&carrier_intersections(&oa, &ob), near) {
            Some(meet) if oa.runs_forward_between(a_start, meet) => Ok((meet, meet, Vec::new())),
            _ if turn.abs() <= 1e-7
                && along > 0.0
                && oa.runs_forward_between(a_start, oa.end()) =>
            {
                // Parallel and the same way (a notch the tool cannot
                // enter): straight on.
                Ok((
                    oa.end(),
                    ob.start(),
                    vec![corner_line(oa.end(), ob.start(), at)],
                ))
            }
            _ => Err(CornerFailure::LeadReversed),
        };
    }
    // Tangent: the equidistants meet, or (a step in curvature) nearly.
    // Where the equidistant ends unchanged (tangent, outside), it must
    // still run forward from where it starts.
    let keeps_end = !(side * turn > 0.0 && !(turn.abs() <= 1e-7 && along > 0.0));
    if keeps_end && !oa.runs_forward_between(a_start, oa.end()) {
        return Err(CornerFailure::LeadReversed);
    }
    if turn.abs() <= 1e-7 && along > 0.0 {
        let mut pieces = Vec::new();
        if planar::distance(oa.end(), ob.start()) > 1e-6 {
            pieces.push(corner_line(oa.end(), ob.start(), at));
        }
        return Ok((oa.end(), ob.start(), pieces));
    }
    if side * turn > 0.0 {
        // Inside: where the equidistants meet, nearest the corner.
        let meet = nearest(&carrier_intersections(&oa, &ob), at).ok_or_else(|| {
            CornerFailure::Alarm(collision(
                "the equidistants of an inside corner do not meet: the tool cannot follow the contour",
            ))
        })?;
        // Under `CDON` the leaving element is checked at its own end.
        if !oa.runs_forward_between(a_start, meet)
            || (!detect && !ob.runs_forward_between(meet, ob.end()))
        {
            return Err(CornerFailure::LeadReversed);
        }
        return Ok((meet, meet, Vec::new()));
    }
    // Outside, or a reversal: round the corner on the tool's side.
    let circle = |pieces: &mut Vec<Piece>| {
        pieces.push(Piece {
            kind: InsertedElement::TransitionCircle,
            path: arc_between(at, oa.end(), ob.start(), side < 0.0),
            corner: at,
        });
    };
    let mut pieces = Vec::new();
    match mode {
        CornerMode::Circle { disc: 0 } => circle(&mut pieces),
        CornerMode::Circle { disc } => {
            match transition_curve(at, oa.end(), ta, ob.start(), tb, disc) {
                Some(curve) => pieces.extend(curve),
                None => circle(&mut pieces),
            }
        }
        CornerMode::Intersection => {
            let lines = matches!(a, Segment::Line { .. }) && matches!(b, Segment::Line { .. });
            match planar::line_line(oa.end(), ta, ob.start(), tb) {
                Some(meet) if lines => return Ok((meet, meet, pieces)),
                Some(meet) => {
                    pieces.push(corner_line(oa.end(), meet, at));
                    pieces.push(corner_line(meet, ob.start(), at));
                }
                None => circle(&mut pieces),
            }
        }
    }
    Ok((oa.end(), ob.start(), pieces))
}

/// Straight pieces in which a `DISC=` transition curve is drawn: the conic
/// from `start` (leaving along `ta`) to `end` (arriving along `tb`) whose
/// control point is where those tangents meet. At `disc` 0 it is the
/// transition circle; its shoulder moves `disc` percent of the way from
/// the circle's middle to the tangents' intersection, which it reaches at
/// 100. `None` where the tangents do not meet (a reversal).
fn transition_curve(
    corner: P2,
    start: P2,
    ta: P2,
    end: P2,
    tb: P2,
    disc: u8,
) -> Option<Vec<Piece>> {
    /// Pieces a curve is drawn in.
    const PIECES: usize = 8;
    let meet = planar::line_line(start, ta, end, tb)?;
    let chord_middle = scale(add(start, end), 0.5);
    // The circle's middle: on the bisector, the radius from the corner.
    let radius = planar::distance(corner, start);
    let towards = planar::unit(planar::sub(meet, corner))?;
    let circle_middle = add(corner, scale(towards, radius));
    let shoulder = add(
        circle_middle,
        scale(
            planar::sub(meet, circle_middle),
            f64::from(disc.min(100)) / 100.0,
        ),
    );
    let to_meet = planar::distance(shoulder, meet);
    if to_meet <= EPS {
        return Some(vec![
            corner_line(start, meet, corner),
            corner_line(meet, end, corner),
        ]);
    }
    // The shoulder of a rational quadratic Bézier of weight w is
    // (chord middle + w · control point) / (1 + w).
    let weight = planar::distance(shoulder, chord_middle) / to_meet;
    let at = |t: f64| {
        let (a, b, c) = ((1.0 - t) * (1.0 - t), 2.0 * weight * t * (1.0 - t), t * t);
        let sum = a + b + c;
        [
            (a * start[0] + b * meet[0] + c * end[0]) / sum,
            (a * start[1] + b * meet[1] + c * end[1]) / sum,
        ]
    };
    let mut pieces = Vec::with_capacity(PIECES);
    let mut from = start;
    for k in 1..=PIECES {
        let to = if k == PIECES {
            end
        } else {
            at(k as f64 / PIECES as f64)
        };
        pieces.push(Piece {
            kind: InsertedElement::TransitionCurve,
            path: Segment::Line {
                start: from,
                end: to,
            },
            corner,
        });
        from = to;
    }
    Some(pieces)
}

fn corner_line(start: P2, end: P2, corner: P2) -> Piece {
    Piece {
        kind: InsertedElement::CornerLine,
        path: Segment::Line { start, end },
        corner,
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
        planar::distance(a, b) < 1e-9
    }

    /// The corner at a 2 mm offset under `G450`, between adjacent elements.
    fn circle_corner(
        a: &Segment,
        a_start: P2,
        b: &Segment,
    ) -> Result<(P2, P2, Vec<Piece>), CornerFailure> {
        corner(
            a,
            a_start,
            b,
            2.0,
            CornerMode::Circle { disc: 0 },
            false,
            true,
        )
    }

    #[test]
    fn a_tangent_arc_touches_its_direction_and_passes_its_point() {
        // Touching +X at the origin, through (10, 10): the quarter circle
        // about (0, 10), counter-clockwise.
        let Some(Segment::Arc {
            centre,
            radius,
            sweep,
            ..
        }) = tangent_arc([0.0, 0.0], [1.0, 0.0], [10.0, 10.0])
        else {
            panic!("an arc")
        };
        assert!(close(centre, [0.0, 10.0]) && (radius - 10.0).abs() < 1e-9);
        assert!((sweep - PI / 2.0).abs() < 1e-9, "{sweep}");
        assert!(tangent_arc([0.0, 0.0], [1.0, 0.0], [10.0, 0.0]).is_none());
    }

    #[test]
    fn an_inside_corner_of_two_lines_meets_at_the_intersection() {
        // A pocket wall: right along Y=0, then up X=10; the tool on the
        // left (G41) is inside the turn.
        let a = line([0.0, 0.0], [10.0, 0.0]);
        let b = line([10.0, 0.0], [10.0, 10.0]);
        let (end, start, pieces) = circle_corner(&a, [0.0, 2.0], &b).unwrap();
        assert!(close(end, [8.0, 2.0]) && close(start, [8.0, 2.0]));
        assert!(pieces.is_empty());
    }

    #[test]
    fn an_outside_corner_gets_a_transition_circle_or_the_intersection() {
        // Right along Y=0, then down: a right turn, G41 outside.
        let a = line([0.0, 0.0], [10.0, 0.0]);
        let b = line([10.0, 0.0], [10.0, -10.0]);
        let (end, start, pieces) = circle_corner(&a, [0.0, 2.0], &b).unwrap();
        assert!(close(end, [10.0, 2.0]) && close(start, [12.0, 0.0]));
        let [piece] = pieces.as_slice() else {
            panic!("{pieces:?}")
        };
        let Segment::Arc { centre, sweep, .. } = piece.path else {
            panic!()
        };
        assert!(close(centre, [10.0, 0.0]));
        assert!(
            (sweep + PI / 2.0).abs() < 1e-9,
            "clockwise round the corner: {sweep}"
        );
        let (end, start, pieces) = corner(
            &a,
            [0.0, 2.0],
            &b,
            2.0,
            CornerMode::Intersection,
            false,
            true,
        )
        .unwrap();
        assert!(close(end, [12.0, 2.0]) && close(start, [12.0, 2.0]) && pieces.is_empty());
    }

    #[test]
    fn a_disc_curve_runs_between_the_circle_and_the_intersection() {
        // Right along Y=0, then down at X=10: the circle's middle is at
        // (10 + √2, √2), the intersection at (12, 2).
        let a = line([0.0, 0.0], [10.0, 0.0]);
        let b = line([10.0, 0.0], [10.0, -10.0]);
        let shoulder = |disc: u8| {
            let (_, _, pieces) = corner(
                &a,
                [0.0, 2.0],
                &b,
                2.0,
                CornerMode::Circle { disc },
                false,
                true,
            )
            .unwrap();
            assert_eq!(pieces.len(), if disc == 100 { 2 } else { 8 });
            assert!(
                pieces
                    .iter()
                    .all(|p| p.kind == InsertedElement::TransitionCurve || disc == 100)
            );
            pieces[pieces.len() / 2 - 1].path.end()
        };
        let root = 2f64.sqrt();
        assert!(close(
            shoulder(1).map(|v| (v * 10.0).round() / 10.0),
            [11.4, 1.4]
        ));
        let half = shoulder(50);
        let expected = [10.0 + root + (2.0 - root) / 2.0, root + (2.0 - root) / 2.0];
        assert!(planar::distance(half, expected) < 1e-9, "{half:?}");
        assert!(close(shoulder(100), [12.0, 2.0]));
    }

    #[test]
    fn an_inside_circle_smaller_than_the_tool_is_an_alarm() {
        let a = line([0.0, 0.0], [10.0, 0.0]);
        // A counter-clockwise circle of radius 1: G41 is inside it.
        let b = Segment::Arc {
            start: [10.0, 0.0],
            end: [10.0, 2.0],
            centre: [10.0, 1.0],
            radius: 1.0,
            sweep: PI,
        };
        let Err(CornerFailure::Alarm(error)) = circle_corner(&a, [0.0, 2.0], &b) else {
            panic!("an alarm")
        };
        assert_eq!(error.code, codes::run::COMPENSATION_COLLISION);
    }

    #[test]
    fn an_element_shorter_than_the_radius_at_inside_corners_is_an_alarm() {
        // Up 1 mm between two inside corners with a 2 mm tool on the left.
        let a = line([0.0, 0.0], [10.0, 0.0]);
        let b = line([10.0, 0.0], [10.0, 1.0]);
        assert!(matches!(
            circle_corner(&a, [9.0, 2.0], &b),
            Err(CornerFailure::LeadReversed)
        ));
    }
}
