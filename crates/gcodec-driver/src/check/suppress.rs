//! Suppression comments in a program: `; gcodec: allow(CODE, …)` at the
//! end of a block suppresses those codes on its line; on a line of its
//! own above the first block (only comments, blank lines and the `%`
//! header above it) in the whole file. The comments are found with the
//! lexer, so a `;` inside a string is no comment; a file with no `;`
//! followed by `gcodec:` is not lexed.
//!
//! A name that is no code or area, or a comment that starts with
//! `gcodec:` but is no `allow(…)`, is `gcodec::check::bad_suppression`;
//! a code or area that suppressed nothing is
//! `gcodec::check::unused_suppression`. Both are found after the rule
//! levels (a suppression of a code the levels drop suppresses nothing)
//! and are not themselves suppressible: only rule levels change them.

use std::collections::HashMap;

use gcodec_lexer::{Lexer, TokenKind};
use gcodec_source::{Diagnostic, Diagnostics, SourceFile, Span, codes};

use super::Selector;

/// What every suppression starts with, after the `;` and blanks.
const MARK: &[u8] = b"gcodec:";

/// Where a suppression applies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scope {
    /// The whole file: a line of its own above the first block.
    File,
    /// One block: at the end of the block on this line (1-based).
    Block(u32),
    /// A line of its own below the first block: its own line, which has
    /// no code, so it suppresses nothing.
    OwnLine(u32),
}

/// One code or area named in a suppression.
#[derive(Debug)]
struct Named {
    selector: Selector,
    scope: Scope,
    /// Where it is written in the comment.
    span: Span,
    used: bool,
}

/// The suppressions of a file, and what is wrong with them.
#[derive(Debug, Default)]
struct Suppressions {
    named: Vec<Named>,
    problems: Vec<Diagnostic>,
}

/// Takes the diagnostics `file`'s suppressions name out of
/// `diagnostics` (already at their levels): those of a block by the line
/// their primary span starts on, those of the file wherever they are
/// (the ones counted but not kept too, by code). Returns the
/// suppressions' own diagnostics (`bad_suppression`,
/// `unused_suppression`) at their codes' levels.
pub(super) fn apply(file: &SourceFile, diagnostics: &mut Diagnostics) -> Vec<Diagnostic> {
    let mut found = suppressions(file);
    if found.named.is_empty() {
        return found.problems;
    }
    let mut by_line: HashMap<u32, Vec<usize>> = HashMap::new();
    let mut whole_file = Vec::new();
    for (i, named) in found.named.iter().enumerate() {
        match named.scope {
            Scope::File => whole_file.push(i),
            Scope::Block(line) | Scope::OwnLine(line) => by_line.entry(line).or_default().push(i),
        }
    }
    let named = &mut found.named;
    diagnostics.retain(|d| {
        let line = d.span().map(|span| file.line_col(span.start).0);
        let on_line = line.and_then(|line| by_line.get(&line));
        let matching = whole_file
            .iter()
            .chain(on_line.into_iter().flatten())
            .find(|&&i| named[i].selector.matches(d.code));
        match matching {
            Some(&i) => {
                named[i].used = true;
                false
            }
            None => true,
        }
    });
    for &i in &whole_file {
        let selector = named[i].selector;
        if diagnostics.forget_omitted(|code| selector.matches(code)) > 0 {
            named[i].used = true;
        }
    }
    let unused = named.iter().filter(|n| !n.used).map(unused_diagnostic);
    found.problems.extend(unused);
    found.problems
}

fn unused_diagnostic(named: &Named) -> Diagnostic {
    let (place, help) = match named.scope {
        Scope::File => (
            "in this file",
            "remove it from the comment; a suppression applies after the rule levels",
        ),
        Scope::Block(_) => (
            "on this block",
            "remove it from the comment; a suppression applies after the rule levels",
        ),
        Scope::OwnLine(_) => (
            "on its own line",
            "a suppression on a line of its own applies to the whole file only above the \
             first block; put it at the end of the block it is for",
        ),
    };
    let message = match named.selector {
        Selector::Code(code) => format!("the suppression of `{code}` suppressed nothing {place}"),
        Selector::Area(area) => {
            format!("the suppression of `gcodec::{area}::*` suppressed nothing {place}")
        }
    };
    Diagnostic::new(codes::check::UNUSED_SUPPRESSION, message)
        .with_label(named.span, "suppresses nothing")
        .with_help(help)
}

