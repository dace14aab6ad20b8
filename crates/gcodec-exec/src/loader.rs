//! The interface through which the channel gets the programs a running
//! program calls (subprograms and cycles).
//!
//! The channel asks a [`ProgramLoader`] for a program by the name in the
//! AIL `call` (`CYCLE81`, `L100`, a `PCALL`/`CALL` path) and gets it lowered
//! and shared ([`Loaded`]), or a [`LoadError`] it turns into an alarm.
//! Finding, reading, parsing and lowering programs is the compiler's job:
//! `gcodec-driver` implements this trait for files on a search path and
//! for programs given as text.

use std::borrow::Cow;
use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use gcodec_source::{Code, Severity};

use crate::event::{DiagnosticEvent, Event};
use crate::program::Program;

// ---------------------------------------------------------------------------
// The loader interface

/// Loads called programs by name.
pub trait ProgramLoader {
    /// The program `request` names, lowered; the same `Arc` for every
    /// later request of the same program.
    fn load(&mut self, request: &LoadRequest<'_>) -> Result<Loaded, LoadError>;

    /// Whether [`ProgramLoader::load`] would find the program `request`
    /// names (`ISFILE`), without loading it; `None` where the loader
    /// cannot tell (the default) or `request` names no program.
    fn exists(&self, _request: &LoadRequest<'_>) -> Option<bool> {
        None
    }
}

impl<T: ProgramLoader + ?Sized> ProgramLoader for &mut T {
    fn load(&mut self, request: &LoadRequest<'_>) -> Result<Loaded, LoadError> {
        (**self).load(request)
    }

    fn exists(&self, request: &LoadRequest<'_>) -> Option<bool> {
        (**self).exists(request)
    }
}

impl<T: ProgramLoader + ?Sized> ProgramLoader for Box<T> {
    fn load(&mut self, request: &LoadRequest<'_>) -> Result<Loaded, LoadError> {
        (**self).load(request)
    }

    fn exists(&self, request: &LoadRequest<'_>) -> Option<bool> {
        (**self).exists(request)
    }
}

/// What the channel asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoadRequest<'a> {
    /// As in the AIL `call`: the name in upper case (`CYCLE81`, `L100`),
    /// for `PCALL` and a computed `CALL` a path (`/_N_SPF_DIR/_N_SUB_SPF`)
    /// or name. Any text; one that cannot name a program is not found.
    pub name: &'a str,
    /// `PCALL`: `name` is a path in the control's file system. It is
    /// looked up by its last component either way; this only words the
    /// error.
    pub by_path: bool,
    /// `EXTCALL`: looked for in the external program path first.
    pub external: bool,
    /// The file of the calling program ([`Program::file`]): its directory
    /// is searched first.
    pub caller_file: &'a str,
}

/// A program found and lowered.
#[derive(Clone, Debug)]
pub struct Loaded {
    pub program: Arc<Program>,
    /// The diagnostics of reading, parsing and lowering it, as diagnostic
    /// events in source order with `file`, `line` and `col` set (line 1,
    /// column 1 for one without a place; `level` 0: the channel sets it).
    /// Only the first time the program is loaded; empty afterwards.
    pub diagnostics: Vec<Event>,
    /// Whether any diagnostic of the program is an error; the same on
    /// every load.
    pub has_errors: bool,
}

/// Why a program could not be loaded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LoadError {
    /// [`codes::run::PROGRAM_NOT_FOUND`](gcodec_source::codes::run::PROGRAM_NOT_FOUND),
    /// [`codes::run::PROGRAM_UNREADABLE`](gcodec_source::codes::run::PROGRAM_UNREADABLE),
    /// or the `io` code of a file that is not read (a link outside the
    /// search path, a FIFO or a device, a file too large, UTF-16 text).
    pub code: &'static Code,
    /// One sentence naming the program and, when not found, every
    /// directory searched.
    pub message: String,
    /// The directories searched, in order (for a file that cannot be read:
    /// up to the one holding it), including those that do not exist.
    pub searched: Vec<PathBuf>,
    /// How to fix it.
    pub help: Option<String>,
}

impl LoadError {
    /// As a diagnostic event's payload (an error; no alarm number: the
    /// channel sets it).
    pub fn to_diagnostic(&self) -> DiagnosticEvent {
        DiagnosticEvent {
            code: self.code,
            severity: Severity::Error,
            message: Cow::Owned(self.message.clone()),
            alarm: None,
            help: self.help.clone().map(Cow::Owned),
        }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for LoadError {}
