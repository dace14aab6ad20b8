//! Runtime events: what the channel does, as it does it.
//!
//! The executor hands every event to an [`EventSink`] the moment it
//! happens and keeps nothing of it, so memory does not grow with the
//! length of a program or the number of loop passes. An event is one JSON
//! object with `"event"` naming its kind, the kind's fields and
//! `"source": {"file", "line", "col", "level"}` (SPEC §11.x "Events").
//!
//! The kinds of the tool-change, M-function and work-offset designs keep
//! their field names exactly: `tool_change` (`previous_tool`, `new_tool`,
//! `selection_source`, `substituted`), `m_function` (`m_value`, `class`,
//! `phase`, `action`), and the work-offset context of `motion`
//! (`effective_work_offset_selected`,
//! `effective_work_offset_enabled`, `effective_suppression_mask`).
//!
//! The types are the schema: `docs/schema/events.schema.json` is generated
//! from them ([`events_json_schema`]) and a test fails when the checked-in
//! file is stale.
//!
//! Sinks: [`JsonlSink`] (one object a line), [`TextSink`] (a readable
//! trace, one line an event), [`VecSink`] (keeps them, for tests) and
//! [`CountingSink`] (counts them, for benchmarks). The CSV format is not a
//! sink: its rows describe the state after each executed block, which
//! only the executor knows; it fills a [`BlockRow`] and hands it to a
//! [`CsvWriter`].
//!
//! This file holds the event model and [`EventSink`]; the work-offset
//! context of a motion is in `work_offset.rs` (the toolchanger's edges
//! are the toolchanger's, `crate::toolchanger`), axis names and
//! [`AxisMap`] in `axis_map.rs`, the sinks in `jsonl.rs`, `text.rs` and
//! `sinks.rs`, the CSV rows in `csv.rs`, and the number texts the writers
//! share in `numbers.rs`. Everything public is re-exported here.

mod axis_map;
mod csv;
mod jsonl;
mod line_buffer;
mod numbers;
mod sinks;
mod text;
mod work_offset;

use std::borrow::Cow;
use std::fmt;
use std::io;
use std::sync::Arc;

use gcodec_source::{Code, Severity};

pub use gcodec_ail::{MTiming, SelectorKind, Suppression, ToolChangeTrigger, ToolTiming};
pub use gcodec_lang::{MClass, MotionKind};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use crate::geometry::Plane;
pub use crate::toolchanger::{ToolchangerEdge, ToolchangerEvent};
pub use axis_map::{AxisMap, AxisName, axis_name, axis_names};
pub use csv::{BlockRow, CsvRows, CsvWriter, MAIN_MODAL_GROUPS, ModalColumn};
pub use jsonl::JsonlSink;
pub use sinks::{CountingSink, EventQueue, VecSink};
pub use text::{TextSink, write_trace_line};
pub use work_offset::{SuppressionMask, WorkOffsetContext};

/// One runtime event: what happened and where.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Event {
    #[serde(flatten)]
    pub kind: EventKind,
    pub source: EventSource,
}

impl Event {
    /// The kind's name as it appears in `"event"` (`motion`, `m_function`).
    pub fn kind_name(&self) -> &'static str {
        EVENT_KINDS[self.kind.index()]
    }
}

/// Where an event comes from: the block that caused it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct EventSource {
    /// The file as given to gcodec (a subprogram: as found on the search
    /// path).
    pub file: Arc<str>,
    /// 1-based line.
    pub line: u32,
    /// 1-based byte column.
    pub col: u32,
    /// The program level: 0 for the main program, 1 for a subprogram it
    /// calls, and so on.
    pub level: u32,
}

/// The names of the event kinds, in the order of [`EventKind`].
pub const EVENT_KINDS: [&str; 16] = [
    "motion",
    "modal_change",
    "m_function",
    "h_function",
    "tool_select",
    "tool_change",
    "spindle",
    "dwell",
    "message",
    "call",
    "return",
    "stop",
    "program_end",
    "diagnostic",
    "interrupt",
    "toolchanger",
];

