//! Blocks of constant words for a straight motion (`G1 X… Y… F…`) are
//! lowered directly (`lower/constant_words.rs`); everything else, and
//! those blocks too when asked, by the general path. Both must give the
//! same instructions and diagnostics, in the same order, for every
//! program and machine.

use gcodec_profile::Profile;
use gcodec_testkit::agreement::assert_direct_lowering_agrees;
use gcodec_testkit::{machine, profile};

mod common;

/// The shipped profiles and machines that treat `G0`, `G1` and the axes
/// differently: a legacy alias on `G1`, `G0` ruled out, no `Y` axis.
fn machines() -> Vec<(&'static str, Profile)> {
    let mut all: Vec<(&'static str, Profile)> = [
        "default.toml",
        "lathe_828d.toml",
        "mill_5axis.toml",
        "mill_g505_g599.toml",
        "grinder_fb422.toml",
    ]
    .into_iter()
    .map(|name| (name, profile(name)))
    .collect();
    all.push((
        "G1 an alias",
        machine(
            "[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\nlegacy_aliases = { G1 = \"G505\" }\n",
        ),
    ));
    all.push((
        "G0 ruled out",
        machine("[g_codes]\nunsupported = [\"G0\"]\n"),
    ));
    all
}

#[test]
fn fixtures_and_corpus_lower_the_same_either_way() {
    let builtin = gcodec_profile::builtin().unwrap();
    gcodec_testkit::each_program(|name, src| assert_direct_lowering_agrees(name, src, &builtin));
}

#[test]
fn fixtures_and_corpus_lower_the_same_either_way_on_every_machine() {
    gcodec_testkit::each_program_on(&machines(), assert_direct_lowering_agrees);
}

/// The pieces generated blocks are made of: the words the direct path
/// takes, their near misses, and what changes the state around them.
const PIECES: &[&str] = &[
    "G0", "G1", "G1", "g1", "G01", "G-0", "G1.0", "G2", "G3", "G17", "G90", "G91", "G4", "G54",
    "G53", "G500", "G34", "G64", "X1", "X1", "X-2.5", "x.5", "Y2", "Y+3", "Z-0", "Z4", "A5", "B6",
    "C7", "U1", "V2", "W3", "Q1", "E1", "I1", "J2", "K3", "F100", "F100", "F-5", "F0", "F1.5",
    "S1000", "M3", "M30", "T1", "D1", "H1", "CR=5", "X=5", "X1=2", "AC(3)", "R1=2",
];

/// What may stand between or around generated blocks.
const LINES: &[&str] = &[
    "IF R1>0 GOTOF L1",
    "L1:",
    "L1: X1",
    "MCALL CYCLE81(1,2,3)",
    "MCALL",
    "G34 Z-10 K2 F0.1",
    "WHILE R1<3",
    "R1=R1+1",
    "ENDWHILE",
    "REPEAT L1 P=2",
    "N10",
    "; comment",
];

/// A deterministic generator: each program of a dozen lines, each line a
/// block of up to six pieces or one of the other lines, some with a
/// block number or skip mark.
#[test]
fn generated_programs_lower_the_same_either_way() {
    let machines = machines();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = |n: usize| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 33) as usize % n
    };
    for round in 0..1500 {
        let mut src = String::new();
        for line in 0..12 {
            match next(8) {
                0 => src.push_str(LINES[next(LINES.len())]),
                k => {
                    match next(6) {
                        0 => src.push_str(&format!("N{} ", line * 10)),
                        1 => src.push_str("/ "),
                        _ => {}
                    }
                    for _ in 0..=next(k.min(6)) {
                        src.push_str(PIECES[next(PIECES.len())]);
                        src.push(' ');
                    }
                }
            }
            src.push('\n');
        }
        let (machine, profile) = &machines[next(machines.len())];
        assert_direct_lowering_agrees(
            &format!("round {round} on {machine}:\n{src}"),
            src.as_bytes(),
            profile,
        );
    }
}
