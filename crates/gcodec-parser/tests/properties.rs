//! Property tests: the parser never panics or hangs, every span it reports
//! lies inside the file and names its true line and column, parsing is
//! deterministic, and the lexer is lossless.
//!
//! Each case runs on a thread with a 2 MiB stack (what `cargo test` and a
//! typical worker thread give) under a watchdog, so a hang fails the case
//! instead of stalling CI. The case counts are modest to keep the file fast
//! in debug builds; raise them for a deeper run with
//! `PROPTEST_CASES=5000 cargo test -p gcodec-parser --test properties`.

mod common;

use std::sync::mpsc;
use std::thread;
use std::time::Duration;

use common::invariants::{check_parse_of, show, spans_in};
use gcodec_lexer::{Lexer, Token};
use gcodec_parser::{Parse, parse_bytes};
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};
use proptest::prelude::*;
use proptest::test_runner::TestCaseError;
use serde_json::Value;

/// The stack a `cargo test` thread gets.
const SMALL_STACK: usize = 2 * 1024 * 1024;

/// A case taking longer than this counts as a hang (inputs are at most a
/// few KB; a healthy case takes milliseconds even in debug builds).
const WATCHDOG: Duration = Duration::from_secs(20);

/// Case count: `PROPTEST_CASES` if set, else `default`.
fn config(default: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default);
    ProptestConfig {
        cases,
        // Shrinking a hang re-runs it: bound the time spent.
        max_shrink_time: 60_000,
        ..ProptestConfig::default()
    }
}

/// Runs `check(src)` on a fresh 2 MiB thread under the watchdog.
fn guarded(src: &[u8], check: fn(&[u8]) -> Result<(), String>) -> Result<(), TestCaseError> {
    let owned = src.to_vec();
    guard(src, move || check(&owned))
}

/// Runs `f` on a fresh 2 MiB thread under the watchdog; a panic, a failed
/// check or a timeout fails the case, with `input` shown as an escaped byte
/// string.
fn guard(
    input: &[u8],
    f: impl FnOnce() -> Result<(), String> + Send + 'static,
) -> Result<(), TestCaseError> {
    let (tx, rx) = mpsc::channel();
    let handle = thread::Builder::new()
        .stack_size(SMALL_STACK)
        .spawn(move || {
            let result = f();
            let _ = tx.send(result);
        })
        .expect("spawn case thread");
    let shown = show(input);
    match rx.recv_timeout(WATCHDOG) {
        Ok(Ok(())) => Ok(()),
        Ok(Err(msg)) => Err(TestCaseError::fail(format!("{msg}\ninput: {shown}"))),
        Err(mpsc::RecvTimeoutError::Timeout) => Err(TestCaseError::fail(format!(
            "no result within {WATCHDOG:?} (hang)\ninput: {shown}"
        ))),
        Err(mpsc::RecvTimeoutError::Disconnected) => {
            let payload = handle.join().expect_err("the thread died without sending");
            let msg = payload
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| payload.downcast_ref::<&str>().map(|s| (*s).to_owned()))
                .unwrap_or_else(|| "non-string panic".to_owned());
            Err(TestCaseError::fail(format!("panic: {msg}\ninput: {shown}")))
        }
    }
}

/// Rendering must cope with every label (non-UTF-8 sources included).
fn check_render(src: &[u8], parse: &Parse) -> Result<(), String> {
    let file = SourceFile::new("prop.mpf", src);
    let rendered = render_diagnostics(&parse.diagnostics, Some(&file), RenderOptions::default());
    if parse.diagnostics.is_empty() != rendered.is_empty() {
        return Err("rendering lost or invented diagnostics".to_owned());
    }
    Ok(())
}

fn check_parse(src: &[u8]) -> Result<(), String> {
    let parse = parse_bytes("prop.mpf", src);
    check_parse_of(src, &parse)?;
    check_render(src, &parse)
}

/// Parses twice; both results must be identical (NaN-safe: compared as
/// debug text).
fn check_deterministic(src: &[u8]) -> Result<(), String> {
    let first = parse_bytes("prop.mpf", src);
    check_parse_of(src, &first)?;
    check_render(src, &first)?;
    let second = parse_bytes("prop.mpf", src);
    if format!("{first:?}") != format!("{second:?}") {
        return Err("two parses of the same input differ".to_owned());
    }
    Ok(())
}

/// Token texts concatenated reproduce the input: contiguous, non-empty,
/// starting at 0 and ending at the end.
fn check_lexer(src: &[u8]) -> Result<(), String> {
    let mut at = 0u32;
    let mut rebuilt = Vec::with_capacity(src.len());
    for Token { kind, start, end } in Lexer::new(src) {
        if start != at || end <= start || end as usize > src.len() {
            return Err(format!(
                "{kind:?} at {start}..{end}, expected to start at {at}"
            ));
        }
        rebuilt.extend_from_slice(&src[start as usize..end as usize]);
        at = end;
    }
    if at as usize != src.len() || rebuilt != src {
        return Err(format!("tokens cover {at} of {} bytes", src.len()));
    }
    Ok(())
}

