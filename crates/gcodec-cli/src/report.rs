//! What every command shares: how diagnostics are shown,
//! reading the files a command is given (programs, profiles, definition
//! files) and rendering what is wrong with them.

use std::cell::{OnceCell, RefCell};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_driver::check::{CheckConfig, find_config};
use gcodec_driver::diagnostics::FileReport;
use gcodec_source::{Diagnostics, Encoding, RenderOptions, SourceFile, TextEncoding, render_kept};

use crate::diagnostic_formats::{DiagnosticFormat, diagnostics_text};
use crate::exit::EXIT_USAGE;
use crate::output::to_stderr;

// How diagnostics are shown.
#[derive(Clone, Copy, Debug, clap::Args)]
pub struct DiagnosticOptions {
    /// Show at most N diagnostics per file, then count the rest (0: all).
    /// The exit code counts them all.
    #[arg(long, value_name = "N", default_value_t = 100)]
    max_diagnostics: usize,
}

impl DiagnosticOptions {
    fn render_options(self) -> RenderOptions {
        self.render_options_for(std::io::stderr().is_terminal())
    }

    /// The options for rendering to a stream, coloured where it is a
    /// terminal (`terminal`) and `NO_COLOR` is not set.
    pub fn render_options_for(self, terminal: bool) -> RenderOptions {
        RenderOptions {
            color: terminal && std::env::var_os("NO_COLOR").is_none(),
            limit: (self.max_diagnostics > 0).then_some(self.max_diagnostics),
        }
    }
}

/// Where a command's diagnostics go, in which format: `full` renders
/// each batch on stderr as it comes; the other formats collect them, file
/// by file, and write one document on stderr when the command ends
/// ([`Reporter::finish`]), so that stderr holds that document alone.
///
/// With a configuration ([`Reporter::use_config`]) every diagnostic is
/// reported at the level its `[rules]` and its file's `ignore` give it.
pub struct Reporter {
    options: DiagnosticOptions,
    format: DiagnosticFormat,
    files: RefCell<Vec<FileReport>>,
    config: OnceCell<Arc<CheckConfig>>,
}

impl Reporter {
    pub fn new(options: DiagnosticOptions, format: DiagnosticFormat) -> Self {
        Self {
            options,
            format,
            files: RefCell::new(Vec::new()),
            config: OnceCell::new(),
        }
    }

    /// Reports every diagnostic from now on at the levels `config` sets.
    pub fn use_config(&self, config: Arc<CheckConfig>) {
        let _ = self.config.set(config);
    }

    /// miette's reports on stderr (`parse`, `profile`).
    pub fn full(options: DiagnosticOptions) -> Self {
        Self::new(options, DiagnosticFormat::Full)
    }

    /// Whether the diagnostics are written as data at the end (not
    /// rendered as they come).
    pub fn collects(&self) -> bool {
        self.format != DiagnosticFormat::Full
    }

    /// Reports `diagnostics` of the file named `name`, against its text
    /// `file` where they have spans; true if any is an error at the
    /// levels in force.
    pub fn report(&self, diagnostics: &Diagnostics, file: Option<&SourceFile>, name: &str) -> bool {
        let releveled;
        let diagnostics = match self.config.get() {
            Some(config) => {
                releveled = config.releveled(Path::new(name), diagnostics.clone());
                &releveled
            }
            None => diagnostics,
        };
        if diagnostics.is_empty() {
            return diagnostics.has_errors();
        }
        if !self.collects() {
            to_stderr(&render_kept(
                diagnostics,
                file,
                self.options.render_options(),
            ));
            return diagnostics.has_errors();
        }
        let mut files = self.files.borrow_mut();
        match files.last_mut() {
            // A run reports a file's diagnostics one at a time.
            Some(last) if last.name == name && last.file.is_some() == file.is_some() => {
                last.diagnostics.append(diagnostics.clone());
            }
            _ => files.push(FileReport {
                name: name.to_owned(),
                file: file.map(|f| Arc::new(f.clone())),
                diagnostics: diagnostics.clone(),
            }),
        }
        diagnostics.has_errors()
    }

