//! A streamed run outlines a program chunk by chunk, then lowers it chunk
//! by chunk again: the chunks' instructions, filled in from the dataflow,
//! are the document of lowering the whole program, and their diagnostics its diagnostics.

use gcodec_sema::{
    ChunkLowering, Definitions, ProgramKind, lower_chunks, lower_in_parts, outline_chunks,
};
use gcodec_source::SourceFile;
use gcodec_stream::chunks;
use gcodec_testkit::agreement::assert_streamed_lowering_agrees;

mod common;

#[path = "../../gcodec-parser/benches/program/mod.rs"]
mod program;

/// In chunks of one, three and 64 lines, on one thread and on three
/// workers taking turns.
fn assert_streamed_agrees(name: &str, src: &[u8], profile: &gcodec_profile::Profile) {
    assert_streamed_lowering_agrees(name, src, profile, &[1, 3, 64], &[1, 3]);
}

#[test]
fn chunks_out_of_order_are_refused() {
    let profile = gcodec_profile::builtin().unwrap();
    let definitions = Definitions::new();
    let src = b"G1 X1 F100\nX2\nM30\n";
    let parsed = gcodec_parser::parse_bytes("order.mpf", src);
    let outline = gcodec_sema::outline(&parsed.program, ProgramKind::Main, &profile, &definitions);
    let mut lowering = ChunkLowering::new(&outline, &profile, src);
    assert!(lowering.lower(1, &parsed.program.blocks[1..]).is_none());
    assert!(lowering.lower(0, &parsed.program.blocks[..1]).is_some());
    assert!(lowering.lower(0, &parsed.program.blocks[..1]).is_none());
}

#[test]
fn values_out_of_range_are_named_as_written_streamed() {
    let profile = gcodec_profile::builtin().unwrap();
    let src = b"T0099999999999\nG0999\nD040000\nM[0100]=3\nM30\n";
    assert_streamed_agrees("written.mpf", src, &profile);
    // A `ChunkLowering` too, whose diagnostics the check above leaves out.
    let parsed = gcodec_parser::parse_bytes("written.mpf", src);
    let definitions = Definitions::new();
    let outline = gcodec_sema::outline(&parsed.program, ProgramKind::Main, &profile, &definitions);
    let mut lowering = ChunkLowering::new(&outline, &profile, src);
    let lowered = lowering.lower(0, &parsed.program.blocks).expect("in order");
    let messages: Vec<String> = lowered
        .diagnostics
        .iter()
        .map(|d| d.message.to_string())
        .collect();
    assert_eq!(
        messages,
        [
            "T0099999999999 is out of range",
            "`G0999` is not a G command of the control",
            "D040000 is out of range",
            "`M[0100]`: a spindle number is a whole number 0…99",
        ]
    );
}

/// Lines of constant words are lowered straight from their bytes in a
/// streamed run; those lowering must see as blocks are handed back: one
/// longer than the machine takes (reported), a jump's target (control-flow
/// facts), words of no straight motion (`G2`, `M3`, an `L`), and word
/// lines between lines that are parsed.
#[test]
fn constant_word_lines_handed_back_lower_the_same_streamed() {
    let profile = gcodec_profile::builtin().unwrap();
    let long = format!("G1 X1{}Y2 F100\n", " ".repeat(600));
    let src = format!(
        "G0 X0 Y0\n{long}N20 X3\nGOTOB N20\nG2 X1 Y1 I0.5 J0\nX2 Y2\nM3 S1000\n\
         G1 X1 ; cut\nG1 X2\nR1=5\nG1 X=R1\nG1 Y4\nL100\nM30\n"
    );
    assert_streamed_agrees("handed_back.mpf", src.as_bytes(), &profile);
    let parsed = gcodec_parser::parse_bytes("handed_back.mpf", src.as_bytes());
    let definitions = Definitions::new();
    let whole = lower_in_parts(&parsed.program, &profile, &definitions, 1);
    let too_long = whole
        .diagnostics
        .iter()
        .filter(|d| d.code == gcodec_source::codes::lower::BLOCK_TOO_LONG)
        .count();
    assert_eq!(too_long, 1, "{:?}", whole.diagnostics);
}

#[test]
fn the_generated_program_lowers_the_same_streamed() {
    let src = program::generate(3_000);
    let profile = gcodec_profile::builtin().unwrap();
    assert_streamed_agrees("bench.mpf", &src, &profile);
}

