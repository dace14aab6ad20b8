//! Skimming a chunk for lowering's `Outline` (`skim_chunk`) leaves out
//! only what no `Outline` reads: every block it keeps is the parsed block,
//! and every block it leaves out keeps the parsed block's span, skip mark
//! and number, holds only words (no `M`), assignments, calls by name and
//! frames, and follows a block that leaves the plain lines after it
//! skimmable, with only left-out blocks between.

#[path = "../benches/program/mod.rs"]
#[allow(dead_code)]
mod program;

use gcodec_parser::ast::StatementKind;
use gcodec_parser::{Macros, parse_chunk, plain_lines_skimmable_after, skim_chunk};
use gcodec_source::Encoding;
use gcodec_stream::chunks;
use proptest::prelude::*;

/// Whether a statement is one a left-out block may hold.
fn may_be_left_out(kind: &StatementKind) -> bool {
    match kind {
        StatementKind::Word(w) => w.address() != "M",
        StatementKind::Assign(_) | StatementKind::Call(_) | StatementKind::Frame(_) => true,
        _ => false,
    }
}

/// Checks the skim of `src` in chunks of `lines` lines against the parse;
/// returns how many blocks it left out.
fn assert_skim_agrees(name: &str, src: &[u8], lines: usize) -> usize {
    let mut left_out = 0;
    for chunk in chunks(src, lines) {
        let parsed = parse_chunk(src, Encoding::UTF_8, &chunk, &Macros::default());
        let skimmed = skim_chunk(src, Encoding::UTF_8, &chunk, &Macros::default());
        let place =
            |i: usize| format!("{name}, chunks of {lines}, block {}", chunk.first_block + i);
        assert_eq!(parsed.blocks.len(), skimmed.blocks.len(), "{name}");
        assert_eq!(parsed.structure_blocks, skimmed.structure_blocks, "{name}");
        assert!(skimmed.diagnostics.is_empty(), "{name}");
        // The skim finds the header the parse finds.
        assert_eq!(parsed.header, skimmed.header, "{name}: the header");
        let mut skimmable = false;
        for (i, (whole, skim)) in parsed.blocks.iter().zip(&skimmed.blocks).enumerate() {
            if whole == skim {
                // A block without statements or label reads the same
                // parsed or left out, and either way leaves the state as
                // it was.
                if !whole.statements.is_empty() || whole.label.is_some() {
                    skimmable = plain_lines_skimmable_after(whole);
                }
                continue;
            }
            left_out += 1;
            assert!(
                skimmable,
                "{}: left out after a block that leaves no line skimmable",
                place(i)
            );
            assert_eq!(whole.span, skim.span, "{}", place(i));
            assert_eq!(whole.skip, skim.skip, "{}", place(i));
            assert_eq!(whole.number, skim.number, "{}", place(i));
            assert!(
                whole.label.is_none() && skim.label.is_none(),
                "{}",
                place(i)
            );
            assert!(skim.statements.is_empty(), "{}", place(i));
            for statement in &whole.statements {
                assert!(
                    may_be_left_out(&statement.kind),
                    "{}: left out {:?}",
                    place(i),
                    statement.kind
                );
            }
        }
    }
    left_out
}

#[test]
fn fixtures_and_corpus_skim_as_they_parse() {
    gcodec_testkit::each_program(|name, src| {
        for lines in [1, 7, 1024] {
            assert_skim_agrees(name, src, lines);
        }
    });
}

#[test]
fn most_blocks_of_the_generated_program_are_left_out() {
    let src = program::generate(20_000);
    let left_out = assert_skim_agrees("generated", &src, 1024);
    assert!(left_out > 20_000 * 3 / 4, "only {left_out} left out");
}

