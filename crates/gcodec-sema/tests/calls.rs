//! `CASE`, `REPEAT` sections, `GOTOS`, computed jump targets, calls
//! (`CALL`, `PCALL`, `MCALL`), `PROC` and `EXTERN` signatures, and frames.

use gcodec_ail::{JumpSearch, Op, Value};
use gcodec_sema::{Lowered, lower};

mod common;

use common::{codes, motions, selections};

fn lower_src(src: &str) -> Lowered {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    common::lower_named("calls.mpf", &profile, src)
}

fn ops(l: &Lowered) -> Vec<&Op> {
    l.document.instructions.iter().map(|i| &i.op).collect()
}

fn listing(l: &Lowered) -> String {
    let mut out = String::new();
    gcodec_ail::write_listing(&l.document, &mut out).unwrap();
    out
}

/// The instruction lines of the listing, without line and column.
fn lines(l: &Lowered) -> Vec<String> {
    listing(l)
        .lines()
        .map(|line| {
            line.split_whitespace()
                .skip(1)
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect()
}

#[test]
fn case_arms_are_conditional_jumps_then_the_default() {
    let l = lower_src(
        "CASE R1 OF 1 GOTOF ONE 'H2' GOTOF TWO DEFAULT GOTOF OTHER\nONE: X1\nTWO: X2\nOTHER: X3\nM30\n",
    );
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let lines = lines(&l);
    assert_eq!(lines[0], "jump condition=(R1==1) target=\"ONE@2\"");
    assert_eq!(lines[1], "jump condition=(R1==2) target=\"TWO@3\"");
    assert_eq!(lines[2], "jump target=\"OTHER@4\"");
}

#[test]
fn case_without_default_falls_through() {
    let l = lower_src("CASE R1 OF 1 GOTOF ONE\nX5\nONE: X1\nM30\n");
    let jumps: Vec<_> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::Jump { condition, .. } => Some(condition.is_some()),
            _ => None,
        })
        .collect();
    assert_eq!(jumps, [true], "only the conditional arm");
}

#[test]
fn case_arms_compare_with_constants() {
    let l = lower_src("CASE R1 OF R2 GOTOF ONE\nONE: M30\n");
    assert_eq!(codes(&l), ["gcodec::lower::case_value_not_constant"]);
}

#[test]
fn case_targets_missing_warn_like_jumps() {
    let l = lower_src("CASE R1 OF 1 GOTOB NOWHERE\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::missing_jump_target"]);
}

const SECTIONS: &str = "START: X1
N60 X2
ENDLABEL: X3
N80 X4
N90 REPEAT START P=2
N100 REPEATB N80 P=R5
N110 REPEAT START N60
M30
";

/// The section label after the last block of a section.
fn section_ends(l: &Lowered) -> Vec<(u32, String)> {
    l.document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            Op::Label { name } if name.starts_with("SECTION@") => {
                Some((i.source.line, name.clone()))
            }
            _ => None,
        })
        .collect()
}

fn sections(l: &Lowered) -> Vec<(String, String, Value)> {
    ops(l)
        .into_iter()
        .filter_map(|op| match op {
            Op::RepeatSection(r) => Some((r.start.clone(), r.end.clone(), r.passes.clone())),
            _ => None,
        })
        .collect()
}

#[test]
fn repeat_sections_run_from_their_label_to_their_end() {
    let l = lower_src(SECTIONS);
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let sections = sections(&l);
    // `REPEAT START`: from START to the ENDLABEL after it.
    assert_eq!(sections[0].0, "START@1");
    assert_eq!(sections[0].1, "SECTION@5.end");
    assert_eq!(sections[0].2, Value::Const(2.0));
    // `REPEATB N80`: that block alone, passes computed.
    assert_eq!(sections[1].0, "N80@4");
    assert!(matches!(sections[1].2, Value::Expr(_)));
    // `REPEAT START N60`: between two labels; P omitted is one pass.
    assert_eq!(sections[2].0, "START@1");
    assert_eq!(sections[2].2, Value::Const(1.0));
    assert_eq!(
        section_ends(&l),
        [
            (2, "SECTION@7.end".to_owned()),
            (3, "SECTION@5.end".to_owned()),
            (4, "SECTION@6.end".to_owned()),
        ]
    );
}

#[test]
fn a_section_without_endlabel_ends_before_the_repeat() {
    let l = lower_src("BEGIN: X1\nX2\nX3\nREPEAT BEGIN P=3\nM30\n");
    assert_eq!(section_ends(&l), [(3, "SECTION@4.end".to_owned())]);
    // The end label comes after everything of its block.
    let last_of_block_3 = l
        .document
        .instructions
        .iter()
        .rfind(|i| i.source.line == 3)
        .unwrap();
    assert!(matches!(&last_of_block_3.op, Op::Label { name } if name == "SECTION@4.end"));
}

