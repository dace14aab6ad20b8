//! What a check found: per file, its text and its diagnostics at the
//! levels in force, in a stable order; and counts.

use gcodec_source::{Code, Severity};

use crate::diagnostics::FileReport;

/// Every file checked, sorted by name.
#[derive(Debug, Default)]
pub struct CheckReport {
    pub files: Vec<FileReport>,
}

/// How many diagnostics a check found at each level, and in how many
/// files.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub files: usize,
    pub files_with_findings: usize,
    pub errors: u64,
    pub warnings: u64,
    pub advice: u64,
}

impl CheckReport {
    /// True if any diagnostic, shown or not, is an error.
    pub fn has_errors(&self) -> bool {
        self.files.iter().any(|f| f.diagnostics.has_errors())
    }

    /// The counts of the whole check.
    pub fn counts(&self) -> Counts {
        let mut counts = Counts {
            files: self.files.len(),
            ..Counts::default()
        };
        for (_, severity, n) in self.by_code() {
            match severity {
                Severity::Error => counts.errors += n,
                Severity::Warning => counts.warnings += n,
                Severity::Advice => counts.advice += n,
            }
        }
        counts.files_with_findings = self
            .files
            .iter()
            .filter(|f| f.diagnostics.total() > 0)
            .count();
        counts
    }

    /// How many diagnostics of each code and level, kept or not: the most
    /// frequent first, then by code.
    pub fn by_code(&self) -> Vec<(&'static Code, Severity, u64)> {
        let mut counts: Vec<(&'static Code, Severity, u64)> = Vec::new();
        let mut add = |code: &'static Code, severity: Severity, n: u64| match counts
            .iter_mut()
            .find(|(c, s, _)| *c == code && *s == severity)
        {
            Some((_, _, count)) => *count += n,
            None => counts.push((code, severity, n)),
        };
        for file in &self.files {
            for d in file.diagnostics.iter() {
                add(d.code, d.severity, 1);
            }
            for &(code, severity, n) in file.diagnostics.omitted().by_code() {
                add(code, severity, n);
            }
        }
        counts.sort_by(|a, b| b.2.cmp(&a.2).then_with(|| a.0.name().cmp(b.0.name())));
        counts
    }
}