#[test]
fn edge_cases_skim_as_they_parse() {
    let lines = [
        "N10 G1 X1 F100",
        "X2 Y3 ; comment: with GOTOF and M30",
        "N20 M30",
        "m17",
        "M=30",
        "N30 X4",
        "N40 X5 ; after the end",
        "R1=R2 AND R3 OR NOT R4 B_AND 5 DIV 2 MOD 3",
        "N50 X=",
        "N60 X1 .",
        "N70 X1 _",
        "N80 X1 ?",
        "N90.5 X1",
        "N99999999999999999999 X1",
        "N100=5",
        "N110 == 5",
        "/ N120 X1",
        "/3 N130 X1",
        "/ 5 N140 X1",
        "/12 N150 X1",
        "  & N160 X1",
        "N170 X1EX2 Y1.",
        "N180 X1IF",
        "N190 IF1=2",
        "N200 GOTOF1=3",
        "N210 X1 GOTOF N10",
        "N220 XIF=1",
        "N230 MYSUB",
        "N240 TRANS X1",
        "N250 CR=5 X1",
        "N260 R1=1+1+1",
        "N270 $R1=1",
        "N280 X1 \"a\"",
        "N290 X1 'H1F'",
        "LBL: X1",
        "N300 X2",
        "DEF REAL AA",
        "N310 X3",
        "N320 X4\r",
        "",
        "N330",
        "N340 X(((1)))",
        "N350 X1 ENDIF",
        "ENDPROC",
        "N360 X1",
        "N370 X2",
        "%_N_ABC_MPF",
        "N380 X3",
        "N390 X4 ä",
        "N400 X5",
        "N410 =5",
        "N420==5",
        "N430;c",
        "N440&X1",
        "n450\tX1",
        "N460E3",
        "N470EX2 X1",
        "N480X1",
        "   N490",
        "N X1",
        "NX1=2",
        "N0000000000000000000000001 X1",
    ];
    let src = lines.join("\n");
    for chunk_lines in [1, 2, 3, 1024] {
        assert_skim_agrees("edges", src.as_bytes(), chunk_lines);
    }
    // Blocks are left out here and others kept: the test sees both kinds.
    assert!(assert_skim_agrees("edges", src.as_bytes(), 1024) >= 5);
    // Headers after lines a skim may leave out.
    for src in ["; c\nX1\n%_N_T_MPF\nX2\n", "\nX1 Y2\n\n%_N_T_MPF\n"] {
        for chunk_lines in [1, 2, 1024] {
            assert_skim_agrees(src, src.as_bytes(), chunk_lines);
        }
    }
}

/// A line of pieces that are plain and pieces that are not.
fn line() -> impl Strategy<Value = String> {
    let piece = prop::sample::select(vec![
        "N10",
        "n20",
        "G1",
        "X1.5",
        "Y-2",
        "Z.5",
        "F100",
        "R1=R2+1",
        "X=R1*2",
        "CR=5",
        "M8",
        "M30",
        "m2",
        "IF R1>0",
        "ENDIF",
        "ELSE",
        "WHILE 1",
        "ENDWHILE",
        "LBL:",
        "GOTOF LBL",
        "GOTOB N10",
        "DEF REAL AA",
        "AA=1",
        "PROC P",
        "ENDPROC",
        "RET",
        "MYSUB",
        "TRANS X1",
        "\"s\"",
        "$P_UIFR[1]=0",
        "N10=5",
        "/",
        "/3",
        "/ 5",
        ";c",
        "; GOTOF",
        "X=",
        "(",
        ")",
        "AND",
        "IF1",
        "_",
        ".",
        "?",
        "1EX2",
        "REPEAT",
        "UNTIL 1",
        "CALL \"X\" BLOCK A TO B",
        "L10",
        "%_N_X_MPF",
        "\t",
        "&",
    ]);
    prop::collection::vec(piece, 0..5).prop_map(|pieces| pieces.join(" "))
}

proptest! {
    #[test]
    fn random_programs_skim_as_they_parse(
        lines in prop::collection::vec(line(), 1..40),
        chunk_lines in 1usize..8,
    ) {
        let src = lines.join("\n");
        assert_skim_agrees("random", src.as_bytes(), chunk_lines);
    }
}
