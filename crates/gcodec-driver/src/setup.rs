//! What a run or a lowering is set up with: the files it reads and the
//! machine profile, checked in full.

use std::path::Path;

use gcodec_profile::Profile;
use gcodec_source::{Diagnostic, SourceFile, TextEncoding, codes};

/// Reads a file named on the command line, at most `max_len` bytes (the
/// profile's `[program] max_file_size`), decoded as `encoding` says; one
/// that cannot be read is `gcodec::io::read`, a FIFO or a device
/// `gcodec::io::not_a_file`, a larger file `gcodec::io::too_large`,
/// UTF-16 text `gcodec::io::utf16`.
pub fn read_source(
    path: &Path,
    max_len: u64,
    encoding: TextEncoding,
) -> Result<SourceFile, Diagnostic> {
    let file = SourceFile::read_capped(path, max_len).map_err(|e| {
        Diagnostic::new(e.code(), format!("cannot read `{}`: {e}", path.display()))
            .with_help(e.help())
    })?;
    Ok(file.decoded(encoding))
}

/// The built-in profile's file (`profiles/default.toml`, compiled in).
pub fn builtin_profile_file() -> SourceFile {
    SourceFile::new(gcodec_profile::BUILTIN_NAME, gcodec_profile::BUILTIN_TOML)
}

/// A machine profile that cannot be used: every problem, against the
/// profile's text.
#[derive(Debug)]
pub struct ProfileError {
    pub diagnostics: Vec<Diagnostic>,
}

/// Checks the profile in `file` in full: its form (TOML, keys, ranges,
/// references; [`gcodec_profile::load`]) and then its G codes against the
/// G-group table ([`gcodec_sema::check_profile`]). The profile and the
/// warnings of the second check, or every problem found.
pub fn load_profile(file: &SourceFile) -> Result<(Profile, Vec<Diagnostic>), ProfileError> {
    let Ok(text) = std::str::from_utf8(file.bytes()) else {
        let d = Diagnostic::new(
            codes::profile::SYNTAX,
            format!("`{}` is not UTF-8 text", file.name()),
        )
        .with_help("TOML files are UTF-8");
        return Err(ProfileError {
            diagnostics: vec![d],
        });
    };
    let profile = gcodec_profile::load(text).map_err(|diagnostics| ProfileError { diagnostics })?;
    let diagnostics = gcodec_sema::check_profile(&profile);
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(ProfileError { diagnostics });
    }
    Ok((profile, diagnostics))
}
