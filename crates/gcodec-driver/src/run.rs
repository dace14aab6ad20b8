//! Running a main program as `gcodec run` does: streamed, with its calls
//! found on the search path, against one machine profile.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_exec::channel::{BlockObserver, Channel, RunOptions, RunOutcome};
use gcodec_exec::event::EventSink;
use gcodec_exec::machine::SimulatedMachine;
use gcodec_exec::program::Program;
use gcodec_exec::toolchanger::SimulatedChanger;
use gcodec_exec::vars::Global;
use gcodec_profile::Profile;
use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{Diagnostics, SourceFile, TextEncoding};

use crate::loaded_files::LoadedFiles;
use crate::loader::{FileLoader, SearchPath, program_name};
use crate::stream::{StreamOptions, run_streamed};

/// What a run is set up with.
#[derive(Clone, Debug)]
pub struct RunSetup {
    pub profile: Arc<Profile>,
    /// The profile's file: its relative `subprogram_paths` are taken
    /// against its directory (`None`: the built-in profile, against the
    /// current directory).
    pub profile_file: Option<PathBuf>,
    pub definitions: Arc<Definitions>,
    /// Directories searched for called programs after the caller's and
    /// the profile's (`--subprogram-path`).
    pub search_dirs: Vec<PathBuf>,
    pub options: RunOptions,
    pub stream: StreamOptions,
    /// Where the run records the file of each program it loads, the main
    /// program's first: a sink labelling the run's diagnostic events as
    /// they happen finds them there (a clone of it shares the files).
    pub loaded_files: LoadedFiles,
    /// How called programs are decoded: the profile's code page, or one
    /// encoding for every file (`--encoding`). The main program and the
    /// definition files are decoded when they are read
    /// ([`crate::read_source`]).
    pub encoding: TextEncoding,
    /// The simulated toolchanger the run starts with
    /// ([`crate::load_toolchanger`], `--toolchanger`); `None`: the
    /// profile's, if it has a `[toolchanger]` table.
    pub toolchanger: Option<SimulatedChanger>,
}

impl RunSetup {
    /// The defaults for a machine ([`RunOptions::for_profile`]), no
    /// definitions, no further directories.
    pub fn new(profile: impl Into<Arc<Profile>>) -> Self {
        let profile = profile.into();
        Self {
            options: RunOptions::for_profile(&profile),
            encoding: profile.program.text_encoding(),
            profile,
            profile_file: None,
            definitions: Arc::new(Definitions::new()),
            search_dirs: Vec::new(),
            stream: StreamOptions::default(),
            loaded_files: LoadedFiles::new(),
            toolchanger: None,
        }
    }
}

/// What a run gives back besides its events.
#[derive(Debug)]
pub struct RunReport {
    /// How the run ended, or the error that stopped writing its events.
    pub outcome: io::Result<RunOutcome>,
    /// All the main program's own diagnostics (parse, structure, outline,
    /// lowering), in source order, as many as are kept; those of the
    /// run and of called programs are events.
    pub diagnostics: Diagnostics,
}

/// Runs the main program in `file` streamed (its name is the one its
/// file gives, [`program_name`]): events go to `sink`, the state after
/// each block to `observer`.
pub fn run_main(
    file: Arc<SourceFile>,
    setup: &RunSetup,
    sink: &mut dyn EventSink,
    observer: Option<&mut dyn BlockObserver>,
) -> RunReport {
    setup.loaded_files.insert(Arc::clone(&file));
    let name = program_name(Path::new(file.name()));
    let kind = ProgramKind::of_file(file.name());
    let (outcome, diagnostics) = run_streamed(
        &file,
        name,
        kind,
        &setup.profile,
        &setup.definitions,
        setup.stream,
        |main| run_program(main, setup, sink, observer),
    );
    RunReport {
        outcome,
        diagnostics,
    }
}

/// Runs `main` (lowered already, or streamed by [`run_main`]) on the
/// machine `setup` describes, its calls found on the search path: events
/// go to `sink`, the state after each block to `observer`. The main
/// program's file is recorded in `setup.loaded_files` by the caller.
pub fn run_program(
    main: Arc<Program>,
    setup: &RunSetup,
    sink: &mut dyn EventSink,
    observer: Option<&mut dyn BlockObserver>,
) -> io::Result<RunOutcome> {
    let search = SearchPath::new()
        .with_profile(&setup.profile, setup.profile_file.as_deref())
        .with_dirs(setup.search_dirs.iter().cloned());
    let mut loader = FileLoader::new(
        search,
        Arc::clone(&setup.profile),
        Arc::clone(&setup.definitions),
    )
    .with_loaded_files(setup.loaded_files.clone())
    .with_encoding(setup.encoding);
    let globals = globals(&setup.definitions);
    let mut channel = Channel::new(
        Arc::clone(&setup.profile),
        setup.options.clone(),
        &mut loader,
        sink,
    )
    .with_globals(&globals);
    if let Some(changer) = &setup.toolchanger {
        let changer = Box::new(changer.clone());
        channel = channel.with_machine(SimulatedMachine::with_changer(Some(changer)));
    }
    if let Some(observer) = observer {
        channel = channel.with_observer(observer);
    }
    channel.run(main)
}

/// The global user data of `definitions` as the channel declares it, in
/// the order of their files' names and their lines (the order in which
/// they take the memory for variables). A variable whose type or
/// dimensions are not constants the channel can hold is left out
/// (reading it is an error naming it).
pub fn globals(definitions: &Definitions) -> Vec<Global> {
    let mut globals: Vec<Global> = definitions
        .variables()
        .filter_map(|variable| {
            let data_type = Some(variable.data_type).filter(|ty| ty.is_declarable())?;
            let dims = variable
                .dims
                .iter()
                .map(|d| d.map(|d| d as usize))
                .collect::<Option<Vec<usize>>>()?;
            Some(Global {
                name: variable.name.to_ascii_uppercase(),
                data_type,
                dims,
                file: Arc::from(variable.file.as_str()),
                line: variable.line,
                col: variable.col,
            })
        })
        .collect();
    globals.sort_by(|a, b| (&a.file, a.line, a.col).cmp(&(&b.file, b.line, b.col)));
    globals
}
