//! `gcodec check`: a tree of part programs and definition files checked
//! as its `gcodec.toml` says ([`gcodec_driver::check`]), the diagnostics
//! written to stdout in one of the formats of [`crate::diagnostic_formats`].

use std::io::{IsTerminal, Read, Write};
use std::path::{Path, PathBuf};

use clap::ValueEnum;
use gcodec_driver::check::{
    CheckConfig, CheckOptions, CheckReport, FileReport, Input, Progress, RunChecks, Selection,
    Selector, find_config,
};
use gcodec_source::{codes, render_diagnostics, render_kept};

use crate::diagnostic_formats::{DiagnosticFormat, write_diagnostics};
use crate::exit::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE};
use crate::output::{Stdout, after_output, to_stderr};
use crate::report::{DiagnosticOptions, Reporter, load_config};

/// What `--deny` makes fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Denied {
    /// Warnings are errors.
    Warnings,
}

// The options of `gcodec check`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Every code in the output is explained by `gcodec explain CODE`; \
                        `gcodec explain --list` lists them all."
)]
pub struct CheckArgs {
    /// Files and folders to check (folders walked for `.mpf`, `.spf` and
    /// `.def` files); `-` reads standard input. Default: the current
    /// folder.
    pub paths: Vec<PathBuf>,
    /// The configuration; without it, the nearest `gcodec.toml` in the
    /// first path's folder or a folder above it.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Report only these codes or areas (`gcodec::lower::*`), comma
    /// separated or repeated.
    #[arg(long, value_name = "CODES", value_delimiter = ',', value_parser = Selector::parse)]
    pub select: Vec<Selector>,
    /// Do not report these codes or areas, comma separated or repeated.
    #[arg(long, value_name = "CODES", value_delimiter = ',', value_parser = Selector::parse)]
    pub ignore: Vec<Selector>,
    /// `--deny warnings`: warnings fail the check as errors do.
    #[arg(long, value_enum, value_name = "WHAT")]
    pub deny: Option<Denied>,
    /// Output format.
    #[arg(long, value_enum, default_value_t = DiagnosticFormat::Full)]
    pub output_format: DiagnosticFormat,
    /// Instead of the diagnostics, how many there are of each code.
    #[arg(long)]
    pub statistics: bool,
    /// The name of the program read from standard input (`-`): it is
    /// shown, and the configuration's globs and the file kind go by it.
    #[arg(long, value_name = "NAME")]
    pub stdin_filename: Option<String>,
    /// Also run each main program (not `.spf`, not `.def`) that lowers
    /// without errors, so that run-time errors are found; its calls are
    /// found in its folder, the profile's `subprogram_paths` and the
    /// configuration's `search_paths`.
    #[arg(long)]
    pub run: bool,
    /// With `--run`: stop a run after this many blocks
    /// (`gcodec::run::step_limit`).
    #[arg(long, value_name = "N", default_value_t = RunChecks::default().max_steps, requires = "run")]
    pub max_steps: u64,
    /// Do not report the findings this baseline lists (as many of each
    /// as it counts): only new findings are reported and fail.
    #[arg(long, value_name = "FILE", conflicts_with = "write_baseline")]
    pub baseline: Option<PathBuf>,
    /// Write every finding to this baseline file instead of reporting
    /// them, and exit 0.
    #[arg(long, value_name = "FILE")]
    pub write_baseline: Option<PathBuf>,
    #[command(flatten)]
    pub diagnostics: DiagnosticOptions,
}

/// `gcodec check`: exit 0 when nothing is at error level, 1 when
/// something is, 2 on a usage, IO or configuration error.
pub fn check(args: CheckArgs) -> u8 {
    let paths = if args.paths.is_empty() {
        vec![PathBuf::from(".")]
    } else {
        args.paths.clone()
    };
    if args.stdin_filename.is_some() && !paths.iter().any(|p| p.as_os_str() == "-") {
        to_stderr(
            "error: `--stdin-filename` names the program read from standard input, \
             which is read only for the path `-`\n",
        );
        return EXIT_USAGE;
    }
    let stdin_name = args
        .stdin_filename
        .clone()
        .unwrap_or_else(|| "-".to_owned());
    let config = match configuration(&args, &paths, &stdin_name) {
        Ok(config) => config,
        Err(code) => return code,
    };
    let inputs = match inputs(&paths, &stdin_name) {
        Ok(inputs) => inputs,
        Err(code) => return code,
    };
    let baseline = match &args.baseline {
        Some(path) => match crate::baseline::read(path, args.diagnostics) {
            Ok(baseline) => Some((baseline, path)),
            Err(code) => return code,
        },
        None => None,
    };
    let selection = Selection {
        select: args.select.clone(),
        ignore: args.ignore.clone(),
        deny_warnings: args.deny == Some(Denied::Warnings),
    };
    let progress = ProgressBar::for_stderr();
    let options = CheckOptions {
        run: args.run.then_some(RunChecks {
            max_steps: args.max_steps,
        }),
    };
    let checked =
        gcodec_driver::check::check_with(&config, inputs, &selection, &options, &progress);
    progress.finish();
    let mut report = match checked {
        Ok(report) => report,
        Err(error) => {
            for problem in &error.reports {
                report_to_stderr(problem, args.diagnostics);
            }
            return EXIT_USAGE;
        }
    };
    if let Some(path) = &args.write_baseline {
        return crate::baseline::write(&report, path);
    }
    if let Some((baseline, path)) = &baseline {
        let applied = baseline.apply(&mut report, crate::baseline::folder(path));
        crate::baseline::tell(applied);
    }
    let exit = if report.has_errors() {
        EXIT_DIAGNOSTICS
    } else {
        EXIT_CLEAN
    };
    let (mut out, written) = if args.statistics {
        let mut out = Stdout::text();
        let written = write_statistics(&report, &mut out);
        (out, written)
    } else {
        let format = args.output_format;
        let mut out = if format.is_plain_text() {
            Stdout::text()
        } else {
            Stdout::data()
        };
        let render = args
            .diagnostics
            .render_options_for(std::io::stdout().is_terminal());
        let mut written = write_diagnostics(format, &report.files, render, &mut out);
        if format == DiagnosticFormat::Full {
            written = written.and_then(|()| writeln!(out, "{}", summary(&report)));
        }
        (out, written)
    };
    after_output(exit, written.and_then(|()| out.flush()))
}

