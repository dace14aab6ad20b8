//! The channel's side of the path stage (`crate::path`): what it keeps of
//! a motion while the stage holds it, when motions go through the stage,
//! and how released elements become motion events with their figures.

use std::sync::Arc;

use gcodec_ail::{Instruction, Op};
use gcodec_lang::MotionKind;
use gcodec_lang::addresses::TransitionKind;
use gcodec_source::{Code, codes};

use super::Channel;
use super::motion::fill_map;
use crate::event::{BlockRow, Event, EventKind, EventSource, InsertedElement, ToolArc, ToolCentre};
use crate::frames::Frame;
use crate::geometry::{self, BoundingBox, Plane, Point3};
use crate::path::planar::{self, P2, Segment};
use crate::path::{
    Approach, Compensation, CornerElement, CornerMode, Element, Held, PathDiagnostic, Side,
};
use crate::program::Program;
use crate::value::RunError;

/// What the channel keeps of a motion the stage holds.
#[derive(Clone, Debug)]
pub(crate) struct HeldMotion {
    /// The motion event of the programmed contour, source included.
    event: Event,
    place: Placement,
}

/// Where a held motion runs: what its events are computed from.
#[derive(Clone, Debug)]
pub(crate) struct Placement {
    /// Start and end of every axis, workpiece coordinates (mm, radius).
    wcs_start: Vec<f64>,
    wcs_end: Vec<f64>,
    /// The frame the block ran in, for machine coordinates (shared by the
    /// blocks that run in one frame).
    frame: Arc<Frame>,
    /// The channel axes of the plane's abscissa and ordinate.
    plane_axes: [Option<usize>; 2],
    /// The programmed element's length (mm) and time (s): elements made
    /// from it take its time per length.
    length: f64,
    time: f64,
    /// Where the figures of the block's tool are.
    slot: usize,
}

/// What else the channel outputs while the stage holds motions.
#[derive(Debug)]
pub(crate) enum HeldOutput {
    Event(Event),
    Row(BlockRow),
}

pub(crate) type PathStage = crate::path::PathStage<HeldMotion, HeldOutput>;

/// The first block of a contour definition, waiting for its second.
#[derive(Clone, Copy, Debug)]
pub(crate) struct PendingContour {
    /// `ANG=` of the first block, degrees from the plane's abscissa.
    angle: f64,
    /// Where it starts, in the plane.
    start: P2,
    line: u32,
}

