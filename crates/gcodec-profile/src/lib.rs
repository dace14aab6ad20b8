//! Machine profiles: what a machine has and how its control is configured
//! (axes, tool change, tool table, M-function and work-offset policies,
//! skip levels, limits, subprogram search paths), read from TOML.
//!
//! [`load`] parses and checks a profile; every problem is a
//! [`Diagnostic`] pointing into the TOML, and all of them are reported in
//! one pass. [`builtin`] is `profiles/default.toml`, compiled in so that
//! gcodec works with no profile given, and precompiled (`builtin/`) so
//! that no start parses it. [`load_scenario`] reads a
//! toolchanger scenario (the simulated changer's behaviour and the faults
//! to inject) the same way.
//!
//! The checks that need the G-group registry (`modal_defaults` codes and
//! groups, `[g_codes] unsupported` names, `legacy_aliases` keys) are
//! `gcodec_sema::check_profile`, run after [`load`]. The registry itself is
//! `gcodec_lang::ggroups`; [`reset_defaults`] and [`m_class`] read it
//! with a profile's settings. Not built yet: the profile's use by the executor.

mod builtin;
mod group8;
mod m_classes;
mod reset;
mod scenario;
mod schema;
pub mod system_variables;
mod toml_file;
mod validate;

pub use group8::{group8_index, group8_range};
pub use m_classes::m_class;
pub use reset::reset_defaults;
pub use scenario::{InjectAction, InjectAt, Injection, Scenario, load_scenario};
pub use schema::*;
pub use toml_file::{TomlKind, read_toml};

use gcodec_source::{Diagnostic, Span, codes};

/// The text of the built-in profile.
pub const BUILTIN_TOML: &str = include_str!("../../../profiles/default.toml");

/// The name the built-in profile has in diagnostics and dumps.
pub const BUILTIN_NAME: &str = "<built-in profiles/default.toml>";

/// Parses and checks a profile. On error, every diagnostic found, with
/// spans into `text`.
pub fn load(text: &str) -> Result<Profile, Vec<Diagnostic>> {
    let profile: Profile = read_toml(text, PROFILE_TOML).map_err(|d| vec![d])?;
    let mut problems = validate::check(&profile);
    problems.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    if problems.iter().any(Diagnostic::is_error) {
        Err(problems)
    } else {
        Ok(profile)
    }
}

/// The built-in profile: `profiles/default.toml` as [`load`] reads it,
/// built by precompiled code instead of parsed (a test keeps the two the
/// same). Never an error; the `Result` is [`load`]'s, which its callers
/// handle alike.
pub fn builtin() -> Result<Profile, Vec<Diagnostic>> {
    Ok(builtin::profile())
}

const PROFILE_TOML: TomlKind = TomlKind {
    syntax: codes::profile::SYNTAX,
    schema: codes::profile::SCHEMA,
    what: "profile",
    help: "see profiles/README.md for the profile schema",
};

/// A byte range of the TOML as a span.
pub(crate) fn span(range: std::ops::Range<usize>) -> Span {
    Span::new(range.start as u32, range.end as u32)
}
