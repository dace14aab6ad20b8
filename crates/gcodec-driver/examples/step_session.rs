//! An application that embeds gcodec and has a machine of its own: it
//! steps a run by hand, answers a pending tool change late, and cancels a
//! second run in the middle of a change (SPEC §11.10, §12).
//!
//! The machine here is a cell controller that owns a simulated
//! toolchanger and drives it one cycle at a time when it likes, as an HMI
//! or a simulator would: a tool change starts the changer and answers
//! "pending"; the application cycles the changer and resumes the run when
//! the change is acknowledged.
//!
//! `cargo run -p gcodec-driver --example step_session`

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;

use gcodec_driver::event::{Event, EventKind, EventQueue};
use gcodec_driver::machine::{
    AbortCause, Answer, ChangeResult, Machine, MachineEvents, Outcome, PendingToken, ToolRequest,
};
use gcodec_driver::session::{Session, Step};
use gcodec_driver::toolchanger::{
    self, AbortReason, ChangerTool, SimulatedChanger, Status, Toolchanger, ToolchangerEvent,
};
use gcodec_driver::{Channel, Definitions, MemoryLoader, ProgramKind, RunOptions, compile_text};

const PROFILE: &str = r#"
[machine]
name = "cell with a toolchanger"
control = "840d_sl"

[toolchanger]
cycle_time = 0.05

[[tools]]
number = 1
location = 1
edges = [{ d = 1, length = 40.0 }]

[[tools]]
number = 2
location = 2
edges = [{ d = 1, length = 55.0 }]
"#;

const PROGRAM: &str = "N10 T1 M6\nN20 D1 G0 X10 Z5\nN30 T2 M6\nN40 G1 Z-2 F300\nN50 M30\n";

/// The changer the application and its machine share.
type SharedChanger = Rc<RefCell<SimulatedChanger>>;

/// The application's machine: prepares at once, starts a change and
/// leaves it to the application to finish.
struct CellMachine {
    changer: SharedChanger,
    /// The changer's edges not yet handed to the run.
    edges: Rc<RefCell<Vec<ToolchangerEvent>>>,
    tokens: u64,
}

impl CellMachine {
    fn hand_over(&self, events: &mut MachineEvents) {
        events.extend(
            self.edges
                .borrow_mut()
                .drain(..)
                .map(EventKind::Toolchanger),
        );
    }
}

impl Machine for CellMachine {
    fn prepare_tool(
        &mut self,
        request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<()> {
        let tool = request.tool.map(|label| ChangerTool {
            number: request.number,
            label: label.to_owned(),
        });
        let mut changer = self.changer.borrow_mut();
        toolchanger::prepare(&mut *changer, tool, &mut self.edges.borrow_mut());
        drop(changer);
        self.hand_over(events);
        Answer::Ready(())
    }

    fn change_tool(
        &mut self,
        _request: &ToolRequest<'_>,
        events: &mut MachineEvents,
    ) -> Answer<ChangeResult> {
        let mut changer = self.changer.borrow_mut();
        let mut edges = self.edges.borrow_mut();
        changer.request_change(&mut edges);
        changer.cycle(&mut edges);
        drop((changer, edges));
        self.hand_over(events);
        self.tokens += 1;
        Answer::Pending(PendingToken(self.tokens))
    }

    fn resumed(&mut self, _token: PendingToken, events: &mut MachineEvents) {
        self.hand_over(events);
    }

    fn abort(&mut self, cause: AbortCause, events: &mut MachineEvents) {
        let reason = match cause {
            AbortCause::Cancelled => AbortReason::USER_ABORT,
            AbortCause::Alarm => AbortReason::TASK_EXEC_ERROR,
        };
        let mut changer = self.changer.borrow_mut();
        toolchanger::abort(&mut *changer, reason, &mut self.edges.borrow_mut());
        drop(changer);
        self.hand_over(events);
    }
}

fn show(events: Vec<Event>) {
    for event in events {
        let line = event.source.line;
        match &event.kind {
            EventKind::ToolChange(c) => println!(
                "  line {line}: tool change {} -> {} (committed: {})",
                c.previous_tool.as_deref().unwrap_or("none"),
                c.new_tool.as_deref().unwrap_or("none"),
                c.committed
            ),
            EventKind::Toolchanger(t) => println!(
                "  line {line}: toolchanger {:?} -> {} at cycle {}{}",
                t.edge,
                t.state.name(),
                t.cycle,
                t.abort_reason
                    .map(|r| format!(" (abort reason {r})"))
                    .unwrap_or_default()
            ),
            EventKind::Diagnostic(d) => println!("  line {line}: {} {}", d.code, d.message),
            EventKind::ProgramEnd(end) => println!("  line {line}: program end {:?}", end.reason),
            _ => {}
        }
    }
}

/// Runs the program, answering each change after the changer has worked
/// through it; with `cancel_second`, the second change is cancelled
/// half-way instead.
fn run(cancel_second: bool) {
    let profile = Arc::new(gcodec_profile::load(PROFILE).expect("the cell's profile"));
    let compiled = compile_text(
        "CELL.MPF",
        PROGRAM,
        ProgramKind::Main,
        &profile,
        &Definitions::new(),
    );
    assert!(!compiled.has_errors(), "{:?}", compiled.diagnostics);
    let main = compiled.into_loaded("CELL").program;
    let scenario = gcodec_profile::load_scenario("ack_cycles = 4").expect("a scenario");
    let changer = Rc::new(RefCell::new(
        SimulatedChanger::new(&profile, &scenario).expect("the changer"),
    ));
    let edges = Rc::new(RefCell::new(Vec::new()));
    let machine = CellMachine {
        changer: Rc::clone(&changer),
        edges: Rc::clone(&edges),
        tokens: 0,
    };
    let queue = EventQueue::new();
    let mut loader = MemoryLoader::new(Arc::clone(&profile), Definitions::new());
    let options = RunOptions::for_profile(&profile);
    let channel = Channel::new(Arc::clone(&profile), options, &mut loader, queue.clone())
        .with_machine(machine);
    let mut session = Session::new(channel, main);
    let mut changes = 0;
    loop {
        match session.step() {
            Step::Events => show(queue.take()),
            Step::Pending(pending) => {
                show(queue.take());
                changes += 1;
                println!(
                    "  pending at line {}: {:?}",
                    pending.source.line, pending.action
                );
                if cancel_second && changes == 2 {
                    println!("  the operator cancels the run");
                    session.cancel();
                    continue;
                }
                // The application's own loop: cycle the changer until it
                // has acknowledged the change.
                let mut result = ChangeResult::COMMITTED;
                loop {
                    let status = changer.borrow_mut().cycle(&mut edges.borrow_mut());
                    match status {
                        Status::Busy => {}
                        Status::Done => break,
                        Status::Failed => {
                            result.committed = false;
                            break;
                        }
                    }
                }
                session
                    .resume(pending.token, Outcome::ToolChanged(result))
                    .expect("the answer fits the action");
            }
            Step::Ended(outcome) => {
                show(queue.take());
                let outcome = outcome.expect("events kept");
                let fault = changer.borrow().fault();
                println!(
                    "  ended: {:?}, {} blocks, toolchanger {} with fault {fault:?}",
                    outcome.reason,
                    outcome.summary.blocks,
                    changer.borrow().state().name()
                );
                break;
            }
        }
    }
}

fn main() {
    println!("A run whose tool changes are answered late:");
    run(false);
    println!("A run cancelled in the middle of its second change:");
    run(true);
}
