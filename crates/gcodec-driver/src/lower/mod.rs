//! `gcodec lower` streamed: a program's instructions are handed on as
//! they are made, chunk by chunk, and neither its syntax tree nor (where
//! the whole-program analysis is not needed) all its instructions are
//! ever held (docs/ARCHITECTURE.md, "Streaming").
//!
//! The two passes are those of a streamed run ([`crate::stream`]): pass
//! 1 outlines the program, pass 2 lowers it chunk by chunk against the
//! outline. The chunks' instructions, one after the other, are those of
//! lowering the whole program ([`crate::compile`]) but for what the
//! dataflow over the whole document fills in
//! ([`gcodec_sema::resolve_from_dataflow`]): a motion after a join whose
//! command is not known there (`motion: modal`), a work offset whose
//! Group 8 selection is not (`group8_selected: null`). Those are the only
//! instructions that analysis changes, so everything before the first of
//! them is final when it is made and is handed on at once. From the first
//! of them on, the instructions are held to the end; then the chunks
//! before it are lowered again for the analysis, which needs the whole
//! document, and the rest is handed on filled in. A program without such
//! an instruction (straight-line code, and any program whose every
//! motion after a join names its command) is streamed whole.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

use gcodec_ail::{AIL_VERSION, Document, Instruction, Op};
use gcodec_lang::MotionKind;
use gcodec_profile::Profile;
use gcodec_sema::{
    Definitions, LoweredChunk, Outline, ProgramKind, lower_chunks, outline_chunks,
    resolve_from_dataflow,
};
use gcodec_source::{Diagnostics, SourceFile};
use gcodec_stream::{Chunk, SpentBin, chunks_at};

use crate::stream::StreamOptions;

mod hot_json;
mod json;
mod listing;
mod rendered;

pub use json::write_json;
pub use listing::write_listing;

/// Pages the channel holds before pass 2 waits for the writer.
const PAGES_AHEAD: usize = 2;

/// Instructions a page of the held rest of a program holds: about those
/// of a chunk of the straight-line programs measured.
const HELD_PAGE: usize = 4096;

/// Instructions handed on in order: those of one chunk, or the held rest
/// of the program filled in from the dataflow. Dropped, a chunk's page
/// goes back to the worker that lowered it, to be freed there.
#[derive(Debug, Default)]
pub struct Page {
    instructions: Vec<Instruction>,
    spent: Option<SpentBin>,
}

impl Page {
    /// The page's instructions.
    pub fn instructions(&self) -> &[Instruction] {
        &self.instructions
    }
}

impl Drop for Page {
    fn drop(&mut self) {
        if let Some(bin) = self.spent.take() {
            bin.give_back(std::mem::take(&mut self.instructions));
        }
    }
}

/// The pages of a streamed lowering, in order, as pass 2 makes them.
pub struct Pages {
    receiver: Receiver<Page>,
}

impl Iterator for Pages {
    type Item = Page;

    fn next(&mut self) -> Option<Page> {
        self.receiver.recv().ok()
    }
}

/// Lowers the program in `file` (started as `kind`) streamed: `write`
/// gets its pages while pass 2 still lowers it, and returns what
/// `lower_streamed` returns with all the program's diagnostics (parse,
/// structure, outline, lowering) in source order, those
/// [`crate::compile`] gives. The pages are the instructions of
/// [`crate::compile`]'s document, in order. If `write` stops taking
/// pages (its output failed), lowering goes on for the diagnostics.
pub fn lower_streamed<R>(
    file: &Arc<SourceFile>,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
    options: StreamOptions,
    write: impl FnOnce(&mut Pages) -> R,
) -> (R, Diagnostics) {
    let src = file.bytes();
    let chunks = chunks_at(file.line_starts(), src.len(), options.page_lines);
    let (outline, structure_diagnostics) =
        outline_chunks(file, kind, &chunks, options.workers, profile, definitions);
    let (sender, receiver) = sync_channel::<Page>(PAGES_AHEAD);
    let (written, lowered) = std::thread::scope(|scope| {
        let pass2 = scope.spawn(|| {
            let mut pass2 = Pass2 {
                sender: Some(sender),
                parse_diagnostics: Diagnostics::new(),
                diagnostics: Diagnostics::new(),
                handed_on: 0,
                chunks_taken: 0,
                chunks: chunks.len(),
                held: None,
            };
            lower_chunks(
                file,
                &chunks,
                options.workers,
                &outline,
                profile,
                |lowered| pass2.lowered(lowered),
            );
            pass2.finish(file, &chunks, options.workers, &outline, profile)
        });
        let mut pages = Pages { receiver };
        let written = write(&mut pages);
        // Pass 2 must not wait for a writer that has stopped.
        drop(pages);
        let lowered = pass2
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (written, lowered)
    });
    // In the order `compile` gives them, as a streamed run orders them.
    let (parse_diagnostics, lowering_diagnostics) = lowered;
    let diagnostics = crate::stream::in_program_order(
        src,
        definitions,
        structure_diagnostics,
        outline.diagnostics(),
        parse_diagnostics,
        lowering_diagnostics,
    );
    (written, diagnostics)
}

