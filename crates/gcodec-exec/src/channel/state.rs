//! The channel's machine state apart from the variables: modal G groups,
//! axis positions, frames and offsets, tool, feed and spindles. It answers
//! the system variables a program reads ([`RuntimeInterface`]).

use std::cell::{Ref, RefCell};
use std::sync::Arc;

use gcodec_lang::WorkOffsetCode;
use gcodec_lang::addresses::letter_str;
use gcodec_lang::functions::Function;
use gcodec_lang::ggroups;
use gcodec_lang::modal::GROUP_COUNT;
use gcodec_lang::sysvars::SysVarId;
use gcodec_profile::reset_defaults;
use gcodec_profile::{AxisKind, Profile};
use gcodec_source::codes;

use crate::eval::{
    RuntimeInterface, machine_axis_number, profile_offsets, profile_system_variable,
    settable_offset,
};
use gcodec_ail::{Suppression, VarName};

use super::machine_calls::MachineReads;
use super::tool_data::ToolData;
use crate::event::{AxisName, Plane, SpindleState};
use crate::frames::{Frame, FrameAxes, chain_values, frame_function};
use crate::geometry::Point3;
use crate::tool_resolution::{PendingTool, ToolRef};
use crate::value::{FrameValue, RtValue, RunError};

/// One channel axis.
#[derive(Clone, Debug)]
pub struct AxisInfo {
    /// Upper case, as AIL names it.
    pub name: AxisName,
    pub rotary: bool,
    /// The geometry axis number 0…2, if it is one.
    pub geometry: Option<usize>,
    /// The lathe's diameter axis (DIAMON).
    pub diameter: bool,
    /// Rapid rate, mm/min or deg/min.
    pub rapid: f64,
}

/// A spindle.
#[derive(Clone, Debug, Default)]
pub struct Spindle {
    pub number: u32,
    pub state: SpindleState,
    pub speed: f64,
    pub position: Option<f64>,
    /// M40…M45: 0 automatic, 1…5.
    pub gear: u32,
    /// `G25 S…`/`G26 S…`: the lower and upper speed limits.
    pub speed_limits: [Option<f64>; 2],
}

/// The machine state of the channel.
pub struct MachineState {
    pub profile: Arc<Profile>,
    pub axes: Vec<AxisInfo>,
    pub frame_axes: FrameAxes,
    /// Per G group (index group − 1) the registry index of the command in
    /// force ([`ggroups::member`]); 0 for none (non-modal groups).
    pub modal: [u8; GROUP_COUNT],
    /// The tool reference point in machine coordinates, mm (the diameter
    /// axis as a radius), per axis.
    pub machine: Vec<f64>,
    /// The settable frames (`G54`…`G57`, `G505`…), by Group 8 index.
    pub settable: Vec<Frame>,
    /// The programmable frame (`TRANS`, `ROT`, …: `$P_PFRAME`).
    pub programmable: Frame,
    /// The Group 8 selection.
    pub group8: WorkOffsetCode,
    /// This block's suppression.
    pub suppression: Option<Suppression>,
    pub active_tool: Option<ToolRef>,
    /// A `T` selection waiting for the change (the tool-change design).
    pub pending: Option<PendingTool>,
    /// The number of the last tool programmed (`$P_TOOLP`; 0 for none or
    /// `T0`): it stays after the change.
    pub programmed_tool: u32,
    /// The active cutting edge (D); 0: none.
    pub edge: u32,
    /// The active edge's length, mm.
    pub tool_length: f64,
    /// The active edge's radius, mm (tool radius compensation).
    pub tool_radius: f64,
    /// The active edge's cutting edge position (`$TC_DP2`; 0: none).
    pub edge_position: u8,
    /// Under tool radius compensation, where the tool centre (a turning
    /// tool's tip) stands, machine coordinates: what `$AA_IM` reads.
    pub tool_centre: Option<Vec<f64>>,
    /// The contour settings of the named addresses `OFFN=`, `RNDM=`,
    /// `DISC=`.
    pub contour: ContourSettings,
    /// The run's tool table and the tool data the program wrote.
    pub(super) tool_data: ToolData,
    /// The programmed F, in the unit of group 15.
    pub feed: f64,
    pub spindles: Vec<Spindle>,
    /// `MCALL`: the modal call in force.
    pub(super) modal_call: Option<super::calls::ModalCall>,
    /// The pole and the polar end point last programmed.
    pub polar: Polar,
    /// `G25`/`G26`.
    pub working_area: WorkingArea,
    /// The total frame the last motion ran in (`None` before the first):
    /// an increment after a change traverses it (SD42440).
    pub traversed_frame: Option<Frame>,
    /// The end point the last motion was programmed to, while it is the
    /// workpiece position ([`Self::workpiece_position`]).
    end_point: EndPoint,
    /// `SETINT`: the routine of each input.
    pub(super) interrupts: super::interrupts::Interrupts,
    /// The reads of system variables the machine answers.
    pub(super) machine_reads: MachineReads,
    /// The last total frame with what it was made of, so that a motion
    /// does not chain frames (and allocate) unless one changed.
    frame_cache: RefCell<FrameCache>,
    /// The neutral frame (`G500`, a suppressed block).
    neutral: Frame,
    /// Room for a position, reused.
    scratch: RefCell<Vec<f64>>,
    /// Per Group 8 index whether the machine has that settable offset
    /// (`work_offsets.supported_group8_offsets`).
    supported_group8: [bool; 100],
    /// Per letter `A`…`Z` the axis it names ([`Self::axis_index_by_name`]):
    /// a motion's targets are mostly single letters, found without
    /// comparing names.
    letter_axes: [Option<usize>; 26],
    codes: ModalCodes,
}

