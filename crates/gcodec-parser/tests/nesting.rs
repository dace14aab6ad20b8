//! Pathological nesting and size: the parser must finish on a thread with
//! a 2 MiB stack (what `cargo test` gives each test, and what a host
//! application's worker thread typically has), without panicking, and report
//! the documented diagnostics (SPEC §5, §6 "Control structures", §7).
//!
//! Each case runs on a thread of its own with an explicit 2 MiB stack, so
//! `RUST_MIN_STACK` cannot hide an overflow, and under a watchdog, so a hang
//! fails the test instead of stalling CI. Dropping the result happens on the
//! small stack too: a syntax tree whose destructor recurses per level would
//! overflow there.

mod common;

use std::sync::mpsc;
use std::thread;
use std::time::{Duration, Instant};

use common::invariants::line_count;
use gcodec_parser::ast::{StatementKind, StructureKind};
use gcodec_parser::{MAX_EXPRESSION_DEPTH, MAX_OPERATORS_PER_BLOCK, Parse, parse_bytes};
use gcodec_source::{Diagnostic, Severity, Span};

/// The stack a `cargo test` thread gets.
const SMALL_STACK: usize = 2 * 1024 * 1024;

/// How long one case may take in a debug build on a busy 2-core machine
/// before it counts as a hang. The real cases take well under a second in
/// release builds; this bound only catches runaway (quadratic or endless)
/// behaviour.
const WATCHDOG: Duration = Duration::from_secs(120);

/// Runs `f` on a fresh 2 MiB thread under the watchdog and returns its
/// result; a panic in `f` is re-raised here.
fn on_small_stack<T: Send + 'static>(what: &str, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = mpsc::channel();
    let started = Instant::now();
    let handle = thread::Builder::new()
        .name(what.to_owned())
        .stack_size(SMALL_STACK)
        .spawn(move || {
            let out = f();
            let _ = tx.send(());
            out
        })
        .expect("spawn test thread");
    match rx.recv_timeout(WATCHDOG) {
        Ok(()) => {
            let out = handle.join().expect("thread finished");
            eprintln!("{what}: {:.2?}", started.elapsed());
            out
        }
        Err(mpsc::RecvTimeoutError::Timeout) => {
            panic!("{what}: did not finish within {WATCHDOG:?} (hang or runaway time)")
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => match handle.join() {
            Err(panic) => std::panic::resume_unwind(panic),
            Ok(_) => unreachable!("the thread sends before it returns"),
        },
    }
}

fn check_span(src: &[u8], span: Span, what: &str) {
    let len = src.len() as u32;
    assert!(
        span.start <= span.end && span.end <= len,
        "{what}: span {span:?} out of bounds (len {len})"
    );
}

/// Invariants every parse must satisfy, cheap enough for huge inputs (no
/// walk into expressions: the deep-expression cases check those by
/// serialising).
fn check_invariants(src: &[u8], parse: &Parse) {
    assert_eq!(
        parse.program.blocks.len(),
        line_count(src),
        "one block per line"
    );
    for block in &parse.program.blocks {
        check_span(src, block.span, "block");
        for st in &block.statements {
            check_span(src, st.span, "statement");
        }
    }
    for d in &parse.diagnostics {
        for label in &d.labels {
            check_span(src, label.span, d.code.name());
        }
    }
}

fn count(diagnostics: &[Diagnostic], code: &str) -> usize {
    diagnostics.iter().filter(|d| d.code == code).count()
}

fn codes(diagnostics: &[Diagnostic]) -> Vec<&'static str> {
    let mut codes: Vec<_> = diagnostics.iter().map(|d| d.code.name()).collect();
    codes.sort_unstable();
    codes.dedup();
    codes
}

/// Parses `src` on a small stack; returns the diagnostics (the program is
/// checked and dropped on the small stack).
fn parse_small(what: &str, src: Vec<u8>) -> Vec<Diagnostic> {
    on_small_stack(what, move || {
        let parse = parse_bytes("nesting.mpf", &src);
        check_invariants(&src, &parse);
        parse.diagnostics.to_vec()
    })
}

const N: usize = 10_000;

