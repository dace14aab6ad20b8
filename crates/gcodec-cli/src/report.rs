//! What every command shares: how diagnostics are shown,
//! reading the files a command is given (programs, profiles, definition
//! files) and rendering what is wrong with them.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use gcodec_source::{Diagnostics, Encoding, RenderOptions, SourceFile, TextEncoding, render_kept};

use crate::exit::EXIT_USAGE;
use crate::output::to_stderr;

/// How diagnostics are shown.
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

/// The encoding of the files a command reads, where one is named.
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
    options: DiagnosticOptions,
) -> Result<gcodec_profile::Profile, u8> {
    let file = match path {
        // A profile is read before any profile says how large a file may
        // be; TOML is UTF-8, which loading checks.
        Some(path) => read(
            path,
            Reading::builtin(EncodingOption { encoding: None }),
            options,
        )?,
        None => gcodec_driver::builtin_profile_file(),
    };
    match gcodec_driver::load_profile(&file) {
        Ok((profile, warnings)) => {
            report(&warnings.into(), Some(&file), options);
            Ok(profile)
        }
        Err(error) => {
            report(&error.diagnostics.into(), Some(&file), options);
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
    options: DiagnosticOptions,
) -> Result<gcodec_driver::toolchanger::SimulatedChanger, u8> {
    let file = read(
        path,
        Reading::builtin(EncodingOption { encoding: None }),
        options,
    )?;
    gcodec_driver::load_toolchanger(&file, profile).map_err(|error| {
        report(&error.diagnostics.into(), Some(&file), options);
        EXIT_USAGE
    })
}

/// Renders `diagnostics` on stderr, against `file` where they have spans.
pub fn report(diagnostics: &Diagnostics, file: Option<&SourceFile>, options: DiagnosticOptions) {
    if diagnostics.is_empty() {
        return;
    }
    to_stderr(&render_kept(diagnostics, file, options.render_options()));
}

/// Reads a file as `reading` says; an unreadable one is reported and is
/// exit code 2.
pub fn read(path: &Path, reading: Reading, options: DiagnosticOptions) -> Result<SourceFile, u8> {
    gcodec_driver::read_source(path, reading.max_len, reading.encoding).map_err(|d| {
        report(&vec![d].into(), None, options);
        EXIT_USAGE
    })
}

/// Reads the definition files in order, as `reading` says; an unreadable
/// file or one with errors is reported and is exit code 2.
pub fn load_definitions(
    paths: &[PathBuf],
    reading: Reading,
    options: DiagnosticOptions,
) -> Result<gcodec_driver::Definitions, u8> {
    let mut definitions = gcodec_driver::Definitions::new();
    let mut bad = false;
    for path in paths {
        let file = read(path, reading, options)?;
        let diagnostics = definitions.load(&file);
        report(&diagnostics, Some(&file), options);
        bad |= diagnostics.has_errors();
    }
    if bad {
        Err(EXIT_USAGE)
    } else {
        Ok(definitions)
    }
}