#[test]
fn repeat_searches_its_start_towards_the_program_start() {
    // `REPEAT L` only looks back: a label after it is not found.
    let l = lower_src("REPEAT LATER P=2\nLATER: X1\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::missing_jump_target"]);
    assert!(sections(&l).is_empty());
    // `REPEATB` looks back first, then forward.
    let l = lower_src("REPEATB LATER P=2\nLATER: X1\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert_eq!(sections(&l)[0].0, "LATER@2");
}

#[test]
fn repeat_passes_are_whole_numbers() {
    for passes in ["P=0", "P=1.5"] {
        let l = lower_src(&format!("LB: X1\nREPEAT LB {passes}\nM30\n"));
        assert_eq!(codes(&l), ["gcodec::lower::invalid_value"], "{passes}");
    }
}

#[test]
fn gotos_goes_back_to_the_start_when_asked() {
    let l = lower_src("X1\nGOTOS\nIF R1>1 GOTOS\nM30\n");
    let found: Vec<bool> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::GotoStart { condition } => Some(condition.is_some()),
            _ => None,
        })
        .collect();
    assert_eq!(found, [false, true]);
}

#[test]
fn computed_targets_are_searched_at_run_time() {
    let l = lower_src("N10 X1\nLBL1: X2\nGOTOF \"LBL\"<<R1\nGOTOC \"N\"<<R2\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let jumps: Vec<(JumpSearch, bool)> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::ComputedJump(j) => Some((j.search, j.continue_if_missing)),
            _ => None,
        })
        .collect();
    assert_eq!(
        jumps,
        [
            (JumpSearch::Forward, false),
            (JumpSearch::ForwardThenBackward, true)
        ]
    );
    // Every label and block number can be the target: each is a label.
    let labels: Vec<&str> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::Label { name } => Some(name.as_str()),
            _ => None,
        })
        .collect();
    assert_eq!(labels, ["N10@1", "LBL1@2"]);
}

#[test]
fn modal_calls_and_their_cancel() {
    let l = lower_src("MCALL CYCLE81(10,0,2,-5)\nX10\nX20\nMCALL\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let ops = ops(&l);
    assert!(matches!(ops[0], Op::Call(c) if c.modal && c.target == "CYCLE81" && c.args.len() == 4));
    assert!(ops.iter().any(|op| matches!(op, Op::CancelModalCall)));
}

#[test]
fn indirect_and_path_calls() {
    let l = lower_src(
        "DEF STRING[20] PRG\nCALL PRG\nCALL BLOCK LB TO N20\nCALL \"SUB\" BLOCK \"N10\" TO \"N20\"\nPCALL /_N_WKS_DIR/_N_W_WPD/_N_SUB_SPF(1,2)\nLB: M30\n",
    );
    let calls: Vec<&gcodec_ail::Call> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::Call(c) => Some(c.as_ref()),
            _ => None,
        })
        .collect();
    assert_eq!(calls.len(), 4);
    assert!(calls[0].target.is_empty() && calls[0].target_expr.is_some());
    assert!(calls[0].section.is_none());
    // No program: a section of the calling program.
    assert!(calls[1].target_expr.is_none() && calls[1].section.is_some());
    assert!(calls[2].target_expr.is_some() && calls[2].section.is_some());
    assert!(calls[3].by_path && calls[3].target == "/_N_WKS_DIR/_N_W_WPD/_N_SUB_SPF");
    assert_eq!(calls[3].args.len(), 2);
}

#[test]
fn a_procedure_keeps_its_signature() {
    let l = lower_src("PROC CONTOUR(REAL XX1, VAR INT NN, REAL DD=2) SBLOF DISPLOF\nRET\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let Op::Procedure(p) = ops(&l)[0] else {
        panic!("{}", listing(&l));
    };
    assert_eq!(p.name, "CONTOUR");
    assert_eq!(p.attributes, ["SBLOF", "DISPLOF"]);
    let params: Vec<(&str, String, bool, bool)> = p
        .params
        .iter()
        .map(|q| {
            (
                q.name.as_str(),
                q.data_type.describe(),
                q.by_reference,
                q.default.is_some(),
            )
        })
        .collect();
    assert_eq!(
        params,
        [
            ("XX1", "REAL".to_owned(), false, false),
            ("NN", "INT".to_owned(), true, false),
            ("DD", "REAL".to_owned(), false, true)
        ]
    );
}

