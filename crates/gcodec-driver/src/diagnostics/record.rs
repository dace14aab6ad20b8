//! A diagnostic as data: the objects of `--output-format json` (of
//! `check`, `lower` and `run`), whose JSON Schema is
//! `docs/schema/check.schema.json`.

use gcodec_source::{Diagnostic, Severity, SourceFile, Span};
use schemars::JsonSchema;
use serde::Serialize;

/// One diagnostic of one file. Lines and columns are 1-based, columns
/// counted in characters of the decoded line; an end is the position just
/// after the last character. A diagnostic without a place (a file that
/// cannot be read) has `null` for every position.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, JsonSchema)]
pub struct DiagnosticRecord {
    /// The file's name as shown: its path as walked or given.
    pub file: String,
    #[serde(flatten)]
    pub position: Position,
    /// The stable code, `gcodec::AREA::NAME`; `gcodec explain CODE`
    /// explains it.
    pub code: String,
    /// `error`, `warning` or `advice`, after the rule levels.
    pub level: Severity,
    pub message: String,
    /// How to fix it, where a fix is known.
    pub help: Option<String>,
    /// Every labelled place, the primary one first.
    pub labels: Vec<LabelRecord>,
}

/// A labelled place of a diagnostic.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, JsonSchema)]
pub struct LabelRecord {
    #[serde(flatten)]
    pub position: Position,
    /// What is there.
    pub message: Option<String>,
}

/// Where in the file: lines, columns and byte offsets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, JsonSchema)]
pub struct Position {
    /// The line of the start, from 1.
    pub line: Option<u32>,
    /// The column of the start, from 1, in characters.
    pub column: Option<u32>,
    /// The line of the end.
    pub end_line: Option<u32>,
    /// The column just after the last character, from 1, in characters.
    pub end_column: Option<u32>,
    /// Byte offset of the start in the file (after a UTF-8 byte-order
    /// mark).
    pub start_byte: Option<u32>,
    /// Byte offset just after the end.
    pub end_byte: Option<u32>,
}

impl DiagnosticRecord {
    /// The record of `diagnostic`, found in the file named `name` whose
    /// text is `file` (where it could be read).
    pub fn of(diagnostic: &Diagnostic, name: &str, file: Option<&SourceFile>) -> Self {
        let at = |span: Span| file.map(|f| Position::of(f, span)).unwrap_or_default();
        Self {
            file: name.to_owned(),
            position: diagnostic.span().map(at).unwrap_or_default(),
            code: diagnostic.code.name().to_owned(),
            level: diagnostic.severity,
            message: diagnostic.message.to_string(),
            help: diagnostic.help.as_ref().map(ToString::to_string),
            labels: diagnostic
                .labels
                .iter()
                .map(|label| LabelRecord {
                    position: at(label.span),
                    message: label.message.as_ref().map(ToString::to_string),
                })
                .collect(),
        }
    }
}

impl Position {
    fn of(file: &SourceFile, span: Span) -> Self {
        let (line, column) = line_column(file, span.start);
        let (end_line, end_column) = line_column(file, span.end);
        Self {
            line: Some(line),
            column: Some(column),
            end_line: Some(end_line),
            end_column: Some(end_column),
            start_byte: Some(span.start),
            end_byte: Some(span.end),
        }
    }
}

/// The 1-based line and character column of a byte offset.
fn line_column(file: &SourceFile, offset: u32) -> (u32, u32) {
    let (line, _) = file.line_col(offset);
    let start = (line.checked_sub(1))
        .and_then(|i| file.line_starts().get(i as usize))
        .copied()
        .unwrap_or(0);
    let before = file.text(Span::new(start, offset.max(start)));
    let chars = u32::try_from(before.chars().count()).unwrap_or(u32::MAX);
    (line, chars.saturating_add(1))
}

/// The JSON Schema of `--output-format json` (an array of
/// [`DiagnosticRecord`]s), as checked in under
/// `docs/schema/check.schema.json`.
pub fn check_json_schema() -> String {
    let schema = schemars::schema_for!(Vec<DiagnosticRecord>);
    let mut text = serde_json::to_string_pretty(&schema).unwrap_or_default();
    text.push('\n');
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcodec_source::codes;

    #[test]
    fn columns_count_characters_of_the_decoded_line() {
        let file = SourceFile::new("a.mpf", "N10 ; äöü\nG1 X1 ÄQ\n");
        let at = "N10 ; äöü\nG1 X1 Ä".len() as u32;
        let d = Diagnostic::new(codes::parse::INVALID_WORD, "bad")
            .with_label(Span::new(at, at + 1), "here");
        let record = DiagnosticRecord::of(&d, "a.mpf", Some(&file));
        assert_eq!(record.position.line, Some(2));
        assert_eq!(record.position.column, Some(8));
        assert_eq!(record.position.end_column, Some(9));
        assert_eq!(record.position.start_byte, Some(at));
        assert_eq!(record.labels[0].position, record.position);
    }

    #[test]
    fn a_diagnostic_without_a_place_has_no_position() {
        let d = Diagnostic::new(codes::io::READ, "cannot read");
        let record = DiagnosticRecord::of(&d, "gone.mpf", None);
        assert_eq!(record.position, Position::default());
        assert!(record.labels.is_empty());
    }
}