/// What happened.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum EventKind {
    /// A traversing block. Not boxed: it is the commonest event, and an
    /// executor that refills one motion event allocates nothing per block.
    Motion(MotionEvent),
    /// The command of a modal G group changed.
    ModalChange(ModalChangeEvent),
    /// An M function was output (the M-function design).
    MFunction(MFunctionEvent),
    /// An H function was output to the PLC.
    HFunction(HFunctionEvent),
    /// A tool was selected (the tool-change design).
    ToolSelect(ToolSelectEvent),
    /// The tool changed (the tool-change design).
    ToolChange(ToolChangeEvent),
    /// A spindle's state or speed changed.
    Spindle(SpindleEvent),
    /// `G4`: the channel waits.
    Dwell(DwellEvent),
    /// `MSG("…")`: a message for the operator; empty clears it.
    Message(MessageEvent),
    /// A subprogram, cycle or program section starts (one event a pass).
    Call(CallEvent),
    /// A subprogram, cycle or program section ends.
    Return(ReturnEvent),
    /// The program stops or waits (`M0`, `M1`, `STOPRE`).
    Stop(StopEvent),
    /// The main program ends; the last event of a run.
    ProgramEnd(ProgramEndEvent),
    /// A problem found while running (an alarm of the control, a warning).
    Diagnostic(DiagnosticEvent),
    /// An input's interrupt assignment changed (`SETINT`, `ENABLE`,
    /// `DISABLE`, `CLRINT`).
    Interrupt(InterruptEvent),
    /// An edge of the toolchanger protocol (SPEC §12): a request, an
    /// acknowledgement, a committed change, a fault, an abort.
    Toolchanger(ToolchangerEvent),
}

impl EventKind {
    /// The position of the kind in [`EVENT_KINDS`].
    pub fn index(&self) -> usize {
        match self {
            Self::Motion(_) => 0,
            Self::ModalChange(_) => 1,
            Self::MFunction(_) => 2,
            Self::HFunction(_) => 3,
            Self::ToolSelect(_) => 4,
            Self::ToolChange(_) => 5,
            Self::Spindle(_) => 6,
            Self::Dwell(_) => 7,
            Self::Message(_) => 8,
            Self::Call(_) => 9,
            Self::Return(_) => 10,
            Self::Stop(_) => 11,
            Self::ProgramEnd(_) => 12,
            Self::Diagnostic(_) => 13,
            Self::Interrupt(_) => 14,
            Self::Toolchanger(_) => 15,
        }
    }
}

/// An input's interrupt assignment as it is after the statement: the
/// simulation records it, but no input ever fires.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct InterruptEvent {
    /// The fast input, 1…8.
    pub input: u32,
    /// What the statement did.
    pub change: InterruptChange,
    /// The routine; `null` for `LIFTFAST` alone and after `CLRINT`.
    pub routine: Option<String>,
    /// 1 (highest) … 128; `null` after `CLRINT`.
    pub priority: Option<u32>,
    /// `LIFTFAST`: a fast retraction before the routine.
    pub lift_fast: bool,
    /// `BLSYNC`: the routine starts at the end of the block in progress.
    pub block_sync: bool,
    /// Whether the input's signal would start the routine now.
    pub enabled: bool,
}

/// What an interrupt statement did to its input's assignment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InterruptChange {
    /// `SETINT`: assigned (or assigned anew) and enabled.
    Assigned,
    /// `ENABLE`.
    Enabled,
    /// `DISABLE`.
    Disabled,
    /// `CLRINT`: the assignment is removed.
    Cleared,
}

