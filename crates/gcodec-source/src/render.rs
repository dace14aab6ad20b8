//! Rendering diagnostics with miette.

use std::fmt;

use miette::{GraphicalReportHandler, GraphicalTheme, LabeledSpan, NamedSource, SourceSpan};

use crate::source::cp1252;
use crate::{Diagnostic, Severity, SourceFile};

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
    let theme = if options.color {
        GraphicalTheme::unicode()
    } else {
        GraphicalTheme::unicode_nocolor()
    };
    let handler = GraphicalReportHandler::new_themed(theme).with_width(100);
    let display = file.map(DisplaySource::new);
    let mut out = String::new();
    let shown = options
        .limit
        .map_or(diagnostics.len(), |limit| limit.min(diagnostics.len()));
    let (shown, hidden) = diagnostics.split_at(shown);
    for diagnostic in shown {
        let report = Report {
            diagnostic,
            source: display.as_ref(),
        };
        if !out.is_empty() {
            out.push('\n');
        }
        if handler.render_report(&mut out, &report).is_err() {
            out.push_str(&format!("{}: {}\n", diagnostic.code, diagnostic.message));
        }
    }
    if !hidden.is_empty() {
        let errors = hidden.iter().filter(|d| d.is_error()).count();
        out.push_str(&format!(
            "\n… and {} more diagnostics not shown ({errors} errors, {} others)\n",
            hidden.len(),
            hidden.len() - errors
        ));
    }
    out
}

/// The file as UTF-8 text for miette, with a map from stored byte offsets to
/// offsets in the decoded text (they differ where a Latin-1 byte became a
/// two-byte UTF-8 sequence).
struct DisplaySource {
    named: NamedSource<String>,
    offsets: Option<Vec<u32>>,
}

impl DisplaySource {
    fn new(file: &SourceFile) -> Self {
        let bytes = file.bytes();
        let (text, offsets) = match std::str::from_utf8(bytes) {
            Ok(s) => (s.to_owned(), None),
            Err(_) => {
                let mut text = String::with_capacity(bytes.len() + bytes.len() / 8);
                let mut offsets = Vec::with_capacity(bytes.len() + 1);
                for &b in bytes {
                    offsets.push(text.len() as u32);
                    text.push(cp1252(b));
                }
                offsets.push(text.len() as u32);
                (text, Some(offsets))
            }
        };
        Self {
            named: NamedSource::new(file.name(), text).with_language("SINUMERIK"),
            offsets,
        }
    }

    fn map(&self, offset: u32) -> usize {
        match &self.offsets {
            None => offset as usize,
            Some(map) => map
                .get(offset as usize)
                .copied()
                .unwrap_or_else(|| *map.last().unwrap_or(&0)) as usize,
        }
    }
}

struct Report<'a> {
    diagnostic: &'a Diagnostic,
    source: Option<&'a DisplaySource>,
}

impl fmt::Debug for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.diagnostic, f)
    }
}

impl fmt::Display for Report<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.diagnostic.message)
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
            .map(|h| Box::new(h) as Box<dyn fmt::Display>)
    }

    fn source_code(&self) -> Option<&dyn miette::SourceCode> {
        self.source.map(|s| &s.named as &dyn miette::SourceCode)
    }

    fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
        let source = self.source?;
        Some(Box::new(self.diagnostic.labels.iter().enumerate().map(
            move |(i, label)| {
                let start = source.map(label.span.start);
                let end = source.map(label.span.end).max(start);
                let span = SourceSpan::from(start..end);
                let text = label.message.as_deref().map(str::to_owned);
                if i == 0 {
                    LabeledSpan::new_primary_with_span(text, span)
                } else {
                    LabeledSpan::new_with_span(text, span)
                }
            },
        )))
    }
}