/// The end point a motion was programmed to, in workpiece coordinates,
/// with what made the machine position of it: it is the workpiece
/// position while the frame, the tool length and the plane (whose infeed
/// axis the length acts along) stay and nothing else moves the machine.
#[derive(Debug, Default)]
struct EndPoint {
    /// `false` before the first motion and after a motion whose end point
    /// is not the machine's image ([`MachineState::forget_end_point`]).
    kept: bool,
    wcs: Vec<f64>,
    tool_length: u64,
    plane: Plane,
}

/// The registry indices of the commands the queries of every motion test
/// for ([`MachineState::plane`], [`MachineState::inch`], …): comparing an
/// index costs less than looking up the command's name and comparing it.
/// `None` for a command the registry lacks (no index matches it).
#[derive(Clone, Copy, Debug)]
struct ModalCodes {
    g18: Option<u8>,
    g19: Option<u8>,
    g40: Option<u8>,
    g70: Option<u8>,
    g700: Option<u8>,
    g91: Option<u8>,
    g94: Option<u8>,
    diamon: Option<u8>,
    diam90: Option<u8>,
}

impl ModalCodes {
    fn new() -> Self {
        let index = |group: u8, code: &str| {
            ggroups::lookup(code)
                .filter(|&(found, _)| found == group)
                .map(|(_, index)| index)
        };
        Self {
            g18: index(6, "G18"),
            g19: index(6, "G19"),
            g40: index(7, "G40"),
            g70: index(13, "G70"),
            g700: index(13, "G700"),
            g91: index(14, "G91"),
            g94: index(15, "G94"),
            diamon: index(29, "DIAMON"),
            diam90: index(29, "DIAM90"),
        }
    }
}

struct FrameCache {
    /// Counts the rebuilds: a total frame of another generation may be
    /// another frame.
    generation: u64,
    group8: WorkOffsetCode,
    suppressed: bool,
    settable: Frame,
    programmable: Frame,
    total: Frame,
    /// `total` changes no value ([`Frame::is_identity`]).
    total_is_identity: bool,
}

/// The pole and the polar end point last programmed, in workpiece
/// coordinates of the geometry slots (mm) and degrees.
#[derive(Clone, Debug, Default)]
pub struct Polar {
    /// `G110`/`G111`/`G112`; the workpiece zero until one is programmed.
    pub pole: Point3,
    /// `AP`: kept until a new pole or a change of plane.
    pub angle: f64,
    /// `RP`: kept until it is programmed again.
    pub radius: f64,
}

/// `G25`/`G26`: the working-area limits per channel axis, machine
/// coordinates (mm, degrees); `None` where none is programmed.
#[derive(Clone, Debug, Default)]
pub struct WorkingArea {
    pub lower: Vec<Option<f64>>,
    pub upper: Vec<Option<f64>>,
}

