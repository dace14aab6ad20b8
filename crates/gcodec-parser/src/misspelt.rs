//! Comparison operators of other languages written in a SINUMERIK program
//! (`=<`, `=>`, `!=`, `=!`). The lexer reads each as two tokens (or a
//! reserved `!`), which alone would give an unexpected-token error far
//! from the mistake; this names the operator meant instead.

use chumsky::span::SimpleSpan;
use gcodec_lexer::TokenKind;
use gcodec_source::{Diagnostic, Span, codes};

use crate::grammar::{Ctx, Spanned};

/// An operator written the way another language spells it, and the
/// SINUMERIK operator of that meaning.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Misspelt {
    pub span: Span,
    pub written: &'static str,
    pub meant: &'static str,
}

impl Misspelt {
    /// `=` touching a `<` or `>` after it, in a line's significant tokens.
    pub fn in_tokens(tokens: &[Spanned], ctx: &Ctx<'_>) -> Option<Self> {
        tokens.windows(2).find_map(|pair| {
            let [(TokenKind::Eq, eq), (next, after)] = pair else {
                return None;
            };
            let (written, meant) = match next {
                TokenKind::Lt => ("=<", "<="),
                TokenKind::Gt => ("=>", ">="),
                _ => return None,
            };
            (eq.end == after.start).then(|| Self {
                span: ctx.span(SimpleSpan::from(eq.start..after.end)),
                written,
                meant,
            })
        })
    }

    /// `!` at `at` (a reserved character) with an `=` touching it.
    pub fn around_bang(src: &[u8], at: usize) -> Option<Self> {
        let before = at.checked_sub(1).and_then(|i| src.get(i)) == Some(&b'=');
        let after = src.get(at + 1) == Some(&b'=');
        let (range, written) = match (before, after) {
            (_, true) => (at..at + 2, "!="),
            (true, false) => (at - 1..at + 1, "=!"),
            (false, false) => return None,
        };
        Some(Self {
            span: Span::new(range.start as u32, range.end as u32),
            written,
            meant: "<>",
        })
    }

    pub fn diagnostic(self) -> Diagnostic {
        Diagnostic::new(
            codes::parse::INVALID_OPERATOR,
            format!("`{}` is not an operator of the NC language", self.written),
        )
        .with_label(self.span, format!("did you mean `{}`?", self.meant))
        .with_help(format!(
            "the comparison operators are `==`, `<>`, `<`, `>`, `<=` and `>=`; write `{}`",
            self.meant
        ))
    }
}
