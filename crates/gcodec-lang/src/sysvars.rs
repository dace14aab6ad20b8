//! The registry of SINUMERIK system variables (`$…` names) that lowering
//! checks references against.
//!
//! The control rejects a `$` name it does not know (alarm at translation
//! time), and so must we: [`lookup`] answers whether a name is known and, if
//! so, which indices it takes ([`IndexShape`]) and whether a program may
//! assign it ([`SysVar::writable`]).
//!
//! # What is listed
//!
//! Two tables. The catalogue (`data/system-variables.tsv`, the control's
//! lists of 05/2017 as the shared reference gives them, turned into a
//! sorted table by `build.rs`) holds every system variable of the lists,
//! 2132 `$` names, with its data type and number of dimensions: a
//! catalogue entry's indices are counted, not kinded
//! ([`IndexShape::Dims`]). The registry below refines the names programs
//! use, and adds the machine and setting data the lists lack, with the
//! exact shape of their indices, whether a program may write them and a
//! description. [`lookup`] asks the registry first, then the catalogue.
//!
//! The registry is the part of the control's vocabulary the project has
//! evidence for:
//!
//! - every `$` name used in the shared program corpus (`shared/corpus`),
//!   including names that appear only in commented-out lines, because the
//!   programs' authors evidently used them on a real control;
//! - every `$` name the language reference names (§5 tools, §6 work offsets,
//!   §7 variables, §8 subprograms, §9 frames, and the machine data it cites);
//! - the complete families a listed name belongs to where the family is
//!   small and fixed (`$TC_DP1`…`$TC_DP25`, `$TC_TPG1`…`$TC_TPG9`,
//!   `$P_ISO1FRAME`…`$P_ISO4FRAME`), so that a program using `$TC_DP5`
//!   next to `$TC_DP3` is not rejected.
//!
//! Machine data (`$MN_`, `$MC_`, `$MA_`) and setting data (`$SN_`, `$SC_`,
//! `$SA_`) are only listed where used or named. There are thousands of them,
//! so [`lookup`] does **not** accept an arbitrary name with such a prefix —
//! the syntax-check program in the corpus expects `$MN_G53_TOLCORR` (a typo
//! for `$MN_G53_TOOLCORR`) to be rejected as unknown. Callers that want a
//! softer policy for unlisted machine or setting data (a warning rather than
//! an error, or a profile-supplied list) can ask
//! [`is_machine_or_setting_data`].
//!
//! # Spelling
//!
//! Names are case-insensitive, as on the control. The `$$` prefix (read or
//! write the variable at main run, e.g. `$$SA_LEAD_OFFSET_OUT_POS[X]` in a
//! synchronized action) names the same variable as `$`: [`lookup`] strips
//! one `$` and looks up the rest. Whether `$$` is allowed on a given name is
//! left to the caller.
//!
//! `;$PATH=…` in a file header is a comment, not a variable, and is not
//! listed.

use crate::DataType;
use crate::names::compare_ignore_case;

/// The indices a system variable takes in brackets.
///
/// The variants are the shapes found in the corpus and the reference; they
/// are few on purpose, because lowering only needs to check the count and
/// the kind (axis name or number) of each index.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IndexShape {
    /// No index: `$P_TOOLNO`, `$MN_SCALING_VALUE_INCH`, `$PI`.
    None,
    /// One axis name, or an expression of type `AXIS`: `$AA_IM[X]`,
    /// `$P_EP[_Z]`, `$SA_SPIND_S[C]`, `$MA_CEC_ENABLE[AX1]`. Axial machine
    /// and setting data take this shape too.
    Axis,
    /// One integer expression: `$A_IN[1]`, `$P_GG[8]`, `$R[20]`,
    /// `$TC_TPG1[t]`, `$MC_GCODE_RESET_VALUES[group-1]`.
    Number,
    /// This many integer expressions: `$TC_DP1[t,d]` and `$AN_CEC[table,point]`
    /// are `Numbers(2)`.
    ///
    /// Tool offsets with the flat-D-number option take one index
    /// (`$TC_DP1[d]`); that option is machine configuration, not modelled
    /// here, so `$TC_DP…` is `Numbers(2)` as in the reference and the corpus.
    Numbers(u8),
    /// A single frame: bare for the whole frame
    /// (`$P_UBFR = CTRANS(X,10) : CROT(Z,45)`), or `[axis, component]` for one
    /// component (`$P_UBFR[Y,TR]=5`, `$P_ACTFRAME[_Z,SC]`). Components are
    /// `TR` translation, `FI` fine offset, `RT` rotation, `SC` scale and `MI`
    /// mirror.
    Frame,
    /// An array of frames: `[n]` for a whole frame (`$P_UIFR[1]=CTRANS(X,10)`)
    /// or `[n, axis, component]` for one component (`$P_UIFR[1,X,TR]=10`).
    FrameComponent,
    /// This many indices, of a kind the catalogue does not give (an axis
    /// or a number): `$VA_IM[X]`, `$AC_PARAM[1]`, `$TC_MPP1[m,p]`.
    Dims(u8),
    /// Not settled by the sources: any number and kind of index is accepted.
    ///
    /// No built-in entry uses it today — every listed name's shape follows
    /// from its uses in the corpus or from the reference. It exists for
    /// catalogue entries added later whose shape is unknown, so that they
    /// can be known by name without a guessed shape causing false errors.
    Any,
}

impl IndexShape {
    /// Whether a reference with `count` indices fits this shape.
    ///
    /// Only the count is checked; whether an index is an axis name or a
    /// number needs the expression's type, which the caller has.
    pub fn accepts(self, count: usize) -> bool {
        match self {
            IndexShape::None => count == 0,
            IndexShape::Axis | IndexShape::Number => count == 1,
            IndexShape::Numbers(n) | IndexShape::Dims(n) => count == usize::from(n),
            IndexShape::Frame => count == 0 || count == 2,
            IndexShape::FrameComponent => count == 1 || count == 3,
            IndexShape::Any => true,
        }
    }
}

