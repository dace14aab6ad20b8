//! Straight motions to constant end points in a plain state take the
//! executor's direct path (`channel/motion.rs`, `direct_straight_motion`);
//! everything else, and those motions too when `RunOptions::direct_motions`
//! is off, the general path. Both must give the same JSONL events, the
//! same CSV rows and the same summary, byte for byte, for every program
//! and machine: the fixtures, the corpus, and generated programs that
//! switch between plain and framed states block by block.

use std::sync::Arc;

use gcodec_profile::Profile;
use gcodec_source::SourceFile;
use gcodec_testkit::agreement::{assert_direct_motions_agree, run_outputs};
use gcodec_testkit::{machine, profile};

/// Both paths agree on `src`, run to at most 20,000 blocks.
fn assert_same(name: &str, src: &[u8], profile: &Arc<Profile>) {
    assert_direct_motions_agree(name, src, profile, 20_000);
}

/// The shipped machines a motion differs on: a mill, a lathe (diameter
/// axis, X Z only), five axes (rotary), and a mill that does not traverse
/// an offset change with an increment.
fn machines() -> Vec<(&'static str, Arc<Profile>)> {
    let mut all: Vec<(&'static str, Arc<Profile>)> = [
        "default.toml",
        "lathe_828d.toml",
        "mill_5axis.toml",
        "mill_g505_g599.toml",
    ]
    .into_iter()
    .map(|name| (name, Arc::new(profile(name))))
    .collect();
    all.push((
        "increments not traversing offset changes",
        Arc::new(machine(
            "[work_offsets]\nincremental_traverses_offset_change = false\n",
        )),
    ));
    all
}

#[test]
fn fixtures_and_corpus_run_the_same_either_way() {
    let builtin = Arc::new(gcodec_profile::builtin().unwrap());
    gcodec_testkit::each_program(|name, src| assert_same(name, src, &builtin));
}

#[test]
fn fixtures_and_corpus_run_the_same_either_way_on_every_machine() {
    gcodec_testkit::each_program_on(&machines(), assert_same);
}

/// The blocks generated programs are made of: plain motions, and what
/// makes a state other than plain or a motion other than direct (frames,
/// offsets, tool lengths, suppression, increments, inches, diameters,
/// rotary positions, `-0`, polar words, arcs).
const MILL_BLOCKS: &[&str] = &[
    "G1 X10 Y20 F1000",
    "G0 X-0 Y0.5",
    "X-0",
    "Z-0.0",
    "G1 X0.001 Y-3.25 Z7",
    "X1000",
    "Y=7.5",
    "G91",
    "G90",
    "G1 X=IC(2) Y3",
    "X=AC(4)",
    "G70",
    "G71",
    "G700",
    "G710",
    "TRANS X5 Y-2",
    "ATRANS Z-0",
    "TRANS",
    "ROT Z30",
    "ROT",
    "SCALE X2",
    "MIRROR Y0",
    "G54",
    "G500",
    "G53 X1 Y2",
    "SUPA Z3",
    "T1 M6 D1",
    "D0",
    "G18",
    "G17",
    "G2 X5 Y5 CR=100000",
    "G3 X1 Y-1 CR=-100000",
    "G1 AP=45 RP=10",
    "G111 X0 Y0",
    "G1 X20 ANG=30",
    "RNDM=1",
    "RNDM=0",
    "G41",
    "G40",
    "F0",
    "F500",
    "G1 X2 Y3 Z4 F200",
    "G0 Z50",
];

const FIVE_AXIS_BLOCKS: &[&str] = &[
    "G1 A30 C-90 F1000",
    "C=DC(10)",
    "A=ACP(350)",
    "G0 B-0",
    "C720",
];

/// Tools with lengths on `mill_tool_management.toml`, selected by
/// location as tool management wants.
const TOOL_BLOCKS: &[&str] = &["T=1 M6 D1", "T=2 M6 D1", "G500"];

const LATHE_BLOCKS: &[&str] = &[
    "G1 X20 Z-5 F0.2",
    "DIAMON",
    "DIAMOF",
    "DIAM90",
    "G0 X-0 Z0",
    "G91 X2",
    "G90",
    "G18",
    "TRANS Z-30",
    "TRANS",
    "G54",
    "G500",
    "T1 D1",
    "D0",
    "G1 X=DAC(10)",
    "X=RIC(1)",
    "G95",
    "G94",
    "G70",
    "G71",
];

/// A deterministic stream of choices (xorshift; no dependency on a
/// random source).
struct Choices(u64);

impl Choices {
    fn next(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }
}

