//! The G-group registry: all 64 groups of the language reference §3.2 with
//! their members in index order, their effect and their 840D reset default.
//!
//! The index of a member is the number the control itself uses: MD20150
//! `$MC_GCODE_RESET_VALUES[group-1]` stores it and `$P_GG[group]` returns it,
//! so programs compare against it (`IF $P_GG[8]==3 …`). That is why member
//! positions must never shift, not even where the manual skips a number.
//!
//! The defaults here are Siemens' standard MD20150 values for the 840D.
//! Machine builders change them (lathes often start in `G18`, `G95`,
//! `DIAMON`) and 828D defaults come from the machine's own MD20150, so the
//! modal engine should take its reset state from the machine profile and
//! treat [`default_member`] as the fallback.

use crate::modal::GROUP_COUNT;

/// Whether a group's command stays in force after its block (the "W"
/// column of the manual's tables: `m` or `s`).
///
/// Group 3 is non-modal although its *effects* persist: `TRANS`, `G25` or
/// `G110` write frame, working-area or pole data that outlives the block,
/// but the command itself is not a state that later blocks are "in".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Stays active until another member of the same group replaces it.
    ///
    /// The unassigned groups 5 and 63 are recorded as modal too: the
    /// reference names groups 2, 3, 9, 11 and 62 as the non-modal ones and
    /// calls all others modal, and MD20150 keeps an (inactive) slot for them
    /// like for any modal group.
    Modal,
    /// Acts only in the block where it is written (block scope).
    NonModal,
}

/// One G group of the language reference §3.2.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GGroup {
    /// Group number, 1…64, as used by MD20150 and `$P_GG`.
    pub number: u8,
    /// The group's title from the reference, for messages.
    pub title: &'static str,
    /// Modal or block scope.
    pub effect: Effect,
    /// Upper-case command names in index order: `members[0]` is index 1.
    ///
    /// An empty string stands for an index the control does not assign, so
    /// that the indices after it stay right: group 3 has no index 9 and
    /// `G25` is index 10. Unassigned groups (5 and 63) have no members.
    pub members: &'static [&'static str],
    /// 1-based index of the reset default (Siemens standard MD20150 for the
    /// 840D); `None` for non-modal and unassigned groups, which have none.
    pub default_index: Option<u8>,
}

