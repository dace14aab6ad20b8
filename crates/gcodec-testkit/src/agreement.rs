//! What "the fast path agrees with the general one" means, checked in one
//! place for the tests and the fuzz targets (`fuzz/fuzz_targets/
//! lower_paths.rs`, `run_paths.rs`). Each check panics with the first
//! difference.
//!
//! - [`assert_direct_lowering_agrees`]: blocks of constant words
//!   (`G1 X… Y… F…`) lowered directly against the general path.
//! - [`assert_streamed_lowering_agrees`]: a streamed run's lowering, chunk
//!   by chunk, against lowering the whole program.
//! - [`assert_direct_motions_agree`]: the executor's direct path for
//!   straight motions against its general path, in a streamed run.

use std::io;
use std::sync::Arc;

use gcodec_ail::Document;
use gcodec_exec::event::{CsvWriter, Event, EventSink, JsonlSink};
use gcodec_profile::Profile;
use gcodec_sema::{
    ChunkLowering, Definitions, ProgramKind, lower_by_the_general_path, lower_chunks,
    lower_in_parts, outline_chunks, resolve_from_dataflow,
};
use gcodec_source::SourceFile;
use gcodec_stream::{Chunk, chunks};

/// Lowering `src` gives the same instructions and diagnostics, in the same
/// order, with the direct path for blocks of constant words as by the
/// general path alone.
pub fn assert_direct_lowering_agrees(name: &str, src: &[u8], profile: &Profile) {
    let parsed = gcodec_parser::parse_bytes(name, src);
    let definitions = Definitions::new();
    let direct = lower_in_parts(&parsed.program, profile, &definitions, 1);
    let general = lower_by_the_general_path(&parsed.program, profile, &definitions);
    assert_eq!(
        direct.diagnostics, general.diagnostics,
        "{name}: diagnostics differ"
    );
    assert!(
        direct.document == general.document,
        "{name}: instructions differ\n{}",
        first_different_instruction(("direct", &direct.document), ("general", &general.document))
    );
}

/// The first instruction that differs, both ways, each under its name,
/// for the message.
fn first_different_instruction(
    (a_name, a): (&str, &Document),
    (b_name, b): (&str, &Document),
) -> String {
    let json = |d: &Document, i: usize| {
        d.instructions.get(i).map_or("(none)".to_owned(), |x| {
            serde_json::to_string(x).unwrap_or_else(|e| e.to_string())
        })
    };
    let n = a.instructions.len().max(b.instructions.len());
    (0..n)
        .find(|&i| a.instructions.get(i) != b.instructions.get(i))
        .map_or("(same instructions)".to_owned(), |i| {
            format!("#{i}\n {a_name}: {}\n {b_name}: {}", json(a, i), json(b, i))
        })
}

/// A streamed run's lowering of `src` agrees with lowering the whole
/// program, in chunks of each of `chunk_lines` lines on each of `workers`
/// threads: pass 1 outlines the chunks, pass 2 lowers them, and the
/// chunks' instructions, once the dataflow fills them in, are the whole
/// program's, their diagnostics its diagnostics and their parse
/// diagnostics its parse's. The chunks lowered in order by one
/// [`ChunkLowering`] give the same instructions as the workers before the
/// dataflow.
pub fn assert_streamed_lowering_agrees(
    name: &str,
    src: &[u8],
    profile: &Profile,
    chunk_lines: &[usize],
    workers: &[usize],
) {
    let parsed = gcodec_parser::parse_bytes(name, src);
    let file = SourceFile::new(name, src);
    let definitions = Definitions::new();
    let whole = lower_in_parts(&parsed.program, profile, &definitions, 1);
    for &lines in chunk_lines {
        let chunks = chunks(src, lines);
        let in_order = lowered_in_order(&file, src, &chunks, profile, &definitions);
        for &workers in workers {
            // Pass 1: the outline, the chunks skimmed and their trees
            // dropped chunk by chunk.
            let (outline, structure_diagnostics) = outline_chunks(
                &file,
                ProgramKind::of_file(name),
                &chunks,
                workers,
                profile,
                &definitions,
            );
            let mut diagnostics = outline.diagnostics().to_vec();
            // Pass 2: the chunks parsed and lowered, then the end.
            let mut document = Document::new();
            let mut parse_diagnostics = Vec::new();
            let mut taken = 0;
            lower_chunks(&file, &chunks, workers, &outline, profile, |mut lowered| {
                taken += 1;
                document.instructions.append(&mut lowered.instructions);
                diagnostics.extend(lowered.diagnostics);
                parse_diagnostics.extend(lowered.parse_diagnostics);
            });
            let place = format!("{name}, chunks of {lines}, {workers} workers");
            assert_eq!(taken, chunks.len() + 1, "{place}: chunks in order");
            parse_diagnostics.extend(structure_diagnostics);
            parse_diagnostics.sort_by_key(|d| d.span().map_or(0, |s| s.start));
            assert_eq!(
                parsed.diagnostics[..],
                parse_diagnostics,
                "{place}: parse diagnostics differ"
            );
            assert!(
                in_order == document,
                "{place}: instructions differ from lowering in order\n{}",
                first_different_instruction(("workers", &document), ("in order", &in_order))
            );
            resolve_from_dataflow(&mut document, profile, outline.is_subprogram());
            assert_eq!(
                whole.diagnostics[..],
                diagnostics,
                "{place}: diagnostics differ"
            );
            assert!(
                whole.document == document,
                "{place}: instructions differ\n{}",
                first_different_instruction(("streamed", &document), ("whole", &whole.document))
            );
        }
    }
}

