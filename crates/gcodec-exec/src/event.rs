//! Runtime events: what the channel does, as it does it.
//!
//! The executor hands every event to an [`EventSink`] the moment it
//! happens and keeps nothing of it, so memory does not grow with the
//! length of a program or the number of loop passes. An event is one JSON
//! object with `"event"` naming its kind, the kind's fields and
//! `"source": {"file", "line", "col", "level"}` (SPEC §11.x "Events").
//!
//! The kinds of the design seeds keep their field names exactly:
//! `tool_change` (seed 000: `previous_tool`, `new_tool`,
//! `selection_source`, `substituted`), `m_function` (seed 001: `m_value`,
//! `class`, `phase`, `action`), and the work-offset context of `motion`
//! (seed 003: `effective_work_offset_selected`,
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

use std::borrow::Cow;
use std::fmt;
use std::io::{self, BufWriter, Write};
use std::sync::Arc;

pub use gcodec_ail::{MTiming, SelectorKind, Suppression, ToolChangeTrigger, ToolTiming};
use gcodec_lang::addresses::letter_str;
pub use gcodec_lang::{MClass, MotionKind};
use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// An axis name in upper case (`X`, `C1`). Single letters are borrowed
/// statics, as in AIL, so that copying a name costs nothing.
pub type AxisName = Cow<'static, str>;

/// A profile's axis name as events and CSV columns write it: upper case,
/// a single letter borrowed.
pub fn axis_name(name: &str) -> AxisName {
    match name.as_bytes() {
        [b] if b.is_ascii_alphabetic() => Cow::Borrowed(letter_str(b.to_ascii_uppercase())),
        _ => Cow::Owned(name.to_ascii_uppercase()),
    }
}

/// The names of the channel axes of `profile`, in order.
pub fn axis_names(profile: &gcodec_profile::Profile) -> impl Iterator<Item = AxisName> + '_ {
    profile.axes.iter().map(|a| axis_name(a.name.get_ref()))
}

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
pub const EVENT_KINDS: [&str; 14] = [
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
    /// An M function was output (seed 001).
    MFunction(MFunctionEvent),
    /// An H function was output to the PLC.
    HFunction(HFunctionEvent),
    /// A tool was selected (seed 000).
    ToolSelect(ToolSelectEvent),
    /// The tool changed (seed 000).
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
        }
    }
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
    /// The work offset in effect for this block (seed 003).
    #[serde(flatten)]
    pub work_offset: WorkOffsetContext,
}

fn is_zero(value: &u32) -> bool {
    *value == 0
}

pub use crate::geometry::Plane;

/// The effective work-offset context of a block (seed 003): the modal
/// Group 8 selection and what the block's `G53`/`G153`/`SUPA` suppresses.
/// Suppression never changes the selection.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct WorkOffsetContext {
    /// The modal Group 8 selection (`g54`), lower case.
    pub effective_work_offset_selected: WorkOffsetCode,
    /// Whether the selected settable work offset acts in this block:
    /// false under a suppression and under `G500` (which deactivates it).
    pub effective_work_offset_enabled: bool,
    /// What the block suppresses.
    pub effective_suppression_mask: SuppressionMask,
}

impl WorkOffsetContext {
    /// The context of a block with the selection `selected` and the
    /// block's strongest suppression, if any.
    pub fn new(selected: WorkOffsetCode, suppression: Option<Suppression>) -> Self {
        Self {
            effective_work_offset_selected: selected,
            effective_work_offset_enabled: suppression.is_none()
                && selected != WorkOffsetCode::G500,
            effective_suppression_mask: SuppressionMask::from(suppression),
        }
    }
}

impl Default for WorkOffsetContext {
    /// `G500` without suppression, the registry's reset state.
    fn default() -> Self {
        Self::new(WorkOffsetCode::G500, None)
    }
}

/// A Group 8 command by its number (`G54` is 54, `G505` is 505). Every
/// member of group 8 is `G` and a number, so the number is the whole
/// identity; in JSON it is the lower-case code of seed 003 (`"g54"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct WorkOffsetCode(pub u16);

impl WorkOffsetCode {
    /// `G500`: no settable work offset.
    pub const G500: Self = Self(500);
    /// `G54`.
    pub const G54: Self = Self(54);

    /// Reads `G54`, `g54`, `G505`; `None` for anything else.
    pub fn parse(code: &str) -> Option<Self> {
        let digits = code.strip_prefix(['g', 'G'])?;
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        digits.parse().ok().map(Self)
    }
}

impl fmt::Display for WorkOffsetCode {
    /// The seed 003 spelling: `g54`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "g{}", self.0)
    }
}

impl Serialize for WorkOffsetCode {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for WorkOffsetCode {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = Cow::<str>::deserialize(deserializer)?;
        Self::parse(&text).ok_or_else(|| {
            serde::de::Error::custom(format!("`{text}` is not a Group 8 code like `g54`"))
        })
    }
}

impl JsonSchema for WorkOffsetCode {
    fn schema_name() -> Cow<'static, str> {
        "WorkOffsetCode".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A Group 8 command in lower case: `g500`, `g54`…`g57`, `g505`…`g599`.",
            "type": "string",
            "pattern": "^g[0-9]+$",
        })
    }
}

