//! The lines of a file that a diagnostic shows, as miette reads them.
//!
//! miette finds a span's line by scanning its source from the first byte,
//! counts a lone CR as a line end and echoes every byte; over a whole
//! file that made each report cost the length of the file before it,
//! disagreed with gcodec's positions after a lone CR and let a program's
//! control characters reach the terminal. An [`Excerpt`] holds only the
//! lines around one diagnostic's labels, found in the file's line table:
//! each decoded, its control characters escaped, a long line cut to the
//! stretches around its labels, and every position taken from the line
//! table, so the header says what gcodec says.

use std::ops::Range;

use miette::{MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};

use crate::encoding::Encoding;
use crate::escape::{escape_controls, push_escaped};
use crate::{SourceFile, Span};

/// Lines shown as one piece when a diagnostic's labels lie this close
/// together (counting a line of context before and after), as miette
/// shows them; labels further apart are shown each with its context.
const MAX_EXCERPT_LINES: usize = 24;

/// Lines of a longer label that are shown; the label ends with them.
const MAX_LABEL_LINES: usize = 8;

/// A line longer than this (in bytes) is cut to the stretches around the
/// label ends on it, [`WINDOW`] bytes each side.
const MAX_LINE_BYTES: usize = 256;

/// Bytes kept each side of a label's start and end on a long line.
const WINDOW: usize = 48;

/// What stands for the bytes left out of a long line.
const ELLIPSIS: &str = "…";

/// The lines of `file` around some labels, ready for miette.
pub(crate) struct Excerpt<'a> {
    file: &'a SourceFile,
    name: String,
    text: String,
    lines: Vec<ExcerptLine>,
    /// (file offset, text offset) of every character shown, of every cut
    /// and of every line's end, in order of both.
    points: Vec<(u32, u32)>,
    /// The labels' spans in `text`.
    labels: Vec<SourceSpan>,
}

struct ExcerptLine {
    /// The 0-based line number in the file.
    number: usize,
    /// Where the line is in `text` (without its `\n`).
    text: Range<usize>,
}

impl<'a> Excerpt<'a> {
    /// The lines around `labels` (spans into `file`).
    pub(crate) fn new(file: &'a SourceFile, labels: &[Span]) -> Self {
        let mut excerpt = Self {
            file,
            name: escape_controls(file.name()).into_owned(),
            text: String::new(),
            lines: Vec::new(),
            points: Vec::new(),
            labels: Vec::new(),
        };
        let shown: Vec<Span> = labels.iter().map(|&l| excerpt.shown_part(l)).collect();
        for range in excerpt.line_ranges(&shown) {
            for number in range {
                excerpt.push_line(number, &shown);
            }
        }
        excerpt.labels = shown
            .iter()
            .map(|l| {
                let start = excerpt.text_offset(l.start);
                SourceSpan::from(start..excerpt.text_offset(l.end).max(start))
            })
            .collect();
        excerpt
    }

    /// The labels' spans in the excerpt's text, in the order given.
    pub(crate) fn labels(&self) -> &[SourceSpan] {
        &self.labels
    }

    /// The part of a label shown: inside the file, and over at most
    /// [`MAX_LABEL_LINES`] lines.
    fn shown_part(&self, label: Span) -> Span {
        let len = self.file.bytes().len() as u32;
        let start = label.start.min(len);
        let end = label.end.clamp(start, len);
        let first = self.line_of(start);
        let last = self.line_of(end.saturating_sub(1).max(start));
        if last - first < MAX_LABEL_LINES {
            return Span::new(start, end);
        }
        let cut = self.line_bytes(first + MAX_LABEL_LINES - 1).end as u32;
        Span::new(start, cut.max(start))
    }

    /// The 0-based line of a file offset.
    fn line_of(&self, offset: u32) -> usize {
        self.file
            .line_starts()
            .partition_point(|&s| s <= offset)
            .saturating_sub(1)
    }

    /// The bytes of line `number` without its line end (LF or CR LF).
    fn line_bytes(&self, number: usize) -> Range<usize> {
        let starts = self.file.line_starts();
        let bytes = self.file.bytes();
        let start = starts[number] as usize;
        let mut end = starts
            .get(number + 1)
            .map_or(bytes.len(), |&s| s as usize - 1);
        if end > start && bytes[end - 1] == b'\r' && end < bytes.len() && bytes[end] == b'\n' {
            end -= 1;
        }
        start..end
    }

