//! Diagnostics kept in memory up to a bound, every one counted.
//!
//! One line of twelve million axis words gave as many `repeated_axis`
//! diagnostics, all kept (15 GB). A [`Diagnostics`] keeps at most
//! [`MAX_KEPT_PER_BLOCK`] of a block and, once a file's are gathered,
//! [`MAX_KEPT_PER_FILE`]; the rest are counted by code and level, so the
//! exit code and the count of what is not shown still count them all.

use std::ops::{Deref, DerefMut};

use crate::{Code, Diagnostic, Severity};

/// Diagnostics of one block kept (the first ones found); a block's
/// diagnostics beyond them are counted.
pub const MAX_KEPT_PER_BLOCK: usize = 16;

/// Diagnostics of one file kept once gathered (the first ones found);
/// those beyond are counted.
pub const MAX_KEPT_PER_FILE: usize = 100_000;

/// Diagnostics not kept, counted by code and level.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Omitted(Vec<(&'static Code, Severity, u64)>);

impl Omitted {
    fn count(&mut self, code: &'static Code, severity: Severity, n: u64) {
        match self
            .0
            .iter_mut()
            .find(|(c, s, _)| std::ptr::eq(*c, code) && *s == severity)
        {
            Some((_, _, count)) => *count += n,
            None => self.0.push((code, severity, n)),
        }
    }

    /// Each code and level with how many were not kept.
    pub fn by_code(&self) -> &[(&'static Code, Severity, u64)] {
        &self.0
    }

    /// How many were not kept.
    pub fn total(&self) -> u64 {
        self.0.iter().map(|(_, _, n)| n).sum()
    }

    /// How many errors were not kept.
    pub fn errors(&self) -> u64 {
        self.0
            .iter()
            .filter(|(_, s, _)| *s == Severity::Error)
            .map(|(_, _, n)| n)
            .sum()
    }
}

/// A file's or a part's diagnostics: the first ones kept in full (read
/// them as a slice), the rest counted ([`Diagnostics::omitted`]).
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    kept: Vec<Diagnostic>,
    /// Where the current block's diagnostics start in `kept`, once
    /// [`Diagnostics::begin_block`] was called.
    block_start: Option<usize>,
    omitted: Omitted,
}

impl Diagnostics {
    pub fn new() -> Self {
        Self::default()
    }

    /// The diagnostics pushed from now on are a new block's.
    pub fn begin_block(&mut self) {
        self.block_start = Some(self.kept.len());
    }

    /// Keeps `diagnostic`, or counts it where its block has
    /// [`MAX_KEPT_PER_BLOCK`] kept.
    pub fn push(&mut self, diagnostic: Diagnostic) {
        match self.block_start {
            Some(start) if self.kept.len() - start >= MAX_KEPT_PER_BLOCK => {
                self.omitted.count(diagnostic.code, diagnostic.severity, 1);
            }
            _ => self.kept.push(diagnostic),
        }
    }

    /// Counts a diagnostic of `code` at `severity` as omitted without
    /// keeping it: for a producer that already keeps as many as a file
    /// may have.
    pub fn count_omitted(&mut self, code: &'static Code, severity: Severity) {
        self.omitted.count(code, severity, 1);
    }

    /// Gathers `other` (a later part of the same file) into these: kept
    /// while fewer than [`MAX_KEPT_PER_FILE`] are, counted beyond.
    pub fn append(&mut self, other: Diagnostics) {
        let room = MAX_KEPT_PER_FILE.saturating_sub(self.kept.len());
        let mut kept = other.kept;
        for d in kept.drain(room.min(kept.len())..) {
            self.omitted.count(d.code, d.severity, 1);
        }
        self.kept.append(&mut kept);
        for &(code, severity, n) in other.omitted.by_code() {
            self.omitted.count(code, severity, n);
        }
        self.block_start = None;
    }

    /// Those not kept.
    pub fn omitted(&self) -> &Omitted {
        &self.omitted
    }

    /// How many were found, kept or not.
    pub fn total(&self) -> u64 {
        self.kept.len() as u64 + self.omitted.total()
    }

    /// True if any diagnostic, kept or not, is an error.
    pub fn has_errors(&self) -> bool {
        self.omitted.errors() > 0 || self.kept.iter().any(Diagnostic::is_error)
    }

    /// Sorts the kept ones by where they start (a stable sort: those at
    /// one place stay in the order found); those without a place first.
    pub fn sort_by_start(&mut self) {
        self.kept.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    }

