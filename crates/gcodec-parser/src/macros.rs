//! Macros (`DEFINE NAME AS text` in a definition file) expanded in a
//! line before it is parsed, so that a macro may stand for a keyword
//! (structures are paired after expansion), an M code or whole words.
//!
//! A line with a macro use is rewritten with the macro's text in place of
//! its name (again inside that text, up to [`MAX_MACRO_DEPTH`] levels and
//! [`MAX_EXPANDED_BYTES`] bytes, so a recursive macro ends in a
//! diagnostic, never a hang). The grammar reads the rewritten line, and
//! every span it makes is mapped back to the file as stored: what the
//! file holds keeps its place, and what a macro's text produced is at the
//! macro's use, so a diagnostic inside an expansion points at the use.

use std::collections::HashMap;

use chumsky::span::SimpleSpan;
use gcodec_lexer::{Lexer, TokenKind};
use gcodec_source::{Diagnostic, Span, codes};

/// Deepest nesting of a macro in another's text.
pub const MAX_MACRO_DEPTH: usize = 16;

/// Longest line a line's expansion may make.
pub const MAX_EXPANDED_BYTES: usize = 4096;

/// One macro: its name, the text it stands for and where it is defined.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Macro {
    pub name: String,
    pub body: String,
    /// The definition file and the 1-based line of the `DEFINE`.
    pub file: String,
    pub line: u32,
}

/// The macros a program is parsed with, by name in any case.
#[derive(Clone, Debug, Default)]
pub struct Macros {
    by_name: HashMap<String, usize>,
    list: Vec<Macro>,
}

impl Macros {
    /// Adds `m`; `false` (and nothing added) when its name is taken.
    pub fn insert(&mut self, m: Macro) -> bool {
        let key = m.name.to_ascii_uppercase();
        if self.by_name.contains_key(&key) {
            return false;
        }
        self.by_name.insert(key, self.list.len());
        self.list.push(m);
        true
    }

    pub fn get(&self, name: &str) -> Option<&Macro> {
        self.index(name).map(|i| &self.list[i])
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    fn index(&self, name: &str) -> Option<usize> {
        self.by_name.get(&name.to_ascii_uppercase()).copied()
    }

    /// Labels each diagnostic of `src` whose first label lies on a macro's
    /// use with the macro it expands to. The parser labels its own as it
    /// expands; lowering sees only the expanded tree, whose nodes a macro
    /// produced sit at the use, so its diagnostics are labelled here.
    pub fn label_expansions(&self, src: &[u8], diagnostics: &mut [Diagnostic]) {
        if self.is_empty() {
            return;
        }
        for d in diagnostics {
            let Some(span) = d.span() else { continue };
            let text = src.get(span.range()).unwrap_or_default();
            let named = std::str::from_utf8(text)
                .ok()
                .and_then(|name| self.get(name.trim()));
            let Some(m) = named else { continue };
            let note = m.expansion_note();
            if d.labels
                .iter()
                .any(|l| l.message.as_deref() == Some(note.as_str()))
            {
                continue;
            }
            d.labels.push(gcodec_source::Label {
                span,
                message: Some(note.into()),
            });
        }
    }
}

impl Macro {
    /// What a diagnostic in this macro's expansion says of it.
    fn expansion_note(&self) -> String {
        format!(
            "in the expansion of the macro `{}` ({}:{}: `{}`)",
            self.name, self.file, self.line, self.body
        )
    }
}

/// Where a piece of an expanded line comes from.
#[derive(Clone, Copy, Debug)]
enum Origin {
    /// The file, from this offset on.
    File(u32),
    /// The text of a macro used at `at` in the file (the outermost use:
    /// what the program writes); `depth` counts the nesting.
    Macro {
        at: Span,
        index: usize,
        depth: usize,
    },
}

#[derive(Clone, Debug)]
struct Piece {
    text: Vec<u8>,
    origin: Origin,
}

/// A line with its macros expanded: its bytes, its significant tokens
/// (spans into those bytes) and the map back to the file.
pub(crate) struct Expanded {
    pub bytes: Vec<u8>,
    pub tokens: Vec<(TokenKind, SimpleSpan)>,
    /// Each piece's start in `bytes` and its origin, in order.
    pieces: Vec<(usize, Origin)>,
    /// The uses in the file and the macro of each.
    uses: Vec<(Span, usize)>,
}

/// Why a line could not be expanded.
pub(crate) enum ExpansionError {
    TooDeep { at: Span, name: String },
    TooLong { at: Span },
}

impl ExpansionError {
    pub fn diagnostic(&self) -> Diagnostic {
        match self {
            ExpansionError::TooDeep { at, name } => Diagnostic::new(
                codes::parse::MACRO_EXPANSION,
                format!("the macro `{name}` expands more than {MAX_MACRO_DEPTH} levels deep"),
            )
            .with_label(*at, "expanded here")
            .with_help("a macro that uses itself, directly or through another, never ends; break the cycle in the definition files"),
            ExpansionError::TooLong { at } => Diagnostic::new(
                codes::parse::MACRO_EXPANSION,
                format!("the macros of this block expand to more than {MAX_EXPANDED_BYTES} bytes"),
            )
            .with_label(*at, "expanded here")
            .with_help("the control's blocks are at most 512 characters; shorten the macros or split the block"),
        }
    }
}

impl Expanded {
    /// The line `start..end` of `src` (its significant tokens `tokens`)
    /// with its macros expanded; `None` where it uses none. A `DEFINE`
    /// line is not expanded: it names a macro, it does not use one.
    pub fn line(
        src: &[u8],
        (start, end): (u32, u32),
        tokens: &[(TokenKind, SimpleSpan)],
        macros: &Macros,
    ) -> Option<Result<Self, ExpansionError>> {
        if macros.is_empty() || tokens.first().is_some_and(|t| t.0 == TokenKind::Define) {
            return None;
        }
        let mut pieces = Vec::new();
        let mut uses = Vec::new();
        let mut at = start as usize;
        for &(kind, span) in tokens {
            let Some(index) = use_of(kind, &src[span.start..span.end], macros) else {
                continue;
            };
            let used = Span::new(span.start as u32, span.end as u32);
            pieces.push(file_piece(src, at, span.start));
            pieces.push(macro_piece(macros, index, used, 1));
            uses.push((used, index));
            at = span.end;
        }
        if uses.is_empty() {
            return None;
        }
        pieces.push(file_piece(src, at, end as usize));
        Some(expand_nested(pieces, macros).map(|pieces| Self::assemble(pieces, uses)))
    }

