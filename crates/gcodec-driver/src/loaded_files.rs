//! The files of the programs a run has loaded, kept for whoever labels
//! the run's diagnostic events with their lines as the events happen.

use std::fmt;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use gcodec_source::SourceFile;
use rustc_hash::FxHashMap;

/// The source file of each program a run has loaded (the main program
/// and every called one), by the name the run's events give it
/// ([`EventSource::file`](gcodec_exec::event::EventSource::file)): the
/// loader reads each file once and records it here, and a sink labelling
/// the run's diagnostics finds it here while the run goes on. Clones
/// share the files.
#[derive(Clone, Default)]
pub struct LoadedFiles {
    files: Arc<Mutex<FxHashMap<Box<str>, Arc<SourceFile>>>>,
}

impl LoadedFiles {
    /// No files yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// The file the run's events name `name`, if the run has loaded it.
    pub fn get(&self, name: &str) -> Option<Arc<SourceFile>> {
        self.lock().get(name).cloned()
    }

    /// Records `file` under its name, replacing a file of the same name.
    pub(crate) fn insert(&self, file: Arc<SourceFile>) {
        self.lock().insert(file.name().into(), file);
    }

    fn lock(&self) -> MutexGuard<'_, FxHashMap<Box<str>, Arc<SourceFile>>> {
        // The map is whole between calls, so a panic on another thread
        // while it held the lock leaves nothing half done.
        self.files.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl fmt::Debug for LoadedFiles {
    // The names only: the files' text would drown everything else.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_set().entries(self.lock().keys()).finish()
    }
}