    /// The runs of lines to show: each label's lines with one line of context each side, all as
    /// one run where they fit in [`MAX_EXCERPT_LINES`].
    fn line_ranges(&self, labels: &[Span]) -> Vec<Range<usize>> {
        let last_line = self.file.line_starts().len() - 1;
        let mut ranges: Vec<Range<usize>> = labels
            .iter()
            .map(|label| {
                let first = self.line_of(label.start);
                let last = self.line_of(label.end.saturating_sub(1).max(label.start));
                first.saturating_sub(1)..(last + 1).min(last_line) + 1
            })
            .collect();
        ranges.sort_by_key(|r| r.start);
        let (Some(first), Some(last)) = (ranges.first(), ranges.iter().map(|r| r.end).max()) else {
            return ranges;
        };
        if last - first.start <= MAX_EXCERPT_LINES {
            return std::iter::once(first.start..last).collect();
        }
        let mut merged: Vec<Range<usize>> = Vec::new();
        for range in ranges {
            match merged.last_mut() {
                Some(previous) if range.start <= previous.end => {
                    previous.end = previous.end.max(range.end);
                }
                _ => merged.push(range),
            }
        }
        merged
    }

    /// Appends line `number`, cut where it is long, and its points.
    fn push_line(&mut self, number: usize, labels: &[Span]) {
        if !self.text.is_empty() {
            self.text.push('\n');
        }
        let line = self.line_bytes(number);
        let utf8 = (self.file.encoding() == Encoding::UTF_8)
            .then(|| std::str::from_utf8(&self.file.bytes()[line.clone()]).ok())
            .flatten();
        let start = self.text.len();
        let mut shown_to = line.start;
        for kept in kept_stretches(line.clone(), labels, utf8) {
            if kept.start > shown_to {
                self.cut_at(shown_to);
            }
            shown_to = kept.end;
            self.push_stretch(kept, line.start, utf8);
        }
        if line.end > shown_to {
            self.cut_at(shown_to);
        }
        self.points.push((line.end as u32, self.text.len() as u32));
        self.lines.push(ExcerptLine {
            number,
            text: start..self.text.len(),
        });
    }

    /// Marks the bytes left out from file offset `from` on.
    fn cut_at(&mut self, from: usize) {
        self.points.push((from as u32, self.text.len() as u32));
        self.text.push_str(ELLIPSIS);
    }

    /// Appends the bytes `stretch` of the file (a line of a UTF-8 file as
    /// UTF-8, else byte by byte in the file's code page),
    /// escaped, with a point per character.
    fn push_stretch(&mut self, stretch: Range<usize>, line_start: usize, utf8: Option<&str>) {
        match utf8 {
            Some(line) => {
                let text = &line[stretch.start - line_start..stretch.end - line_start];
                for (i, c) in text.char_indices() {
                    self.points
                        .push(((stretch.start + i) as u32, self.text.len() as u32));
                    push_escaped(&mut self.text, c);
                }
            }
            None => {
                for at in stretch {
                    self.points.push((at as u32, self.text.len() as u32));
                    push_escaped(
                        &mut self.text,
                        self.file.encoding().decode_byte(self.file.bytes()[at]),
                    );
                }
            }
        }
    }

    /// Where file offset `offset` is shown: at its character, or at the
    /// cut or line end it lies in.
    fn text_offset(&self, offset: u32) -> usize {
        let i = self.points.partition_point(|p| p.0 <= offset);
        i.checked_sub(1).map_or(0, |i| self.points[i].1 as usize)
    }

    /// The file offset shown at text offset `at` (the nearest before it).
    fn file_offset(&self, at: usize) -> u32 {
        let i = self.points.partition_point(|p| p.1 as usize <= at);
        i.checked_sub(1).map_or(0, |i| self.points[i].0)
    }

    /// The index in `lines` of the line holding text offset `at`.
    fn line_at(&self, at: usize) -> usize {
        self.lines
            .partition_point(|l| l.text.start <= at)
            .saturating_sub(1)
    }

    /// The last index from `i` on whose lines follow each other in the
    /// file without a gap.
    fn run_end(&self, i: usize) -> usize {
        let mut end = i;
        while self
            .lines
            .get(end + 1)
            .is_some_and(|l| l.number == self.lines[end].number + 1)
        {
            end += 1;
        }
        end
    }
}

/// The stretches of `line` (file offsets) to show: all of it, or around
/// the label ends on it where it is longer than [`MAX_LINE_BYTES`] (its
/// start where none is on it), on character boundaries of `utf8`.
fn kept_stretches(line: Range<usize>, labels: &[Span], utf8: Option<&str>) -> Vec<Range<usize>> {
    if line.len() <= MAX_LINE_BYTES {
        return vec![line];
    }
    let boundary = |at: usize, forward: bool| match utf8 {
        None => at,
        Some(text) => {
            let mut at = at - line.start;
            while !text.is_char_boundary(at) {
                if forward { at += 1 } else { at -= 1 }
            }
            line.start + at
        }
    };
    let mut ends: Vec<usize> = labels
        .iter()
        .flat_map(|l| [l.start as usize, l.end as usize])
        .filter(|&at| line.contains(&at) || at == line.end)
        .collect();
    if ends.is_empty() {
        ends.push(line.start);
    }
    ends.sort_unstable();
    let mut kept: Vec<Range<usize>> = Vec::new();
    for at in ends {
        let start = boundary(at.saturating_sub(WINDOW).max(line.start), false);
        let end = boundary((at + WINDOW).min(line.end), true);
        match kept.last_mut() {
            Some(previous) if start <= previous.end => previous.end = previous.end.max(end),
            _ => kept.push(start..end),
        }
    }
    kept
}