/// One known system variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SysVar {
    /// The name with one `$`, in upper case (`$P_UIFR`).
    pub name: &'static str,
    /// The indices it takes.
    pub shape: IndexShape,
    /// Whether a part program may assign it.
    ///
    /// False for what the control computes or reports: actual positions
    /// and inputs (`$AA_IM`, `$A_IN`), programmed state (`$P_TOOLNO`,
    /// `$P_GG`, `$P_EP`), values passed to replacement cycles (`$C_T`), the
    /// results of frame chaining (`$P_ACTFRAME`) and `$PI`. The reference
    /// states this by kind (§7.4: `$A…` current values, `$P…` programmed
    /// values) rather than per name, and no corpus program writes one.
    ///
    /// True for tool data, R parameters, the frames that hold offsets,
    /// outputs and compensation tables, and for machine and setting data:
    /// the control lets a program write those given the access level (the
    /// corpus does: `$SN_CEC_TABLE_ENABLE[0]=0`,
    /// `$MN_G53_TOOLCORR = 'H20' ; known`); access levels and when a written
    /// machine datum takes effect are not modelled. Where the sources settle
    /// nothing (the system frames such as `$P_SETFRAME`) the entry is
    /// writable, so that an uncertain entry never causes a false error.
    pub writable: bool,
    /// What it holds, in a few words.
    pub description: &'static str,
    /// Its data type as the catalogue gives it; `None` in the registry,
    /// where [`SysVar::data_type`] finds it.
    pub ty: Option<DataType>,
}

/// Shorthand that keeps each table entry on one line.
const fn var(
    name: &'static str,
    shape: IndexShape,
    writable: bool,
    description: &'static str,
) -> SysVar {
    SysVar {
        name,
        shape,
        writable,
        description,
        ty: None,
    }
}

include!(concat!(env!("OUT_DIR"), "/catalogue_sysvars.rs"));

use IndexShape::{Axis, Frame, FrameComponent, Number, Numbers};

/// Read-only and writable, spelled out so the table reads as a table.
const RO: bool = false;
const RW: bool = true;

/// `$R<n>`: an R parameter named by number (`$R1`), the form synchronized
/// actions use (reference §7.2). It is not in [`TABLE`] because the number
/// is part of the name; [`lookup`] returns this entry for any `$R` followed
/// by digits. Whether `n` is below MD28050 `$MC_MM_NUM_R_PARAM` is the
/// caller's check.
static R_NUMBERED: SysVar = var(
    "$R<n>",
    IndexShape::None,
    RW,
    "R parameter n (main-run form of Rn)",
);

