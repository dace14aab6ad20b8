//! The TOML schema of a machine profile. Field and policy names follow the
//! designs for tool change, M functions and work offsets.
//! Unknown keys are rejected everywhere; every section has defaults, so a
//! profile states only what differs from a plain 840D sl milling machine.

use std::collections::BTreeMap;

use gcodec_lang::MClass;
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// A machine profile as written, after defaults.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    pub machine: Machine,
    /// The channel axes in channel order.
    #[serde(default = "default_axes")]
    pub axes: Vec<Axis>,
    /// G-group reset defaults (as machine data MD20150 sets them): group
    /// number (1…64) → G code. Groups not named keep the control's default.
    /// That the group is modal and the code one of its commands is checked
    /// by the semantic stage (`gcodec_sema::check_profile`).
    #[serde(default)]
    pub modal_defaults: BTreeMap<Spanned<String>, Spanned<String>>,
    #[serde(default)]
    pub tool_change: ToolChange,
    /// The tool table.
    #[serde(default)]
    pub tools: Vec<Tool>,
    #[serde(default)]
    pub m_functions: MFunctions,
    #[serde(default)]
    pub work_offsets: WorkOffsets,
    #[serde(default)]
    pub program: ProgramSettings,
    #[serde(default)]
    pub g_codes: GCodes,
    /// Values of system variables the simulation cannot know (test mode,
    /// block search, inputs, measured values): `"$P_ISTEST" = true`,
    /// `"$A_IN[3]" = false`, `"$AC_MEA" = 1` (for every index). Read by
    /// the run only where it has no value of its own; see
    /// [`crate::system_variables`].
    #[serde(default)]
    pub system_variables: BTreeMap<Spanned<String>, SystemValue>,
    /// The machine's toolchanger as the toolchanger protocol drives it;
    /// without the table (and without a scenario) a tool change is
    /// instant and cannot fail.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub toolchanger: Option<ToolchangerSettings>,
}

/// `[toolchanger]`: the changer's side of the toolchanger protocol.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ToolchangerSettings {
    /// The changer takes the start-change handshake at the very start of
    /// a change (iov2's `-support-start-change`).
    #[serde(default)]
    pub support_start_change: bool,
    /// A random-pocket changer: the tool leaving the spindle takes the
    /// pocket of the tool that comes in (iov2's `RANDOM_TOOLCHANGER`).
    #[serde(default)]
    pub random: bool,
    /// Seconds per protocol cycle (iov2's `CYCLE_TIME`), counted in the
    /// run's time estimate.
    #[serde(default = "default_cycle_time")]
    pub cycle_time: Spanned<f64>,
    /// Cycles an acknowledgement may take before the operation is aborted
    /// (reason 102).
    #[serde(default = "default_timeout_cycles")]
    pub timeout_cycles: Spanned<u32>,
}

impl Default for ToolchangerSettings {
    fn default() -> Self {
        Self {
            support_start_change: false,
            random: false,
            cycle_time: default_cycle_time(),
            timeout_cycles: default_timeout_cycles(),
        }
    }
}

/// `[toolchanger] cycle_time` when not given: iov2's `CYCLE_TIME`.
pub const DEFAULT_CYCLE_TIME: f64 = 0.1;

/// `[toolchanger] timeout_cycles` when not given: 10 s at the default
/// cycle time, over thirty times the slowest handshake of the recorded
/// traces (0.3 s).
pub const DEFAULT_TIMEOUT_CYCLES: u32 = 100;

fn default_cycle_time() -> Spanned<f64> {
    spanned(DEFAULT_CYCLE_TIME)
}

fn default_timeout_cycles() -> Spanned<u32> {
    spanned(DEFAULT_TIMEOUT_CYCLES)
}

/// A value of `[system_variables]`.
#[derive(Clone, Debug, PartialEq, Deserialize, Serialize)]
#[serde(untagged)]
pub enum SystemValue {
    Bool(bool),
    Int(i64),
    Real(f64),
    Text(String),
}

/// Which G commands the control has. By default every command of the
/// G-group registry (reference §3.2); an 828D or a machine without an
/// option rules some out.
#[derive(Clone, Debug, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GCodes {
    /// Commands the control rejects: `["G33", "OEMIPO1"]`. Each must be a
    /// command of the registry (checked by the semantic stage).
    #[serde(default)]
    pub unsupported: Vec<Spanned<String>>,
    /// Whole G groups (1…64) the control lacks, e.g. punching and
    /// nibbling (35, 36, 38).
    #[serde(default)]
    pub unsupported_groups: Vec<Spanned<u8>>,
}