/// Fragments of SINUMERIK syntax, valid and not, joined at random.
const VOCAB: &[&[u8]] = &[
    b"G1",
    b"G0",
    b"G",
    b"X",
    b"Y1",
    b"Z",
    b"X1=",
    b"-",
    b"+",
    b"*",
    b"/",
    b"10",
    b"0",
    b".5",
    b"5.",
    b"1.5EX-3",
    b"1EX999",
    b"=",
    b"==",
    b"<>",
    b"<",
    b">=",
    b"R1",
    b"R",
    b"(",
    b")",
    b"[",
    b"]",
    b"IF",
    b"ELSE",
    b"ENDIF",
    b"WHILE",
    b"ENDWHILE",
    b"FOR",
    b"TO",
    b"ENDFOR",
    b"LOOP",
    b"ENDLOOP",
    b"REPEAT",
    b"REPEATB",
    b"UNTIL",
    b"CASE",
    b"OF",
    b"DEFAULT",
    b"GOTOF",
    b"GOTOB",
    b"GOTO",
    b"GOTOS",
    b"GOTOC",
    b"LBL:",
    b"LBL",
    b";c",
    b";",
    b"\n",
    b"\r\n",
    b"\"s\"",
    b"\"",
    b"'H1F'",
    b"'B101'",
    b"'Hx'",
    b"'",
    b"$P_UIFR",
    b"$AA_IM[X]",
    b"$",
    b",",
    b"<<",
    b":",
    b":10",
    b"DEF INT",
    b"DEF REAL",
    b"DEF STRING[8]",
    b"DEF NCK",
    b"REDEF",
    b"DEFINE M AS",
    b"PROC",
    b"ENDPROC",
    b"EXTERN",
    b"VAR",
    b"RET",
    b"N10",
    b"N",
    b"/1",
    b"/12",
    b" ",
    b"\t",
    b"&",
    b"AND",
    b"OR",
    b"NOT",
    b"B_AND",
    b"B_NOT",
    b"DIV",
    b"MOD",
    b"TRUE",
    b"FALSE",
    b"SIN(30)",
    b"CYCLE81",
    b"CYCLE800(,\"TC1\",,,)",
    b"CALL",
    b"BLOCK",
    b"PCALL",
    b"MCALL",
    b"SET(1,,3)",
    b"REP(0)",
    b"ID=1",
    b"IDS=",
    b"WHEN",
    b"WHENEVER",
    b"DO",
    b"TRANS",
    b"ROT",
    b"RPL=",
    b"CR=",
    b"IC(",
    b"M2=3",
    b"M[",
    b"T=\"A\"",
    b"P3",
    b"P=",
    b"L12",
    b"AX[X]",
    b"%_N_A_MPF",
    b"%",
    b"?",
    b"\xfc",
    b"\x00",
    b"_",
    b"STOPRE",
];

fn vocab_program() -> impl Strategy<Value = Vec<u8>> {
    prop::collection::vec(prop::sample::select(VOCAB), 0..64).prop_map(|parts| parts.concat())
}

/// Bytes that mostly form tokens, so the grammar runs on many lines.
fn gcode_bytes() -> impl Strategy<Value = Vec<u8>> {
    const ALPHABET: &[u8] = b"GXYZRNMFSTLPIJK=+-*/()[],:<>.0123456789 \n\n\n;\"'$_ABCDEFHOQUVW&\r";
    prop::collection::vec(prop::sample::select(ALPHABET), 0..2048)
}

/// A short program of lines built from the vocabulary (no line ends or
/// headers inside a line).
fn vocab_line() -> impl Strategy<Value = Vec<u8>> {
    let line_vocab: Vec<&[u8]> = VOCAB
        .iter()
        .copied()
        .filter(|f| !f.contains(&b'\n') && !f.starts_with(b"%"))
        .collect();
    prop::collection::vec(prop::sample::select(line_vocab), 0..12)
        .prop_map(|parts| parts.join(&b' '))
}

/// A line's statements and syntax diagnostics with positions removed, for
/// comparing one line parsed in two places.
fn line_summary(parse: &Parse, block: usize) -> String {
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                let is_span = map.contains_key("start")
                    && map.contains_key("end")
                    && map
                        .keys()
                        .all(|k| ["start", "end", "line", "col"].contains(&k.as_str()));
                if is_span {
                    *v = Value::Null;
                } else {
                    map.values_mut().for_each(strip);
                }
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    let mut statements = serde_json::to_value(&parse.program.blocks[block].statements)
        .expect("statements serialise");
    strip(&mut statements);
    let line = parse.program.blocks[block].span;
    let mut codes: Vec<&str> = parse
        .diagnostics
        .iter()
        .filter(|d| {
            d.span()
                .is_some_and(|s| line.start <= s.start && s.start <= line.end)
        })
        .filter(|d| {
            // Pairing and header placement depend on the other lines.
            ![
                "gcodec::parse::unclosed_structure",
                "gcodec::parse::unmatched_end",
                "gcodec::parse::deep_nesting",
                "gcodec::parse::misplaced_header",
            ]
            .contains(&d.code.name())
        })
        .map(|d| d.code.name())
        .collect();
    codes.sort_unstable();
    format!("{statements} {codes:?}")
}

