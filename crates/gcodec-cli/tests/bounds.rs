//! Diagnostics kept in memory are bounded, and every one is counted: one
//! block of thousands of repeated axis words keeps the first of its
//! diagnostics, the count of those not shown counts them all, and the
//! block's snippet is a few dozen bytes of it.

mod common;

use gcodec_source::MAX_KEPT_PER_BLOCK;

use common::*;

const WORDS: usize = 5_000;

/// `G1 X0 X1 … X4999`: one `block_too_long` and a `repeated_axis` per
/// word after the first, in a folder of the `test` that reads it (tests
/// run in parallel: one writing the file while another reads it made the
/// reader see a part of it).
fn repeated_axes(test: &str) -> std::path::PathBuf {
    let words: Vec<String> = (0..WORDS).map(|i| format!("X{i}")).collect();
    temp_file(
        test,
        "AXES.MPF",
        &format!("G1 {} F100\nM30\n", words.join(" ")),
    )
}

#[test]
fn a_block_keeps_a_bounded_number_of_diagnostics_and_counts_all() {
    let program = repeated_axes("bounded");
    for command in ["lower", "run"] {
        let out = gcodec(
            [command, "--max-diagnostics", "0"]
                .map(String::from)
                .into_iter()
                .chain([program.display().to_string()]),
        );
        let err = stderr(&out);
        assert_eq!(code(&out), EXIT_DIAGNOSTICS, "{command}");
        let shown = err.matches("gcodec::lower::repeated_axis").count()
            + err.matches("gcodec::lower::block_too_long").count();
        assert_eq!(shown, MAX_KEPT_PER_BLOCK, "{command}");
        let total = WORDS; // 4,999 repeated axes and the block's length
        let not_kept = total - MAX_KEPT_PER_BLOCK;
        assert!(
            err.contains(&format!(
                "… and {not_kept} more diagnostics not shown ({not_kept} errors, 0 others)"
            )),
            "{command}: {}",
            &err[err.len().saturating_sub(300)..]
        );
    }
}

/// The reports of a block of 25 kB show a few dozen bytes of it each.
#[test]
fn a_long_block_is_not_echoed() {
    let program = repeated_axes("not_echoed");
    let length = std::fs::metadata(&program).expect("the program").len() as usize;
    let out = gcodec(["lower".to_string(), program.display().to_string()]);
    let err = stderr(&out);
    assert!(err.contains("gcodec::lower::block_too_long"), "{err}");
    assert!(
        err.len() < MAX_KEPT_PER_BLOCK * 1_000 && err.len() < length,
        "{} bytes of reports for a block of {length}",
        err.len()
    );
}