/// A traversing block.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MotionEvent {
    /// The interpolation; never `modal` (the executor knows the command
    /// when the block runs).
    pub motion: MotionKind,
    /// The position at the block's start, in workpiece coordinates (the
    /// active frames and offsets applied), every axis of the channel in
    /// the profile's order.
    pub from: AxisMap,
    /// The position at the block's end, in workpiece coordinates.
    pub to: AxisMap,
    /// The end position in machine coordinates.
    pub to_machine: AxisMap,
    /// The centre of an arc or helix, in workpiece coordinates (the axes
    /// of the plane); left out for other motions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub centre: Option<AxisMap>,
    /// The radius of an arc; left out for other motions.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<f64>,
    /// `TURN=`: full turns of a helix besides the arc; left out when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub turns: u32,
    /// The feed in force (its unit per `feed_mode`); `null` for rapid
    /// traverse.
    pub feed: Option<f64>,
    /// The group 15 command giving the feed's meaning (`G94` per minute,
    /// `G95` per revolution, `G93` inverse time, …).
    pub feed_mode: Cow<'static, str>,
    /// The working plane (group 6).
    pub plane: Plane,
    /// The work offset in effect for this block (the work-offset design).
    #[serde(flatten)]
    pub work_offset: WorkOffsetContext,
    /// An element the control inserts rather than one a block programs:
    /// a chamfer or rounding of the contour (`CHF`, `CHR`, `RND`, `RNDM`),
    /// or a corner element of the tool-centre path only; left out for a
    /// programmed element. `source` is the block that caused it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inserted: Option<InsertedElement>,
    /// With tool radius compensation on (`G41`/`G42`): where the tool
    /// centre goes; left out while compensation is off. Boxed: most
    /// programs never compensate, and the commonest event stays small.
    #[serde(default, flatten, skip_serializing_if = "Option::is_none")]
    pub tool: Option<Box<ToolCentre>>,
}

impl MotionEvent {
    /// Makes this event the programmed one `other`, reusing its storage;
    /// the tool fields are left as they are, for the caller to set.
    pub fn copy_from(&mut self, other: &MotionEvent) {
        self.motion = other.motion;
        self.from.copy_from(&other.from);
        self.to.copy_from(&other.to);
        self.to_machine.copy_from(&other.to_machine);
        match (&mut self.centre, &other.centre) {
            (Some(centre), Some(source)) => centre.copy_from(source),
            (centre, source) => centre.clone_from(source),
        }
        self.radius = other.radius;
        self.turns = other.turns;
        self.feed = other.feed;
        if !axis_map::same_name(&self.feed_mode, &other.feed_mode) {
            self.feed_mode.clone_from(&other.feed_mode);
        }
        self.plane = other.plane;
        self.work_offset = other.work_offset;
        self.inserted = other.inserted;
    }
}

/// Where the tool centre goes under tool radius compensation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ToolCentre {
    /// The tool centre at the element's end, in workpiece coordinates as
    /// `to` (the program's unit, diameters as programmed).
    pub tool_to: AxisMap,
    /// The tool centre's end position in machine coordinates.
    pub tool_to_machine: AxisMap,
    /// The compensated radius: the cutting edge's radius plus `OFFN`, in
    /// the program's unit.
    pub tool_radius: f64,
    /// The tool centre's own circle where the element's is not it: the
    /// tangential approach or retraction (`KONTT`) of a straight block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool_arc: Option<ToolArc>,
}

/// A circle of the tool-centre path.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ToolArc {
    /// `arc_cw` or `arc_ccw`, seen as the plane's circles are.
    pub motion: MotionKind,
    /// Its centre, in workpiece coordinates (the axes of the plane).
    pub centre: AxisMap,
    pub radius: f64,
}

/// What kind of element the control inserted into the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InsertedElement {
    /// A chamfer of the contour (`CHF=`, `CHR=`).
    Chamfer,
    /// A tangent rounding arc of the contour (`RND=`, `RNDM=`).
    Rounding,
    /// A circle of the tool-centre path round an outside corner (`G450`);
    /// the contour does not move (`from` = `to` = the corner).
    TransitionCircle,
    /// A straight piece of the tool-centre path at a corner (`G451`
    /// beyond its limit, `KONT` round a start point); the contour does
    /// not move.
    CornerLine,
    /// One of the straight pieces a `DISC=` transition curve is drawn in
    /// round an outside corner (`G450`); the contour does not move.
    TransitionCurve,
}

impl InsertedElement {
    /// The name as the events spell it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Chamfer => "chamfer",
            Self::Rounding => "rounding",
            Self::TransitionCircle => "transition_circle",
            Self::CornerLine => "corner_line",
            Self::TransitionCurve => "transition_curve",
        }
    }
}

