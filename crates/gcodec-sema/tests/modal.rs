//! The statically known modal state at every block (`gcodec_sema::modal`):
//! straight-line code, joins, loops, jumps, calls and odd documents.

mod common;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

use std::sync::Arc;

use gcodec_ail::{ByteRange, Document, Instruction, Op, Source, Value};
use gcodec_lang::WorkOffsetCode;
use gcodec_profile::Profile;
use gcodec_sema::modal::{LineState, ModalState, ModalStates, Start};

fn builtin() -> Profile {
    gcodec_profile::builtin().expect("built-in profile")
}

/// Lowers `src` with `profile`; the program must parse cleanly.
fn lower_with(src: &str, profile: &Profile) -> Document {
    let parsed = gcodec_parser::parse_bytes("modal.mpf", src.as_bytes());
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    gcodec_sema::lower(&parsed.program, profile).document
}

/// The states of `src` as a main program on the built-in profile.
fn main_program(src: &str) -> ModalStates {
    let profile = builtin();
    ModalStates::analyse(&lower_with(src, &profile), Start::Reset(&profile))
}

/// The state at `line`, which must be reached.
fn at(states: &ModalStates, line: u32) -> &ModalState {
    states
        .state_at_line(line)
        .unwrap_or_else(|| panic!("line {line}: {:?}", states.line_state(line)))
}

/// Group `group`'s command at `line`.
fn group_at(states: &ModalStates, line: u32, group: u8) -> Option<&'static str> {
    at(states, line).get(group)
}

#[test]
fn straight_line_states_follow_the_blocks() {
    let states = main_program("G0 X1\nG17 G91 G4 F2\nG1 X2\nG18 Y1\nM30\n");
    // Line 1 starts in the built-in profile's reset state.
    let reset = at(&states, 1);
    assert_eq!(reset.get(1), Some("G1"));
    assert_eq!(reset.get(6), Some("G17"));
    assert_eq!(reset.get(8), Some("G500"));
    assert_eq!(reset.get(14), Some("G90"));
    assert_eq!(reset.get(15), Some("G94"));
    assert_eq!(reset.index(1), Some(2));
    assert_eq!(reset.modal_call_active(), Some(false));
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 2, 14), Some("G90"));
    assert_eq!(group_at(&states, 3, 14), Some("G91"));
    // G4 is non-modal (group 2): no state carries it.
    assert_eq!(group_at(&states, 3, 2), None);
    assert_eq!(group_at(&states, 4, 1), Some("G1"));
    assert_eq!(group_at(&states, 5, 6), Some("G18"));
    assert_eq!(group_at(&states, 5, 1), Some("G1"));
    // Out of range groups are no groups.
    assert_eq!(reset.get(0), None);
    assert_eq!(reset.get(65), None);
    // Five lines, five different states.
    assert_eq!(states.distinct_states(), 5);
    assert_eq!(
        states.iter().map(|(line, _)| line).collect::<Vec<_>>(),
        [1, 2, 3, 4, 5]
    );
    assert_eq!(states.line_state(6), LineState::NoInstructions);
}

#[test]
fn repeated_commands_share_one_state() {
    let states = main_program("G0 X1\nG0 X2\nG0 X3\nG0 X4\n");
    assert_eq!(at(&states, 2), at(&states, 4));
    // The reset state and the G0 state.
    assert_eq!(states.distinct_states(), 2);
}

#[test]
fn reset_state_comes_from_the_profile() {
    let lathe = common::profile("lathe_828d.toml");
    let document = lower_with("G53 X0\nX1\n", &lathe);
    let states = ModalStates::analyse(&document, Start::Reset(&lathe));
    let start = at(&states, 1);
    assert_eq!(start.get(6), Some("G18"));
    assert_eq!(start.get(15), Some("G95"));
    assert_eq!(start.get(29), Some("DIAMON"));
    // Group 8 starts at `default_group8_offset`, the selection the
    // lowering's `work_offset` instructions start from, so a suppression
    // keeps it known.
    assert_eq!(start.get(8), Some("G54"));
    assert_eq!(group_at(&states, 2, 8), Some("G54"));
}

#[test]
fn if_else_whose_branches_agree_stays_known() {
    let src = "G0 X0\nIF R1==1\nG1 G18 X1\nELSE\nG1 X2\nENDIF\nX3\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 7, 1), Some("G1"));
    // The branches disagree on the plane.
    assert_eq!(group_at(&states, 7, 6), None);
    assert_eq!(group_at(&states, 5, 6), Some("G17"));
    assert_eq!(group_at(&states, 5, 1), Some("G0"));
}