    /// Writes what was collected, in the format chosen, on stderr.
    pub fn finish(self) {
        if !self.collects() {
            return;
        }
        let files = self.files.into_inner();
        match diagnostics_text(self.format, &files, self.options.render_options()) {
            Ok(text) => to_stderr(&text),
            Err(e) => to_stderr(&format!("gcodec: cannot write the diagnostics: {e}\n")),
        }
    }
}

// The configuration a command that lowers or runs one program reads.
#[derive(Clone, Debug, clap::Args)]
pub struct ConfigOption {
    /// The configuration (`gcodec.toml`, as `gcodec check` reads it);
    /// without it, the nearest `gcodec.toml` in the program's folder or a
    /// folder above it.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
}

/// What a program is lowered or run with: the profile and definition
/// files the command line names, else those `gcodec.toml` assigns it,
/// the names it assumes defined and its search paths.
#[derive(Debug, Default)]
pub struct ProgramSetup {
    pub profile: Option<PathBuf>,
    pub definitions: Vec<PathBuf>,
    pub assume_defined: Vec<String>,
    pub search_paths: Vec<PathBuf>,
}

impl ProgramSetup {
    /// The setup of the program at `program`: the configuration
    /// `option` names or the one found upward from the program, whose
    /// levels `reporter` then applies. A configuration that cannot be
    /// read or has problems is reported and is exit code 2.
    pub fn of(
        option: &ConfigOption,
        program: &Path,
        profile: Option<&Path>,
        definitions: &[PathBuf],
        reporter: &Reporter,
    ) -> Result<Self, u8> {
        let mut setup = Self {
            profile: profile.map(Path::to_path_buf),
            definitions: definitions.to_vec(),
            ..Self::default()
        };
        let Some(path) = option.config.clone().or_else(|| find_config(program)) else {
            return Ok(setup);
        };
        let config = load_config(&path, reporter)?;
        let settings = config.program_settings(program);
        // The command line wins over the configuration.
        if setup.profile.is_none() {
            setup.profile = settings.profile;
        }
        if setup.definitions.is_empty() {
            setup.definitions = settings.definitions;
        }
        setup.assume_defined = settings.assume_defined;
        setup.search_paths = config.search_paths.clone();
        reporter.use_config(Arc::new(config));
        Ok(setup)
    }
}

/// Reads and checks the configuration at `path`; one that cannot be read
/// or has problems is reported and is exit code 2.
pub fn load_config(path: &Path, reporter: &Reporter) -> Result<CheckConfig, u8> {
    let file = SourceFile::read(path).map_err(|e| {
        let d = gcodec_source::Diagnostic::new(
            e.code(),
            format!("cannot read `{}`: {e}", path.display()),
        )
        .with_help(e.help());
        reporter.report(&vec![d].into(), None, &path.display().to_string());
        EXIT_USAGE
    })?;
    let shown = file.clone();
    CheckConfig::load(file).map_err(|problems| {
        reporter.report(&problems.into(), Some(&shown), shown.name());
        EXIT_USAGE
    })
}

// The encoding of the files a command reads, where one is named.
#[derive(Clone, Copy, Debug, clap::Args)]
pub struct EncodingOption {
    /// Read every program and definition file in this encoding (a WHATWG
    /// label: `windows-1251`, `iso-8859-2`, `utf-8`). Without it a file
    /// is UTF-8 where it is valid UTF-8, else in the profile's
    /// `[program] code_page` (Windows-1252 by default).
    #[arg(long, value_name = "NAME", value_parser = parse_encoding)]
    encoding: Option<Encoding>,
}

fn parse_encoding(label: &str) -> Result<Encoding, String> {
    Encoding::for_label(label).ok_or_else(|| {
        format!(
            "`{label}` is not an encoding program text can be in; name one by its WHATWG \
             label: `windows-1252`, `windows-1251`, `iso-8859-2`, `utf-8`"
        )
    })
}

/// How a command reads its program and definition files: at most
/// `max_len` bytes each (the profile's `[program] max_file_size`),
/// decoded as `encoding` says.
#[derive(Clone, Copy, Debug)]
pub struct Reading {
    pub max_len: u64,
    pub encoding: TextEncoding,
}

