//! Traversing blocks: end points from the programmed values (G90/G91,
//! `AC`/`IC`, units, diameter programming), arcs and helices, frames, the
//! tool length offset, the motion event and the figures of the summary.

use std::borrow::Cow;
use std::sync::Arc;

use gcodec_ail::{AxisValue, Circle, Instruction, Op, Value};
use gcodec_lang::motion::MOTION_GROUP;
use gcodec_lang::{DimensionMode, MotionKind};
use gcodec_source::{Severity, codes};

use super::Channel;
use crate::eval;
use crate::event::{AxisMap, Event, EventKind, MotionEvent, Plane, WorkOffsetContext};
use crate::frames::{identity_inward_as_is, identity_outward};
use crate::geometry::{self, ArcForm, BoundingBox, Direction, Point3};
use crate::program::Program;
use crate::value::{RtValue, RunError, finite_real};

use super::polar::{ContourAngle, PolarWords};
use super::state::MachineState;

/// Buffers reused by every motion, so that a traversing block allocates
/// nothing.
pub(super) struct MotionScratch {
    /// The start point in workpiece coordinates (mm, radius).
    pub wcs: Vec<f64>,
    /// Where incremental values count from: `wcs`, or after a change of
    /// the frame the position in the frame it was programmed in
    /// (SD42440, [`Channel::increment_start`]).
    increment_start: Vec<f64>,
    pub(super) target: Vec<f64>,
    pub(super) machine: Vec<f64>,
    pub(super) event: Event,
    /// The end tangent of the last path element (for `CT`).
    last_tangent: Option<Point3>,
    /// The block begins a contour definition at this angle (`ANG=` with
    /// no end point in the plane).
    pub(super) begins_contour: Option<f64>,
    /// Positions are taken as they are where no frame or tool length
    /// changes them ([`super::RunOptions::direct_motions`]).
    direct: bool,
    /// The motion being made goes to the machine position of its end
    /// point as it is (a plain state, [`Channel::direct_straight_motion`]):
    /// the machine position is the workpiece position after it, and no
    /// end point need be kept ([`MachineState::keep_end_point`]). Taken by
    /// [`Channel::finish_motion`].
    end_is_machine: bool,
}

impl MotionScratch {
    pub fn new(state: &MachineState, direct: bool) -> Self {
        let n = state.axes.len();
        let map = || AxisMap::with_capacity(n);
        Self {
            wcs: vec![0.0; n],
            increment_start: vec![0.0; n],
            target: vec![0.0; n],
            machine: vec![0.0; n],
            event: Event {
                kind: EventKind::Motion(MotionEvent {
                    motion: MotionKind::Linear,
                    from: map(),
                    to: map(),
                    to_machine: map(),
                    centre: None,
                    radius: None,
                    turns: 0,
                    feed: None,
                    feed_mode: Cow::Borrowed("G94"),
                    plane: Plane::G17,
                    work_offset: WorkOffsetContext::default(),
                    inserted: None,
                    tool: None,
                }),
                source: crate::event::EventSource {
                    file: Arc::from(""),
                    line: 0,
                    col: 0,
                    level: 0,
                },
            },
            last_tangent: None,
            begins_contour: None,
            direct,
            end_is_machine: false,
        }
    }

    /// Fills `wcs` with the current position in workpiece coordinates
    /// ([`MachineState::workpiece_position`]): the machine position as it
    /// is where no frame or tool length changes it.
    pub fn workpiece_position(&mut self, state: &MachineState) {
        // Where the machine position is taken as it is, a kept end point
        // says the same: a motion keeps `0 + v`, and an identity frame
        // put the machine at `0 + v` too.
        let frame = state.total_frame();
        let as_is = self.direct && state.workpiece_is_machine_in(&frame);
        if !(as_is && identity_inward_as_is(&state.machine, &mut self.wcs)) {
            state.workpiece_position(&frame, &mut self.wcs);
        }
    }
}