#[test]
fn if_else_whose_branches_disagree_is_unknown() {
    let src = "G0 X0\nIF R1==1\nG2 X1 CR=5\nELSE\nG3 X2 CR=5\nENDIF\nX3\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 7, 1), None);
    assert_eq!(group_at(&states, 7, 6), Some("G17"));
    // An IF without ELSE joins the skipped path.
    let states = main_program("G0 X0\nIF R1==1\nG1 X1\nENDIF\nX3\n");
    assert_eq!(group_at(&states, 5, 1), None);
}

#[test]
fn a_loop_body_changing_a_group_makes_the_head_unknown() {
    let src = "G0 X0\nWHILE R1<3\nG1 X1\nR1=R1+1\nENDWHILE\nX2\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 2, 1), None, "loop head");
    assert_eq!(group_at(&states, 3, 1), None);
    assert_eq!(group_at(&states, 4, 1), Some("G1"));
    // The loop may run no pass or several.
    assert_eq!(group_at(&states, 6, 1), None);
    assert_eq!(group_at(&states, 6, 6), Some("G17"));
    // A body that keeps group 1 keeps the head known.
    let states = main_program("G0 X0\nWHILE R1<3\nX1\nG18\nENDWHILE\nX2\n");
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 2, 6), None);
    assert_eq!(group_at(&states, 6, 1), Some("G0"));
}

#[test]
fn repeat_until_and_for_loops_join_at_their_heads() {
    let states = main_program("G0 X0\nREPEAT\nX1\nG2 X2 CR=5\nUNTIL R1>2\nX3\n");
    assert_eq!(group_at(&states, 3, 1), None);
    assert_eq!(group_at(&states, 6, 1), Some("G2"));
    // `FOR` sets its counter before the head label in the same block: the
    // block starts as it is entered; the body sees the join.
    let states = main_program("G0 X0\nFOR R3=1 TO 5\nX1\nG1 X2\nENDFOR\nX3\n");
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 3, 1), None);
    assert_eq!(group_at(&states, 6, 1), None);
}

#[test]
fn goto_skips_blocks_and_joins_at_its_target() {
    let states = main_program("G0 X0\nGOTOF SKIP\nG1 X1\nSKIP: X2\n");
    assert_eq!(states.line_state(3), LineState::Unreachable);
    assert_eq!(states.unreachable_lines().collect::<Vec<_>>(), [3]);
    assert_eq!(group_at(&states, 4, 1), Some("G0"));
    // A backward jump joins into its target.
    let states = main_program("N10 X0\nG0 X1\nIF R1<5 GOTOB N10\nX2\n");
    assert_eq!(group_at(&states, 1, 1), None);
    assert_eq!(group_at(&states, 4, 1), Some("G0"));
    // A conditional forward jump joins both paths.
    let states = main_program("G0 X0\nIF R1==1 GOTOF SKIP\nG1 X1\nSKIP: X2\n");
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    assert_eq!(group_at(&states, 4, 1), None);
}

#[test]
fn a_skipped_block_joins_both_paths_after_itself() {
    // The block may run or not: what it sets is unknown after it.
    let states = main_program("G0 X0\n/G1 G18 X1\nX2\n");
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 3, 1), None);
    assert_eq!(group_at(&states, 3, 6), None);
    // What it does not change stays known.
    let states = main_program("G0 X0\n/3 G0 X1 M8\nX2\n");
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    assert_eq!(group_at(&states, 3, 6), Some("G17"));
    // A jump to a skipped block lands before its test.
    let states = main_program("G0 X0\n/LBL: G1 X1\nG0 X2\nIF R1<3 GOTOB LBL\nX3\n");
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 5, 1), Some("G0"));
    // A skipped `MCALL` may leave the modal call in force.
    let states = main_program("MCALL CYCLE81(1,2,3)\n/MCALL\nG17\n");
    assert_eq!(at(&states, 3).modal_call_active(), None);
}

#[test]
fn program_end_and_return_end_the_path() {
    let states = main_program("G0 X0\nM30\nG1 X1\n");
    assert_eq!(states.line_state(3), LineState::Unreachable);
    let states = main_program("G0 X0\nG1 X1 M2\nMARK: X2\n");
    assert_eq!(states.line_state(3), LineState::Unreachable);
    let states = main_program("G0 X0\nRET\nX1\n");
    assert_eq!(states.line_state(3), LineState::Unreachable);
    // M0 stops and goes on.
    let states = main_program("G0 X0\nM0\nX1\n");
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
}

#[test]
fn a_call_makes_every_group_unknown() {
    let states = main_program("G0 G18 X0\nL100\nX1\nG1 X2\nCYCLE81(1,2,3)\nX3\n");
    assert_eq!(group_at(&states, 2, 6), Some("G18"));
    let after = at(&states, 3);
    assert_eq!(after.known().count(), 0, "{after:?}");
    assert_eq!(group_at(&states, 5, 1), Some("G1"));
    assert_eq!(group_at(&states, 5, 6), None);
    assert_eq!(at(&states, 6).known().count(), 0);
}

