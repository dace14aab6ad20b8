//! AIL, the executable instruction list: what lowering produces from a
//! checked program and what the executor runs.
//!
//! A document is `{"ail_version": 1, "instructions": [...]}`. Every
//! instruction is one JSON object with `"kind"`, the kind's fields and
//! `"source": {"file", "line", "col", "span"}`. The kinds of the
//! tool-change, M-function and work-offset designs keep their field names
//! exactly: `tool_select` and `tool_change`, `m_function`, `work_offset`.
//!
//! The types are the schema: `docs/schema/ail.schema.json` is generated
//! from them ([`json_schema`]) and a test fails when the checked-in file is
//! stale. Any change to the JSON shape that is not additive raises
//! [`AIL_VERSION`].
//!
//! `gcodec-sema` writes documents (`gcodec lower`); the executor runs
//! them.

mod expr;
mod hot_listing;
mod json_text;
mod number_text;

use std::borrow::Cow;
use std::sync::Arc;

pub use expr::{Callee, Expr, Value, VarKind, VarName};
use gcodec_lang::addresses::{AddressScope, NamedAddress, TransitionKind};
use gcodec_lang::ggroups::GCommand;
use gcodec_lang::{DataType, DimensionMode, FrameOp, MClass, MotionKind, WorkOffsetCode};
pub use json_text::{FileJsonText, write_json_string};
pub use number_text::{ShortNumberText, fixed_point_text, write_fixed_point, write_json_f64};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The version of the instruction schema written into every document.
pub const AIL_VERSION: u32 = 1;

/// An AIL document: the instructions of one program, in order.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Document {
    /// Always [`AIL_VERSION`] for documents this crate writes.
    pub ail_version: u32,
    pub instructions: Vec<Instruction>,
}

impl Document {
    /// An empty document of the current version.
    pub fn new() -> Self {
        Self {
            ail_version: AIL_VERSION,
            instructions: Vec::new(),
        }
    }
}

impl Default for Document {
    fn default() -> Self {
        Self::new()
    }
}

/// One instruction: what it does and where it comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Instruction {
    #[serde(flatten)]
    pub op: Op,
    pub source: Source,
}

/// Where an instruction comes from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Source {
    /// The file as given to gcodec.
    pub file: Arc<str>,
    /// 1-based line.
    pub line: u32,
    /// 1-based byte column.
    pub col: u32,
    pub span: ByteRange,
}

/// A byte range in the source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ByteRange {
    pub start: u32,
    pub end: u32,
}