    /// The same diagnostics, each at the level `level` gives it from its
    /// code and level, or left out where it gives none: kept ones and
    /// counted ones alike, so that the counts stay true.
    pub fn releveled(self, level: impl Fn(&'static Code, Severity) -> Option<Severity>) -> Self {
        let mut omitted = Omitted::default();
        for &(code, severity, n) in self.omitted.by_code() {
            if let Some(severity) = level(code, severity) {
                omitted.count(code, severity, n);
            }
        }
        let kept = self
            .kept
            .into_iter()
            .filter_map(|d| {
                let severity = level(d.code, d.severity)?;
                Some(d.with_severity(severity))
            })
            .collect();
        Self {
            kept,
            block_start: None,
            omitted,
        }
    }

    /// Keeps only the kept ones `keep` says (a suppression, a baseline);
    /// those counted are left as they are: they have no place to judge.
    pub fn retain(&mut self, keep: impl FnMut(&Diagnostic) -> bool) {
        self.kept.retain(keep);
        self.block_start = None;
    }

    /// Forgets the counted ones whose code `forget` says (a suppression
    /// of a whole file); returns how many were forgotten.
    pub fn forget_omitted(&mut self, forget: impl Fn(&'static Code) -> bool) -> u64 {
        let before = self.omitted.total();
        self.omitted.0.retain(|(code, _, _)| !forget(code));
        before - self.omitted.total()
    }

    /// Forgets every one, kept or counted.
    pub fn clear(&mut self) {
        *self = Self::default();
    }
}

/// The same diagnostics kept and counted (where blocks began aside).
impl PartialEq for Diagnostics {
    fn eq(&self, other: &Self) -> bool {
        self.kept == other.kept && self.omitted == other.omitted
    }
}

impl Deref for Diagnostics {
    type Target = [Diagnostic];

    fn deref(&self) -> &[Diagnostic] {
        &self.kept
    }
}

impl DerefMut for Diagnostics {
    fn deref_mut(&mut self) -> &mut [Diagnostic] {
        &mut self.kept
    }
}

impl Extend<Diagnostic> for Diagnostics {
    fn extend<I: IntoIterator<Item = Diagnostic>>(&mut self, diagnostics: I) {
        for d in diagnostics {
            self.push(d);
        }
    }
}

impl FromIterator<Diagnostic> for Diagnostics {
    fn from_iter<I: IntoIterator<Item = Diagnostic>>(diagnostics: I) -> Self {
        let mut all = Self::new();
        all.extend(diagnostics);
        all
    }
}

impl From<Vec<Diagnostic>> for Diagnostics {
    fn from(kept: Vec<Diagnostic>) -> Self {
        Self {
            kept,
            ..Self::default()
        }
    }
}

impl IntoIterator for Diagnostics {
    type Item = Diagnostic;
    type IntoIter = std::vec::IntoIter<Diagnostic>;

    /// The kept ones.
    fn into_iter(self) -> Self::IntoIter {
        self.kept.into_iter()
    }
}

impl<'a> IntoIterator for &'a Diagnostics {
    type Item = &'a Diagnostic;
    type IntoIter = std::slice::Iter<'a, Diagnostic>;

    fn into_iter(self) -> Self::IntoIter {
        self.kept.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codes;

    fn repeated(n: usize) -> impl Iterator<Item = Diagnostic> {
        (0..n).map(|_| Diagnostic::new(codes::lower::REPEATED_AXIS, "again"))
    }

    /// A block keeps its first diagnostics; every one is counted.
    #[test]
    fn a_block_keeps_a_bounded_number() {
        let mut all = Diagnostics::new();
        all.begin_block();
        all.extend(repeated(1_000));
        all.begin_block();
        all.push(Diagnostic::new(codes::lower::NOT_LOWERED, "next block"));
        assert_eq!(all.len(), MAX_KEPT_PER_BLOCK + 1);
        assert_eq!(all.total(), 1_001);
        assert_eq!(
            all.omitted().by_code(),
            [(
                codes::lower::REPEATED_AXIS,
                Severity::Error,
                (1_000 - MAX_KEPT_PER_BLOCK) as u64
            )]
        );
        assert!(all.has_errors());
    }

    /// Releveling reaches the counted ones too: dropped ones leave the
    /// count, raised ones count as errors.
    #[test]
    fn releveling_changes_kept_and_counted_alike() {
        let mut all = Diagnostics::new();
        all.begin_block();
        all.extend(repeated(MAX_KEPT_PER_BLOCK + 4));
        all.push(Diagnostic::new(codes::lower::NOT_LOWERED, "kept"));
        let warned = all.clone().releveled(|code, severity| {
            (code == codes::lower::REPEATED_AXIS)
                .then_some(Severity::Warning)
                .or(Some(severity))
        });
        assert!(!warned.has_errors());
        assert_eq!(warned.total(), all.total());
        assert!(warned.iter().all(|d| d.severity == Severity::Warning));
        let dropped = all
            .releveled(|code, severity| (code != codes::lower::REPEATED_AXIS).then_some(severity));
        assert_eq!(dropped.total(), 1);
        assert!(!dropped.has_errors());
    }

    /// Parts gathered into a file keep its first diagnostics, with the
    /// parts' counts added up.
    #[test]
    fn a_file_keeps_a_bounded_number() {
        let mut file = Diagnostics::new();
        for _ in 0..3 {
            let mut part = Diagnostics::new();
            part.begin_block();
            part.extend(repeated(MAX_KEPT_PER_BLOCK + 1));
            for _ in 0..MAX_KEPT_PER_FILE / 2 {
                part.begin_block();
                part.push(Diagnostic::new(codes::parse::INVALID_WORD, "bad"));
            }
            file.append(part);
        }
        assert_eq!(file.len(), MAX_KEPT_PER_FILE);
        assert_eq!(
            file.total(),
            3 * (MAX_KEPT_PER_BLOCK + 1 + MAX_KEPT_PER_FILE / 2) as u64
        );
        assert_eq!(
            file.omitted().errors(),
            file.total() - MAX_KEPT_PER_FILE as u64
        );
    }

    /// Retaining judges the kept ones; forgetting the counted ones goes
    /// by code and says how many.
    #[test]
    fn retain_and_forget_omitted_take_diagnostics_out() {
        let mut all = Diagnostics::new();
        all.begin_block();
        all.extend(repeated(MAX_KEPT_PER_BLOCK + 3));
        all.push(Diagnostic::new(codes::lower::NOT_LOWERED, "counted"));
        all.begin_block();
        all.push(Diagnostic::new(codes::lower::NOT_LOWERED, "kept"));
        all.retain(|d| d.code != codes::lower::REPEATED_AXIS);
        assert_eq!(all.len(), 1);
        assert_eq!(all.total(), 5);
        assert_eq!(
            all.forget_omitted(|code| code == codes::lower::REPEATED_AXIS),
            3
        );
        assert_eq!(all.total(), 2);
        assert_eq!(all.forget_omitted(|_| false), 0);
    }
}
