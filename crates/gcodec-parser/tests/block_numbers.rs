//! A block number beyond 64 bits is diagnosed as written, where the
//! block number or jump target stands, rather than read as an `N` word
//! (issue 14).

use gcodec_parser::parse_bytes;

/// The code and message of the one diagnostic of `src`.
fn diagnosis(src: &str) -> (&'static str, String) {
    let parsed = parse_bytes("numbers.mpf", src.as_bytes());
    let diagnostics: Vec<_> = parsed.diagnostics.iter().collect();
    assert_eq!(diagnostics.len(), 1, "{src}: {diagnostics:?}");
    (
        diagnostics[0].code.name(),
        diagnostics[0].message.to_string(),
    )
}

#[test]
fn block_numbers_beyond_64_bits_are_out_of_range_as_written() {
    for (src, written) in [
        ("N999999999999999999999 G1 X1", "N999999999999999999999"),
        ("/ n018446744073709551616", "n018446744073709551616"),
        ("GOTOF N999999999999999999999", "N999999999999999999999"),
        (
            "IF R1==1 GOTOB N99999999999999999999",
            "N99999999999999999999",
        ),
    ] {
        assert_eq!(
            diagnosis(src),
            (
                "gcodec::parse::invalid_number",
                format!("block number `{written}` is out of range")
            ),
            "{src}"
        );
        let parsed = parse_bytes("numbers.mpf", src.as_bytes());
        let block = &parsed.program.blocks[0];
        assert!(
            block.number.is_none() && block.statements.is_empty(),
            "{src}: {block:?}"
        );
    }
}

#[test]
fn the_largest_block_number_is_still_one() {
    let parsed = parse_bytes(
        "numbers.mpf",
        b"N18446744073709551615 G1 X1\nGOTOB N18446744073709551615",
    );
    assert!(parsed.diagnostics.is_empty(), "{:?}", parsed.diagnostics);
    let number = parsed.program.blocks[0].number.as_ref().map(|n| n.value);
    assert_eq!(number, Some(u64::MAX));
}