/// What an instruction does.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Op {
    /// `T5`, `T=5`, `T1=5`, `T="DRILL_10"` (the tool-change design).
    ToolSelect(Box<ToolSelect>),
    /// The change itself: by the change M function (deferred mode) or by
    /// the `T` word (direct mode) (the tool-change design).
    ToolChange { trigger: ToolChangeTrigger },
    /// `D1`: the cutting edge; `D0` deselects the tool offset.
    CuttingEdge { edge: Value },
    /// `M3`, `M2=5` (the M-function design).
    MFunction(Box<MFunction>),
    /// The Group 8 selection and the block's suppression (the work-offset
    /// design).
    WorkOffset {
        /// The modal Group 8 code after this block, lower case (`g54`);
        /// `null` when the block only suppresses and its selection is not
        /// known before the program runs (the block is reached from places
        /// with different selections, or starts a subprogram): the
        /// executor knows it then.
        #[schemars(with = "Option<String>")]
        group8_selected: Option<WorkOffsetCode>,
        /// The strongest of `G53`, `G153`, `SUPA` in the block.
        suppression: Option<Suppression>,
        /// `block` when there is a suppression.
        suppression_scope: Option<SuppressionScope>,
    },
    /// A modal G command of any group but 8.
    ModalChange {
        // `code`'s group, written out for readers of the JSON (a doc
        // comment would change the schema).
        group: u8,
        /// The command in upper case (`G17`, `DIAMON`).
        #[schemars(with = "String")]
        code: GCommand,
    },
    /// A traversing block.
    Motion {
        motion: MotionKind,
        /// The programmed axes, in the order written.
        targets: Vec<AxisValue>,
        /// The circle data of arcs.
        circle: Option<Box<Circle>>,
        /// The rarer parts of a motion (axes named when the block runs,
        /// spline data, thread lead, contour transition), kept out of line
        /// so that the commonest instruction stays small. In JSON their
        /// fields are the motion's own, each left out when absent.
        #[serde(flatten, default, deserialize_with = "MotionDetails::deserialize_flat")]
        details: Option<Box<MotionDetails>>,
    },
    /// `F`.
    Feed { value: Value },
    /// `S`, `S2=…`, `S[SPINU]=…`.
    SpindleSpeed {
        spindle: Option<u32>,
        speed: Value,
        /// `S[SPINU]=…`: the spindle number, computed when the block runs
        /// (`spindle` is then `null`).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        spindle_expr: Option<Box<Expr>>,
    },
    /// `G4 F…` (seconds) or `G4 S…` (spindle revolutions).
    Dwell {
        seconds: Option<Value>,
        revolutions: Option<Value>,
    },
    /// A named address the executor interprets: `SPOS=90`, `FA[X]=400`,
    /// `OVR=50`, `LIMS=3000`, `DL=1`, `SD=3`, `POS[C]=90`.
    Address(Box<Address>),
    /// `H5`, `H2=5`, `H=QU(7)`: an auxiliary function for the PLC
    /// (reference §4.5), output like an M function.
    HFunction(Box<HFunction>),
    /// `G[8]=KORD`: the G command of `group` at the index `index` has when
    /// the block runs (indirect G programming); group 8 selects the work
    /// offset.
    ModalChangeIndirect { group: u8, index: Value },
    /// `TRANS`, `AROT`, …; no values resets the frame.
    Frame(Box<Frame>),
    /// A group 3 command whose axis words set a value instead of moving:
    /// the working-area limits (`G25`/`G26`, with `S` the spindle-speed
    /// limits), the pole (`G110`/`G111`/`G112`), the axial programmable
    /// offsets (`G58`/`G59`).
    AxisSetting(Box<AxisSetting>),
    /// `G74 X1=0` (reference point) or `G75 FP=2 X1=0` (fixed point): the
    /// named machine axes go to that point at rapid, outside every frame.
    ApproachPoint(Box<ApproachPoint>),
    /// `DEF`.
    Declare(Box<Declare>),
    /// `R1=…`, `NAME=…`, `$…=…`.
    Assign { target: Box<Expr>, value: Value },
    /// `A[0]=SET(1,2,3)`, `A[0]=(1,2,3)`, `A[2]=REP(0,5)`: values for
    /// consecutive elements of an array, from the element `target` names
    /// on, in storage order (the last index runs fastest).
    AssignList(Box<AssignList>),
    /// A jump target: a label, a block number, or a structure boundary.
    Label { name: String },
    /// Continue at `target`, if `condition` holds (always when absent).
    Jump {
        target: String,
        condition: Option<Box<Expr>>,
    },
    /// `/`, `/0`…`/9` before a block: when skip level `level` is on (the
    /// operator's switch or the profile's `skip_levels`), the block does not
    /// run: continue at the label `end`, right after the block's
    /// instructions. It follows the labels the block starts with (a jump to
    /// the block lands before the test, as on the control).
    SkipBlock {
        /// The skip level, 0…9 (`/` alone is 0).
        #[schemars(range(max = 9))]
        level: u8,
        /// The label right after the block's last instruction
        /// (`SKIP@<line>.end`).
        end: String,
    },
    /// A call of a subprogram or cycle.
    Call(Box<Call>),
    /// `MCALL` alone: the modal call ends.
    CancelModalCall,
    /// `REPEAT`/`REPEATB`: runs the instructions from the label `start`
    /// to the label `end` `passes` times, then goes on after this
    /// instruction, like a call of a part of the program.
    RepeatSection(Box<RepeatSection>),
    /// A jump whose target is a STRING computed when it runs
    /// (`GOTOF "LBL"<<I`). The executor searches the document's labels
    /// (every label and block number is a `label` instruction named
    /// `<name>@<line>` in such a document) the way `search` says.
    ComputedJump(Box<ComputedJump>),
    /// `GOTOS`: back to the start of the program when the PLC asks for it
    /// (otherwise on with the next instruction); `IF … GOTOS` only if
    /// `condition` holds.
    GotoStart { condition: Option<Box<Expr>> },
    /// `PROC`: the name and formal parameters of the program.
    Procedure(Box<Procedure>),
    /// `EXTERN`: the declared signature of a subprogram this program
    /// calls.
    External(Box<External>),
    /// `RET`, `M17` at the end of a subprogram.
    Return { values: Vec<Value> },
    /// `MSG("…")`.
    Message { text: Value },
    /// `STOPRE` and the like: a stop of the block preparation.
    Stop { reason: String },
    /// `SETINT(3) PRIO=1 LIFT_Z`: the interrupt routine of an input.
    InterruptAssign(Box<InterruptAssign>),
    /// `ENABLE(3)`, `DISABLE(3)`, `CLRINT(3)`: what acts on an input's
    /// interrupt assignment.
    InterruptControl {
        action: InterruptAction,
        /// The input, 1…8 (checked when computed).
        input: Value,
    },
    /// The end of the program text.
    End,
}

