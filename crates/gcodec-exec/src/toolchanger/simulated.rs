//! [`SimulatedChanger`]: the protocol, a changer scripted by a scenario
//! and the pocket bookkeeping, behind [`Toolchanger`].

use gcodec_profile::{Profile, Scenario, ToolchangerSettings};
use gcodec_source::{Diagnostic, Span, codes};

use super::device::{Device, Handshake};
use super::pockets::Pockets;
use super::protocol::{ChangerState, Protocol};
use super::reason::{AbortReason, FaultReason};
use super::{Answer, ChangerTool, Prepared, Status, Toolchanger};
use super::{ToolchangerEdge, ToolchangerEvent};
use crate::tool_resolution::table_tool;

/// The default toolchanger: acknowledges as the scenario says (every
/// handshake after one cycle, no faults, by default).
#[derive(Clone, Debug)]
pub struct SimulatedChanger {
    settings: ToolchangerSettings,
    timeout_cycles: u32,
    protocol: Protocol,
    device: Device,
    pockets: Pockets,
    /// The tool of the prepare under way.
    preparing: Option<Prepared>,
    prepared: Option<Prepared>,
    /// The operation the last request started, for [`Status`].
    operation: Option<Handshake>,
    cycles: u64,
    /// The protocol's edges of one cycle, reused.
    edges: Vec<(ToolchangerEdge, ChangerState)>,
}

impl SimulatedChanger {
    /// A changer for `profile` (its `[toolchanger]` table, or the table's
    /// defaults) behaving as `scenario` says. An `initial_tool` the tool
    /// table lacks is `gcodec::scenario::unknown_tool`, spanned into the
    /// scenario's TOML.
    pub fn new(profile: &Profile, scenario: &Scenario) -> Result<Self, Diagnostic> {
        let settings = profile.toolchanger.clone().unwrap_or_default();
        let management = profile.tool_change.tool_management_enabled;
        let initial = match &scenario.initial_tool {
            None => None,
            Some(number) => {
                let n = *number.get_ref();
                match profile.tool(n) {
                    Some(tool) => Some(ChangerTool {
                        number: n,
                        label: table_tool(tool, management).label,
                    }),
                    None if profile.tools.is_empty() => Some(ChangerTool {
                        number: n,
                        label: format!("T{n}"),
                    }),
                    None => {
                        let span = number.span();
                        return Err(Diagnostic::new(
                            codes::scenario::UNKNOWN_TOOL,
                            format!("tool {n} is not in the profile's tool table"),
                        )
                        .with_label(Span::new(span.start as u32, span.end as u32), "here")
                        .with_help("name a tool of the profile's `[[tools]]`"));
                    }
                }
            }
        };
        Ok(Self {
            timeout_cycles: scenario
                .timeout_cycles
                .unwrap_or(*settings.timeout_cycles.get_ref()),
            pockets: Pockets::new(profile, settings.random, initial),
            settings,
            protocol: Protocol::new(scenario.initial_fault.map(FaultReason)),
            device: Device::new(scenario),
            preparing: None,
            prepared: None,
            operation: None,
            cycles: 0,
            edges: Vec::new(),
        })
    }

    /// The pins and the state, for tests that compare with iov2's.
    pub fn protocol(&self) -> &Protocol {
        &self.protocol
    }

    fn event(&self, edge: ToolchangerEdge, state: ChangerState) -> ToolchangerEvent {
        ToolchangerEvent::new(edge, state, self.cycles)
    }

    /// An event naming a prepared tool and its pocket.
    fn tool_event(
        &self,
        edge: ToolchangerEdge,
        state: ChangerState,
        prepared: Option<&Prepared>,
    ) -> ToolchangerEvent {
        ToolchangerEvent {
            tool: prepared
                .and_then(|p| p.tool.as_ref())
                .map(|t| t.label.clone()),
            pocket: prepared.and_then(|p| p.pocket),
            ..self.event(edge, state)
        }
    }

    fn abort_event(&self, edge: ToolchangerEdge, reason: AbortReason) -> ToolchangerEvent {
        ToolchangerEvent {
            abort_reason: Some(reason),
            ..self.event(edge, self.protocol.state())
        }
    }