#[test]
fn a_modal_call_makes_every_traversing_block_a_call() {
    let src = "G0 X0\nMCALL CYCLE81(1,2,3)\nG17\nX1\nX2\nMCALL\nG17\nX3\nX4\n";
    let states = main_program(src);
    // `MCALL` itself calls nothing.
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    assert_eq!(at(&states, 3).modal_call_active(), Some(true));
    assert_eq!(group_at(&states, 4, 6), Some("G17"));
    // After a traversing block the cycle has run.
    assert_eq!(at(&states, 5).known().count(), 0);
    assert_eq!(at(&states, 7).modal_call_active(), Some(false));
    assert_eq!(group_at(&states, 8, 6), Some("G17"));
    assert_eq!(group_at(&states, 9, 6), Some("G17"));
    // Paths that disagree on the modal call: motion forgets.
    let src = "G0 X0\nIF R1==1\nMCALL CYCLE81(1,2,3)\nENDIF\nG17\nX1\nX2\n";
    let states = main_program(src);
    assert_eq!(at(&states, 5).modal_call_active(), None);
    assert_eq!(group_at(&states, 6, 6), Some("G17"));
    assert_eq!(group_at(&states, 7, 6), None);
}

#[test]
fn a_subprogram_starts_unknown() {
    let profile = builtin();
    let document = lower_with("G1 X1\nX2\nG17\nX3\n", &profile);
    let states = ModalStates::analyse(&document, Start::Unknown);
    assert_eq!(at(&states, 1).known().count(), 0);
    assert_eq!(group_at(&states, 2, 1), Some("G1"));
    assert_eq!(group_at(&states, 2, 6), None);
    assert_eq!(group_at(&states, 4, 6), Some("G17"));
    // The same text as a main program knows the plane from the start.
    let states = ModalStates::analyse(&document, Start::Reset(&profile));
    assert_eq!(group_at(&states, 2, 6), Some("G17"));
}

#[test]
fn a_missing_jump_target_ends_the_path() {
    let profile = builtin();
    let parsed = gcodec_parser::parse_bytes("m.mpf", b"G0 X0\nGOTOF NOWHERE\nG1 X1\nM30\n");
    let document = gcodec_sema::lower(&parsed.program, &profile).document;
    assert!(document.instructions.iter().any(|i| matches!(
        &i.op,
        Op::Jump { target, .. } if target == "NOWHERE@missing"
    )));
    let states = ModalStates::analyse(&document, Start::Reset(&profile));
    // Alarm 14080 when the jump runs: nothing after it runs.
    assert_eq!(states.line_state(3), LineState::Unreachable);
    // A conditional jump may go on.
    let parsed = gcodec_parser::parse_bytes("m.mpf", b"G0 X0\nIF R1 GOTOF NOWHERE\nX1\nM30\n");
    let document = gcodec_sema::lower(&parsed.program, &profile).document;
    let states = ModalStates::analyse(&document, Start::Reset(&profile));
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
}

#[test]
fn a_computed_jump_may_reach_every_label() {
    let src = "G0 X0\nIF R2==1 GOTOF \"MA\"<<R1\nG1 X1\nMA1: X2\nG18\nMA2: X3\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    // Reached from line 3 with G1 and from the jump with G0.
    assert_eq!(group_at(&states, 4, 1), None);
    assert_eq!(group_at(&states, 4, 6), Some("G17"));
    // The jump brings G17, the block before G18.
    assert_eq!(group_at(&states, 6, 6), None);
    // An unconditional computed jump does not go on.
    let states = main_program("G0 X0\nGOTOF \"MA\"<<R1\nG1 X1\nMA1: X2\n");
    assert_eq!(states.line_state(3), LineState::Unreachable);
    assert_eq!(group_at(&states, 4, 1), Some("G0"));
}

#[test]
fn goto_start_joins_into_the_first_block() {
    let states = main_program("G0 X0\nG2 X1 CR=5\nGOTOS\nX2\n");
    assert_eq!(group_at(&states, 1, 1), None);
    assert_eq!(group_at(&states, 1, 6), Some("G17"));
    assert_eq!(group_at(&states, 4, 1), Some("G2"));
}