/// What a block's suppression switches off (seed 003). Each level
/// includes the ones before it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SuppressionMask {
    /// Nothing suppressed.
    #[default]
    None,
    /// `G53`: the settable and the programmable work offsets.
    SuppressSettableAndProgrammable,
    /// `G153`: as `G53`, and the basic frames.
    SuppressSettableProgrammableAndBasic,
    /// `SUPA`: as `G153`, and DRF (handwheel), overlaid movements, the
    /// external work offset and PRESET.
    SuppressSettableProgrammableBasicAndExternal,
}

impl From<Option<Suppression>> for SuppressionMask {
    fn from(suppression: Option<Suppression>) -> Self {
        match suppression {
            None => Self::None,
            Some(Suppression::G53) => Self::SuppressSettableAndProgrammable,
            Some(Suppression::G153) => Self::SuppressSettableProgrammableAndBasic,
            Some(Suppression::Supa) => Self::SuppressSettableProgrammableBasicAndExternal,
        }
    }
}

impl SuppressionMask {
    /// The name used in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::SuppressSettableAndProgrammable => "suppress_settable_and_programmable",
            Self::SuppressSettableProgrammableAndBasic => {
                "suppress_settable_programmable_and_basic"
            }
            Self::SuppressSettableProgrammableBasicAndExternal => {
                "suppress_settable_programmable_basic_and_external"
            }
        }
    }

    /// The command that suppresses this much (`G53`, `G153`, `SUPA`);
    /// `None` for no suppression.
    pub fn command(self) -> Option<&'static str> {
        match self {
            Self::None => None,
            Self::SuppressSettableAndProgrammable => Some("G53"),
            Self::SuppressSettableProgrammableAndBasic => Some("G153"),
            Self::SuppressSettableProgrammableBasicAndExternal => Some("SUPA"),
        }
    }
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

/// An M function (seed 001).
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

/// What the channel does with an M function (seed 001).
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

/// A tool selection (seed 000).
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

/// A tool change (seed 000).
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
}

/// How a tool change came about (seed 000).
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
}

/// A problem found while running.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct DiagnosticEvent {
    /// Stable code, `gcodec::exec::name`.
    pub code: Cow<'static, str>,
    pub severity: EventSeverity,
    /// One sentence saying what is wrong.
    pub message: Cow<'static, str>,
    /// The alarm number the control shows (`14080`), where there is one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alarm: Option<u32>,
    /// How to fix it, where a fix is known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub help: Option<Cow<'static, str>>,
}

/// How bad a diagnostic is; as [`gcodec_source::Severity`].
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum EventSeverity {
    Advice,
    Warning,
    /// The control raises an alarm; the run ends.
    Error,
}

impl From<gcodec_source::Severity> for EventSeverity {
    fn from(severity: gcodec_source::Severity) -> Self {
        match severity {
            gcodec_source::Severity::Advice => Self::Advice,
            gcodec_source::Severity::Warning => Self::Warning,
            gcodec_source::Severity::Error => Self::Error,
        }
    }
}

impl EventSeverity {
    /// The name used in JSON.
    pub fn name(self) -> &'static str {
        match self {
            Self::Advice => "advice",
            Self::Warning => "warning",
            Self::Error => "error",
        }
    }
}

// ---------------------------------------------------------------------------
// Axis maps

/// Axis → value, in the order the axes were put in (the profile's order
/// for positions). In JSON an object, `{"X": 10, "Y": 5}`, its keys in
/// that order.
///
/// A handful of axes per map makes a vector faster than any hash map, and
/// [`AxisMap::update`] and [`AxisMap::copy_from`] reuse it, so an executor
/// that refills one map per block allocates nothing.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AxisMap {
    entries: Vec<(AxisName, f64)>,
}

impl AxisMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty map with room for `capacity` axes.
    pub fn with_capacity(capacity: usize) -> Self {
        Self {
            entries: Vec::with_capacity(capacity),
        }
    }

    /// The value of `axis`.
    pub fn get(&self, axis: &str) -> Option<f64> {
        self.entries
            .iter()
            .find(|(name, _)| name == axis)
            .map(|(_, value)| *value)
    }

    /// Sets `axis`, appending it when it is new.
    pub fn insert(&mut self, axis: AxisName, value: f64) {
        match self.entries.iter_mut().find(|(name, _)| *name == axis) {
            Some(entry) => entry.1 = value,
            None => self.entries.push((axis, value)),
        }
    }

    /// Sets `axis` if the map has it; false otherwise. Never allocates.
    pub fn update(&mut self, axis: &str, value: f64) -> bool {
        match self.entries.iter_mut().find(|(name, _)| name == axis) {
            Some(entry) => {
                entry.1 = value;
                true
            }
            None => false,
        }
    }

    /// Makes this map equal to `other`, reusing its storage (names that
    /// are already in place are not copied).
    pub fn copy_from(&mut self, other: &AxisMap) {
        self.entries.truncate(other.entries.len());
        for (index, (name, value)) in other.entries.iter().enumerate() {
            match self.entries.get_mut(index) {
                Some(entry) => {
                    if entry.0 != *name {
                        entry.0.clone_from(name);
                    }
                    entry.1 = *value;
                }
                None => self.entries.push((name.clone(), *value)),
            }
        }
    }

    /// Removes every axis, keeping the storage.
    pub fn clear(&mut self) {
        self.entries.clear();
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The axes and values in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = (&str, f64)> + '_ {
        self.entries.iter().map(|(name, value)| (&**name, *value))
    }

    /// The values in order, to change them in place.
    pub fn values_mut(&mut self) -> impl ExactSizeIterator<Item = &mut f64> + '_ {
        self.entries.iter_mut().map(|(_, value)| value)
    }
}

