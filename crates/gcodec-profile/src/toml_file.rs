//! Reading a TOML file of gcodec's (a profile, a toolchanger scenario, a
//! check configuration) into its raw form: the syntax first, since a
//! syntax error makes schema errors meaningless, then the schema.

use gcodec_source::{Code, Diagnostic};
use serde::de::DeserializeOwned;

/// The codes and words a kind of TOML file reports its problems with.
#[derive(Clone, Copy, Debug)]
pub struct TomlKind {
    /// Text that is not TOML.
    pub syntax: &'static Code,
    /// TOML that does not fit the schema.
    pub schema: &'static Code,
    /// What the file is, in a message: `profile`.
    pub what: &'static str,
    /// Where its keys are documented, as help.
    pub help: &'static str,
}

/// `text` read as a `T`; a syntax or schema error as one diagnostic
/// labelled where the TOML parser found it.
pub fn read_toml<T: DeserializeOwned>(text: &str, kind: TomlKind) -> Result<T, Diagnostic> {
    if let Err(e) = text.parse::<toml::Table>() {
        return Err(toml_diagnostic(kind.syntax, &e, kind));
    }
    toml::from_str(text).map_err(|e| toml_diagnostic(kind.schema, &e, kind))
}

fn toml_diagnostic(code: &'static Code, error: &toml::de::Error, kind: TomlKind) -> Diagnostic {
    let message = error.message().trim().to_owned();
    let diagnostic =
        Diagnostic::new(code, format!("invalid {}: {message}", kind.what)).with_help(kind.help);
    match error.span() {
        Some(range) => diagnostic.with_label(crate::span(range), "here"),
        None => diagnostic,
    }
}
