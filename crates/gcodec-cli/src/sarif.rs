//! `--output-format sarif`: the diagnostics of every file as one SARIF
//! 2.1.0 log (`docs/schema/sarif-2.1.0.json`), in the subset GitHub code
//! scanning reads: one run, the codes that occur as its rules (with their
//! explanations as help), a result per diagnostic.
//!
//! - A rule is each code that occurs, not the whole registry: the log of
//!   a clean tree stays small, and a code's explanation is only read with
//!   its findings. The rules are sorted by code, so `ruleIndex` is stable.
//! - Artifact URIs are the files' names as shown, with forward slashes
//!   and percent-encoded: relative ones (to the folder `gcodec` ran in,
//!   the repository's top in CI) with `uriBaseId` `%SRCROOT%`, as
//!   GitHub's own tools write them; absolute ones as `file://` URIs,
//!   which `upload-sarif` makes relative to the checkout.
//! - Columns count the characters (Unicode code points) of the line as
//!   decoded (`columnKind` `unicodeCodePoints`), as every other format's;
//!   `charOffset`/`charLength` count characters of the decoded text too.
//! - No `helpUri`: gcodec has no published documentation address; the
//!   explanation is the rule's `help` (text and markdown).

use std::collections::BTreeMap;
use std::io::{self, Write};

use gcodec_driver::diagnostics::{DiagnosticRecord, FileReport, Position};
use gcodec_source::{Code, Diagnostic, Severity, SourceFile, Span, codes};
use percent_encoding::{AsciiSet, CONTROLS, utf8_percent_encode};
use serde_sarif::sarif;

/// The schema a log names (`$schema`): OASIS's address of the standard's
/// schema, of which `docs/schema/sarif-2.1.0.json` is a copy.
const SARIF_SCHEMA: &str =
    "https://docs.oasis-open.org/sarif/sarif/v2.1.0/os/schemas/sarif-schema-2.1.0.json";

/// The characters of a path escaped in a URI: all but the unreserved
/// ones, `/` and the sub-delimiters a path may hold.
const URI_PATH: &AsciiSet = &CONTROLS
    .add(b' ')
    .add(b'"')
    .add(b'#')
    .add(b'%')
    .add(b'<')
    .add(b'>')
    .add(b'?')
    .add(b'[')
    .add(b'\\')
    .add(b']')
    .add(b'^')
    .add(b'`')
    .add(b'{')
    .add(b'|')
    .add(b'}');

/// Writes the SARIF log of `files`' diagnostics, pretty-printed.
pub fn write_sarif(files: &[FileReport], out: &mut dyn Write) -> io::Result<()> {
    serde_json::to_writer_pretty(&mut *out, &sarif_log(files))?;
    writeln!(out)
}

/// The SARIF log of `files`' diagnostics.
pub fn sarif_log(files: &[FileReport]) -> sarif::Sarif {
    let mut rules: BTreeMap<&'static str, &'static Code> = BTreeMap::new();
    for file in files {
        for d in file.diagnostics.iter() {
            rules.insert(d.code.name(), d.code);
        }
    }
    let index: BTreeMap<&str, usize> = rules.keys().enumerate().map(|(i, c)| (*c, i)).collect();
    let results = files
        .iter()
        .flat_map(|file| file.diagnostics.iter().map(move |d| (file, d)))
        .map(|(file, d)| result(d, &file.name, file.file.as_deref(), index[d.code.name()]))
        .collect::<Vec<_>>();
    let driver = sarif::ToolComponent::builder()
        .name("gcodec")
        .version(env!("CARGO_PKG_VERSION"))
        .information_uri(env!("CARGO_PKG_REPOSITORY"))
        .rules(rules.values().map(|code| rule(code)).collect::<Vec<_>>())
        .build();
    let run = sarif::Run::builder()
        .tool(sarif::Tool::builder().driver(driver).build())
        .column_kind(serde_json::json!("unicodeCodePoints"))
        .results(results)
        .build();
    sarif::Sarif::builder()
        .schema(SARIF_SCHEMA)
        .version(serde_json::json!("2.1.0"))
        .runs(vec![run])
        .build()
}

/// A code as a rule: its summary, its explanation as the description
/// and the help, its default level.
fn rule(code: &Code) -> sarif::ReportingDescriptor {
    let explanation = code.explanation().trim_end();
    let first_paragraph = explanation
        .split("\n\n")
        .next()
        .unwrap_or_default()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let full = if first_paragraph.is_empty() {
        code.summary().to_owned()
    } else {
        first_paragraph
    };
    sarif::ReportingDescriptor::builder()
        .id(code.name())
        .short_description(text(code.summary()))
        .full_description(text(&full))
        .help(
            sarif::MultiformatMessageString::builder()
                .text(codes::explain(code))
                .markdown(explanation)
                .build(),
        )
        .default_configuration(
            sarif::ReportingConfiguration::builder()
                .level(serde_json::json!(level(code.level())))
                .build(),
        )
        .build()
}

fn text(text: &str) -> sarif::MultiformatMessageString {
    sarif::MultiformatMessageString::builder()
        .text(text)
        .build()
}

/// SARIF's level of a severity: advice is a `note`.
fn level(severity: Severity) -> &'static str {
    match severity {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Advice => "note",
    }
}