/// A tool selection (the tool-change design).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ToolSelect {
    pub selector_kind: SelectorKind,
    /// The tool number or location as digits, the tool name, or a
    /// computed selector as written.
    pub selector_value: String,
    /// The expression of a `computed` selector (`T=NAMES[I]`),
    /// evaluated when the block runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub selector_expr: Option<Expr>,
    /// `T1=…`: the spindle the selection is for.
    pub spindle_extension: Option<u32>,
    pub timing: ToolTiming,
    /// The word as written.
    pub raw: String,
}

/// An M function (the M-function design).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MFunction {
    /// `null` when the value is computed (`M1=DIR`): see `m_expr`.
    pub m_value: Option<u32>,
    /// The expression of a computed value, evaluated when the block
    /// runs (the executor checks its range then).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub m_expr: Option<Expr>,
    pub address_extension: Option<u32>,
    /// `M[SPINU]=3`: the spindle number, computed when the block runs
    /// (`address_extension` is then `null`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub address_extension_expr: Option<Expr>,
    pub class: MClass,
    pub timing: MTiming,
    pub raw: String,
}

/// A `DEF` of one variable.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Declare {
    pub name: String,
    /// `INT`, `REAL`, `BOOL`, `CHAR`, `STRING[n]` (`STRING` where the
    /// length is not a constant), `AXIS`, `FRAME`.
    #[schemars(with = "String")]
    pub data_type: DataType,
    pub dims: Vec<Value>,
    /// One value per element in storage order (the last index runs
    /// fastest); an omitted value (`SET(1,,3)`) is `null` and, like the
    /// elements after the list, keeps the type's initial value (0, FALSE,
    /// empty).
    pub init: Vec<Option<Value>>,
    /// `REP(value)` / `REP(value, count)`: `value` for `count` elements
    /// from the first on (for all of them without `count`); `init` is
    /// then empty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub init_repeat: Option<Repeat>,
}

/// `SETINT(<input>) PRIO=<priority> <routine> [LIFTFAST] [BLSYNC]`: when
/// the input's signal rises, the routine interrupts the program.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct InterruptAssign {
    /// The input, 1…8 (checked when computed).
    pub input: Value,
    /// 1 (highest) … 128 (checked when computed).
    pub priority: Value,
    /// The routine's name in upper case; `null` for `LIFTFAST` alone (a
    /// fast retraction without a routine).
    pub routine: Option<String>,
    /// `LIFTFAST`: retract fast before the routine.
    pub lift_fast: bool,
    /// `BLSYNC`: the routine starts at the end of the block in progress.
    pub block_sync: bool,
}

/// What `ENABLE`, `DISABLE` and `CLRINT` do to an input's interrupt.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum InterruptAction {
    /// `ENABLE(n)`: the assignment acts again.
    Enable,
    /// `DISABLE(n)`: the assignment stays but does not act.
    Disable,
    /// `CLRINT(n)`: the assignment is removed.
    Clear,
}