impl Channel<'_> {
    /// The compensation in force now.
    fn compensation(&self) -> Compensation {
        let side = match self.state.modal(7) {
            Some("G41") => Some(Side::Left),
            Some("G42") => Some(Side::Right),
            _ => None,
        };
        Compensation {
            side,
            radius: (self.state.tool_radius + self.state.contour.offn).max(0.0),
            corner: match self.state.modal(18) {
                Some("G451") => CornerMode::Intersection,
                _ => CornerMode::Circle {
                    disc: self.state.contour.disc.clamp(0.0, 100.0).round() as u8,
                },
            },
            collision_detection: self.state.modal(23) == Some("CDON"),
            approach: match self.state.modal(17) {
                Some("KONT") => Approach::AroundEnds,
                Some("KONTT" | "KONTC") => Approach::Tangent,
                _ => Approach::Normal,
            },
            tip: self.tip_offset(),
        }
    }

    /// Where a turning tool's theoretical tip lies from the centre of its
    /// nose radius, in the plane's (abscissa, ordinate): by the active
    /// edge's cutting edge position, in the turning plane `G18` (Z, X).
    /// The positions are numbered as ISO's (and LinuxCNC's lathe tool
    /// orientations): 1 tip at +Z −X, 2 at −Z −X, 3 at −Z +X, 4 at +Z +X,
    /// 5 at +Z, 6 at −X, 7 at −Z, 8 at +X, 9 (and 0) at the centre.
    fn tip_offset(&self) -> P2 {
        let r = self.state.tool_radius;
        if self.state.plane() != Plane::G18 || r <= 0.0 {
            return [0.0, 0.0];
        }
        let p = self.state.edge_position;
        let x = match p {
            1 | 2 | 6 => -r,
            3 | 4 | 8 => r,
            _ => 0.0,
        };
        let z = match p {
            2 | 3 | 7 => -r,
            1 | 4 | 5 => r,
            _ => 0.0,
        };
        // G18: the abscissa is Z, the ordinate X.
        [z, x]
    }

    /// The corner element the block programs (`CHF=`, `CHR=`, `RND=`), or
    /// the modal rounding (`RNDM=`).
    pub(super) fn corner_element(
        &self,
        instruction: &Instruction,
    ) -> Result<Option<CornerElement>, RunError> {
        let transition = match &instruction.op {
            Op::Motion {
                details: Some(details),
                ..
            } => details.transition.as_ref(),
            _ => None,
        };
        if let Some(t) = transition {
            let value = self.state.length_in_mm(self.real_of(&t.value)?);
            return Ok(Some(match t.kind {
                TransitionKind::Chamfer => CornerElement::ChamferLength(value),
                TransitionKind::ChamferLeg => CornerElement::ChamferLeg(value),
                TransitionKind::Rounding => CornerElement::Rounding(value),
            }));
        }
        let modal = self.state.contour.rndm;
        Ok((modal > 0.0).then_some(CornerElement::Rounding(modal)))
    }

    /// Whether a motion goes through the stage: it holds something, or
    /// the motion is compensated, has a corner element or begins a
    /// contour definition.
    pub(super) fn path_engaged(&self, corner: Option<CornerElement>) -> bool {
        !self.path.is_idle()
            || corner.is_some()
            || self.motion.begins_contour.is_some()
            || self.state.radius_compensation_selected()
    }

    /// The second block of a contour definition (`X… Y… ANG=α2`, its end
    /// point already in `scratch.target`): the first block's line at its
    /// angle and this one at `angle` meet where the first ends and this
    /// one starts. The held first block gets that end point, and the
    /// channel moves there before this block.
    pub(super) fn complete_contour(&mut self, angle: f64) -> Result<(), RunError> {
        let Some(pending) = self.pending_contour.take() else {
            return Ok(());
        };
        let (h, v, _) = self.state.plane().axes();
        let end = self.state.geometry_point(&self.motion.target);
        let direction = |degrees: f64| {
            let (sin, cos) = degrees.to_radians().sin_cos();
            [cos, sin]
        };
        let corner = planar::line_line(
            pending.start,
            direction(pending.angle),
            [end[h], end[v]],
            direction(angle),
        )
        .ok_or_else(|| {
            RunError::new(
                codes::run::CONTOUR_ANGLE,
                format!(
                    "the lines at `ANG={}` (line {}) and `ANG={angle}` are parallel: the contour's corner is nowhere",
                    pending.angle, pending.line
                ),
            )
        })?;
        let mut wcs = self.motion.wcs.clone();
        let mut machine = vec![0.0; wcs.len()];
        let state = &self.state;
        let frame = state.total_frame().clone();
        let length = planar::distance(pending.start, corner);
        let feed = state.feed;
        self.path
            .complete_pending(|element| {
                let HeldMotion { event, place } = &mut element.motion;
                let mut end = std::mem::take(&mut place.wcs_end);
                place.set_plane(&mut end, corner);
                place.wcs_end = end;
                wcs.copy_from_slice(&place.wcs_end);
                state.to_machine(&frame, &place.wcs_end, &mut machine);
                if let EventKind::Motion(m) = &mut event.kind {
                    fill_map(&mut m.to, state, &place.wcs_end, true);
                    fill_map(&mut m.to_machine, state, &machine, false);
                    let rapid = m.motion == MotionKind::Rapid;
                    place.time += if rapid || feed <= 0.0 {
                        0.0
                    } else {
                        length / feed * 60.0
                    };
                }
                place.length += length;
                element.contour = Some(Segment::Line {
                    start: pending.start,
                    end: corner,
                });
            })
            .map_err(path_error)?;
        self.state.machine.copy_from_slice(&machine);
        self.state.forget_end_point();
        self.motion.wcs.copy_from_slice(&wcs);
        Ok(())
    }

    /// Hands the motion just filled in `self.motion.event` to the stage.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn hold_motion(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        start: Point3,
        end: Point3,
        arc: Option<&geometry::Arc>,
        length: f64,
        time: f64,
        corner: Option<CornerElement>,
    ) -> Result<(), RunError> {
        let plane = self.state.plane();
        let (h, v, n) = plane.axes();
        let flat = |p: Point3| -> P2 { [p[h], p[v]] };
        let contour = match arc {
            // A circle in the plane (an oblique `CIP` circle is taken by
            // its chord).
            Some(a) if a.normal[n] > 0.999 => Segment::Arc {
                start: flat(start),
                end: flat(end),
                centre: flat(a.centre),
                radius: a.radius,
                sweep: a.sweep,
            },
            _ => Segment::Line {
                start: flat(start),
                end: flat(end),
            },
        };
        if contour.is_point() && corner.is_some() && self.motion.begins_contour.is_none() {
            self.not_simulated(program, instruction, "corner-without-plane-motion", || {
                "a chamfer or rounding in a block without motion in the plane inserts nothing"
                    .into()
            });
        }
        let mut plane_axes = [None; 2];
        for (i, info) in self.state.axes.iter().enumerate() {
            match info.geometry {
                Some(g) if g == h => plane_axes[0] = Some(i),
                Some(g) if g == v => plane_axes[1] = Some(i),
                _ => {}
            }
        }
        let slot = {
            self.figures();
            self.figures_slot.unwrap_or_default()
        };
        let frame = {
            let current = self.state.total_frame();
            match &self.path_frame {
                Some(shared) if shared.same_as(&current) => Arc::clone(shared),
                _ => Arc::new(current.clone()),
            }
        };
        self.path_frame = Some(Arc::clone(&frame));
        let motion = HeldMotion {
            event: self.motion.event.clone(),
            place: Placement {
                wcs_start: self.motion.wcs.clone(),
                wcs_end: self.motion.target.clone(),
                frame,
                plane_axes,
                length,
                time,
                slot,
            },
        };
        if !contour.is_point() {
            self.block.moved_in_plane = true;
        }
        let compensation = self.compensation();
        let tip = compensation.tip_in_force();
        let element = Element {
            motion,
            contour: Some(contour),
            compensation,
            corner,
            inserted: None,
            trimmed: false,
            tool: None,
            pending: false,
        };
        if let Some(angle) = self.motion.begins_contour.take() {
            let (h, v, _) = self.state.plane().axes();
            self.pending_contour = Some(PendingContour {
                angle,
                start: [start[h], start[v]],
                line: instruction.source.line,
            });
            self.path.hold_pending(element);
            return Ok(());
        }
        let pushed = self.path.push(element);
        self.report_path_warnings(program, instruction);
        pushed.map_err(path_error)?;
        self.release_path(false);
        self.note_tool_centre(tip);
        Ok(())
    }

    /// Keeps where the tool centre stands now for `$AA_IM` (machine
    /// coordinates: the block's end with the plane's coordinates the
    /// tool centre's, `tip` added).
    fn note_tool_centre(&mut self, tip: P2) {
        let Some(point) = self.path.tool_centre_now() else {
            self.state.tool_centre = None;
            return;
        };
        let (h, v, _) = self.state.plane().axes();
        let mut wcs = self.motion.target.clone();
        for (i, info) in self.state.axes.iter().enumerate() {
            match info.geometry {
                Some(g) if g == h => wcs[i] = point[0] + tip[0],
                Some(g) if g == v => wcs[i] = point[1] + tip[1],
                _ => {}
            }
        }
        let mut machine = self.state.tool_centre.take().unwrap_or_default();
        machine.resize(wcs.len(), 0.0);
        let frame = self.state.total_frame();
        self.state.to_machine(&frame, &wcs, &mut machine);
        drop(frame);
        self.state.tool_centre = Some(machine);
    }

    /// Reports what the stage left out or reduced, at `instruction`.
    fn report_path_warnings(&mut self, program: &Arc<Program>, instruction: &Instruction) {
        for warning in std::mem::take(&mut self.path.warnings) {
            let level = warning.code.level();
            self.diagnostic_at(
                program,
                instruction,
                warning.code,
                level,
                warning.message,
                None,
            );
        }
    }

    /// Sends what the stage has made final; with `finish`, everything
    /// (the program ends).
    pub(super) fn release_path(&mut self, finish: bool) {
        let mut ready = std::mem::take(&mut self.path_ready);
        if finish {
            self.path.finish(&mut ready);
        } else {
            self.path.release(&mut ready);
        }
        for held in ready.drain(..) {
            match held {
                Held::Output(HeldOutput::Event(event)) => self.send_if_taken(&event),
                Held::Output(HeldOutput::Row(mut row)) => {
                    if let Some(tool) = self.last_tool_point.as_ref() {
                        for (i, info) in self.state.axes.iter().enumerate() {
                            if let Some(value) = tool.get(i) {
                                row.positions
                                    .update(&info.name, self.state.as_programmed(i, *value));
                            }
                        }
                    }
                    if let Some(observer) = self.observer.as_mut()
                        && let Err(error) = observer.block(&row)
                    {
                        self.output_error.get_or_insert(error);
                    }
                }
                Held::Element(element) => self.send_element(element),
            }
        }
        // What the end left out, after what it released.
        if finish {
            for warning in std::mem::take(&mut self.path.warnings) {
                let source = self.last_source();
                self.send_diagnostic(warning.code, warning.message, source);
            }
        }
        self.path_ready = ready;
    }

    /// The motion events of a released element: the tool-only pieces
    /// before it, then the element itself.
    fn send_element(&mut self, element: Element<HeldMotion>) {
        let Element {
            motion:
                HeldMotion {
                    event: programmed,
                    place,
                },
            contour,
            compensation,
            inserted,
            trimmed,
            tool,
            ..
        } = element;
        let rate = if place.length > 0.0 {
            place.time / place.length
        } else {
            0.0
        };
        let radius = compensation.radius;
        let offset = compensation.offset();
        let tip = compensation.tip;
        if let Some(track) = &tool {
            for piece in &track.before {
                let mut wcs = place.wcs_start.clone();
                place.set_plane(&mut wcs, piece.corner);
                let mut tool_wcs = wcs.clone();
                place.set_plane(&mut tool_wcs, planar::add(piece.path.end(), tip));
                let mut event = self.event_like(&programmed);
                self.fill_element_event(
                    &mut event,
                    &place,
                    (&wcs, &wcs),
                    &piece.path,
                    Some(piece.kind),
                    Some((&tool_wcs, radius)),
                );
                let length = piece.path.length();
                let path = piece.path.translated(tip);
                self.add_element_figures(&place, &event, length, length * rate, &path, &tool_wcs);
                self.last_tool_point = Some(tool_wcs);
                self.send_if_taken(&event);
                self.path_event = Some(event);
            }
        }
        let Some(contour) = contour else {
            // No motion in the plane: as programmed, the tool where it is.
            let mut event = self.event_like(&programmed);
            if let Some(point) = tool.as_ref().and_then(|t| t.end) {
                let mut tool_wcs = place.wcs_end.clone();
                place.set_plane(&mut tool_wcs, planar::add(point, tip));
                self.attach_tool(&mut event, &place, &tool_wcs, radius);
                self.last_tool_point = Some(tool_wcs);
            } else {
                if let EventKind::Motion(m) = &mut event.kind {
                    m.tool = None;
                }
                self.last_tool_point = None;
            }
            let line = Segment::Line {
                start: [0.0; 2],
                end: [0.0; 2],
            };
            let end = place.wcs_end.clone();
            self.add_element_figures(&place, &event, place.length, place.time, &line, &end);
            self.send_if_taken(&event);
            self.path_event = Some(event);
            return;
        };
        let mut wcs_start = place.wcs_start.clone();
        let mut wcs_end = place.wcs_end.clone();
        if trimmed || inserted.is_some() {
            place.set_plane_along(&mut wcs_start, contour.start());
            place.set_plane_along(&mut wcs_end, contour.end());
        }
        // The retraction ends uncompensated: the tip on the programmed
        // point.
        let end_tip = compensation.tip_in_force();
        let traversed = match tool.as_ref() {
            Some(t) => tool_path(&contour, t, offset).translated(end_tip),
            None => contour,
        };
        let mut tool_wcs = None;
        if let Some(end) = tool.as_ref().and_then(|t| t.end) {
            let mut wcs = wcs_end.clone();
            place.set_plane(&mut wcs, planar::add(end, end_tip));
            tool_wcs = Some(wcs);
        }
        let mut event = self.event_like(&programmed);
        self.fill_element_event(
            &mut event,
            &place,
            (&wcs_start, &wcs_end),
            &contour,
            inserted,
            tool_wcs.as_deref().map(|w| (w, radius)),
        );
        // A tangential approach or retraction: the tool centre's circle.
        if let Some(crate::path::ToolTrack {
            curve:
                Some(Segment::Arc {
                    centre,
                    radius: arc_radius,
                    sweep,
                    ..
                }),
            ..
        }) = &tool
            && let EventKind::Motion(m) = &mut event.kind
            && let Some(tool_centre) = m.tool.as_mut()
        {
            let mut map = crate::event::AxisMap::default();
            place.fill_plane_map(&mut map, &self.state, planar::add(*centre, end_tip));
            tool_centre.tool_arc = Some(ToolArc {
                motion: arc_kind(*sweep),
                centre: map,
                radius: self.state.length_as_programmed(*arc_radius),
            });
        }
        // Off the plane (an infeed with the element), as programmed.
        let rise = place.off_plane_travel(&wcs_start, &wcs_end);
        let planar_length = traversed.length();
        let length = planar_length.hypot(rise);
        let contour_length = contour.length().hypot(rise);
        let time = if trimmed || inserted.is_some() || tool.is_some() {
            if contour_length > 0.0 && place.length > 0.0 {
                length * rate
            } else {
                place.time
            }
        } else {
            place.time
        };
        let end_point = tool_wcs.clone().unwrap_or_else(|| wcs_end.clone());
        self.add_element_figures(&place, &event, length, time, &traversed, &end_point);
        self.last_tool_point = tool_wcs;
        self.send_if_taken(&event);
        let source = event.source.clone();
        self.path_event = Some(event);
        if tool.as_ref().is_some_and(|t| t.left_out) {
            self.send_diagnostic(
                codes::run::COMPENSATION_BLOCK_LEFT_OUT,
                "`CDON` leaves this block out: its equidistant would run backwards between its neighbours'; the tool centre stands still".into(),
                source,
            );
        }
    }

    /// Sends a diagnostic at its own level from `source`, counted, past
    /// the stage (what it is about is released already).
    fn send_diagnostic(&mut self, code: &'static Code, message: String, source: EventSource) {
        self.count(code.level());
        let event = Event {
            kind: EventKind::Diagnostic(crate::event::DiagnosticEvent::new(code, message)),
            source,
        };
        super::send(&mut *self.sink, &mut self.output_error, &event);
    }

    /// An event to fill for an element of `programmed`: the stage's
    /// reused one made equal to it (no allocation once its maps have
    /// their size), or a copy the first time. Its tool fields are left
    /// from before, for the caller to refill or clear.
    fn event_like(&mut self, programmed: &Event) -> Event {
        match self.path_event.take() {
            Some(mut event) => {
                if let (EventKind::Motion(target), EventKind::Motion(source)) =
                    (&mut event.kind, &programmed.kind)
                {
                    target.copy_from(source);
                    event.source.clone_from(&programmed.source);
                    return event;
                }
                programmed.clone()
            }
            None => programmed.clone(),
        }
    }

    /// Refills `event` for an element from `from` to `to` (workpiece
    /// coordinates) along `path`, as inserted, with the tool centre.
    fn fill_element_event(
        &self,
        event: &mut Event,
        place: &Placement,
        (from, to): (&[f64], &[f64]),
        path: &Segment,
        inserted: Option<InsertedElement>,
        tool: Option<(&[f64], f64)>,
    ) {
        let state = &self.state;
        let mut machine = vec![0.0; to.len()];
        state.to_machine(&place.frame, to, &mut machine);
        let EventKind::Motion(m) = &mut event.kind else {
            return;
        };
        fill_map(&mut m.from, state, from, true);
        fill_map(&mut m.to, state, to, true);
        fill_map(&mut m.to_machine, state, &machine, false);
        m.inserted = inserted;
        match (inserted, path) {
            (
                Some(InsertedElement::Rounding | InsertedElement::TransitionCircle),
                Segment::Arc {
                    centre,
                    radius,
                    sweep,
                    ..
                },
            ) => {
                m.motion = arc_kind(*sweep);
                let mut map = m.centre.take().unwrap_or_default();
                place.fill_plane_map(&mut map, state, *centre);
                m.centre = Some(map);
                m.radius = Some(state.length_as_programmed(*radius));
                m.turns = 0;
            }
            (
                Some(
                    InsertedElement::Chamfer
                    | InsertedElement::CornerLine
                    | InsertedElement::TransitionCurve,
                ),
                _,
            ) => {
                if m.motion != MotionKind::Rapid {
                    m.motion = MotionKind::Linear;
                }
                m.centre = None;
                m.radius = None;
                m.turns = 0;
            }
            _ => {}
        }
        match tool {
            Some((tool_wcs, radius)) => self.attach_tool(event, place, tool_wcs, radius),
            None => {
                if let EventKind::Motion(m) = &mut event.kind {
                    m.tool = None;
                }
            }
        }
    }

    fn attach_tool(&self, event: &mut Event, place: &Placement, tool_wcs: &[f64], radius: f64) {
        let state = &self.state;
        let mut machine = vec![0.0; tool_wcs.len()];
        state.to_machine(&place.frame, tool_wcs, &mut machine);
        let EventKind::Motion(m) = &mut event.kind else {
            return;
        };
        let mut centre = m.tool.take().unwrap_or_else(|| {
            Box::new(ToolCentre {
                tool_to: Default::default(),
                tool_to_machine: Default::default(),
                tool_radius: 0.0,
                tool_arc: None,
            })
        });
        centre.tool_arc = None;
        fill_map(&mut centre.tool_to, state, tool_wcs, true);
        fill_map(&mut centre.tool_to_machine, state, &machine, false);
        centre.tool_radius = state.length_as_programmed(radius);
        m.tool = Some(centre);
    }

    /// The figures of a released element: its length, time and extent.
    fn add_element_figures(
        &mut self,
        place: &Placement,
        event: &Event,
        length: f64,
        time: f64,
        path: &Segment,
        end: &[f64],
    ) {
        let rapid = matches!(&event.kind, EventKind::Motion(m) if m.motion == MotionKind::Rapid);
        let base = self.state.geometry_point(end);
        let mut extent = BoundingBox::point(base);
        if !path.is_point() {
            let (h, v, _) = self.state.plane().axes();
            for p in extent_points(path) {
                let mut q = base;
                q[h] = p[0];
                q[v] = p[1];
                extent.include(q);
            }
        }
        self.summary
            .at(place.slot)
            .add_motion(rapid, length, time, extent);
    }

    /// Holds `event` if the stage holds motions before it; else sends it.
    pub(super) fn emit_in_order(&mut self, event: &Event) {
        if self.path.is_idle() {
            super::send(&mut *self.sink, &mut self.output_error, event);
        } else {
            self.path.hold_output(HeldOutput::Event(event.clone()));
        }
    }

    /// Holds the block's CSV row if the stage holds motions before it.
    /// `false`: write it now.
    pub(super) fn hold_row(&mut self) -> bool {
        if self.path.is_idle() {
            return false;
        }
        self.path.hold_output(HeldOutput::Row(self.row.clone()));
        true
    }

    /// The end of a block for the stage: too many blocks without motion
    /// in the plane under compensation is an alarm at the next block.
    pub(super) fn path_block_ended(&mut self) {
        if self.path.is_idle() {
            return;
        }
        if let Err(error) = self.path.block_ended(self.block.moved_in_plane) {
            self.path_alarm.get_or_insert(path_error(error));
        }
    }
}