impl MachineState {
    pub fn new(profile: Arc<Profile>) -> Self {
        let frame_axes = FrameAxes::from_profile(&profile);
        let axes: Vec<AxisInfo> = profile
            .axes
            .iter()
            .enumerate()
            .map(|(i, a)| AxisInfo {
                name: crate::event::axis_name(a.name.get_ref()),
                rotary: a.kind == AxisKind::Rotary,
                // X, Y, Z keep their slots (a lathe's X and Z are the
                // first and third geometry axes).
                geometry: frame_axes.geometry_slot(i),
                diameter: a.diameter,
                rapid: *a.rapid.get_ref(),
            })
            .collect();
        let settable = (0..100)
            .map(|index| settable_frame(&profile, &frame_axes, index))
            .collect();
        let defaults = reset_defaults(&profile);
        let group8 = defaults[7]
            .and_then(WorkOffsetCode::parse)
            .unwrap_or(WorkOffsetCode::G500);
        let modal =
            defaults.map(|code| code.and_then(ggroups::lookup).map_or(0, |(_, index)| index));
        let spindles = profile
            .machine
            .spindles
            .iter()
            .map(|n| Spindle {
                number: *n.get_ref(),
                ..Spindle::default()
            })
            .collect();
        let neutral = Frame::neutral(&frame_axes);
        let letter_axes = std::array::from_fn(|i| {
            axis_index_by_name(&frame_axes, axes.len(), letter_str(b'A' + i as u8))
        });
        Self {
            machine: vec![0.0; axes.len()],
            programmable: neutral.clone(),
            settable,
            axes,
            modal,
            group8,
            suppression: None,
            active_tool: None,
            pending: None,
            programmed_tool: 0,
            edge: 0,
            tool_length: 0.0,
            tool_radius: 0.0,
            edge_position: 0,
            tool_centre: None,
            contour: ContourSettings::default(),
            tool_data: ToolData::new(&profile),
            feed: 0.0,
            spindles,
            modal_call: None,
            polar: Polar::default(),
            working_area: WorkingArea::default(),
            traversed_frame: None,
            end_point: EndPoint::default(),
            interrupts: Default::default(),
            machine_reads: MachineReads::default(),
            // A group 8 code no block selects: the first motion fills it.
            frame_cache: RefCell::new(FrameCache {
                generation: 0,
                group8: WorkOffsetCode(0),
                suppressed: false,
                settable: neutral.clone(),
                programmable: neutral.clone(),
                total: neutral.clone(),
                total_is_identity: true,
            }),
            neutral,
            frame_axes,
            scratch: RefCell::new(Vec::new()),
            supported_group8: profile.work_offsets.supported_group8(),
            letter_axes,
            codes: ModalCodes::new(),
            profile,
        }
    }

    /// The geometry axes of `values` (indexed like the channel's axes) as
    /// a point; 0 for a geometry axis the machine lacks.
    pub fn geometry_point(&self, values: &[f64]) -> Point3 {
        let mut p = [0.0; 3];
        for (info, v) in self.axes.iter().zip(values) {
            if let Some(g) = info.geometry {
                p[g] = *v;
            }
        }
        p
    }

    /// The axis named `name` (any case).
    pub fn axis_index(&self, name: &str) -> Option<usize> {
        match name.as_bytes() {
            [letter @ b'A'..=b'Z'] => self.letter_axes[usize::from(letter - b'A')],
            _ => self.axis_index_by_name(name),
        }
    }

    /// [`Self::axis_index`] by comparing names.
    fn axis_index_by_name(&self, name: &str) -> Option<usize> {
        axis_index_by_name(&self.frame_axes, self.axes.len(), name)
    }

