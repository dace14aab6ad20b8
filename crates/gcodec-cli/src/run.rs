//! `gcodec run`: runs a program on the machine a profile describes and
//! streams its events (jsonl, a text trace, or CSV rows of the state).
//! Its options and setup ([`RunInputs`], [`prepare`], [`run_events`],
//! [`conclude`]) are every running command's (`plot` too).

use std::io::{self, Write};
use std::path::PathBuf;
use std::sync::Arc;

use clap::ValueEnum;
use gcodec_driver::event::{
    CsvRows, CsvWriter, Event, EventKind, EventSink, JsonlSink, ProgramEndReason, TextSink,
};
use gcodec_driver::{BlockObserver, LoadedFiles, RunOutcome, RunReport, RunSetup, run_main};
use gcodec_source::{SourceFile, escape_controls};

use crate::diagnostic_formats::DiagnosticFormat;
use crate::exit::{EXIT_CLEAN, EXIT_DIAGNOSTICS};
use crate::output::{Stdout, after_output, to_stderr};
use crate::report::{
    ConfigOption, DiagnosticOptions, EncodingOption, ProgramSetup, Reading, Reporter,
    load_definitions, load_profile, load_toolchanger, read,
};

/// How events are written.
#[derive(Clone, Copy, Debug, ValueEnum)]
pub enum RunFormat {
    /// One JSON object per event, one a line.
    Jsonl,
    /// A readable trace, one line per event.
    Text,
    /// A row per block that moves or changes the state (positions, tool,
    /// feed, spindle, the main modal groups), and for the last block.
    Csv,
}

/// Which blocks `--format csv` writes a row for.
#[derive(Clone, Copy, Debug, Default, ValueEnum)]
pub enum CsvRowsOption {
    /// A block with a motion or after which a column shows something
    /// new, and the last block; the `blocks` column counts all of them.
    #[default]
    Changes,
    /// Every executed block, `WHILE` and `ENDWHILE` included.
    EveryBlock,
}

impl From<CsvRowsOption> for CsvRows {
    fn from(option: CsvRowsOption) -> Self {
        match option {
            CsvRowsOption::Changes => CsvRows::Changes,
            CsvRowsOption::EveryBlock => CsvRows::EveryBlock,
        }
    }
}

// The options of `gcodec run`.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    #[command(flatten)]
    pub inputs: RunInputs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = RunFormat::Jsonl)]
    pub format: RunFormat,
    /// Which blocks get a row with `--format csv`.
    #[arg(long, value_enum, value_name = "ROWS", default_value_t = CsvRowsOption::Changes)]
    pub csv_rows: CsvRowsOption,
}

// What a command that runs a program (`run`, `plot`) runs it with: the
// program, the machine, definitions, search paths, the configuration,
// the limits of the run and how diagnostics are shown.
#[derive(Debug, clap::Args)]
pub struct RunInputs {
    /// The main program (`.mpf`).
    pub file: PathBuf,
    /// The machine profile (TOML); the built-in one if omitted.
    #[arg(long)]
    pub profile: Option<PathBuf>,
    /// A definition file (`MGUD.DEF`, `SMAC.DEF`). Repeat for several.
    #[arg(long = "definitions", value_name = "FILE.DEF")]
    pub definitions: Vec<PathBuf>,
    /// How the diagnostics are written on stderr: `full` renders each as
    /// it comes (the run's as they happen, the program's after the run);
    /// the others write one document of them all after the run, alone on
    /// stderr (the figures a `jsonl` or `csv` run or a plot write there
    /// are then left out).
    #[arg(long, value_enum, default_value_t = DiagnosticFormat::Full)]
    pub output_format: DiagnosticFormat,
    #[command(flatten)]
    pub config: ConfigOption,
    #[command(flatten)]
    pub encoding: EncodingOption,
    /// A directory searched for subprograms and cycles, after the calling
    /// program's directory and the profile's `subprogram_paths`. Repeat
    /// for several.
    #[arg(long = "subprogram-path", value_name = "DIR")]
    pub subprogram_paths: Vec<PathBuf>,
    /// The skip levels switched on, e.g. `0,3`; `none` for none. Replaces
    /// the profile's `skip_levels`.
    #[arg(long, value_name = "LEVELS", value_parser = parse_skip_levels)]
    pub skip_levels: Option<SkipLevels>,
    /// Stop after this many blocks (a guard against endless loops).
    #[arg(long, value_name = "N", default_value_t = 10_000_000)]
    pub max_steps: u64,
    /// Stop before the run's work on arrays passes this many element
    /// operations (elements declared, and written by lists, `REP` and
    /// `VAR` copies): a guard against blocks that each cost millions.
    #[arg(long, value_name = "N", default_value_t = gcodec_driver::DEFAULT_MAX_WORK)]
    pub max_work: u64,
    /// Go on after `M0` (and `M1`) instead of ending the run there (as the
    /// profile's `[program] stop_at_m0 = false` does).
    #[arg(long)]
    pub no_stop: bool,
    /// The operator's optional-stop switch: `M1` stops like `M0`.
    #[arg(long)]
    pub optional_stop: bool,
    /// Run tool changes through the simulated toolchanger, behaving (and
    /// faulting) as this scenario says (`docs/toolchanger.md`).
    #[arg(long, value_name = "SCENARIO.toml")]
    pub toolchanger: Option<PathBuf>,
    #[command(flatten)]
    pub diagnostics: DiagnosticOptions,
}