/// `count` programs of 40 blocks from `blocks`, every other block a plain
/// motion so that most motions follow a change.
fn generated(blocks: &[&str], plain: &[&str], seed: u64, count: usize) -> Vec<String> {
    let mut choices = Choices(seed);
    (0..count)
        .map(|_| {
            let mut program = String::new();
            for i in 0..40 {
                let block = if i % 2 == 0 {
                    plain[choices.next(plain.len())]
                } else {
                    blocks[choices.next(blocks.len())]
                };
                program.push_str(block);
                program.push('\n');
            }
            program.push_str("M30\n");
            program
        })
        .collect()
}

/// Generated programs of one machine: its name, profile, the blocks
/// between the plain motions, and the plain motions.
struct GeneratedRun<'a> {
    machine: &'a str,
    profile: Profile,
    blocks: Vec<&'a str>,
    plain: &'a [&'a str],
}

#[test]
fn generated_programs_run_the_same_either_way() {
    // Each names G0 or G1: a block of the lists above without one follows
    // one of these, never an arc.
    let plain_mill = &["G1 X1.5 Y2", "G1 X3.25", "G0 Y-4 Z1", "G1 Z0 F300"];
    let plain_lathe = &["G1 X10 Z-2", "G1 Z-4.5", "G0 X30 Z5"];
    let runs = [
        GeneratedRun {
            machine: "mill",
            profile: profile("default.toml"),
            blocks: MILL_BLOCKS.to_vec(),
            plain: plain_mill,
        },
        GeneratedRun {
            machine: "mill-with-tool-lengths",
            profile: profile("mill_tool_management.toml"),
            blocks: MILL_BLOCKS
                .iter()
                .filter(|block| !block.starts_with("T1"))
                .chain(TOOL_BLOCKS)
                .copied()
                .collect(),
            plain: plain_mill,
        },
        GeneratedRun {
            machine: "five-axes",
            profile: profile("mill_5axis.toml"),
            blocks: MILL_BLOCKS
                .iter()
                .chain(FIVE_AXIS_BLOCKS)
                .copied()
                .collect(),
            plain: plain_mill,
        },
        GeneratedRun {
            machine: "lathe",
            profile: profile("lathe_828d.toml"),
            blocks: LATHE_BLOCKS.to_vec(),
            plain: plain_lathe,
        },
    ];
    for (seed, run) in runs.into_iter().enumerate() {
        let profile = Arc::new(run.profile);
        let seed = 0x9E37_79B9_7F4A_7C15 + seed as u64;
        for (i, program) in generated(&run.blocks, run.plain, seed, 150)
            .iter()
            .enumerate()
        {
            let name = format!("generated-{}-{i}.mpf", run.machine);
            assert_same(&name, program.as_bytes(), &profile);
        }
    }
}

/// A flood of plain motions, the direct path's whole purpose
/// (`MachineState::positions_plain` is tested where it is defined).
#[test]
fn a_flood_of_plain_motions_runs_the_same_either_way() {
    let mut program = String::from("G1 F1000\n");
    for i in 0..200 {
        program.push_str(&format!("X{}.{} Y-{i}\n", i / 3, i % 7));
    }
    let mill = Arc::new(profile("default.toml"));
    assert_same("flood.mpf", program.as_bytes(), &mill);
    let file = Arc::new(SourceFile::new("flood.mpf", program.as_bytes()));
    let (direct, _) = run_outputs(&mill, &file, 20_000, true);
    assert_eq!(direct.matches("\"event\":\"motion\"").count(), 200);
}

/// Floods under a frame the motions keep running in — a work offset (as
/// real programs mostly run), a rotation, a scale and mirroring, a tool
/// length — take the direct path with the frame's arithmetic: the same
/// either way, signed zeros and increments included.
#[test]
fn floods_under_a_frame_they_keep_run_the_same_either_way() {
    let heads = [
        "G54 G1 F1000",
        "TRANS X5 Y-2 Z-0\nG1 F1000",
        "ROT Z30\nG1 F1000",
        "SCALE X2 Y0.5\nMIRROR Y0\nG1 F1000",
        "T=1 M6 D1\nG54 G1 F1000",
        "G54 G91 G1 F1000",
    ];
    let machine = Arc::new(profile("mill_tool_management.toml"));
    for head in heads {
        let mut program = format!("{head}\n");
        for i in 0..120 {
            let z = if i % 5 == 0 { "-0" } else { "0.5" };
            program.push_str(&format!("X{}.{} Y-{i} Z{z}\n", i / 3, i % 7));
        }
        assert_same(head, program.as_bytes(), &machine);
    }
}