    fn assemble(pieces: Vec<Piece>, uses: Vec<(Span, usize)>) -> Self {
        let mut bytes = Vec::new();
        let mut starts = Vec::with_capacity(pieces.len());
        for piece in pieces {
            starts.push((bytes.len(), piece.origin));
            bytes.extend_from_slice(&piece.text);
        }
        let tokens = Lexer::new(&bytes)
            .filter(|t| !matches!(t.kind, TokenKind::Whitespace | TokenKind::Comment))
            .map(|t| (t.kind, SimpleSpan::from(t.start as usize..t.end as usize)))
            .collect();
        Self {
            bytes,
            tokens,
            pieces: starts,
            uses,
        }
    }

    /// `s`, a span of the expanded line, in the file: a span the file
    /// holds keeps its place, one from a macro's text is its use.
    pub fn map_span(&self, s: SimpleSpan) -> Span {
        let start = self.map(s.start, false);
        let end = if s.end == s.start {
            start
        } else {
            self.map(s.end, true)
        };
        Span::new(start, end.max(start))
    }

    /// The file offset of `offset`; an end offset belongs to the piece
    /// before it.
    fn map(&self, offset: usize, is_end: bool) -> u32 {
        let after = self
            .pieces
            .partition_point(|&(at, _)| if is_end { at < offset } else { at <= offset });
        let Some(&(at, origin)) = after.checked_sub(1).map(|i| &self.pieces[i]) else {
            return self.pieces.first().map_or(0, |&(_, o)| file_start(o));
        };
        match origin {
            Origin::File(start) => start + (offset - at) as u32,
            Origin::Macro { at: used, .. } if is_end => used.end,
            Origin::Macro { at: used, .. } => used.start,
        }
    }

