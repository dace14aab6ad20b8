//! Large files are parsed in chunks of whole lines, one a thread, and a
//! streamed run parses them chunk by chunk with the structures paired as
//! the chunks come: neither split may change the tree or the diagnostics.

use gcodec_parser::ast::{Program, SourceText};
use gcodec_parser::{
    Macros, Pairing, WordLine, parse_bytes_in_chunks, parse_chunk, parse_chunk_of_lexed_lines,
};
use gcodec_source::Encoding;
use gcodec_stream::chunks;

/// Parses `src` chunk by chunk, pairing structures as the chunks come.
fn parse_chunk_by_chunk(name: &str, src: &[u8], lines: usize) -> gcodec_parser::Parse {
    let mut pairing = Pairing::default();
    let mut program = Program {
        file: name.to_owned(),
        header: None,
        path: None,
        blocks: Vec::new(),
        structures: Vec::new(),
        source: SourceText::new(src),
    };
    let mut diagnostics = Vec::new();
    for chunk in chunks(src, lines) {
        let encoding = Encoding::detect(src, Encoding::WINDOWS_1252);
        let mut parsed = parse_chunk(src, encoding, &chunk, &Macros::default());
        assert_eq!(
            parsed.blocks.len(),
            chunk.blocks,
            "{name}: one block per line"
        );
        assert_eq!(
            parsed.first_block,
            program.blocks.len(),
            "{name}: chunks in order"
        );
        let mut structure_diagnostics = Vec::new();
        pairing.feed(
            &mut parsed.blocks,
            parsed.first_block,
            &parsed.structure_blocks,
            &mut structure_diagnostics,
        );
        program.header = program.header.take().or(parsed.header);
        program.path = program.path.take().or(parsed.path);
        program.blocks.append(&mut parsed.blocks);
        diagnostics.extend(parsed.diagnostics);
        diagnostics.extend(structure_diagnostics);
    }
    let (structures, unclosed) = pairing.finish();
    program.structures = structures;
    diagnostics.extend(unclosed);
    diagnostics.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    gcodec_parser::Parse {
        program,
        diagnostics: diagnostics.into(),
    }
}

fn assert_split_invariant(name: &str, src: &[u8]) {
    let whole = parse_bytes_in_chunks(name, src, 1);
    for lines in [1, 2, 7, 1000] {
        let chunked = parse_chunk_by_chunk(name, src, lines);
        assert_eq!(
            whole.program, chunked.program,
            "{name} in chunks of {lines}"
        );
        assert_eq!(
            whole.diagnostics, chunked.diagnostics,
            "{name} in chunks of {lines}"
        );
    }
    for threads in [2, 3, 7] {
        let split = parse_bytes_in_chunks(name, src, threads);
        assert_eq!(
            whole.program, split.program,
            "{name} in {threads} chunks on threads"
        );
        assert_eq!(
            whole.diagnostics, split.diagnostics,
            "{name} in {threads} chunks on threads"
        );
    }
}

#[test]
fn fixtures_and_corpus_parse_the_same_in_chunks() {
    gcodec_testkit::each_program(assert_split_invariant);
}

#[test]
fn structures_headers_and_errors_across_chunk_boundaries() {
    let mut src = String::from("%_N_SPLIT_MPF\n;$PATH=/_N_MPF_DIR\n");
    for i in 0..300 {
        src.push_str(&format!("N{i} IF R1>{i}\nG1 X{i} Y-{i}.5 ; move\n"));
        if i % 7 == 0 {
            src.push_str("M 5\n%_N_LATE_MPF\n;$PATH=/_N_OTHER_DIR\n");
        }
        if i % 3 != 0 {
            src.push_str("ENDIF\n");
        }
    }
    src.push_str("M30"); // no final line end
    assert_split_invariant("split.mpf", src.as_bytes());
    let whole = parse_bytes_in_chunks("split.mpf", src.as_bytes(), 5);
    assert_eq!(
        whole.program.path.as_ref().map(|p| p.path.as_str()),
        Some("/_N_MPF_DIR")
    );
    assert!(whole.program.header.is_some());
}