/// One diagnostic as a result: its primary place (or the file alone) as
/// its location, its other labels as related locations.
fn result(
    diagnostic: &Diagnostic,
    name: &str,
    file: Option<&SourceFile>,
    rule_index: usize,
) -> sarif::Result {
    let record = DiagnosticRecord::of(diagnostic, name, file);
    let mut message = record.message.clone();
    if let Some(help) = &record.help {
        message.push_str("\nhelp: ");
        message.push_str(help);
    }
    let spans: Vec<Span> = diagnostic.labels.iter().map(|l| l.span).collect();
    let mut labels = record.labels.iter().zip(spans);
    let primary = labels.next();
    let primary_location = location(
        name,
        file,
        primary.map(|(label, span)| (label.position, span)),
        primary.and_then(|(label, _)| label.message.as_deref()),
        None,
    );
    let related: Vec<sarif::Location> = labels
        .enumerate()
        .map(|(i, (label, span))| {
            location(
                name,
                file,
                Some((label.position, span)),
                label.message.as_deref(),
                Some(i as i64 + 1),
            )
        })
        .collect();
    let mut result = sarif::Result::builder()
        .rule_id(record.code.clone())
        .rule_index(rule_index as i64)
        .level(match record.level {
            Severity::Error => sarif::ResultLevel::Error,
            Severity::Warning => sarif::ResultLevel::Warning,
            Severity::Advice => sarif::ResultLevel::Note,
        })
        .message(sarif::Message::builder().text(message).build())
        .locations(vec![primary_location])
        .build();
    if !related.is_empty() {
        result.related_locations = Some(related);
    }
    result
}

/// A place in the file named `name`: its region where it has a position.
fn location(
    name: &str,
    file: Option<&SourceFile>,
    at: Option<(Position, Span)>,
    message: Option<&str>,
    id: Option<i64>,
) -> sarif::Location {
    let mut physical = sarif::PhysicalLocation::builder()
        .artifact_location(artifact(name))
        .build();
    if let (Some((position, span)), Some(file)) = (at, file) {
        physical.region = Some(region(position, span, file));
    }
    let mut location = sarif::Location::builder()
        .physical_location(physical)
        .build();
    location.message = message.map(|m| sarif::Message::builder().text(m).build());
    location.id = id;
    location
}

fn region(position: Position, span: Span, file: &SourceFile) -> sarif::Region {
    let number = |n: Option<u32>| n.map(i64::from);
    let before = chars(file, Span::new(0, span.start));
    let length = chars(file, span);
    sarif::Region {
        start_line: number(position.line),
        start_column: number(position.column),
        end_line: number(position.end_line),
        end_column: number(position.end_column),
        char_offset: Some(before),
        char_length: Some(length),
        ..sarif::Region::default()
    }
}

/// How many characters the decoded text of `span` has.
fn chars(file: &SourceFile, span: Span) -> i64 {
    i64::try_from(file.text(span).chars().count()).unwrap_or(i64::MAX)
}

/// The file named `name` as an artifact: a relative URI from the
/// source root, or a `file://` URI for an absolute path.
fn artifact(name: &str) -> sarif::ArtifactLocation {
    let slashed = name.replace('\\', "/");
    // A program found on the search path `.` is named `./NAME`.
    let slashed = slashed.strip_prefix("./").unwrap_or(&slashed).to_owned();
    let encoded = utf8_percent_encode(&slashed, URI_PATH).to_string();
    let absolute = slashed.starts_with('/') || slashed.as_bytes().get(1) == Some(&b':');
    if absolute {
        let root = if slashed.starts_with('/') { "" } else { "/" };
        sarif::ArtifactLocation::builder()
            .uri(format!("file://{root}{encoded}"))
            .build()
    } else {
        sarif::ArtifactLocation::builder()
            .uri(encoded)
            .uri_base_id("%SRCROOT%")
            .build()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_become_uris_from_the_source_root_or_file_uris() {
        let relative = artifact(r"lathe\part 1#2.mpf");
        assert_eq!(relative.uri.as_deref(), Some("lathe/part%201%232.mpf"));
        assert_eq!(relative.uri_base_id.as_deref(), Some("%SRCROOT%"));
        let absolute = artifact("/srv/nc/ä.mpf");
        assert_eq!(absolute.uri.as_deref(), Some("file:///srv/nc/%C3%A4.mpf"));
        assert_eq!(absolute.uri_base_id, None);
        assert_eq!(artifact("./SUB.SPF").uri.as_deref(), Some("SUB.SPF"));
        let windows = artifact(r"C:\nc\a.mpf");
        assert_eq!(windows.uri.as_deref(), Some("file:///C:/nc/a.mpf"));
    }

    #[test]
    fn char_offsets_count_characters_of_the_decoded_text() {
        let file = SourceFile::new("a.mpf", "; äö\nG1 ÄQ\n");
        let at = "; äö\nG1 Ä".len() as u32;
        let d = gcodec_source::Diagnostic::new(codes::parse::INVALID_WORD, "bad")
            .with_label(Span::new(at, at + 1), "here");
        let record = DiagnosticRecord::of(&d, "a.mpf", Some(&file));
        let region = region(record.position, Span::new(at, at + 1), &file);
        assert_eq!(region.char_offset, Some(9));
        assert_eq!(region.char_length, Some(1));
        assert_eq!(region.start_column, Some(5));
    }
}