#[test]
fn ten_thousand_nested_parentheses() {
    let mut src = b"N10 R1=".to_vec();
    src.extend(std::iter::repeat_n(b'(', N));
    src.push(b'1');
    src.extend(std::iter::repeat_n(b')', N));
    src.extend_from_slice(b"\nN20 M30\n");
    let diags = parse_small("parentheses", src);
    assert_eq!(codes(&diags), ["gcodec::parse::nesting_too_deep"]);
    assert_eq!(diags.len(), 1, "one diagnostic for the block: {diags:#?}");
    let span = diags[0].span().expect("labelled");
    // The first bracket past the limit: `N10 R1=` is 7 bytes.
    assert_eq!(span.start as usize, 7 + MAX_EXPRESSION_DEPTH);
    assert_eq!(span.len(), 1);
}

#[test]
fn ten_thousand_nested_brackets() {
    let mut src = b"R[".to_vec();
    for _ in 1..N {
        src.extend_from_slice(b"R[");
    }
    src.push(b'1');
    src.extend(std::iter::repeat_n(b']', N));
    src.extend_from_slice(b"=1\n");
    let diags = parse_small("brackets", src);
    assert_eq!(codes(&diags), ["gcodec::parse::nesting_too_deep"]);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    let span = diags[0].span().expect("labelled");
    // Bracket number 65 sits at byte 64 * 2 + 1.
    assert_eq!(span.start as usize, MAX_EXPRESSION_DEPTH * 2 + 1);
}

#[test]
fn ten_thousand_mixed_brackets_and_parentheses() {
    let mut src = b"X=".to_vec();
    for _ in 0..N / 2 {
        src.extend_from_slice(b"A[(");
    }
    src.push(b'1');
    for _ in 0..N / 2 {
        src.extend_from_slice(b")]");
    }
    let diags = parse_small("mixed brackets", src);
    assert_eq!(codes(&diags), ["gcodec::parse::nesting_too_deep"]);
    assert_eq!(diags.len(), 1, "{diags:#?}");
}

/// Exactly at the limit the expression is parsed, and the tree (64 levels
/// deep) is serialised and dropped on the small stack.
#[test]
fn nesting_at_the_limit_parses_and_serialises() {
    for (open, close) in [(b'(', b')'), (b'[', b']')] {
        let mut src = b"R1=".to_vec();
        for _ in 0..MAX_EXPRESSION_DEPTH {
            if open == b'[' {
                src.extend_from_slice(b"R[");
            } else {
                src.push(open);
            }
        }
        src.push(b'1');
        src.extend(std::iter::repeat_n(close, MAX_EXPRESSION_DEPTH));
        src.push(b'\n');
        let what = format!("limit {}", open as char);
        let text = String::from_utf8(src.clone()).expect("ASCII");
        let (diags, json_len) = on_small_stack(&what, move || {
            let parse = parse_bytes("limit.mpf", &src);
            check_invariants(&src, &parse);
            let json = serde_json::to_string(&parse.program).expect("serialises");
            (parse.diagnostics, json.len())
        });
        assert!(diags.is_empty(), "{text}: {diags:#?}");
        assert!(json_len > 0);
    }
    // One more is too deep.
    let mut src = b"R1=".to_vec();
    src.extend(std::iter::repeat_n(b'(', MAX_EXPRESSION_DEPTH + 1));
    src.push(b'1');
    src.extend(std::iter::repeat_n(b')', MAX_EXPRESSION_DEPTH + 1));
    let diags = parse_small("limit + 1", src);
    assert_eq!(codes(&diags), ["gcodec::parse::nesting_too_deep"]);
}