impl Channel<'_> {
    pub(super) fn motion(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
    ) -> Result<(), RunError> {
        let Op::Motion {
            motion,
            targets,
            circle,
            details,
        } = &instruction.op
        else {
            return Ok(());
        };
        let kind = self
            .state
            .modal_index(MOTION_GROUP)
            .and_then(|index| MotionKind::of_command(MOTION_GROUP, index))
            .unwrap_or(*motion);
        if matches!(
            kind,
            MotionKind::ThreadIncreasingLead | MotionKind::ThreadDecreasingLead
        ) {
            self.lead_change_was_fed();
        }
        if circle.is_none() && details.is_none() && self.direct_straight_motion(kind, targets) {
            return self.finish_direct_straight_motion(program, instruction, kind);
        }
        self.motion.workpiece_position(&self.state);
        self.motion.target.copy_from_slice(&self.motion.wcs);
        self.increment_start();
        let plane = self.state.plane();
        let (h, v, _) = plane.axes();
        let mut polar = PolarWords::default();
        let mut written = (false, false);
        for target in targets {
            if polar.take(target) {
                continue;
            }
            let axis = self.axis(&target.axis)?;
            self.set_target(axis, &target.value, target.mode)?;
            match self.state.axes[axis].geometry {
                Some(g) if g == h => written.0 = true,
                Some(g) if g == v => written.1 = true,
                _ => {}
            }
        }
        if let Some(details) = details {
            for target in &details.indirect_targets {
                let name = eval::eval(&self.env(), &target.axis)?;
                let name = match name {
                    RtValue::Axis(a) | RtValue::String(a) => a,
                    v => {
                        return Err(RunError::new(
                            codes::run::TYPE_MISMATCH,
                            format!("a {} value names no axis", v.type_name()),
                        ));
                    }
                };
                let axis = self.axis(&name)?;
                self.set_target(axis, &target.value, target.mode)?;
            }
            if details.spline.is_some() {
                self.not_simulated(program, instruction, "motion-details", || "spline weights (`PW`, `PL`) are not simulated: the path is the programmed element".into());
            }
        }
        let mut start = self.state.geometry_point(&self.motion.wcs);
        let contour_error =
            |message: &str| Err(RunError::new(codes::run::CONTOUR_ANGLE, message.to_owned()));
        let pole = if polar.is_polar() {
            if self.pending_contour.take().is_some() {
                self.path.abandon_pending();
                return contour_error(
                    "the block after `ANG=` without an end point must end the contour: `X… Y… ANG=…` in Cartesian coordinates",
                );
            }
            Some(self.polar_end_point(&polar, plane, written)?)
        } else {
            let step = self.contour_angle_end_point(&polar, plane, written, start)?;
            match (step, self.pending_contour.is_some()) {
                (ContourAngle::Ends(angle), true) if kind_is_straight(kind) => {
                    self.complete_contour(angle)?;
                    start = self.state.geometry_point(&self.motion.wcs);
                }
                (_, true) => {
                    self.pending_contour = None;
                    self.path.abandon_pending();
                    return contour_error(
                        "the block after `ANG=` without an end point must end the contour: a straight block with both coordinates of the plane and its own `ANG=`",
                    );
                }
                (ContourAngle::Begins(angle), false) => {
                    if !kind_is_straight(kind) {
                        return contour_error(
                            "a contour definition by `ANG=` is made of straight blocks (`G0`, `G1`)",
                        );
                    }
                    self.motion.begins_contour = Some(angle);
                }
                (ContourAngle::Ends(angle), false) => {
                    return Err(RunError::new(
                        codes::run::CONTOUR_ANGLE,
                        format!(
                            "`ANG={angle}` with both coordinates of the plane: the end point fixes the line already, and no contour definition was begun"
                        ),
                    ));
                }
                (ContourAngle::None, false) => {}
            }
            None
        };
        self.warn_if_no_feed(program, instruction, kind);
        let mut end = self.state.geometry_point(&self.motion.target);
        let is_arc = matches!(
            kind,
            MotionKind::ArcCw
                | MotionKind::ArcCcw
                | MotionKind::ArcThroughPoint
                | MotionKind::ArcTangential
        );
        let mut arc = None;
        // `TURN=` as programmed (`resolve_arc` accepted it: 0…999, whole).
        let mut arc_turns = 0;
        if is_arc {
            let (resolved, turns) = self.arc(kind, plane, start, end, circle.as_deref(), pole)?;
            arc_turns = turns;
            // `AR=` with a centre computes the end point in the plane.
            end = resolved.end;
            for (i, info) in self.state.axes.iter().enumerate() {
                if let Some(g) = info.geometry {
                    self.motion.target[i] = end[g];
                }
            }
            arc = Some(resolved);
        } else if !matches!(kind, MotionKind::Rapid | MotionKind::Linear) {
            let modal = self.state.modal(1);
            self.not_simulated(program, instruction, kind_key(kind), || {
                format!(
                    "`{}` motions are simulated as straight lines to their end points",
                    modal.unwrap_or("this")
                )
            });
        }
        {
            let frame = self.state.total_frame();
            let scratch = &mut self.motion;
            self.state
                .to_machine(&frame, &scratch.target, &mut scratch.machine);
        }
        self.state.note_traversed_frame();
        self.finish_motion(program, instruction, kind, start, end, arc, arc_turns)
    }

    /// A `G34`/`G35` motion: an `F` its block ran as a feed was the change
    /// of the thread lead (lowering gives it as a feed where it cannot
    /// know the block's motion command: paths meet there). The feed goes
    /// back to what it was before the block; the lead change itself is
    /// not simulated (SPEC §11.4).
    fn lead_change_was_fed(&mut self) {
        if let Some(feed) = self.block.feed_before_f.take() {
            self.state.feed = feed;
        }
    }

    /// Sets up a straight motion (`G0`, `G1`) to constant end points the
    /// direct way, in a plain state
    /// ([`super::state::MachineState::positions_plain`]: the workpiece
    /// position is the machine position, the machine end point the end
    /// point) or in the frame the last motion ran in
    /// ([`super::state::MachineState::frame_as_traversed`]: a work offset,
    /// mostly; both go through the frame's arithmetic as the general
    /// path's do): the end point the programmed values, with none of the
    /// general path's evaluation, increments across a frame change, polar
    /// or contour-angle words. `false`, with nothing of
    /// the channel changed but the motion's scratch buffers, when the
    /// block or the state is not such a motion: the general path runs it,
    /// and says what is wrong with it. Both paths give the same events and
    /// summary, bit for bit (`tests/direct_motions.rs`).
    fn direct_straight_motion(&mut self, kind: MotionKind, targets: &[AxisValue]) -> bool {
        let state = &self.state;
        if !self.options.direct_motions
            || !kind_is_straight(kind)
            || self.pending_contour.is_some()
            || state.frame_axes.len() != state.machine.len()
        {
            return false;
        }
        // The motion runs in the frame the last one ran in, fetched once:
        // in a plain state the positions are the machine's as they are;
        // otherwise (a work offset, mostly) they go through the frame's
        // arithmetic as the general path's do.
        let frame = state.total_frame();
        if !state.frame_as_traversed(&frame) {
            return false;
        }
        let plain = state.workpiece_is_machine_in(&frame);
        if plain {
            if !identity_inward_as_is(&state.machine, &mut self.motion.wcs) {
                return false;
            }
        } else {
            // The frame changes values or a tool length acts: the
            // workpiece position is the last end point or the frame's
            // image of the machine's.
            state.workpiece_position_in_traversed_frame(&frame, &mut self.motion.wcs);
        }
        let scratch = &mut self.motion;
        scratch.target.copy_from_slice(&scratch.wcs);
        // Under G71 and G90 a value is the end point itself on a linear
        // axis that reads no diameters ([`Self::dimension`]).
        let as_written = !state.inch() && !state.incremental();
        for target in targets {
            // A single letter names an axis, never a polar word (`AP`,
            // `RP`, `ANG`).
            let (Some(value), [_]) = (target.plain_constant(), target.axis.as_bytes()) else {
                return false;
            };
            let Some(axis) = self.state.axis_index(&target.axis) else {
                return false;
            };
            let info = &self.state.axes[axis];
            let start = self.motion.wcs[axis];
            let end = if as_written && !info.rotary && !info.diameter {
                value
            } else {
                self.dimension(axis, value, None, start, start)
            };
            if !end.is_finite() {
                return false;
            }
            self.motion.target[axis] = end;
        }
        let scratch = &mut self.motion;
        if plain {
            identity_outward(&scratch.target, &mut scratch.machine);
            scratch.end_is_machine = true;
        } else {
            self.state
                .to_machine(&frame, &scratch.target, &mut scratch.machine);
        }
        true
    }

    /// The rest of a motion [`Self::direct_straight_motion`] set up.
    fn finish_direct_straight_motion(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        kind: MotionKind,
    ) -> Result<(), RunError> {
        self.warn_if_no_feed(program, instruction, kind);
        let start = self.state.geometry_point(&self.motion.wcs);
        let end = self.state.geometry_point(&self.motion.target);
        // The motion runs in the frame the last one ran in
        // (`positions_plain`, `frame_as_traversed`): no frame to note.
        self.finish_motion(program, instruction, kind, start, end, None, 0)
    }

    /// A feed motion without a feed: warned of once.
    #[inline]
    fn warn_if_no_feed(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        kind: MotionKind,
    ) {
        if kind != MotionKind::Rapid && self.state.feed <= 0.0 {
            self.once(program, instruction, "no-feed", codes::run::NO_FEED, Severity::Warning, || "a feed motion without a feed (`F`): the control stops with alarm 10860; the simulation goes on without a time for it".into());
        }
    }

    /// The motion from `scratch.wcs` (the start point `start`) to
    /// `scratch.target` (`end`; in machine coordinates `scratch.machine`),
    /// along `arc` if one: the summary's figures, the end tangent, the
    /// event, the new position. The caller notes the frame the motion
    /// runs in (`note_traversed_frame`) where it may have changed.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn finish_motion(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        kind: MotionKind,
        start: Point3,
        end: Point3,
        arc: Option<geometry::Arc>,
        arc_turns: u32,
    ) -> Result<(), RunError> {
        // Taken first: no later motion may find it set.
        let end_is_machine = std::mem::take(&mut self.motion.end_is_machine);
        let length = match &arc {
            Some(a) => a.length,
            None => distance(start, end),
        };
        let time = self.motion_time(kind, length);
        self.motion.last_tangent = match &arc {
            Some(a) => {
                let p = a.point_at(1.0);
                let q = a.point_at(1.0 - 1e-6);
                Some([p[0] - q[0], p[1] - q[1], p[2] - q[2]])
            }
            None if length > 0.0 => Some([end[0] - start[0], end[1] - start[1], end[2] - start[2]]),
            None => self.motion.last_tangent,
        };
        self.block.had_motion = true;
        let corner = self.corner_element(instruction)?;
        let engaged = self.path_engaged(corner);
        // The stage holds the event; a sink that takes no motions (the
        // CSV's) needs none built.
        if engaged || self.sink_takes_motions {
            self.fill_motion_event(program, instruction, kind, arc.as_ref(), arc_turns);
        }
        // The channel is at the programmed end point, held or not.
        self.state.machine.copy_from_slice(&self.motion.machine);
        if engaged {
            // Compensation or a corner element: the stage holds the
            // motion until the next element makes it final, and may move
            // the machine to a corner of the tool-centre path.
            self.state.forget_end_point();
            return self.hold_motion(
                program,
                instruction,
                start,
                end,
                arc.as_ref(),
                length,
                time,
                corner,
            );
        }
        if end_is_machine {
            // The machine position is the workpiece position as it is.
            self.state.forget_end_point();
        } else {
            self.state.keep_end_point(&self.motion.target);
        }
        let extent = match &arc {
            Some(a) => a.bounding_box(),
            // The end point only: a start point is the previous end, or a
            // position from before a frame or offset change, which is no
            // point of the part in this frame.
            None => BoundingBox::point(end),
        };
        self.figures()
            .add_motion(kind == MotionKind::Rapid, length, time, extent);
        super::send_if_taken(
            &mut *self.sink,
            self.sink_takes_motions,
            &mut self.output_error,
            &self.motion.event,
        );
        Ok(())
    }

    /// Fills the scratch motion event from `scratch.wcs` to
    /// `scratch.target` (`scratch.machine`), along `arc` if one.
    fn fill_motion_event(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        kind: MotionKind,
        arc: Option<&geometry::Arc>,
        arc_turns: u32,
    ) {
        let level = self.program_level();
        let state = &self.state;
        let scratch = &mut self.motion;
        // In place: the file mostly stays, and counting a reference to it
        // and dropping one, every motion, costs more than the rest.
        let source = &mut scratch.event.source;
        super::keep_file(&mut source.file, &program.file);
        source.line = instruction.source.line;
        source.col = instruction.source.col;
        source.level = level;
        if let EventKind::Motion(event) = &mut scratch.event.kind {
            event.motion = kind;
            fill_map(&mut event.from, state, &scratch.wcs, true);
            fill_map(&mut event.to, state, &scratch.target, true);
            fill_map(&mut event.to_machine, state, &scratch.machine, false);
            match arc {
                Some(a) => {
                    let mut centre = event.centre.take().unwrap_or_default();
                    centre.clear();
                    let (h, v, _) = state.plane().axes();
                    for (i, info) in state.axes.iter().enumerate() {
                        if let Some(g) = info.geometry
                            && (g == h || g == v)
                        {
                            centre.insert(info.name.clone(), state.as_programmed(i, a.centre[g]));
                        }
                    }
                    event.centre = Some(centre);
                    event.radius = Some(state.length_as_programmed(a.radius));
                    event.turns = arc_turns;
                }
                None => {
                    event.centre = None;
                    event.radius = None;
                    event.turns = 0;
                }
            }
            event.feed = (kind != MotionKind::Rapid).then_some(state.feed);
            event.feed_mode = Cow::Borrowed(state.modal(15).unwrap_or("G94"));
            event.plane = state.plane();
            event.work_offset = WorkOffsetContext::new(state.group8, state.suppression);
            event.inserted = None;
            if event.tool.is_some() {
                event.tool = None;
            }
        }
    }

    /// Where incremental values count from (SD42440,
    /// `incremental_traverses_offset_change`): after a change of the
    /// frame, the position in the frame the last motion ran in, so that
    /// the change is traversed; otherwise (and in a block whose frames are
    /// suppressed) the position in this frame.
    fn increment_start(&mut self) {
        let state = &self.state;
        let scratch = &mut self.motion;
        match &state.traversed_frame {
            Some(before)
                if state
                    .profile
                    .work_offsets
                    .incremental_traverses_offset_change
                    && state.suppression.is_none()
                    && !before.same_as(&state.total_frame()) =>
            {
                state.to_workpiece(before, &state.machine, &mut scratch.increment_start)
            }
            _ => scratch.increment_start.copy_from_slice(&scratch.wcs),
        }
    }

    pub(super) fn axis(&self, name: &str) -> Result<usize, RunError> {
        self.state.axis_index(name).ok_or_else(|| {
            RunError::new(
                codes::run::UNKNOWN_AXIS,
                format!("the machine has no axis `{name}`"),
            )
        })
    }

    /// Converts a programmed value to mm (radius) in workpiece
    /// coordinates: units, diameter programming, absolute or incremental.
    fn set_target(
        &mut self,
        axis: usize,
        value: &Value,
        mode: Option<DimensionMode>,
    ) -> Result<(), RunError> {
        let value = self.real_of(value)?;
        let start = self.motion.wcs[axis];
        let increment_start = self.motion.increment_start[axis];
        let target = self.dimension(axis, value, mode, start, increment_start);
        // An increment, inch or unit conversion can overflow too.
        self.motion.target[axis] = finite_real(target, || {
            format!("the position on `{}`", self.state.axes[axis].name)
        })?;
        Ok(())
    }

    /// `value` on `axis` as an absolute workpiece coordinate (mm, radius):
    /// an increment counts from `increment_start`, a rotary position from
    /// `start`.
    fn dimension(
        &self,
        axis: usize,
        value: f64,
        mode: Option<DimensionMode>,
        start: f64,
        increment_start: f64,
    ) -> f64 {
        use DimensionMode as M;
        let info = &self.state.axes[axis];
        let mut v = value;
        if !info.rotary && self.state.inch() {
            v *= 25.4;
        }
        let incremental = match mode {
            Some(M::Ic | M::Cic | M::Dic | M::Ric) => true,
            Some(_) => false,
            None => self.state.incremental(),
        };
        if info.diameter {
            let (absolute_diameter, incremental_diameter) = self.state.diameter_mode();
            let diameter = match mode {
                Some(M::Dac | M::Dic) => true,
                Some(M::Rac | M::Ric) => false,
                _ if incremental => incremental_diameter,
                _ => absolute_diameter,
            };
            if diameter {
                v /= 2.0;
            }
        }
        if incremental {
            return increment_start + v;
        }
        if info.rotary {
            let delta = (v - start).rem_euclid(360.0);
            return match mode {
                Some(M::Dc | M::Cdc) => start + if delta > 180.0 { delta - 360.0 } else { delta },
                Some(M::Acp | M::Cacp) => start + delta,
                Some(M::Acn | M::Cacn) => start + if delta == 0.0 { 0.0 } else { delta - 360.0 },
                _ => v,
            };
        }
        v
    }

    /// Resolves the arc of a block; with its `TURN=`.
    fn arc(
        &self,
        kind: MotionKind,
        plane: Plane,
        start: Point3,
        end: Point3,
        circle: Option<&Circle>,
        pole: Option<Point3>,
    ) -> Result<(geometry::Arc, u32), RunError> {
        let empty = Circle::default();
        let circle = circle.unwrap_or(&empty);
        let direction = if kind == MotionKind::ArcCw {
            Direction::Cw
        } else {
            Direction::Ccw
        };
        let env = self.env();
        let real = |v: &gcodec_ail::Value| eval::eval_real(&env, v);
        let length = |v: f64| if self.state.inch() { v * 25.4 } else { v };
        // `I J K` (and `I1 J1 K1`) to a point of the geometry axes.
        let offsets =
            |values: &[AxisValue], relative_default: bool| -> Result<Option<Point3>, RunError> {
                if values.is_empty() {
                    return Ok(None);
                }
                let mut p = start;
                for value in values {
                    let g = match value.axis.as_ref() {
                        "I" | "I1" => 0,
                        "J" | "J1" => 1,
                        "K" | "K1" => 2,
                        _ => continue,
                    };
                    let v = length(real(&value.value)?);
                    let relative = match value.mode {
                        Some(DimensionMode::Ac) => false,
                        Some(DimensionMode::Ic) => true,
                        _ => relative_default,
                    };
                    p[g] = if relative { start[g] + v } else { v };
                }
                Ok(Some(p))
            };
        let form = if kind == MotionKind::ArcThroughPoint {
            let point =
                offsets(&circle.intermediate, self.state.incremental())?.ok_or_else(|| {
                    RunError::new(
                        codes::run::CIRCLE_INTERMEDIATE,
                        "`CIP` needs an intermediate point (`I1= J1= K1=`)",
                    )
                })?;
            ArcForm::Intermediate { point }
        } else if kind == MotionKind::ArcTangential {
            let tangent = self.motion.last_tangent.unwrap_or([0.0; 3]);
            ArcForm::Tangent { tangent }
        } else {
            let radius = circle.radius.as_ref().map(real).transpose()?.map(length);
            let angle = circle.opening_angle.as_ref().map(real).transpose()?;
            // A polar end point without circle data: about the pole.
            let centre = offsets(&circle.centre, true)?
                .or(pole.filter(|_| radius.is_none() && angle.is_none()));
            match (centre, radius, angle) {
                (Some(centre), _, Some(angle)) => ArcForm::AngleFromCentre {
                    direction,
                    centre,
                    angle,
                },
                (Some(centre), _, None) => ArcForm::Centre { direction, centre },
                (None, Some(radius), _) => ArcForm::Radius { direction, radius },
                (None, None, Some(angle)) => ArcForm::AngleToEnd { direction, angle },
                (None, None, None) => {
                    return Err(RunError::new(
                        codes::run::CIRCLE_DATA,
                        "the circle has neither a centre (`I J K`), a radius (`CR=`) nor an opening angle (`AR=`)",
                    ));
                }
            }
        };
        let turns = circle.turns.as_ref().map(real).transpose()?.unwrap_or(0.0);
        geometry::resolve_arc(
            plane,
            start,
            end,
            &form,
            turns,
            &self.options.circle_tolerance,
        )
        // `resolve_arc` accepts only whole turns 0…999 (`circle_turns`).
        .map(|arc| (arc, turns as u32))
        .map_err(|e| RunError::new(e.code(), e.to_string()))
    }

    /// The time of a motion of `length` mm, seconds.
    fn motion_time(&self, kind: MotionKind, length: f64) -> f64 {
        let scratch = &self.motion;
        if kind == MotionKind::Rapid {
            let mut minutes: f64 = 0.0;
            for (i, info) in self.state.axes.iter().enumerate() {
                let delta = (scratch.machine[i] - self.state.machine[i]).abs();
                if info.rapid > 0.0 {
                    minutes = minutes.max(delta / info.rapid);
                }
            }
            return minutes * 60.0;
        }
        let feed = self.state.feed;
        if feed <= 0.0 || !feed.is_finite() {
            return 0.0;
        }
        // Rotary axes alone: the feed is in degrees per minute.
        let travel = if length > 0.0 {
            length
        } else {
            scratch
                .machine
                .iter()
                .zip(&self.state.machine)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max)
        };
        // G94, the commonest, is known without looking up the name.
        let feed_mode = if self.state.feeds_per_minute() {
            None
        } else {
            self.state.modal(15)
        };
        let minutes = match feed_mode {
            Some("G93") => 1.0 / feed,
            Some(
                "G95" | "G96" | "G961" | "G97" | "G971" | "G942" | "G952" | "G962" | "G972"
                | "G973",
            ) => {
                let speed = self.state.master_spindle().map_or(0.0, |s| s.speed);
                if speed <= 0.0 {
                    return 0.0;
                }
                travel / (feed * speed)
            }
            _ => travel / feed,
        };
        minutes * 60.0
    }
}

