//! What a run or a lowering is set up with: the files it reads and the
//! machine profile, checked in full.

use std::path::Path;

use gcodec_exec::toolchanger::SimulatedChanger;
use gcodec_profile::Profile;
use gcodec_source::{Code, Diagnostic, SourceFile, TextEncoding, codes};

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

/// The built-in profile's file (`profiles/default.toml`, compiled in):
/// what diagnostics about the built-in profile point into.
pub fn builtin_profile_file() -> SourceFile {
    SourceFile::new(gcodec_profile::BUILTIN_NAME, gcodec_profile::BUILTIN_TOML)
}

/// The built-in profile checked as [`load_profile`] checks
/// [`builtin_profile_file`], with the same result, but precompiled
/// ([`gcodec_profile::builtin`]): no TOML is parsed, only the G-code
/// check runs. Every start without `--profile` takes this path.
pub fn load_builtin_profile() -> Result<(Profile, Vec<Diagnostic>), ProfileError> {
    let profile = gcodec_profile::builtin().map_err(|diagnostics| ProfileError { diagnostics })?;
    checked(profile)
}

/// A machine profile that cannot be used: every problem, against the
/// profile's text.
#[derive(Debug)]
pub struct ProfileError {
    pub diagnostics: Vec<Diagnostic>,
}

/// The text of a TOML file; one that is not UTF-8 is `code`.
fn toml_text<'a>(file: &'a SourceFile, code: &'static Code) -> Result<&'a str, ProfileError> {
    std::str::from_utf8(file.bytes()).map_err(|_| {
        let d = Diagnostic::new(code, format!("`{}` is not UTF-8 text", file.name()))
            .with_help("TOML files are UTF-8");
        ProfileError {
            diagnostics: vec![d],
        }
    })
}

/// Reads the toolchanger scenario in `file` (`gcodec run --toolchanger`)
/// and makes the simulated toolchanger of `profile` that plays it: every
/// problem (TOML, keys, ranges, an `initial_tool` the tool table lacks) is
/// a diagnostic into the scenario's text.
pub fn load_toolchanger(
    file: &SourceFile,
    profile: &Profile,
) -> Result<SimulatedChanger, ProfileError> {
    let text = toml_text(file, codes::scenario::SYNTAX)?;
    let scenario =
        gcodec_profile::load_scenario(text).map_err(|diagnostics| ProfileError { diagnostics })?;
    SimulatedChanger::new(profile, &scenario).map_err(|d| ProfileError {
        diagnostics: vec![d],
    })
}

/// Checks the profile in `file` in full: its form (TOML, keys, ranges,
/// references; [`gcodec_profile::load`]) and then its G codes against the
/// G-group table ([`gcodec_sema::check_profile`]). The profile and the
/// warnings of the second check, or every problem found.
pub fn load_profile(file: &SourceFile) -> Result<(Profile, Vec<Diagnostic>), ProfileError> {
    let text = toml_text(file, codes::profile::SYNTAX)?;
    let profile = gcodec_profile::load(text).map_err(|diagnostics| ProfileError { diagnostics })?;
    checked(profile)
}

/// A loaded profile after its check against the G-group table.
fn checked(profile: Profile) -> Result<(Profile, Vec<Diagnostic>), ProfileError> {
    let diagnostics = gcodec_sema::check_profile(&profile);
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(ProfileError { diagnostics });
    }
    Ok((profile, diagnostics))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The precompiled built-in profile is what checking its text gives,
    /// spans and warnings included (`Spanned`'s `==` ignores spans; its
    /// `Debug` shows them).
    #[test]
    fn the_builtin_profile_is_its_file_checked() {
        let (precompiled, precompiled_warnings) = load_builtin_profile().expect("precompiled");
        let (loaded, loaded_warnings) = load_profile(&builtin_profile_file()).expect("loaded");
        assert_eq!(format!("{precompiled:#?}"), format!("{loaded:#?}"));
        assert_eq!(
            format!("{precompiled_warnings:?}"),
            format!("{loaded_warnings:?}")
        );
    }
}
