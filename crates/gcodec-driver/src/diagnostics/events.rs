//! Diagnostics and events, each as the other: a program's diagnostics
//! reach the run as events, and a run's diagnostic events are rendered
//! as diagnostics.

use std::sync::Arc;

use gcodec_exec::event::{DiagnosticEvent, Event, EventKind, EventSource};
use gcodec_source::{Diagnostic, SourceFile};

/// A diagnostic of `file` as an event at its primary span (line 1,
/// column 1 without one).
pub(crate) fn diagnostic_event(d: Diagnostic, file: &SourceFile, file_name: &Arc<str>) -> Event {
    let (line, col) = d.span().map_or((1, 1), |span| file.line_col(span.start));
    Event {
        kind: EventKind::Diagnostic(DiagnosticEvent {
            code: d.code,
            severity: d.severity,
            message: d.message,
            alarm: None,
            help: d.help,
        }),
        source: EventSource {
            file: file_name.clone(),
            line,
            col,
            level: 0,
        },
    }
}

/// A run-time diagnostic as a [`Diagnostic`]: labelled at its block where
/// its file is known, its position in the message where not, its alarm
/// number after the message.
pub fn runtime_diagnostic(
    event: &DiagnosticEvent,
    source: &EventSource,
    file: Option<&SourceFile>,
) -> Diagnostic {
    let mut message = event.message.to_string();
    if let Some(alarm) = event.alarm {
        message.push_str(&format!(" (alarm {alarm})"));
    }
    let span = file.and_then(|f| f.line_span(source.line, source.col));
    if span.is_none() {
        message = format!("{}:{}:{}: {message}", source.file, source.line, source.col);
    }
    let mut diagnostic = Diagnostic::new(event.code, message).with_severity(event.severity);
    if let Some(span) = span {
        diagnostic = diagnostic.with_label(span, "the run is here");
    }
    diagnostic.help = event.help.clone();
    diagnostic
}