/// `depth` IFs, each in a block of its own, a block inside them, then
/// `depth` ENDIFs: one warning at the 17th IF, every structure paired, and
/// the flat tree serialises without recursing per level.
fn nested_ifs(depth: usize) {
    let mut src = Vec::new();
    for i in 0..depth {
        src.extend_from_slice(format!("IF R{}==1\n", i % 100).as_bytes());
    }
    src.extend_from_slice(b"G1 X1\n");
    for _ in 0..depth {
        src.extend_from_slice(b"ENDIF\n");
    }
    let (diags, json_len) = on_small_stack("nested IFs", move || {
        let parse = parse_bytes("ifs.mpf", &src);
        check_invariants(&src, &parse);
        let program = &parse.program;
        assert_eq!(program.structures.len(), depth);
        for (i, s) in program.structures.iter().enumerate() {
            assert_eq!(s.kind, StructureKind::If);
            assert_eq!(s.open as usize, i);
            assert_eq!(s.close.map(|c| c as usize), Some(2 * depth - i));
            assert_eq!(s.middle, None);
        }
        assert_eq!(
            program.blocks[depth].depth as usize, depth,
            "innermost block"
        );
        assert_eq!(program.blocks[2 * depth].depth, 0, "last ENDIF");
        assert!(matches!(
            program.blocks[0].statements[0].kind,
            StatementKind::If(_)
        ));
        // The tree is flat: serialising it must not recurse per level.
        let json = serde_json::to_string(&parse.program).expect("serialises");
        (parse.diagnostics, json.len())
    });
    assert!(json_len > depth * 10);
    assert_eq!(codes(&diags), ["gcodec::parse::deep_nesting"], "{diags:#?}");
    assert_eq!(
        diags.len(),
        1,
        "one warning, at the first structure too deep"
    );
    assert_eq!(diags[0].severity, Severity::Warning);
    let span = diags[0].span().expect("labelled");
    let line_17: usize = (0..16).map(|i| format!("IF R{}==1\n", i % 100).len()).sum();
    assert_eq!(
        span.start as usize, line_17,
        "the 17th IF is the first too deep"
    );
}

#[test]
fn ten_thousand_nested_ifs() {
    nested_ifs(N);
}

/// The same within one 2048-line parse chunk, so that a failure here
/// separates the pairing logic from the chunking.
#[test]
fn thousand_nested_ifs() {
    nested_ifs(1_000);
}

/// `depth` IFs never closed, then `M30` without a line end.
fn unclosed_ifs(depth: usize) {
    let mut src = Vec::new();
    for _ in 0..depth {
        src.extend_from_slice(b"IF 1\n");
    }
    src.extend_from_slice(b"M30");
    let len = src.len() as u32;
    let diags = parse_small("unclosed IFs", src);
    assert_eq!(count(&diags, "gcodec::parse::unclosed_structure"), depth);
    assert_eq!(count(&diags, "gcodec::parse::deep_nesting"), 1);
    assert_eq!(diags.len(), depth + 1, "{:#?}", &diags[..5]);
    for d in diags
        .iter()
        .filter(|d| d.code == "gcodec::parse::unclosed_structure")
    {
        assert!(d.is_error());
        assert_eq!(d.labels.len(), 2, "opener and expected end");
        // The end is expected at the end of the last block, `M30`.
        let end = d.labels[1].span;
        assert_eq!((end.start, end.end), (len, len));
    }
}

#[test]
fn ten_thousand_unclosed_ifs() {
    unclosed_ifs(N);
}

#[test]
fn thousand_unclosed_ifs() {
    unclosed_ifs(1_000);
}

fn endifs_without_if(n: usize) {
    let src = b"ENDIF\n".repeat(n);
    let diags = parse_small("ENDIFs", src);
    assert_eq!(codes(&diags), ["gcodec::parse::unmatched_end"]);
    assert_eq!(diags.len(), n);
    assert!(diags.iter().all(Diagnostic::is_error));
    // Reported in source order.
    assert!(
        diags
            .windows(2)
            .all(|w| w[0].labels[0].span.start < w[1].labels[0].span.start)
    );
}

#[test]
fn hundred_thousand_endifs_without_if() {
    endifs_without_if(100_000);
}

#[test]
fn two_thousand_endifs_without_if() {
    endifs_without_if(2_000);
}

/// The driver parses 2048 lines at a time. The line after a chunk must
/// still get its own tokens: here line 2049 is `X1 Y2`.
#[test]
fn line_straddling_a_chunk_boundary() {
    // Panics: the first 2048 lines hold 4096 tokens, line 2049 two.
    let src = [b"G1\n".repeat(2048), b"X1".to_vec()].concat();
    let diags = parse_small("2049 lines", src);
    assert!(diags.is_empty(), "{diags:#?}");
    // Silently wrong: the first chunk holds 2 tokens, so line 2049 loses
    // its first two (`X`, `1`) and keeps only `Y2`.
    let src = [b"G1\n".to_vec(), b"\n".repeat(2047), b"X1 Y2\n".to_vec()].concat();
    let statements = on_small_stack("2049 lines, 2 tokens", move || {
        let parse = parse_bytes("chunk.mpf", &src);
        check_invariants(&src, &parse);
        assert!(parse.diagnostics.is_empty(), "{:#?}", parse.diagnostics);
        parse.program.blocks[2048].statements.len()
    });
    assert_eq!(statements, 2, "`X1 Y2` is two words");
}

