//! Running small programs into a [`PlotSink`], and hand-built events.

#![allow(dead_code)]

use std::sync::Arc;

use gcodec_driver::event::{
    AxisMap, Event, EventKind, EventSource, InsertedElement, MotionEvent, MotionKind, Plane,
    ToolCentre, ToolChangeEvent, ToolChangeTrigger, WorkOffsetContext,
};
use gcodec_driver::event::{SelectionSource, VecSink};
use gcodec_driver::{RunSetup, run_main};
use gcodec_plot::{Plot, PlotSink, View};
use gcodec_source::SourceFile;

/// Runs `text` (a main program named `name`) on the built-in profile
/// into a plot sink seeing `view`; the run must end cleanly.
pub fn plot_program(name: &str, text: &str, view: Option<View>) -> Plot {
    let events = run(name, text);
    let mut sink = PlotSink::new(view);
    for event in &events {
        sink.plot(event);
    }
    sink.into_plot()
}

/// The events of `text` run on the built-in profile; the run must end
/// cleanly.
pub fn run(name: &str, text: &str) -> Vec<Event> {
    run_on(gcodec_testkit::profile("default.toml"), name, text)
}

/// The events of `text` run on `profile`; the run must end cleanly.
pub fn run_on(profile: gcodec_profile::Profile, name: &str, text: &str) -> Vec<Event> {
    let setup = RunSetup::new(profile);
    let mut sink = VecSink::default();
    let report = run_main(
        Arc::new(SourceFile::new(name, text.as_bytes())),
        &setup,
        &mut sink,
        None,
    );
    assert!(
        report.diagnostics.is_empty(),
        "{name}: {:?}",
        report.diagnostics
    );
    let outcome = report.outcome.expect("no output error");
    assert_eq!(outcome.errors, 0, "{name}: {:?}", sink.events);
    sink.events
}

/// An axis map of X, Y, Z.
pub fn xyz(x: f64, y: f64, z: f64) -> AxisMap {
    AxisMap::from([("X", x), ("Y", y), ("Z", z)])
}

fn source(line: u32) -> EventSource {
    EventSource {
        file: Arc::from("compensated.mpf"),
        line,
        col: 1,
        level: 0,
    }
}

/// A motion event in `G17` at `G94 F500` (`null` for a rapid).
pub fn motion(motion: MotionKind, from: AxisMap, to: AxisMap) -> MotionEvent {
    MotionEvent {
        motion,
        to_machine: to.clone(),
        from,
        to,
        centre: None,
        radius: None,
        turns: 0,
        feed: (motion != MotionKind::Rapid).then_some(500.0),
        feed_mode: "G94".into(),
        plane: Plane::G17,
        work_offset: WorkOffsetContext::default(),
        inserted: None,
        tool: None,
    }
}

/// The event of `motion` at `line`.
pub fn event(line: u32, motion: MotionEvent) -> Event {
    Event {
        kind: EventKind::Motion(motion),
        source: source(line),
    }
}

/// `motion` with the tool centre going to `tool_to` (compensation on).
pub fn compensated(mut motion: MotionEvent, tool_to: AxisMap, radius: f64) -> MotionEvent {
    motion.tool = Some(Box::new(ToolCentre {
        tool_to_machine: tool_to.clone(),
        tool_to,
        tool_radius: radius,
        tool_arc: None,
    }));
    motion
}

/// `motion` as an element the control inserted.
pub fn inserted(mut motion: MotionEvent, element: InsertedElement) -> MotionEvent {
    motion.inserted = Some(element);
    motion
}

/// `motion` as an arc about `centre` (X, Y).
pub fn about(mut motion: MotionEvent, x: f64, y: f64, radius: f64) -> MotionEvent {
    motion.centre = Some(AxisMap::from([("X", x), ("Y", y)]));
    motion.radius = Some(radius);
    motion
}

/// A committed tool change to `tool`.
pub fn tool_change(line: u32, tool: &str) -> Event {
    Event {
        kind: EventKind::ToolChange(ToolChangeEvent {
            previous_tool: None,
            new_tool: Some(tool.to_owned()),
            selection_source: SelectionSource::PendingThenM6,
            substituted: false,
            trigger: ToolChangeTrigger::M6,
            committed: true,
            fault_reason: None,
        }),
        source: source(line),
    }
}