/// A call of a subprogram, cycle or predefined procedure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Call {
    /// The program's name in upper case; for `PCALL` the path as written;
    /// empty when `target_expr` computes it.
    pub target: String,
    /// `CALL <expr>`: the name or path, computed when the call runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_expr: Option<Expr>,
    /// `CALL … BLOCK <from> TO <to>`: only this part of the program runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub section: Option<CallSection>,
    /// `PCALL`: `target` is a path in the control's file system.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub by_path: bool,
    /// `EXTCALL`: a program from external storage, looked for first in
    /// the profile's `external_program_path` (`$SC_EXT_PROG_PATH`).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub external: bool,
    pub args: Vec<Option<Value>>,
    pub passes: Option<Value>,
    /// `MCALL`: called after every traversing block until cancelled.
    pub modal: bool,
}

/// How a tool is named (the tool-change design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SelectorKind {
    Number,
    Name,
    Location,
    /// A value computed when the block runs: a number, or with tool
    /// management a name or location, depending on its type then.
    Computed,
}

/// When a selection takes effect (the tool-change design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ToolTiming {
    Immediate,
    DeferredUntilM6,
}

/// What changes the tool (the tool-change design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ToolChangeTrigger {
    /// The profile's change M function (M6 by default).
    M6,
    /// The `T` word itself, in direct mode.
    TWord,
}

/// When an M function acts (the M-function design): `M0 M1 M2 M17 M30` in a
/// block with motion act after it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum MTiming {
    InBlock,
    PostMotion,
}

/// Block-scope suppression of offsets (the work-offset design), weakest first.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Suppression {
    G53,
    G153,
    Supa,
}

/// The scope of a suppression: always the block (the work-offset design).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum SuppressionScope {
    Block,
}

/// A value for one axis (or circle parameter), with its dimension mode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AxisValue {
    /// The axis or address in upper case (`X`, `C1`, `I`).
    pub axis: Cow<'static, str>,
    pub value: Value,
    /// `AC(…)`, `IC(…)`, … when written; otherwise the modal G90/G91 holds.
    pub mode: Option<DimensionMode>,
}

impl AxisValue {
    /// The value of a target written as a plain constant, with no `AC`,
    /// `IC` or other mode: the targets the hand-written listing and JSON
    /// lines cover.
    pub fn plain_constant(&self) -> Option<f64> {
        match (&self.value, self.mode) {
            (Value::Const(value), None) => Some(*value),
            _ => None,
        }
    }
}

/// The data of an arc, in the form it was programmed.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Circle {
    /// `I J K` (incremental from the start unless `=AC(…)`).
    pub centre: Vec<AxisValue>,
    /// `CR=`: negative for more than 180°.
    pub radius: Option<Value>,
    /// `AR=`: the opening angle in degrees.
    pub opening_angle: Option<Value>,
    /// `CIP I1= J1= K1=`.
    pub intermediate: Vec<AxisValue>,
    /// `TURN=`: extra full turns of a helix.
    pub turns: Option<Value>,
}

/// A named address (`kind: "address"`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Address {
    /// The address in upper case: `SPOS`, `FA`, `OVR`, `DL`.
    #[schemars(with = "String")]
    pub address: NamedAddress,
    /// The axis in brackets, when written as a name (`FA[X]` → `X`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<String>,
    /// The axis in brackets, computed when the block runs (`FA[AXN]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis_expr: Option<Expr>,
    /// The spindle of `SPOS[2]=`, `SPOSA[2]=`; the number of
    /// `TOFFL[1]=`, `FMA[2,X]=`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extension: Option<u32>,
    /// The spindle or number, computed when the block runs
    /// (`SPOS[SPINU]=`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extension_expr: Option<Expr>,
    /// The leading axis of a generic coupling (`CPLNUM[X,Y]=` → `Y`;
    /// `axis` is the following one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leading_axis: Option<String>,
    /// The leading axis, computed when the block runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub leading_axis_expr: Option<Expr>,
    pub value: Value,
    /// `AC`, `IC`, `DC`, `ACP`, `ACN`, … when written.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode: Option<DimensionMode>,
    /// Whether the value stays in force after the block.
    pub scope: AddressScope,
}

impl Address {
    /// `address` with `value` and nothing in brackets.
    pub fn new(address: NamedAddress, value: Value, scope: AddressScope) -> Self {
        Self {
            address,
            axis: None,
            axis_expr: None,
            extension: None,
            extension_expr: None,
            leading_axis: None,
            leading_axis_expr: None,
            value,
            mode: None,
            scope,
        }
    }
}

