//! Large files are parsed in segments of whole lines on several threads;
//! the split must not change the tree or the diagnostics.

mod common;

use gcodec_parser::parse_bytes_in_segments;

fn assert_split_invariant(name: &str, src: &[u8]) {
    let whole = parse_bytes_in_segments(name, src, 1);
    for threads in [2, 3, 7] {
        let split = parse_bytes_in_segments(name, src, threads);
        assert_eq!(whole.program, split.program, "{name} in {threads} segments");
        assert_eq!(
            whole.diagnostics, split.diagnostics,
            "{name} in {threads} segments"
        );
    }
}

#[test]
fn fixtures_and_corpus_parse_the_same_in_segments() {
    common::each_program(assert_split_invariant);
}

#[test]
fn structures_headers_and_errors_across_segment_boundaries() {
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
    let whole = parse_bytes_in_segments("split.mpf", src.as_bytes(), 5);
    assert_eq!(
        whole.program.path.as_ref().map(|p| p.path.as_str()),
        Some("/_N_MPF_DIR")
    );
    assert!(whole.program.header.is_some());
}

#[test]
fn empty_and_tiny_inputs_in_many_segments() {
    for src in ["", "\n", "G1", "G1\n", "\n\n\n", "IF 1\n"] {
        assert_split_invariant(src, src.as_bytes());
    }
}