    /// The command in force of group `group`.
    pub fn modal(&self, group: u8) -> Option<&'static str> {
        ggroups::member(group, self.modal_index(group)?)
    }

    /// The registry index of the command of `group` in force (what
    /// `$P_GG` returns); `None` for none.
    pub fn modal_index(&self, group: u8) -> Option<u8> {
        self.modal
            .get(usize::from(group).wrapping_sub(1))
            .copied()
            .filter(|&index| index != 0)
    }

    /// Whether `code` (an index of [`ModalCodes`]) of `group` is in force.
    fn in_force(&self, group: u8, code: Option<u8>) -> bool {
        code.is_some() && self.modal_index(group) == code
    }

    pub fn plane(&self) -> Plane {
        if self.in_force(6, self.codes.g18) {
            Plane::G18
        } else if self.in_force(6, self.codes.g19) {
            Plane::G19
        } else {
            Plane::G17
        }
    }

    /// G70/G700: programmed lengths are inches.
    pub fn inch(&self) -> bool {
        self.in_force(13, self.codes.g70) || self.in_force(13, self.codes.g700)
    }

    /// A command of group 7 other than G40 (G41, G42) is in force: tool
    /// radius compensation is selected.
    pub fn radius_compensation_selected(&self) -> bool {
        self.modal_index(7)
            .is_some_and(|index| Some(index) != self.codes.g40)
    }

    /// G91: incremental unless a value says otherwise.
    pub fn incremental(&self) -> bool {
        self.in_force(14, self.codes.g91)
    }

    /// G94: the feed is in mm (inch) per minute.
    pub fn feeds_per_minute(&self) -> bool {
        self.in_force(15, self.codes.g94)
    }

    /// Whether a position in mm (radius) is written otherwise in the
    /// program: in inches (G70/G700) or as a diameter (DIAMON/DIAM90,
    /// [`Self::as_programmed`]).
    pub fn converts_programmed_positions(&self) -> bool {
        self.inch() || self.diameter_mode().0
    }

    /// How the diameter axis reads values (group 29): (absolute values are
    /// diameters, incremental values are diameters).
    pub fn diameter_mode(&self) -> (bool, bool) {
        if self.in_force(29, self.codes.diamon) {
            (true, true)
        } else if self.in_force(29, self.codes.diam90) {
            (true, false)
        } else {
            (false, false)
        }
    }

    /// The infeed axis of the plane (where the tool length acts).
    pub fn infeed_axis(&self) -> Option<usize> {
        self.frame_axes.geometry_axis(self.plane().infeed())
    }

    /// The settable frame in force (`$P_IFRAME`): the selected offset's,
    /// neutral under `G500`.
    pub fn active_settable(&self) -> &Frame {
        match self.settable.get(usize::from(self.group8_index())) {
            Some(s) if self.group8 != WorkOffsetCode::G500 => s,
            _ => &self.neutral,
        }
    }

    /// The frame from workpiece to machine coordinates in force for this
    /// block: the settable offset (unless G500 or suppressed) chained with
    /// the programmable frame (unless suppressed).
    pub fn total_frame(&self) -> Ref<'_, Frame> {
        let suppressed = self.suppression.is_some();
        let settable = self.active_settable();
        let fresh = {
            let c = self.frame_cache.borrow();
            c.group8 == self.group8
                && c.suppressed == suppressed
                && c.settable.same_as(settable)
                && c.programmable.same_as(&self.programmable)
        };
        if !fresh {
            let total = if suppressed {
                self.neutral.clone()
            } else {
                settable.chain(&self.programmable)
            };
            let generation = self.frame_cache.borrow().generation + 1;
            *self.frame_cache.borrow_mut() = FrameCache {
                generation,
                group8: self.group8,
                suppressed,
                settable: settable.clone(),
                programmable: self.programmable.clone(),
                total_is_identity: total.is_identity(),
                total,
            };
        }
        Ref::map(self.frame_cache.borrow(), |c| &c.total)
    }

    /// The generation of the total frame [`Self::total_frame`] gives now:
    /// the same generation, the same frame.
    pub fn total_frame_generation(&self) -> u64 {
        drop(self.total_frame());
        self.frame_cache.borrow().generation
    }

    /// Whether a motion now finds the workpiece position in the machine
    /// position as it is, and the machine position in the end point as
    /// it is: no block suppression, no tool length, a total frame that
    /// changes no value and that the last motion ran in too (so that no
    /// change of it is left for an increment to traverse). Positions that
    /// are `-0.0` or not finite are the caller's to rule out: the frame's
    /// arithmetic can change those.
    pub fn positions_plain(&self) -> bool {
        let total = self.total_frame();
        self.frame_as_traversed(&total) && self.workpiece_is_machine_in(&total)
    }

    /// Whether a motion now runs in the frame the last motion ran in,
    /// `total` ([`Self::total_frame`], which the caller has at hand), with
    /// no block suppression: no change of frame is left for an increment
    /// to traverse, and the motion notes no new one
    /// ([`Self::note_traversed_frame`] would change nothing).
    pub fn frame_as_traversed(&self, total: &Frame) -> bool {
        self.suppression.is_none()
            && self
                .traversed_frame
                .as_ref()
                .is_some_and(|f| f.same_as(total))
    }

    /// Whether workpiece and machine coordinates are the same numbers
    /// now: no tool length and a total frame that changes no value
    /// (`-0.0` and values out of range aside, [`Frame::is_identity`]).
    pub fn workpiece_is_machine(&self) -> bool {
        self.workpiece_is_machine_in(&self.total_frame())
    }

    /// [`Self::workpiece_is_machine`] where the caller holds the total
    /// frame ([`Self::total_frame`]: while it is held, nothing it is made
    /// of changes, and the cache's note of it stands).
    pub(super) fn workpiece_is_machine_in(&self, _total: &Frame) -> bool {
        self.tool_length.to_bits() == 0 && self.frame_cache.borrow().total_is_identity
    }

    /// Keeps the total frame of the motion just made, for the increments
    /// that follow ([`Self::traversed_frame`]); a clone only when it
    /// changed. A block under `G53`/`G153`/`SUPA` programs machine
    /// positions and changes nothing of it.
    pub fn note_traversed_frame(&mut self) {
        if self.suppression.is_some() {
            return;
        }
        let changed = {
            let total = self.total_frame();
            (!self
                .traversed_frame
                .as_ref()
                .is_some_and(|f| f.same_as(&total)))
            .then(|| total.clone())
        };
        if let Some(total) = changed {
            self.traversed_frame = Some(total);
        }
    }

    /// `$P_UIFRNUM`: the index of the Group 8 selection.
    pub fn group8_index(&self) -> u8 {
        self.group8.index().unwrap_or(0)
    }

    /// Workpiece coordinates (mm, radius) of the machine position `machine`
    /// under `frame`.
    pub fn to_workpiece(&self, frame: &Frame, machine: &[f64], out: &mut [f64]) {
        let axis = match self.infeed_axis() {
            // `x − (+0)` is `x`, bit for bit: without a tool length (or an
            // infeed axis) the position goes into the frame as it is.
            Some(axis) if self.tool_length.to_bits() != 0 => axis,
            _ => return frame.to_inner(machine, out),
        };
        let mut shifted = self.scratch.borrow_mut();
        shifted.clear();
        shifted.extend_from_slice(machine);
        shifted[axis] -= self.tool_length;
        frame.to_inner(&shifted, out);
    }

    /// The workpiece position now, in the total frame `frame` (the one in
    /// force, [`Self::total_frame`]): the end point the last motion was
    /// programmed to, bit for bit, where that motion ran in this frame
    /// with this tool length along this infeed axis and nothing has moved
    /// the machine since; the frame's image of the machine position
    /// otherwise. The control keeps the programmed position; computed
    /// back from the machine position, through the frame's arithmetic
    /// there and back, it could differ in the last bit (`X100.037` under
    /// an offset read back as `100.03700000000003`).
    pub fn workpiece_position(&self, frame: &Frame, out: &mut [f64]) {
        if self.frame_as_traversed(frame) {
            self.workpiece_position_in_traversed_frame(frame, out);
        } else {
            self.to_workpiece(frame, &self.machine, out);
        }
    }

    /// [`Self::workpiece_position`] where the caller knows the frame in
    /// force, `frame`, is the one the last motion ran in
    /// ([`Self::frame_as_traversed`]).
    pub(super) fn workpiece_position_in_traversed_frame(&self, frame: &Frame, out: &mut [f64]) {
        let end = &self.end_point;
        if end.kept && end.tool_length == self.tool_length.to_bits() && end.plane == self.plane() {
            out.copy_from_slice(&end.wcs);
        } else {
            self.to_workpiece(frame, &self.machine, out);
        }
    }

    /// Keeps `wcs`, the end point of the motion that just set the machine
    /// position (its image in the frame it ran in, which
    /// [`Self::note_traversed_frame`] has noted), as the workpiece
    /// position. A block with its frames suppressed (`G53`, `SUPA`)
    /// programs machine positions: its end point is forgotten.
    pub(super) fn keep_end_point(&mut self, wcs: &[f64]) {
        let plane = self.plane();
        let end = &mut self.end_point;
        end.kept = self.suppression.is_none();
        end.wcs.resize(wcs.len(), 0.0);
        for (kept, value) in end.wcs.iter_mut().zip(wcs) {
            // `-0` is kept as `0`, as the frame's arithmetic there and
            // back gives it, and as the machine position as it is says
            // where a motion keeps nothing.
            *kept = 0.0 + value;
        }
        end.tool_length = self.tool_length.to_bits();
        end.plane = plane;
    }

    /// The machine position moved other than to a kept end point (a
    /// corner of the tool-centre path), or to one that needs no keeping
    /// (a motion in a plain state, whose machine position is its
    /// workpiece position as it is): the workpiece position is the
    /// machine position's image again.
    pub(super) fn forget_end_point(&mut self) {
        self.end_point.kept = false;
    }

    /// Machine coordinates of the workpiece point `wcs`.
    pub fn to_machine(&self, frame: &Frame, wcs: &[f64], out: &mut [f64]) {
        frame.to_outer(wcs, out);
        if let Some(axis) = self.infeed_axis() {
            out[axis] += self.tool_length;
        }
    }

    /// A position (mm, radius) as the program writes it: inches under
    /// G70/G700, the diameter axis as a diameter under DIAMON/DIAM90.
    pub fn as_programmed(&self, axis: usize, value: f64) -> f64 {
        let info = &self.axes[axis];
        let mut v = value;
        if info.diameter && self.diameter_mode().0 {
            v *= 2.0;
        }
        if !info.rotary && self.inch() {
            v /= 25.4;
        }
        v
    }

    /// A length in mm as the program writes it: inches under G70/G700.
    pub fn length_as_programmed(&self, mm: f64) -> f64 {
        if self.inch() { mm / 25.4 } else { mm }
    }

    /// A length as the program writes it, in mm.
    pub fn length_in_mm(&self, programmed: f64) -> f64 {
        if self.inch() {
            programmed * 25.4
        } else {
            programmed
        }
    }

    /// The spindle an address extension names: `None` or 0 the master
    /// spindle, another number one of the profile's spindles. The table is
    /// the profile's and never grows: a spindle the machine does not have
    /// is an alarm at its first use, as on the control (lowering rejects
    /// the constant ones; this catches the computed `S[N]=`).
    pub fn spindle(&mut self, number: Option<u32>) -> Result<&mut Spindle, RunError> {
        let at = match number.filter(|&n| n != 0) {
            None => (!self.spindles.is_empty()).then_some(0),
            Some(n) => self.spindles.iter().position(|s| s.number == n),
        };
        match at {
            Some(i) => Ok(&mut self.spindles[i]),
            None => Err(RunError::new(
                codes::run::UNKNOWN_SPINDLE,
                match number.filter(|&n| n != 0) {
                    Some(n) => format!("this machine has no spindle {n}"),
                    None => "this machine has no spindle".to_owned(),
                },
            )),
        }
    }

    pub fn master_spindle(&self) -> Option<&Spindle> {
        self.spindles.first()
    }
}

