use std::borrow::Cow;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::{Code, Span};

/// How bad a diagnostic is. Only `Error` makes a command exit with 1.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Severity {
    /// A hint; the program is fine.
    Advice,
    /// The program runs, but probably not as meant, or not on every control.
    Warning,
    /// The real control would reject the program.
    Error,
}

impl Severity {
    /// The name used in JSON and in messages: `error`, `warning`, `advice`.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Advice => "advice",
            Self::Warning => "warning",
            Self::Error => "error",
        }
    }
}

/// A labelled span inside a diagnostic.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Label {
    /// Where.
    pub span: Span,
    /// What is there; shown next to the span.
    pub message: Option<Cow<'static, str>>,
}

/// A problem found in a part program, a profile or the environment.
///
/// `code` is stable (`gcodec::AREA::NAME`): tools and CI scripts may match on
/// it. The first label is the primary one.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Diagnostic {
    /// Stable code, `gcodec::AREA::NAME`, from the registry; serialised as
    /// its name.
    pub code: &'static Code,
    /// Error, warning or advice.
    pub severity: Severity,
    /// One sentence saying what is wrong.
    pub message: Cow<'static, str>,
    /// Source locations, primary first.
    pub labels: Vec<Label>,
    /// How to fix it, where a fix is known.
    pub help: Option<Cow<'static, str>>,
}

impl Diagnostic {
    /// A diagnostic with `code`, at the code's level, and `message`.
    pub fn new(code: &'static Code, message: impl Into<Cow<'static, str>>) -> Self {
        Self {
            code,
            severity: code.level(),
            message: message.into(),
            labels: Vec::new(),
            help: None,
        }
    }

    /// At another level than the code's: where a profile policy decides
    /// it (`unknown_mcode_policy`, `on_unresolved_tool`, …).
    pub fn with_severity(mut self, severity: Severity) -> Self {
        self.severity = severity;
        self
    }

    /// Adds a labelled span.
    pub fn with_label(mut self, span: Span, message: impl Into<Cow<'static, str>>) -> Self {
        self.labels.push(Label {
            span,
            message: Some(message.into()),
        });
        self
    }

    /// Adds help text.
    pub fn with_help(mut self, help: impl Into<Cow<'static, str>>) -> Self {
        self.help = Some(help.into());
        self
    }

    /// The primary span, if any.
    pub fn span(&self) -> Option<Span> {
        self.labels.first().map(|l| l.span)
    }

    /// True for error severity.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}
