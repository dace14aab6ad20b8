//! The run set-up the tests repeat: compile a main program, run it on a
//! channel with a file loader. Thin, so that the pipeline's facade can
//! take its place.

use std::path::Path;
use std::sync::Arc;

use gcodec_driver::{Definitions, FileLoader, ProgramKind, SearchPath, compile, program_name};
use gcodec_exec::channel::{BlockObserver, Channel, RunOptions, RunOutcome};
use gcodec_exec::event::{Event, EventSink, VecSink};
use gcodec_exec::loader::Loaded;
use gcodec_exec::program::Program;
use gcodec_profile::Profile;
use gcodec_source::SourceFile;

/// Compiles the main program in `file` as `gcodec run` does, named as
/// callers name its file.
pub fn compile_main(
    file: &Arc<SourceFile>,
    profile: &Profile,
    definitions: &Definitions,
) -> Loaded {
    let name = program_name(Path::new(file.name()));
    let kind = ProgramKind::of_file(file.name());
    compile(Arc::clone(file), kind, profile, definitions).into_loaded(name)
}

/// The events of the main program `program`, given as the text of the
/// file `name`, run on `profile` as `gcodec run` runs it; panics when it
/// does not compile cleanly.
pub fn events_of_text(profile: Profile, name: &str, program: &str) -> Vec<Event> {
    events_of_text_with(&gcodec_driver::RunSetup::new(profile), name, program)
}

/// [`events_of_text`] with the run set up as `setup` says (search
/// directories, options).
pub fn events_of_text_with(
    setup: &gcodec_driver::RunSetup,
    name: &str,
    program: &str,
) -> Vec<Event> {
    let file = Arc::new(SourceFile::new(name, program));
    let mut sink = VecSink::new();
    let report = gcodec_driver::run_main(file, setup, &mut sink, None);
    assert!(
        !report.diagnostics.iter().any(|d| d.is_error()),
        "{program}: {:?}",
        report.diagnostics
    );
    sink.events
}

/// What a run is given besides its main program.
pub struct RunSetup {
    pub profile: Arc<Profile>,
    pub options: RunOptions,
    /// Their global variables are declared before the run.
    pub definitions: Arc<Definitions>,
    /// Searched after the caller's directory, as `--subprogram-path`.
    pub search: SearchPath,
}

/// Runs `main` with its events to `sink` (and its blocks to `observer`),
/// called programs loaded from files as `gcodec run` loads them.
pub fn run_main(
    main: Arc<Program>,
    setup: RunSetup,
    sink: &mut dyn EventSink,
    observer: Option<&mut dyn BlockObserver>,
) -> RunOutcome {
    let RunSetup {
        profile,
        options,
        definitions,
        search,
    } = setup;
    let mut loader = FileLoader::new(search, Arc::clone(&profile), Arc::clone(&definitions));
    let globals = gcodec_driver::globals(&definitions);
    let channel = Channel::new(profile, options, &mut loader, sink).with_globals(&globals);
    match observer {
        Some(observer) => channel.with_observer(observer).run(main),
        None => channel.run(main),
    }
    .expect("events go to memory")
}

/// The codes of the diagnostic events, in order.
pub fn diagnostic_codes(events: &[Event]) -> Vec<String> {
    events
        .iter()
        .filter_map(|e| match &e.kind {
            gcodec_exec::event::EventKind::Diagnostic(d) => Some(d.code.to_string()),
            _ => None,
        })
        .collect()
}

/// Runs `main` on `profile` against `machine` in a session that `drive`
/// steps (programs it calls come from nowhere); the run's events.
pub fn in_session<M: gcodec_exec::machine::Machine>(
    profile: &Arc<Profile>,
    main: Arc<Program>,
    machine: M,
    drive: impl FnOnce(&mut gcodec_exec::session::Session<'_>),
) -> Vec<Event> {
    let mut loader = gcodec_driver::MemoryLoader::new(Arc::clone(profile), Definitions::new());
    let mut sink = VecSink::new();
    let options = RunOptions::for_profile(profile);
    let channel =
        Channel::new(Arc::clone(profile), options, &mut loader, &mut sink).with_machine(machine);
    let mut session = gcodec_exec::session::Session::new(channel, main);
    drive(&mut session);
    drop(session);
    sink.events
}

/// Runs `main` on `profile` against `machine` to its end (`Channel::run`:
/// nothing answers a pending action); the outcome and the events.
pub fn run_against<M: gcodec_exec::machine::Machine>(
    profile: &Arc<Profile>,
    main: Arc<Program>,
    machine: M,
) -> (RunOutcome, Vec<Event>) {
    let mut loader = gcodec_driver::MemoryLoader::new(Arc::clone(profile), Definitions::new());
    let mut sink = VecSink::new();
    let options = RunOptions::for_profile(profile);
    let outcome = Channel::new(Arc::clone(profile), options, &mut loader, &mut sink)
        .with_machine(machine)
        .run(main)
        .expect("events written");
    (outcome, sink.events)
}