#[test]
fn one_megabyte_line_of_words() {
    // `G1 X1 Y2 ` … : about 110,000 statements on one line, no line end.
    let unit = b"G1 X1.5 Y-2 ";
    let src = unit.repeat((1 << 20) / unit.len() + 1);
    let statements = src.len() / unit.len() * 3;
    let (diags, n) = on_small_stack("1 MB of words", move || {
        let parse = parse_bytes("long.mpf", &src);
        check_invariants(&src, &parse);
        (parse.diagnostics, parse.program.blocks[0].statements.len())
    });
    assert!(diags.is_empty(), "{:#?}", &diags[..diags.len().min(3)]);
    assert_eq!(n, statements);
}

#[test]
fn one_megabyte_comment_line() {
    let mut src = b"G1 X1 ;".to_vec();
    src.extend(std::iter::repeat_n(b'c', 1 << 20));
    src.extend_from_slice(b"\r\nM30\r\n");
    let diags = parse_small("1 MB comment", src);
    assert!(diags.is_empty(), "{diags:#?}");
}

#[test]
fn one_megabyte_line_of_garbage() {
    // Invalid characters, unclosed strings and stray brackets: one
    // diagnostic for the line, not one per byte.
    let unit = b"?! \"x ] ) ( [ 'H' ";
    let src = unit.repeat((1 << 20) / unit.len() + 1);
    let diags = parse_small("1 MB of garbage", src);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert_eq!(diags[0].code, "gcodec::parse::invalid_character");
}

#[test]
fn one_megabyte_line_of_unbalanced_brackets() {
    // A million closers never deepen: the grammar runs and fails once.
    let mut src = b"R1=1".to_vec();
    src.extend(std::iter::repeat_n(b')', 1 << 20));
    let diags = parse_small("1 MB of `)`", src);
    assert_eq!(diags.len(), 1, "{diags:#?}");
    assert!(diags[0].is_error());
}

#[test]
fn line_of_ten_thousand_statements() {
    let mut src = b"N10".to_vec();
    for i in 0..N {
        let word = match i % 5 {
            0 => format!(" G{}", i % 4),
            1 => format!(" X{i}"),
            2 => format!(" Y=R{}", i % 100),
            3 => format!(" R{}={}", i % 100, i),
            _ => " M=QU(8)".to_owned(),
        };
        src.extend_from_slice(word.as_bytes());
    }
    src.push(b'\n');
    let (diags, n, number) = on_small_stack("10,000 statements", move || {
        let parse = parse_bytes("many.mpf", &src);
        check_invariants(&src, &parse);
        let block = &parse.program.blocks[0];
        (
            parse.diagnostics.clone(),
            block.statements.len(),
            block.number.as_ref().map(|n| n.value),
        )
    });
    assert!(diags.is_empty(), "{:#?}", &diags[..diags.len().min(3)]);
    assert_eq!(n, N);
    assert_eq!(number, Some(10));
}

#[test]
fn hundred_ifs_on_one_line() {
    // Structure openers in one block: each still counts as nesting.
    let src = format!("{}\n{}\n", "IF 1 ".repeat(100), "ENDIF ".repeat(100)).into_bytes();
    let diags = parse_small("100 IFs on one line", src);
    assert_eq!(codes(&diags), ["gcodec::parse::deep_nesting"], "{diags:#?}");
}

/// `R1=1+1+…` with `n` operators, or `R1=--…-1` with `prefix`.
fn chain(op: &str, n: usize, prefix: bool) -> Vec<u8> {
    let mut src = b"R1=".to_vec();
    if prefix {
        src.extend_from_slice(op.repeat(n).as_bytes());
        src.push(b'1');
    } else {
        src.push(b'1');
        for _ in 0..n {
            src.extend_from_slice(op.as_bytes());
            src.push(b'1');
        }
    }
    src.push(b'\n');
    src
}

const TOO_COMPLEX: &str = "gcodec::parse::block_too_complex";

