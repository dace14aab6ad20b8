//! A block whose statements cannot be read keeps the skip mark, block
//! number and label it opens with, where the grammar reads them plainly
//! (SPEC §7): a jump to the number or label still finds the block.

use gcodec_parser::parse_bytes;

/// The skip level, number (main or not), and label of the one block of
/// `src`, which must be an error without statements.
fn prefix_of(src: &str) -> (Option<u8>, Option<(bool, u64)>, Option<String>) {
    let parsed = parse_bytes("recovery.mpf", src.as_bytes());
    assert!(parsed.has_errors(), "{src}");
    let block = &parsed.program.blocks[0];
    assert!(block.statements.is_empty(), "{src}: {block:?}");
    (
        block.skip.as_ref().map(|s| s.level),
        block.number.as_ref().map(|n| (n.main, n.value)),
        block.label.as_ref().map(|l| l.name.to_string()),
    )
}

#[test]
fn blocks_with_errors_keep_a_plain_prefix() {
    // A syntax error, a lexical error, too many operators, too deep.
    assert_eq!(prefix_of("N10 G1 X="), (None, Some((false, 10)), None));
    assert_eq!(prefix_of("/ N20 X1 ?"), (Some(0), Some((false, 20)), None));
    assert_eq!(prefix_of("/3 N30 X1 ä"), (Some(3), Some((false, 30)), None));
    let long = format!("N40 R1=1{}", "+1".repeat(1001));
    assert_eq!(prefix_of(&long), (None, Some((false, 40)), None));
    let deep = format!("N50 R1={}1{}", "(".repeat(65), ")".repeat(65));
    assert_eq!(prefix_of(&deep), (None, Some((false, 50)), None));
    // Main block numbers and labels.
    assert_eq!(prefix_of(":60 X="), (None, Some((true, 60)), None));
    let label = Some("LBL".to_string());
    assert_eq!(prefix_of("LBL: X="), (None, None, label.clone()));
    assert_eq!(
        prefix_of("/ N70 LBL: X="),
        (Some(0), Some((false, 70)), label)
    );
}

#[test]
fn a_prefix_the_grammar_must_judge_is_not_kept() {
    assert_eq!(prefix_of("N10.5 X="), (None, None, None));
    assert_eq!(prefix_of("N99999999999999999999 X="), (None, None, None));
    assert_eq!(prefix_of(":10.5 LBL: X="), (None, None, None));
}

/// A skip mark in error is not kept, the number after it is.
#[test]
fn a_skip_mark_in_error_drops_only_itself() {
    assert_eq!(prefix_of("/12 N10 X1"), (None, Some((false, 10)), None));
    assert_eq!(prefix_of("/ 5 N20 X1"), (None, Some((false, 20)), None));
    assert_eq!(prefix_of("/ 5"), (None, None, None));
}

/// `/ 5`: a blank between the mark and a number is an error at the mark
/// and the number, not level 0 with the number dropped (SPEC §3).
#[test]
fn a_blank_between_the_skip_mark_and_its_level_is_an_error() {
    for (src, end) in [("/ 5 N10 G1 X1", 3), ("/  7", 4), ("N1\n/ 0 X1", 3)] {
        let parsed = parse_bytes("skip.mpf", src.as_bytes());
        let codes: Vec<_> = parsed.diagnostics.iter().map(|d| d.code.name()).collect();
        assert_eq!(codes, ["gcodec::parse::separated_skip_level"], "{src}");
        let span = parsed.diagnostics[0].span().expect("a place");
        let start = src.rfind('/').unwrap() as u32;
        assert_eq!((span.start, span.end), (start, start + end), "{src}");
    }
    // Against the mark it is a level; a blank after a level is fine.
    for src in ["/5 N10 G1 X1", "/ N10 X1", "/5 7"] {
        let parsed = parse_bytes("skip.mpf", src.as_bytes());
        assert!(
            parsed
                .diagnostics
                .iter()
                .all(|d| d.code != "gcodec::parse::separated_skip_level"),
            "{src}"
        );
    }
}

/// A file with several independent errors (the fixture
/// `errors/several_errors.mpf`): every error is reported in one run, and
/// the blocks between them still parse.
#[test]
fn several_errors_are_all_reported_and_parsing_resumes() {
    let root = gcodec_testkit::fixtures::root("parse");
    let fixture = gcodec_testkit::Fixture::read(
        "parse",
        &std::path::Path::new(&root).join("errors/several_errors.mpf"),
    );
    let file = &fixture.file;
    let parsed = gcodec_parser::parse(file);
    let mut error_lines: Vec<u32> = parsed
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .filter_map(|d| d.span().map(|s| file.line_col(s.start).0))
        .collect();
    error_lines.sort_unstable();
    assert_eq!(error_lines, [3, 5, 6, 7, 8, 9]);
    // The good blocks around the bad ones keep their statements.
    for line in [2, 4, 10] {
        let block = &parsed.program.blocks[line - 1];
        assert!(
            !block.statements.is_empty(),
            "block on line {line} lost its statements"
        );
    }
}
