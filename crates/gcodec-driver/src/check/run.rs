//! `gcodec check --run`: a main program that lowered without errors is
//! also run, as `gcodec run` runs it, on its machine's profile (and the
//! profile's simulated toolchanger), its calls found in its own folder,
//! the profile's `subprogram_paths` and the configuration's
//! `search_paths`, under a step limit. Of the run's events only the
//! diagnostics are kept, each once per file, code and place, as they
//! come: an endless loop's warnings do not pile up.

use std::collections::HashSet;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_ail::Document;
use gcodec_exec::event::{Event, EventKind, EventSink};
use gcodec_exec::program::Program;
use gcodec_source::{Code, Diagnostic, SourceFile};

use super::machines::Machine;
use crate::{LoadedFiles, RunSetup, StreamOptions, program_name, run_program, runtime_diagnostic};

/// How `--run` runs the main programs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunChecks {
    /// Blocks a run may execute before it is stopped with
    /// `gcodec::run::step_limit` (`--max-steps`).
    pub max_steps: u64,
}

impl Default for RunChecks {
    /// The limit `gcodec run` has.
    fn default() -> Self {
        Self {
            max_steps: 10_000_000,
        }
    }
}

/// A diagnostic of a run, with the file it is in: the main program's or
/// a called program's.
#[derive(Debug)]
pub(super) struct RunFinding {
    /// The file's name as the run gave it.
    pub name: Arc<str>,
    /// Its text, where the run loaded it.
    pub file: Option<Arc<SourceFile>>,
    pub diagnostic: Diagnostic,
}

/// Runs the main program of `file`, lowered into `document`, on
/// `machine`; returns the run's diagnostics.
pub(super) fn run(
    file: &Arc<SourceFile>,
    document: Document,
    machine: &Machine,
    search_paths: &[PathBuf],
    checks: RunChecks,
) -> Vec<RunFinding> {
    let mut setup = RunSetup::new(Arc::clone(&machine.profile));
    setup.profile_file.clone_from(&machine.profile_file);
    setup.definitions = Arc::clone(&machine.definitions);
    setup.search_dirs = search_paths.to_vec();
    setup.options.max_steps = checks.max_steps;
    // Files are run in parallel already.
    setup.stream = StreamOptions {
        workers: 1,
        ..StreamOptions::default()
    };
    setup.loaded_files.insert(Arc::clone(file));
    let name = program_name(Path::new(file.name()));
    let program = Arc::new(Program::new(name, Arc::clone(file), document));
    let mut sink = DiagnosticsOnly::new(setup.loaded_files.clone());
    // The sink never fails, and how the run ended is in its diagnostics
    // (an alarm, `run::step_limit`).
    let _ = run_program(program, &setup, &mut sink, None);
    sink.found
}

/// Keeps the diagnostic events of a run, each once, and drops every
/// other event.
struct DiagnosticsOnly {
    files: LoadedFiles,
    /// File, code and line and column of the ones kept.
    seen: HashSet<(Arc<str>, &'static Code, u32, u32)>,
    found: Vec<RunFinding>,
}

impl DiagnosticsOnly {
    fn new(files: LoadedFiles) -> Self {
        Self {
            files,
            seen: HashSet::new(),
            found: Vec::new(),
        }
    }
}

impl EventSink for DiagnosticsOnly {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        let EventKind::Diagnostic(d) = &event.kind else {
            return Ok(());
        };
        let source = &event.source;
        let key = (Arc::clone(&source.file), d.code, source.line, source.col);
        if self.seen.insert(key) {
            let file = self.files.get(&source.file);
            self.found.push(RunFinding {
                name: Arc::clone(&source.file),
                diagnostic: runtime_diagnostic(d, source, file.as_deref()),
                file,
            });
        }
        Ok(())
    }

    /// Only diagnostics are kept: the executor need not build motions.
    fn takes_motions(&self) -> bool {
        false
    }
}
