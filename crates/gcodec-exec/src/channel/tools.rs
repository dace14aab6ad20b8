//! Tool selection (`T`), the tool change (`M6` or the `T` word itself) and
//! cutting edges (`D`): resolving a selection against the tool table, the
//! pending selection, and the active edge's length offset.

use std::sync::Arc;

use gcodec_ail::{Instruction, SelectorKind, ToolChangeTrigger, ToolSelect, Value};
use gcodec_profile::{Policy, Tool, ToolState, UnresolvedToolPolicy};
use gcodec_source::{Severity, codes};

use super::Channel;
use super::state::ToolRef;
use crate::eval;
use crate::event::{EventKind, SelectionSource, ToolChangeEvent, ToolSelectEvent};
use crate::program::Program;
use crate::value::{RtValue, RunError};

impl Channel<'_> {
    pub(super) fn tool_select(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        select: &ToolSelect,
    ) -> Result<(), RunError> {
        let (kind, value) = match &select.selector_expr {
            Some(expr) => {
                let v = eval::eval(&self.env(), expr)?;
                let management = self.state.profile.tool_change.tool_management_enabled;
                match v {
                    RtValue::String(s) => (SelectorKind::Name, s.to_string()),
                    other => {
                        let n = other.to_int()?;
                        let kind = if management {
                            SelectorKind::Location
                        } else {
                            SelectorKind::Number
                        };
                        (kind, n.to_string())
                    }
                }
            }
            None => (select.selector_kind, select.selector_value.clone()),
        };
        let resolved = self.resolve_tool(program, instruction, kind, &value)?;
        let event = EventKind::ToolSelect(ToolSelectEvent {
            selector_kind: kind,
            selector_value: value,
            selected_tool: resolved.as_ref().map(|(t, _)| t.label.clone()),
            spindle_extension: select.spindle_extension,
            timing: select.timing,
        });
        self.emit_at(program, instruction, event);
        self.state.pending = Some(super::state::PendingTool {
            substituted: resolved.as_ref().is_some_and(|(_, s)| *s),
            tool: resolved.map(|(t, _)| t),
        });
        Ok(())
    }

    /// Resolves a selection against the tool table (`None`: `T0`, no tool),
    /// with whether a sister tool was substituted.
    fn resolve_tool(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        kind: SelectorKind,
        value: &str,
    ) -> Result<Option<(ToolRef, bool)>, RunError> {
        if value == "0" && kind != SelectorKind::Name {
            return Ok(None);
        }
        let profile = Arc::clone(&self.state.profile);
        let management = profile.tool_change.tool_management_enabled;
        let literal = || match kind {
            SelectorKind::Name => ToolRef {
                label: value.to_owned(),
                number: 0,
            },
            _ => ToolRef {
                label: format!("T{value}"),
                number: value.parse().unwrap_or(0),
            },
        };
        if profile.tools.is_empty() {
            return Ok(Some((literal(), false)));
        }
        let label = |tool: &Tool| match (&tool.name, management) {
            (Some(name), true) => name.get_ref().clone(),
            _ => format!("T{}", tool.number.get_ref()),
        };
        let candidates: Vec<&Tool> = match kind {
            SelectorKind::Number | SelectorKind::Location => profile
                .tools
                .iter()
                .filter(|t| t.is_selected_by(kind, value))
                .collect(),
            _ => {
                let mut sisters: Vec<&Tool> = profile
                    .tools
                    .iter()
                    .filter(|t| t.is_selected_by(SelectorKind::Name, value))
                    .collect();
                sisters.sort_by_key(|t| t.duplo);
                sisters
            }
        };
        let usable = candidates
            .iter()
            .position(|t| t.state == ToolState::Enabled);
        let chosen = match usable {
            Some(0) => Some((candidates[0], false)),
            Some(i) if profile.tool_change.allow_substitution => Some((candidates[i], true)),
            _ => None,
        };
        if let Some((tool, substituted)) = chosen {
            return Ok(Some((
                ToolRef {
                    label: label(tool),
                    number: *tool.number.get_ref(),
                },
                substituted,
            )));
        }
        let why = if candidates.is_empty() {
            format!("no tool `{value}` in the machine's tool table")
        } else {
            format!("the tool `{value}` is disabled or locked and no sister tool may replace it")
        };
        match profile.tool_change.on_unresolved_tool {
            UnresolvedToolPolicy::Error => Err(RunError::new(codes::run::UNRESOLVED_TOOL, why)),
            UnresolvedToolPolicy::Warning => {
                self.diagnostic_at(
                    program,
                    instruction,
                    codes::run::UNRESOLVED_TOOL,
                    Severity::Warning,
                    why,
                    None,
                );
                Ok(Some((literal(), false)))
            }
            UnresolvedToolPolicy::Fallback => Ok(Some((literal(), false))),
        }
    }

    pub(super) fn tool_change(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        trigger: ToolChangeTrigger,
    ) -> Result<(), RunError> {
        let previous = self.state.active_tool.as_ref().map(|t| t.label.clone());
        let (new, source, substituted) = if let Some(pending) = self.state.pending.take() {
            let source = match trigger {
                ToolChangeTrigger::M6 => SelectionSource::PendingThenM6,
                ToolChangeTrigger::TWord => SelectionSource::DirectTWord,
            };
            (pending.tool, source, pending.substituted)
        } else {
            match self.state.profile.tool_change.m6_without_pending_policy {
                Policy::Error => {
                    return Err(RunError::new(
                        codes::run::M6_WITHOUT_PENDING,
                        "the tool change has no tool selected before it (T…)",
                    ));
                }
                Policy::Warning => self.diagnostic_at(
                    program,
                    instruction,
                    codes::run::M6_WITHOUT_PENDING,
                    Severity::Warning,
                    "the tool change has no tool selected before it (T…); the tool stays".into(),
                    Some("select the tool with T before the change"),
                ),
                Policy::Ignore => {}
            }
            (
                self.state.active_tool.clone(),
                SelectionSource::M6WithoutPending,
                false,
            )
        };
        let event = EventKind::ToolChange(ToolChangeEvent {
            previous_tool: previous,
            new_tool: new.as_ref().map(|t| t.label.clone()),
            selection_source: source,
            substituted,
            trigger,
        });
        self.state.active_tool = new;
        self.figures_slot = None;
        self.emit_at(program, instruction, event);
        // The new tool's first edge is active (MD20270 = 1), D0 without a
        // tool.
        let edge = if self.state.active_tool.is_some() {
            1
        } else {
            0
        };
        self.set_edge(program, instruction, edge, false);
        Ok(())
    }

    pub(super) fn cutting_edge(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        edge: &Value,
    ) -> Result<(), RunError> {
        let d = eval::eval_value(&self.env(), edge)?.to_int()?;
        let d = u32::try_from(d).map_err(|_| {
            RunError::new(
                codes::run::OVERFLOW,
                format!("`D{d}`: an edge is 0 or more"),
            )
        })?;
        self.set_edge(program, instruction, d, true);
        Ok(())
    }

    /// Activates edge `d` of the active tool and its length offset.
    fn set_edge(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        d: u32,
        programmed: bool,
    ) {
        self.state.edge = d;
        self.state.tool_length = 0.0;
        if d == 0 {
            return;
        }
        let Some(tool) = &self.state.active_tool else {
            return;
        };
        let Some(entry) = self.state.tool_data.tool(tool.number) else {
            return;
        };
        match entry.edge(d).map(|e| e.length) {
            Some(length) => self.state.tool_length = length,
            None if programmed => {
                let message = format!(
                    "tool {} has no cutting edge D{d} in the tool table; no length offset",
                    tool.label
                );
                self.diagnostic_at(
                    program,
                    instruction,
                    codes::run::UNKNOWN_EDGE,
                    Severity::Warning,
                    message,
                    None,
                );
            }
            None => {}
        }
    }
}
