//! Rendering diagnostics with miette.
//!
//! Everything a report shows that came from a program or a file name
//! (the message, labels, help, the file's lines and name) has its
//! control characters escaped (`crate::escape`).

use std::borrow::Cow;
use std::fmt;

use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan};

use crate::escape::escape_controls;
use crate::excerpt::Excerpt;
use crate::{Diagnostic, Diagnostics, Omitted, Severity, SourceFile};

/// How to render diagnostics.
#[derive(Clone, Copy, Debug, Default)]
pub struct RenderOptions {
    /// ANSI colours and Unicode box drawing (for a terminal).
    pub color: bool,
    /// Render at most this many reports, then one line counting the rest
    /// (`None`: all). A file with ten thousand unclosed `IF`s would
    /// otherwise print millions of lines.
    pub limit: Option<usize>,
}

/// Renders diagnostics about one file as miette reports, one after another.
pub fn render_diagnostics(
    diagnostics: &[Diagnostic],
    file: Option<&SourceFile>,
    options: RenderOptions,
) -> String {
    render(diagnostics, &Omitted::default(), file, options)
}

/// [`render_diagnostics`] for the diagnostics kept of a file: the line
/// counting those not shown counts those not kept too.
pub fn render_kept(
    diagnostics: &Diagnostics,
    file: Option<&SourceFile>,
    options: RenderOptions,
) -> String {
    render(diagnostics, diagnostics.omitted(), file, options)
}

fn render(
    diagnostics: &[Diagnostic],
    omitted: &Omitted,
    file: Option<&SourceFile>,
    options: RenderOptions,
) -> String {
    let theme = if options.color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme).with_width(100);
    let mut out = String::new();
    let shown = options
        .limit
        .map_or(diagnostics.len(), |limit| limit.min(diagnostics.len()));
    let (shown, hidden) = diagnostics.split_at(shown);
    for diagnostic in shown {
        let spans: Vec<_> = diagnostic.labels.iter().map(|l| l.span).collect();
        let report = Report {
            diagnostic,
            message: escape_controls(&diagnostic.message),
            excerpt: file.map(|file| Excerpt::new(file, &spans)),
        };
        if !out.is_empty() {
            out.push('\n');
        }
        if handler.render_report(&mut out, &report).is_err() {
            out.push_str(&format!("{}: {}\n", diagnostic.code, report.message));
        }
    }
    let not_shown = hidden.len() as u64 + omitted.total();
    if not_shown > 0 {
        let errors = hidden.iter().filter(|d| d.is_error()).count() as u64 + omitted.errors();
        out.push_str(&format!(
            "\n… and {not_shown} more diagnostics not shown ({errors} errors, {} others)\n",
            not_shown - errors
        ));
    }
    out
}

struct Report<'a> {
    diagnostic: &'a Diagnostic,
    /// The message, escaped.
    message: Cow<'a, str>,
    /// The lines the labels point at, when the file is known.
    excerpt: Option<Excerpt<'a>>,
}

impl fmt::Debug for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.diagnostic, f)
    }
}

impl fmt::Display for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Report<'_> {}

impl miette::Diagnostic for Report<'_> {
    fn code<'b>(&'b self) -> Option<Box<dyn fmt::Display + 'b>> {
        Some(Box::new(self.diagnostic.code))
    }

    fn severity(&self) -> Option<miette::Severity> {
        Some(match self.diagnostic.severity {
            Severity::Error => miette::Severity::Error,
            Severity::Warning => miette::Severity::Warning,
            Severity::Advice => miette::Severity::Advice,
        })
    }

    fn help<'b>(&'b self) -> Option<Box<dyn fmt::Display + 'b>> {
        self.diagnostic
            .help
            .as_deref()
            .map(|h| Box::new(escape_controls(h)) as Box<dyn fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.excerpt.as_ref().map(|e| e as &dyn miette::SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let excerpt = self.excerpt.as_ref()?;
        Some(Box::new(
            self.diagnostic
                .labels
                .iter()
                .zip(excerpt.labels())
                .enumerate()
                .map(|(i, (label, &span))| {
                    let text = label
                        .message
                        .as_deref()
                        .map(|m| escape_controls(m).into_owned());
                    if i == 0 {
                        LabeledSpan::new_primary_with_span(text, span)
                    } else {
                        LabeledSpan::new_with_span(text, span)
                    }
                }),
        ))
    }
}
