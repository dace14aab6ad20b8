//! Diagnostics whose level a profile policy chooses
//! (`unknown_mcode_policy`, `on_unresolved_tool`, …), shared by the
//! M-function and tool checks.

use gcodec_source::{Code, Diagnostic, Severity};

/// A diagnostic at the severity a profile policy chose: an error or a
/// warning.
pub(crate) fn by_policy(error: bool, code: &'static Code, message: String) -> Diagnostic {
    let severity = if error {
        Severity::Error
    } else {
        Severity::Warning
    };
    Diagnostic::new(code, message).with_severity(severity)
}