/// A line parses the same after `filler` other lines as on its own.
fn check_line_independent(filler: &[Vec<u8>], line: &[u8]) -> Result<(), String> {
    let mut src = Vec::new();
    for f in filler {
        src.extend_from_slice(f);
        src.push(b'\n');
    }
    src.extend_from_slice(line);
    src.push(b'\n');
    let alone = parse_bytes("alone.mpf", &[line, b"\n"].concat());
    let within = parse_bytes("within.mpf", &src);
    check_parse_of(&src, &within)?;
    let (a, w) = (line_summary(&alone, 0), line_summary(&within, filler.len()));
    if a != w {
        return Err(format!(
            "line {} parses differently after {} lines:\nalone:  {a}\nwithin: {w}",
            show(line),
            filler.len()
        ));
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    /// (a) Arbitrary bytes: no panic, every span in bounds and on its true
    /// line, one block per line, diagnostics render.
    #[test]
    fn arbitrary_bytes_parse(src in prop::collection::vec(any::<u8>(), 0..2048)) {
        guarded(&src, check_parse)?;
    }

    /// (a) Bytes from the G-code alphabet reach the grammar far more often.
    #[test]
    fn gcode_alphabet_parses(src in gcode_bytes()) {
        guarded(&src, check_parse)?;
    }

    /// (b) Sequences of SINUMERIK fragments: no panic, spans in bounds,
    /// deterministic.
    #[test]
    fn fragment_sequences_parse_deterministically(src in vocab_program()) {
        guarded(&src, check_deterministic)?;
    }

    /// (c) The lexer is lossless on arbitrary bytes.
    #[test]
    fn lexer_round_trips_bytes(src in prop::collection::vec(any::<u8>(), 0..2048)) {
        guarded(&src, check_lexer)?;
    }

    /// (c) The lexer is lossless on fragment sequences.
    #[test]
    fn lexer_round_trips_fragments(src in vocab_program()) {
        guarded(&src, check_lexer)?;
    }
}

proptest! {
    #![proptest_config(config(64))]

    /// One malformed block never changes how another parses: a line parses
    /// the same after a few other lines as on its own.
    #[test]
    fn lines_parse_independently(
        filler in prop::collection::vec(vocab_line(), 0..16),
        line in vocab_line(),
    ) {
        let input = [filler.join(&b'\n'), line.clone()].join(&b'\n');
        guard(&input, move || check_line_independent(&filler, &line))?;
    }
}

proptest! {
    #![proptest_config(config(16))]

    /// The same across the driver's 2048-line chunk boundary: the line
    /// after 2048 others starts a new chunk.
    #[test]
    fn lines_parse_independently_across_chunks(
        filler in prop_oneof![Just(2048usize), 2040..2056usize]
            .prop_flat_map(|n| prop::collection::vec(vocab_line(), n)),
        line in vocab_line(),
    ) {
        let input = [filler.join(&b'\n'), line.clone()].join(&b'\n');
        guard(&input, move || check_line_independent(&filler, &line))?;
    }
}

/// The span walk must actually see nested spans, or the properties above
/// would check nothing.
#[test]
fn span_walk_reaches_expressions() {
    let src = b"N10 G1 X=R1+SIN(30) ; c\nIF R2==1 GOTOF LBL\n";
    let parse = parse_bytes("walk.mpf", src);
    assert!(parse.diagnostics.is_empty(), "{:#?}", parse.diagnostics);
    let value = serde_json::to_value(&parse.program).expect("serialises");
    let spans = spans_in(&value).expect("every span has its position");
    // Among them the `30` inside `SIN(30)`, on line 1 at column 17.
    assert!(
        spans
            .iter()
            .any(|s| &src[s.span.range()] == b"30" && (s.line, s.col) == (1, 17)),
        "{spans:#?}"
    );
    assert!(spans.len() > 15, "{}", spans.len());
    check_parse(src).expect("valid");
}

/// Found by the `parse` fuzz target: the spans of a parse of bytes with a
/// leading byte-order mark counted the mark, which the file holding the
/// same bytes drops, so they ran past the file's end.
#[test]
fn a_leading_byte_order_mark_is_not_part_of_the_parsed_program() {
    let src = b"\xef\xbb\xbfSETAL(%12X1";
    check_parse(src).expect("spans into the file's bytes");
    let with_mark = parse_bytes("bom.mpf", src);
    let without = parse_bytes("bom.mpf", &src[3..]);
    assert_eq!(with_mark.program, without.program);
    assert_eq!(with_mark.diagnostics, without.diagnostics);
}
