//! Lowering a program in parts on several threads gives exactly what one
//! run gives: the same instructions and the same diagnostics in the same
//! order, whatever the number of parts.

use gcodec_sema::{Definitions, lower_in_parts};

mod common;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

fn assert_parts_agree(name: &str, src: &[u8], profile: &gcodec_profile::Profile) {
    let parsed = gcodec_parser::parse_bytes(name, src);
    let definitions = Definitions::new();
    let one = lower_in_parts(&parsed.program, profile, &definitions, 1);
    for parts in [2, 3, 7] {
        let many = lower_in_parts(&parsed.program, profile, &definitions, parts);
        assert_eq!(
            one.diagnostics, many.diagnostics,
            "{name}: diagnostics differ with {parts} parts"
        );
        assert!(
            one.document == many.document,
            "{name}: instructions differ with {parts} parts"
        );
    }
}

#[test]
fn the_generated_program_lowers_the_same_in_parts() {
    let src = program::generate(20_000);
    let profile = gcodec_profile::builtin().unwrap();
    assert_parts_agree("bench.mpf", &src, &profile);
}

#[test]
fn state_across_part_boundaries_is_settled() {
    let profile = gcodec_profile::builtin().unwrap();
    // Every block a boundary for 7 parts: motions and suppressions that
    // inherit the motion command and the Group 8 selection, a modal call
    // in force across a boundary, G34 feeding the lead change, joins.
    let src = "G55 G0 X0\nX1\nG53 X2\nG1 X3 F100\nMCALL CYCLE81(1,2,3)\nX4\nX5\nMCALL\n\
               G34 Z-10 K2 F0.1\nZ-20 K2 F0.1\nIF R1>0\nG2 X1 Y1 CR=5\nENDIF\nX6\nG53 X7\nM30\n";
    assert_parts_agree("boundaries.mpf", src.as_bytes(), &profile);
    // Skipped blocks: each a join after itself, across boundaries.
    let src = "G55 G0 X0\n/G1 X1\nX2\n/3 G56\nG53 X3\n/M8\nX4\nMCALL CYCLE81(1,2,3)\n\
               /MCALL\nG1 X5\nX6\nMCALL\nX7\nM30\n";
    assert_parts_agree("skips.mpf", src.as_bytes(), &profile);
    let subprogram = "X1\nG54\nX2\nG53 X3\nM17\n";
    assert_parts_agree("SUB.SPF", subprogram.as_bytes(), &profile);
    // An arc without circle data under an inherited `G2`: one run reports
    // it, so the parts must too.
    let arcs = "G2 X1 Y1 CR=5 F100\nX2 Y2\nX3 Y3 CR=5\nG3 X4 Y4 I1\nX5 Y5\nM30\n";
    assert_parts_agree("arcs.mpf", arcs.as_bytes(), &profile);
}

#[test]
fn corpus_programs_lower_the_same_in_parts() {
    let Some(dir) = common::corpus_dir() else {
        return;
    };
    let profile = gcodec_profile::builtin().unwrap();
    for path in common::programs(&dir) {
        let bytes = std::fs::read(&path).unwrap();
        assert_parts_agree(&path.display().to_string(), &bytes, &profile);
    }
}