/// An H auxiliary function (reference §4.5).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct HFunction {
    /// The value (REAL or INT per MD22110); `null` when computed.
    pub h_value: Option<f64>,
    /// The expression of a computed value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub h_expr: Option<Expr>,
    /// `H2=5`: the extension 0…99.
    pub address_extension: Option<u32>,
    /// `H[I]=5`: the extension, computed when the block runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub address_extension_expr: Option<Expr>,
    /// `H=QU(…)`: quick output.
    #[serde(default)]
    pub quick: bool,
    pub timing: MTiming,
    /// The word as written.
    pub raw: String,
}

/// A programmable frame instruction.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Frame {
    /// The instruction in upper case (`TRANS`, `AROT`).
    #[schemars(with = "String")]
    pub op: FrameOp,
    pub values: Vec<AxisValue>,
    /// Values for axes named when the block runs (`ATRANS AX[_XX]=5`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub indirect_values: Vec<IndirectAxisValue>,
}

/// A group 3 command with its values ([`Op::AxisSetting`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct AxisSetting {
    /// `G25`, `G26`, `G110`, `G111`, `G112`, `G58` or `G59`.
    #[schemars(with = "String")]
    pub command: GCommand,
    /// The axis words in the order written; a pole may also be given by
    /// `AP`/`RP`.
    pub values: Vec<AxisValue>,
    /// `G25 S…`/`G26 S…`: the lower/upper spindle-speed limits.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub spindle_limits: Vec<SpindleLimit>,
}

/// A spindle-speed limit of `G25`/`G26` (`S1=…`; no extension: the master
/// spindle).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SpindleLimit {
    pub spindle: Option<u32>,
    pub speed: Value,
}

/// The approach of a machine-data point ([`Op::ApproachPoint`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ApproachPoint {
    /// `G74` (reference point) or `G75` (fixed point).
    #[schemars(with = "String")]
    pub command: GCommand,
    /// `FP=` of `G75` (1 when not written); `null` for `G74`.
    pub fixed_point: Option<Value>,
    /// The channel axes of the machine axes named (`X1=0` names the
    /// machine axis of `X`), upper case; the programmed values only select
    /// the axes.
    pub axes: Vec<Cow<'static, str>>,
}

/// The rarer parts of a motion ([`Op::Motion`]).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MotionDetails {
    /// Axes named when the block runs (`AX[_Z]=…`, `AX[AXNAME]=…`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub indirect_targets: Vec<IndirectAxisValue>,
    /// `PW=`, `PL=` of a spline or polynomial block.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spline: Option<SplineData>,
    /// The lead of a thread or tapping block (`G33 Z… K…`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thread: Option<Thread>,
    /// `CHF=`, `CHR=`, `RND=`: the transition inserted between this
    /// block's contour element and the next one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub transition: Option<Transition>,
}

impl MotionDetails {
    /// Nothing but defaults.
    pub fn is_empty(&self) -> bool {
        *self == Self::default()
    }

    /// The details of a motion, `None` when it has none (as it was
    /// written), so that a document reads back as it was.
    fn deserialize_flat<'de, D: serde::Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<Box<Self>>, D::Error> {
        let details = Self::deserialize(deserializer)?;
        Ok((!details.is_empty()).then(|| Box::new(details)))
    }
}

/// A motion target whose axis is named when the block runs (`AX[_Z]=5`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct IndirectAxisValue {
    /// The expression naming the axis.
    pub axis: Expr,
    pub value: Value,
    pub mode: Option<DimensionMode>,
}

/// Spline data of a block: `PW=` point weight, `PL=` parameter interval
/// length. (`SD=`, the modal spline degree, is an `address`.)
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct SplineData {
    pub weight: Option<Value>,
    pub interval: Option<Value>,
}

/// The lead of a thread or tapping block.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Thread {
    /// `I J K`: the lead along X, Y, Z.
    pub lead: Vec<AxisValue>,
    /// `G34`/`G35`: the change of lead (programmed with `F`).
    pub lead_change: Option<Value>,
}