/// The registry, sorted by name (byte order of the upper-case names, so
/// `$AA_IM` < `$A_IN` and `$TC_DP19` < `$TC_DP2`) for binary search. The
/// test `table_is_sorted_without_duplicates` keeps it so. One entry per
/// line, so it is left out of rustfmt.
#[rustfmt::skip]
const TABLE: &[SysVar] = &[
    // $A…: main-run (actual) values (§7.4). Reading them stops preprocessing.
    var("$AA_IM", Axis, RO, "axis position in the machine coordinate system (setpoint)"),
    var("$AA_IW", Axis, RO, "axis position in the workpiece coordinate system (setpoint)"),
    var("$AA_MW", Axis, RO, "measured axis position in the workpiece coordinate system"),
    // Probe status; the corpus only reads it (MS150.SPF) and the control sets it.
    var("$AC_MEA", Number, RO, "measuring job status: probe n has switched"),
    var("$AC_TIME", IndexShape::None, RO, "time since block start"),
    // Compensation tables (CEC, sag/angularity): written by the corpus
    // program NC_LEC_X_FB419.SPF to load a table.
    var("$AN_CEC", Numbers(2), RW, "compensation table: value at interpolation point"),
    var("$AN_CEC_DIRECTION", Number, RW, "compensation table: direction dependence"),
    var("$AN_CEC_INPUT_AXIS", Number, RW, "compensation table: basic (input) axis"),
    var("$AN_CEC_IS_MODULO", Number, RW, "compensation table: cyclic repetition"),
    var("$AN_CEC_MAX", Number, RW, "compensation table: end position"),
    var("$AN_CEC_MIN", Number, RW, "compensation table: start position"),
    var("$AN_CEC_MULT_BY_TABLE", Number, RW, "compensation table: multiply by table"),
    var("$AN_CEC_OUTPUT_AXIS", Number, RW, "compensation table: compensation (output) axis"),
    var("$AN_CEC_STEP", Number, RW, "compensation table: distance between interpolation points"),
    var("$A_DBB", Number, RW, "data byte from/to the PLC"),
    var("$A_IN", Number, RO, "digital NC input"),
    var("$A_OUT", Number, RW, "digital NC output"),
    // $C_…: values passed to replacement cycles (MD10715/10717, §4.4). The
    // cycle reads them; the control sets them.
    var("$C_D", IndexShape::None, RO, "replacement cycle: programmed D number"),
    // Not named in the reference; listed with $C_ME, the address extension
    // of the same M function, which it names.
    var("$C_M", IndexShape::None, RO, "replacement cycle: programmed M value"),
    var("$C_ME", IndexShape::None, RO, "replacement cycle: address extension of the M function"),
    var("$C_T", IndexShape::None, RO, "replacement cycle: programmed T number"),
    var("$C_TS", IndexShape::None, RO, "replacement cycle: programmed tool name"),
    // Machine data, axial.
    var("$MA_CEC_ENABLE", Axis, RW, "MD32710: enable sag compensation"),
    // Machine data, channel.
    var("$MC_AUXFU_H_TYPE_INT", IndexShape::None, RW, "MD22110: H values are INT"),
    var("$MC_AUXFU_M_SYNC_TYPE", IndexShape::None, RW, "MD22200: output timing of M functions"),
    var("$MC_AXCONF_CHANAX_NAME_TAB", Number, RW, "MD20080: channel axis names"),
    var("$MC_AXCONF_GEOAX_NAME_TAB", Number, RW, "MD20060: geometry axis names"),
    var("$MC_CUTTING_EDGE_DEFAULT", IndexShape::None, RW, "MD20270: edge after a tool change"),
    var("$MC_CUTTING_EDGE_RESET_VALUE", IndexShape::None, RW, "MD20130: edge after reset"),
    var("$MC_DIAMETER_AX_DEF", IndexShape::None, RW, "MD20100: transverse axis"),
    var("$MC_FRAME_SUPPRESS_MODE", IndexShape::None, RW, "MD24020: frame suppression mode"),
    var("$MC_GCODE_RESET_MODE", Number, RW, "MD20152: reset behaviour per G group"),
    var("$MC_GCODE_RESET_VALUES", Number, RW, "MD20150: initial G code per group"),
    var("$MC_MM_NUM_R_PARAM", IndexShape::None, RW, "MD28050: number of R parameters"),
    var("$MC_MM_NUM_USER_FRAMES", IndexShape::None, RW, "MD28080: number of settable frames"),
    var("$MC_MM_SYSTEM_FRAME_MASK", IndexShape::None, RW, "MD28082: configured system frames"),
    var("$MC_PFRAME_RESET_MODE", IndexShape::None, RW, "programmable frame kept over reset"),
    var("$MC_RESET_MODE_MASK", IndexShape::None, RW, "MD20110: reset behaviour"),
    var("$MC_SPF_END_TO_VDI", IndexShape::None, RW, "MD20800: subprogram end to PLC"),
    var("$MC_SPIND_RIGID_TAPPING_M_NR", IndexShape::None, RW, "MD20094: M number for axis mode"),
    var("$MC_START_MODE_MASK", IndexShape::None, RW, "MD20112: program start behaviour"),
    var("$MC_TOOL_CHANGE_ERROR_MODE", IndexShape::None, RW, "MD22562: tool change error handling"),
    var("$MC_TOOL_CHANGE_MODE", IndexShape::None, RW, "MD22550: tool change with T or M6"),
    var("$MC_TOOL_CHANGE_M_CODE", IndexShape::None, RW, "MD22560: tool change M function"),
    var("$MC_TOOL_PRESEL_RESET_VALUE", IndexShape::None, RW, "MD20121: preselected T after reset"),
    var("$MC_TOOL_RESET_NAME", IndexShape::None, RW, "MD20122: active tool name after reset"),
    var("$MC_TOOL_RESET_VALUE", IndexShape::None, RW, "MD20120: active tool after reset"),
    var("$MC_T_M_ADDRESS_EXT_IS_SPINO", IndexShape::None, RW, "MD20096: T/M extension is spindle"),
    // Machine data, NCK.
    var("$MN_AUXFU_GROUP_SPEC", Number, RW, "MD11110: output spec per auxiliary function group"),
    var("$MN_AXCONF_MACHAX_NAME_TAB", Number, RW, "MD10000: machine axis names"),
    var("$MN_FRAME_ANGLE_INPUT_MODE", IndexShape::None, RW, "MD10600: RPY or Euler angles"),
    var("$MN_G53_TOOLCORR", IndexShape::None, RW, "MD10760: tool offsets with G53/G153/SUPA"),
    var("$MN_LUD_EXTENDED_SCOPE", IndexShape::None, RW, "MD11120: main program LUD become PUD"),
    var("$MN_MIRROR_REF_AX", IndexShape::None, RW, "MD10610: reference axis for mirroring"),
    var("$MN_MIRROR_TOGGLE", IndexShape::None, RW, "MD10612: mirror toggles"),
    var("$MN_MM_EXTERN_CNC_SYSTEM", IndexShape::None, RW, "MD10880: ISO dialect"),
    var("$MN_M_NO_FCT_CYCLE", Number, RW, "MD10715: M functions replaced by a cycle"),
    var("$MN_M_NO_FCT_CYCLE_NAME", Number, RW, "MD10716: replacement cycle names"),
    var("$MN_M_NO_FCT_EOP", IndexShape::None, RW, "MD10714: M function keeping spindles on"),
    var("$MN_M_NO_FCT_STOPRE", Number, RW, "MD10713: M functions with preprocessing stop"),
    var("$MN_PREPROCESSING_LEVEL", IndexShape::None, RW, "MD10700: preprocessing of cycles"),
    var("$MN_PROG_FUNCTION_MASK", IndexShape::None, RW, "MD10280: language function mask"),
    var("$MN_SCALING_SYSTEM_IS_METRIC", IndexShape::None, RW, "MD10240: basic system is metric"),
    var("$MN_SCALING_VALUE_INCH", IndexShape::None, RW, "MD10250: inch conversion factor"),
    var("$MN_T_NO_FCT_CYCLE_NAME", IndexShape::None, RW, "MD10717: T replacement cycle name"),
    // π (§7.4), used by SYNTAX_CHECK.SPF as `R0 = $PI`.
    var("$PI", IndexShape::None, RO, "the constant pi"),
    // $P…: preprocessing (programmed) values and frames (§5.2, §6, §7.4,
    // §8.4-8.5, §9.2). Programmed state is read-only. Frames are written
    // to set offsets ($P_UIFR, $P_UBFR in §6/§9.3), except $P_ACTFRAME and
    // $P_ACTBFRAME, which §9.2 defines as the chain's results. For the
    // system frames (…PARTFRAME, …SETFRAME, …EXTFRAME, ISO1…4, GFRAME,
    // TOOLFRAME, WPFRAME, TRAFRAME, CYCFRAME) the reference does not say
    // whether a program may write them directly: writable, by the rule for
    // uncertain entries.
    var("$P_ACTBFRAME", Frame, RO, "chained active basic frames (result)"),
    var("$P_ACTFRAME", Frame, RO, "total active frame (result of the chain)"),
    var("$P_AXN1", IndexShape::None, RO, "first axis (abscissa) of the active plane"),
    var("$P_AXN2", IndexShape::None, RO, "second axis (ordinate) of the active plane"),
    var("$P_AXN3", IndexShape::None, RO, "third axis (applicate) of the active plane"),
    var("$P_BFRAME", Frame, RW, "first channel basic frame ($P_CHBFRAME[0])"),
    var("$P_CHBFRAME", FrameComponent, RW, "channel basic frames"),
    var("$P_CYCFRAME", Frame, RW, "system frame for cycles"),
    var("$P_DRYRUN", IndexShape::None, RO, "dry run feed active"),
    var("$P_EP", Axis, RO, "programmed end position of the axis (WCS)"),
    var("$P_EXTFRAME", Frame, RW, "system frame: external work offset"),
    var("$P_F", IndexShape::None, RO, "last programmed path feed F"),
    var("$P_GFRAME", Frame, RW, "grinding frame"),
    var("$P_GG", Number, RO, "active G code (index) of group n"),
    var("$P_IFRAME", Frame, RW, "active settable frame (G54…)"),
    var("$P_ISO1FRAME", Frame, RW, "system frame for ISO mode (G51.1 mirror)"),
    var("$P_ISO2FRAME", Frame, RW, "system frame for ISO mode (G68 2D rotation)"),
    var("$P_ISO3FRAME", Frame, RW, "system frame for ISO mode (G68 3D rotation)"),
    var("$P_ISO4FRAME", Frame, RW, "system frame for ISO mode (G51 scale)"),
    var("$P_MC", IndexShape::None, RO, "modal subprogram call (MCALL) active"),
    var("$P_NCBFRAME", FrameComponent, RW, "NCK-global basic frames"),
    var("$P_PARTFRAME", Frame, RW, "system frame for TCARR / PAROT"),
    var("$P_PFRAME", Frame, RW, "programmable frame (TRANS/ROT/…)"),
    var("$P_PROG", Number, RO, "name of the program at level n"),
    var("$P_SETFRAME", Frame, RW, "system frame: preset actual value / scratching"),
    var("$P_STACK", IndexShape::None, RO, "current program level"),
    var("$P_SUBPAR", Number, RO, "parameter n was programmed in the call"),
    var("$P_TOOL", IndexShape::None, RO, "active D number"),
    var("$P_TOOLEXIST", Number, RO, "tool t exists"),
    var("$P_TOOLFRAME", Frame, RW, "system frame for TOROT / TOFRAME"),
    var("$P_TOOLL", Number, RO, "active total tool length, component n"),
    var("$P_TOOLND", Number, RO, "number of cutting edges of tool t"),
    var("$P_TOOLNO", IndexShape::None, RO, "active tool number T"),
    var("$P_TOOLP", IndexShape::None, RO, "last programmed tool number T"),
    var("$P_TOOLR", IndexShape::None, RO, "active tool radius"),
    var("$P_TRAFRAME", Frame, RW, "system frame for transformations"),
    var("$P_UBFR", Frame, RW, "first basic frame (data management)"),
    var("$P_UIFR", FrameComponent, RW, "settable frames: 0 = G500, 1 = G54 … 99 = G599"),
    var("$P_UIFRNUM", IndexShape::None, RO, "index of the active settable frame"),
    var("$P_WPFRAME", Frame, RW, "system frame: workpiece reference points"),
    // R parameters as an array (§7.2): `$R[20]=4` in SYNTAX_CHECK.SPF.
    var("$R", Number, RW, "R parameter array"),
    // Setting data, axial.
    var("$SA_LEAD_OFFSET_OUT_POS", Axis, RW, "master value coupling: offset of the curve output"),
    var("$SA_OSCILL_IS_ACTIVE", Axis, RW, "oscillation active"),
    var("$SA_SPIND_S", Axis, RW, "spindle speed for start via the PLC interface"),
    // Setting data, channel and NCK.
    var("$SC_FRAME_OFFSET_INCR_PROG", IndexShape::None, RW, "SD42440: offset traversed with G91"),
    var("$SN_CEC_TABLE_ENABLE", Number, RW, "SD41300: enable compensation table n"),
    // Tool data (§5.3): offsets per tool t and edge d, the whole family.
    var("$TC_DP1", Numbers(2), RW, "tool type"),
    var("$TC_DP10", Numbers(2), RW, "angle between tool face and toroidal surface"),
    var("$TC_DP11", Numbers(2), RW, "angle between tool axis and toroidal surface"),
    var("$TC_DP12", Numbers(2), RW, "wear: length 1"),
    var("$TC_DP13", Numbers(2), RW, "wear: length 2"),
    var("$TC_DP14", Numbers(2), RW, "wear: length 3"),
    var("$TC_DP15", Numbers(2), RW, "wear: radius"),
    var("$TC_DP16", Numbers(2), RW, "wear: slotting saw corner radius"),
    var("$TC_DP17", Numbers(2), RW, "wear: slotting saw length"),
    var("$TC_DP18", Numbers(2), RW, "wear: reserved"),
    var("$TC_DP19", Numbers(2), RW, "wear: angle between tool face and toroidal surface"),
    var("$TC_DP2", Numbers(2), RW, "cutting edge position"),
    var("$TC_DP20", Numbers(2), RW, "wear: angle between tool axis and toroidal surface"),
    var("$TC_DP21", Numbers(2), RW, "base dimension: length 1"),
    var("$TC_DP22", Numbers(2), RW, "base dimension: length 2"),
    var("$TC_DP23", Numbers(2), RW, "base dimension: length 3"),
    var("$TC_DP24", Numbers(2), RW, "clearance angle"),
    var("$TC_DP25", Numbers(2), RW, "reserved"),
    var("$TC_DP3", Numbers(2), RW, "geometry: length 1"),
    var("$TC_DP4", Numbers(2), RW, "geometry: length 2"),
    var("$TC_DP5", Numbers(2), RW, "geometry: length 3"),
    var("$TC_DP6", Numbers(2), RW, "geometry: radius"),
    var("$TC_DP7", Numbers(2), RW, "slotting saw: corner radius"),
    var("$TC_DP8", Numbers(2), RW, "slotting saw: length"),
    var("$TC_DP9", Numbers(2), RW, "geometry: reserved"),
    // Tool data per tool t (§5.2).
    var("$TC_TP1", Number, RW, "duplo number"),
    var("$TC_TP2", Number, RW, "tool identifier (name)"),
    // Grinding tool data per tool t: the whole family, as the corpus
    // (NadjImre grinding cycles) reads TPG1, TPG3 and writes TPG5.
    var("$TC_TPG1", Number, RW, "grinding: spindle number"),
    var("$TC_TPG2", Number, RW, "grinding: chaining rule"),
    var("$TC_TPG3", Number, RW, "grinding: minimum wheel radius"),
    var("$TC_TPG4", Number, RW, "grinding: minimum wheel width"),
    var("$TC_TPG5", Number, RW, "grinding: current wheel width"),
    var("$TC_TPG6", Number, RW, "grinding: maximum speed"),
    var("$TC_TPG7", Number, RW, "grinding: maximum peripheral speed"),
    var("$TC_TPG8", Number, RW, "grinding: angle of inclined wheel"),
    var("$TC_TPG9", Number, RW, "grinding: parameter number for radius calculation"),
];