/// Which control and which machine.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Machine {
    /// A name for people.
    pub name: String,
    pub control: Control,
    /// The spindle numbers (`S2=…`, `M2=3`, `T2=…` address spindle 2).
    #[serde(default = "default_spindles")]
    pub spindles: Vec<Spanned<u32>>,
}

/// The control family.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
pub enum Control {
    #[serde(rename = "840d_sl")]
    Sinumerik840dSl,
    #[serde(rename = "828d")]
    Sinumerik828d,
}

/// One channel axis.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The channel axis name (`X`, `Y`, `Z`, `A`, `C`, `X1`).
    pub name: Spanned<String>,
    pub kind: AxisKind,
    /// One of the (at most three) geometry axes.
    #[serde(default)]
    pub geometry: bool,
    /// The lathe's transverse axis, programmed in diameter under `DIAMON`.
    #[serde(default)]
    pub diameter: bool,
    /// Rapid traverse rate, mm/min (degrees/min for rotary axes).
    #[serde(default = "default_rapid")]
    pub rapid: Spanned<f64>,
    /// The reference point in machine coordinates (MD34100
    /// `$MA_REFP_SET_POS`), where `G74` goes: mm (degrees), radius.
    #[serde(default = "default_reference_point")]
    pub reference_point: Spanned<f64>,
    /// Fixed points 1…4 in machine coordinates (MD30600
    /// `$MA_FIX_POINT_POS`), where `G75 FP=n` goes: mm (degrees), radius.
    #[serde(default)]
    pub fixed_points: Vec<Spanned<f64>>,
}

/// Linear or rotary.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisKind {
    Linear,
    Rotary,
}

/// Tool change per the tool-change design.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ToolChange {
    /// `direct`: `T` changes the tool; `deferred_m6`: `T` preselects and
    /// the change M code changes.
    #[serde(default = "default_tool_change_mode")]
    pub tool_change_mode: ToolChangeMode,
    /// The M function that changes the tool in `deferred_m6` mode.
    #[serde(default = "default_change_m_code")]
    pub change_m_code: Spanned<u32>,
    /// Tools are selected by name or location (`T="DRILL"`), not number.
    #[serde(default)]
    pub tool_management_enabled: bool,
    #[serde(default = "default_on_unresolved_tool")]
    pub on_unresolved_tool: UnresolvedToolPolicy,
    #[serde(default)]
    pub allow_substitution: bool,
    #[serde(default = "default_m6_without_pending_policy")]
    pub m6_without_pending_policy: Policy,
    /// Whether a preselected tool is channel state or belongs to the
    /// program level that selected it.
    #[serde(default = "default_pending_selection_scope")]
    pub pending_selection_scope: PendingSelectionScope,
    /// MD20270 `$MC_CUTTING_EDGE_DEFAULT`: the edge after a change without
    /// a `D` (0 none, n edge n, −1 the old edge number, −2 the old tool's
    /// offset until a `D` is programmed).
    #[serde(default = "default_cutting_edge_default")]
    pub cutting_edge_default: Spanned<i64>,
    /// MD22562 `$MC_TOOL_CHANGE_ERROR_MODE` bit 2: what `D` > 0 does with
    /// no tool in the spindle.
    #[serde(default = "default_edge_without_tool")]
    pub edge_without_tool: EdgeWithoutTool,
}

impl Default for ToolChange {
    fn default() -> Self {
        Self {
            tool_change_mode: default_tool_change_mode(),
            change_m_code: default_change_m_code(),
            tool_management_enabled: false,
            on_unresolved_tool: default_on_unresolved_tool(),
            allow_substitution: false,
            m6_without_pending_policy: default_m6_without_pending_policy(),
            pending_selection_scope: default_pending_selection_scope(),
            cutting_edge_default: default_cutting_edge_default(),
            edge_without_tool: default_edge_without_tool(),
        }
    }
}

/// Where a pending tool selection lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PendingSelectionScope {
    /// Channel state, kept across a call and its return (the control).
    Channel,
    /// Per program level: a subprogram starts with none, and its own is
    /// dropped at its return, where the caller's comes back.
    ProgramLevel,
}

/// `D` > 0 without a tool (MD22562 bit 2).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EdgeWithoutTool {
    /// The edge is active with no offset (bit 2 = 0).
    NoOffset,
    /// A tool alarm (bit 2 = 1).
    Alarm,
}

