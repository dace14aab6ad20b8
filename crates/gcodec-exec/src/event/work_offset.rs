//! The effective work-offset context of a motion: the Group 8 selection,
//! whether it acts, and what the block suppresses, with the JSON
//! spellings the work-offset design gives them.

use std::borrow::Cow;
use std::fmt;

use gcodec_ail::Suppression;
use schemars::{JsonSchema, Schema, SchemaGenerator, json_schema};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The effective work-offset context of a block: the modal
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

/// A Group 8 command by its number (`G54` is 54, `G505` is 505). Every member
/// of group 8 is `G` and a number, so the number is the whole identity; in JSON
/// it is the lower-case code of the work-offset design (`"g54"`).
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
    /// The work-offset design's spelling: `g54`.
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

/// What a block's suppression switches off (the work-offset design). Each level
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
