use std::borrow::Cow;

use serde::Serialize;

use crate::Span;

/// How bad a diagnostic is. Only `Error` makes a command exit with 1.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
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
    /// Stable code, `gcodec::AREA::NAME`.
    pub code: &'static str,
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
    /// An error with `code` and `message`.
    pub fn error(code: &'static str, message: impl Into<Cow<'static, str>>) -> Self {
        Self {
            code,
            severity: Severity::Error,
            message: message.into(),
            labels: Vec::new(),
            help: None,
        }
    }

    /// A warning with `code` and `message`.
    pub fn warning(code: &'static str, message: impl Into<Cow<'static, str>>) -> Self {
        Self {
            severity: Severity::Warning,
            ..Self::error(code, message)
        }
    }

    /// Advice with `code` and `message`: something worth a look that the
    /// control itself accepts.
    pub fn advice(code: &'static str, message: impl Into<Cow<'static, str>>) -> Self {
        Self {
            severity: Severity::Advice,
            ..Self::error(code, message)
        }
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
