use serde::{Deserialize, Serialize};

/// A byte range in one source file plus the position of its first byte.
///
/// `line` and `col` are 1-based; `col` counts bytes from the start of the
/// line, because files are not necessarily UTF-8. Spans are small (16 bytes)
/// and `Copy` so that every AST node, AIL instruction and runtime event can
/// carry one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Span {
    /// Byte offset of the first byte.
    pub start: u32,
    /// Byte offset one past the last byte.
    pub end: u32,
    /// 1-based line of `start`.
    pub line: u32,
    /// 1-based byte column of `start`.
    pub col: u32,
}

impl Span {
    /// A span from `start` to `end` whose first byte sits at `line`, `col`.
    pub const fn new(start: u32, end: u32, line: u32, col: u32) -> Self {
        Self {
            start,
            end,
            line,
            col,
        }
    }

    /// Length in bytes.
    pub const fn len(&self) -> u32 {
        self.end - self.start
    }

    /// True for an empty span (a position, such as "end of block").
    pub const fn is_empty(&self) -> bool {
        self.end == self.start
    }

    /// The smallest span covering `self` and `other`; line and column come
    /// from whichever starts first.
    pub fn cover(self, other: Span) -> Span {
        let (first, _) = if self.start <= other.start {
            (self, other)
        } else {
            (other, self)
        };
        Span {
            start: first.start,
            end: self.end.max(other.end),
            line: first.line,
            col: first.col,
        }
    }

    /// The byte range, for slicing the source.
    pub fn range(&self) -> std::ops::Range<usize> {
        self.start as usize..self.end as usize
    }
}