impl FromIterator<(AxisName, f64)> for AxisMap {
    fn from_iter<I: IntoIterator<Item = (AxisName, f64)>>(iter: I) -> Self {
        let mut map = Self::new();
        for (axis, value) in iter {
            map.insert(axis, value);
        }
        map
    }
}

impl<const N: usize> From<[(&'static str, f64); N]> for AxisMap {
    fn from(entries: [(&'static str, f64); N]) -> Self {
        entries
            .into_iter()
            .map(|(axis, value)| (Cow::Borrowed(axis), value))
            .collect()
    }
}

impl Serialize for AxisMap {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.entries.len()))?;
        for (axis, value) in &self.entries {
            map.serialize_entry(&**axis, value)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for AxisMap {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct AxisMapVisitor;

        impl<'de> Visitor<'de> for AxisMapVisitor {
            type Value = AxisMap;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object of axis names and numbers")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut access: A) -> Result<AxisMap, A::Error> {
                let mut map = AxisMap::with_capacity(access.size_hint().unwrap_or(0).min(64));
                while let Some((axis, value)) = access.next_entry::<String, f64>()? {
                    map.insert(Cow::Owned(axis), value);
                }
                Ok(map)
            }
        }

        deserializer.deserialize_map(AxisMapVisitor)
    }
}

impl JsonSchema for AxisMap {
    fn schema_name() -> Cow<'static, str> {
        "AxisMap".into()
    }

    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "Axis name (upper case) → value, in the channel's axis order.",
            "type": "object",
            "additionalProperties": {"type": "number"},
        })
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

// ---------------------------------------------------------------------------
// Sinks

/// Where events go. The executor calls [`EventSink::event`] as each event
/// happens and [`EventSink::finish`] once at the end of the run; an error
/// (a closed pipe, a full disk) ends the run.
pub trait EventSink {
    fn event(&mut self, event: &Event) -> io::Result<()>;

    /// Flushes whatever the sink buffers.
    fn finish(&mut self) -> io::Result<()> {
        Ok(())
    }
}

impl<S: EventSink + ?Sized> EventSink for &mut S {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        (**self).event(event)
    }

    fn finish(&mut self) -> io::Result<()> {
        (**self).finish()
    }
}

impl<S: EventSink + ?Sized> EventSink for Box<S> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        (**self).event(event)
    }

    fn finish(&mut self) -> io::Result<()> {
        (**self).finish()
    }
}

/// `--format jsonl`: one JSON object a line, buffered.
///
/// Motions and modal changes, most of the output, are written by hand
/// rather than through serde: the derived path (a flattened, internally
/// tagged enum) costs about 1 µs an event, several times the hand-written
/// one. The bytes are the same; tests compare them. Lines are built
/// straight into the output buffer, which goes to the writer in blocks of
/// about 64 KiB; [`EventSink::finish`], [`JsonlSink::into_inner`] or
/// dropping the sink writes the rest.
pub struct JsonlSink<W: Write> {
    /// `None` only after [`JsonlSink::into_inner`].
    out: Option<W>,
    /// Lines not yet written.
    buffer: Vec<u8>,
    /// The last motion's `to`, as written.
    last_to: AxisMapText,
    /// The last event's file, as written.
    last_file: FileText,
}

/// A file name and its JSON text: every event names its file, mostly the
/// same one.
#[derive(Default)]
struct FileText {
    file: Option<Arc<str>>,
    text: Vec<u8>,
}

impl FileText {
    fn write(&mut self, out: &mut Vec<u8>, file: &Arc<str>) {
        if !self.file.as_ref().is_some_and(|f| Arc::ptr_eq(f, file)) {
            self.text.clear();
            write_str_json(&mut self.text, file);
            self.file = Some(Arc::clone(file));
        }
        out.extend_from_slice(&self.text);
    }
}

/// An axis map and its JSON text. A motion's `from` is the last motion's
/// `to`, and its `to_machine` is its `to` while no offset or frame is
/// active: their text is copied rather than written again (the numbers
/// were most of the time spent writing motions).
#[derive(Default)]
struct AxisMapText {
    /// The axes and the bits of their values.
    axes: Vec<(AxisName, u64)>,
    text: Vec<u8>,
}

impl AxisMapText {
    /// Whether `map` holds the same axes and the same values, bit for bit
    /// (`-0.0` is not `0.0`: their text differs).
    fn holds(&self, map: &AxisMap) -> bool {
        self.axes.len() == map.entries.len()
            && self
                .axes
                .iter()
                .zip(&map.entries)
                .all(|((axis, bits), (other, value))| {
                    *bits == value.to_bits() && same_name(axis, other)
                })
    }

    /// Writes `map` to `out` and remembers it.
    fn write(&mut self, out: &mut Vec<u8>, map: &AxisMap) {
        let start = out.len();
        write_axis_map_json(out, map);
        self.text.clear();
        self.text.extend_from_slice(&out[start..]);
        // The names are the same from motion to motion: cloning an owned
        // one each time would allocate.
        self.axes.truncate(map.entries.len());
        for (index, (axis, value)) in map.entries.iter().enumerate() {
            match self.axes.get_mut(index) {
                Some(slot) => {
                    if !same_name(&slot.0, axis) {
                        slot.0 = axis.clone();
                    }
                    slot.1 = value.to_bits();
                }
                None => self.axes.push((axis.clone(), value.to_bits())),
            }
        }
    }