#[test]
fn repeat_of_a_section_goes_on_as_the_section_ends() {
    let src = "G2 X0 CR=5\nN10 G0 X0\nN20 G1 X1\nG3 X2 CR=5\nREPEAT N10 N20 P=2\nX3\n";
    let states = main_program(src);
    // Neither G3 (the REPEAT ignored) nor unknown (a call of another file).
    assert_eq!(group_at(&states, 6, 1), Some("G1"));
    assert_eq!(group_at(&states, 6, 6), Some("G17"));
    // The section's start is entered with G2, G3 and (second pass) G1.
    assert_eq!(group_at(&states, 2, 1), None);
    // The second pass starts where the first ended.
    let src = "G0 X0\nN10 X1\nN20 G1 X2\nG0 X3\nREPEAT N10 N20 P=2\nX4\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 2, 1), None);
    assert_eq!(group_at(&states, 6, 1), Some("G1"));
    let states = main_program(&src.replace("P=2", "P=1"));
    assert_eq!(group_at(&states, 2, 1), Some("G0"));
    assert_eq!(group_at(&states, 6, 1), Some("G1"));
}

#[test]
fn a_suppression_keeps_group_8_only_where_it_is_known() {
    let states = main_program("G55 X0\nG53 X1\nX2\n");
    assert_eq!(group_at(&states, 2, 8), Some("G55"));
    assert_eq!(group_at(&states, 3, 8), Some("G55"));
    // Lowering names G56 the selection at line 4 (line order); along the
    // jump it is G55.
    let src = "G55 X0\nIF R1==1 GOTOF MARK\nG56\nMARK: G53 X0\nX1\nG57\nX2\n";
    let states = main_program(src);
    assert_eq!(group_at(&states, 4, 8), None);
    assert_eq!(group_at(&states, 5, 8), None);
    assert_eq!(group_at(&states, 7, 8), Some("G57"));
}

#[test]
fn indirect_g_programming_sets_or_forgets_its_group() {
    let states = main_program("G0 X0\nG[6]=R1\nX1\nG[1]=2\nX2\n");
    assert_eq!(group_at(&states, 3, 6), None);
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    assert_eq!(group_at(&states, 5, 1), Some("G1"));
    // Lowering folds a constant index into `modal_change`; another writer
    // may not.
    let doc = document(vec![
        (
            1,
            Op::ModalChangeIndirect {
                group: 6,
                index: Value::Const(2.0),
            },
        ),
        (
            2,
            Op::ModalChangeIndirect {
                group: 1,
                index: Value::Const(99.0),
            },
        ),
        (3, Op::End),
    ]);
    let states = ModalStates::analyse(&doc, Start::Reset(&builtin()));
    assert_eq!(group_at(&states, 2, 6), Some("G18"));
    assert_eq!(group_at(&states, 2, 1), Some("G1"));
    assert_eq!(group_at(&states, 3, 1), None, "no index 99");
}

/// A document of hand-made instructions, one per line unless given.
fn document(ops: Vec<(u32, Op)>) -> Document {
    let file: Arc<str> = Arc::from("odd.mpf");
    Document {
        instructions: ops
            .into_iter()
            .map(|(line, op)| Instruction {
                op,
                source: Source {
                    file: file.clone(),
                    line,
                    col: 1,
                    span: ByteRange { start: 0, end: 0 },
                },
            })
            .collect(),
        ..Document::new()
    }
}

fn modal(group: u8, code: &'static str) -> Op {
    Op::ModalChange {
        group,
        code: gcodec_lang::ggroups::GCommand::named(code).expect("a G command"),
    }
}

fn label(name: &str) -> Op {
    Op::Label { name: name.into() }
}

fn jump(target: &str) -> Op {
    Op::Jump {
        target: target.into(),
        condition: None,
    }
}

#[test]
fn odd_documents_give_answers_not_panics() {
    let profile = builtin();
    let empty = ModalStates::analyse(&Document::new(), Start::Reset(&profile));
    assert_eq!(empty.iter().count(), 0);
    assert_eq!(empty.line_state(1), LineState::NoInstructions);
    // Wrong groups, a duplicate label (a jump goes to both), lines out of
    // order, instructions after `end`, a section whose labels are missing.
    let doc = document(vec![
        (1, modal(0, "G1")),
        (1, modal(99, "G1")),
        (1, modal(6, "G1")),
        (2, modal(1, "G0")),
        (2, jump("TWICE")),
        (5, label("TWICE")),
        (5, modal(1, "G2")),
        (5, jump("AFTER")),
        (3, label("TWICE")),
        (3, Op::End),
        (4, label("AFTER")),
        (
            4,
            Op::RepeatSection(Box::new(gcodec_ail::RepeatSection {
                start: "NONE".into(),
                end: "NONE.end".into(),
                passes: Value::Const(1.0),
            })),
        ),
        (6, modal(1, "G3")),
        (7, Op::End),
        (2, modal(1, "G1")),
    ]);
    let states = ModalStates::analyse(&doc, Start::Reset(&profile));
    assert_eq!(at(&states, 1).get(6), Some("G17"), "unchanged by line 1");
    assert_eq!(group_at(&states, 2, 6), None, "G1 is no plane");
    assert_eq!(group_at(&states, 5, 1), Some("G0"));
    assert_eq!(group_at(&states, 3, 1), Some("G0"));
    assert_eq!(group_at(&states, 4, 1), Some("G2"));
    // After the broken section nothing is known.
    assert_eq!(at(&states, 6).known().count(), 0);
    assert_eq!(group_at(&states, 7, 1), Some("G3"));
    // Line 2 appears again after `end`; its state is its first run's.
    assert_eq!(
        states.iter().map(|(l, _)| l).collect::<Vec<_>>(),
        [1, 2, 3, 4, 5, 6, 7]
    );
}