fn path_error(error: PathDiagnostic) -> RunError {
    RunError::new(error.code, error.message)
}

impl Placement {
    /// Refills `map` with plane point `p` (mm) on the plane's two axes, as
    /// the program writes them.
    fn fill_plane_map(&self, map: &mut crate::event::AxisMap, state: &super::MachineState, p: P2) {
        map.clear();
        for (k, axis) in self.plane_axes.iter().enumerate() {
            if let Some(i) = axis {
                map.insert(state.axes[*i].name.clone(), state.as_programmed(*i, p[k]));
            }
        }
    }

    /// Puts plane point `p` into the plane axes of `wcs`.
    fn set_plane(&self, wcs: &mut [f64], p: P2) {
        for (k, axis) in self.plane_axes.iter().enumerate() {
            if let Some(i) = axis {
                wcs[*i] = p[k];
            }
        }
    }

    /// Puts plane point `p`, a point of the element, into `wcs`, the other
    /// axes where the element is at `p` (linearly between its ends).
    fn set_plane_along(&self, wcs: &mut [f64], p: P2) {
        let (Some(h), Some(v)) = (self.plane_axes[0], self.plane_axes[1]) else {
            return;
        };
        let a = [self.wcs_start[h], self.wcs_start[v]];
        let b = [self.wcs_end[h], self.wcs_end[v]];
        let total = planar::distance(a, b);
        let t = if total > planar::EPS {
            (planar::distance(a, p) / total).clamp(0.0, 1.0)
        } else {
            0.0
        };
        for (i, slot) in wcs.iter_mut().enumerate() {
            if i != h && i != v {
                *slot = self.wcs_start[i] + t * (self.wcs_end[i] - self.wcs_start[i]);
            }
        }
        wcs[h] = p[0];
        wcs[v] = p[1];
    }