/// A listed system variable by its place in the registry: what the AIL
/// carries and the executor matches, so no name is compared when a
/// program runs. In JSON it is the name ([`SysVarId::name`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct SysVarId(u16);

impl SysVarId {
    // The variables the executor gives values to.
    pub const AA_IM: Self = Self::listed("$AA_IM");
    pub const AA_IW: Self = Self::listed("$AA_IW");
    pub const MC_MM_NUM_R_PARAM: Self = Self::listed("$MC_MM_NUM_R_PARAM");
    pub const MC_TOOL_CHANGE_MODE: Self = Self::listed("$MC_TOOL_CHANGE_MODE");
    pub const PI: Self = Self::listed("$PI");
    pub const P_ACTFRAME: Self = Self::listed("$P_ACTFRAME");
    pub const P_AXN1: Self = Self::listed("$P_AXN1");
    pub const P_AXN2: Self = Self::listed("$P_AXN2");
    pub const P_AXN3: Self = Self::listed("$P_AXN3");
    pub const P_EP: Self = Self::listed("$P_EP");
    pub const P_F: Self = Self::listed("$P_F");
    pub const P_GG: Self = Self::listed("$P_GG");
    pub const P_IFRAME: Self = Self::listed("$P_IFRAME");
    pub const P_MC: Self = Self::listed("$P_MC");
    pub const P_PFRAME: Self = Self::listed("$P_PFRAME");
    pub const P_TOOL: Self = Self::listed("$P_TOOL");
    pub const P_TOOLNO: Self = Self::listed("$P_TOOLNO");
    pub const P_TOOLP: Self = Self::listed("$P_TOOLP");
    pub const P_UIFR: Self = Self::listed("$P_UIFR");
    pub const P_UIFRNUM: Self = Self::listed("$P_UIFRNUM");
    pub const R: Self = Self::listed("$R");
    /// `$TC_DP1`…`$TC_DP25`, the tool offset parameters, in their order.
    pub const TC_DP: [Self; 25] = [
        Self::listed("$TC_DP1"),
        Self::listed("$TC_DP2"),
        Self::listed("$TC_DP3"),
        Self::listed("$TC_DP4"),
        Self::listed("$TC_DP5"),
        Self::listed("$TC_DP6"),
        Self::listed("$TC_DP7"),
        Self::listed("$TC_DP8"),
        Self::listed("$TC_DP9"),
        Self::listed("$TC_DP10"),
        Self::listed("$TC_DP11"),
        Self::listed("$TC_DP12"),
        Self::listed("$TC_DP13"),
        Self::listed("$TC_DP14"),
        Self::listed("$TC_DP15"),
        Self::listed("$TC_DP16"),
        Self::listed("$TC_DP17"),
        Self::listed("$TC_DP18"),
        Self::listed("$TC_DP19"),
        Self::listed("$TC_DP20"),
        Self::listed("$TC_DP21"),
        Self::listed("$TC_DP22"),
        Self::listed("$TC_DP23"),
        Self::listed("$TC_DP24"),
        Self::listed("$TC_DP25"),
    ];