/// `direct` or `deferred_m6`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolChangeMode {
    Direct,
    DeferredM6,
}

/// What a tool selection that names no tool in the table does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum UnresolvedToolPolicy {
    Error,
    Warning,
    Fallback,
}

/// `error`, `warning` or `ignore`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Policy {
    Error,
    Warning,
    Ignore,
}

/// One tool of the tool table.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Tool {
    /// The T number (without tool management) or internal number.
    pub number: Spanned<u32>,
    /// The tool's name (needed with tool management).
    #[serde(default)]
    pub name: Option<Spanned<String>>,
    /// Duplo number: sister tools share a name.
    #[serde(default = "default_duplo")]
    pub duplo: u32,
    /// Magazine location.
    #[serde(default)]
    pub location: Option<u32>,
    #[serde(default = "default_tool_state")]
    pub state: ToolState,
    /// Cutting edges `D1`, `D2`, …
    #[serde(default)]
    pub edges: Vec<Edge>,
}

impl Profile {
    /// The tool numbered `number` in the tool table.
    pub fn tool(&self, number: u32) -> Option<&Tool> {
        self.tools.iter().find(|t| *t.number.get_ref() == number)
    }
}

impl Tool {
    /// A tool with no name, duplo 1 and no edges, as a program's write of
    /// its data makes it (not written in any profile: no span).
    pub fn unnamed(number: u32) -> Self {
        Self {
            number: Spanned::new(0..0, number),
            name: None,
            duplo: default_duplo(),
            location: None,
            state: default_tool_state(),
            edges: Vec::new(),
        }
    }

    /// Whether a tool selection of `kind` naming `value` (a T number, a
    /// magazine location, a name in any case; as AIL writes a selection)
    /// selects this tool. A computed selection is known only at run time:
    /// it may select any tool.
    pub fn is_selected_by(&self, kind: gcodec_ail::SelectorKind, value: &str) -> bool {
        use gcodec_ail::SelectorKind;
        match kind {
            SelectorKind::Number => self.number.get_ref().to_string() == value,
            SelectorKind::Location => self.location.is_some_and(|l| l.to_string() == value),
            SelectorKind::Name => self
                .name
                .as_ref()
                .is_some_and(|n| n.get_ref().eq_ignore_ascii_case(value)),
            SelectorKind::Computed => true,
        }
    }

    /// The cutting edge `D<d>`, made with no length and radius if the
    /// tool lacks it.
    pub fn edge_or_new(&mut self, d: u32) -> &mut Edge {
        let at = match self.edges.iter().position(|e| *e.d.get_ref() == d) {
            Some(at) => at,
            None => {
                self.edges.push(Edge {
                    d: Spanned::new(0..0, d),
                    length: 0.0,
                    radius: 0.0,
                    position: default_edge_position(),
                    tool_type: None,
                });
                self.edges.len() - 1
            }
        };
        &mut self.edges[at]
    }

    /// The cutting edge `D<d>`.
    pub fn edge(&self, d: u32) -> Option<&Edge> {
        self.edges.iter().find(|e| *e.d.get_ref() == d)
    }
}

/// Whether a tool may be used.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ToolState {
    Enabled,
    Disabled,
    Locked,
}

/// One cutting edge.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Edge {
    /// The `D` number.
    pub d: Spanned<u32>,
    /// Length compensation, mm.
    #[serde(default)]
    pub length: f64,
    /// Radius, mm.
    #[serde(default)]
    pub radius: f64,
    /// The cutting edge position of a turning tool (`$TC_DP2`), 1…9:
    /// where the theoretical tip, the point the machine positions, lies
    /// from the centre of the nose radius (SPEC §11.12); 0 (the default)
    /// and 9: at the centre, as for a milling tool.
    #[serde(default = "default_edge_position")]
    pub position: Spanned<u8>,
    /// The tool type of the edge (`$TC_DP1`: 1xx milling, 2xx drilling,
    /// 4xx grinding, 5xx turning, 7xx special, 9xx auxiliary tools);
    /// `None` where the profile does not say.
    #[serde(default, rename = "type", skip_serializing_if = "Option::is_none")]
    pub tool_type: Option<Spanned<u32>>,
}

impl Edge {
    /// Sets the tool type, as a program's write of `$TC_DP1` does (no
    /// span in the profile).
    pub fn set_tool_type(&mut self, tool_type: u32) {
        self.tool_type = Some(spanned(tool_type));
    }