    /// The travel of the linear axes outside the plane between `a` and
    /// `b`.
    fn off_plane_travel(&self, a: &[f64], b: &[f64]) -> f64 {
        let mut sum = 0.0;
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            if Some(i) != self.plane_axes[0] && Some(i) != self.plane_axes[1] {
                sum += (y - x) * (y - x);
            }
        }
        sum.sqrt()
    }
}

/// The tool centre's path along `contour` from the track's start to its
/// end: a straight line for the approach and retraction, else the
/// equidistant between them.
fn tool_path(contour: &Segment, track: &crate::path::ToolTrack, offset: f64) -> Segment {
    if let Some(curve) = track.curve {
        return curve;
    }
    let start = track.start.unwrap_or(contour.start());
    let end = track.end.unwrap_or(contour.end());
    if track.approach || matches!(contour, Segment::Line { .. }) {
        return Segment::Line { start, end };
    }
    match contour.offset(offset) {
        Some(equidistant) => equidistant.with_ends(start, end),
        None => Segment::Line { start, end },
    }
}

/// The motion kind of a circle of signed `sweep` (positive
/// counter-clockwise).
fn arc_kind(sweep: f64) -> MotionKind {
    if sweep >= 0.0 {
        MotionKind::ArcCcw
    } else {
        MotionKind::ArcCw
    }
}

/// Points that bound `path`: its ends and, for an arc, the extremes of
/// its circle that it passes.
fn extent_points(path: &Segment) -> Vec<P2> {
    let mut points = vec![path.start(), path.end()];
    if let Segment::Arc {
        centre,
        radius,
        sweep,
        start,
        ..
    } = *path
    {
        let a0 = planar::angle(planar::sub(start, centre));
        for k in 0..4 {
            let target = f64::from(k) * std::f64::consts::FRAC_PI_2;
            let delta = if sweep >= 0.0 {
                (target - a0).rem_euclid(std::f64::consts::TAU)
            } else {
                (a0 - target).rem_euclid(std::f64::consts::TAU)
            };
            if delta <= sweep.abs() {
                points.push([
                    centre[0] + radius * target.cos(),
                    centre[1] + radius * target.sin(),
                ]);
            }
        }
    }
    points
}