/// The settable frame `$P_UIFR[index]` as the profile's
/// `work_offsets.values` give it (translations).
/// Modal values of the contour and its compensation, in mm.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ContourSettings {
    /// `OFFN=`: the allowance added to the tool radius under
    /// compensation.
    pub offn: f64,
    /// `RNDM=`: the modal rounding at every corner; 0 is off.
    pub rndm: f64,
    /// `DISC=`: the transition circle's overshoot, 0…100.
    pub disc: f64,
}

/// The axis named `name` (any case) among `frame_axes`, or by its machine
/// axis number (`AX2`) among `count` axes.
fn axis_index_by_name(frame_axes: &FrameAxes, count: usize, name: &str) -> Option<usize> {
    frame_axes
        .index_of(name)
        .or_else(|| machine_axis_number(name, count))
}

fn settable_frame(profile: &Profile, frame_axes: &FrameAxes, index: usize) -> Frame {
    let values: Vec<(usize, f64)> = profile_offsets(profile, index)
        .filter_map(|(axis, v)| Some((frame_axes.index_of(axis)?, v)))
        .collect();
    Frame::translation(frame_axes, &values).unwrap_or_else(|_| Frame::neutral(frame_axes))
}

impl MachineState {
    fn axis_argument(&self, name: &str, value: &RtValue) -> Result<usize, RunError> {
        let axis = match value {
            RtValue::Axis(a) | RtValue::String(a) => a.clone(),
            v => return Err(RunError::type_mismatch(v, "AXIS")),
        };
        self.axis_index(&axis).ok_or_else(|| {
            RunError::new(
                codes::run::UNKNOWN_AXIS,
                format!("`{name}[{axis}]`: the machine has no axis `{axis}`"),
            )
        })
    }