/// All G groups; group `n` is at position `n - 1`.
///
/// Transcribed from the reference's §3.2 table, with its ranges written
/// out. Use the table here rather than CEAD's `ggroups.json`, which swaps
/// groups 53 and 56 and numbers the groups from 59 on one off.
pub static G_GROUPS: [GGroup; GROUP_COUNT] = [
    GGroup {
        number: 1,
        title: "Modally valid motion commands",
        effect: Effect::Modal,
        members: &[
            "G0", "G1", "G2", "G3", "CIP", "ASPLINE", "BSPLINE", "CSPLINE", "POLY", "G33", "G331",
            "G332", "OEMIPO1", "OEMIPO2", "CT", "G34", "G35", "INVCW", "INVCCW", "G335", "G336",
        ],
        default_index: Some(2),
    },
    GGroup {
        number: 2,
        title: "Non-modal motions, dwell time",
        effect: Effect::NonModal,
        members: &[
            "G4", "G63", "G74", "G75", "REPOSL", "REPOSQ", "REPOSH", "REPOSA", "REPOSQA",
            "REPOSHA", "G147", "G247", "G347", "G148", "G248", "G348", "G5", "G7",
        ],
        default_index: None,
    },
    // Index 9 is not assigned (ONE p.1249): the "" keeps G25 at 10.
    GGroup {
        number: 3,
        title: "Programmable frame, working-area limitation, pole",
        effect: Effect::NonModal,
        members: &[
            "TRANS", "ROT", "SCALE", "MIRROR", "ATRANS", "AROT", "ASCALE", "AMIRROR", "", "G25",
            "G26", "G110", "G111", "G112", "G58", "G59", "ROTS", "AROTS",
        ],
        default_index: None,
    },
    GGroup {
        number: 4,
        title: "FIFO",
        effect: Effect::Modal,
        members: &["STARTFIFO", "STOPFIFO", "FIFOCTRL"],
        default_index: Some(1),
    },
    // Groups 5 and 63 are not assigned; MD20150 marks them inactive.
    GGroup {
        number: 5,
        title: "not assigned",
        effect: Effect::Modal,
        members: &[],
        default_index: None,
    },
    GGroup {
        number: 6,
        title: "Plane selection",
        effect: Effect::Modal,
        members: &["G17", "G18", "G19"],
        default_index: Some(1),
    },
    GGroup {
        number: 7,
        title: "Tool radius compensation",
        effect: Effect::Modal,
        members: &["G40", "G41", "G42"],
        default_index: Some(1),
    },
    GGroup {
        number: 8,
        title: "Settable work offset",
        effect: Effect::Modal,
        members: &[
            "G500", "G54", "G55", "G56", "G57", "G505", "G506", "G507", "G508", "G509", "G510",
            "G511", "G512", "G513", "G514", "G515", "G516", "G517", "G518", "G519", "G520", "G521",
            "G522", "G523", "G524", "G525", "G526", "G527", "G528", "G529", "G530", "G531", "G532",
            "G533", "G534", "G535", "G536", "G537", "G538", "G539", "G540", "G541", "G542", "G543",
            "G544", "G545", "G546", "G547", "G548", "G549", "G550", "G551", "G552", "G553", "G554",
            "G555", "G556", "G557", "G558", "G559", "G560", "G561", "G562", "G563", "G564", "G565",
            "G566", "G567", "G568", "G569", "G570", "G571", "G572", "G573", "G574", "G575", "G576",
            "G577", "G578", "G579", "G580", "G581", "G582", "G583", "G584", "G585", "G586", "G587",
            "G588", "G589", "G590", "G591", "G592", "G593", "G594", "G595", "G596", "G597", "G598",
            "G599",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 9,
        title: "Frame and tool-offset suppression",
        effect: Effect::NonModal,
        members: &["G53", "SUPA", "G153", "SUPD"],
        default_index: None,
    },
    GGroup {
        number: 10,
        title: "Exact stop / continuous-path",
        effect: Effect::Modal,
        members: &["G60", "G64", "G641", "G642", "G643", "G644", "G645"],
        default_index: Some(1),
    },
    GGroup {
        number: 11,
        title: "Exact stop, non-modal",
        effect: Effect::NonModal,
        members: &["G9"],
        default_index: None,
    },
    GGroup {
        number: 12,
        title: "Block-change criterion at exact stop",
        effect: Effect::Modal,
        members: &["G601", "G602", "G603"],
        default_index: Some(1),
    },
    GGroup {
        number: 13,
        title: "Workpiece dimensioning inch/metric",
        effect: Effect::Modal,
        members: &["G70", "G71", "G700", "G710"],
        default_index: Some(2),
    },
    GGroup {
        number: 14,
        title: "Absolute/incremental",
        effect: Effect::Modal,
        members: &["G90", "G91"],
        default_index: Some(1),
    },
    // The reference's default cell reads "`G94` (1)", which contradicts its
    // own member list (index 1 is G93, inverse-time feed). The name is taken
    // as the intended value, since feed per minute (G94) is the familiar
    // 840D power-on state, so the index here is 2.
    GGroup {
        number: 15,
        title: "Feed type",
        effect: Effect::Modal,
        members: &[
            "G93", "G94", "G95", "G96", "G97", "G931", "G961", "G971", "G942", "G952", "G962",
            "G972", "G973",
        ],
        default_index: Some(2),
    },
    GGroup {
        number: 16,
        title: "Feed override at inside/outside curvature",
        effect: Effect::Modal,
        members: &["CFC", "CFTCP", "CFIN"],
        default_index: Some(1),
    },
    GGroup {
        number: 17,
        title: "Approach/retract behaviour, tool offset",
        effect: Effect::Modal,
        members: &["NORM", "KONT", "KONTT", "KONTC"],
        default_index: Some(1),
    },
    GGroup {
        number: 18,
        title: "Corner behaviour, tool offset",
        effect: Effect::Modal,
        members: &["G450", "G451"],
        default_index: Some(1),
    },
    GGroup {
        number: 19,
        title: "Spline start transition",
        effect: Effect::Modal,
        members: &["BNAT", "BTAN", "BAUTO"],
        default_index: Some(1),
    },
    GGroup {
        number: 20,
        title: "Spline end transition",
        effect: Effect::Modal,
        members: &["ENAT", "ETAN", "EAUTO"],
        default_index: Some(1),
    },
    GGroup {
        number: 21,
        title: "Acceleration profile",
        effect: Effect::Modal,
        members: &["BRISK", "SOFT", "DRIVE"],
        default_index: Some(1),
    },
    GGroup {
        number: 22,
        title: "Tool offset type",
        effect: Effect::Modal,
        members: &[
            "CUT2D", "CUT2DF", "CUT3DC", "CUT3DF", "CUT3DFS", "CUT3DFF", "CUT3DCC", "CUT3DCCD",
            "CUT2DD", "CUT2DFD", "CUT3DCD", "CUT3DFD",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 23,
        title: "Collision monitoring at inside contours",
        effect: Effect::Modal,
        members: &["CDOF", "CDON", "CDOF2"],
        default_index: Some(1),
    },
    GGroup {
        number: 24,
        title: "Feedforward control",
        effect: Effect::Modal,
        members: &["FFWOF", "FFWON"],
        default_index: Some(1),
    },
    GGroup {
        number: 25,
        title: "Tool orientation reference",
        effect: Effect::Modal,
        members: &["ORIWKS", "ORIMKS"],
        default_index: Some(1),
    },
    GGroup {
        number: 26,
        title: "REPOS mode (modal)",
        effect: Effect::Modal,
        members: &["RMB", "RMI", "RME", "RMN"],
        default_index: Some(2),
    },
    GGroup {
        number: 27,
        title: "Orientation change at outside corners",
        effect: Effect::Modal,
        members: &["ORIC", "ORID"],
        default_index: Some(1),
    },
    GGroup {
        number: 28,
        title: "Working-area limitation",
        effect: Effect::Modal,
        members: &["WALIMON", "WALIMOF"],
        default_index: Some(1),
    },
    GGroup {
        number: 29,
        title: "Radius/diameter programming",
        effect: Effect::Modal,
        members: &["DIAMOF", "DIAMON", "DIAM90", "DIAMCYCOF"],
        default_index: Some(1),
    },
    GGroup {
        number: 30,
        title: "NC block compression",
        effect: Effect::Modal,
        members: &["COMPOF", "COMPON", "COMPCURV", "COMPCAD", "COMPSURF"],
        default_index: Some(1),
    },
    GGroup {
        number: 31,
        title: "OEM G commands",
        effect: Effect::Modal,
        members: &[
            "G810", "G811", "G812", "G813", "G814", "G815", "G816", "G817", "G818", "G819",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 32,
        title: "OEM G commands",
        effect: Effect::Modal,
        members: &[
            "G820", "G821", "G822", "G823", "G824", "G825", "G826", "G827", "G828", "G829",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 33,
        title: "Settable fine tool offset",
        effect: Effect::Modal,
        members: &["FTOCOF", "FTOCON"],
        default_index: Some(1),
    },
    GGroup {
        number: 34,
        title: "Tool orientation smoothing",
        effect: Effect::Modal,
        members: &["OSOF", "OSC", "OSS", "OSSE", "OSD", "OST"],
        default_index: Some(1),
    },
    GGroup {
        number: 35,
        title: "Punching and nibbling",
        effect: Effect::Modal,
        members: &["SPOF", "SON", "PON", "SONS", "PONS"],
        default_index: Some(1),
    },
    GGroup {
        number: 36,
        title: "Punching with delay",
        effect: Effect::Modal,
        members: &["PDELAYON", "PDELAYOF"],
        default_index: Some(1),
    },
    GGroup {
        number: 37,
        title: "Feedrate profile",
        effect: Effect::Modal,
        members: &["FNORM", "FLIN", "FCUB"],
        default_index: Some(1),
    },
    GGroup {
        number: 38,
        title: "Fast I/O assignment for punching/nibbling",
        effect: Effect::Modal,
        members: &["SPIF1", "SPIF2"],
        default_index: Some(1),
    },
    GGroup {
        number: 39,
        title: "Programmable contour accuracy",
        effect: Effect::Modal,
        members: &["CPRECOF", "CPRECON"],
        default_index: Some(1),
    },
    GGroup {
        number: 40,
        title: "Tool radius compensation constant",
        effect: Effect::Modal,
        members: &["CUTCONOF", "CUTCONON"],
        default_index: Some(1),
    },
    GGroup {
        number: 41,
        title: "Interruptible thread cutting",
        effect: Effect::Modal,
        members: &["LFOF", "LFON"],
        default_index: Some(1),
    },
    GGroup {
        number: 42,
        title: "Tool carrier",
        effect: Effect::Modal,
        members: &["TCOABS", "TCOFR", "TCOFRZ", "TCOFRY", "TCOFRX"],
        default_index: Some(1),
    },
    GGroup {
        number: 43,
        title: "SAR approach direction",
        effect: Effect::Modal,
        members: &["G140", "G141", "G142", "G143"],
        default_index: Some(1),
    },
    GGroup {
        number: 44,
        title: "SAR path segmentation",
        effect: Effect::Modal,
        members: &["G340", "G341"],
        default_index: Some(1),
    },
    GGroup {
        number: 45,
        title: "Path reference for FGROUP axes",
        effect: Effect::Modal,
        members: &["SPATH", "UPATH"],
        default_index: Some(1),
    },
    GGroup {
        number: 46,
        title: "Plane for fast retraction",
        effect: Effect::Modal,
        members: &["LFTXT", "LFWP", "LFPOS"],
        default_index: Some(1),
    },
    GGroup {
        number: 47,
        title: "Mode switch for external NC code",
        effect: Effect::Modal,
        members: &["G290", "G291"],
        default_index: Some(1),
    },
    GGroup {
        number: 48,
        title: "Approach/retract with TRC",
        effect: Effect::Modal,
        members: &["G460", "G461", "G462"],
        default_index: Some(3),
    },
    GGroup {
        number: 49,
        title: "Point-to-point motion",
        effect: Effect::Modal,
        members: &["CP", "PTP", "PTPG0", "PTPWOC"],
        default_index: Some(1),
    },
    GGroup {
        number: 50,
        title: "Orientation programming",
        effect: Effect::Modal,
        members: &[
            "ORIEULER", "ORIRPY", "ORIVIRT1", "ORIVIRT2", "ORIAXPOS", "ORIRPY2",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 51,
        title: "Orientation interpolation type",
        effect: Effect::Modal,
        members: &[
            "ORIVECT",
            "ORIAXES",
            "ORIPATH",
            "ORIPLANE",
            "ORICONCW",
            "ORICONCCW",
            "ORICONIO",
            "ORICONTO",
            "ORICURVE",
            "ORIPATHS",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 52,
        title: "Frame rotation relative to workpiece",
        effect: Effect::Modal,
        members: &["PAROTOF", "PAROT"],
        default_index: Some(1),
    },
    // Groups 53 (TOROT…) and 56 (TOW…) as in ONE p.1263, FU04 p.449,
    // FU06 p.493 and MD20150; CEAD's ggroups.json has them swapped.
    GGroup {
        number: 53,
        title: "Frame rotation relative to tool",
        effect: Effect::Modal,
        members: &[
            "TOROTOF", "TOROT", "TOROTZ", "TOROTY", "TOROTX", "TOFRAME", "TOFRAMEZ", "TOFRAMEY",
            "TOFRAMEX",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 54,
        title: "Vector rotation for polynomial programming",
        effect: Effect::Modal,
        members: &["ORIROTA", "ORIROTR", "ORIROTT", "ORIROTC"],
        default_index: Some(1),
    },
    GGroup {
        number: 55,
        title: "Rapid traverse with/without linear interpolation",
        effect: Effect::Modal,
        members: &["RTLION", "RTLIOF"],
        default_index: Some(1),
    },
    GGroup {
        number: 56,
        title: "Inclusion of tool wear",
        effect: Effect::Modal,
        members: &["TOWSTD", "TOWMCS", "TOWWCS", "TOWBCS", "TOWTCS", "TOWKCS"],
        default_index: Some(1),
    },
    GGroup {
        number: 57,
        title: "Corner deceleration",
        effect: Effect::Modal,
        members: &["FENDNORM", "G62", "G621"],
        default_index: Some(1),
    },
    // Default uncertain (reference §3.2 group 58, open point 15): the
    // MD20150 text gives RELIEVEON (1), the older FU04/FU06 G tables mark
    // RELIEVEOF "Def.". RELIEVEON is kept because every default in this
    // table is an MD20150 standard value and that text is the newer
    // source. The title marks the group as reserved, so the choice should
    // rarely matter, and a machine profile's MD20150 overrides it anyway.
    GGroup {
        number: 58,
        title: "Retract from software limit (reserved)",
        effect: Effect::Modal,
        members: &["RELIEVEON", "RELIEVEOF"],
        default_index: Some(1),
    },
    GGroup {
        number: 59,
        title: "Dynamic response mode for path interpolation",
        effect: Effect::Modal,
        members: &[
            "DYNNORM",
            "DYNPOS",
            "DYNROUGH",
            "DYNSEMIFIN",
            "DYNFINISH",
            "DYNPREC",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 60,
        title: "WCS working-area limitation",
        effect: Effect::Modal,
        members: &[
            "WALCS0", "WALCS1", "WALCS2", "WALCS3", "WALCS4", "WALCS5", "WALCS6", "WALCS7",
            "WALCS8", "WALCS9", "WALCS10",
        ],
        default_index: Some(1),
    },
    GGroup {
        number: 61,
        title: "Tool orientation smoothing",
        effect: Effect::Modal,
        members: &["ORISOF", "ORISON"],
        default_index: Some(1),
    },
    GGroup {
        number: 62,
        title: "REPOS mode (non-modal)",
        effect: Effect::NonModal,
        members: &["RMBBL", "RMIBL", "RMEBL", "RMNBL"],
        default_index: None,
    },
    GGroup {
        number: 63,
        title: "not assigned",
        effect: Effect::Modal,
        members: &[],
        default_index: None,
    },
    // Default index 1 = GFRAME0; the MD20150 text calls it "GS0" [?].
    GGroup {
        number: 64,
        title: "Grinding frames",
        effect: Effect::Modal,
        members: &[
            "GFRAME0",
            "GFRAME1",
            "GFRAME2",
            "GFRAME3",
            "GFRAME4",
            "GFRAME5",
            "GFRAME6",
            "GFRAME7",
            "GFRAME8",
            "GFRAME9",
            "GFRAME10",
            "GFRAME11",
            "GFRAME12",
            "GFRAME13",
            "GFRAME14",
            "GFRAME15",
            "GFRAME16",
            "GFRAME17",
            "GFRAME18",
            "GFRAME19",
            "GFRAME20",
            "GFRAME21",
            "GFRAME22",
            "GFRAME23",
            "GFRAME24",
            "GFRAME25",
            "GFRAME26",
            "GFRAME27",
            "GFRAME28",
            "GFRAME29",
            "GFRAME30",
            "GFRAME31",
            "GFRAME32",
            "GFRAME33",
            "GFRAME34",
            "GFRAME35",
            "GFRAME36",
            "GFRAME37",
            "GFRAME38",
            "GFRAME39",
            "GFRAME40",
            "GFRAME41",
            "GFRAME42",
            "GFRAME43",
            "GFRAME44",
            "GFRAME45",
            "GFRAME46",
            "GFRAME47",
            "GFRAME48",
            "GFRAME49",
            "GFRAME50",
            "GFRAME51",
            "GFRAME52",
            "GFRAME53",
            "GFRAME54",
            "GFRAME55",
            "GFRAME56",
            "GFRAME57",
            "GFRAME58",
            "GFRAME59",
            "GFRAME60",
            "GFRAME61",
            "GFRAME62",
            "GFRAME63",
            "GFRAME64",
            "GFRAME65",
            "GFRAME66",
            "GFRAME67",
            "GFRAME68",
            "GFRAME69",
            "GFRAME70",
            "GFRAME71",
            "GFRAME72",
            "GFRAME73",
            "GFRAME74",
            "GFRAME75",
            "GFRAME76",
            "GFRAME77",
            "GFRAME78",
            "GFRAME79",
            "GFRAME80",
            "GFRAME81",
            "GFRAME82",
            "GFRAME83",
            "GFRAME84",
            "GFRAME85",
            "GFRAME86",
            "GFRAME87",
            "GFRAME88",
            "GFRAME89",
            "GFRAME90",
            "GFRAME91",
            "GFRAME92",
            "GFRAME93",
            "GFRAME94",
            "GFRAME95",
            "GFRAME96",
            "GFRAME97",
            "GFRAME98",
            "GFRAME99",
            "GFRAME100",
        ],
        default_index: Some(1),
    },
];

/// The group with this number (1…64).
pub fn group(number: u8) -> Option<&'static GGroup> {
    G_GROUPS.get(usize::from(number).checked_sub(1)?)
}

/// Whether group `number` keeps its command after its block (false for
/// non-modal groups and numbers outside 1…64).
pub fn is_modal(number: u8) -> bool {
    group(number).is_some_and(|g| g.effect == Effect::Modal)
}

/// The command a group is reset to, per the Siemens 840D standard MD20150
/// values; `None` for non-modal and unassigned groups and for numbers
/// outside 1…64.
pub fn default_member(number: u8) -> Option<&'static str> {
    member(number, group(number)?.default_index?)
}

/// The command at a group number and 1-based index, as the registry
/// spells it; `None` outside the table and for index gaps.
pub fn member(number: u8, index: u8) -> Option<&'static str> {
    let name = *group(number)?
        .members
        .get(usize::from(index).checked_sub(1)?)?;
    (!name.is_empty()).then_some(name)
}

/// A G command by its place in the registry: the group and the 1-based
/// index the control itself uses (what `$P_GG` returns). Two bytes, and
/// its name is [`member`]; in JSON it is the name (`"G17"`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct GCommand {
    group: u8,
    index: u8,
}

impl GCommand {
    /// The command at `group` and `index`; `None` where the registry has
    /// none.
    pub fn new(group: u8, index: u8) -> Option<Self> {
        member(group, index).map(|_| Self { group, index })
    }

    /// The command named `code`, as [`lookup`] reads it.
    pub fn named(code: &str) -> Option<Self> {
        let (group, index) = lookup(code)?;
        Some(Self { group, index })
    }

    pub const fn group(self) -> u8 {
        self.group
    }

    pub const fn index(self) -> u8 {
        self.index
    }

    /// The name as the registry spells it (`G17`, `DIAMON`).
    pub fn name(self) -> &'static str {
        // Every `GCommand` is made from a member, so the fallback is never
        // taken.
        member(self.group, self.index).unwrap_or("")
    }
}

impl serde::Serialize for GCommand {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> serde::Deserialize<'de> for GCommand {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let code = std::borrow::Cow::<'de, str>::deserialize(deserializer)?;
        Self::named(&code)
            .ok_or_else(|| serde::de::Error::custom(format_args!("`{code}` is not a G command")))
    }
}

/// The (group number, 1-based index) of a G command, or `None` if `code` is
/// not a member of any group.
///
/// Case-insensitive, as keywords are on the control. A `G` followed only by
/// digits is taken by its value, so `G01` is `G1` and `G00` is `G0`: the
/// control reads the value of a DIN word, whose leading zeros are optional
/// (reference §1.3, "Word value"). Names that merely end in digits are not
/// rewritten (`WALCS01` is not `WALCS1`), since those are identifiers, not
/// address + value.
///
/// Runs for every G word of every block and every modal change a run
/// executes: `G<digits>` is read from [`lookup_g`]'s table, other names
/// are normalised into a stack buffer and binary-searched in a sorted
/// table.
pub fn lookup(code: &str) -> Option<(u8, u8)> {
    match code.as_bytes() {
        [b'G' | b'g', digits @ ..]
            if (1..=3).contains(&digits.len()) && digits.iter().all(u8::is_ascii_digit) =>
        {
            let n = digits.iter().fold(0, |n, d| n * 10 + u64::from(d - b'0'));
            lookup_g(n)
        }
        _ => search(code),
    }
}

/// [`lookup`] by binary search.
fn search(code: &str) -> Option<(u8, u8)> {
    let mut buf = [0u8; MAX_NAME_LEN];
    let key = normalise(code.as_bytes(), &mut buf)?;
    let names = by_name();
    let at = names
        .binary_search_by(|(name, _, _)| name.as_bytes().cmp(key))
        .ok()?;
    let (_, group, index) = names[at];
    Some((group, index))
}

/// [`lookup`] of `G<n>`: the commonest word of all, so the numbered
/// commands below 1,000 are read from a table by number, with no
/// text to write and no search.
pub fn lookup_g(n: u64) -> Option<(u8, u8)> {
    match usize::try_from(n).ok().and_then(|i| BY_NUMBER.get(i)) {
        Some(found) => *found,
        None => search(&format!("G{n}")),
    }
}

/// Every numbered G command of the control is below this.
const NUMBERED_G: u64 = 1000;

/// [`lookup_g`]'s table: the group and index of `G<n>` at `n`. Built from
/// [`G_GROUPS`] at compile time, so no start spends time on it (building
/// it on first use, by a search per number, was a tenth of the start of a
/// one-line program).
static BY_NUMBER: [Option<(u8, u8)>; NUMBERED_G as usize] = numbered_members();

const fn numbered_members() -> [Option<(u8, u8)>; NUMBERED_G as usize] {
    let mut table = [None; NUMBERED_G as usize];
    let mut g = 0;
    while g < G_GROUPS.len() {
        let group = &G_GROUPS[g];
        let mut i = 0;
        while i < group.members.len() {
            if let Some(n) = g_number(group.members[i].as_bytes())
                && n < NUMBERED_G
            {
                // At most 21 members a group: the index fits a byte.
                table[n as usize] = Some((group.number, (i + 1) as u8));
            }
            i += 1;
        }
        g += 1;
    }
    table
}

/// `n` for a member named `G<n>` as [`search`] finds it by `G{n}`: the
/// digits without a leading zero (`G0` itself is the one exception).
const fn g_number(name: &[u8]) -> Option<u64> {
    if name.len() < 2 || name[0] != b'G' || (name[1] == b'0' && name.len() > 2) {
        return None;
    }
    let mut n = 0u64;
    let mut i = 1;
    while i < name.len() {
        if !name[i].is_ascii_digit() {
            return None;
        }
        n = n * 10 + (name[i] - b'0') as u64;
        i += 1;
    }
    Some(n)
}

/// Length of the longest member name (`DYNSEMIFIN`); anything longer
/// cannot match, which bounds the normalisation buffer.
const MAX_NAME_LEN: usize = 10;

/// Upper-cases `code` into `buf` and strips leading zeros from the value of
/// a `G<digits>` word (keeping one digit, so `G00` → `G0`). `None` when the
/// result would be longer than any member.
fn normalise<'a>(code: &[u8], buf: &'a mut [u8; MAX_NAME_LEN]) -> Option<&'a [u8]> {
    let (prefix, rest): (&[u8], &[u8]) = match code {
        [b'G' | b'g', digits @ ..]
            if !digits.is_empty() && digits.iter().all(u8::is_ascii_digit) =>
        {
            let first = digits
                .iter()
                .position(|&d| d != b'0')
                .unwrap_or(digits.len() - 1);
            (b"G", &digits[first..])
        }
        _ => (b"", code),
    };
    let len = prefix.len() + rest.len();
    if len > MAX_NAME_LEN {
        return None;
    }
    buf[..prefix.len()].copy_from_slice(prefix);
    for (to, from) in buf[prefix.len()..len].iter_mut().zip(rest) {
        *to = from.to_ascii_uppercase();
    }
    Some(&buf[..len])
}

