//! The fast path must build exactly what the grammar builds, for every
//! block it accepts, and leave every other block to the grammar.

#[path = "../benches/program/mod.rs"]
#[allow(dead_code)]
mod program;

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
    gcodec_testkit::each_program(assert_same);
}

#[test]
fn edge_cases_parse_the_same_either_way() {
    for src in [
        "N10 G1 X-1.5 Y+2 Z.5 F200 ; c",
        "/ N10 X1",
        "/3 N10 X1",
        "/12 X1",
        "/ 5 N10 X1",
        "/ 5",
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

#[test]
fn expression_edge_cases_parse_the_same_either_way() {
    for src in [
        "R1=R1+0.5",
        "R2=R3*2-1.25",
        "R4=(R5+R6)/2",
        "r4 = ( r5 + r6 ) / 2",
        "R1=-R2*3",
        "R1=--5",
        "R1=-(1)",
        "R1=NOT R2==1",
        "R1=B_NOT 3 B_AND 4 B_OR 5 B_XOR 6",
        "R1=1 DIV 2 MOD 3",
        "R1=1-2-3",
        "R1=2*(3+4)*5",
        "R1=((((1))))",
        "R1=1<<2",
        "R1=<<R2",
        "R1=R2:R3",
        "R1=R2==R3==R4",
        "R1=1 AND 2 OR 3 XOR 4",
        "R1=R2 R3=4",
        "R1=R2R3=4",
        "R1=(1,2)",
        "R1=(5)",
        "R1=5(3)",
        "R1=5,",
        "R1=R2[1]",
        "R1=R[2]",
        "R1=X1+X",
        "R1=X1.5",
        "R1=1EX999",
        "R1=R99999999999999999999",
        "R1='H1F'",
        "R1=\"s\"",
        "R1=SIN(30)",
        "R1=TRUE",
        "R1=",
        "R1=(1",
        "R1=1)",
        "R=5",
        "R-1=5",
        "R1.5=3",
        "R99999999999=1",
        "R1 X2",
        "R1 = 5",
        "N10 R1=R1+0.5 ; c",
        "/ R1=1",
        "/3 N20 R1=R2*R3",
        "X=R1*2",
        "x=r1",
        "X=",
        "X=(1,2)",
        "X=5 (3)",
        "X=\"s\"",
        "X=IC(5)",
        "X=5X=6",
        "F=R3*2 G1",
        "M=5",
        "P=3 CYCLE81",
        "L10 P=3",
        "N=5",
        "L=5",
        "CR=R1+2",
        "TURN=2*R1",
        "cr=-r1",
        "CR=5,3",
        "AX=5",
        "TRANS=5",
        "LBL: R1=1",
        "IF R1==1 GOTOF LBL",
        "IF R1==1 GOTOB N10",
        "IF (R13<=R14) AND (R15<>0)",
        "IF R1 X5",
        "IF",
        "IF R1==",
        "WHILE R1<5",
        "WHILE",
        "UNTIL R1>=10",
        "N10 ENDWHILE R1=1",
        "ELSE R1=1",
        "REPEAT R1=1",
    ] {
        assert_same(src, src.as_bytes());
    }
}

/// Every operator next to every other, with and without a prefix: the
/// fast path's precedence and associativity are the grammar's.
#[test]
fn every_pair_of_operators_parses_the_same_either_way() {
    const INFIX: [&str; 20] = [
        "*", "/", " DIV ", " MOD ", "+", "-", " B_AND ", " B_XOR ", " B_OR ", " AND ", " XOR ",
        " OR ", "<<", "==", "<>", "<", ">", "<=", ">=", ":",
    ];
    const PREFIX: [&str; 6] = ["", "-", "+", "NOT ", "B_NOT ", "<<"];
    for a in INFIX {
        for b in INFIX {
            for p in PREFIX {
                let src = format!("R1={p}1{a}2{b}3\nIF {p}R1{a}R2{b}R3\n");
                assert_same(&src, src.as_bytes());
            }
        }
    }
}

#[test]
fn the_benchmark_program_parses_the_same_either_way() {
    let src = program::generate(3_000);
    assert_same("generated", &src);
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

fn operand() -> impl Strategy<Value = String> {
    prop::sample::select(vec![
        "1",
        "2.5",
        ".5",
        "5.",
        "1EX2",
        "1EX999",
        "R1",
        "r12",
        "X1",
        "X",
        "R[1]",
        "SIN(30)",
        "\"s\"",
        "'H1F'",
        "TRUE",
        "R1.5",
        "N10",
        "R99999999999999999999",
    ])
    .prop_map(str::to_owned)
}

/// Expressions of operands, prefix and infix operators and parentheses,
/// with and without blanks.
fn expression() -> impl Strategy<Value = String> {
    let prefix = prop::sample::select(vec!["", "", "-", "+", "NOT ", "B_NOT ", "<<"]);
    let leaf = (prefix, operand()).prop_map(|(p, o)| format!("{p}{o}"));
    leaf.prop_recursive(4, 24, 3, |inner| {
        let op = prop::sample::select(vec![
            "+", "-", "*", "/", " DIV ", " MOD ", " AND ", " OR ", " XOR ", "==", "<>", "<", ">",
            "<=", ">=", " B_AND ", " B_OR ", " B_XOR ", "<<", ":", " + ", " * ",
        ]);
        prop_oneof![
            (inner.clone(), op, inner.clone()).prop_map(|(l, o, r)| format!("{l}{o}{r}")),
            inner.clone().prop_map(|e| format!("({e})")),
            inner.prop_map(|e| format!("-{e}")),
        ]
    })
}

fn expression_statement() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec![
            "R1=", "R12 = ", "r3=", "X=", "F=", "CR=", "TURN=", "IF ", "WHILE ", "UNTIL ",
        ]),
        expression(),
        prop::sample::select(vec![
            "",
            "",
            " ",
            ",",
            ")",
            "(2)",
            " GOTOF L1",
            " X5",
            " R3=1",
            "X5",
            " ; c",
        ]),
    )
        .prop_map(|(head, e, tail)| format!("{head}{e}{tail}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]
    #[test]
    fn generated_expression_lines_parse_the_same_either_way(
        number in prop::sample::select(vec!["", "N10 ", "/ N20 "]),
        statements in prop::collection::vec(expression_statement(), 1..3),
        words in prop::collection::vec(word(), 0..3),
    ) {
        let line = format!("{number}{} {}\n", statements.join(" "), words.concat());
        let fast = parse_bytes("gen", line.as_bytes());
        let grammar = parse_bytes_with_grammar_only("gen", line.as_bytes());
        prop_assert_eq!(fast.program, grammar.program, "{:?}", line);
        prop_assert_eq!(fast.diagnostics, grammar.diagnostics, "{:?}", line);
    }
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

/// Lines of constant words are read from their bytes (`word_line.rs`):
/// each of these, alone and among lines that are lexed, gives the
/// grammar's blocks.
#[test]
fn constant_word_lines_parse_the_same_either_way() {
    let lines = [
        "",
        "  ",
        "/ X1",
        "G1 X100.037 Y200.053 F1000",
        "N10 G1 X-1.5 Y+2 Z.5 F200",
        "n10 g1 x-.5 y5.",
        "N10G1X1Y2",
        "G0X1Y2Z3",
        "  N10  G1\tX1  ",
        "G1 X1\r",
        "X1\r Y2",
        "X-0 Y+0 Z0.0",
        "X.",
        "X-",
        "X- 5",
        "X--5",
        "X1.2.3",
        "X1EX2",
        "X1E5",
        "X1.5ex-3",
        "X1EXY",
        "N10.5 X1",
        "N10",
        "N10 ",
        "N10=5",
        "N10X",
        "G1 X1 L5",
        "R1 X1",
        "G1 X1 N20",
        "X1Y",
        "XY1",
        "X_1",
        "X1_",
        "X1 ; c",
        "X1;c",
        "X1&Y2",
        "X1 =5",
        "X1=5",
        "X1(2)",
        "X1[2]",
        "X1\"s\"",
        "X1'H1F'",
        "X1 %",
        "X99999999999999999999999",
        "X1234567890123456.5",
        "X123456789012345.5",
        "X0.00000000000000000000001",
        "X0.0000000000000000000001",
        "N99999999999999999999999 X1",
        "G1 X1 Y2 Z3 A4 B5 C6 U7 V8 W9 F10 S11 T12 D13 M14 H15 E16",
        "G1 X1 Y2 Z3 A4 B5 C6 U7 V8 W9 F10 S11 T12 D13 M14 H15 E16 I17",
        "X\u{e4}1",
    ];
    for line in lines {
        assert_same(line, line.as_bytes());
        let among = format!("G1 X1\n{line}\nIF R1==1\nX2\n{line}\nENDIF\n{line}");
        assert_same(line, among.as_bytes());
    }
}

fn constant_word() -> impl Strategy<Value = String> {
    (
        prop::sample::select(vec!["G", "g", "X", "y", "Z", "F", "M", "S", "A", "T", "E"]),
        prop::sample::select(vec!["", "", "-", "+"]),
        prop::sample::select(vec![
            "1",
            "0",
            "-0",
            "100.037",
            ".5",
            "5.",
            "007",
            "123456789012345",
            "1234567890123456",
            "0.1234567890123456789",
            "1EX2",
        ]),
        prop::sample::select(vec![" ", "", "  ", "\t", " ; c", "=1"]),
    )
        .prop_map(|(a, s, n, t)| format!("{a}{s}{n}{t}"))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn generated_constant_word_programs_parse_the_same_either_way(
        lines in prop::collection::vec(
            (
                prop::sample::select(vec!["", "", "N10 ", "N20", "  ", "/ "]),
                prop::collection::vec(constant_word(), 0..6),
                prop::sample::select(vec!["\n", "\n", "\r\n", "\nENDIF\n", "\nR1=2\n"]),
            ),
            1..12,
        ),
    ) {
        let src: String = lines
            .iter()
            .map(|(number, words, end)| format!("{number}{}{end}", words.concat()))
            .collect();
        let fast = parse_bytes("gen", src.as_bytes());
        let grammar = parse_bytes_with_grammar_only("gen", src.as_bytes());
        prop_assert_eq!(fast.program, grammar.program, "{:?}", src);
        prop_assert_eq!(fast.diagnostics, grammar.diagnostics, "{:?}", src);
    }
}