/// Every suppression comment of `file`, read.
fn suppressions(file: &SourceFile) -> Suppressions {
    let mut found = Suppressions::default();
    let bytes = file.bytes();
    if !memchr::memchr_iter(b';', bytes).any(|at| starts_with_mark(&bytes[at + 1..])) {
        return found;
    }
    let mut line = 1u32;
    let mut code_on_line = false;
    let mut code_above = false;
    for token in Lexer::new(bytes) {
        match token.kind {
            TokenKind::Newline => {
                line += 1;
                code_above |= code_on_line;
                code_on_line = false;
            }
            TokenKind::Whitespace | TokenKind::Header => {}
            TokenKind::Comment => {
                let scope = if code_on_line {
                    Scope::Block(line)
                } else if code_above {
                    Scope::OwnLine(line)
                } else {
                    Scope::File
                };
                read_comment(bytes, token.start, token.end, scope, &mut found);
            }
            _ => code_on_line = true,
        }
    }
    found
}

/// Reads the comment `bytes[start..end]` (from its `;`) as a suppression
/// where it is one.
fn read_comment(bytes: &[u8], start: u32, end: u32, scope: Scope, found: &mut Suppressions) {
    let comment = &bytes[start as usize..end as usize];
    let body = comment.get(1..).unwrap_or_default();
    if !starts_with_mark(body) {
        return;
    }
    let blanks = body.iter().take_while(|b| b.is_ascii_whitespace()).count();
    let comment_span = Span::new(start, end);
    // Offsets below are from the comment's start.
    let after_mark = 1 + blanks + MARK.len();
    let Some((list_start, list_end)) = allow_list(comment, after_mark) else {
        found.problems.push(
            Diagnostic::new(
                codes::check::BAD_SUPPRESSION,
                "this `gcodec:` comment is no suppression gcodec can read",
            )
            .with_label(comment_span, "not `gcodec: allow(CODE, …)`")
            .with_help(
                "write `; gcodec: allow(CODE)` (several codes separated by commas); \
                 a comment that is no suppression must not start with `gcodec:`",
            ),
        );
        return;
    };
    let at = |from: usize, to: usize| Span::new(start + from as u32, start + to as u32);
    let mut piece_start = list_start;
    let mut named_any = false;
    for piece in comment[list_start..list_end].split(|&b| b == b',') {
        let piece_end = piece_start + piece.len();
        let lead = piece.iter().take_while(|b| b.is_ascii_whitespace()).count();
        let trail = piece[lead..]
            .iter()
            .rev()
            .take_while(|b| b.is_ascii_whitespace())
            .count();
        let (from, to) = (piece_start + lead, piece_end - trail);
        piece_start = piece_end + 1;
        if from == to {
            continue;
        }
        named_any = true;
        let span = at(from, to);
        let parsed = std::str::from_utf8(&comment[from..to])
            .map_err(|_| "this name is not text".to_owned())
            .and_then(Selector::parse);
        match parsed {
            Ok(selector) => found.named.push(Named {
                selector,
                scope,
                span,
                used: false,
            }),
            Err(message) => found.problems.push(
                Diagnostic::new(codes::check::BAD_SUPPRESSION, message)
                    .with_label(span, "this name")
                    .with_help("`gcodec explain --list` lists every code"),
            ),
        }
    }
    if !named_any {
        found.problems.push(
            Diagnostic::new(
                codes::check::BAD_SUPPRESSION,
                "this suppression names no code",
            )
            .with_label(at(list_start, list_end), "an empty list")
            .with_help("name the codes to suppress: `; gcodec: allow(CODE)`"),
        );
    }
}

/// Whether `text` (what follows a `;`) is blanks, then [`MARK`] in any
/// case.
fn starts_with_mark(text: &[u8]) -> bool {
    let blanks = text.iter().take_while(|b| b.is_ascii_whitespace()).count();
    text.get(blanks..blanks + MARK.len())
        .is_some_and(|m| m.eq_ignore_ascii_case(MARK))
}