#[test]
fn proc_opens_the_program() {
    let l = lower_src("; a comment first is fine\nPROC FIRST\nM17\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let l = lower_src("X1\nPROC LATE\nM17\n");
    assert_eq!(codes(&l), ["gcodec::lower::proc_not_first"]);
}

#[test]
fn endproc_returns() {
    let l = lower_src("PROC P\nX1\nENDPROC\n");
    assert!(
        ops(&l)
            .iter()
            .any(|op| matches!(op, Op::Return { values } if values.is_empty()))
    );
}

#[test]
fn calls_are_checked_against_extern_signatures() {
    let l = lower_src("EXTERN SUB(REAL, VAR INT)\nSUB(1, R1)\nSUB(1)\nSUB\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    assert!(matches!(ops(&l)[0], Op::External(e) if e.name == "SUB" && e.params[1].by_reference));
    let l = lower_src("EXTERN SUB(REAL, VAR INT)\nSUB(1, R1, 3)\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::too_many_arguments"]);
    let l = lower_src("EXTERN SUB(REAL, VAR INT)\nSUB(1, R1+1)\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::argument_not_variable"]);
}

#[test]
fn calls_of_the_files_own_procedure_are_checked() {
    let l = lower_src("PROC COUNTDOWN(INT NN)\nIF NN>0\nCOUNTDOWN(NN-1, 2)\nENDIF\nM17\n");
    assert_eq!(codes(&l), ["gcodec::lower::too_many_arguments"]);
    // Modal calls too.
    let l = lower_src("EXTERN CYC(REAL)\nMCALL CYC(1, 2)\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::too_many_arguments"]);
}