impl SourceCode for Excerpt<'_> {
    fn read_span<'b>(
        &'b self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'b> + 'b>, MietteError> {
        let start = span.offset();
        let end = start + span.len();
        if self.lines.is_empty() || end > self.text.len() {
            return Err(MietteError::OutOfBounds);
        }
        let first = self.line_at(start);
        let last = self
            .line_at(if span.is_empty() { end } else { end - 1 })
            .max(first);
        let run_end = self.run_end(first);
        if last > run_end {
            return Err(MietteError::OutOfBounds);
        }
        let mut from = first;
        while from > 0
            && first - from < context_lines_before
            && self.lines[from - 1].number + 1 == self.lines[from].number
        {
            from -= 1;
        }
        let to = (last + context_lines_after).min(run_end);
        let data_start = if context_lines_before == 0 {
            start
        } else {
            self.lines[from].text.start
        };
        let data_end = self.lines[to].text.end.max(end);
        let (line, column) = if context_lines_before == 0 {
            let (line, col) = self.file.line_col(self.file_offset(start));
            (line as usize - 1, col as usize - 1)
        } else {
            (self.lines[from].number, 0)
        };
        let line_count = self.lines[run_end].number - self.lines[from].number;
        Ok(Box::new(
            MietteSpanContents::new_named(
                self.name.clone(),
                &self.text.as_bytes()[data_start..data_end],
                SourceSpan::from(data_start..data_end),
                line,
                column,
                line_count,
            )
            .with_language("SINUMERIK"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(excerpt: &Excerpt) -> Vec<usize> {
        excerpt.lines.iter().map(|l| l.number).collect()
    }

    /// However far into the file a label is, its excerpt holds its line
    /// and one each side: rendering a file's diagnostics reads each
    /// diagnostic's lines, not the file before them.
    #[test]
    fn an_excerpt_holds_the_lines_around_its_labels_only() {
        let text = "N10 G1 X=\n".repeat(10_000);
        let file = SourceFile::new("many.mpf", text);
        for line in [0, 5_000, 9_999] {
            let at = file.line_starts()[line] + 7;
            let excerpt = Excerpt::new(&file, &[Span::new(at, at + 2)]);
            let expected: Vec<usize> = (line.saturating_sub(1)..=(line + 1).min(10_000)).collect();
            assert_eq!(lines(&excerpt), expected);
            assert!(excerpt.text.len() <= 3 * 10, "{}", excerpt.text);
        }
    }

    /// Labels close together are one run of lines, as miette shows them;
    /// labels far apart are each shown with their context.
    #[test]
    fn labels_far_apart_are_shown_apart() {
        let file = SourceFile::new("t.mpf", "G1 X1\n".repeat(100));
        let at = |line: usize| file.line_starts()[line];
        let near = Excerpt::new(
            &file,
            &[Span::new(at(2), at(2) + 2), Span::new(at(9), at(9))],
        );
        assert_eq!(lines(&near), (1..=10).collect::<Vec<_>>());
        let far = Excerpt::new(
            &file,
            &[Span::new(at(2), at(2) + 2), Span::new(at(90), at(90))],
        );
        assert_eq!(lines(&far), [1, 2, 3, 89, 90, 91]);
    }

    /// A line of a million bytes is shown as the stretches around the
    /// label's ends.
    #[test]
    fn a_long_line_is_cut_around_the_label() {
        let mut text = String::from("G1");
        while text.len() < 1_000_000 {
            text.push_str(" X1");
        }
        let file = SourceFile::new("long.mpf", format!("{text}\nM30\n"));
        let excerpt = Excerpt::new(&file, &[Span::new(0, text.len() as u32)]);
        assert!(excerpt.text.len() < 4 * WINDOW, "{}", excerpt.text);
        assert!(excerpt.text.starts_with("G1 X1") && excerpt.text.contains(ELLIPSIS));
        assert!(excerpt.text.ends_with(" X1\nM30"), "{}", excerpt.text);
        let label = excerpt.labels()[0];
        assert_eq!(
            (label.offset(), label.len()),
            (0, excerpt.text.find('\n').unwrap())
        );
    }
}