    /// Writes `map` to `out`, copying the remembered text if it is the
    /// same map.
    fn write_if_same(&self, out: &mut Vec<u8>, map: &AxisMap) {
        if self.holds(map) {
            out.extend_from_slice(&self.text);
        } else {
            write_axis_map_json(out, map);
        }
    }
}

/// Axis names are mostly the same static strings: compare addresses
/// first.
fn same_name(a: &str, b: &str) -> bool {
    std::ptr::eq(a, b) || a == b
}

/// The size at which [`JsonlSink`] hands its lines to the writer.
const JSONL_BLOCK: usize = 1 << 16;

impl<W: Write> JsonlSink<W> {
    pub fn new(writer: W) -> Self {
        Self {
            out: Some(writer),
            buffer: Vec::with_capacity(JSONL_BLOCK + 4096),
            last_to: AxisMapText::default(),
            last_file: FileText::default(),
        }
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(mut self) -> io::Result<W> {
        self.write_buffer()?;
        let mut out = self.out.take().ok_or_else(taken)?;
        out.flush()?;
        Ok(out)
    }

    /// Hands the buffered lines to the writer.
    fn write_buffer(&mut self) -> io::Result<()> {
        if self.buffer.is_empty() {
            return Ok(());
        }
        let out = self.out.as_mut().ok_or_else(taken)?;
        let result = out.write_all(&self.buffer);
        self.buffer.clear();
        result
    }
}

/// The writer was given back (not reachable through the public API).
fn taken() -> io::Error {
    io::Error::other("the JSONL sink has no writer any more")
}

impl<W: Write> Drop for JsonlSink<W> {
    /// Writes what is buffered, as a `BufWriter` does when dropped.
    fn drop(&mut self) {
        let _ = self.write_buffer();
    }
}

impl<W: Write> EventSink for JsonlSink<W> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        match &event.kind {
            EventKind::Motion(motion) => {
                write_motion_json(&mut self.buffer, motion, &mut self.last_to);
                write_source_json(&mut self.buffer, &event.source, &mut self.last_file);
            }
            EventKind::ModalChange(change) => {
                write_modal_change_json(&mut self.buffer, change);
                write_source_json(&mut self.buffer, &event.source, &mut self.last_file);
            }
            _ => serde_json::to_writer(&mut self.buffer, event)?,
        }
        self.buffer.push(b'\n');
        if self.buffer.len() >= JSONL_BLOCK {
            self.write_buffer()?;
        }
        Ok(())
    }

    fn finish(&mut self) -> io::Result<()> {
        self.write_buffer()?;
        self.out.as_mut().ok_or_else(taken)?.flush()
    }
}

/// A motion event as serde writes it: the same fields in the same order,
/// numbers in the same shortest form.
/// (without its source and closing brace).
fn write_motion_json(out: &mut Vec<u8>, motion: &MotionEvent, last_to: &mut AxisMapText) {
    out.extend_from_slice(b"{\"event\":\"motion\",\"motion\":\"");
    out.extend_from_slice(motion_name(motion.motion).as_bytes());
    out.extend_from_slice(b"\",\"from\":");
    last_to.write_if_same(out, &motion.from);
    out.extend_from_slice(b",\"to\":");
    last_to.write(out, &motion.to);
    out.extend_from_slice(b",\"to_machine\":");
    last_to.write_if_same(out, &motion.to_machine);
    if let Some(centre) = &motion.centre {
        out.extend_from_slice(b",\"centre\":");
        write_axis_map_json(out, centre);
    }
    if let Some(radius) = motion.radius {
        out.extend_from_slice(b",\"radius\":");
        write_f64_json(out, radius);
    }
    if motion.turns != 0 {
        out.extend_from_slice(b",\"turns\":");
        write_u64(out, u64::from(motion.turns));
    }
    out.extend_from_slice(b",\"feed\":");
    match motion.feed {
        Some(feed) => write_f64_json(out, feed),
        None => out.extend_from_slice(b"null"),
    }
    out.extend_from_slice(b",\"feed_mode\":");
    write_str_json(out, &motion.feed_mode);
    out.extend_from_slice(b",\"plane\":\"");
    out.extend_from_slice(motion.plane.code().as_bytes());
    let context = &motion.work_offset;
    out.extend_from_slice(b"\",\"effective_work_offset_selected\":\"g");
    write_u64(out, u64::from(context.effective_work_offset_selected.0));
    out.extend_from_slice(b"\",\"effective_work_offset_enabled\":");
    out.extend_from_slice(if context.effective_work_offset_enabled {
        b"true"
    } else {
        b"false"
    });
    out.extend_from_slice(b",\"effective_suppression_mask\":\"");
    out.extend_from_slice(context.effective_suppression_mask.name().as_bytes());
    out.push(b'"');
}

/// A modal change as serde writes it (the second commonest event),
/// without its source and closing brace.
fn write_modal_change_json(out: &mut Vec<u8>, change: &ModalChangeEvent) {
    out.extend_from_slice(b"{\"event\":\"modal_change\",\"group\":");
    write_u64(out, u64::from(change.group));
    out.extend_from_slice(b",\"code\":");
    write_str_json(out, &change.code);
    out.extend_from_slice(b",\"previous\":");
    match &change.previous {
        Some(previous) => write_str_json(out, previous),
        None => out.extend_from_slice(b"null"),
    }
}

