//! `gcodec check --baseline FILE` and `--write-baseline FILE`: the
//! baseline read before the check and applied to its report, or the
//! report written as one ([`gcodec_driver::check::baseline`]).

use std::io::IsTerminal;
use std::path::Path;

use gcodec_driver::check::CheckReport;
use gcodec_driver::check::baseline::{Applied, Baseline};
use gcodec_source::{Diagnostic, SourceFile, codes, escape_controls, render_diagnostics};

use crate::exit::{EXIT_CLEAN, EXIT_USAGE};
use crate::output::to_stderr;
use crate::report::DiagnosticOptions;

/// The folder a baseline's file names are relative to.
pub fn folder(path: &Path) -> &Path {
    path.parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// Reads the baseline at `path`; a problem is written to stderr and is
/// exit 2.
pub fn read(path: &Path, options: DiagnosticOptions) -> Result<Baseline, u8> {
    let render = options.render_options_for(std::io::stderr().is_terminal());
    let file = SourceFile::read(path).map_err(|e| {
        let d = Diagnostic::new(
            e.code(),
            format!("cannot read the baseline `{}`: {e}", path.display()),
        )
        .with_help(e.help());
        to_stderr(&render_diagnostics(&[d], None, render));
        EXIT_USAGE
    })?;
    Baseline::read(&file).map_err(|d| {
        to_stderr(&render_diagnostics(&[d], Some(&file), render));
        EXIT_USAGE
    })
}

/// Writes every finding of `report` to `path` as a baseline: exit 0, or
/// 2 where it cannot be written.
pub fn write(report: &CheckReport, path: &Path) -> u8 {
    let baseline = Baseline::of(report, folder(path));
    if let Err(e) = std::fs::write(path, baseline.to_json()) {
        let d = Diagnostic::new(
            codes::io::WRITE,
            format!("cannot write the baseline `{}`: {e}", path.display()),
        );
        to_stderr(&render_diagnostics(&[d], None, Default::default()));
        return EXIT_USAGE;
    }
    to_stderr(&format!(
        "wrote {} findings in {} entries to {}\n",
        baseline.findings(),
        baseline.entries().len(),
        escape_controls(&path.display().to_string())
    ));
    EXIT_CLEAN
}

/// Says on stderr what the baseline matched and which of its entries are
/// fixed.
pub fn tell(applied: Applied) {
    let plural = |n: u64, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    let mut text = format!(
        "{} matched the baseline and are not reported\n",
        plural(applied.matched, "finding", "findings")
    );
    if applied.fixed > 0 {
        text.push_str(&format!(
            "{} fixed; rewrite with --write-baseline\n",
            plural(applied.fixed, "baseline entry is", "baseline entries are")
        ));
    }
    to_stderr(&text);
}