fn is_zero(value: &u32) -> bool {
    *value == 0
}

/// The command of a modal G group changed.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ModalChangeEvent {
    /// The group, 1…64.
    pub group: u8,
    /// The new command as the registry spells it (`G1`, `G54`, `DIAMON`).
    pub code: Cow<'static, str>,
    /// The command before; `null` when the group had none.
    pub previous: Option<Cow<'static, str>>,
}

/// An M function (the M-function design).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct MFunctionEvent {
    /// The value, computed if it was an expression.
    pub m_value: u32,
    /// `M2=3`: the spindle; `null` for the master spindle.
    pub address_extension: Option<u32>,
    pub class: MClass,
    /// When it acted: `in_block`, or `post_motion` after the block's
    /// traversing motion (`M0 M1 M2 M17 M30` in a block with motion).
    pub phase: MTiming,
    /// What the channel did with it.
    pub action: MAction,
}

/// What the channel does with an M function (the M-function design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MAction {
    /// `M0`: programmed stop.
    ProgramStop,
    /// `M1`: optional stop (it stops only when the operator selected it).
    OptionalStop,
    /// `M2`, `M30`: end of the main program.
    ProgramEnd,
    /// `M17`: end of a subprogram (the return).
    SubprogramEnd,
    /// `M3`: spindle clockwise.
    SpindleCw,
    /// `M4`: spindle counter-clockwise.
    SpindleCcw,
    /// `M5`: spindle stop.
    SpindleStop,
    /// `M19`: spindle positioning.
    SpindlePosition,
    /// `M70`: the spindle switches to axis mode.
    SpindleAxisMode,
    /// The tool-change M (`M6`): the pending selection becomes active.
    ToolChange,
    /// `M40`: automatic gear stage selection.
    GearStageAuto,
    /// `M41`…`M45`: gear stage 1…5.
    GearStage,
    /// Any other value: output to the PLC, no action in the channel.
    Output,
}

/// An H function (reference §4.5), output to the PLC.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct HFunctionEvent {
    /// The value, computed if it was an expression.
    pub h_value: f64,
    /// `H2=5`: the extension 0…99; `null` when none is written.
    pub address_extension: Option<u32>,
    /// `H=QU(…)`: quick output.
    pub quick: bool,
    pub phase: MTiming,
}

/// A tool selection (the tool-change design).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ToolSelectEvent {
    /// How the program named the tool; never `computed` (the value is
    /// known when the block runs).
    pub selector_kind: SelectorKind,
    /// The number, location or name the selection resolved to.
    pub selector_value: String,
    /// The tool selected, as in `tool_change` (`T7`, `DRILL_10`); `null`
    /// for `T0` (no tool).
    pub selected_tool: Option<String>,
    /// `T1=…`: the spindle the selection is for.
    pub spindle_extension: Option<u32>,
    /// Whether the change is pending until the change M
    /// (`deferred_until_m6`) or happens now (`immediate`, followed by a
    /// `tool_change` event).
    pub timing: ToolTiming,
}

/// A tool change (the tool-change design).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ToolChangeEvent {
    /// The tool before the change (`T12`, or its name with tool
    /// management); `null` when the spindle held none.
    pub previous_tool: Option<String>,
    /// The tool after the change; `null` for `T0` (the tool is put away).
    pub new_tool: Option<String>,
    /// Where the change came from.
    pub selection_source: SelectionSource,
    /// Whether tool management replaced the selected tool by a substitute
    /// (a sister tool of the same name).
    pub substituted: bool,
    /// What triggered it: the change M (`m6`) or the `T` word (`t_word`).
    pub trigger: ToolChangeTrigger,
    /// Whether `new_tool` is in the spindle after it. `false`: the machine
    /// did not make the change (a soft toolchanger fault skipped it, the
    /// program goes on; or a hard fault aborted it, and an alarm follows):
    /// `previous_tool` stays in the spindle.
    pub committed: bool,
    /// The toolchanger's fault reason when a fault kept the change from
    /// being made.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fault_reason: Option<i32>,
}

