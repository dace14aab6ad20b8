//! Tool selection (`T`), the tool change (`M6` or the `T` word itself) and
//! cutting edges (`D`): resolving a selection against the tool table, the
//! pending selection, and the active edge's length offset.

use std::sync::Arc;

use gcodec_ail::{Instruction, SelectorKind, ToolChangeTrigger, ToolSelect, Value};
use gcodec_profile::{EdgeWithoutTool, PendingSelectionScope, Policy, UnresolvedToolPolicy};
use gcodec_source::{Severity, codes};

use super::machine_calls::{ChangeInProgress, Continuation};
use super::{Channel, Flow};
use crate::eval;
use crate::event::{EventKind, SelectionSource, ToolChangeEvent, ToolSelectEvent};
use crate::machine::{ChangeResult, MachineAction, ToolRequest};
use crate::program::Program;
use crate::tool_resolution::{
    CallerSelection, PendingTool, ResolutionContext, ToolRef, ToolResolution, ToolSelector,
};
use crate::value::{RtValue, RunError};

impl Channel<'_> {
    pub(super) fn tool_select(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        select: &ToolSelect,
    ) -> Result<Flow, RunError> {
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
        let selector = ToolSelector { kind, value };
        // `T0` selects no tool: there is nothing to resolve.
        let resolved = if selector.value == "0" && kind != SelectorKind::Name {
            None
        } else {
            Some(self.resolve_tool(program, instruction, &selector)?)
        };
        let event = EventKind::ToolSelect(ToolSelectEvent {
            selector_kind: selector.kind,
            selector_value: selector.value,
            selected_tool: resolved.as_ref().map(|(t, _)| t.label.clone()),
            spindle_extension: select.spindle_extension,
            timing: select.timing,
        });
        self.emit_at(program, instruction, event);
        let pending = PendingTool {
            substituted: resolved.as_ref().is_some_and(|(_, s)| *s),
            tool: resolved.map(|(t, _)| t),
        };
        // The machine brings the tool to the change position (in direct
        // mode the change follows at once).
        let previous = self.state.active_tool.as_ref().map(|t| t.label.clone());
        let request = ToolRequest {
            tool: pending.tool.as_ref().map(|t| t.label.as_str()),
            number: pending.tool.as_ref().map_or(0, |t| t.number),
            previous: previous.as_deref(),
        };
        let answer = self
            .machine
            .prepare_tool(&request, &mut self.machine_events);
        let tool = request.tool.map(str::to_owned);
        self.state.programmed_tool = request.number;
        self.state.pending = Some(pending);
        let action = || MachineAction::PrepareTool { tool };
        self.machine_done(program, pc, instruction, answer, action)
    }

    /// Asks the channel's resolver what `selector` names, with whether a
    /// replacement tool was chosen; an unresolved or ambiguous selection
    /// follows `on_unresolved_tool`.
    fn resolve_tool(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        selector: &ToolSelector,
    ) -> Result<(ToolRef, bool), RunError> {
        let profile = Arc::clone(&self.state.profile);
        let context = ResolutionContext {
            active_tool: self.state.active_tool.as_ref(),
            tools: self.state.tool_data.tools(),
            tool_management: profile.tool_change.tool_management_enabled,
        };
        let resolution = self
            .tool_resolver
            .resolve_selection(selector, &profile, &context);
        let (code, why, fallback) = match resolution {
            ToolResolution::Resolved { tool, substituted }
                if !substituted || profile.tool_change.allow_substitution =>
            {
                return Ok((tool, substituted));
            }
            ToolResolution::Resolved { tool, .. } => (
                codes::run::UNRESOLVED_TOOL,
                format!(
                    "the tool resolver replaces `{}` by {}, and the profile allows no substitution",
                    selector.value, tool.label
                ),
                None,
            ),
            ToolResolution::Unresolved { why } => (codes::run::UNRESOLVED_TOOL, why, None),
            ToolResolution::Ambiguous { mut candidates } => {
                // The resolver's order is no rule: the message and the
                // fallback do not depend on it.
                candidates.sort_by(|a, b| (a.number, &a.label).cmp(&(b.number, &b.label)));
                candidates.dedup();
                match candidates.len() {
                    0 => (
                        codes::run::UNRESOLVED_TOOL,
                        format!(
                            "no tool `{}` among the resolver's candidates",
                            selector.value
                        ),
                        None,
                    ),
                    1 => return Ok((candidates.swap_remove(0), false)),
                    _ => {
                        let names: Vec<&str> =
                            candidates.iter().map(|t| t.label.as_str()).collect();
                        (
                            codes::run::AMBIGUOUS_TOOL,
                            format!(
                                "the tool `{}` is ambiguous: {} fit, and the tool resolver has no rule to choose",
                                selector.value,
                                names.join(", ")
                            ),
                            candidates.into_iter().next(),
                        )
                    }
                }
            }
        };
        match profile.tool_change.on_unresolved_tool {
            UnresolvedToolPolicy::Error => Err(RunError::new(code, why)),
            UnresolvedToolPolicy::Warning => {
                self.diagnostic_at(program, instruction, code, Severity::Warning, why, None);
                Ok((selector.literal(), false))
            }
            UnresolvedToolPolicy::Fallback => {
                Ok((fallback.unwrap_or_else(|| selector.literal()), false))
            }
        }
    }

    /// A program level opens: with `pending_selection_scope =
    /// "program_level"` it starts with no pending selection and no
    /// programmed tool, and the caller's are put aside (returned) until
    /// the level closes.
    pub(super) fn enter_pending_scope(&mut self) -> Option<CallerSelection> {
        match self.state.profile.tool_change.pending_selection_scope {
            PendingSelectionScope::Channel => None,
            PendingSelectionScope::ProgramLevel => Some(CallerSelection {
                pending: self.state.pending.take(),
                programmed: std::mem::take(&mut self.state.programmed_tool),
            }),
        }
    }

    /// A program level closes: with `"program_level"` its own selection is
    /// dropped and the caller's (`caller`) comes back.
    pub(super) fn leave_pending_scope(&mut self, caller: Option<CallerSelection>) {
        if let Some(caller) = caller {
            self.state.pending = caller.pending;
            self.state.programmed_tool = caller.programmed;
        }
    }

    pub(super) fn tool_change(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        trigger: ToolChangeTrigger,
    ) -> Result<Flow, RunError> {
        let previous = self.state.active_tool.as_ref().map(|t| t.label.clone());
        let (new, source, substituted) = if let Some(pending) = self.state.pending.take() {
            let source = match trigger {
                ToolChangeTrigger::M6 => SelectionSource::PendingThenM6,
                ToolChangeTrigger::TWord => SelectionSource::DirectTWord,
            };
            let change = ChangeInProgress {
                previous,
                new: pending.tool,
                source,
                substituted: pending.substituted,
                trigger,
            };
            return self.change_on_machine(program, pc, instruction, change);
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
        // Nothing to change: the tool stays, the machine is not asked.
        let change = ChangeInProgress {
            previous,
            new,
            source,
            substituted,
            trigger,
        };
        self.finish_change(program, instruction, change, ChangeResult::COMMITTED)
            .map(|()| Flow::Next)
    }

    /// Hands the change to the machine; its answer finishes it now or
    /// when the application resumes the run.
    fn change_on_machine(
        &mut self,
        program: &Arc<Program>,
        pc: usize,
        instruction: &Instruction,
        change: ChangeInProgress,
    ) -> Result<Flow, RunError> {
        let request = ToolRequest {
            tool: change.new.as_ref().map(|t| t.label.as_str()),
            number: change.new.as_ref().map_or(0, |t| t.number),
            previous: change.previous.as_deref(),
        };
        let answer = self.machine.change_tool(&request, &mut self.machine_events);
        let action = || MachineAction::ChangeTool {
            tool: change.new.as_ref().map(|t| t.label.clone()),
            previous: change.previous.clone(),
        };
        let continuation = Continuation::ToolChange(Box::new(change.clone()));
        match self.machine_answer(program, pc, instruction, answer, action, continuation) {
            Ok(Some(result)) => self
                .finish_change(program, instruction, change, result)
                .map(|()| Flow::Next),
            Ok(None) => Ok(Flow::Pending),
            // The change is reported as not made before the alarm: the
            // events say which tool is in the spindle.
            Err(error) => {
                self.report_change(program, instruction, change, false, None);
                Err(error)
            }
        }
    }

    /// The change as the machine made it (or did not): its event, the
    /// spindle's tool, the edge after it.
    pub(super) fn finish_change(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        change: ChangeInProgress,
        result: ChangeResult,
    ) -> Result<(), RunError> {
        let new = change.new.clone();
        self.report_change(
            program,
            instruction,
            change,
            result.committed,
            result.fault_reason,
        );
        if !result.committed {
            return Ok(());
        }
        self.state.active_tool = new;
        self.figures_slot = None;
        self.edge_after_change(program, instruction)
    }

    fn report_change(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        change: ChangeInProgress,
        committed: bool,
        fault_reason: Option<i32>,
    ) {
        let event = EventKind::ToolChange(ToolChangeEvent {
            previous_tool: change.previous,
            new_tool: change.new.map(|t| t.label),
            selection_source: change.source,
            substituted: change.substituted,
            trigger: change.trigger,
            committed,
            fault_reason,
        });
        self.emit_at(program, instruction, event);
    }

    /// The edge after a change: the `D` of its block, else MD20270
    /// (`cutting_edge_default`); `D0` without a tool, whatever the default.
    fn edge_after_change(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
    ) -> Result<(), RunError> {
        if self.state.active_tool.is_none() {
            return self.set_edge(program, instruction, 0, false);
        }
        if let Some(d) = self.block.edge {
            return self.set_edge(program, instruction, d, true);
        }
        match *self
            .state
            .profile
            .tool_change
            .cutting_edge_default
            .get_ref()
        {
            // −2: the old tool's offset stays until a `D` is programmed.
            -2 => Ok(()),
            // −1: the old edge number, of the new tool.
            -1 => self.set_edge(program, instruction, self.state.edge, false),
            // Validation keeps the default within −2…32000.
            n => self.set_edge(program, instruction, u32::try_from(n).unwrap_or(0), false),
        }
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
        self.block.edge = Some(d);
        self.set_edge(program, instruction, d, true)
    }

    /// Activates edge `d` of the active tool and its length offset
    /// (`programmed`: a `D` of the program, not a change's default).
    fn set_edge(
        &mut self,
        program: &Arc<Program>,
        instruction: &Instruction,
        d: u32,
        programmed: bool,
    ) -> Result<(), RunError> {
        self.state.edge = d;
        self.state.tool_length = 0.0;
        self.state.tool_radius = 0.0;
        self.state.edge_position = 0;
        if d == 0 {
            return Ok(());
        }
        let Some(tool) = &self.state.active_tool else {
            return match self.state.profile.tool_change.edge_without_tool {
                EdgeWithoutTool::NoOffset => Ok(()),
                EdgeWithoutTool::Alarm => Err(RunError::new(
                    codes::run::EDGE_WITHOUT_TOOL,
                    format!("`D{d}` with no tool in the spindle"),
                )),
            };
        };
        let Some(entry) = self.state.tool_data.tool(tool.number) else {
            return Ok(());
        };
        // A cutting edge position places the tip of turning tools only.
        let position = |e: &gcodec_profile::Edge| {
            if e.is_turning() {
                *e.position.get_ref()
            } else {
                0
            }
        };
        match entry.edge(d).map(|e| (e.length, e.radius, position(e))) {
            Some((length, radius, position)) => {
                self.state.tool_length = length;
                self.state.tool_radius = radius;
                self.state.edge_position = position;
            }
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
        Ok(())
    }
}
