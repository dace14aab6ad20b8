//! The effective work-offset context of a motion: the Group 8 selection,
//! whether it acts, and what the block suppresses, with the JSON
//! spellings the work-offset design gives them.

use gcodec_ail::Suppression;
use gcodec_lang::WorkOffsetCode;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

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