    /// The settable offset `$P_UIFR[n]` reads: one the machine has.
    fn supported_settable(&self, n: i32) -> Result<usize, RunError> {
        settable_offset(n, |i| i < self.settable.len() && self.supported_group8[i])
    }

    fn frame_value(&self, frame: &Frame) -> RtValue {
        RtValue::Frame(Arc::new(frame.to_value(&self.frame_axes)))
    }
}

impl MachineState {
    /// The channel's own state first; the profile's defaults for the rest
    /// ([`profile_system_variable`]).
    fn own_system_variable(&self, var: &VarName, indices: &[RtValue]) -> Result<RtValue, RunError> {
        let name = var.as_str();
        let one_axis = |what: &str| -> Result<usize, RunError> {
            match indices {
                [axis] => self.axis_argument(name, axis),
                _ => Err(RunError::new(
                    codes::run::INDEX_COUNT,
                    format!("`{name}` takes one axis index ({what})"),
                )),
            }
        };
        let Some(id) = var.system() else {
            return profile_system_variable(Some(&self.profile), var, indices);
        };
        match (id, indices) {
            // Tool numbers go to 4294967295 and edges are u32: beyond the
            // INT range a number is a REAL, as a constant is, not wrapped.
            (SysVarId::P_TOOLNO, []) => Ok(crate::eval::number(
                self.active_tool
                    .as_ref()
                    .map_or(0.0, |t| f64::from(t.number)),
            )),
            (SysVarId::P_TOOLP, []) => Ok(crate::eval::number(f64::from(self.programmed_tool))),
            (SysVarId::P_TOOL, []) => Ok(crate::eval::number(f64::from(self.edge))),
            (SysVarId::P_F, []) => Ok(RtValue::Real(self.feed)),
            (SysVarId::P_MC, []) => Ok(RtValue::Bool(self.modal_call.is_some())),
            (SysVarId::P_UIFRNUM, []) => Ok(RtValue::Int(i32::from(self.group8_index()))),
            (SysVarId::P_PFRAME, []) => Ok(self.frame_value(&self.programmable)),
            (SysVarId::P_IFRAME, []) => Ok(self.frame_value(self.active_settable())),
            (SysVarId::P_ACTFRAME, []) => Ok(self.frame_value(&self.total_frame())),
            (SysVarId::P_UIFR, [n]) => {
                let slot = self.supported_settable(n.to_int()?)?;
                Ok(self.frame_value(&self.settable[slot]))
            }
            (SysVarId::P_UIFR, [n, axis, component]) => {
                let slot = self.supported_settable(n.to_int()?)?;
                let frame = self.settable[slot].to_value(&self.frame_axes);
                let axis = self.axis_argument(name, axis)?;
                frame
                    .component_of(&self.axes[axis].name, component)
                    .map(RtValue::Real)
            }
            (SysVarId::P_GG, [n]) => {
                let n = n.to_int()?;
                let group = u8::try_from(n).ok().filter(|g| (1..=64).contains(g));
                let Some(group) = group else {
                    return Err(RunError::new(
                        codes::run::INDEX_OUT_OF_RANGE,
                        format!("`$P_GG[{n}]`: there is no G group {n}"),
                    ));
                };
                let index = self.modal_index(group).map_or(0, i32::from);
                Ok(RtValue::Int(index))
            }
            // The actual positions are the tool centre's; the programmed
            // end point (`$P_EP`) is the contour's.
            (SysVarId::AA_IM, _) => {
                let axis = one_axis("the machine position")?;
                let actual = self.tool_centre.as_deref().unwrap_or(&self.machine);
                Ok(RtValue::Real(actual[axis]))
            }
            (SysVarId::AA_IW | SysVarId::P_EP, _) => {
                let axis = one_axis("the workpiece position")?;
                let mut wcs = vec![0.0; self.axes.len()];
                let frame = self.total_frame();
                match (id, &self.tool_centre) {
                    (SysVarId::AA_IW, Some(actual)) => {
                        self.to_workpiece(&frame, actual, &mut wcs);
                    }
                    _ => self.workpiece_position(&frame, &mut wcs),
                }
                Ok(RtValue::Real(self.as_programmed(axis, wcs[axis])))
            }
            _ => match self.tool_data.read(id, indices) {
                Some(value) => value,
                None => profile_system_variable(Some(&self.profile), var, indices),
            },
        }
    }
}