    /// The variable spelled exactly `name` (upper case, one `$`), if the
    /// registry lists it; `None` for other spellings (`$$P_UIFR`,
    /// `$p_uifr`, `$R5`), which [`lookup`] reads as the same variable.
    pub fn exactly(name: &str) -> Option<Self> {
        if let Ok(at) = TABLE.binary_search_by(|entry| entry.name.cmp(name)) {
            return Some(Self(at as u16));
        }
        let at = CATALOGUE
            .binary_search_by(|entry| entry.name.cmp(name))
            .ok()?;
        Some(Self((TABLE.len() + at) as u16))
    }

    /// The entry: the registry's, else the catalogue's.
    pub fn var(self) -> &'static SysVar {
        let at = usize::from(self.0);
        TABLE
            .get(at)
            .unwrap_or_else(|| &CATALOGUE[at - TABLE.len()])
    }

    /// The name with one `$`, in upper case (`$P_UIFR`).
    pub fn name(self) -> &'static str {
        self.var().name
    }

    /// The registry's variable `name`, found when the constants above are
    /// compiled: a name the registry lacks stops the build, never a run.
    const fn listed(name: &str) -> Self {
        let mut at = 0;
        while at < TABLE.len() {
            if bytes_equal(TABLE[at].name.as_bytes(), name.as_bytes()) {
                return Self(at as u16);
            }
            at += 1;
        }
        panic!("a system variable the registry does not list");
    }
}

const fn bytes_equal(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}

/// System variables of known type, sorted by name.
const SYSTEM_TYPES: &[(&str, DataType)] = &[
    ("$AA_IM", DataType::Real),
    ("$AA_IW", DataType::Real),
    ("$AA_MW", DataType::Real),
    ("$AN_CEC_INPUT_AXIS", DataType::Axis),
    ("$AN_CEC_OUTPUT_AXIS", DataType::Axis),
    ("$C_TS", DataType::String { length: None }),
    ("$PI", DataType::Real),
    ("$P_AXN1", DataType::Axis),
    ("$P_AXN2", DataType::Axis),
    ("$P_AXN3", DataType::Axis),
    ("$P_EP", DataType::Real),
    ("$P_F", DataType::Real),
    ("$P_PROG", DataType::String { length: None }),
    ("$P_TOOLNO", DataType::Int),
    ("$P_TOOLP", DataType::Int),
    ("$P_TOOLR", DataType::Real),
    ("$R", DataType::Real),
    ("$R<n>", DataType::Real),
];

