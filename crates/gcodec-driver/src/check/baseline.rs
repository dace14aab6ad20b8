//! The baseline of a check (`--baseline FILE`, written by
//! `--write-baseline FILE`): the findings a repository accepts for now,
//! so that a check fails only on new ones.
//!
//! The file is JSON, pretty-printed and sorted, so that it diffs well:
//! an object with `version` (1) and `entries`, each an object with
//! `file`, `code` (the full name), `text` and `count` (`docs/linting.md`
//! shows one).
//!
//! An entry is a file (its path relative to the baseline's folder, `/`
//! between folders; as shown where it is outside), a code, and the
//! fingerprint `text`: the line the finding's primary span starts on,
//! trimmed, at most [`MAX_TEXT_CHARS`] characters ("" for a finding
//! without a place). Not the line number: a finding stays matched when
//! lines are added above it, and becomes new when its own line changes.
//! `count` is how many findings share the three (two `M77` on one
//! line, a block repeated): a baseline matches as many findings as it
//! counts, so one more copy of a known problem is new (as eslint's
//! bulk suppressions count per file and rule, here per line).
//! Findings counted but not kept (§7) have no line and are not written.

use std::collections::BTreeMap;
use std::path::Path;

use gcodec_source::{Code, Diagnostic, SourceFile, Span, codes};
use serde::{Deserialize, Serialize};

use super::{CheckReport, FileReport};

/// The version of the file's form.
const VERSION: u32 = 1;

/// The longest fingerprint kept, in characters.
pub const MAX_TEXT_CHARS: usize = 120;

/// A baseline file, read or to write.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Baseline {
    version: u32,
    entries: Vec<Entry>,
}

/// Findings of one code on one line of one file.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Entry {
    pub file: String,
    pub code: &'static Code,
    /// The line the findings start on, trimmed.
    pub text: String,
    pub count: u64,
}

/// What applying a baseline did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Applied {
    /// Findings the baseline matched, dropped from the report.
    pub matched: u64,
    /// Findings the baseline counts that were not found: fixed since it
    /// was written.
    pub fixed: u64,
}