/// How a tool change came about (the tool-change design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SelectionSource {
    /// Deferred mode: a `T` selection was pending and the change M made it
    /// active.
    PendingThenM6,
    /// Direct mode: the `T` word changed the tool at once.
    DirectTWord,
    /// The change M found no pending selection (`m6_without_pending_policy`
    /// is `warning` or `ignore`): the tool stays, `new_tool` is
    /// `previous_tool`.
    M6WithoutPending,
}

/// A spindle's state or speed changed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SpindleEvent {
    /// The spindle number (the master spindle when not programmed).
    pub spindle: u32,
    pub state: SpindleState,
    /// The programmed speed `S` (rev/min; under `G96` the cutting speed),
    /// kept while the spindle stands.
    pub speed: f64,
    /// `SPOS`, `M19`: the target position in degrees; left out otherwise.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<f64>,
}

/// What a spindle does.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SpindleState {
    /// `M5`, and the reset state.
    #[default]
    Stopped,
    /// `M3`.
    Cw,
    /// `M4`.
    Ccw,
    /// `M19`, `SPOS`: position-controlled, at `position`.
    Positioned,
    /// `M70`: the spindle is an axis.
    Axis,
}

impl SpindleState {
    /// The name used in JSON (`cw`, `stopped`).
    pub fn name(self) -> &'static str {
        match self {
            Self::Stopped => "stopped",
            Self::Cw => "cw",
            Self::Ccw => "ccw",
            Self::Positioned => "positioned",
            Self::Axis => "axis",
        }
    }
}

/// `G4`: a dwell, by time or by spindle revolutions.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DwellEvent {
    /// `G4 F…`: seconds.
    pub seconds: Option<f64>,
    /// `G4 S…`: revolutions of the master spindle.
    pub revolutions: Option<f64>,
}

/// `MSG("…")`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct MessageEvent {
    /// The text; empty when the program clears the message (`MSG()`).
    pub text: String,
}

/// A subprogram, cycle or section starts; its blocks run at the level of
/// this event's source plus one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CallEvent {
    /// The program called (upper case; for `PCALL` the path as written);
    /// for a `REPEAT` section, the section's start label.
    pub target: String,
    pub call_kind: CallKind,
    /// This pass, from 1.
    pub pass: u32,
    /// How many passes (`P3`; 1 when not written).
    pub passes: u32,
    /// `CALL … BLOCK … TO …`, `REPEAT`: the part of the program that
    /// runs, as labels or block numbers; left out for a whole program.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub section: Option<SectionEvent>,
    /// The arguments as the call passes them (evaluated; `null` for an
    /// omitted one); left out when there are none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub arguments: Vec<Option<ArgumentValue>>,
}

/// An argument of a call, evaluated.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum ArgumentValue {
    /// INT and REAL.
    Number(f64),
    Bool(bool),
    /// STRING, CHAR (one character), AXIS (its name), FRAME (`"FRAME"`).
    Text(String),
}

impl fmt::Display for ArgumentValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Number(n) => write!(f, "{n}"),
            Self::Bool(b) => write!(f, "{}", if *b { "TRUE" } else { "FALSE" }),
            Self::Text(t) => write!(f, "\"{t}\""),
        }
    }
}

/// How a call came about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum CallKind {
    /// Programmed in the block (`L123`, `CYCLE81(…)`, `CALL`, `PCALL`).
    Program,
    /// `MCALL`: the modal call after a traversing block.
    Modal,
    /// `REPEAT`, `REPEATB`: a section of the calling program.
    Repeat,
}

/// The part of a program a call runs.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct SectionEvent {
    pub from: String,
    pub to: String,
}

/// The end of what a `call` started; back at this event's level minus one.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ReturnEvent {
    /// The `target` of the matching `call`.
    pub target: String,
}

/// The program stops or waits.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct StopEvent {
    pub reason: StopReason,
    /// The instruction as the program wrote it (`STOPRE`), where that says
    /// more than `reason`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub detail: Option<String>,
}

/// Why the program stops.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// `M0`.
    ProgramStop,
    /// `M1`, with optional stop selected.
    OptionalStop,
    /// `STOPRE` and the like: block preparation waits for the main run.
    PreprocessingStop,
}

