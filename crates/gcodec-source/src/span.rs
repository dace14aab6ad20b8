use std::cell::RefCell;

use serde::ser::SerializeStruct;
use serde::{Deserialize, Serialize, Serializer};

/// A byte range in one source file.
///
/// Spans are 8 bytes and `Copy`, so every AST node can carry one at little
/// cost: a large program has millions of nodes. Line and column are not
/// stored but derived from the file's line table ([`crate::SourceFile::line_col`],
/// or the parser's `Program::line_col`), as rust-analyzer and ruff do with
/// their text ranges. Columns are 1-based *byte* columns, because files are
/// not necessarily UTF-8.
///
/// Serialised, a span is `{"start", "end"}`, plus `"line"` and `"col"` when
/// it is serialised inside [`with_line_starts`] (the parser's `Program` does
/// this for its whole tree), so JSON consumers never re-read the file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Deserialize)]
pub struct Span {
    /// Byte offset of the first byte.
    pub start: u32,
    /// Byte offset one past the last byte.
    pub end: u32,
}

impl Span {
    /// The bytes `start..end`.
    pub const fn new(start: u32, end: u32) -> Self {
        Self { start, end }
    }

    /// Length in bytes.
    pub const fn len(&self) -> u32 {
        self.end - self.start
    }

    /// True for an empty span (a position, such as "end of block").
    pub const fn is_empty(&self) -> bool {
        self.end == self.start
    }

    /// The smallest span covering `self` and `other`.
    pub fn cover(self, other: Span) -> Span {
        Span {
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    /// The byte range, for slicing the source.
    pub fn range(&self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}

/// 1-based line and byte column of `offset`, given the byte offset at which
/// each line starts (the first is 0).
pub fn line_col(line_starts: &[u32], offset: u32) -> (u32, u32) {
    let line = line_starts.partition_point(|&s| s <= offset);
    let line_start = line_starts.get(line.wrapping_sub(1)).copied().unwrap_or(0);
    (line.max(1) as u32, offset - line_start.min(offset) + 1)
}

thread_local! {
    /// The line table of the file whose spans are being serialised.
    static LINE_STARTS: RefCell<Option<Vec<u32>>> = const { RefCell::new(None) };
}

/// Runs `f` with `line_starts` as the line table for serialising spans:
/// every [`Span`] serialised inside `f` on this thread carries `line` and
/// `col`. Scopes nest; the previous table is restored afterwards, even if
/// `f` unwinds.
pub fn with_line_starts<R>(line_starts: Vec<u32>, f: impl FnOnce() -> R) -> R {
    struct Restore(Option<Vec<u32>>);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take();
            LINE_STARTS.with(|cell| *cell.borrow_mut() = previous);
        }
    }
    let previous = LINE_STARTS.with(|cell| cell.borrow_mut().replace(line_starts));
    let _restore = Restore(previous);
    f()
}

impl Serialize for Span {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let position = LINE_STARTS.with(|cell| {
            cell.borrow()
                .as_deref()
                .map(|starts| line_col(starts, self.start))
        });
        let mut s = serializer.serialize_struct("Span", if position.is_some() { 4 } else { 2 })?;
        s.serialize_field("start", &self.start)?;
        s.serialize_field("end", &self.end)?;
        if let Some((line, col)) = position {
            s.serialize_field("line", &line)?;
            s.serialize_field("col", &col)?;
        }
        s.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_are_one_based_byte_columns() {
        let starts = [0, 3, 6, 7];
        assert_eq!(line_col(&starts, 0), (1, 1));
        assert_eq!(line_col(&starts, 2), (1, 3));
        assert_eq!(line_col(&starts, 3), (2, 1));
        assert_eq!(line_col(&starts, 7), (4, 1));
        assert_eq!(line_col(&starts, 9), (4, 3));
        assert_eq!(line_col(&[], 5), (1, 6));
    }

    #[test]
    fn spans_serialise_positions_only_inside_a_scope() {
        let span = Span::new(4, 6);
        let bare = serde_json::to_string(&span).unwrap();
        assert_eq!(bare, r#"{"start":4,"end":6}"#);
        let placed = with_line_starts(vec![0, 3], || serde_json::to_string(&span).unwrap());
        assert_eq!(placed, r#"{"start":4,"end":6,"line":2,"col":2}"#);
        // The scope ends with the closure.
        assert_eq!(serde_json::to_string(&span).unwrap(), bare);
    }

    #[test]
    fn cover_spans_both() {
        assert_eq!(Span::new(5, 7).cover(Span::new(2, 3)), Span::new(2, 7));
    }
}
