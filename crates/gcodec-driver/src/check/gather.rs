//! A check's files before their levels, and the findings of `--run`
//! gathered into the files they are in: a called program's into its own
//! report (a file the check reads anyway, or one more report for a file
//! found only on the search path), each finding once per file, code and
//! place, so that a subprogram many programs call is reported once and
//! what its lowering already found is not repeated by the run.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_source::{Diagnostic, Diagnostics, SourceFile};

use super::config::CheckConfig;
use super::run::RunFinding;

/// One file's findings at the levels its code gives them.
#[derive(Debug)]
pub(super) struct Checked {
    /// The name shown: the path as walked, given, or found by a run.
    pub name: String,
    /// The path the configuration's globs match.
    pub relative: PathBuf,
    pub file: Option<Arc<SourceFile>>,
    pub diagnostics: Diagnostics,
}

impl Checked {
    pub fn new(
        name: String,
        relative: PathBuf,
        file: Option<Arc<SourceFile>>,
        diagnostics: Diagnostics,
    ) -> Self {
        Self {
            name,
            relative,
            file,
            diagnostics,
        }
    }
}

/// What makes two findings of one file the same: the code and where the
/// primary span starts (the message, for one without a place).
type Sameness = (usize, Result<u32, String>);

fn sameness(d: &Diagnostic) -> Sameness {
    let code = std::ptr::from_ref(d.code) as usize;
    (
        code,
        d.span()
            .map(|s| s.start)
            .ok_or_else(|| d.message.to_string()),
    )
}

/// Adds every run's findings to the file each is in, `checked` gaining a
/// report for a file no path named.
pub(super) fn run_findings(
    config: &CheckConfig,
    checked: &mut Vec<Checked>,
    runs: Vec<Vec<RunFinding>>,
) {
    let key = |name: &str| std::path::absolute(name).unwrap_or_else(|_| PathBuf::from(name));
    let mut index: HashMap<PathBuf, usize> = (checked.iter().enumerate())
        .map(|(i, c)| (key(&c.name), i))
        .collect();
    let mut known: HashMap<usize, HashSet<Sameness>> = HashMap::new();
    for finding in runs.into_iter().flatten() {
        let at = *index.entry(key(&finding.name)).or_insert_with(|| {
            let name = shown(&finding.name);
            let relative = config.relative(Path::new(&name), Path::new(""));
            let file = finding.file.clone();
            checked.push(Checked::new(name, relative, file, Diagnostics::new()));
            checked.len() - 1
        });
        let file = &mut checked[at];
        let seen = known
            .entry(at)
            .or_insert_with(|| file.diagnostics.iter().map(sameness).collect());
        if seen.insert(sameness(&finding.diagnostic)) {
            file.diagnostics.push(finding.diagnostic);
        }
    }
    for &at in known.keys() {
        checked[at].diagnostics.sort_by_start();
    }
}

/// The name a file found only by a run is shown by: relative to the
/// current folder where it is inside it (a configuration's search paths
/// are absolute), else as the run found it.
fn shown(name: &str) -> String {
    let path = Path::new(name);
    std::env::current_dir()
        .ok()
        .and_then(|here| path.strip_prefix(here).ok())
        .map_or_else(|| name.to_owned(), |inside| inside.display().to_string())
}
