//! The fast path for constant-word blocks must build exactly what the
//! grammar builds.

mod common;

use gcodec_parser::{parse_bytes, parse_bytes_with_grammar_only};
use proptest::prelude::*;

fn assert_same(name: &str, src: &[u8]) {
    let fast = parse_bytes(name, src);
    let grammar = parse_bytes_with_grammar_only(name, src);
    assert_eq!(fast.program, grammar.program, "{name}");
    assert_eq!(fast.diagnostics, grammar.diagnostics, "{name}");
}

#[test]
fn fixtures_and_corpus_parse_the_same_either_way() {
    let all = common::all_programs();
    assert!(all.len() >= 30, "found only {} programs", all.len());
    for path in all {
        let bytes = std::fs::read(&path).expect("readable");
        assert_same(&path.display().to_string(), &bytes);
    }
}

#[test]
fn edge_cases_parse_the_same_either_way() {
    for src in [
        "N10 G1 X-1.5 Y+2 Z.5 F200 ; c",
        "/ N10 X1",
        "/3 N10 X1",
        "/12 X1",
        "N10",
        "N10=5",
        "X1=5",
        "X1 =5",
        "M5[10]=3",
        "M 5",
        "X- 5",
        "X -5",
        "L12 P3",
        "R1 X2",
        "T\"10\"",
        "T1\"10\"",
        "X1(2)",
        "x1.5ex-3 y2EX2",
        "X99999999999999999999999",
        "N99999999999999999999999 X1",
        "G0X1Y2Z3",
        "X1.5EX",
        "G2 X1 CR=-20.5",
        "CR=5",
        "CR=+5 X1",
        "CR=5+1",
        "CR=5X1",
        "CR=1EX999",
        "cr=5 spos=90 M3",
        "ELX=3",
        "CR=(5)",
        "CR=R1",
        "CR=-5 ; c",
        "ENDIF",
        "N10 ENDIF ; end",
        "/ ELSE",
        "REPEAT",
        "REPEAT LBL",
        "ELSE X1",
        "LOOP",
        "ENDPROC",
    ] {
        assert_same(src, src.as_bytes());
    }
}

fn word() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => letter_word(),
        1 => named_word(),
    ]
}

fn named_word() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec!["CR", "cr", "TURN", "ELX", "AR"]),
        prop::sample::select(vec!["=", " = ", "="]),
        prop::sample::select(vec!["", "-", "+"]),
        prop::sample::select(vec!["5", "-20.5", ".5", "1EX999", "R1"]),
        prop::sample::select(vec![" ", "", "+1", "*2 "]),
    )
        .prop_map(|(a, e, s, n, t)| format!("{a}{e}{s}{n}{t}"))
}

fn letter_word() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec![
            "G", "X", "y", "Z", "F", "M", "S", "N", "A", "R", "L", "T", "D",
        ]),
        prop::sample::select(vec!["", "-", "+", " ", " -"]),
        prop::sample::select(vec!["1", "10", "-0", ".5", "5.", "1.5EX-3", "007", "1.2.3"]),
        prop::sample::select(vec![" ", "", "  ", "=", "[1]", "(2)", "\"s\""]),
    )
        .prop_map(|(a, s, n, t)| format!("{a}{s}{n}{t}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn generated_word_lines_parse_the_same_either_way(
        skip in prop::sample::select(vec!["", "/", "/2 ", "/ "]),
        words in prop::collection::vec(word(), 0..8),
        keyword in prop::sample::select(vec!["", "ENDIF", "ELSE ", "LOOP", "N5 ENDWHILE"]),
        comment in prop::sample::select(vec!["", " ; move", ";x"]),
    ) {
        let line = if keyword.is_empty() {
            format!("{skip}{}{comment}\n", words.concat())
        } else {
            format!("{skip}{keyword}{comment}\n")
        };
        let fast = parse_bytes("gen", line.as_bytes());
        let grammar = parse_bytes_with_grammar_only("gen", line.as_bytes());
        prop_assert_eq!(fast.program, grammar.program, "{:?}", line);
        prop_assert_eq!(fast.diagnostics, grammar.diagnostics, "{:?}", line);
    }
}