impl SysVar {
    /// The type of this variable read or written with `count` indices,
    /// where its shape or the reference settles it; `None` where it is
    /// not known (never an error).
    pub fn data_type(&self, count: usize) -> Option<DataType> {
        use DataType::*;
        match (self.shape, count) {
            // A whole frame, or one of an array of frames; a component is REAL.
            (IndexShape::Frame, 0) | (IndexShape::FrameComponent, 1) => return Some(Frame),
            (IndexShape::Frame, 2) | (IndexShape::FrameComponent, 3) => return Some(Real),
            // Indices that fit no form of a frame: no type to check against.
            (IndexShape::Frame | IndexShape::FrameComponent, _) => return None,
            _ => {}
        }
        if self.ty.is_some() {
            return self.ty;
        }
        if let Ok(i) = SYSTEM_TYPES.binary_search_by(|(entry, _)| entry.cmp(&self.name)) {
            return Some(SYSTEM_TYPES[i].1);
        }
        CATALOGUE
            .binary_search_by(|entry| entry.name.cmp(self.name))
            .ok()
            .and_then(|i| CATALOGUE[i].ty)
    }
}

/// Every known variable once (without the `$R<n>` form): the registry's,
/// then the catalogue's the registry does not refine, each part sorted by
/// name.
pub fn all() -> impl Iterator<Item = &'static SysVar> {
    TABLE.iter().chain(
        CATALOGUE
            .iter()
            .filter(|entry| TABLE.binary_search_by(|t| t.name.cmp(entry.name)).is_err()),
    )
}

/// The system variable `name`, if it is known.
///
/// `name` is matched without regard to case and may be written with `$`
/// (`$P_UIFR`), with `$$` (`$$SA_OSCILL_IS_ACTIVE`: one `$` is stripped, it
/// is the same variable read at main run) or without `$`. Indices are not
/// part of the name: pass `$P_UIFR`, not `$P_UIFR[1]`. `$R` followed by
/// digits (`$R5`) is an R parameter and returns the `$R<n>` entry.
///
/// Binary search over the registry, then the catalogue; no allocation.
pub fn lookup(name: &str) -> Option<&'static SysVar> {
    let key = strip_dollars(name)?;
    let numbered_r = key
        .strip_prefix(['R', 'r'])
        .is_some_and(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()));
    if numbered_r {
        return Some(&R_NUMBERED);
    }
    let find = |table: &'static [SysVar]| {
        table
            .binary_search_by(|entry| compare_ignore_case(&entry.name[1..], key))
            .ok()
            .map(|i| &table[i])
    };
    find(TABLE).or_else(|| find(CATALOGUE))
}

/// Whether `name` has the prefix of machine data (`$MN_`, `$MC_`, `$MA_`)
/// or setting data (`$SN_`, `$SC_`, `$SA_`), listed or not.
///
/// For the caller's policy on unlisted data: [`lookup`] knows only the few
/// that are used or named, and rejects the rest. Accepts the same spellings
/// as [`lookup`]. HMI machine data (`$MM_`) are not NC-program data and do
/// not count.
pub fn is_machine_or_setting_data(name: &str) -> bool {
    let Some(key) = strip_dollars(name) else {
        return false;
    };
    let bytes = key.as_bytes();
    bytes.len() > 3
        && bytes[2] == b'_'
        && matches!(
            (bytes[0].to_ascii_uppercase(), bytes[1].to_ascii_uppercase()),
            (b'M' | b'S', b'N' | b'C' | b'A')
        )
}

/// `name` without its leading `$` or `$$`; `None` if nothing is left.
fn strip_dollars(name: &str) -> Option<&str> {
    let key = name
        .strip_prefix("$$")
        .or_else(|| name.strip_prefix('$'))
        .unwrap_or(name);
    (!key.is_empty()).then_some(key)
}

#[cfg(test)]
mod tests {

    #[test]
    fn system_type_table_is_sorted() {
        for pair in SYSTEM_TYPES.windows(2) {
            assert!(pair[0].0 < pair[1].0, "{} {}", pair[0].0, pair[1].0);
        }
    }
    use super::*;
    use std::path::{Path, PathBuf};

    #[test]
    fn catalogue_is_sorted_without_duplicates_and_found() {
        assert_eq!(CATALOGUE.len(), 2132);
        assert_sorted(CATALOGUE);
        for entry in CATALOGUE {
            let found = lookup(entry.name).expect(entry.name);
            assert_eq!(found.name, entry.name);
            assert!(entry.ty.is_some(), "{}", entry.name);
            let id = SysVarId::exactly(entry.name).unwrap();
            assert_eq!(id.var(), found, "{}", entry.name);
        }
        let va_im = lookup("$va_im").unwrap();
        assert_eq!(
            (va_im.shape, va_im.ty),
            (IndexShape::Dims(1), Some(DataType::Real))
        );
        assert_eq!(
            lookup("$P_ISTEST").unwrap().data_type(0),
            Some(DataType::Bool)
        );
        assert!(!lookup("$P_SEARCH").unwrap().writable);
        assert_eq!(
            all().count(),
            TABLE.len() + CATALOGUE.len() - refined().count()
        );
    }

    /// The registry's entries the catalogue lists too.
    fn refined() -> impl Iterator<Item = (&'static SysVar, &'static SysVar)> {
        TABLE.iter().filter_map(|entry| {
            CATALOGUE
                .binary_search_by(|c| c.name.cmp(entry.name))
                .ok()
                .map(|i| (entry, &CATALOGUE[i]))
        })
    }

    /// A registry entry takes the indices its catalogue entry counts, and
    /// its type, where the registry gives one, is the catalogue's.
    #[test]
    fn registry_agrees_with_the_catalogue() {
        for (entry, listed) in refined() {
            let IndexShape::Dims(dims) = listed.shape else {
                assert_eq!(entry.shape, listed.shape, "{}", entry.name);
                continue;
            };
            assert!(entry.shape.accepts(usize::from(dims)), "{}", entry.name);
        }
        assert_eq!(lookup("$TC_DP1").unwrap().data_type(2), Some(DataType::Int));
        assert_eq!(
            lookup("$TC_DP3").unwrap().data_type(2),
            Some(DataType::Real)
        );
        assert_eq!(lookup("$AA_IM").unwrap().data_type(1), Some(DataType::Real));
    }