#[test]
fn random_documents_terminate() {
    // A fixed LCG: the same documents every run.
    let mut seed = 0x1234_5678_9ABC_DEF0_u64;
    let mut next = move |n: u64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 33) % n
    };
    let codes = ["G0", "G1", "G2", "G17", "G18", "G54", "G55", "DIAMON"];
    let profile = builtin();
    let mut reached = 0;
    for _ in 0..200 {
        let len = next(60) as u32 + 1;
        let mut ops = Vec::new();
        for i in 0..len {
            let name = format!("L{}", next(8));
            let condition =
                (next(2) == 0).then(|| Box::new(gcodec_ail::Expr::Bool { value: true }));
            let op = match next(12) {
                0 | 1 => {
                    let code = codes[next(codes.len() as u64) as usize];
                    let group = gcodec_lang::ggroups::lookup(code).map_or(1, |(g, _)| g);
                    modal(group, code)
                }
                2 => label(&name),
                3 if next(4) == 0 => Op::SkipBlock {
                    level: 0,
                    end: name,
                },
                3 => Op::Jump {
                    target: name,
                    condition,
                },
                4 => Op::ComputedJump(Box::new(gcodec_ail::ComputedJump {
                    target: gcodec_ail::Expr::String { value: name },
                    search: gcodec_ail::JumpSearch::Forward,
                    continue_if_missing: next(2) == 0,
                    condition: condition.map(|c| *c),
                })),
                5 => Op::GotoStart { condition },
                6 => Op::RepeatSection(Box::new(gcodec_ail::RepeatSection {
                    start: name,
                    end: format!("L{}", next(8)),
                    passes: Value::Const(next(3) as f64),
                })),
                7 => Op::Return { values: Vec::new() },
                8 => Op::CancelModalCall,
                9 => Op::WorkOffset {
                    group8_selected: Some(WorkOffsetCode(55)),
                    suppression: None,
                    suppression_scope: None,
                },
                _ => Op::Motion {
                    motion: gcodec_lang::MotionKind::Linear,
                    targets: Vec::new(),
                    circle: None,
                    details: None,
                },
            };
            ops.push((i / 2 + 1, op));
        }
        let states = ModalStates::analyse(&document(ops), Start::Reset(&profile));
        reached += states.iter().count();
    }
    assert!(reached > 0);
}

#[test]
fn a_hundred_thousand_blocks_keep_one_state_per_distinct_state() {
    let src = program::generate(100_000);
    let profile = builtin();
    let parsed = gcodec_parser::parse_bytes("big.mpf", &src);
    assert!(parsed.diagnostics.is_empty());
    let document = gcodec_sema::lower(&parsed.program, &profile).document;
    let states = ModalStates::analyse(&document, Start::Reset(&profile));
    let lines = states.iter().count();
    assert_eq!(states.unreachable_lines().count(), 0);
    assert!(lines > 90_000, "{lines}");
    // The generator only ever selects G17, G90 and G54.
    for (line, state) in states.iter() {
        assert_eq!(state.get(6), Some("G17"), "line {line}");
        assert_eq!(state.get(14), Some("G90"), "line {line}");
    }
    // Motion commands change inside loops and branches: some blocks do not
    // know group 1, most do.
    let unknown_motion = states.iter().filter(|(_, s)| s.get(1).is_none()).count();
    assert!(
        unknown_motion > 0 && unknown_motion < lines / 2,
        "{unknown_motion}"
    );
    // Memory: 8 bytes a line, each distinct state once.
    assert!(
        states.distinct_states() < 64,
        "{}",
        states.distinct_states()
    );
    assert!(
        states.heap_bytes() <= lines * 8 + 64 * 65,
        "{} bytes",
        states.heap_bytes()
    );
}

#[test]
fn every_fixture_and_corpus_program_is_analysed() {
    let profile = builtin();
    let mut reached = 0;
    let paths = common::all_programs();
    assert!(paths.len() >= 30, "{} programs", paths.len());
    for path in paths {
        let name = path.display().to_string();
        let bytes = std::fs::read(&path).expect("readable");
        let parsed = gcodec_parser::parse_bytes(&name, &bytes);
        let document = gcodec_sema::lower(&parsed.program, &profile).document;
        for start in [Start::Reset(&profile), Start::Unknown] {
            let states = ModalStates::analyse(&document, start);
            // Every line with instructions is answered, one way or the other.
            for instruction in &document.instructions {
                let line = instruction.source.line;
                assert_ne!(
                    states.line_state(line),
                    LineState::NoInstructions,
                    "{name}:{line}"
                );
            }
            reached += states.iter().count();
        }
    }
    assert!(reached > 0);
}