/// `,"source":{…}}`: the event's source and the event's closing brace.
fn write_source_json(out: &mut Vec<u8>, source: &EventSource, last_file: &mut FileText) {
    out.extend_from_slice(b",\"source\":{\"file\":");
    last_file.write(out, &source.file);
    out.extend_from_slice(b",\"line\":");
    write_u64(out, u64::from(source.line));
    out.extend_from_slice(b",\"col\":");
    write_u64(out, u64::from(source.col));
    out.extend_from_slice(b",\"level\":");
    write_u64(out, u64::from(source.level));
    out.extend_from_slice(b"}}");
}

fn write_axis_map_json(out: &mut Vec<u8>, axes: &AxisMap) {
    out.push(b'{');
    for (index, (axis, value)) in axes.iter().enumerate() {
        if index > 0 {
            out.push(b',');
        }
        write_str_json(out, axis);
        out.push(b':');
        write_f64_json(out, value);
    }
    out.push(b'}');
}

/// A JSON string. Names (axes, G codes, files) are plain almost always;
/// anything else goes through serde_json's escaping.
fn write_str_json(out: &mut Vec<u8>, text: &str) {
    let plain = text
        .bytes()
        .all(|b| b.is_ascii_graphic() && b != b'"' && b != b'\\');
    if plain {
        out.push(b'"');
        out.extend_from_slice(text.as_bytes());
        out.push(b'"');
    } else if serde_json::to_writer(&mut *out, text).is_err() {
        // Writing into a vector does not fail; keep the line valid anyway.
        out.extend_from_slice(b"\"\"");
    }
}

/// A number as serde_json writes an `f64`: `null` when not finite,
/// otherwise the shortest text that reads back as the same value, with
/// `.0` on whole numbers.
fn write_f64_json(out: &mut Vec<u8>, value: f64) {
    use serde_json::ser::Formatter;
    if !value.is_finite() {
        out.extend_from_slice(b"null");
    } else if !write_fixed_point(out, value, true) {
        // Writing into a vector does not fail.
        let _ = serde_json::ser::CompactFormatter.write_f64(out, value);
    }
}

/// Writes `value` with at most 4 decimals when that is its shortest text,
/// a whole number as `1.0` if `point_zero` (JSON) or `1` (Rust's `{}`);
/// false, writing nothing, when it is no such number.
///
/// Positions and feeds mostly have at most 4 decimals. When `n / 10^4`
/// reads back as `value` (IEEE division rounds correctly, so this is
/// exactly the round-trip test), that decimal is the shortest text: below
/// 1e9 an f64's spacing is far under 1e-4, so no other multiple of 1e-4
/// reads back as the same value.
fn write_fixed_point(out: &mut Vec<u8>, value: f64, point_zero: bool) -> bool {
    let scaled = value * 1e4;
    if !(value != 0.0 && value.abs() < 1e9) {
        return false;
    }
    // |scaled| < 1e13: exact in i64. Rounding half away from zero by hand
    // (`f64::round` is a library call here); whatever it gives, the test
    // below only lets an exact text through.
    let rounded = (scaled + 0.5f64.copysign(scaled)) as i64;
    if rounded as f64 / 1e4 != value {
        return false;
    }
    // The whole text is built on the stack and copied once: several small
    // copies per number cost more than the digits.
    let mut text = [0u8; 24];
    let mut len = 0;
    if rounded < 0 {
        text[0] = b'-';
        len = 1;
    }
    let magnitude = rounded.unsigned_abs();
    let mut whole = itoa::Buffer::new();
    let whole = whole.format(magnitude / 10_000).as_bytes();
    text[len..len + whole.len()].copy_from_slice(whole);
    len += whole.len();
    match fraction_digit_bytes(magnitude % 10_000, &mut [0; 4]) {
        b"" if point_zero => {
            text[len..len + 2].copy_from_slice(b".0");
            len += 2;
        }
        b"" => {}
        fraction => {
            text[len] = b'.';
            text[len + 1..len + 1 + fraction.len()].copy_from_slice(fraction);
            len += 1 + fraction.len();
        }
    }
    // A copy of a fixed size is inlined; one of `len` bytes is a call.
    out.extend_from_slice(&text);
    out.truncate(out.len() - text.len() + len);
    true
}

/// `fraction` (0…9999) as 4 decimals without trailing zeros; empty for
/// 0.
fn fraction_digits(fraction: u64, buffer: &mut [u8; 4]) -> &str {
    std::str::from_utf8(fraction_digit_bytes(fraction, buffer)).unwrap_or("")
}

/// [`fraction_digits`] as bytes (no UTF-8 check, for the JSONL writer).
fn fraction_digit_bytes(fraction: u64, buffer: &mut [u8; 4]) -> &[u8] {
    let fraction = fraction % 10_000;
    *buffer = [
        b'0' + (fraction / 1000) as u8,
        b'0' + (fraction / 100 % 10) as u8,
        b'0' + (fraction / 10 % 10) as u8,
        b'0' + (fraction % 10) as u8,
    ];
    let used = 4 - buffer.iter().rev().take_while(|d| **d == b'0').count();
    &buffer[..used]
}

fn write_u64(out: &mut Vec<u8>, value: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(value).as_bytes());
}

/// `--format text`: a readable trace, one line an event:
/// `12:1 [0] motion linear X10 Y5 Z0 F200 G94 G17 g54 machine X110 …`.
///
/// Numbers are rounded to 4 decimals for reading; the exact values are in
/// `jsonl`.
pub struct TextSink<W: Write> {
    out: BufWriter<W>,
    /// The line being built, reused.
    line: String,
}