/// A `%` header may only open the file: blank lines and comments may come
/// before it, nothing else, and the verdict does not depend on the chunk
/// the header falls in (the fuzz target `lower_paths` found both: a header
/// after a line with a syntax error, accepted by the whole parse and
/// refused in chunks; a header after a comment, the other way round).
#[test]
fn a_header_opens_the_file_in_any_chunk() {
    let misplaced = |src: &str| {
        let whole = parse_bytes_in_chunks("header.mpf", src.as_bytes(), 1);
        let codes = whole
            .diagnostics
            .iter()
            .filter(|d| d.code.name() == "gcodec::parse::misplaced_header")
            .count();
        (codes, whole.program.header.is_some())
    };
    let cases: [(&str, (usize, bool)); 9] = [
        ("%_N_T_MPF\nG1 X1\n", (0, true)),
        ("; c\n%_N_T_MPF\nG1 X1\n", (0, true)),
        (
            "\n \t&\r\n;$PATH=/_N_MPF_DIR\n  %_N_T_MPF\nG1 X1\n",
            (0, true),
        ),
        // The fuzz target's input: a syntax error first.
        ("PROL AMOUNT, VAR REAL SUM)\n%_N_T,RET\n", (1, false)),
        ("G1 X1\n%_N_T_MPF\n", (1, false)),
        ("/\n%_N_T_MPF\n", (1, false)),
        ("N10\n%_N_T_MPF\n", (1, false)),
        ("LBL:\n%_N_T_MPF\n", (1, false)),
        ("%_N_A_MPF\n; c\n%_N_B_MPF\n", (1, true)),
    ];
    for (src, expected) in cases {
        assert_eq!(misplaced(src), expected, "{src:?}");
        assert_split_invariant(src, src.as_bytes());
    }
}

#[test]
fn empty_and_tiny_inputs_in_many_chunks() {
    for src in ["", "\n", "G1", "G1\n", "\n\n\n", "IF 1\n"] {
        assert_split_invariant(src, src.as_bytes());
    }
}

/// Chunks cover the source in order, `lines` lines each but the last,
/// one block per line (a last line without a line end included).
#[test]
fn chunks_cover_every_line_once() {
    for src in ["", "G1", "G1\n", "G1\nX2", "\n\n", "G1\r\nX2\n\nY3", "\n"] {
        let src = src.as_bytes();
        let newlines = src.iter().filter(|b| **b == b'\n').count();
        let lines_in = newlines + usize::from(src.last().is_some_and(|b| *b != b'\n'));
        for lines in 1..=4 {
            let cut = chunks(src, lines);
            let (mut at, mut block) = (0, 0);
            for (i, chunk) in cut.iter().enumerate() {
                assert_eq!(chunk.bytes.start, at, "{src:?} by {lines}: contiguous");
                assert_eq!(chunk.first_block, block, "{src:?} by {lines}");
                if i + 1 < cut.len() {
                    assert_eq!(chunk.blocks, lines, "{src:?} by {lines}: full chunk");
                }
                at = chunk.bytes.end;
                block += chunk.blocks;
            }
            assert_eq!(at, src.len(), "{src:?} by {lines}: every byte");
            assert_eq!(block, lines_in, "{src:?} by {lines}: every line");
        }
    }
}

/// A streamed run's lowering reads each line as a `WordLine` first: a
/// line read so gives the block the parser gives, and a run of lines not
/// read so parses with `parse_chunk_of_lexed_lines` as with
/// `parse_chunk`, a line at a time. Gives how many lines were read and
/// how many lexed.
fn assert_word_lines_agree(name: &str, src: &[u8]) -> (usize, usize) {
    let encoding = Encoding::detect(src, Encoding::WINDOWS_1252);
    let macros = Macros::default();
    let mut line = WordLine::default();
    let (mut read, mut lexed) = (0, 0);
    for chunk in chunks(src, 1) {
        let parsed = parse_chunk(src, encoding, &chunk, &macros);
        let (start, text_end, _) = gcodec_parser::lines_of(src, chunk.bytes.clone())
            .next()
            .expect("one line");
        if line.read(src, start, text_end) {
            assert_eq!(parsed.blocks, [line.block()], "{name}: {start}");
            assert!(parsed.diagnostics.is_empty(), "{name}: {start}");
            read += 1;
        } else {
            let again = parse_chunk_of_lexed_lines(src, encoding, &chunk, &macros);
            assert_eq!(parsed.blocks, again.blocks, "{name}: {start}");
            assert_eq!(parsed.diagnostics, again.diagnostics, "{name}: {start}");
            lexed += 1;
        }
    }
    (read, lexed)
}

#[test]
fn word_lines_and_lexed_lines_parse_as_the_parser_parses_them() {
    gcodec_testkit::each_program(|name, src| {
        assert_word_lines_agree(name, src);
    });
    let src = b"N10 G1 X1.5 Y-2 F100\nG1 X1 ; cut\nn20 g0 z.5\r\nX1=2\nN30\n\nG1 X99999999999999999999\nG0X1Y2";
    assert_eq!(assert_word_lines_agree("mixed.mpf", src), (5, 3));
}