/// A straightforward reference for the analysis: one state per
/// instruction, iterated round-robin to the fixed point. `None`: not
/// reached; else (registry index per group, 0 unknown; modal call: 0
/// unknown, 1 inactive, 2 active).
mod reference {
    use std::collections::{BTreeMap, HashSet};

    use gcodec_ail::{Document, Op, Value};
    use gcodec_lang::MClass;
    use gcodec_lang::ggroups;
    use gcodec_sema::modal::ModalState;

    pub type State = ([u8; 64], u8);

    fn member_index(group: u8, code: &str) -> u8 {
        match ggroups::lookup(code) {
            Some((found, index)) if found == group => index,
            _ => 0,
        }
    }

    fn set(state: &mut State, group: u8, index: u8) {
        if (1..=64).contains(&group) {
            state.0[usize::from(group) - 1] = index;
        }
    }

    fn transfer(state: &mut State, op: &Op) {
        match op {
            Op::ModalChange { group, code } if ggroups::is_modal(*group) => {
                set(state, *group, member_index(*group, code.name()));
            }
            Op::ModalChangeIndirect { group, index } if ggroups::is_modal(*group) => {
                let index = match index {
                    Value::Const(v) if v.fract() == 0.0 && (1.0..=255.0).contains(v) => {
                        let v = *v as u8;
                        if ggroups::member(*group, v).is_some() {
                            v
                        } else {
                            0
                        }
                    }
                    _ => 0,
                };
                set(state, *group, index);
            }
            Op::WorkOffset {
                group8_selected: Some(selected),
                suppression,
                ..
            } => {
                let selected = member_index(8, &selected.to_string());
                if suppression.is_none() || !(state.0[7] != 0 && state.0[7] == selected) {
                    state.0[7] = if suppression.is_none() { selected } else { 0 };
                }
            }
            Op::Call(call) if call.modal => state.1 = 2,
            Op::Call(_) => state.0 = [0; 64],
            Op::CancelModalCall => state.1 = 1,
            Op::Motion { .. } if state.1 != 1 => state.0 = [0; 64],
            _ => {}
        }
    }

    fn join(into: &mut Option<State>, state: &State) -> bool {
        match into {
            None => {
                *into = Some(*state);
                true
            }
            Some(mine) => {
                let before = *mine;
                for (m, t) in mine.0.iter_mut().zip(&state.0) {
                    if m != t {
                        *m = 0;
                    }
                }
                if mine.1 != state.1 {
                    mine.1 = 0;
                }
                *mine != before
            }
        }
    }

    /// The state before each instruction.
    pub fn states(document: &Document, initial: State) -> Vec<Option<State>> {
        let ops: Vec<&Op> = document.instructions.iter().map(|i| &i.op).collect();
        let n = ops.len();
        let labels = |name: &str| -> Vec<usize> {
            (0..n)
                .filter(|&i| matches!(ops[i], Op::Label { name: l } if l == name))
                .collect()
        };
        let all_labels: Vec<usize> = (0..n)
            .filter(|&i| matches!(ops[i], Op::Label { .. }))
            .collect();
        let mut at: Vec<Option<State>> = vec![None; n];
        if n == 0 {
            return at;
        }
        at[0] = Some(initial);
        let mut changed = true;
        while changed {
            changed = false;
            for i in 0..n {
                let Some(mut state) = at[i] else { continue };
                transfer(&mut state, ops[i]);
                let mut flows: Vec<(usize, State)> = Vec::new();
                match ops[i] {
                    Op::Jump { target, condition } => {
                        flows.extend(labels(target).into_iter().map(|l| (l, state)));
                        if condition.is_some() {
                            flows.push((i + 1, state));
                        }
                    }
                    Op::SkipBlock { end, .. } => {
                        flows.extend(labels(end).into_iter().map(|l| (l, state)));
                        flows.push((i + 1, state));
                    }
                    Op::ComputedJump(jump) => {
                        flows.extend(all_labels.iter().map(|&l| (l, state)));
                        if jump.condition.is_some() || jump.continue_if_missing {
                            flows.push((i + 1, state));
                        }
                    }
                    Op::GotoStart { .. } => {
                        flows.push((0, state));
                        flows.push((i + 1, state));
                    }
                    Op::RepeatSection(section) => {
                        let starts = labels(&section.start);
                        let ends = labels(&section.end);
                        if starts.is_empty() || ends.is_empty() {
                            flows.push((i + 1, ([0; 64], 0)));
                        } else {
                            flows.extend(starts.iter().map(|&l| (l, state)));
                            if !matches!(section.passes, Value::Const(p) if p >= 1.0) {
                                flows.push((i + 1, state));
                            }
                            for end in ends {
                                let Some(end) = at[end] else { continue };
                                flows.push((i + 1, end));
                                if !matches!(section.passes, Value::Const(p) if p == 1.0) {
                                    flows.extend(starts.iter().map(|&l| (l, end)));
                                }
                            }
                        }
                    }
                    Op::Return { .. } | Op::End => {}
                    Op::MFunction(m)
                        if m.class == MClass::ProgramFlow
                            && m.address_extension.is_none()
                            && m.address_extension_expr.is_none()
                            && matches!(m.m_value, Some(2 | 17 | 30)) => {}
                    _ => flows.push((i + 1, state)),
                }
                for (to, state) in flows {
                    if to < n && join(&mut at[to], &state) {
                        changed = true;
                    }
                }
            }
        }
        at
    }