impl<W: Write> TextSink<W> {
    pub fn new(writer: W) -> Self {
        Self {
            out: BufWriter::with_capacity(1 << 16, writer),
            line: String::with_capacity(256),
        }
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(self) -> io::Result<W> {
        self.out
            .into_inner()
            .map_err(io::IntoInnerError::into_error)
    }
}

impl<W: Write> EventSink for TextSink<W> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.line.clear();
        // Formatting into a string fails only if a `Display` impl does,
        // and ours do not.
        write_trace_line(&mut self.line, event).map_err(io::Error::other)?;
        self.out.write_all(self.line.as_bytes())
    }

    fn finish(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// Writes one line of the text trace, newline included.
pub fn write_trace_line(out: &mut impl fmt::Write, event: &Event) -> fmt::Result {
    let source = &event.source;
    write!(
        out,
        "{}:{} [{}] {}",
        source.line,
        source.col,
        source.level,
        event.kind_name()
    )?;
    match &event.kind {
        EventKind::Motion(motion) => {
            write!(out, " {}", motion_name(motion.motion))?;
            write_axes(out, &motion.to)?;
            if let Some(centre) = &motion.centre {
                write!(out, " centre")?;
                write_axes(out, centre)?;
            }
            if let Some(radius) = motion.radius {
                write!(out, " radius {}", Num(radius))?;
            }
            if motion.turns != 0 {
                write!(out, " turns {}", motion.turns)?;
            }
            match motion.feed {
                Some(feed) => write!(out, " F{} {}", Num(feed), motion.feed_mode)?,
                None => write!(out, " {}", motion.feed_mode)?,
            }
            let context = &motion.work_offset;
            write!(
                out,
                " {} {}",
                motion.plane.code(),
                context.effective_work_offset_selected
            )?;
            if let Some(command) = context.effective_suppression_mask.command() {
                write!(out, " {command}")?;
            } else if !context.effective_work_offset_enabled {
                write!(out, " off")?;
            }
            write!(out, " machine")?;
            write_axes(out, &motion.to_machine)?;
        }
        EventKind::ModalChange(change) => {
            write!(out, " group {}", change.group)?;
            match &change.previous {
                Some(previous) => write!(out, " {previous} -> {}", change.code)?,
                None => write!(out, " {}", change.code)?,
            }
        }
        EventKind::MFunction(m) => {
            match m.address_extension {
                Some(extension) => write!(out, " M{extension}={}", m.m_value)?,
                None => write!(out, " M{}", m.m_value)?,
            }
            write!(
                out,
                " {} {} {}",
                snake_name(&m.class),
                snake_name(&m.phase),
                snake_name(&m.action)
            )?;
        }
        EventKind::HFunction(h) => {
            match h.address_extension {
                Some(extension) => write!(out, " H{extension}={}", Num(h.h_value))?,
                None => write!(out, " H{}", Num(h.h_value))?,
            }
            if h.quick {
                write!(out, " quick")?;
            }
            write!(out, " {}", snake_name(&h.phase))?;
        }
        EventKind::ToolSelect(select) => {
            write!(
                out,
                " {} {} {}",
                select.selected_tool.as_deref().unwrap_or("none"),
                snake_name(&select.selector_kind),
                snake_name(&select.timing)
            )?;
            if let Some(spindle) = select.spindle_extension {
                write!(out, " spindle {spindle}")?;
            }
        }
        EventKind::ToolChange(change) => {
            write!(
                out,
                " {} -> {} {} {}",
                change.previous_tool.as_deref().unwrap_or("none"),
                change.new_tool.as_deref().unwrap_or("none"),
                snake_name(&change.selection_source),
                snake_name(&change.trigger)
            )?;
            if change.substituted {
                write!(out, " substituted")?;
            }
        }
        EventKind::Spindle(spindle) => {
            write!(
                out,
                " S{} {} {}",
                spindle.spindle,
                spindle.state.name(),
                Num(spindle.speed)
            )?;
            if let Some(position) = spindle.position {
                write!(out, " at {}", Num(position))?;
            }
        }
        EventKind::Dwell(dwell) => {
            if let Some(seconds) = dwell.seconds {
                write!(out, " {}s", Num(seconds))?;
            }
            if let Some(revolutions) = dwell.revolutions {
                write!(out, " {}rev", Num(revolutions))?;
            }
        }
        EventKind::Message(message) => write!(out, " {}", Quoted(&message.text))?,
        EventKind::Call(call) => {
            write!(
                out,
                " {} {} pass {}/{}",
                call.target,
                snake_name(&call.call_kind),
                call.pass,
                call.passes
            )?;
            if let Some(section) = &call.section {
                write!(out, " {}..{}", section.from, section.to)?;
            }
            if !call.arguments.is_empty() {
                out.write_str(" (")?;
                for (i, argument) in call.arguments.iter().enumerate() {
                    if i > 0 {
                        out.write_str(", ")?;
                    }
                    if let Some(argument) = argument {
                        write!(out, "{argument}")?;
                    }
                }
                out.write_char(')')?;
            }
        }
        EventKind::Return(ret) => write!(out, " {}", ret.target)?,
        EventKind::Stop(stop) => {
            write!(out, " {}", snake_name(&stop.reason))?;
            if let Some(detail) = &stop.detail {
                write!(out, " {detail}")?;
            }
        }
        EventKind::ProgramEnd(end) => {
            write!(out, " {} blocks {}", snake_name(&end.reason), end.blocks)?;
        }
        EventKind::Diagnostic(diagnostic) => {
            write!(out, " {} {}", diagnostic.severity.name(), diagnostic.code)?;
            if let Some(alarm) = diagnostic.alarm {
                write!(out, " alarm {alarm}")?;
            }
            write!(out, ": {}", diagnostic.message)?;
        }
    }
    out.write_char('\n')
}

fn write_axes(out: &mut impl fmt::Write, axes: &AxisMap) -> fmt::Result {
    for (axis, value) in axes.iter() {
        write!(out, " {axis}{}", Num(value))?;
    }
    Ok(())
}

/// The JSON name of a motion kind, without the allocation of
/// [`snake_name`]: motions are most of a trace.
fn motion_name(motion: MotionKind) -> &'static str {
    match motion {
        MotionKind::Modal => "modal",
        MotionKind::Rapid => "rapid",
        MotionKind::Linear => "linear",
        MotionKind::ArcCw => "arc_cw",
        MotionKind::ArcCcw => "arc_ccw",
        MotionKind::ArcThroughPoint => "arc_through_point",
        MotionKind::ArcTangential => "arc_tangential",
        MotionKind::Aspline => "aspline",
        MotionKind::Bspline => "bspline",
        MotionKind::Cspline => "cspline",
        MotionKind::Poly => "poly",
        MotionKind::Thread => "thread",
        MotionKind::ThreadIncreasingLead => "thread_increasing_lead",
        MotionKind::ThreadDecreasingLead => "thread_decreasing_lead",
        MotionKind::Tapping => "tapping",
        MotionKind::TappingRetract => "tapping_retract",
        MotionKind::ThreadConvexCw => "thread_convex_cw",
        MotionKind::ThreadConvexCcw => "thread_convex_ccw",
        MotionKind::InvoluteCw => "involute_cw",
        MotionKind::InvoluteCcw => "involute_ccw",
    }
}