/// Skip levels from the command line.
#[derive(Clone, Copy, Debug)]
pub struct SkipLevels([bool; 10]);

fn parse_skip_levels(text: &str) -> Result<SkipLevels, String> {
    let mut levels = [false; 10];
    if text.trim().eq_ignore_ascii_case("none") {
        return Ok(SkipLevels(levels));
    }
    for part in text.split(',') {
        let part = part.trim();
        let level: usize = part
            .parse()
            .ok()
            .filter(|l| *l <= 9)
            .ok_or_else(|| format!("`{part}` is not a skip level 0…9"))?;
        levels[level] = true;
    }
    Ok(SkipLevels(levels))
}

/// Reports runtime diagnostics as they happen (besides the event stream,
/// so a CI job sees them whatever the format), each against the file of
/// the program it happened in, and hands every event on.
struct Diagnostics<'r, S> {
    inner: S,
    reporter: &'r Reporter,
    /// The files of the programs the run has loaded, which the
    /// diagnostics point into.
    files: LoadedFiles,
}

impl<'r, S: EventSink> Diagnostics<'r, S> {
    fn new(inner: S, files: LoadedFiles, reporter: &'r Reporter) -> Self {
        Self {
            inner,
            reporter,
            files,
        }
    }
}

impl<S: EventSink> EventSink for Diagnostics<'_, S> {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        if let EventKind::Diagnostic(d) = &event.kind {
            let file = self.files.get(&event.source.file);
            let file = file.as_deref();
            self.reporter.report(
                &vec![gcodec_driver::runtime_diagnostic(d, &event.source, file)].into(),
                file,
                &event.source.file,
            );
        }
        self.inner.event(event)
    }

    fn finish(&mut self) -> io::Result<()> {
        self.inner.finish()
    }

    fn takes_motions(&self) -> bool {
        self.inner.takes_motions()
    }
}

/// Events go nowhere (the CSV format writes rows, not events).
struct Discard;

impl EventSink for Discard {
    fn event(&mut self, _: &Event) -> io::Result<()> {
        Ok(())
    }

    fn takes_motions(&self) -> bool {
        false
    }
}

pub fn run(args: RunArgs) -> u8 {
    let reporter = Reporter::new(args.inputs.diagnostics, args.inputs.output_format);
    let exit = run_with(&args, &reporter);
    reporter.finish();
    exit
}

/// A program ready to run: its file, and the run's setup from the
/// command line and the configuration.
pub struct PreparedRun {
    pub file: Arc<SourceFile>,
    pub setup: RunSetup,
}

/// Reads what `inputs` names (the configuration, profile, definitions,
/// toolchanger scenario, the program) and sets the run up, Ctrl-C
/// stopping it cleanly; the exit code if anything cannot be read.
pub fn prepare(inputs: &RunInputs, reporter: &Reporter) -> Result<PreparedRun, u8> {
    let program = ProgramSetup::of(
        &inputs.config,
        &inputs.file,
        inputs.profile.as_deref(),
        &inputs.definitions,
        reporter,
    )?;
    let profile_path = program.profile.as_deref();
    let profile = Arc::new(load_profile(profile_path, reporter)?);
    let reading = Reading::new(&profile, inputs.encoding);
    let mut definitions = load_definitions(&program.definitions, reading, reporter)?;
    for name in &program.assume_defined {
        definitions.assume_defined(name);
    }
    let definitions = Arc::new(definitions);
    let toolchanger = match &inputs.toolchanger {
        Some(path) => Some(load_toolchanger(path, &profile, reporter)?),
        None => None,
    };
    let file = read(&inputs.file, reading, reporter)?;
    let mut setup = RunSetup::new(profile);
    setup.toolchanger = toolchanger;
    setup.encoding = reading.encoding;
    setup.profile_file = profile_path.map(PathBuf::from);
    setup.definitions = definitions;
    // The command line's folders first, then the configuration's.
    setup.search_dirs = inputs.subprogram_paths.clone();
    setup
        .search_dirs
        .extend(program.search_paths.iter().cloned());
    let run_options = &mut setup.options;
    if let Some(SkipLevels(levels)) = inputs.skip_levels {
        run_options.skip_levels = levels;
    }
    run_options.max_steps = inputs.max_steps;
    run_options.max_work = inputs.max_work;
    if inputs.no_stop {
        run_options.stop_at_m0 = false;
    }
    run_options.optional_stop = inputs.optional_stop;
    run_options.interrupt = Some(crate::interrupt::ctrl_c_flag());
    Ok(PreparedRun {
        file: Arc::new(file),
        setup,
    })
}

