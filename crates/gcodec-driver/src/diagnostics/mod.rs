//! Diagnostics as the commands hand them on: a run's events as
//! diagnostics and a program's diagnostics as events ([`runtime_diagnostic`]),
//! the diagnostics of one file together ([`FileReport`]), and each one as
//! data ([`DiagnosticRecord`], the objects of every command's
//! `--output-format json`, whose schema is `docs/schema/check.schema.json`).

mod events;
mod record;

use std::sync::Arc;

use gcodec_source::{Diagnostic, Diagnostics, SourceFile};

pub(crate) use events::diagnostic_event;
pub use events::runtime_diagnostic;
pub use record::{DiagnosticRecord, LabelRecord, Position, check_json_schema};

/// One file's diagnostics: what `check` found in it, or what `lower`
/// or `run` reported against it.
#[derive(Debug)]
pub struct FileReport {
    /// The file's name as shown: its path as walked or given.
    pub name: String,
    /// Its text, where it could be read.
    pub file: Option<Arc<SourceFile>>,
    /// Its diagnostics, in source order, at the levels in force.
    pub diagnostics: Diagnostics,
}

impl FileReport {
    pub fn new(name: String, file: Option<SourceFile>, diagnostics: Vec<Diagnostic>) -> Self {
        let mut kept = Diagnostics::new();
        kept.extend(diagnostics);
        Self {
            name,
            file: file.map(Arc::new),
            diagnostics: kept,
        }
    }
}