impl Reading {
    /// The profile's limits and code page, the encoding `option` names
    /// in place of the code page.
    pub fn new(profile: &gcodec_profile::Profile, option: EncodingOption) -> Self {
        Self {
            max_len: *profile.program.max_file_size.get_ref(),
            encoding: option
                .encoding
                .map_or_else(|| profile.program.text_encoding(), TextEncoding::Fixed),
        }
    }

    /// Where no profile is chosen (`gcodec parse`, a profile's own file):
    /// the built-in profile's.
    pub fn builtin(option: EncodingOption) -> Self {
        match gcodec_profile::builtin() {
            Ok(profile) => Self::new(&profile, option),
            Err(_) => Self {
                max_len: gcodec_source::DEFAULT_MAX_FILE_SIZE,
                encoding: option
                    .encoding
                    .map_or_else(TextEncoding::default, TextEncoding::Fixed),
            },
        }
    }
}

/// Reads and checks a profile (the built-in one for `None`) in full
/// ([`gcodec_driver::load_profile`]), reporting its diagnostics against
/// the profile's text; a bad or unreadable profile is exit code 2.
pub fn load_profile(
    path: Option<&Path>,
    reporter: &Reporter,
) -> Result<gcodec_profile::Profile, u8> {
    let (file, loaded) = match path {
        Some(path) => {
            // A profile is read before any profile says how large a file
            // may be; TOML is UTF-8, which loading checks.
            let file = read(
                path,
                Reading::builtin(EncodingOption { encoding: None }),
                reporter,
            )?;
            let loaded = gcodec_driver::load_profile(&file);
            (file, loaded)
        }
        None => (
            gcodec_driver::builtin_profile_file(),
            gcodec_driver::load_builtin_profile(),
        ),
    };
    match loaded {
        Ok((profile, warnings)) => {
            reporter.report(&warnings.into(), Some(&file), file.name());
            Ok(profile)
        }
        Err(error) => {
            reporter.report(&error.diagnostics.into(), Some(&file), file.name());
            Err(EXIT_USAGE)
        }
    }
}

/// Reads a toolchanger scenario and makes the toolchanger that plays it
/// on `profile` ([`gcodec_driver::load_toolchanger`]), reporting its
/// diagnostics against the scenario's text; a bad or unreadable scenario
/// is exit code 2.
pub fn load_toolchanger(
    path: &Path,
    profile: &gcodec_profile::Profile,
    reporter: &Reporter,
) -> Result<gcodec_driver::toolchanger::SimulatedChanger, u8> {
    let file = read(
        path,
        Reading::builtin(EncodingOption { encoding: None }),
        reporter,
    )?;
    gcodec_driver::load_toolchanger(&file, profile).map_err(|error| {
        reporter.report(&error.diagnostics.into(), Some(&file), file.name());
        EXIT_USAGE
    })
}

/// Reads a file as `reading` says; an unreadable one is reported and is
/// exit code 2.
pub fn read(path: &Path, reading: Reading, reporter: &Reporter) -> Result<SourceFile, u8> {
    gcodec_driver::read_source(path, reading.max_len, reading.encoding).map_err(|d| {
        reporter.report(&vec![d].into(), None, &path.display().to_string());
        EXIT_USAGE
    })
}

/// Reads the definition files in order, as `reading` says; an unreadable
/// file or one with errors is reported and is exit code 2.
pub fn load_definitions(
    paths: &[PathBuf],
    reading: Reading,
    reporter: &Reporter,
) -> Result<gcodec_driver::Definitions, u8> {
    let mut definitions = gcodec_driver::Definitions::new();
    let mut bad = false;
    for path in paths {
        let file = read(path, reading, reporter)?;
        let diagnostics = definitions.load(&file);
        reporter.report(&diagnostics, Some(&file), file.name());
        bad |= diagnostics.has_errors();
    }
    if bad {
        Err(EXIT_USAGE)
    } else {
        Ok(definitions)
    }
}