/// A contour transition at the end of a block's contour element.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Transition {
    pub kind: TransitionKind,
    pub value: Value,
}

/// The JSON Schema of an AIL document, as checked in under
/// `docs/schema/ail.schema.json`.
pub fn json_schema() -> String {
    let schema = schemars::schema_for!(Document);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}

/// Writes the readable listing of `gcodec lower --format text`: one
/// instruction a line, `line:col kind field=value…`, expressions in infix
/// form (`R1+5`), fully parenthesised so that the order of evaluation shows.
pub fn write_listing(document: &Document, out: &mut impl std::fmt::Write) -> std::fmt::Result {
    for instruction in &document.instructions {
        write_instruction_listing(instruction, out)?;
    }
    Ok(())
}

/// Writes the line of [`write_listing`] for one instruction, newline
/// included: a listing written as the instructions come.
pub fn write_instruction_listing(
    instruction: &Instruction,
    out: &mut impl std::fmt::Write,
) -> std::fmt::Result {
    if let Some(written) = hot_listing::write_hot(instruction, out) {
        return written;
    }
    write_general_listing(instruction, out)
}

/// [`write_instruction_listing`] of any instruction, through its JSON
/// value.
fn write_general_listing(
    instruction: &Instruction,
    out: &mut impl std::fmt::Write,
) -> std::fmt::Result {
    let source = &instruction.source;
    let fields = serde_json::to_value(&instruction.op).unwrap_or_default();
    let kind = fields.get("kind").and_then(|k| k.as_str()).unwrap_or("?");
    write!(out, "{:>6}:{:<4} {kind}", source.line, source.col)?;
    if let Some(map) = fields.as_object() {
        for (key, value) in map.iter().filter(|(k, v)| *k != "kind" && !v.is_null()) {
            write!(out, " {key}={}", listing_value(value))?;
        }
    }
    writeln!(out)
}

/// A field of the listing: expressions (objects with `op`) in infix form,
/// everything else as compact JSON.
fn listing_value(value: &serde_json::Value) -> String {
    use serde_json::Value as J;
    let text = |v: &J| v.as_str().unwrap_or("?").to_owned();
    match value {
        J::Array(items) => {
            let items: Vec<String> = items.iter().map(listing_value).collect();
            format!("[{}]", items.join(", "))
        }
        J::Object(map) => match map.get("op").and_then(J::as_str) {
            Some("number") => map.get("value").map_or_else(String::new, listing_value),
            Some("string") => format!("\"{}\"", text(&map["value"])),
            Some("bool") => map
                .get("value")
                .map_or_else(String::new, ToString::to_string),
            Some("var") => {
                let name = text(&map["name"]);
                let indices: Vec<String> = map["indices"]
                    .as_array()
                    .map(|i| i.iter().map(listing_value).collect())
                    .unwrap_or_default();
                match (name.as_str(), indices.as_slice()) {
                    (_, []) => name,
                    ("R", [index]) if map["var_kind"] == "r_parameter" => format!("R{index}"),
                    _ => format!("{name}[{}]", indices.join(",")),
                }
            }
            Some("call") => {
                let args: Vec<String> = map["args"]
                    .as_array()
                    .map(|a| {
                        a.iter()
                            .map(|x| {
                                if x.is_null() {
                                    String::new()
                                } else {
                                    listing_value(x)
                                }
                            })
                            .collect()
                    })
                    .unwrap_or_default();
                format!("{}({})", text(&map["name"]), args.join(","))
            }
            Some("unary") => {
                let op = match map["operator"].as_str() {
                    Some("neg") => "-",
                    Some("plus") => "+",
                    Some("not") => "NOT ",
                    Some("b_not") => "B_NOT ",
                    _ => "<<",
                };
                format!("{op}{}", listing_value(&map["operand"]))
            }
            Some("binary") => {
                let op = match map["operator"].as_str().unwrap_or("") {
                    "mul" => "*",
                    "div" => "/",
                    "int_div" => " DIV ",
                    "mod" => " MOD ",
                    "add" => "+",
                    "sub" => "-",
                    "b_and" => " B_AND ",
                    "b_xor" => " B_XOR ",
                    "b_or" => " B_OR ",
                    "and" => " AND ",
                    "xor" => " XOR ",
                    "or" => " OR ",
                    "concat" => "<<",
                    "eq" => "==",
                    "ne" => "<>",
                    "lt" => "<",
                    "gt" => ">",
                    "le" => "<=",
                    "ge" => ">=",
                    _ => ":",
                };
                format!(
                    "({}{op}{})",
                    listing_value(&map["lhs"]),
                    listing_value(&map["rhs"])
                )
            }
            _ => {
                let fields: Vec<String> = map
                    .iter()
                    .filter(|(_, v)| !v.is_null() && v.as_array().is_none_or(|a| !a.is_empty()))
                    .map(|(k, v)| format!("{k}={}", listing_value(v)))
                    .collect();
                format!("{{{}}}", fields.join(" "))
            }
        },
        J::Number(n) => match n.as_f64() {
            // Whole numbers as the program writes them: `R1`, not `R1.0`.
            Some(v) if v.fract() == 0.0 && v.abs() < 1e15 => format!("{}", v as i64),
            _ => n.to_string(),
        },
        other => other.to_string(),
    }
}