    /// The state of each line with instructions (its first run's), and
    /// how many distinct states the reached runs have (the analysis keeps
    /// those of later runs of a line too).
    pub fn lines(document: &Document, initial: State) -> (BTreeMap<u32, Option<State>>, usize) {
        let at = states(document, initial);
        let mut lines = BTreeMap::new();
        let mut distinct = HashSet::new();
        let mut previous = None;
        for (i, instruction) in document.instructions.iter().enumerate() {
            let line = instruction.source.line;
            if previous != Some(line) {
                previous = Some(line);
                lines.entry(line).or_insert(at[i]);
                distinct.extend(at[i]);
            }
        }
        (lines, distinct.len())
    }

    pub fn of(state: &ModalState) -> State {
        let mut groups = [0; 64];
        for (g, slot) in groups.iter_mut().enumerate() {
            *slot = state.index(g as u8 + 1).unwrap_or(0);
        }
        let call = match state.modal_call_active() {
            None => 0,
            Some(false) => 1,
            Some(true) => 2,
        };
        (groups, call)
    }
}

/// Asserts that the analysis agrees with the reference on `document`.
fn check_against_reference(document: &Document, profile: &Profile, name: &str) {
    for (start, initial) in [
        (
            Start::Reset(profile),
            reference::of(&ModalState::reset(profile)),
        ),
        (Start::Unknown, reference::of(&ModalState::unknown())),
    ] {
        let states = ModalStates::analyse(document, start);
        let (expected, distinct) = reference::lines(document, initial);
        let reached: Vec<(u32, reference::State)> = states
            .iter()
            .map(|(line, state)| (line, reference::of(state)))
            .collect();
        let expected_reached: Vec<(u32, reference::State)> = expected
            .iter()
            .filter_map(|(&line, state)| Some((line, (*state)?)))
            .collect();
        assert_eq!(reached, expected_reached, "{name}");
        let unreachable: Vec<u32> = states.unreachable_lines().collect();
        let expected_unreachable: Vec<u32> = expected
            .iter()
            .filter(|(_, state)| state.is_none())
            .map(|(&line, _)| line)
            .collect();
        assert_eq!(unreachable, expected_unreachable, "{name}");
        for (&line, state) in &expected {
            match (states.line_state(line), state) {
                (LineState::Reached(s), Some(e)) => assert_eq!(reference::of(s), *e, "{name}"),
                (LineState::Unreachable, None) => {}
                (got, _) => panic!("{name}:{line}: {got:?}"),
            }
        }
        let last = expected.keys().last().copied().unwrap_or(0);
        for line in 0..=last + 1 {
            if !expected.contains_key(&line) {
                assert_eq!(states.line_state(line), LineState::NoInstructions, "{name}");
            }
        }
        assert_eq!(states.distinct_states(), distinct, "{name}");
    }
}