/// Every member of [`G_GROUPS`] as (name, group, index), sorted by the
/// bytes of the name for [`lookup`]: derived from the one table, so no
/// second table can drift from it, and at compile time, so no start
/// sorts it (sorting it on first use was a sixth of a one-line run).
fn by_name() -> &'static [(&'static str, u8, u8)] {
    &BY_NAME
}

/// The number of members, gaps left out.
const NAME_COUNT: usize = {
    let mut count = 0;
    let mut g = 0;
    while g < G_GROUPS.len() {
        let mut i = 0;
        while i < G_GROUPS[g].members.len() {
            if !G_GROUPS[g].members[i].is_empty() {
                count += 1;
            }
            i += 1;
        }
        g += 1;
    }
    count
};

static BY_NAME: [(&str, u8, u8); NAME_COUNT] = sorted_names();

const fn sorted_names() -> [(&'static str, u8, u8); NAME_COUNT] {
    let mut names = [("", 0, 0); NAME_COUNT];
    let mut count = 0;
    let mut g = 0;
    while g < G_GROUPS.len() {
        let group = &G_GROUPS[g];
        let mut i = 0;
        while i < group.members.len() {
            if !group.members[i].is_empty() {
                // At most 21 members a group: the index fits a byte.
                names[count] = (group.members[i], group.number, (i + 1) as u8);
                count += 1;
            }
            i += 1;
        }
        g += 1;
    }
    // Insertion sort: a few hundred names, once, by the compiler.
    let mut i = 1;
    while i < NAME_COUNT {
        let mut j = i;
        while j > 0 && bytes_before(names[j].0.as_bytes(), names[j - 1].0.as_bytes()) {
            let before = names[j - 1];
            names[j - 1] = names[j];
            names[j] = before;
            j -= 1;
        }
        i += 1;
    }
    names
}

/// `a < b` as `[u8]`'s `Ord` has it, in a `const fn`.
const fn bytes_before(a: &[u8], b: &[u8]) -> bool {
    let mut i = 0;
    while i < a.len() && i < b.len() {
        if a[i] != b[i] {
            return a[i] < b[i];
        }
        i += 1;
    }
    a.len() < b.len()
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    /// What `lookup` must agree with: the obvious scan over every member.
    fn scan(name: &str) -> Option<(u8, u8)> {
        G_GROUPS.iter().find_map(|g| {
            let at = g.members.iter().position(|m| !m.is_empty() && *m == name)?;
            Some((g.number, u8::try_from(at + 1).unwrap()))
        })
    }

    fn index_of(group_number: u8, name: &str) -> usize {
        let members = group(group_number).unwrap().members;
        members.iter().position(|m| *m == name).unwrap() + 1
    }

    #[test]
    fn numbered_g_commands_are_found_by_number_as_by_name() {
        for n in (0..2 * NUMBERED_G).chain([u64::MAX]) {
            let name = format!("G{n}");
            assert_eq!(lookup_g(n), search(&name), "{name}");
            assert_eq!(lookup(&name), search(&name), "{name}");
            assert_eq!(lookup(&format!("g00{n}")), search(&name), "{name}");
        }
        // Every numbered member is below the table's end.
        for g in G_GROUPS {
            for m in g.members {
                if let Some(n) = m.strip_prefix('G').and_then(|d| d.parse::<u64>().ok()) {
                    assert!(n < NUMBERED_G, "{m}");
                    assert!(lookup_g(n).is_some(), "{m}");
                }
            }
        }
    }

    #[test]
    fn groups_are_numbered_1_to_64_in_order() {
        assert_eq!(G_GROUPS.len(), 64);
        for (i, g) in G_GROUPS.iter().enumerate() {
            assert_eq!(usize::from(g.number), i + 1);
            assert!(!g.title.is_empty());
            assert_eq!(group(g.number), Some(g));
        }
        assert_eq!(group(0), None);
        assert_eq!(group(65), None);
    }

    #[test]
    fn member_counts_follow_the_table() {
        let count = |n| group(n).unwrap().members.len();
        assert_eq!(count(1), 21);
        assert_eq!(count(2), 18);
        assert_eq!(count(3), 18);
        assert_eq!(count(8), 100);
        assert_eq!(count(15), 13);
        assert_eq!(count(31), 10);
        assert_eq!(count(32), 10);
        assert_eq!(count(60), 11);
        assert_eq!(count(64), 101);
    }

    #[test]
    fn group_8_indices() {
        assert_eq!(index_of(8, "G500"), 1);
        assert_eq!(index_of(8, "G54"), 2);
        assert_eq!(index_of(8, "G57"), 5);
        assert_eq!(index_of(8, "G505"), 6);
        assert_eq!(index_of(8, "G599"), 100);
    }

    #[test]
    fn group_3_keeps_the_gap_at_index_9() {
        assert_eq!(group(3).unwrap().members[8], "");
        assert_eq!(index_of(3, "AMIRROR"), 8);
        assert_eq!(index_of(3, "G25"), 10);
        assert_eq!(index_of(3, "G58"), 15);
        assert_eq!(index_of(3, "ROTS"), 17);
        assert_eq!(index_of(3, "AROTS"), 18);
    }

    #[test]
    fn gaps_only_in_group_3() {
        for g in &G_GROUPS {
            let gaps = g.members.iter().filter(|m| m.is_empty()).count();
            assert_eq!(gaps, usize::from(g.number == 3), "group {}", g.number);
        }
    }

    #[test]
    fn range_groups_are_expanded() {
        assert_eq!(group(31).unwrap().members.first(), Some(&"G810"));
        assert_eq!(group(31).unwrap().members.last(), Some(&"G819"));
        assert_eq!(group(32).unwrap().members.first(), Some(&"G820"));
        assert_eq!(group(32).unwrap().members.last(), Some(&"G829"));
        assert_eq!(index_of(60, "WALCS0"), 1);
        assert_eq!(index_of(60, "WALCS10"), 11);
        assert_eq!(index_of(64, "GFRAME0"), 1);
        assert_eq!(index_of(64, "GFRAME100"), 101);
    }

    #[test]
    fn defaults_follow_the_table() {
        for (n, name) in [
            (1, "G1"),
            (4, "STARTFIFO"),
            (6, "G17"),
            (7, "G40"),
            (8, "G500"),
            (10, "G60"),
            (13, "G71"),
            (14, "G90"),
            (15, "G94"),
            (26, "RMI"),
            (29, "DIAMOF"),
            (31, "G810"),
            (32, "G820"),
            (48, "G462"),
            (53, "TOROTOF"),
            (56, "TOWSTD"),
            (58, "RELIEVEON"),
            (60, "WALCS0"),
            (64, "GFRAME0"),
        ] {
            assert_eq!(default_member(n), Some(name), "group {n}");
        }
        assert_eq!(group(1).unwrap().default_index, Some(2));
        assert_eq!(group(15).unwrap().default_index, Some(2));
        assert_eq!(group(48).unwrap().default_index, Some(3));
    }

    #[test]
    fn every_modal_assigned_group_has_a_default() {
        for g in &G_GROUPS {
            let expected = g.effect == Effect::Modal && !g.members.is_empty();
            assert_eq!(
                default_member(g.number).is_some(),
                expected,
                "group {}",
                g.number
            );
            assert_eq!(g.default_index.is_some(), expected, "group {}", g.number);
        }
        assert_eq!(default_member(0), None);
        assert_eq!(default_member(65), None);
    }

    #[test]
    fn non_modal_groups_are_2_3_9_11_62() {
        let non_modal: Vec<u8> = G_GROUPS
            .iter()
            .filter(|g| g.effect == Effect::NonModal)
            .map(|g| g.number)
            .collect();
        assert_eq!(non_modal, [2, 3, 9, 11, 62]);
    }

    #[test]
    fn unassigned_groups_are_empty() {
        for n in [5, 63] {
            let g = group(n).unwrap();
            assert!(g.members.is_empty());
            assert_eq!(g.default_index, None);
            assert_eq!(g.effect, Effect::Modal);
        }
        let empty: Vec<u8> = G_GROUPS
            .iter()
            .filter(|g| g.members.is_empty())
            .map(|g| g.number)
            .collect();
        assert_eq!(empty, [5, 63]);
    }

    #[test]
    fn lookup_examples() {
        assert_eq!(lookup("G1"), Some((1, 2)));
        assert_eq!(lookup("g1"), Some((1, 2)));
        assert_eq!(lookup("G01"), Some((1, 2)));
        assert_eq!(lookup("G0"), Some((1, 1)));
        assert_eq!(lookup("G00"), Some((1, 1)));
        assert_eq!(lookup("g000"), Some((1, 1)));
        assert_eq!(lookup("G0599"), Some((8, 100)));
        assert_eq!(lookup("DIAMON"), Some((29, 2)));
        assert_eq!(lookup("diamon"), Some((29, 2)));
        assert_eq!(lookup("DiamOn"), Some((29, 2)));
        assert_eq!(lookup("G599"), Some((8, 100)));
        assert_eq!(lookup("G58"), Some((3, 15)));
        assert_eq!(lookup("G25"), Some((3, 10)));
        assert_eq!(lookup("G94"), Some((15, 2)));
        assert_eq!(lookup("gframe100"), Some((64, 101)));
        assert_eq!(lookup("DYNSEMIFIN"), Some((59, 4)));
    }

    #[test]
    fn lookup_rejects_non_members() {
        for code in [
            "",
            "G",
            "g",
            "G5000",
            "G6",
            "G504",
            "G600",
            "G646",
            "G-1",
            "G1.0",
            "G 1",
            " G1",
            "G1 ",
            "X1",
            "WALCS01",
            "GFRAME101",
            "GFRAME1000",
            "DYNSEMIFINX",
            "GÖ",
            "É",
        ] {
            assert_eq!(lookup(code), None, "{code:?}");
        }
    }

    #[test]
    fn long_runs_of_leading_zeros_still_normalise() {
        assert_eq!(lookup("G0000000000000000001"), Some((1, 2)));
        assert_eq!(lookup("G00000000000000000000"), Some((1, 1)));
    }

    #[test]
    fn lookup_agrees_with_a_linear_scan() {
        let mut checked = 0;
        for g in &G_GROUPS {
            for (i, name) in g.members.iter().enumerate() {
                if name.is_empty() {
                    continue;
                }
                let expected = Some((g.number, u8::try_from(i + 1).unwrap()));
                assert_eq!(scan(name), expected, "{name}");
                assert_eq!(lookup(name), expected, "{name}");
                assert_eq!(lookup(&name.to_ascii_lowercase()), expected, "{name}");
                if let Some(value) = name.strip_prefix('G').filter(|v| v.parse::<u16>().is_ok()) {
                    assert_eq!(lookup(&format!("g0{value}")), expected, "{name}");
                }
                checked += 1;
            }
        }
        assert_eq!(checked, by_name().len());
    }

    #[test]
    fn commands_are_written_by_name() {
        let g17 = GCommand::named("g17").unwrap();
        assert_eq!((g17.group(), g17.index(), g17.name()), (6, 1, "G17"));
        assert_eq!(GCommand::new(6, 1), Some(g17));
        assert_eq!(GCommand::new(3, 9), None);
        assert_eq!(GCommand::new(65, 1), None);
        assert_eq!(serde_json::to_string(&g17).unwrap(), "\"G17\"");
        let back: GCommand = serde_json::from_str("\"G17\"").unwrap();
        assert_eq!(back, g17);
        assert!(serde_json::from_str::<GCommand>("\"G6\"").is_err());
    }

    #[test]
    fn names_are_sorted_and_unique() {
        assert!(
            by_name()
                .windows(2)
                .all(|w| w[0].0.as_bytes() < w[1].0.as_bytes())
        );
        assert_eq!(by_name().len(), 492);
    }

    #[test]
    fn every_member_is_in_exactly_one_group() {
        let mut seen: HashMap<&str, u8> = HashMap::new();
        for g in &G_GROUPS {
            for &name in g.members.iter().filter(|m| !m.is_empty()) {
                if let Some(other) = seen.insert(name, g.number) {
                    panic!("{name} is in groups {other} and {}", g.number);
                }
            }
        }
    }

    #[test]
    fn members_are_upper_case_and_fit_the_buffer() {
        for g in &G_GROUPS {
            for name in g.members.iter().filter(|m| !m.is_empty()) {
                assert!(name.len() <= MAX_NAME_LEN, "{name}");
                assert!(
                    name.bytes()
                        .all(|b| b.is_ascii_uppercase() || b.is_ascii_digit()),
                    "{name}"
                );
                // Stored G codes are already in normal form, or lookup could not find them.
                if let Some(value) = name
                    .strip_prefix('G')
                    .filter(|v| v.bytes().all(|b| b.is_ascii_digit()))
                {
                    assert!(value == "0" || !value.starts_with('0'), "{name}");
                }
            }
        }
        let longest = G_GROUPS
            .iter()
            .flat_map(|g| g.members)
            .map(|m| m.len())
            .max();
        assert_eq!(longest, Some(MAX_NAME_LEN));
    }
}