/// The instructions of `chunks` lowered in order by one [`ChunkLowering`].
fn lowered_in_order(
    file: &SourceFile,
    src: &[u8],
    chunks: &[Chunk],
    profile: &Profile,
    definitions: &Definitions,
) -> Document {
    let (outline, _) = outline_chunks(
        file,
        ProgramKind::of_file(file.name()),
        chunks,
        1,
        profile,
        definitions,
    );
    let mut lowering = ChunkLowering::new(&outline, profile, src);
    let mut document = Document::new();
    for chunk in chunks {
        let parsed = gcodec_parser::parse_chunk(src, file.encoding(), chunk, definitions.macros());
        let mut lowered = lowering
            .lower(parsed.first_block, &parsed.blocks)
            .expect("chunks are given in order");
        document.instructions.append(&mut lowered.instructions);
    }
    document
        .instructions
        .append(&mut lowering.finish().instructions);
    document
}

/// Every event but the motions, as JSONL: what a CSV run writes besides
/// its rows.
struct AllButMotions(JsonlSink<Vec<u8>>);

impl EventSink for AllButMotions {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.0.event(event)
    }

    fn takes_motions(&self) -> bool {
        false
    }
}

/// A streamed run of `src` (`gcodec run`'s way, at most `max_steps`
/// blocks, going on after `M0`) gives the same JSONL, the same CSV rows,
/// the same events beside the rows and the same outcome, byte for byte,
/// with the executor's direct path for straight motions as with its
/// general path alone (`RunOptions::direct_motions` off).
pub fn assert_direct_motions_agree(name: &str, src: &[u8], profile: &Arc<Profile>, max_steps: u64) {
    let file = Arc::new(SourceFile::new(name, src));
    let (direct_events, direct_csv) = run_outputs(profile, &file, max_steps, true);
    let (general_events, general_csv) = run_outputs(profile, &file, max_steps, false);
    for (what, direct, general) in [
        ("events", &direct_events, &general_events),
        ("CSV", &direct_csv, &general_csv),
    ] {
        if direct == general {
            continue;
        }
        let (line, (a, b)) = direct
            .lines()
            .zip(general.lines())
            .enumerate()
            .find(|(_, (a, b))| a != b)
            .unwrap_or((0, ("(a line more or less)", "")));
        // A generated program is shown whole: it is in no file.
        let shown = if src.len() < 4096 {
            String::from_utf8_lossy(src)
        } else {
            "".into()
        };
        panic!(
            "{name}: the {what} differ at line {}\n direct:  {a}\n general: {b}\n{shown}",
            line + 1
        );
    }
}

/// A streamed run's JSONL, and its CSV with the events beside it, as
/// text, each with the outcome; the direct path for straight motions on
/// if `direct`.
pub fn run_outputs(
    profile: &Arc<Profile>,
    file: &Arc<SourceFile>,
    max_steps: u64,
    direct: bool,
) -> (String, String) {
    let mut setup = gcodec_driver::RunSetup::new(Arc::clone(profile));
    setup.options.max_steps = max_steps;
    setup.options.stop_at_m0 = false;
    setup.options.direct_motions = direct;
    let mut jsonl = JsonlSink::new(Vec::new());
    let report = gcodec_driver::run_main(Arc::clone(file), &setup, &mut jsonl, None);
    let events = format!(
        "{}{:?}",
        String::from_utf8_lossy(&jsonl.into_inner().expect("written to memory")),
        report.outcome.map_err(|e| e.to_string())
    );
    let mut rows = CsvWriter::for_profile(Vec::new(), profile).expect("written to memory");
    let mut others = AllButMotions(JsonlSink::new(Vec::new()));
    let report = gcodec_driver::run_main(Arc::clone(file), &setup, &mut others, Some(&mut rows));
    rows.finish().expect("written to memory");
    let csv = format!(
        "{}{}{:?}",
        String::from_utf8_lossy(&rows.into_inner().expect("written to memory")),
        String::from_utf8_lossy(&others.0.into_inner().expect("written to memory")),
        report.outcome.map_err(|e| e.to_string())
    );
    (events, csv)
}