fn kind_is_straight(kind: MotionKind) -> bool {
    matches!(kind, MotionKind::Rapid | MotionKind::Linear)
}

fn kind_key(kind: MotionKind) -> &'static str {
    match kind {
        MotionKind::Aspline | MotionKind::Bspline | MotionKind::Cspline | MotionKind::Poly => {
            "motion-spline"
        }
        MotionKind::InvoluteCw | MotionKind::InvoluteCcw => "motion-involute",
        _ => "motion-thread",
    }
}

fn distance(a: Point3, b: Point3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Refills an axis map with every axis of the channel: as programmed
/// (`programmed`: inches, diameters) or in mm.
// Inlined: the call cost as much as the copy.
#[inline(always)]
pub(super) fn fill_map(map: &mut AxisMap, state: &MachineState, values: &[f64], programmed: bool) {
    // Under G71 without diameter programming a position is written as it
    // is: asking per axis costs more than the copy.
    let programmed = programmed && state.converts_programmed_positions();
    if programmed || map.len() != state.axes.len() {
        refill_map(map, state, values, programmed);
        return;
    }
    for (slot, value) in map.values_mut().zip(values) {
        *slot = *value;
    }
}

/// [`fill_map`] of a map to be made anew or of positions to convert.
fn refill_map(map: &mut AxisMap, state: &MachineState, values: &[f64], programmed: bool) {
    let value = |i: usize| {
        if programmed {
            state.as_programmed(i, values[i])
        } else {
            values[i]
        }
    };
    if map.len() != state.axes.len() {
        map.clear();
        for (i, info) in state.axes.iter().enumerate() {
            map.insert(info.name.clone(), value(i));
        }
        return;
    }
    for (i, slot) in map.values_mut().enumerate() {
        *slot = value(i);
    }
}