impl RuntimeInterface for MachineState {
    fn profile(&self) -> Option<&Profile> {
        Some(&self.profile)
    }

    /// The channel's own state first, then the profile's defaults
    /// ([`profile_system_variable`]), then what the machine answered
    /// (`channel::machine_calls`): a read none of them answers is kept
    /// for the channel to ask the machine.
    fn system_variable(&self, var: &VarName, indices: &[RtValue]) -> Result<RtValue, RunError> {
        match self.own_system_variable(var, indices) {
            Err(error) if error.code == codes::run::SYSTEM_VARIABLE => {
                match self.machine_reads.lookup(var.as_str(), indices) {
                    Some(value) => Ok(value),
                    None => {
                        self.machine_reads.unanswered(var.as_str(), indices);
                        Err(error)
                    }
                }
            }
            result => result,
        }
    }

    fn set_system_variable(
        &mut self,
        var: &VarName,
        indices: &[RtValue],
        value: &RtValue,
    ) -> Result<(), RunError> {
        let name = var.as_str();
        match (var.system(), indices) {
            (Some(SysVarId::P_PFRAME), []) => {
                let RtValue::Frame(f) = value else {
                    return Err(RunError::type_mismatch(value, "FRAME"));
                };
                self.programmable = Frame::from_value(&self.frame_axes, f)?;
                Ok(())
            }
            (Some(SysVarId::P_UIFR), [n]) => {
                let n = n.to_int()?;
                let RtValue::Frame(f) = value else {
                    return Err(RunError::type_mismatch(value, "FRAME"));
                };
                let frame = Frame::from_value(&self.frame_axes, f)?;
                let slot = settable_offset(n, |i| i < self.settable.len())?;
                self.settable[slot] = frame;
                Ok(())
            }
            (Some(SysVarId::P_UIFR), [n, axis, component]) => {
                let slot = settable_offset(n.to_int()?, |i| i < self.settable.len())?;
                let axis = self.axis_argument(name, axis)?;
                let mut frame = self.settable[slot].to_value(&self.frame_axes);
                frame.set_component(&self.axes[axis].name, component, value)?;
                self.settable[slot] = Frame::from_value(&self.frame_axes, &frame)?;
                Ok(())
            }
            (Some(id), _) => self.tool_data.write(id, indices, value).unwrap_or_else(|| {
                Err(RunError::new(
                    codes::run::READ_ONLY,
                    format!("the system variable `{name}` cannot be written in the simulation"),
                ))
            }),
            (None, _) => Err(RunError::new(
                codes::run::READ_ONLY,
                format!("the system variable `{name}` cannot be written in the simulation"),
            )),
        }
    }

    fn function(
        &self,
        function: Function,
        args: &[Option<RtValue>],
    ) -> Option<Result<RtValue, RunError>> {
        frame_function(&self.frame_axes, function, args)
    }

