//! What every command shares: how diagnostics are shown,
//! reading the files a command is given (programs, profiles, definition
//! files) and rendering what is wrong with them.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use gcodec_source::{Diagnostics, RenderOptions, SourceFile, render_kept};

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
        RenderOptions {
            color: std::io::stderr().is_terminal() && std::env::var_os("NO_COLOR").is_none(),
            limit: (self.max_diagnostics > 0).then_some(self.max_diagnostics),
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
        // A profile is read before any profile says how large a file may be.
        Some(path) => read(path, builtin_max_file_size(), options)?,
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

/// Renders `diagnostics` on stderr, against `file` where they have spans.
pub fn report(diagnostics: &Diagnostics, file: Option<&SourceFile>, options: DiagnosticOptions) {
    if diagnostics.is_empty() {
        return;
    }
    to_stderr(&render_kept(diagnostics, file, options.render_options()));
}

/// The largest file read where no profile is chosen (`gcodec parse`, a
/// profile's own file): the built-in profile's `[program] max_file_size`.
pub fn builtin_max_file_size() -> u64 {
    gcodec_profile::builtin().map_or(gcodec_source::DEFAULT_MAX_FILE_SIZE, |profile| {
        *profile.program.max_file_size.get_ref()
    })
}

/// Reads a file of at most `max_len` bytes; an unreadable one is reported
/// and is exit code 2.
pub fn read(path: &Path, max_len: u64, options: DiagnosticOptions) -> Result<SourceFile, u8> {
    gcodec_driver::read_source(path, max_len).map_err(|d| {
        report(&vec![d].into(), None, options);
        EXIT_USAGE
    })
}

/// Reads the definition files in order, at most `max_len` bytes each;
/// an unreadable file or one with errors is reported and is exit code 2.
pub fn load_definitions(
    paths: &[PathBuf],
    max_len: u64,
    options: DiagnosticOptions,
) -> Result<gcodec_driver::Definitions, u8> {
    let mut definitions = gcodec_driver::Definitions::new();
    let mut bad = false;
    for path in paths {
        let file = read(path, max_len, options)?;
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
