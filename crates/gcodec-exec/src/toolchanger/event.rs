//! The `toolchanger` event: one edge of the toolchanger protocol.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{AbortReason, ChangerState};

/// One edge of the toolchanger protocol (SPEC §12).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct ToolchangerEvent {
    pub edge: ToolchangerEdge,
    /// The protocol's state after the edge.
    pub state: ChangerState,
    /// The changer's cycle count at the edge (from 0 when the run starts).
    pub cycle: u64,
    /// The tool the edge is about, named as `tool_change` names it; left
    /// out for no tool (`T0`) and for faults and aborts.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tool: Option<String>,
    /// The pocket the tool comes from (on a random changer, where the
    /// spindle's tool goes); left out where it does not apply or the tool
    /// has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pocket: Option<u32>,
    /// `fault_latched`: the changer's reason, above 0 soft, 0 and below
    /// hard.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fault_reason: Option<i32>,
    /// `abort_raised`, `abort_acknowledged`: the abort's reason.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub abort_reason: Option<AbortReason>,
}

impl ToolchangerEvent {
    /// An edge with none of the optional fields.
    pub fn new(edge: ToolchangerEdge, state: ChangerState, cycle: u64) -> Self {
        Self {
            edge,
            state,
            cycle,
            tool: None,
            pocket: None,
            fault_reason: None,
            abort_reason: None,
        }
    }
}

/// The edges of the toolchanger protocol.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ToolchangerEdge {
    PrepareRequested,
    PrepareAcknowledged,
    StartChangeRequested,
    StartChangeAcknowledged,
    ChangeRequested,
    ChangeAcknowledged,
    /// The tool in the spindle is the prepared one now.
    ChangeCommitted,
    FaultLatched,
    FaultCleared,
    AbortRaised,
    AbortAcknowledged,
}

impl ToolchangerEdge {
    /// The edge in words, for the text trace.
    pub fn words(self) -> &'static str {
        match self {
            Self::PrepareRequested => "prepare requested",
            Self::PrepareAcknowledged => "prepare acknowledged",
            Self::StartChangeRequested => "start-change requested",
            Self::StartChangeAcknowledged => "start-change acknowledged",
            Self::ChangeRequested => "change requested",
            Self::ChangeAcknowledged => "change acknowledged",
            Self::ChangeCommitted => "change committed",
            Self::FaultLatched => "fault latched",
            Self::FaultCleared => "fault cleared",
            Self::AbortRaised => "abort raised",
            Self::AbortAcknowledged => "abort acknowledged",
        }
    }
}