#[test]
fn the_analysis_agrees_with_a_reference_on_programs() {
    let profile = builtin();
    let paths = common::all_programs();
    for path in paths {
        let name = path.display().to_string();
        let bytes = std::fs::read(&path).expect("readable");
        let parsed = gcodec_parser::parse_bytes(&name, &bytes);
        let document = gcodec_sema::lower(&parsed.program, &profile).document;
        check_against_reference(&document, &profile, &name);
    }
    let src = program::generate(3_000);
    let parsed = gcodec_parser::parse_bytes("gen.mpf", &src);
    let document = gcodec_sema::lower(&parsed.program, &profile).document;
    check_against_reference(&document, &profile, "generated");
    for src in [
        "G0 X0\nMCALL CYCLE81(1,2,3)\nG17\nX1\nX2\nMCALL\nG17\nX3\nX4\n",
        "G0 X0\nIF R1==1\nMCALL CYCLE81(1,2,3)\nENDIF\nG17\nX1\nX2\n",
        "G2 X0 CR=5\nN10 G0 X0\nN20 G1 X1\nG3 X2 CR=5\nREPEAT N10 N20 P=2\nX3\n",
        "G0 X0\nN10 X1\nN20 G1 X2\nG0 X3\nREPEAT N10 N20 P=R1\nX4\n",
        "G55 X0\nIF R1==1 GOTOF MARK\nG56\nMARK: G53 X0\nX1\nG57\nX2\n",
        "G0 X0\nIF R2==1 GOTOF \"MA\"<<R1\nG1 X1\nMA1: X2\nG18\nMA2: X3\n",
        "G0 X0\nG2 X1 CR=5\nGOTOS\nX2\nM30\nX3\n",
        "G0 X0\n/G1 X1\n/3 LBL: G2 X2 CR=5\nX3\nIF R1<2 GOTOB LBL\nM30\n",
        "G0 X0\nSTART: X1\n/G1 X2\nREPEAT START P=2\nX3\n",
    ] {
        check_against_reference(&lower_with(src, &profile), &profile, src);
    }
}

#[test]
fn the_analysis_agrees_with_a_reference_on_random_documents() {
    let mut seed = 0x0BAD_5EED_1234_5678_u64;
    let mut next = move |n: u64| {
        seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (seed >> 33) % n
    };
    let codes = ["G0", "G1", "G2", "G17", "G18", "G54", "G55", "DIAMON", "G4"];
    let profile = builtin();
    for round in 0..2_000 {
        let len = next(50) as u32 + 1;
        let labels = next(6) + 1;
        let mut ops = Vec::new();
        let mut line = 1;
        for _ in 0..len {
            let name = format!("L{}", next(labels));
            let condition =
                (next(2) == 0).then(|| Box::new(gcodec_ail::Expr::Bool { value: true }));
            let motion = || Op::Motion {
                motion: gcodec_lang::MotionKind::Linear,
                targets: Vec::new(),
                circle: None,
                details: None,
            };
            let op = match next(20) {
                0..=2 => {
                    let code = codes[next(codes.len() as u64) as usize];
                    let group = gcodec_lang::ggroups::lookup(code).map_or(1, |(g, _)| g);
                    modal(group, code)
                }
                3 => modal(1, "G17"),
                4 | 5 => label(&name),
                6 if next(4) == 0 => Op::SkipBlock {
                    level: next(10) as u8,
                    end: name,
                },
                6 => Op::Jump {
                    target: if next(8) == 0 {
                        "NOWHERE@missing".into()
                    } else {
                        name
                    },
                    condition,
                },
                7 => Op::ComputedJump(Box::new(gcodec_ail::ComputedJump {
                    target: gcodec_ail::Expr::String { value: name },
                    search: gcodec_ail::JumpSearch::Forward,
                    continue_if_missing: next(2) == 0,
                    condition: condition.map(|c| *c),
                })),
                8 => Op::GotoStart { condition },
                9 => Op::RepeatSection(Box::new(gcodec_ail::RepeatSection {
                    start: name,
                    end: format!("L{}", next(labels + 1)),
                    passes: if next(4) == 0 {
                        Value::Expr(Box::new(gcodec_ail::Expr::Bool { value: true }))
                    } else {
                        Value::Const(next(3) as f64)
                    },
                })),
                10 => {
                    if next(3) == 0 {
                        Op::End
                    } else {
                        Op::Return { values: Vec::new() }
                    }
                }
                11 => Op::CancelModalCall,
                12 => Op::WorkOffset {
                    group8_selected: [None, Some(WorkOffsetCode(55)), Some(WorkOffsetCode::G54)]
                        [next(3) as usize],
                    suppression: (next(2) == 0).then_some(gcodec_ail::Suppression::G53),
                    suppression_scope: None,
                },
                13 => Op::Call(Box::new(gcodec_ail::Call {
                    target: "SUB".into(),
                    target_expr: None,
                    section: None,
                    by_path: false,
                    external: false,
                    args: Vec::new(),
                    passes: None,
                    modal: next(2) == 0,
                })),
                14 => Op::ModalChangeIndirect {
                    group: [1, 6, 2, 8][next(4) as usize],
                    index: Value::Const(next(5) as f64),
                },
                _ => motion(),
            };
            ops.push((line, op));
            // Mostly one or two instructions a line, in order; sometimes a
            // gap, sometimes a line again.
            match next(10) {
                0..=3 => {}
                4..=7 => line += 1,
                8 => line += 2,
                _ => line = next(u64::from(line) + 1) as u32 + 1,
            }
        }
        let document = document(ops);
        check_against_reference(&document, &profile, &format!("round {round}"));
    }
}