/// A finding's key: file, code name, text.
type Key = (String, &'static str, String);

impl Baseline {
    /// Every finding of `report` (kept ones, at their levels), files
    /// named relative to `folder` (the baseline's).
    pub fn of(report: &CheckReport, folder: &Path) -> Self {
        let mut counts: BTreeMap<Key, (&'static Code, u64)> = BTreeMap::new();
        for file in &report.files {
            for d in file.diagnostics.iter() {
                let key = key(file, d, folder);
                counts.entry(key).or_insert((d.code, 0)).1 += 1;
            }
        }
        let entries = counts
            .into_iter()
            .map(|((file, _, text), (code, count))| Entry {
                file,
                code,
                text,
                count,
            })
            .collect();
        Self {
            version: VERSION,
            entries,
        }
    }

    /// How many findings the baseline counts.
    pub fn findings(&self) -> u64 {
        self.entries.iter().map(|e| e.count).sum()
    }

    /// The entries, sorted by file, code and text.
    pub fn entries(&self) -> &[Entry] {
        &self.entries
    }

    /// The file's text.
    pub fn to_json(&self) -> String {
        let mut text = serde_json::to_string_pretty(self).unwrap_or_default();
        text.push('\n');
        text
    }

    /// Reads the baseline in `file`; one that is not a baseline is a
    /// `gcodec::check::bad_baseline` diagnostic into its text.
    pub fn read(file: &SourceFile) -> Result<Self, Diagnostic> {
        let bad = |message: String| Diagnostic::new(codes::check::BAD_BASELINE, message);
        let help = "write it again with `gcodec check --write-baseline FILE`";
        let baseline: Self = serde_json::from_slice(file.bytes()).map_err(|e| {
            let mut d = bad(format!("`{}` is not a baseline: {e}", file.name())).with_help(help);
            if let Some(at) = offset(file, e.line(), e.column()) {
                d = d.with_label(Span::new(at, at), "here");
            }
            d
        })?;
        if baseline.version != VERSION {
            return Err(bad(format!(
                "`{}` is a baseline of version {}; this gcodec reads version {VERSION}",
                file.name(),
                baseline.version
            ))
            .with_help(help));
        }
        Ok(baseline)
    }

    /// Drops from `report` the findings the baseline matches (files
    /// named relative to `folder`, the baseline's), as many of each as it
    /// counts.
    pub fn apply(&self, report: &mut CheckReport, folder: &Path) -> Applied {
        let mut left: BTreeMap<Key, u64> = BTreeMap::new();
        for entry in &self.entries {
            let key = (entry.file.clone(), entry.code.name(), entry.text.clone());
            *left.entry(key).or_default() += entry.count;
        }
        let mut applied = Applied::default();
        for file in &mut report.files {
            let keys: Vec<Key> = file
                .diagnostics
                .iter()
                .map(|d| key(file, d, folder))
                .collect();
            let mut keys = keys.into_iter();
            file.diagnostics.retain(|_| {
                let Some(key) = keys.next() else {
                    return true;
                };
                match left.get_mut(&key) {
                    Some(n) if *n > 0 => {
                        *n -= 1;
                        applied.matched += 1;
                        false
                    }
                    _ => true,
                }
            });
        }
        applied.fixed = left.values().sum();
        applied
    }
}

/// The key of `d`, a finding of `file`.
fn key(file: &FileReport, d: &Diagnostic, folder: &Path) -> Key {
    let text = match (&file.file, d.span()) {
        (Some(source), Some(span)) => line_text(source, span.start),
        _ => String::new(),
    };
    (relative_name(&file.name, folder), d.code.name(), text)
}

/// `name` relative to `folder` with `/` between folders, where it is
/// inside it; else as it is.
fn relative_name(name: &str, folder: &Path) -> String {
    let absolute = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let path = absolute(Path::new(name));
    match path.strip_prefix(absolute(folder)) {
        Ok(inside) => (inside.components())
            .map(|c| c.as_os_str().to_string_lossy())
            .collect::<Vec<_>>()
            .join("/"),
        Err(_) => name.to_owned(),
    }
}

/// The line of `offset`, trimmed, at most [`MAX_TEXT_CHARS`] characters.
fn line_text(file: &SourceFile, offset: u32) -> String {
    let (line, _) = file.line_col(offset);
    let Some(span) = file.line_span(line, 1) else {
        return String::new();
    };
    file.text(span)
        .trim()
        .chars()
        .take(MAX_TEXT_CHARS)
        .collect()
}

/// The byte offset of a 1-based line and column of serde_json's.
fn offset(file: &SourceFile, line: usize, column: usize) -> Option<u32> {
    let start = *file.line_starts().get(line.checked_sub(1)?)?;
    let at = start.checked_add(u32::try_from(column.saturating_sub(1)).ok()?)?;
    Some(at.min(file.bytes().len() as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Arc;

    fn report(text: &str, lines: &[usize]) -> CheckReport {
        let file = SourceFile::new("dir/a.mpf", text);
        let diagnostics = lines
            .iter()
            .map(|&line| {
                let start = file.line_starts()[line - 1] + 4;
                Diagnostic::new(codes::lower::UNKNOWN_M_FUNCTION, "M77")
                    .with_label(Span::new(start, start + 3), "")
            })
            .collect();
        CheckReport {
            files: vec![FileReport {
                name: "dir/a.mpf".into(),
                file: Some(Arc::new(file)),
                diagnostics,
            }],
        }
    }

    #[test]
    fn entries_count_findings_per_file_code_and_line_text() {
        let report = report("N10 M77\nN20 M77\n  N10 M77  \n", &[1, 2, 3]);
        let baseline = Baseline::of(&report, Path::new("dir"));
        let entries: Vec<(&str, &str, u64)> = (baseline.entries().iter())
            .map(|e| (e.file.as_str(), e.text.as_str(), e.count))
            .collect();
        assert_eq!(entries, [("a.mpf", "N10 M77", 2), ("a.mpf", "N20 M77", 1)]);
        let back = Baseline::read(&SourceFile::new("b.json", baseline.to_json()));
        assert_eq!(back, Ok(baseline));
    }

    #[test]
    fn a_baseline_matches_as_many_as_it_counts_whatever_the_line_number() {
        let old = report("N10 M77\nN20 M30\n", &[1]);
        let baseline = Baseline::of(&old, Path::new("dir"));
        let mut shifted = report("; a new first line\nN10 M77\nN10 M77\nN20 M30\n", &[2, 3]);
        let applied = baseline.apply(&mut shifted, Path::new("dir"));
        assert_eq!(
            applied,
            Applied {
                matched: 1,
                fixed: 0
            }
        );
        assert_eq!(shifted.files[0].diagnostics.len(), 1);
        let mut fixed = report("N10 M30\n", &[]);
        let applied = baseline.apply(&mut fixed, Path::new("dir"));
        assert_eq!(
            applied,
            Applied {
                matched: 0,
                fixed: 1
            }
        );
    }

    #[test]
    fn what_is_no_baseline_is_a_diagnostic_into_it() {
        for text in [
            "{\"version\": 1, \"entries\": [}",
            "{\"version\": 1, \"entries\": [], \"extra\": 0}",
            &format!(
                "{{\"version\": 1, \"entries\": [{{\"file\": \"a\", \"code\": \"{}x\", \"text\": \"\", \"count\": 1}}]}}",
                codes::lower::NOT_LOWERED.name()
            ),
            "{\"version\": 2, \"entries\": []}",
        ] {
            let error = Baseline::read(&SourceFile::new("b.json", text)).expect_err(text);
            assert_eq!(error.code, codes::check::BAD_BASELINE, "{text}");
        }
    }
}