/// The part of a program `CALL … BLOCK … TO …` runs: labels or block
/// numbers (`N100`) as written, in upper case; the executor searches them
/// in the called program.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CallSection {
    pub from: Value,
    pub to: Value,
}

/// `REPEAT` of a section of the program.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RepeatSection {
    /// The label before the section's first instruction.
    pub start: String,
    /// The label after the section's last instruction.
    pub end: String,
    /// How often the section runs (`P=`, 1 when not written).
    pub passes: Value,
}

/// How a jump searches for its target (language reference §8.1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum JumpSearch {
    /// `GOTOF`: towards the end of the program.
    Forward,
    /// `GOTOB`: towards its start.
    Backward,
    /// `GOTO`, `GOTOC`: forward first, then backward.
    ForwardThenBackward,
}

/// A jump to a computed target.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ComputedJump {
    /// The STRING expression naming a label or a block number (`"N100"`).
    pub target: Expr,
    pub search: JumpSearch,
    /// `GOTOC`: a target that is not found is no alarm; the program goes
    /// on with the next instruction.
    pub continue_if_missing: bool,
    /// Jump only if this holds (`IF … GOTOF …`).
    pub condition: Option<Expr>,
}

/// `PROC name(params) attributes`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Procedure {
    /// In upper case.
    pub name: String,
    pub params: Vec<Parameter>,
    /// `SBLOF`, `DISPLOF`, `SAVE`, … in upper case.
    pub attributes: Vec<String>,
}

/// A formal parameter of a `PROC`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Parameter {
    /// In upper case.
    pub name: String,
    /// `INT`, `REAL`, `BOOL`, `CHAR`, `STRING[n]` (`STRING` where the
    /// length is not a constant), `AXIS`, `FRAME`.
    #[schemars(with = "String")]
    pub data_type: DataType,
    /// `VAR`: the caller's variable itself, not a copy.
    pub by_reference: bool,
    pub dims: Vec<Value>,
    /// The value when the caller leaves the argument out.
    pub default: Option<Value>,
}

/// `EXTERN name(types)`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct External {
    /// In upper case.
    pub name: String,
    pub params: Vec<ExternalParameter>,
}

/// A parameter type of an `EXTERN` declaration.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ExternalParameter {
    /// As in [`Parameter::data_type`].
    #[schemars(with = "String")]
    pub data_type: DataType,
    pub by_reference: bool,
    /// One entry per array dimension; empty ones (`REAL[,]`) are `null`.
    pub dims: Vec<Option<Value>>,
}

/// Values for consecutive array elements (`assign_list`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct AssignList {
    /// The first element written (`A[0]`, `R[10]`).
    pub target: Expr,
    /// `SET(…)` or `(…)`: one value per element; an omitted one (`null`)
    /// leaves its element as it is. Empty for `REP`.
    pub values: Vec<Option<Value>>,
    /// `REP(value[, count])`: `value` for `count` elements (for the rest
    /// of the array without `count`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat: Option<Repeat>,
}

/// `REP(value[, count])`: one value for several consecutive elements.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Repeat {
    pub value: Value,
    /// How many elements; `None`: to the end of the array.
    pub count: Option<Value>,
}