#[test]
fn calls_of_undeclared_programs_are_not_checked() {
    let l = lower_src("CYCLE81(1, 2, 3, 4, 5, 6, 7, 8, 9)\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
}

#[test]
fn frames_stand_alone_and_name_axes() {
    let l = lower_src("TRANS X10 Y5\nROT RPL=45\nAROT Z30\nTRANS\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let frames: Vec<(String, usize)> = ops(&l)
        .into_iter()
        .filter_map(|op| match op {
            Op::Frame(f) => Some((f.op.keyword().to_owned(), f.values.len())),
            _ => None,
        })
        .collect();
    assert_eq!(
        frames,
        [
            ("TRANS".to_owned(), 2),
            ("ROT".to_owned(), 1),
            ("AROT".to_owned(), 1),
            ("TRANS".to_owned(), 0)
        ]
    );
    let l = lower_src("R1=1 TRANS X10\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::frame_not_alone"]);
}

#[test]
fn a_frame_with_an_unknown_axis_is_rejected_not_a_reset() {
    let l = lower_src("TRANS Q5\nSCALE RPL=2\nM30\n");
    assert_eq!(
        codes(&l),
        [
            "gcodec::lower::unknown_address",
            "gcodec::lower::unknown_address"
        ]
    );
    assert!(!ops(&l).iter().any(|op| matches!(op, Op::Frame(_))));
}

#[test]
fn a_g_command_after_a_frame_instruction_is_another_statement() {
    // The parser reads `G0 Z10` as words of the frame; `G0` names no axis.
    let l = lower_src("TRANS X5 G0 Z10\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::frame_not_alone"]);
    assert!(!ops(&l).iter().any(|op| matches!(op, Op::Frame(_))));
    // An axis letter the machine lacks stays an unknown address.
    let l = lower_src("TRANS X5 A3\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
}

#[test]
fn a_motion_after_paths_with_different_commands_is_decided_when_it_runs() {
    use gcodec_lang::MotionKind::*;
    let l = lower_src("IF R1>0\nG0 X1\nELSE\nG1 X2 F100\nENDIF\nX3\nM30\n");
    assert_eq!(motions(&l), [Rapid, Linear, Modal]);
    // Where every path agrees, the dataflow knows the command.
    let l = lower_src("IF R1>0\nG0 X1\nELSE\nG0 X2\nENDIF\nX3\nM30\n");
    assert_eq!(motions(&l), [Rapid, Rapid, Rapid]);
    // A loop whose body changes the command.
    let l = lower_src("G0 X0\nWHILE R1<3\nX1\nG1 X2 F100\nR1=R1+1\nENDWHILE\nM30\n");
    assert_eq!(motions(&l), [Rapid, Modal, Linear]);
}

#[test]
fn a_motion_after_a_section_repetition_runs_in_the_sections_state() {
    use gcodec_lang::MotionKind::*;
    let l = lower_src("N10 G3 X2 CR=5\nN20 G1 X1 F100\nREPEAT N10 N20 P=2\nX3\nM30\n");
    assert_eq!(motions(&l), [ArcCcw, Linear, Linear]);
}

#[test]
fn calls_and_modal_calls_may_change_the_motion_command() {
    use gcodec_lang::MotionKind::*;
    let l = lower_src("G0 X0\nCYCLE81(10,0,2,-5)\nX1\nM30\n");
    assert_eq!(motions(&l), [Rapid, Modal]);
    let l = lower_src("G0 X0\nMCALL CYCLE81(10,0,2,-5)\nX1\nX2\nMCALL\nM30\n");
    assert_eq!(motions(&l), [Rapid, Rapid, Modal]);
}

#[test]
fn a_subprogram_starts_in_its_callers_state() {
    use gcodec_lang::MotionKind::*;
    let lower_as = |file: &str, src: &str| {
        let parsed = gcodec_parser::parse_bytes(file, src.as_bytes());
        lower(&parsed.program, &gcodec_profile::builtin().unwrap())
    };
    let l = lower_as("SUB.SPF", "X1 Y1\nG1 X2 F100\nM17\n");
    assert_eq!(motions(&l), [Modal, Linear]);
    let l = lower_as("CONTOUR.mpf", "PROC CONTOUR\nX1\nM17\n");
    assert_eq!(motions(&l), [Modal]);
    let l = lower_as("MAIN.MPF", "X1\nM30\n");
    assert_eq!(motions(&l), [Linear]);
}

#[test]
fn a_suppression_after_paths_with_different_offsets_leaves_the_selection_open() {
    let l = lower_src("IF R1>0\nG54\nELSE\nG55\nENDIF\nG53 X0\nM30\n");
    assert_eq!(
        selections(&l),
        [Some("g54".to_owned()), Some("g55".to_owned()), None]
    );
    let l = lower_src("G55\nIF R1>0\nX1\nENDIF\nG53 X0\nM30\n");
    assert_eq!(
        selections(&l),
        [Some("g55".to_owned()), Some("g55".to_owned())]
    );
}

#[test]
fn structure_blocks_carry_no_label_and_no_skip_mark() {
    let l = lower_src("LBL1: IF R1>0\nX1\nENDIF\n/WHILE R1<2\nR1=R1+1\nENDWHILE\nM30\n");
    assert_eq!(
        codes(&l),
        [
            "gcodec::lower::label_in_structure_block",
            "gcodec::lower::skipped_structure_block"
        ]
    );
    // A label before the structure, and skipped blocks inside it, are fine.
    let l = lower_src("LBL1:\nIF R1>0\n/X1\nENDIF\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
}

#[test]
fn frame_values_for_axes_named_in_brackets() {
    let l = lower_src("DEF AXIS _XX=X\nATRANS AX[_XX]=5 AX[Y]=2\nM30\n");
    assert!(l.diagnostics.is_empty(), "{:#?}", l.diagnostics);
    let Some(Op::Frame(frame)) = ops(&l).into_iter().find(|op| matches!(op, Op::Frame(_))) else {
        panic!("{}", listing(&l));
    };
    assert_eq!(frame.op.keyword(), "ATRANS");
    assert_eq!(frame.values.len(), 1);
    assert_eq!(frame.values[0].axis, "Y");
    assert_eq!(frame.indirect_values.len(), 1);
    let l = lower_src("ATRANS AX[Q]=5\nM30\n");
    assert_eq!(codes(&l), ["gcodec::lower::unknown_address"]);
    assert!(!ops(&l).iter().any(|op| matches!(op, Op::Frame(_))));
}

#[test]
fn predefined_procedures_take_the_arguments_of_their_signature() {
    for wrong in [
        "SBLOF(1)",
        "CHANDATA()",
        "CHANDATA(1,2)",
        "SETAL(1,\"A\",3)",
        "STOPREOF(2)",
    ] {
        let l = lower_src(&format!("{wrong}\nM30\n"));
        assert_eq!(codes(&l), ["gcodec::lower::argument_count"], "{wrong}");
    }
    for right in [
        "SBLOF",
        "CHANDATA(1)",
        "SETAL(61000,\"A\")",
        "GEOAX(1,X)",
        "GEOAX()",
        "TRANSMIT(1)",
    ] {
        let l = lower_src(&format!("{right}\nM30\n"));
        assert_eq!(codes(&l), Vec::<&str>::new(), "{right}");
    }
    // A program the file declares is checked against its declaration.
    let l = lower_src("EXTERN CHANDATA(REAL, REAL)\nCHANDATA(1,2)\nM30\n");
    assert_eq!(codes(&l), Vec::<&str>::new());
}