    /// Whether the edge is a turning tool's, whose cutting edge position
    /// places its tip (a type 5xx, or no type and a position).
    pub fn is_turning(&self) -> bool {
        match &self.tool_type {
            Some(t) => (500..600).contains(t.get_ref()),
            None => *self.position.get_ref() != 0,
        }
    }
}

fn default_edge_position() -> Spanned<u8> {
    spanned(0)
}

/// M functions per the M-function design.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MFunctions {
    #[serde(default = "default_max_m_per_block")]
    pub max_m_per_block: Spanned<u32>,
    #[serde(default = "default_unknown_mcode_policy")]
    pub unknown_mcode_policy: Policy,
    /// `M<n>=<value>` addresses a spindle.
    #[serde(default = "yes")]
    pub enable_extended_m_address: bool,
    /// M value → class, overriding the built-in classification. The
    /// classes are those of the `m_function` instruction.
    #[serde(default)]
    pub mcode_class_overrides: BTreeMap<Spanned<String>, MClass>,
    /// The auxiliary-function groups of the master spindle's M functions
    /// (MD22000 ff.): group number (1…64) → M values. A block outputs one
    /// function of a group (alarm 14760).
    #[serde(default = "default_auxiliary_groups")]
    pub auxiliary_groups: BTreeMap<Spanned<String>, Vec<Spanned<u32>>>,
}

impl MFunctions {
    /// The auxiliary-function group of the master spindle's `M<value>`,
    /// if it is in one.
    pub fn auxiliary_group(&self, value: u32) -> Option<&str> {
        self.auxiliary_groups
            .iter()
            .find(|(_, values)| values.iter().any(|v| *v.get_ref() == value))
            .map(|(group, _)| group.get_ref().as_str())
    }
}

impl Default for MFunctions {
    fn default() -> Self {
        Self {
            max_m_per_block: default_max_m_per_block(),
            unknown_mcode_policy: default_unknown_mcode_policy(),
            enable_extended_m_address: true,
            mcode_class_overrides: BTreeMap::new(),
            auxiliary_groups: default_auxiliary_groups(),
        }
    }
}

/// Work offsets per the work-offset design.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct WorkOffsets {
    /// The Group 8 selection after reset (`G500`, `G54`, …).
    #[serde(default = "default_group8_offset")]
    pub default_group8_offset: Spanned<String>,
    /// Codes and ranges of codes the machine has: `"G54"`, `"G505-G599"`.
    #[serde(default = "default_supported_group8_offsets")]
    pub supported_group8_offsets: Vec<Spanned<String>>,
    /// Codes that older programs use for a Group 8 offset
    /// (`G58 = "G505"`); without an alias `G58`/`G59` are the axial
    /// programmable offsets of group 3.
    #[serde(default)]
    pub legacy_aliases: BTreeMap<Spanned<String>, Spanned<String>>,
    /// Several of `G53`, `G153`, `SUPA` in one block.
    #[serde(default = "default_duplicate_suppression_policy")]
    pub duplicate_suppression_policy: DuplicateSuppressionPolicy,
    /// SD42440 `$SC_FRAME_OFFSET_INCR_PROG`: `true` (1, the control's
    /// default), an incremental value after a change of the work offset or
    /// frame traverses the change; `false` (0), only the programmed path.
    #[serde(default = "yes")]
    pub incremental_traverses_offset_change: bool,
    /// The translation of each settable offset, per axis: `[work_offsets.values.G54]`.
    #[serde(default)]
    pub values: BTreeMap<Spanned<String>, BTreeMap<Spanned<String>, f64>>,
}

impl Default for WorkOffsets {
    fn default() -> Self {
        Self {
            default_group8_offset: default_group8_offset(),
            supported_group8_offsets: default_supported_group8_offsets(),
            legacy_aliases: BTreeMap::new(),
            duplicate_suppression_policy: default_duplicate_suppression_policy(),
            incremental_traverses_offset_change: true,
            values: BTreeMap::new(),
        }
    }
}

impl WorkOffsets {
    /// Which Group 8 indices (`$P_UIFR` numbering, 0…99) the machine has,
    /// from `supported_group8_offsets`; entries that do not read as a range
    /// (reported by the profile check) add nothing.
    pub fn supported_group8(&self) -> [bool; 100] {
        let mut supported = [false; 100];
        for entry in &self.supported_group8_offsets {
            if let Ok((lo, hi)) = crate::group8_range(entry.get_ref()) {
                for slot in &mut supported[usize::from(lo)..=usize::from(hi)] {
                    *slot = true;
                }
            }
        }
        supported
    }
}