/// The main program ends.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ProgramEndEvent {
    pub reason: ProgramEndReason,
    /// Blocks executed in the whole run, subprograms and passes included.
    pub blocks: u64,
}

/// Why the main program ends.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProgramEndReason {
    /// `M2`.
    M2,
    /// `M30`.
    M30,
    /// `M17` or `RET` in the main program.
    M17,
    /// The text ended without an end M function.
    EndOfText,
    /// An alarm (a `diagnostic` of severity `error` just before) aborted
    /// the program.
    Alarm,
    /// A limit of the run (blocks, time) was reached, or the run was
    /// interrupted: the simulator's guard against endless loops.
    Limit,
    /// `M0` (or `M1` with optional stop selected) stopped the program; the
    /// simulation does not wait for NC start (`--no-stop` goes on).
    Stopped,
    /// The application stepping the run cancelled it (a
    /// `gcodec::run::cancelled` diagnostic just before).
    Cancelled,
}

/// A problem found while running.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct DiagnosticEvent {
    /// Stable code, `gcodec::AREA::NAME`, from the registry.
    #[schemars(with = "String")]
    pub code: &'static Code,
    /// An error is an alarm of the control: the run ends.
    pub severity: Severity,
    /// One sentence saying what is wrong.
    pub message: Cow<'static, str>,
    /// The alarm number the control shows (`14080`), where there is one:
    /// the code's, or the one a program raised (`SETAL`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alarm: Option<u32>,
    /// How to fix it, where a fix is known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub help: Option<Cow<'static, str>>,
}

impl DiagnosticEvent {
    /// A diagnostic with `code` at its level, with the code's alarm.
    pub fn new(code: &'static Code, message: impl Into<Cow<'static, str>>) -> Self {
        Self {
            code,
            severity: code.level(),
            message: message.into(),
            alarm: code.alarm(),
            help: None,
        }
    }
}

/// The JSON Schema of one event (a line of `jsonl` output), as checked in
/// under `docs/schema/events.schema.json`.
pub fn events_json_schema() -> String {
    let schema = schemars::schema_for!(Event);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}

/// Where events go. The executor calls [`EventSink::event`] as each event
/// happens and [`EventSink::finish`] once at the end of the run; an error
/// (a closed pipe, a full disk) ends the run.
pub trait EventSink {
    fn event(&mut self, event: &Event) -> io::Result<()>;

    /// Flushes whatever the sink buffers.
    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }

    /// Whether a [`crate::session::Session`] should hand over at the end
    /// of the block: the sink holds events for the application.
    fn wants_yield(&self) -> bool {
        false
    }

    /// Whether [`EventSink::wants_yield`] can ever be true: asked once,
    /// when the run starts, so that a sink that never hands over costs
    /// nothing per block.
    fn may_yield(&self) -> bool {
        false
    }

    /// Whether the sink reads motion events: asked once, when the run
    /// starts. A sink that answers `false` is sent none, and the executor
    /// does not build them (the CSV writes rows, `check --run` keeps
    /// diagnostics); every other event still comes, and the run's figures
    /// are the same.
    fn takes_motions(&self) -> bool {
        true
    }
}

impl<S: EventSink + ?Sized> EventSink for &mut S {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        (**self).event(event)
    }

    fn finish(&mut self) -> io::Result<()> {
        (**self).finish()
    }

    fn wants_yield(&self) -> bool {
        (**self).wants_yield()
    }

    fn may_yield(&self) -> bool {
        (**self).may_yield()
    }

    fn takes_motions(&self) -> bool {
        (**self).takes_motions()
    }
}

impl<S: EventSink + ?Sized> EventSink for Box<S> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        (**self).event(event)
    }

    fn finish(&mut self) -> io::Result<()> {
        (**self).finish()
    }

    fn wants_yield(&self) -> bool {
        (**self).wants_yield()
    }

    fn may_yield(&self) -> bool {
        (**self).may_yield()
    }

    fn takes_motions(&self) -> bool {
        (**self).takes_motions()
    }
}