/// A chain of binary operators is not bracket nesting, but it builds an
/// expression tree one level deeper per operator: past
/// [`MAX_OPERATORS_PER_BLOCK`] the block is reported, not parsed (SPEC §5).
#[test]
fn ten_thousand_binary_operators() {
    for op in ["+", "*", " AND ", "<<", ":", "=="] {
        let src = chain(op, N, false);
        let diags = parse_small(&format!("binary chain `{}`", op.trim()), src);
        assert_eq!(codes(&diags), [TOO_COMPLEX], "{op}: {diags:#?}");
        assert_eq!(diags.len(), 1);
        // The first operator over the limit: `R1=1` then `op1` per operator.
        let span = diags[0].span().expect("labelled");
        let first = 4 + MAX_OPERATORS_PER_BLOCK * (op.len() + 1);
        assert_eq!(
            span.start as usize,
            first + op.find(|c| c != ' ').unwrap_or(0),
            "{op}"
        );
    }
}

/// Prefix operators nest like brackets without being brackets.
#[test]
fn ten_thousand_prefix_operators() {
    for op in ["-", "+", "NOT ", "B_NOT ", "<<"] {
        let src = chain(op, N, true);
        let diags = parse_small(&format!("prefix chain `{}`", op.trim()), src);
        assert_eq!(codes(&diags), [TOO_COMPLEX], "{op}: {diags:#?}");
        assert_eq!(diags.len(), 1);
    }
}

/// A 1 MB line holding one expression of half a million operators.
#[test]
fn one_megabyte_operator_chain() {
    for (op, prefix) in [("+", false), ("-", true)] {
        let src = chain(op, (1 << 20) / 2, prefix);
        let diags = parse_small(&format!("1 MB chain `{op}`"), src);
        assert_eq!(codes(&diags), [TOO_COMPLEX], "{diags:#?}");
        assert_eq!(diags.len(), 1);
    }
}

/// At the limits the block parses, and the deepest tree they allow is
/// serialised, cloned, printed and dropped on the small stack.
#[test]
fn deepest_expression_within_the_limits() {
    let n = MAX_OPERATORS_PER_BLOCK;
    let mut cases = vec![
        ("binary", chain("+", n, false)),
        ("prefix", chain("-", n, true)),
        ("right-nested", {
            // `1+(1+(1+(…)))` as deep as brackets allow, then a chain.
            let mut src = b"R1=".to_vec();
            for _ in 0..MAX_EXPRESSION_DEPTH {
                src.extend_from_slice(b"1+(");
            }
            src.push(b'1');
            for _ in 0..n - MAX_EXPRESSION_DEPTH {
                src.extend_from_slice(b"*1");
            }
            src.extend(std::iter::repeat_n(b')', MAX_EXPRESSION_DEPTH));
            src.push(b'\n');
            src
        }),
    ];
    // Prefix and binary operators mixed: `- -1 - -1 …`.
    let mut mixed = b"R1=".to_vec();
    for _ in 0..n / 2 {
        mixed.extend_from_slice(b"-1-");
    }
    mixed.extend_from_slice(b"1\n");
    cases.push(("mixed", mixed));
    for (what, src) in cases {
        let text_len = src.len();
        let (diags, json_len) = on_small_stack(what, move || {
            let parse = parse_bytes("limit.mpf", &src);
            check_invariants(&src, &parse);
            let json = serde_json::to_string(&parse.program).expect("serialises");
            let copy = parse.program.clone();
            assert_eq!(copy, parse.program);
            let debug = format!("{:?}", parse.program);
            assert!(debug.len() > src.len());
            (parse.diagnostics, json.len())
        });
        assert!(diags.is_empty(), "{what}: {diags:#?}");
        assert!(json_len > text_len, "{what}");
    }
    // One operator more is too many.
    let diags = parse_small("limit + 1", chain("+", n + 1, false));
    assert_eq!(codes(&diags), [TOO_COMPLEX]);
}

/// Signs of DIN constants (`X-10`) are not operators: a long line of
/// words is not "too complex".
#[test]
fn signed_words_are_not_operators() {
    let src = b"X-1 Y+2 ".repeat(2 * MAX_OPERATORS_PER_BLOCK);
    let diags = parse_small("signed words", src);
    assert!(diags.is_empty(), "{:#?}", &diags[..diags.len().min(3)]);
}