/// The configuration `--config` names, or the one found upward from the
/// first path (from the standard input's name for `-`), or the default.
fn configuration(args: &CheckArgs, paths: &[PathBuf], stdin_name: &str) -> Result<CheckConfig, u8> {
    let found = match &args.config {
        Some(path) => Some(path.clone()),
        None => {
            let first = &paths[0];
            let start = if first.as_os_str() == "-" {
                Path::new(stdin_name).parent().unwrap_or(Path::new("."))
            } else {
                first.as_path()
            };
            find_config(start)
        }
    };
    let Some(path) = found else {
        let here = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
        return Ok(CheckConfig::default_in(here));
    };
    load_config(&path, &Reporter::full(args.diagnostics))
}

/// A progress bar on stderr while a long check runs: only when stderr is
/// a terminal and there are at least [`ProgressBar::FROM_FILES`] files;
/// it is cleared when the check ends, before the diagnostics are written.
struct ProgressBar {
    terminal: bool,
    bar: std::sync::OnceLock<indicatif::ProgressBar>,
}

impl ProgressBar {
    /// Fewer files are checked in about a second: no bar for them.
    const FROM_FILES: usize = 200;

    fn for_stderr() -> Self {
        Self {
            terminal: std::io::stderr().is_terminal(),
            bar: std::sync::OnceLock::new(),
        }
    }

    fn finish(&self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

impl Progress for ProgressBar {
    fn files_found(&self, files: usize) {
        if self.terminal && files >= Self::FROM_FILES {
            let bar = indicatif::ProgressBar::with_draw_target(
                Some(files as u64),
                indicatif::ProgressDrawTarget::stderr(),
            );
            let _ = self.bar.set(bar);
        }
    }

    fn file_checked(&self) {
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
        }
    }
}

/// The paths as the check's inputs, standard input read for `-`.
fn inputs(paths: &[PathBuf], stdin_name: &str) -> Result<Vec<Input>, u8> {
    let mut inputs = Vec::with_capacity(paths.len());
    let mut stdin_read = false;
    for path in paths {
        if path.as_os_str() != "-" {
            inputs.push(Input::Path(path.clone()));
            continue;
        }
        if std::mem::replace(&mut stdin_read, true) {
            continue;
        }
        let mut bytes = Vec::new();
        if let Err(e) = std::io::stdin().lock().read_to_end(&mut bytes) {
            let d = gcodec_source::Diagnostic::new(
                codes::io::READ,
                format!("cannot read standard input: {e}"),
            );
            to_stderr(&render_diagnostics(&[d], None, Default::default()));
            return Err(EXIT_USAGE);
        }
        inputs.push(Input::Stdin {
            name: stdin_name.to_owned(),
            bytes,
        });
    }
    Ok(inputs)
}

fn report_to_stderr(problem: &FileReport, options: DiagnosticOptions) {
    let terminal = std::io::stderr().is_terminal();
    to_stderr(&render_kept(
        &problem.diagnostics,
        problem.file.as_deref(),
        options.render_options_for(terminal),
    ));
}

/// `checked 3 files: 1 error, 2 warnings, 0 advice (in 2 files)`.
fn summary(report: &CheckReport) -> String {
    let counts = report.counts();
    let plural = |n: u64, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    format!(
        "checked {}: {}, {}, {} advice (in {})",
        plural(counts.files as u64, "file", "files"),
        plural(counts.errors, "error", "errors"),
        plural(counts.warnings, "warning", "warnings"),
        counts.advice,
        plural(counts.files_with_findings as u64, "file", "files"),
    )
}

/// How many of each code and level, the most frequent first.
fn write_statistics(report: &CheckReport, out: &mut impl Write) -> std::io::Result<()> {
    for (code, severity, n) in report.by_code() {
        writeln!(out, "{n:>8}  {:<7}  {code}", severity.name())?;
    }
    writeln!(out, "{}", summary(report))
}