/// `warn`, `error` or `first_wins`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DuplicateSuppressionPolicy {
    Warn,
    Error,
    FirstWins,
}

/// How programs are read and run.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ProgramSettings {
    /// Skip levels switched on: blocks marked `/n` are skipped.
    #[serde(default)]
    pub skip_levels: Vec<Spanned<u8>>,
    /// Longest block the control accepts, in characters.
    #[serde(default = "default_max_block_length")]
    pub max_block_length: Spanned<u32>,
    /// Highest programmable feed, mm/min.
    #[serde(default = "default_max_feed")]
    pub max_feed: Spanned<f64>,
    /// Folders searched for subprograms, relative to the profile's folder.
    #[serde(default)]
    pub subprogram_paths: Vec<String>,
    /// The setting data `$SC_EXT_PROG_PATH` (SD42700): where `EXTCALL`
    /// looks first, relative to the profile's folder; none by default.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub external_program_path: Option<String>,
    /// Folders a symbolic link on the search path may point into besides
    /// the search path's own (a shared cycle folder linked into each
    /// machine's folder), relative to the profile's folder.
    #[serde(default)]
    pub link_target_paths: Vec<String>,
    /// The largest program file read, in bytes: the main program, called
    /// programs and definition files.
    #[serde(default = "default_max_file_size")]
    pub max_file_size: Spanned<u64>,
    /// The code page of program files that are not valid UTF-8 (a WHATWG
    /// label: `windows-1252`, the control's own and the default,
    /// `windows-1251` for Cyrillic comments, `iso-8859-2`, …).
    #[serde(default = "default_code_page")]
    pub code_page: Spanned<String>,
    /// The memory for variables, in bytes: the `DEF` variables of every
    /// active program level and the global user data alive at once (the
    /// control's user memory, which its machine data size).
    #[serde(default = "default_max_variable_memory")]
    pub max_variable_memory: Spanned<u64>,
    /// Whether `M0` ends a simulated run (it waits for NC start on the
    /// machine); `false` lets runs go on, as `gcodec run --no-stop`.
    #[serde(default = "yes")]
    pub stop_at_m0: bool,
    /// MD21000 `CIRCLE_ERROR_CONST`: the end point of a circle may lie this
    /// far (mm) off the circle…
    #[serde(default = "default_circle_error_const")]
    pub circle_error_const: Spanned<f64>,
    /// …or, for large circles, this fraction of the radius (MD21010
    /// `CIRCLE_ERROR_FACTOR`), whichever is larger.
    #[serde(default = "default_circle_error_factor")]
    pub circle_error_factor: Spanned<f64>,
    /// MD20250 `CUTCOM_MAXNUM_DUMMY_BLOCKS`: the blocks without motion in
    /// the working plane allowed between two elements while tool radius
    /// compensation is on (alarm 10762 beyond).
    #[serde(default = "default_cutcom_max_dummy_blocks")]
    pub cutcom_max_dummy_blocks: Spanned<u32>,
    /// MD20240 `CUTCOM_MAXNUM_CHECK_BLOCKS`: the elements collision
    /// detection (`CDON`) looks ahead over for an intersection of the
    /// equidistants (alarm 10751 when there is none).
    #[serde(default = "default_cutcom_check_blocks")]
    pub cutcom_check_blocks: Spanned<u32>,
}

impl Default for ProgramSettings {
    fn default() -> Self {
        Self {
            skip_levels: Vec::new(),
            max_block_length: default_max_block_length(),
            max_feed: default_max_feed(),
            subprogram_paths: Vec::new(),
            external_program_path: None,
            link_target_paths: Vec::new(),
            max_file_size: default_max_file_size(),
            code_page: default_code_page(),
            max_variable_memory: default_max_variable_memory(),
            stop_at_m0: true,
            circle_error_const: default_circle_error_const(),
            circle_error_factor: default_circle_error_factor(),
            cutcom_max_dummy_blocks: default_cutcom_max_dummy_blocks(),
            cutcom_check_blocks: default_cutcom_check_blocks(),
        }
    }
}

fn default_circle_error_const() -> Spanned<f64> {
    spanned(0.01)
}