    /// A request is raised: its event, and the operation the changer
    /// follows.
    fn raised(
        &mut self,
        handshake: Handshake,
        event: ToolchangerEvent,
        events: &mut Vec<ToolchangerEvent>,
    ) -> Answer {
        events.push(event);
        self.operation = Some(handshake);
        self.device.operation(handshake, self.cycles);
        Answer::Raised
    }

    /// An abort is raised: whatever was prepared or under way is off, so
    /// that no later change loads a stale prepare (LinuxCNC issue 330).
    fn aborted(&mut self) {
        self.preparing = None;
        self.prepared = None;
        self.operation = Some(Handshake::Abort);
        self.device.operation(Handshake::Abort, self.cycles);
    }

    /// Where the operation stands; `before` is the operation at the
    /// cycle's start (an abort raised in the cycle fails it).
    fn status(&self, before: Option<Handshake>) -> Status {
        let outputs = self.protocol.outputs();
        if self.protocol.state() == ChangerState::WaitingForAbortAck {
            return if before == Some(Handshake::Abort) {
                Status::Busy
            } else {
                Status::Failed
            };
        }
        match self.operation {
            Some(Handshake::StartChange) if self.protocol.fault().is_some() => Status::Failed,
            Some(Handshake::StartChange) if outputs.start_change => Status::Busy,
            Some(Handshake::Prepare) if outputs.prepare => Status::Busy,
            Some(Handshake::Change) if outputs.change => Status::Busy,
            _ => Status::Done,
        }
    }
}

impl Toolchanger for SimulatedChanger {
    fn supports_start_change(&self) -> bool {
        self.settings.support_start_change
    }

    fn timeout_cycles(&self) -> u32 {
        self.timeout_cycles
    }

    fn cycle_time(&self) -> f64 {
        *self.settings.cycle_time.get_ref()
    }

    /// On a random changer a prepare of the tool in the spindle raises no
    /// handshake (the tool is in "pocket 0"), as in iov2, but unlike iov2
    /// it replaces an earlier prepare, so that the next change keeps the
    /// tool (LinuxCNC issue 330).
    fn request_prepare(
        &mut self,
        tool: Option<ChangerTool>,
        events: &mut Vec<ToolchangerEvent>,
    ) -> Answer {
        let prepared = Prepared {
            pocket: self.pockets.prep_pocket(tool.as_ref()),
            tool,
        };
        if self.settings.random && self.pockets.holds(prepared.tool.as_ref()) {
            self.prepared = Some(prepared);
            self.operation = None;
            return Answer::AlreadyInSpindle;
        }
        let number = prepared.tool.as_ref().map_or(0, |t| t.number);
        if let Err(pending) = self.protocol.prepare(number, prepared.pocket.unwrap_or(0)) {
            return Answer::AbortPending(pending.0);
        }
        let event = self.tool_event(
            ToolchangerEdge::PrepareRequested,
            self.protocol.state(),
            Some(&prepared),
        );
        self.preparing = Some(prepared);
        self.raised(Handshake::Prepare, event, events)
    }

    fn request_start_change(&mut self, events: &mut Vec<ToolchangerEvent>) -> Answer {
        if !self.settings.support_start_change {
            return Answer::NotSupported;
        }
        if let Err(pending) = self.protocol.start_change() {
            return Answer::AbortPending(pending.0);
        }
        let event = self.tool_event(
            ToolchangerEdge::StartChangeRequested,
            self.protocol.state(),
            self.prepared.as_ref(),
        );
        self.raised(Handshake::StartChange, event, events)
    }

