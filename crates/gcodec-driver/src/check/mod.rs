//! `gcodec check`: every program and definition file of a tree parsed
//! and lowered against the profile and definition files its
//! configuration (`gcodec.toml`) assigns, in parallel, the diagnostics
//! at the rule levels in force, as data.
//!
//! - [`CheckConfig`]: `gcodec.toml`, found upward from the paths checked
//!   ([`find_config`]) or named; what it assigns one program `lower` or
//!   `run` is given ([`ProgramSettings`], [`CheckConfig::releveled`]).
//! - [`Selector`], [`RuleLevel`], [`Selection`]: which diagnostics are
//!   reported, at which level.
//! - [`check`]: the files of [`Input`]s checked; a [`CheckReport`] of
//!   [`FileReport`]s sorted by name.
//! - [`DiagnosticRecord`]: one diagnostic as data (`--output-format
//!   json`, `docs/schema/check.schema.json`), from
//!   [`crate::diagnostics`].
//! - [`check_with`] and [`CheckOptions`]: main programs also run
//!   ([`RunChecks`], `--run`), their findings in the files they are in.
//! - A program's `; gcodec: allow(CODE)` comments are applied after the
//!   levels; [`baseline`]: the findings a repository accepts, written
//!   and applied to a [`CheckReport`].

mod alternatives;
pub mod baseline;
mod config;
mod gather;
mod levels;
mod machines;
mod report;
mod run;
mod selector;
mod suppress;
mod walk;

use std::path::Path;
use std::sync::Arc;

use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{Diagnostics, SourceFile};
use rayon::prelude::*;

pub use config::{CONFIG_NAME, CheckConfig, ProgramSettings, find_config};
pub use levels::{RuleLevel, Selection};
// The records and file reports are every command's; named here too, where
// `check` first had them.
pub use crate::diagnostics::{DiagnosticRecord, FileReport, LabelRecord, check_json_schema};
pub use report::{CheckReport, Counts};
pub use run::RunChecks;
pub use selector::Selector;
pub use walk::Input;

use gather::Checked;
use levels::Levels;
use machines::{Machine, Machines};
use run::RunFinding;
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

/// What a check does besides parsing and lowering every file.
#[derive(Clone, Debug, Default)]
pub struct CheckOptions {
    /// Main programs that lower without errors are also run (`--run`).
    pub run: Option<RunChecks>,
}

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
    check_with(
        config,
        inputs,
        selection,
        &CheckOptions::default(),
        progress,
    )
}

/// [`check_with_progress`], doing what `options` says besides.
pub fn check_with(
    config: &CheckConfig,
    inputs: Vec<Input>,
    selection: &Selection,
    options: &CheckOptions,
    progress: &dyn Progress,
) -> Result<CheckReport, SetupError> {
    let found = walk::files(config, inputs).map_err(|d| SetupError {
        reports: vec![FileReport::new(String::new(), None, vec![d])],
    })?;
    let builtin = crate::load_builtin_profile()
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
    let (mut checked, run_findings): (Vec<Checked>, Vec<Vec<RunFinding>>) = found
        .into_par_iter()
        .zip(machine_of)
        .map(|(found, machine)| {
            let checked = check_file(found, machines.machine(machine), config, options);
            progress.file_checked();
            checked
        })
        .unzip();
    gather::run_findings(config, &mut checked, run_findings);
    let mut files: Vec<FileReport> = checked
        .into_par_iter()
        .map(|checked| {
            let file_ignores = config.ignores_of(&checked.relative);
            let levels = Levels {
                rules: &config.rules,
                file_ignores: &file_ignores,
                selection,
            };
            at_levels(checked, &levels)
        })
        .collect();
    files.extend(std::mem::take(&mut machines.problems));
    files.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(CheckReport { files })
}

/// One file read and checked: a definition file loaded as one, a program
/// parsed and lowered, and, for `--run`, a main program without errors
/// run. Its findings, and those of the run in other files.
fn check_file(
    found: Found,
    machine: &Machine,
    config: &CheckConfig,
    options: &CheckOptions,
) -> (Checked, Vec<RunFinding>) {
    let name = found.name();
    let relative = found.relative.clone();
    let file = match found.source {
        Source::File(path) => machine.read(&path),
        Source::Stdin { name, bytes } => {
            Ok(SourceFile::new(name, bytes).decoded(machine.profile.program.text_encoding()))
        }
        Source::Unreadable { problem, .. } => Err(problem),
    };
    let file = match file {
        Ok(file) => Arc::new(file),
        Err(problem) => {
            let diagnostics = Diagnostics::from(vec![problem]);
            let checked = Checked::new(name, relative, None, diagnostics);
            return (checked, Vec::new());
        }
    };
    if is_definition_file(file.name()) {
        let diagnostics = Definitions::new().load(&file);
        return (
            Checked::new(name, relative, Some(file), diagnostics),
            Vec::new(),
        );
    }
    let kind = ProgramKind::of_file(file.name());
    let compiled = crate::compile_linted(
        Arc::clone(&file),
        kind,
        &machine.profile,
        &machine.definitions,
    );
    let run_findings = match options.run {
        Some(checks) if kind == ProgramKind::Main && !compiled.has_errors() => run::run(
            &file,
            compiled.document,
            machine,
            &config.search_paths,
            checks,
        ),
        _ => Vec::new(),
    };
    let checked = Checked::new(name, relative, Some(file), compiled.diagnostics);
    (checked, run_findings)
}

/// A file's findings at the levels in force, its suppressions applied.
fn at_levels(checked: Checked, levels: &Levels<'_>) -> FileReport {
    let relevel = |code, severity| levels.level(code, severity);
    let mut diagnostics = checked.diagnostics.releveled(relevel);
    if let Some(file) = &checked.file {
        let own = suppress::apply(file, &mut diagnostics);
        diagnostics.append(Diagnostics::from(own).releveled(relevel));
        diagnostics.sort_by_start();
    }
    FileReport {
        name: checked.name,
        file: checked.file,
        diagnostics,
    }
}

fn is_definition_file(name: &str) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("def"))
}