/// Runs the prepared program: its events to `sink`, the runtime
/// diagnostics among them reported as they happen, the state after each
/// block to `observer`.
pub fn run_events(
    prepared: &PreparedRun,
    sink: &mut dyn EventSink,
    observer: Option<&mut dyn BlockObserver>,
    reporter: &Reporter,
) -> RunReport {
    let mut sink = Diagnostics::new(sink, prepared.setup.loaded_files.clone(), reporter);
    run_main(
        Arc::clone(&prepared.file),
        &prepared.setup,
        &mut sink,
        observer,
    )
}

/// After the run, once its events are all written: reports the
/// program's own diagnostics (all of them, after the run that went on
/// while it was lowered); the outcome and the exit code the run earned,
/// or the exit code of an output error.
pub fn conclude(
    prepared: &PreparedRun,
    outcome: io::Result<RunOutcome>,
    diagnostics: &gcodec_source::Diagnostics,
    reporter: &Reporter,
) -> Result<(RunOutcome, u8), u8> {
    let file = &prepared.file;
    let has_errors = reporter.report(diagnostics, Some(&**file), file.name());
    let outcome = outcome.map_err(|e| after_output(EXIT_CLEAN, Err(e)))?;
    let exit = if has_errors || outcome.errors > 0 || outcome.reason == ProgramEndReason::Alarm {
        EXIT_DIAGNOSTICS
    } else {
        EXIT_CLEAN
    };
    Ok((outcome, exit))
}

/// The run's summary on stderr, unless stderr holds the diagnostics'
/// document alone.
pub fn summary_to_stderr(outcome: &RunOutcome, reporter: &Reporter) {
    if !reporter.collects() {
        to_stderr(&escape_controls(&outcome.summary.to_string()));
    }
}

fn run_with(args: &RunArgs, reporter: &Reporter) -> u8 {
    let prepared = match prepare(&args.inputs, reporter) {
        Ok(prepared) => prepared,
        Err(code) => return code,
    };
    let out = match args.format {
        RunFormat::Text => Stdout::text(),
        RunFormat::Jsonl | RunFormat::Csv => Stdout::data(),
    };
    let (mut events, mut rows): (Box<dyn EventSink>, _) = match args.format {
        RunFormat::Jsonl => (Box::new(JsonlSink::new(out)), None),
        RunFormat::Text => (Box::new(TextSink::new(out)), None),
        RunFormat::Csv => match CsvWriter::for_profile(out, &prepared.setup.profile) {
            Ok(rows) => (
                Box::new(Discard) as Box<dyn EventSink>,
                Some(rows.with_rows(args.csv_rows.into())),
            ),
            Err(e) => return after_output(EXIT_CLEAN, Err(e)),
        },
    };
    let observer = rows.as_mut().map(|rows| rows as _);
    let RunReport {
        outcome,
        diagnostics,
    } = run_events(&prepared, &mut *events, observer, reporter);
    let outcome = outcome.and_then(|outcome| {
        rows.as_mut().map_or(Ok(()), CsvWriter::finish)?;
        Ok(outcome)
    });
    // The event stream is complete before anything else is written.
    drop(events);
    drop(rows);
    let (outcome, exit) = match conclude(&prepared, outcome, &diagnostics, reporter) {
        Ok(concluded) => concluded,
        Err(code) => return code,
    };
    let written = match args.format {
        RunFormat::Text => {
            let mut out = Stdout::text();
            writeln!(out, "\n{}", outcome.summary).and_then(|()| out.flush())
        }
        RunFormat::Jsonl | RunFormat::Csv => {
            summary_to_stderr(&outcome, reporter);
            Ok(())
        }
    };
    after_output(exit, written)
}