    #[test]
    fn table_is_sorted_without_duplicates() {
        assert_sorted(TABLE);
    }

    fn assert_sorted(table: &[SysVar]) {
        for pair in table.windows(2) {
            assert!(
                pair[0].name < pair[1].name,
                "{} must come before {}",
                pair[0].name,
                pair[1].name
            );
        }
    }

    #[test]
    fn names_are_upper_case_with_one_dollar() {
        for entry in TABLE {
            let rest = entry.name.strip_prefix('$').expect(entry.name);
            assert!(!rest.is_empty() && !rest.starts_with('$'), "{}", entry.name);
            assert!(
                rest.bytes()
                    .all(|b| b.is_ascii_uppercase() || b.is_ascii_digit() || b == b'_'),
                "{}",
                entry.name
            );
            assert!(!entry.description.is_empty(), "{}", entry.name);
            assert_eq!(lookup(entry.name), Some(entry), "{}", entry.name);
        }
    }

    #[test]
    fn lookup_ignores_case_and_accepts_dollar_forms() {
        let uifr = lookup("$P_UIFR").unwrap();
        assert_eq!(uifr.name, "$P_UIFR");
        for spelling in ["$p_uifr", "$P_uIfR", "$$P_UIFR", "P_UIFR", "p_uifr"] {
            assert_eq!(lookup(spelling), Some(uifr), "{spelling}");
        }
        let lead = lookup("$$SA_LEAD_OFFSET_OUT_POS").unwrap();
        assert_eq!(lead.name, "$SA_LEAD_OFFSET_OUT_POS");
        assert_eq!(lookup("$aa_iw").unwrap().name, "$AA_IW");
        for not in [
            "",
            "$",
            "$$",
            "$$$P_UIFR",
            "$P_UIFR[1]",
            "$P_UIF",
            "$P_UIFRX",
            "$ P_UIFR",
        ] {
            assert_eq!(lookup(not), None, "{not:?}");
        }
    }

    #[test]
    fn ids_name_their_entries_exactly() {
        for entry in TABLE {
            let id = SysVarId::exactly(entry.name).unwrap();
            assert_eq!(id.var(), entry);
            assert_eq!(id.name(), entry.name);
        }
        assert_eq!(SysVarId::P_UIFR.name(), "$P_UIFR");
        assert_eq!(SysVarId::TC_DP[0].name(), "$TC_DP1");
        assert_eq!(SysVarId::TC_DP[24].name(), "$TC_DP25");
        for not in ["$$P_UIFR", "$p_uifr", "P_UIFR", "$R5", "$P_UIFR[1]", ""] {
            assert_eq!(SysVarId::exactly(not), None, "{not}");
        }
    }

    #[test]
    fn unknown_machine_data_is_rejected() {
        // SYNTAX_CHECK.SPF marks this typo of $MN_G53_TOOLCORR "; unknown".
        assert_eq!(lookup("$MN_G53_TOLCORR"), None);
        assert!(is_machine_or_setting_data("$MN_G53_TOLCORR"));
        assert!(lookup("$MN_G53_TOOLCORR").is_some());
        assert_eq!(lookup("$MC_NO_SUCH_DATUM"), None);
    }

    #[test]
    fn machine_and_setting_data_prefixes() {
        for yes in [
            "$MN_X", "$MC_X", "$MA_X", "$SN_X", "$SC_X", "$SA_X", "$$SA_X", "$mn_x", "MC_X",
        ] {
            assert!(is_machine_or_setting_data(yes), "{yes}");
        }
        for no in [
            "$MM_X", "$MN_", "$MN", "$P_UIFR", "$TC_DP1", "$AA_IM", "$SD_X", "", "$",
        ] {
            assert!(!is_machine_or_setting_data(no), "{no}");
        }
    }

    #[test]
    fn shapes_from_the_reference_and_corpus() {
        let shape = |name: &str| lookup(name).unwrap_or_else(|| panic!("{name}")).shape;
        assert_eq!(shape("$P_UIFR"), IndexShape::FrameComponent);
        assert_eq!(shape("$P_ACTFRAME"), IndexShape::Frame);
        assert_eq!(shape("$P_UBFR"), IndexShape::Frame);
        assert_eq!(shape("$AA_IM"), IndexShape::Axis);
        assert_eq!(shape("$SA_OSCILL_IS_ACTIVE"), IndexShape::Axis);
        assert_eq!(shape("$TC_DP1"), IndexShape::Numbers(2));
        assert_eq!(shape("$AN_CEC"), IndexShape::Numbers(2));
        assert_eq!(shape("$A_IN"), IndexShape::Number);
        assert_eq!(shape("$P_GG"), IndexShape::Number);
        assert_eq!(shape("$TC_TPG5"), IndexShape::Number);
        assert_eq!(shape("$R"), IndexShape::Number);
        assert_eq!(shape("$P_TOOLNO"), IndexShape::None);
        assert_eq!(shape("$MN_SCALING_VALUE_INCH"), IndexShape::None);
        assert_eq!(shape("$PI"), IndexShape::None);

        let writable = |name: &str| lookup(name).unwrap().writable;
        assert!(!writable("$AA_IM"));
        assert!(!writable("$P_TOOLNO"));
        assert!(!writable("$A_IN"));
        assert!(writable("$P_UIFR"));
        assert!(writable("$TC_DP3"));
        assert!(writable("$R"));
    }

    #[test]
    fn numbered_r_parameters() {
        for name in ["$R1", "$r20", "$R0", "$$R5"] {
            let r = lookup(name).unwrap();
            assert_eq!(r.name, "$R<n>", "{name}");
            assert_eq!(r.shape, IndexShape::None);
            assert!(r.writable);
        }
        assert_eq!(lookup("$R").unwrap().shape, IndexShape::Number);
        assert_eq!(lookup("$R1X"), None);
        assert_eq!(lookup("$RX"), None);
    }