/// The offsets of the list inside `allow(…)` in `comment`, the word
/// `allow` at or after blanks from `from`; text after the `)` is a
/// reason and is not read.
fn allow_list(comment: &[u8], from: usize) -> Option<(usize, usize)> {
    let skip_blanks = |at: usize| {
        at + comment[at..]
            .iter()
            .take_while(|b| b.is_ascii_whitespace())
            .count()
    };
    let word = skip_blanks(from);
    let keyword = b"allow";
    if !comment
        .get(word..word + keyword.len())
        .is_some_and(|w| w.eq_ignore_ascii_case(keyword))
    {
        return None;
    }
    let open = skip_blanks(word + keyword.len());
    if comment.get(open) != Some(&b'(') {
        return None;
    }
    let close = open + 1 + comment[open + 1..].iter().position(|&b| b == b')')?;
    Some((open + 1, close))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn found(text: &str) -> Suppressions {
        suppressions(&SourceFile::new("a.mpf", text))
    }

    #[test]
    fn scopes_follow_where_the_comment_is() {
        let text = "%_N_A_MPF\n; header\n; gcodec: allow(lower::*)\n\
                    N10 M77 ; GCODEC: Allow( not_lowered , parse::invalid_word ) why\n\
                    ; gcodec: allow(lower::not_lowered)\nN20 X\"; gcodec: allow(x)\"\n";
        let found = found(text);
        assert!(found.problems.is_empty(), "{:?}", found.problems);
        let scopes: Vec<Scope> = found.named.iter().map(|n| n.scope).collect();
        assert_eq!(
            scopes,
            [
                Scope::File,
                Scope::Block(4),
                Scope::Block(4),
                Scope::OwnLine(5)
            ]
        );
        let span = found.named[1].span;
        assert_eq!(&text[span.range()], "not_lowered");
    }

    #[test]
    fn malformed_suppressions_and_unknown_names_are_reported() {
        for text in [
            "; gcodec: alow(lower::*)\n",
            "; gcodec: allow(lower::*\n",
            "; gcodec: allow( , )\n",
        ] {
            let found = found(text);
            assert_eq!(found.problems.len(), 1, "{text}");
            assert_eq!(found.problems[0].code, codes::check::BAD_SUPPRESSION);
        }
        let typo = found("G0 ; gcodec: allow(lower::not_lowerd, lower::*)\n");
        assert_eq!(typo.named.len(), 1);
        assert!(
            typo.problems[0]
                .message
                .contains("did you mean `gcodec::lower::not_lowered`"),
            "{:?}",
            typo.problems
        );
        assert!(found("; a comment about gcodec\n").named.is_empty());
        assert!(found("; gcodec allow(lower::*)\n").problems.is_empty());
        assert!(found("G0 ; gcodec is fine\n").problems.is_empty());
    }

    #[test]
    fn apply_drops_what_is_named_and_reports_the_unused() {
        let text = "; gcodec: allow(parse::*)\nN10 M77 ; gcodec: allow(lower::unknown_m_function, lower::not_lowered)\nN20 M77\n";
        let file = SourceFile::new("a.mpf", text);
        let on_line = |line: usize| {
            let start = file.line_starts()[line - 1];
            Span::new(start, start + 3)
        };
        let m77 = |line| {
            Diagnostic::new(codes::lower::UNKNOWN_M_FUNCTION, "M77").with_label(on_line(line), "")
        };
        let mut diagnostics = Diagnostics::from(vec![m77(2), m77(3)]);
        let own = apply(&file, &mut diagnostics);
        assert_eq!(diagnostics.len(), 1);
        assert_eq!(diagnostics[0].span(), Some(on_line(3)));
        let unused: Vec<String> = own.iter().map(|d| d.message.to_string()).collect();
        assert_eq!(
            unused,
            [
                "the suppression of `gcodec::parse::*` suppressed nothing in this file",
                "the suppression of `gcodec::lower::not_lowered` suppressed nothing on this block",
            ]
        );
    }
}
