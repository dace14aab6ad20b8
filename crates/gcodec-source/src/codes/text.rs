//! The registry as text: `gcodec explain CODE`, `gcodec explain --list`
//! and the reference page `docs/diagnostics.md`.

use std::fmt::Write;

use super::{Code, all, areas};

/// What `gcodec explain CODE` prints: the name, level and alarm, the
/// summary, then the explanation as written (markdown reads as plain
/// text).
pub fn explain(code: &Code) -> String {
    let mut out = format!(
        "{}\n{}: {}\nThe check {}.\n\n",
        code.name(),
        facts(code),
        code.summary(),
        code.scope().description()
    );
    out.push_str(code.explanation());
    if !out.ends_with('\n') {
        out.push('\n');
    }
    out
}

/// What `gcodec explain --list` prints: every code with its level and
/// summary, one a line, in columns.
pub fn list() -> String {
    let width = all().iter().map(|c| c.name().len()).max().unwrap_or(0);
    let mut out = String::new();
    for code in all() {
        let _ = writeln!(
            out,
            "{:width$}  {:7}  {}",
            code.name(),
            code.level().name(),
            code.summary()
        );
    }
    out
}

/// `docs/diagnostics.md`: a section per area, per code its name, level,
/// alarm, summary and explanation with its examples.
pub fn reference() -> String {
    let mut out = String::from(
        "# Diagnostics\n\n\
         <!-- Generated from the registry in crates/gcodec-source/src/codes/ by\n\
         `GCODEC_UPDATE_DIAGNOSTICS=1 cargo test -p gcodec-source --test diagnostics`;\n\
         edit the registry, not this file. -->\n\n\
         Every diagnostic gcodec reports has a stable code, `gcodec::AREA::NAME`.\n\
         `gcodec explain CODE` prints a code's entry below, `gcodec explain --list`\n\
         lists them all. An example marked `wrong` makes gcodec report the code, one\n\
         marked `right` does not; `mpf` is the main program, `spf` a subprogram, `def`\n\
         a definition file (`--definitions`), `toml` a machine profile.\n",
    );
    for area in areas() {
        let _ = write!(out, "\n## `{}`: {}\n", area.name, area.title);
        for code in area.codes {
            let _ = write!(
                out,
                "\n### `{}`\n\n{}: {}. The check {}.\n\n{}",
                code.name(),
                facts(code),
                code.summary(),
                code.scope().description(),
                demote_headings(code.explanation())
            );
        }
    }
    out
}

/// "error, alarm 14080" (the alarm where there is one).
fn facts(code: &Code) -> String {
    match code.alarm() {
        Some(alarm) => format!("{}, alarm {alarm}", code.level().name()),
        None => code.level().name().to_owned(),
    }
}

/// An explanation's `## Example` as a heading below the code's own.
fn demote_headings(explanation: &str) -> String {
    let mut out = String::with_capacity(explanation.len() + 8);
    let mut in_fence = false;
    for line in explanation.lines() {
        if line.starts_with("```") {
            in_fence = !in_fence;
        }
        if !in_fence && line.starts_with("## ") {
            out.push_str("##");
        }
        out.push_str(line);
        out.push('\n');
    }
    out
}