    #[test]
    fn shapes_accept_index_counts() {
        assert!(IndexShape::None.accepts(0) && !IndexShape::None.accepts(1));
        assert!(IndexShape::Axis.accepts(1) && !IndexShape::Axis.accepts(0));
        assert!(IndexShape::Number.accepts(1) && !IndexShape::Number.accepts(2));
        assert!(IndexShape::Numbers(2).accepts(2) && !IndexShape::Numbers(2).accepts(1));
        // `$P_UBFR = CTRANS(…)`, `$P_UBFR[Y,TR]`.
        assert!(IndexShape::Frame.accepts(0) && IndexShape::Frame.accepts(2));
        assert!(!IndexShape::Frame.accepts(1) && !IndexShape::Frame.accepts(3));
        // `$P_UIFR[1] = CTRANS(…)`, `$P_UIFR[1,X,TR]`.
        assert!(IndexShape::FrameComponent.accepts(1) && IndexShape::FrameComponent.accepts(3));
        assert!(!IndexShape::FrameComponent.accepts(0) && !IndexShape::FrameComponent.accepts(2));
        assert!((0..5).all(|n| IndexShape::Any.accepts(n)));
    }

    /// Every `$` name in the shared corpus's programs is known, except those
    /// on lines the syntax-check program annotates `; unknown`, which must
    /// be unknown; and every use has an index count its shape accepts.
    #[test]
    fn registry_covers_the_corpus() {
        let root = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../../shared/corpus"
        ));
        if !root.is_dir() {
            eprintln!("skipping: no corpus at {}", root.display());
            return;
        }
        let mut files = Vec::new();
        collect_programs(root, &mut files);
        assert!(!files.is_empty(), "no programs under {}", root.display());

        let (mut known, mut expected_unknown) = (0, 0);
        let (mut missing, mut misshapen) = (Vec::new(), Vec::new());
        for file in &files {
            let bytes = std::fs::read(file).unwrap();
            for (number, line) in bytes.split(|&b| b == b'\n').enumerate() {
                let (names, comment) = scan_line(line);
                let unknown_expected = String::from_utf8_lossy(comment)
                    .trim()
                    .eq_ignore_ascii_case("unknown");
                for (name, indices) in names {
                    let found = lookup(&name);
                    if let Some(var) = found.filter(|var| !var.shape.accepts(indices)) {
                        misshapen.push(format!(
                            "{}:{}: {name} with {indices} indices, shape {:?}",
                            file.display(),
                            number + 1,
                            var.shape
                        ));
                    }
                    if unknown_expected {
                        assert!(
                            found.is_none(),
                            "{}:{}: {name} should be unknown",
                            file.display(),
                            number + 1
                        );
                        expected_unknown += 1;
                    } else if found.is_some() {
                        known += 1;
                    } else {
                        missing.push(format!("{}:{}: {name}", file.display(), number + 1));
                    }
                }
            }
        }
        assert!(
            missing.is_empty(),
            "unknown system variables:\n{}",
            missing.join("\n")
        );
        assert!(
            misshapen.is_empty(),
            "index counts that do not fit:\n{}",
            misshapen.join("\n")
        );
        assert!(known > 0, "no system variables found in the corpus");
        eprintln!(
            "{} programs: {known} known references, {expected_unknown} expected unknown",
            files.len()
        );
    }

    /// The `.mpf`/`.spf` files under `dir`, any case, recursively.
    fn collect_programs(dir: &Path, files: &mut Vec<PathBuf>) {
        let mut entries: Vec<_> = std::fs::read_dir(dir)
            .unwrap()
            .map(|entry| entry.unwrap().path())
            .collect();
        entries.sort();
        for path in entries {
            if path.is_dir() {
                collect_programs(&path, files);
            } else if path.extension().is_some_and(|ext| {
                ext.eq_ignore_ascii_case("mpf") || ext.eq_ignore_ascii_case("spf")
            }) {
                files.push(path);
            }
        }
    }

    /// The `$` names on one line outside strings and before the comment,
    /// each with the number of indices in the brackets that follow it (0
    /// without brackets), and the comment's text (after `;`).
    fn scan_line(line: &[u8]) -> (Vec<(String, usize)>, &[u8]) {
        let is_name_byte = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
        let mut names = Vec::new();
        let mut in_string = false;
        let mut i = 0;
        while i < line.len() {
            match line[i] {
                b'"' => in_string = !in_string,
                b';' if !in_string => return (names, &line[i + 1..]),
                b'$' if !in_string => {
                    let start = i;
                    i += 1;
                    if line.get(i) == Some(&b'$') {
                        i += 1;
                    }
                    let body = i;
                    while i < line.len() && is_name_byte(line[i]) {
                        i += 1;
                    }
                    if i > body {
                        let name = String::from_utf8_lossy(&line[start..i]).into_owned();
                        names.push((name, count_indices(&line[i..])));
                    }
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
        (names, &[])
    }

    /// The number of comma-separated indices in the brackets at the start
    /// of `rest` (nested brackets and parentheses count as one index).
    fn count_indices(rest: &[u8]) -> usize {
        if rest.first() != Some(&b'[') {
            return 0;
        }
        let (mut depth, mut commas, mut content) = (0usize, 0, false);
        for &b in rest {
            match b {
                b'[' | b'(' => {
                    content |= depth > 0;
                    depth += 1;
                }
                b']' | b')' => {
                    depth -= 1;
                    if depth == 0 {
                        break;
                    }
                }
                b',' if depth == 1 => commas += 1,
                b if !b.is_ascii_whitespace() => content = true,
                _ => {}
            }
        }
        if content { commas + 1 } else { 0 }
    }

    #[test]
    fn scanner_skips_comments_and_strings() {
        let (names, comment) =
            scan_line(b"R1=$AA_IM[X] MSG(\"$66021 $P_F\") $$SA_X[Y]=1 ; $P_GG unknown");
        let names: Vec<_> = names.iter().map(|(name, n)| (name.as_str(), *n)).collect();
        assert_eq!(names, [("$AA_IM", 1), ("$$SA_X", 1)]);

        let (names, _) =
            scan_line(b"X=$TC_DP3[T,E[0] ]/2 $P_AXN1 $AN_CEC[0,1]=0 $P_UIFR[N-1,X,FI] $P_TOOLL[ ]");
        let counts: Vec<_> = names.iter().map(|(_, n)| *n).collect();
        assert_eq!(counts, [2, 0, 2, 3, 0]);
        assert_eq!(comment, b" $P_GG unknown");
    }
}
