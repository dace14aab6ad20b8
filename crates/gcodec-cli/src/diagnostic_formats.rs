//! The formats every command that checks programs (`check`, `lower`,
//! `run`) writes its diagnostics in (`--output-format`): the diagnostics
//! of a list of files, each with its name, its text where it could be
//! read, and its diagnostics ([`FileReport`]).

use std::io::{self, Write};

use clap::ValueEnum;
use gcodec_driver::diagnostics::{DiagnosticRecord, FileReport};
use gcodec_source::{RenderOptions, Severity, escape_controls, render_kept};

use crate::sarif::write_sarif;

/// How diagnostics are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum DiagnosticFormat {
    /// Each diagnostic with the lines it points at, grouped per file.
    Full,
    /// One line per diagnostic: `file:line:col: level[code] message`.
    Concise,
    /// A JSON array of objects (`docs/schema/check.schema.json`).
    Json,
    /// GitHub Actions workflow commands (`::error file=…,line=…::…`): the
    /// diagnostics become annotations of the pull request.
    Github,
    /// A SARIF 2.1.0 log, for GitHub code scanning and other SARIF
    /// readers.
    Sarif,
}

impl DiagnosticFormat {
    /// Whether the format is text a person reads, whose control
    /// characters from a program are escaped ([`escape_controls`]); the
    /// others escape by their own rules or render escaped.
    pub fn is_plain_text(self) -> bool {
        self == Self::Concise
    }
}

/// Writes the diagnostics of `files` in `format`; `render` is how `full`
/// renders them.
pub fn write_diagnostics(
    format: DiagnosticFormat,
    files: &[FileReport],
    render: RenderOptions,
    out: &mut dyn Write,
) -> io::Result<()> {
    match format {
        DiagnosticFormat::Full => write_full(files, render, out),
        DiagnosticFormat::Concise => write_concise(files, out),
        DiagnosticFormat::Json => write_json(files, out),
        DiagnosticFormat::Github => write_github(files, out),
        DiagnosticFormat::Sarif => write_sarif(files, out),
    }
}

/// The diagnostics of `files` in `format` as text, escaped where the
/// format is plain text.
pub fn diagnostics_text(
    format: DiagnosticFormat,
    files: &[FileReport],
    render: RenderOptions,
) -> io::Result<String> {
    let mut bytes = Vec::new();
    write_diagnostics(format, files, render, &mut bytes)?;
    let text = String::from_utf8_lossy(&bytes);
    Ok(if format.is_plain_text() {
        escape_controls(&text).into_owned()
    } else {
        text.into_owned()
    })
}

/// miette's reports, file by file.
fn write_full(files: &[FileReport], render: RenderOptions, out: &mut dyn Write) -> io::Result<()> {
    for file in files.iter().filter(|f| f.diagnostics.total() > 0) {
        let text = render_kept(&file.diagnostics, file.file.as_deref(), render);
        // A file that could not be read has no text to name it.
        if file.file.is_none() {
            writeln!(out, "{}:", escape_controls(&file.name))?;
        }
        out.write_all(text.as_bytes())?;
    }
    Ok(())
}

/// One line per diagnostic shown; a file's diagnostics beyond those kept
/// are counted on one line.
fn write_concise(files: &[FileReport], out: &mut dyn Write) -> io::Result<()> {
    for file in files {
        for d in file.diagnostics.iter() {
            let record = DiagnosticRecord::of(d, &file.name, file.file.as_deref());
            let place = match (record.position.line, record.position.column) {
                (Some(line), Some(column)) => format!("{}:{line}:{column}", record.file),
                _ => record.file.clone(),
            };
            writeln!(
                out,
                "{place}: {}[{}] {}",
                record.level.name(),
                record.code,
                record.message
            )?;
        }
        let omitted = file.diagnostics.omitted().total();
        if omitted > 0 {
            writeln!(out, "{}: {omitted} more diagnostics not kept", file.name)?;
        }
    }
    Ok(())
}

/// Every diagnostic shown, as data, file by file.
fn records(files: &[FileReport]) -> impl Iterator<Item = DiagnosticRecord> + '_ {
    files.iter().flat_map(|file| {
        file.diagnostics
            .iter()
            .map(|d| DiagnosticRecord::of(d, &file.name, file.file.as_deref()))
    })
}

fn write_json(files: &[FileReport], out: &mut dyn Write) -> io::Result<()> {
    let records: Vec<DiagnosticRecord> = records(files).collect();
    serde_json::to_writer_pretty(&mut *out, &records)?;
    writeln!(out)
}

/// One workflow command per diagnostic: `error`, `warning` or `notice`
/// (advice), its place and its code as the annotation's title.
fn write_github(files: &[FileReport], out: &mut dyn Write) -> io::Result<()> {
    for record in records(files) {
        let command = match record.level {
            Severity::Error => "error",
            Severity::Warning => "warning",
            Severity::Advice => "notice",
        };
        write!(out, "::{command} file={}", github_property(&record.file))?;
        let p = record.position;
        let places = [
            ("line", p.line),
            ("col", p.column),
            ("endLine", p.end_line),
            ("endColumn", p.end_column),
        ];
        for (key, value) in places {
            if let Some(value) = value {
                write!(out, ",{key}={value}")?;
            }
        }
        let mut message = record.message;
        if let Some(help) = &record.help {
            message.push_str("\nhelp: ");
            message.push_str(help);
        }
        writeln!(
            out,
            ",title={}::{}",
            github_property(&record.code),
            github_data(&message)
        )?;
    }
    Ok(())
}

/// A workflow command's message: `%`, CR and LF escaped as GitHub reads
/// them back.
fn github_data(text: &str) -> String {
    text.replace('%', "%25")
        .replace('\r', "%0D")
        .replace('\n', "%0A")
}

/// A workflow command's property value: also `:` and `,`, which end it.
fn github_property(text: &str) -> String {
    github_data(text).replace(':', "%3A").replace(',', "%2C")
}
