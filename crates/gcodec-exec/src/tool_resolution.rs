//! Tool resolution as a policy (the tool-change design's
//! `ToolChangePolicy::resolveSelection`): what tool a `T` selection names.
//!
//! The channel asks a [`ToolResolver`] for every selection but `T0` (no
//! tool, never asked) and turns the answer into the tool it selects, or a
//! diagnostic under the profile's `on_unresolved_tool` (SPEC §11.7). The
//! default, [`TableResolver`], is the profile's tool table; an
//! application supplies its own with `Channel::with_tool_resolver`. The
//! tool a selection names ([`ToolRef`]) and the selection waiting for the
//! change ([`PendingTool`]) are here too, so that the channel's modules
//! share them without depending on one another.

use gcodec_ail::SelectorKind;
use gcodec_profile::{Profile, Tool, ToolState};

/// The active tool: its identity as events name it, and its number.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolRef {
    /// `T7`, or the tool's name with tool management.
    pub label: String,
    /// The T number (0 when unknown: a name not in the tool table).
    pub number: u32,
}

/// A tool selection waiting for the change.
#[derive(Clone, Debug)]
pub struct PendingTool {
    /// `None`: `T0`, a selection of no tool.
    pub tool: Option<ToolRef>,
    /// Whether it is a substitute (a sister tool).
    pub substituted: bool,
}

/// A caller's tool selection, put aside while a called program runs with
/// `pending_selection_scope = "program_level"`.
#[derive(Clone, Debug)]
pub struct CallerSelection {
    pub pending: Option<PendingTool>,
    /// The number of the last tool the caller programmed (`$P_TOOLP`).
    pub programmed: u32,
}

/// A tool selection as the `tool_select` event names it: the kind of
/// selector and its value (a T number, a magazine location or a name; a
/// computed selection already evaluated).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ToolSelector {
    pub kind: SelectorKind,
    pub value: String,
}

impl ToolSelector {
    /// The selection standing as written: `T7` (number 7), a location as
    /// `T5` (number 5), a name as itself (number 0: not in a table).
    pub fn literal(&self) -> ToolRef {
        match self.kind {
            SelectorKind::Name => ToolRef {
                label: self.value.clone(),
                number: 0,
            },
            _ => ToolRef {
                label: format!("T{}", self.value),
                number: self.value.parse().unwrap_or(0),
            },
        }
    }
}

/// What the run knows when a selection is resolved.
#[derive(Clone, Copy, Debug)]
pub struct ResolutionContext<'a> {
    /// The tool in the spindle (`None`: none).
    pub active_tool: Option<&'a ToolRef>,
    /// The run's tool table: the profile's, with the tools and edges the
    /// program made by writing `$TC_…`.
    pub tools: &'a [Tool],
    /// Tools are selected by name or location (`tool_management_enabled`).
    pub tool_management: bool,
}

/// The outcome of resolving a selection (the design's resolved,
/// unresolved, ambiguous).
#[derive(Clone, Debug, PartialEq)]
pub enum ToolResolution {
    /// The selection names `tool`; `substituted`: a replacement (sister)
    /// tool was chosen for the one named.
    Resolved { tool: ToolRef, substituted: bool },
    /// No tool fits; `why` says what is missing, for the diagnostic.
    Unresolved { why: String },
    /// Several tools fit and the resolver has no rule to choose.
    Ambiguous { candidates: Vec<ToolRef> },
}

/// Resolves tool selections. Object-safe: the channel holds a
/// `Box<dyn ToolResolver>`.
pub trait ToolResolver {
    fn resolve_selection(
        &self,
        selector: &ToolSelector,
        profile: &Profile,
        context: &ResolutionContext<'_>,
    ) -> ToolResolution;
}

/// The default resolver: the run's tool table. A number selects that
/// tool, a location the tool there, a name the sister tools of that name
/// in duplo order; the first of them that is `enabled`, a later one only
/// with `allow_substitution`. Never ambiguous: the duplo order is the
/// rule that chooses. A profile without a tool table does not know the
/// machine's tools: every selection stands as written.
#[derive(Clone, Copy, Debug, Default)]
pub struct TableResolver;

impl ToolResolver for TableResolver {
    fn resolve_selection(
        &self,
        selector: &ToolSelector,
        profile: &Profile,
        context: &ResolutionContext<'_>,
    ) -> ToolResolution {
        if profile.tools.is_empty() {
            return ToolResolution::Resolved {
                tool: selector.literal(),
                substituted: false,
            };
        }
        let value = selector.value.as_str();
        let mut candidates: Vec<&Tool> = context
            .tools
            .iter()
            .filter(|t| t.is_selected_by(selector.kind, value))
            .collect();
        if selector.kind == SelectorKind::Name {
            candidates.sort_by_key(|t| t.duplo);
        }
        let usable = candidates
            .iter()
            .position(|t| t.state == ToolState::Enabled);
        let chosen = match usable {
            Some(0) => Some((candidates[0], false)),
            Some(i) if profile.tool_change.allow_substitution => Some((candidates[i], true)),
            _ => None,
        };
        match chosen {
            Some((tool, substituted)) => ToolResolution::Resolved {
                tool: table_tool(tool, context.tool_management),
                substituted,
            },
            None if candidates.is_empty() => ToolResolution::Unresolved {
                why: format!("no tool `{value}` in the machine's tool table"),
            },
            None => ToolResolution::Unresolved {
                why: format!(
                    "the tool `{value}` is disabled or locked and no sister tool may replace it"
                ),
            },
        }
    }
}

/// A tool of the table as events name it: by its name with tool
/// management, else `T<number>`.
pub fn table_tool(tool: &Tool, tool_management: bool) -> ToolRef {
    let label = match (&tool.name, tool_management) {
        (Some(name), true) => name.get_ref().clone(),
        _ => format!("T{}", tool.number.get_ref()),
    };
    ToolRef {
        label,
        number: *tool.number.get_ref(),
    }
}