    /// A label naming the macro whose expansion `span` (a file span)
    /// lies in, for a diagnostic reported there.
    pub fn note(&self, span: Span, macros: &Macros) -> Option<(Span, String)> {
        let (used, index) = self
            .uses
            .iter()
            .find(|(used, _)| used.start <= span.start && span.end <= used.end)?;
        Some((*used, macros.list[*index].expansion_note()))
    }
}

fn file_start(origin: Origin) -> u32 {
    match origin {
        Origin::File(start) => start,
        Origin::Macro { at, .. } => at.start,
    }
}

/// The macro a token uses: a name token that is a macro's name.
fn use_of(kind: TokenKind, text: &[u8], macros: &Macros) -> Option<usize> {
    (kind == TokenKind::Ident)
        .then(|| std::str::from_utf8(text).ok())
        .flatten()
        .and_then(|name| macros.index(name))
}

fn file_piece(src: &[u8], start: usize, end: usize) -> Piece {
    Piece {
        text: src[start..end.max(start)].to_vec(),
        origin: Origin::File(start as u32),
    }
}

fn macro_piece(macros: &Macros, index: usize, at: Span, depth: usize) -> Piece {
    Piece {
        text: macros.list[index].body.clone().into_bytes(),
        origin: Origin::Macro { at, index, depth },
    }
}

/// Expands the macros used in the macros' texts, level by level.
fn expand_nested(mut pieces: Vec<Piece>, macros: &Macros) -> Result<Vec<Piece>, ExpansionError> {
    loop {
        let mut changed = false;
        let mut next = Vec::with_capacity(pieces.len());
        let mut size = 0usize;
        for piece in pieces {
            let Origin::Macro { at, index, depth } = piece.origin else {
                size += piece.text.len();
                next.push(piece);
                continue;
            };
            let mut from = 0usize;
            for token in Lexer::new(&piece.text) {
                let (s, e) = (token.start as usize, token.end as usize);
                let Some(inner) = use_of(token.kind, &piece.text[s..e], macros) else {
                    continue;
                };
                if depth >= MAX_MACRO_DEPTH {
                    let name = macros.list[inner].name.clone();
                    return Err(ExpansionError::TooDeep { at, name });
                }
                changed = true;
                let before = piece.text[from..s].to_vec();
                size += before.len() + macros.list[inner].body.len();
                next.push(Piece {
                    text: before,
                    origin: piece.origin,
                });
                next.push(Piece {
                    text: macros.list[inner].body.clone().into_bytes(),
                    origin: Origin::Macro {
                        at,
                        index,
                        depth: depth + 1,
                    },
                });
                from = e;
                if size > MAX_EXPANDED_BYTES {
                    return Err(ExpansionError::TooLong { at });
                }
            }
            size += piece.text.len() - from;
            next.push(Piece {
                text: piece.text[from..].to_vec(),
                origin: piece.origin,
            });
            if size > MAX_EXPANDED_BYTES {
                return Err(ExpansionError::TooLong { at });
            }
        }
        pieces = next;
        if !changed {
            return Ok(pieces);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn macros(list: &[(&str, &str)]) -> Macros {
        let mut macros = Macros::default();
        for (i, (name, body)) in list.iter().enumerate() {
            macros.insert(Macro {
                name: (*name).into(),
                body: (*body).into(),
                file: "UMAC.DEF".into(),
                line: i as u32 + 1,
            });
        }
        macros
    }

    fn expand(line: &str, macros: &Macros) -> Option<Result<Expanded, ExpansionError>> {
        let tokens: Vec<_> = Lexer::new(line.as_bytes())
            .filter(|t| !matches!(t.kind, TokenKind::Whitespace | TokenKind::Comment))
            .map(|t| (t.kind, SimpleSpan::from(t.start as usize..t.end as usize)))
            .collect();
        Expanded::line(line.as_bytes(), (0, line.len() as u32), &tokens, macros)
    }

    #[test]
    fn a_use_is_replaced_by_the_text_and_maps_back_to_the_use() {
        let m = macros(&[("LIFT_ON", "M17"), ("MAXN", "100")]);
        let Some(Ok(e)) = expand("N10 LIFT_ON R1=maxn ; x", &m) else {
            panic!("expanded");
        };
        assert_eq!(e.bytes, b"N10 M17 R1=100 ; x");
        // `N10` keeps its place; `M17` is at the use of `LIFT_ON`.
        assert_eq!(e.map_span(SimpleSpan::from(0..3)), Span::new(0, 3));
        assert_eq!(e.map_span(SimpleSpan::from(4..7)), Span::new(4, 11));
        assert_eq!(e.map_span(SimpleSpan::from(8..10)), Span::new(12, 14));
        assert_eq!(e.map_span(SimpleSpan::from(11..14)), Span::new(15, 19));
        assert!(e.note(Span::new(15, 19), &m).unwrap().1.contains("`MAXN`"));
        assert!(e.note(Span::new(0, 3), &m).is_none());
    }

    #[test]
    fn nested_macros_expand_and_recursive_ones_end() {
        let m = macros(&[("PLANE", "G17 LINE"), ("LINE", "G1")]);
        let Some(Ok(e)) = expand("PLANE X1", &m) else {
            panic!("expanded");
        };
        assert_eq!(e.bytes, b"G17 G1 X1");
        let m = macros(&[("AA", "BB"), ("BB", "AA")]);
        assert!(matches!(
            expand("AA", &m),
            Some(Err(ExpansionError::TooDeep { .. }))
        ));
        let m = macros(&[("AA", "BB BB BB BB"), ("BB", "AA AA AA AA")]);
        assert!(expand("AA", &m).is_some_and(|r| r.is_err()));
    }

    #[test]
    fn lines_without_uses_and_definitions_are_left_alone() {
        let m = macros(&[("MAXN", "100")]);
        assert!(expand("G1 X10", &m).is_none());
        assert!(expand("DEFINE MAXN AS 100", &m).is_none());
        assert!(expand("MAXN", &Macros::default()).is_none());
    }
}