    fn chain_frames(&self, lhs: &FrameValue, rhs: &FrameValue) -> Result<FrameValue, RunError> {
        chain_values(&self.frame_axes, lhs, rhs)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The direct path of straight motions runs where this says yes: in
    /// a neutral frame the last motion ran in, without a tool length or
    /// a suppression.
    #[test]
    fn positions_are_plain_only_in_the_frame_of_the_last_motion_without_tool_length() {
        let profile = gcodec_profile::builtin().expect("the built-in profile");
        let mut state = MachineState::new(Arc::new(profile));
        assert!(!state.positions_plain(), "before the first motion");
        assert!(state.workpiece_is_machine());
        state.note_traversed_frame();
        assert!(state.positions_plain());
        state.tool_length = 25.0;
        assert!(!state.positions_plain(), "a tool length");
        assert!(!state.workpiece_is_machine(), "a tool length");
        state.tool_length = -0.0;
        assert!(!state.positions_plain(), "a tool length of -0");
        assert!(!state.workpiece_is_machine(), "a tool length of -0");
        state.tool_length = 0.0;
        state.suppression = Some(Suppression::G53);
        assert!(!state.positions_plain(), "a suppressed block");
        assert!(state.workpiece_is_machine(), "a suppressed block");
        state.suppression = None;
        let axes = state.frame_axes.clone();
        let mut translated = Frame::neutral(&axes);
        translated
            .apply(
                &axes,
                gcodec_lang::FrameOp::Trans,
                &[(0, 5.0)],
                None,
                Plane::G17,
            )
            .unwrap();
        state.programmable = translated;
        assert!(!state.positions_plain(), "a translation");
        assert!(!state.workpiece_is_machine(), "a translation");
        state.note_traversed_frame();
        assert!(!state.positions_plain(), "a translation traversed");
        state.programmable = Frame::neutral(&axes);
        assert!(
            !state.positions_plain(),
            "a neutral frame after a translation, before a motion in it"
        );
        assert!(state.workpiece_is_machine());
        state.note_traversed_frame();
        assert!(state.positions_plain());
    }

    /// `S[CNT]=100` over many passes: each spindle the machine lacks is an
    /// error, and the table stays the profile's.
    #[test]
    fn spindles_the_machine_lacks_are_errors_not_new_entries() {
        let profile = gcodec_profile::builtin().expect("the built-in profile");
        let mut state = MachineState::new(Arc::new(profile));
        assert_eq!(state.spindles.len(), 1);
        for number in 2..100_000 {
            let error = state.spindle(Some(number)).expect_err("no such spindle");
            assert_eq!(error.code, codes::run::UNKNOWN_SPINDLE);
        }
        assert_eq!(state.spindles.len(), 1);
        assert_eq!(state.spindle(Some(0)).map(|s| s.number), Ok(1));
        assert_eq!(state.spindle(None).map(|s| s.number), Ok(1));
    }

    /// The machines of the repository's profiles: a built-in mill, a
    /// lathe (a diameter axis) and a five-axis mill.
    fn states() -> Vec<MachineState> {
        let mut profiles = vec![gcodec_profile::builtin().expect("the built-in profile")];
        for text in [
            include_str!("../../../../profiles/lathe_828d.toml"),
            include_str!("../../../../profiles/mill_5axis.toml"),
        ] {
            profiles.push(gcodec_profile::load(text).expect("a valid profile"));
        }
        profiles
            .into_iter()
            .map(|p| MachineState::new(Arc::new(p)))
            .collect()
    }

    /// The queries compare registry indices: they answer as the names of
    /// the commands would, for every index of their groups.
    #[test]
    fn modal_queries_by_index_answer_as_by_name() {
        let mut state = MachineState::new(Arc::new(
            gcodec_profile::builtin().expect("the built-in profile"),
        ));
        for index in 0..=u8::MAX {
            for group in [6u8, 13, 14, 29] {
                state.modal[usize::from(group) - 1] = index;
            }
            let plane = match state.modal(6) {
                Some("G18") => Plane::G18,
                Some("G19") => Plane::G19,
                _ => Plane::G17,
            };
            assert_eq!(state.plane(), plane, "index {index}");
            let inch = matches!(state.modal(13), Some("G70" | "G700"));
            assert_eq!(state.inch(), inch, "index {index}");
            assert_eq!(
                state.incremental(),
                state.modal(14) == Some("G91"),
                "index {index}"
            );
            let diameter = match state.modal(29) {
                Some("DIAMON") => (true, true),
                Some("DIAM90") => (true, false),
                _ => (false, false),
            };
            assert_eq!(state.diameter_mode(), diameter, "index {index}");
        }
    }

    /// A single capital letter is found in a table made when the state
    /// is: the same axis as by comparing names, on every machine.
    #[test]
    fn letters_name_the_axes_the_names_do() {
        for state in states() {
            for letter in b'A'..=b'Z' {
                let name = char::from(letter).to_string();
                assert_eq!(
                    state.axis_index(&name),
                    state.axis_index_by_name(&name),
                    "{name}"
                );
            }
            for name in ["x", "AX1", "ax2", "C1", "", "XX"] {
                assert_eq!(state.axis_index(name), state.axis_index_by_name(name));
            }
        }
    }
}
