//! Running tool-change programs: a main program with its subprograms in
//! memory, on a profile, with the channel's own tool resolver or one a
//! test supplies; and what the tool tests read from the events.

use std::sync::Arc;

use gcodec_driver::{Definitions, MemoryLoader};
use gcodec_exec::channel::{Channel, RunOptions};
use gcodec_exec::event::{Event, EventKind, ProgramEndReason, ToolChangeEvent, VecSink};
use gcodec_exec::tool_resolution::ToolResolver;
use gcodec_profile::Profile;
use gcodec_source::{Severity, SourceFile};

use super::runs::compile_main;

/// The main program's file name in the events.
pub const MAIN: &str = "TOOLS.MPF";

/// The events of `main` (which must compile cleanly) with the
/// subprograms `subprograms` (file name, text) on `profile`, tools
/// resolved by `resolver` (the profile's tool table without one).
pub fn run_tools(
    profile: &Profile,
    main: &str,
    subprograms: &[(&str, &str)],
    resolver: Option<Box<dyn ToolResolver>>,
) -> Vec<Event> {
    let profile = Arc::new(profile.clone());
    let definitions = Arc::new(Definitions::new());
    let file = Arc::new(SourceFile::new(MAIN, main));
    let compiled = compile_main(&file, &profile, &definitions);
    assert!(!compiled.has_errors, "{main}: {:#?}", compiled.diagnostics);
    let mut loader = MemoryLoader::new(Arc::clone(&profile), definitions);
    for (name, text) in subprograms {
        loader.insert(name, *text);
    }
    let mut sink = VecSink::new();
    let options = RunOptions::for_profile(&profile);
    let channel = Channel::new(profile, options, &mut loader, &mut sink);
    let channel = match resolver {
        Some(resolver) => channel.with_tool_resolver(resolver),
        None => channel,
    };
    channel.run(compiled.program).expect("events go to memory");
    sink.events
}

/// The run's diagnostics of `severity` (code, line) and how it ended.
pub fn diagnostics(
    events: &[Event],
    severity: Severity,
) -> (Vec<(&'static str, u32)>, ProgramEndReason) {
    let mut found = Vec::new();
    let mut end = None;
    for event in events {
        match &event.kind {
            EventKind::Diagnostic(d) if d.severity == severity => {
                found.push((d.code.name(), event.source.line))
            }
            EventKind::ProgramEnd(e) => end = Some(e.reason),
            _ => {}
        }
    }
    (found, end.expect("the program ends"))
}

/// Asserts that the run ended with `M30` and no error (a failed check of
/// [`expect`] is a `SETAL` error at its line).
pub fn assert_clean(events: &[Event], what: &str) {
    assert_eq!(
        diagnostics(events, Severity::Error),
        (vec![], ProgramEndReason::M30),
        "{what}"
    );
}

/// Program lines that raise an alarm unless `variable` is `value` when
/// they run.
pub fn expect(variable: &str, value: f64) -> String {
    format!("IF {variable}<>{value}\nSETAL(65000)\nENDIF\n")
}

/// The `tool_change` events of a run.
pub fn changes(events: &[Event]) -> Vec<&ToolChangeEvent> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::ToolChange(c) => Some(c),
            _ => None,
        })
        .collect()
}

/// The events as JSON lines, as `gcodec run --format jsonl` writes them.
pub fn jsonl(events: &[Event]) -> String {
    events
        .iter()
        .map(|e| serde_json::to_string(e).expect("an event is JSON") + "\n")
        .collect()
}
