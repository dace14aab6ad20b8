//! `gcodec check`: every program and definition file of a tree parsed
//! and lowered against the profile and definition files its
//! configuration (`gcodec.toml`) assigns, in parallel, the diagnostics
//! at the rule levels in force, as data.
//!
//! - [`CheckConfig`]: `gcodec.toml`, found upward from the paths checked
//!   ([`find_config`]) or named.
//! - [`Selector`], [`RuleLevel`], [`Selection`]: which diagnostics are
//!   reported, at which level.
//! - [`check`]: the files of [`Input`]s checked; a [`CheckReport`] of
//!   [`FileReport`]s sorted by name.
//! - [`DiagnosticRecord`]: one diagnostic as data (`--output-format
//!   json`, `docs/schema/check.schema.json`).

mod config;
mod levels;
mod machines;
mod record;
mod report;
mod selector;
mod suppress;
mod walk;

use std::path::Path;
use std::sync::Arc;

use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{Diagnostics, SourceFile};
use rayon::prelude::*;

pub use config::{CONFIG_NAME, CheckConfig, find_config};
pub use levels::{RuleLevel, Selection};
pub use record::{DiagnosticRecord, LabelRecord, check_json_schema};
pub use report::{CheckReport, Counts, FileReport};
pub use selector::Selector;
pub use walk::Input;

use levels::Levels;
use machines::{Machine, Machines};
use walk::{Found, Source};

/// A check that could not start: a path named that does not exist, a
/// profile or definition file the configuration assigns that cannot be
/// used. Every problem, each against its file.
#[derive(Debug)]
pub struct SetupError {
    pub reports: Vec<FileReport>,
}

/// What a long check tells as it goes (a progress bar): called from the
/// threads that check the files.
pub trait Progress: Sync {
    /// The files are found: this many will be checked.
    fn files_found(&self, _files: usize) {}

    /// One more file is checked.
    fn file_checked(&self) {}
}

/// A check that tells nothing as it goes.
pub struct Quiet;

impl Progress for Quiet {}

/// Checks the files of `inputs` as `config` says, at the levels of its
/// rules and `selection`.
pub fn check(
    config: &CheckConfig,
    inputs: Vec<Input>,
    selection: &Selection,
) -> Result<CheckReport, SetupError> {
    check_with_progress(config, inputs, selection, &Quiet)
}

/// [`check`], telling `progress` as files are found and checked.
pub fn check_with_progress(
    config: &CheckConfig,
    inputs: Vec<Input>,
    selection: &Selection,
    progress: &dyn Progress,
) -> Result<CheckReport, SetupError> {
    let found = walk::files(config, inputs).map_err(|d| SetupError {
        reports: vec![FileReport::new(String::new(), None, vec![d])],
    })?;
    let builtin = crate::load_profile(&crate::builtin_profile_file())
        .map(|(profile, _)| profile)
        .map_err(|e| SetupError {
            reports: vec![FileReport::new(
                gcodec_profile::BUILTIN_NAME.to_owned(),
                Some(crate::builtin_profile_file()),
                e.diagnostics,
            )],
        })?;
    let mut machines = Machines::new(config, builtin);
    let machine_of: Vec<Option<usize>> = found
        .iter()
        .map(|f| machines.load(&config.sections_of(&f.relative)))
        .collect();
    let failed = machines.problems.iter().any(|r| r.diagnostics.has_errors());
    let machine_of = match machine_of.into_iter().collect::<Option<Vec<usize>>>() {
        Some(machine_of) if !failed => machine_of,
        _ => {
            return Err(SetupError {
                reports: std::mem::take(&mut machines.problems),
            });
        }
    };
    progress.files_found(found.len());
    let mut files: Vec<FileReport> = found
        .into_par_iter()
        .zip(machine_of)
        .map(|(found, machine)| {
            let file_ignores = config.ignores_of(&found.relative);
            let levels = Levels {
                rules: &config.rules,
                file_ignores: &file_ignores,
                selection,
            };
            let report = check_file(found, machines.machine(machine), &levels);
            progress.file_checked();
            report
        })
        .collect();
    files.extend(std::mem::take(&mut machines.problems));
    files.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(CheckReport { files })
}

/// One file read and checked: a definition file loaded as one, a program
/// parsed and lowered.
fn check_file(found: Found, machine: &Machine, levels: &Levels<'_>) -> FileReport {
    let name = found.name();
    let file = match found.source {
        Source::File(path) => machine.read(&path),
        Source::Stdin { name, bytes } => {
            Ok(SourceFile::new(name, bytes).decoded(machine.profile.program.text_encoding()))
        }
        Source::Unreadable { problem, .. } => Err(problem),
    };
    let (file, diagnostics) = match file {
        Ok(file) => {
            let file = Arc::new(file);
            let diagnostics = findings(&file, machine);
            (Some(file), diagnostics)
        }
        Err(problem) => {
            let mut diagnostics = Diagnostics::new();
            diagnostics.push(problem);
            (None, diagnostics)
        }
    };
    let relevel = |code, severity| levels.level(code, severity);
    let mut diagnostics = diagnostics.releveled(relevel);
    if let Some(file) = &file {
        let own = suppress::apply(file, &mut diagnostics);
        diagnostics.append(Diagnostics::from(own).releveled(relevel));
        diagnostics.sort_by_start();
    }
    FileReport {
        name,
        file,
        diagnostics,
    }
}

/// What checking `file` finds on `machine`.
fn findings(file: &Arc<SourceFile>, machine: &Machine) -> Diagnostics {
    if is_definition_file(file.name()) {
        return Definitions::new().load(file);
    }
    let kind = ProgramKind::of_file(file.name());
    crate::compile_linted(
        Arc::clone(file),
        kind,
        &machine.profile,
        &machine.definitions,
    )
    .diagnostics
}

fn is_definition_file(name: &str) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("def"))
}