/// The serde name of a unit-variant enum (`arc_cw`, `pending_then_m6`),
/// so that the trace uses the JSON's words.
fn snake_name<T: Serialize>(value: &T) -> Cow<'static, str> {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(name)) => Cow::Owned(name),
        _ => Cow::Borrowed("?"),
    }
}

/// A number for reading: rounded to 4 decimals, trailing zeros dropped,
/// whole numbers without a point, no `-0`.
struct Num(f64);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let value = self.0;
        if !value.is_finite() {
            return write!(f, "{value}");
        }
        let scaled = (value * 1e4).round();
        if scaled == 0.0 {
            return f.write_str("0");
        }
        if scaled.abs() >= 1e18 {
            return write!(f, "{:e}", scaled / 1e4);
        }
        // Fixed point in integers: exact, and much cheaper than `{:.4}`.
        let magnitude = scaled.abs() as u64;
        if scaled < 0.0 {
            f.write_str("-")?;
        }
        f.write_str(itoa::Buffer::new().format(magnitude / 10_000))?;
        let mut fraction_buffer = [0; 4];
        let fraction = fraction_digits(magnitude % 10_000, &mut fraction_buffer);
        if !fraction.is_empty() {
            f.write_str(".")?;
            f.write_str(fraction)?;
        }
        Ok(())
    }
}

/// A string in double quotes, with `"`, `\` and line breaks escaped, so
/// that a message stays on its line.
struct Quoted<'a>(&'a str);

impl fmt::Display for Quoted<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("\"")?;
        for c in self.0.chars() {
            match c {
                '"' => f.write_str("\\\"")?,
                '\\' => f.write_str("\\\\")?,
                '\n' => f.write_str("\\n")?,
                '\r' => f.write_str("\\r")?,
                c => fmt::Write::write_char(f, c)?,
            }
        }
        f.write_str("\"")
    }
}

/// Keeps every event, for tests.
#[derive(Clone, Debug, Default)]
pub struct VecSink {
    pub events: Vec<Event>,
}

impl VecSink {
    pub fn new() -> Self {
        Self::default()
    }
}

impl EventSink for VecSink {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.events.push(event.clone());
        Ok(())
    }
}

/// Counts events by kind and keeps nothing else, for benchmarks.
#[derive(Clone, Debug, Default)]
pub struct CountingSink {
    by_kind: [u64; EVENT_KINDS.len()],
}

impl CountingSink {
    pub fn new() -> Self {
        Self::default()
    }

    /// Events of the kind named `kind` (`motion`); 0 for an unknown name.
    pub fn count(&self, kind: &str) -> u64 {
        EVENT_KINDS
            .iter()
            .position(|name| *name == kind)
            .map_or(0, |index| self.by_kind[index])
    }

    /// All events.
    pub fn total(&self) -> u64 {
        self.by_kind.iter().sum()
    }
}

impl EventSink for CountingSink {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.by_kind[event.kind.index()] += 1;
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// CSV

/// A modal group shown as a CSV column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModalColumn {
    pub group: u8,
    /// The column's header.
    pub column: &'static str,
}

/// The modal groups of the CSV, in column order.
pub const MAIN_MODAL_GROUPS: [ModalColumn; 8] = [
    ModalColumn {
        group: 1,
        column: "motion",
    },
    ModalColumn {
        group: 6,
        column: "plane",
    },
    ModalColumn {
        group: 7,
        column: "radius_compensation",
    },
    ModalColumn {
        group: 8,
        column: "work_offset",
    },
    ModalColumn {
        group: 10,
        column: "path_mode",
    },
    ModalColumn {
        group: 13,
        column: "units",
    },
    ModalColumn {
        group: 14,
        column: "dimensions",
    },
    ModalColumn {
        group: 15,
        column: "feed_mode",
    },
];