    /// With a fault latched the change is raised even for the tool in the
    /// spindle, so that the fault aborts it (reason 101): a latched fault
    /// never lets a change pass unnoticed.
    fn request_change(&mut self, events: &mut Vec<ToolchangerEvent>) -> Answer {
        if let Some(reason) = self.protocol.pending_abort() {
            return Answer::AbortPending(reason);
        }
        let Some(prepared) = &self.prepared else {
            return Answer::NothingPrepared;
        };
        if self.protocol.fault().is_none() && self.pockets.holds(prepared.tool.as_ref()) {
            // The change uses the prepare up, as a change that moves does.
            self.prepared = None;
            self.operation = None;
            self.protocol.end_start_change();
            return Answer::AlreadyInSpindle;
        }
        if let Err(pending) = self.protocol.change() {
            return Answer::AbortPending(pending.0);
        }
        let event = self.tool_event(
            ToolchangerEdge::ChangeRequested,
            self.protocol.state(),
            self.prepared.as_ref(),
        );
        self.raised(Handshake::Change, event, events)
    }

    fn request_abort(&mut self, reason: AbortReason, events: &mut Vec<ToolchangerEvent>) -> Answer {
        if !self.protocol.abort(reason) {
            return Answer::AbortPending(self.protocol.pending_abort().unwrap_or(reason));
        }
        events.push(self.abort_event(ToolchangerEdge::AbortRaised, reason));
        self.aborted();
        Answer::Raised
    }

    fn withdraw_abort(&mut self) {
        self.protocol.withdraw_abort();
        self.operation = None;
    }

    fn cycle(&mut self, events: &mut Vec<ToolchangerEvent>) -> Status {
        self.cycles = self.cycles.saturating_add(1);
        let before = self.operation;
        let drive = self.device.drive(self.protocol.outputs(), self.cycles);
        if let Some(reason) = drive.abort {
            self.request_abort(reason, events);
        }
        let acked_reason = self.protocol.pending_abort();
        let mut edges = std::mem::take(&mut self.edges);
        edges.clear();
        self.protocol.cycle(&drive.inputs, &mut edges);
        for &(edge, state) in &edges {
            let event = match edge {
                ToolchangerEdge::FaultLatched => ToolchangerEvent {
                    fault_reason: self.protocol.fault().map(|f| f.0),
                    ..self.event(edge, state)
                },
                ToolchangerEdge::AbortAcknowledged => ToolchangerEvent {
                    abort_reason: acked_reason,
                    ..self.event(edge, state)
                },
                ToolchangerEdge::AbortRaised => {
                    let event = ToolchangerEvent {
                        abort_reason: Some(AbortReason::TOOLCHANGER_FAULT),
                        ..self.event(edge, state)
                    };
                    self.aborted();
                    event
                }
                ToolchangerEdge::PrepareAcknowledged => {
                    let event = self.tool_event(edge, state, self.preparing.as_ref());
                    self.prepared = self.preparing.take();
                    event
                }
                ToolchangerEdge::StartChangeAcknowledged | ToolchangerEdge::ChangeAcknowledged => {
                    self.tool_event(edge, state, self.prepared.as_ref())
                }
                ToolchangerEdge::ChangeCommitted => {
                    let event = self.tool_event(edge, state, self.prepared.as_ref());
                    let incoming = self.prepared.take().and_then(|p| p.tool);
                    self.pockets.commit(incoming);
                    event
                }
                _ => self.event(edge, state),
            };
            events.push(event);
        }
        self.edges = edges;
        let status = self.status(before);
        if status == Status::Done {
            self.operation = None;
        }
        status
    }

    /// An injection due at the block's start acts at once: the changer
    /// runs one cycle.
    fn block(&mut self, line: u32, events: &mut Vec<ToolchangerEvent>) {
        if self.device.block(line, self.cycles) {
            self.cycle(events);
        }
    }

    fn state(&self) -> ChangerState {
        self.protocol.state()
    }

    fn fault(&self) -> Option<FaultReason> {
        self.protocol.fault()
    }

    fn pending_abort(&self) -> Option<AbortReason> {
        self.protocol.pending_abort()
    }

    fn prepared(&self) -> Option<&Prepared> {
        self.prepared.as_ref()
    }

    fn tool_in_spindle(&self) -> Option<&ChangerTool> {
        self.pockets.spindle()
    }

    fn pocket_of(&self, number: u32) -> Option<u32> {
        self.pockets.pocket_of(number)
    }

    fn cycles(&self) -> u64 {
        self.cycles
    }
}