/// An instruction the dataflow over the whole document may fill in
/// (what [`resolve_from_dataflow`] looks for).
fn is_open(instruction: &Instruction) -> bool {
    match &instruction.op {
        Op::Motion { motion, .. } => *motion == MotionKind::Modal,
        Op::WorkOffset {
            group8_selected, ..
        } => group8_selected.is_none(),
        _ => false,
    }
}

/// Pass 2's side: pages handed on, or held from the first open
/// instruction on, and the diagnostics gathered.
struct Pass2 {
    sender: Option<SyncSender<Page>>,
    parse_diagnostics: Diagnostics,
    diagnostics: Diagnostics,
    /// Instructions handed on so far: the index of the next.
    handed_on: usize,
    /// Lowered chunks taken so far.
    chunks_taken: usize,
    /// The chunks of the program.
    chunks: usize,
    held: Option<Held>,
}

/// The instructions from the first open one on, held for the analysis.
struct Held {
    /// The chunks to lower again for the instructions before them: those
    /// up to the one with the first open instruction.
    chunks_before: usize,
    instructions: Vec<Instruction>,
}

impl Pass2 {
    fn lowered(&mut self, chunk: LoweredChunk) {
        self.parse_diagnostics.append(chunk.parse_diagnostics);
        self.diagnostics.append(chunk.diagnostics);
        self.chunks_taken += 1;
        let mut instructions = chunk.instructions;
        if let Some(held) = &mut self.held {
            held.instructions.append(&mut instructions);
            if let Some(bin) = chunk.spent {
                bin.give_back(instructions);
            }
            return;
        }
        if let Some(open) = instructions.iter().position(is_open) {
            // Room for the rest of the program, at the rate of the chunks
            // so far, and for the instructions before it, which are put
            // in front at the end: growing a vector of most of the
            // program copies it. Room not filled takes no memory.
            let per_chunk = (self.handed_on + instructions.len()).div_ceil(self.chunks_taken);
            let to_come = (self.chunks - self.chunks_taken.min(self.chunks) + 1) * per_chunk;
            let room = self.handed_on + open + to_come + to_come / 2;
            let mut held = Vec::with_capacity(room);
            held.extend(instructions.drain(open..));
            self.held = Some(Held {
                chunks_before: self.chunks_taken,
                instructions: held,
            });
        }
        self.hand_on(Page {
            instructions,
            spent: chunk.spent,
        });
    }

    fn hand_on(&mut self, page: Page) {
        self.handed_on += page.instructions.len();
        if let Some(sender) = &self.sender
            && sender.send(page).is_err()
        {
            // The writer has stopped: lowering goes on for the diagnostics.
            self.sender = None;
        }
    }

    /// Hands on what is held, filled in from the dataflow over the
    /// whole document, whose first instructions are lowered again for
    /// it; gives the parse and the lowering diagnostics.
    fn finish(
        mut self,
        file: &SourceFile,
        chunks: &[Chunk],
        workers: usize,
        outline: &Outline<'_>,
        profile: &Profile,
    ) -> (Diagnostics, Diagnostics) {
        if let Some(held) = self.held.take() {
            let before = self.handed_on;
            let mut first = Vec::with_capacity(before);
            // The program's end comes after these chunks: it is left out
            // with whatever else passes `before`.
            let again = &chunks[..held.chunks_before.min(chunks.len())];
            lower_chunks(file, again, workers, outline, profile, |lowered| {
                let wanted = before.saturating_sub(first.len());
                first.extend(lowered.instructions.into_iter().take(wanted));
            });
            // In front of the held ones, in the room kept for them.
            let mut instructions = held.instructions;
            instructions.splice(0..0, first);
            let mut document = Document {
                ail_version: AIL_VERSION,
                instructions,
            };
            resolve_from_dataflow(&mut document, profile, outline.is_subprogram());
            // Handed on in pages, so that the writer renders a page at a
            // time, not the rest of the program at once.
            let mut rest = document.instructions.into_iter().skip(before);
            loop {
                let page: Vec<Instruction> = rest.by_ref().take(HELD_PAGE).collect();
                if page.is_empty() {
                    break;
                }
                self.hand_on(Page {
                    instructions: page,
                    spent: None,
                });
            }
        }
        (self.parse_diagnostics, self.diagnostics)
    }
}