/// The state after one executed block: one row of `--format csv`. The
/// executor keeps one row and refills it after every block (the maps and
/// strings keep their storage).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BlockRow {
    /// `N20`: 20; `None` for a block without a number.
    pub block_number: Option<u32>,
    pub file: Arc<str>,
    pub line: u32,
    /// The program level (0: main program).
    pub level: u32,
    /// The position at the block's end, in workpiece coordinates. Axes the
    /// writer's header names and the map lacks are empty cells.
    pub positions: AxisMap,
    /// The active tool (`T7`, or its name); `None`: no tool.
    pub tool: Option<String>,
    /// The active cutting edge (`D1`); 0: none.
    pub edge: u32,
    /// The feed in force, in the unit of group 15.
    pub feed: f64,
    /// The master spindle's programmed speed and state.
    pub spindle_speed: f64,
    pub spindle: SpindleState,
    /// The command of each group of [`MAIN_MODAL_GROUPS`], in that order
    /// (`G1`, `G17`, …; empty when unknown).
    pub modal: [Cow<'static, str>; MAIN_MODAL_GROUPS.len()],
}

impl BlockRow {
    /// Sets the command of `group` if the CSV shows that group; false
    /// otherwise.
    pub fn set_modal(&mut self, group: u8, code: Cow<'static, str>) -> bool {
        match MAIN_MODAL_GROUPS.iter().position(|c| c.group == group) {
            Some(index) => {
                self.modal[index] = code;
                true
            }
            None => false,
        }
    }
}

/// `--format csv`: a header, then one row per executed block.
///
/// Columns: `block,file,line,level`, one per axis (the order given to
/// [`CsvWriter::new`]), `tool,edge,feed,spindle_speed,spindle`, then the
/// [`MAIN_MODAL_GROUPS`]. Numbers are written exactly (the shortest text
/// that reads back as the same value); fields holding a comma, a quote or
/// a line break are quoted (RFC 4180).
pub struct CsvWriter<W: Write> {
    out: BufWriter<W>,
    axes: Vec<AxisName>,
    /// The row being built, reused.
    line: Vec<u8>,
}

impl<W: Write> CsvWriter<W> {
    /// Writes the header for the channel's `axes`.
    pub fn new(writer: W, axes: impl IntoIterator<Item = AxisName>) -> io::Result<Self> {
        let mut csv = Self {
            out: BufWriter::with_capacity(1 << 16, writer),
            axes: axes.into_iter().collect(),
            line: Vec::with_capacity(256),
        };
        csv.out.write_all(b"block,file,line,level")?;
        for axis in &csv.axes {
            write!(csv.out, ",{}", CsvField(axis))?;
        }
        csv.out
            .write_all(b",tool,edge,feed,spindle_speed,spindle")?;
        for column in &MAIN_MODAL_GROUPS {
            write!(csv.out, ",{}", column.column)?;
        }
        csv.out.write_all(b"\n")?;
        Ok(csv)
    }

    /// Writes the header for the channel axes of `profile`.
    pub fn for_profile(writer: W, profile: &gcodec_profile::Profile) -> io::Result<Self> {
        Self::new(writer, axis_names(profile))
    }

    /// Writes one row.
    pub fn row(&mut self, row: &BlockRow) -> io::Result<()> {
        let line = &mut self.line;
        line.clear();
        if let Some(number) = row.block_number {
            write_u64(line, u64::from(number));
        }
        line.push(b',');
        write_csv_field(line, &row.file);
        line.push(b',');
        write_u64(line, u64::from(row.line));
        line.push(b',');
        write_u64(line, u64::from(row.level));
        for axis in &self.axes {
            line.push(b',');
            if let Some(value) = row.positions.get(axis) {
                write_f64_csv(line, value);
            }
        }
        line.push(b',');
        write_csv_field(line, row.tool.as_deref().unwrap_or(""));
        line.push(b',');
        write_u64(line, u64::from(row.edge));
        line.push(b',');
        write_f64_csv(line, row.feed);
        line.push(b',');
        write_f64_csv(line, row.spindle_speed);
        line.push(b',');
        line.extend_from_slice(row.spindle.name().as_bytes());
        for code in &row.modal {
            line.push(b',');
            write_csv_field(line, code);
        }
        line.push(b'\n');
        self.out.write_all(line)
    }

    /// Flushes.
    pub fn finish(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(self) -> io::Result<W> {
        self.out
            .into_inner()
            .map_err(io::IntoInnerError::into_error)
    }
}

/// A number as Rust's `{}` writes it (shortest text that reads back, no
/// exponent, no `.0`), through the fixed-point path of
/// [`write_f64_json`] where it applies.
fn write_f64_csv(out: &mut Vec<u8>, value: f64) {
    if !write_fixed_point(out, value, false) {
        // Writing into a vector does not fail.
        let _ = write!(out, "{value}");
    }
}

fn write_csv_field(out: &mut Vec<u8>, field: &str) {
    // Writing into a vector does not fail.
    let _ = write!(out, "{}", CsvField(field));
}

/// A CSV field, quoted when it must be.
struct CsvField<'a>(&'a str);

impl fmt::Display for CsvField<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.0.contains([',', '"', '\n', '\r']) {
            return f.write_str(self.0);
        }
        f.write_str("\"")?;
        for (index, part) in self.0.split('"').enumerate() {
            if index > 0 {
                f.write_str("\"\"")?;
            }
            f.write_str(part)?;
        }
        f.write_str("\"")
    }
}