fn default_cutcom_check_blocks() -> Spanned<u32> {
    spanned(4)
}

fn default_cutcom_max_dummy_blocks() -> Spanned<u32> {
    spanned(3)
}

fn default_circle_error_factor() -> Spanned<f64> {
    spanned(0.001)
}

fn spanned<T>(value: T) -> Spanned<T> {
    Spanned::new(0..0, value)
}

fn yes() -> bool {
    true
}

fn default_axes() -> Vec<Axis> {
    ["X", "Y", "Z"]
        .into_iter()
        .map(|name| Axis {
            name: spanned(name.to_owned()),
            kind: AxisKind::Linear,
            geometry: true,
            diameter: false,
            rapid: default_rapid(),
            reference_point: default_reference_point(),
            fixed_points: Vec::new(),
        })
        .collect()
}

fn default_spindles() -> Vec<Spanned<u32>> {
    vec![spanned(1)]
}

fn default_rapid() -> Spanned<f64> {
    spanned(10_000.0)
}

/// Machine zero.
fn default_reference_point() -> Spanned<f64> {
    spanned(0.0)
}

fn default_tool_change_mode() -> ToolChangeMode {
    ToolChangeMode::DeferredM6
}

fn default_change_m_code() -> Spanned<u32> {
    spanned(6)
}

fn default_on_unresolved_tool() -> UnresolvedToolPolicy {
    UnresolvedToolPolicy::Error
}

fn default_m6_without_pending_policy() -> Policy {
    Policy::Warning
}

fn default_pending_selection_scope() -> PendingSelectionScope {
    PendingSelectionScope::Channel
}

/// The new tool's first edge.
fn default_cutting_edge_default() -> Spanned<i64> {
    spanned(1)
}

fn default_edge_without_tool() -> EdgeWithoutTool {
    EdgeWithoutTool::NoOffset
}

fn default_duplo() -> u32 {
    1
}

fn default_tool_state() -> ToolState {
    ToolState::Enabled
}

/// Group 1 the program-flow functions, group 2 the master spindle's
/// (MD22040 and the predefined groups of MD22050 ff.).
fn default_auxiliary_groups() -> BTreeMap<Spanned<String>, Vec<Spanned<u32>>> {
    let group = |values: &[u32]| values.iter().copied().map(spanned).collect();
    BTreeMap::from([
        (spanned("1".to_owned()), group(&[0, 1, 2, 17, 30])),
        (spanned("2".to_owned()), group(&[3, 4, 5, 70])),
    ])
}

fn default_max_m_per_block() -> Spanned<u32> {
    spanned(5)
}

fn default_unknown_mcode_policy() -> Policy {
    Policy::Warning
}

fn default_group8_offset() -> Spanned<String> {
    spanned("G500".to_owned())
}

fn default_supported_group8_offsets() -> Vec<Spanned<String>> {
    vec![spanned("G500".to_owned()), spanned("G54-G57".to_owned())]
}

fn default_duplicate_suppression_policy() -> DuplicateSuppressionPolicy {
    DuplicateSuppressionPolicy::Warn
}

fn default_max_block_length() -> Spanned<u32> {
    spanned(512)
}

fn default_code_page() -> Spanned<String> {
    spanned(gcodec_source::Encoding::WINDOWS_1252.name().to_owned())
}

impl ProgramSettings {
    /// How program files are decoded: UTF-8 where valid, else the
    /// profile's code page (Windows-1252 when the label is unknown, which
    /// the profile's validation reports).
    pub fn text_encoding(&self) -> gcodec_source::TextEncoding {
        let code_page = gcodec_source::Encoding::for_label(self.code_page.get_ref())
            .unwrap_or(gcodec_source::Encoding::WINDOWS_1252);
        gcodec_source::TextEncoding::Detect { code_page }
    }
}

fn default_max_file_size() -> Spanned<u64> {
    spanned(gcodec_source::DEFAULT_MAX_FILE_SIZE)
}

/// `[program] max_variable_memory` when the profile does not give it:
/// 256 MiB, ten of the largest arrays gcodec declares (2^20 REAL
/// elements), far more than any program of the corpus needs.
pub const DEFAULT_MAX_VARIABLE_MEMORY: u64 = 256 << 20;

fn default_max_variable_memory() -> Spanned<u64> {
    spanned(DEFAULT_MAX_VARIABLE_MEMORY)
}

fn default_max_feed() -> Spanned<f64> {
    spanned(10_000.0)
}