#[test]
fn flow_names_and_calls_across_chunks() {
    let profile = gcodec_profile::builtin().unwrap();
    let src = "DEF REAL AA, BB[3]\nDEFINE M_ON AS M3\nEXTERN SUB(REAL, VAR REAL)\nN10 G55 G0 X0\n\
               LBL: X1\nFOR R1=1 TO 3\nG1 X=R1 F100\nENDFOR\nIF AA>0 GOTOF END_LBL\nGOTOB LBL\n\
               WHILE AA<3\nAA=AA+1\nIF AA==2\nG2 X1 Y1 CR=5\nELSE\nX3\nENDIF\nENDWHILE\n\
               REPEAT LBL P=2\nSUB(1, AA)\nSUB(1, 2, 3)\nGOTOF N10\nLBL: X4\nEND_LBL: M30\n";
    assert_streamed_agrees("flow.mpf", src.as_bytes(), &profile);
    let computed = "R1=1\nGOTOF \"L\"<<R1\nL1: X1\nN20 X2\nL2: X3\nM30\n";
    assert_streamed_agrees("computed.mpf", computed.as_bytes(), &profile);
    let late = "G1 X1 F100\nDEF REAL LATE\nX2\nM30\nDEF INT OTHER\nPROC LAST\nX3\nM17\n";
    assert_streamed_agrees("late.mpf", late.as_bytes(), &profile);
    let procedure = "PROC SUB(REAL AA, VAR REAL BB)\nBB=AA*2\nG1 X=AA F100\nM17\n";
    assert_streamed_agrees("SUB.SPF", procedure.as_bytes(), &profile);
    let unclosed = "IF R1>0\nX1\nWHILE 1\nX2\n\nENDIF\nELSE\n";
    assert_streamed_agrees("unclosed.mpf", unclosed.as_bytes(), &profile);
    // State across chunk ends that parts cannot settle between them: a
    // modal call in force, `G34` reading `F`, an arc without circle data
    // under an inherited `G2`, an OEM motion command.
    let carried = "G55 G0 X0\nX1\nG53 X2\nG1 X3 F100\nMCALL CYCLE81(1,2,3)\nX4\nX5\nMCALL\n\
                   G34 Z-10 K2 F0.1\nZ-20 K2 F0.1\nG2 X1 Y1 CR=5\nX2 Y2\nX3 Y3 CR=5\nG0 X0\n\
                   /G1 X1\nX2\n/3 G56\nG53 X3\nM30\n";
    assert_streamed_agrees("carried.mpf", carried.as_bytes(), &profile);
}

/// An arc command other than `G2`/`G3` carried into a chunk (`INVCW`, an
/// involute, which needs no circle data) gives the motion its empty
/// circle data, as lowering under the known command does; so does one
/// the dataflow finds after a label (the fuzz target `lower_paths` found
/// the chunk's motion without it). A thread command (`G33`) likewise
/// gives its empty lead.
#[test]
fn an_arc_or_thread_command_carried_into_a_chunk_keeps_its_data() {
    let profile = gcodec_profile::builtin().unwrap();
    // Whether each motion of `src`, lowered whole, has `data`, once the
    // streamed lowering is checked to agree.
    let motions_with = |name: &str, src: &[u8], data: fn(&gcodec_ail::Op) -> bool| -> Vec<bool> {
        assert_streamed_agrees(name, src, &profile);
        let parsed = gcodec_parser::parse_bytes(name, src);
        let whole = lower_in_parts(&parsed.program, &profile, &Definitions::new(), 1);
        let instructions = whole.document.instructions.iter();
        instructions
            .filter(|i| matches!(i.op, gcodec_ail::Op::Motion { .. }))
            .map(|i| data(&i.op))
            .collect()
    };
    let circle = |op: &gcodec_ail::Op| {
        matches!(
            op,
            gcodec_ail::Op::Motion {
                circle: Some(_),
                ..
            }
        )
    };
    let arcs = b"INVCW\nZ0\nINVCCW X1\nY2\nCIP X3 I1=1 J1=1\nX4\nLBL: Z1\nGOTOB LBL\n";
    assert_eq!(motions_with("involute.mpf", arcs, circle), [true; 6]);
    let lead = |op: &gcodec_ail::Op| match op {
        gcodec_ail::Op::Motion { details, .. } => {
            details.as_ref().is_some_and(|d| d.thread.is_some())
        }
        _ => false,
    };
    let threads = b"G33 Z-0\nX03\nZ-5 K2\nLBL: X4\nGOTOB LBL\n";
    assert_eq!(motions_with("thread.mpf", threads, lead), [true; 4]);
}

#[test]
fn fixtures_and_corpus_lower_the_same_streamed() {
    let profile = gcodec_profile::builtin().unwrap();
    let all = common::all_programs();
    assert!(all.len() >= 30, "found only {} programs", all.len());
    for path in all {
        let bytes = std::fs::read(&path).unwrap();
        assert_streamed_agrees(&path.display().to_string(), &bytes, &profile);
    }
}

/// A chunk lowered on a worker goes back to that worker's bin when spent;
/// one lowered again where the parts are settled (a modal call in force
/// before it) has no bin, so the settling thread, which never frees its
/// own, does not hold chunk after chunk until pass 2 ends.
#[test]
fn only_chunks_lowered_on_a_worker_carry_a_bin() {
    let profile = gcodec_profile::builtin().unwrap();
    let definitions = Definitions::new();
    let src = b"G1 X1 F100\nMCALL CYCLE81(10,0,1,-5)\nX2\nX3\nX4\nMCALL\nX5\nX6\nX7\nM30\n";
    let chunks = chunks(src, 2);
    let file = SourceFile::new("mcall.mpf", *src);
    let (outline, _) = outline_chunks(&file, ProgramKind::Main, &chunks, 2, &profile, &definitions);
    let mut bins = Vec::new();
    lower_chunks(&file, &chunks, 2, &outline, &profile, |lowered| {
        bins.push(lowered.spent.is_some());
    });
    // Lines 3–4 and 5–6 follow a chunk that ends with `MCALL CYCLE81` in
    // force, so they are lowered again; the end has no bin.
    assert_eq!(bins, [true, false, false, true, true, false]);
}
