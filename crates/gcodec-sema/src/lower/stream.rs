//! Lowering a program a chunk of blocks at a time, in order, against its
//! [`Outline`]: what a streamed run needs, which never holds the syntax
//! tree or the instructions of the whole program.
//!
//! The chunks' instructions, one after the other, followed by
//! [`ChunkLowering::finish`]'s end, are the instructions lowering the whole
//! program in one part gives, before what the dataflow fills in
//! (`resolve_from_dataflow`): a motion after a join says `modal`, which
//! the executor resolves from its own state. A test checks this for every fixture and corpus program.
//! [`lower_chunks`] is pass 2 of a streamed run, after
//! [`super::outline::outline_chunks`].

use std::sync::Arc;

use gcodec_ail::Instruction;
use gcodec_parser::ast::Block;
use gcodec_parser::{Macros, WordLine};
use gcodec_profile::Profile;
use gcodec_source::{Diagnostics, Encoding, SourceFile};

use super::outline::Outline;
use super::parts::{Entry, PartLedger};
use super::{Lowering, capacity};
use gcodec_stream::SpentBin;

/// Lowers the program in `file` chunk by chunk against its `outline` (pass 2
/// of a streamed run); `each` takes the instructions of every chunk, then
/// those of the program's end. `chunks` are consecutive from the first
/// block, as [`gcodec_stream::chunks`] cuts them: a chunk out of order is
/// left out. Each chunk comes with its parse diagnostics, which pass 1,
/// skimming, did not find.
///
/// Each of `workers` threads, scheduled below this one and the run
/// ([`gcodec_stream::WorkerPriority::Background`]), parses and lowers its
/// chunks ([`gcodec_stream::map_chunks`]; on one, this thread), each as a part
/// that starts in the state the chunk before it ends in, as
/// [`super::lower_in_parts`] lowers its parts; the part ledger takes
/// them here in order, and a part it cannot fill in is lowered again
/// here, continuing from the chunk before. So a chunk's
/// tree is lowered on the core that parsed it, and the instructions are
/// those a [`ChunkLowering`] gives.
pub fn lower_chunks(
    file: &SourceFile,
    chunks: &[gcodec_stream::Chunk],
    workers: usize,
    outline: &Outline<'_>,
    profile: &Profile,
    mut each: impl FnMut(LoweredChunk),
) {
    let src = file.bytes();
    // Parses `chunk` and lowers it with `lowering`; gives its parse
    // diagnostics.
    let lines = ChunkLines {
        src,
        encoding: file.encoding(),
        macros: outline.macros(),
    };
    let lower_part = |chunk: &gcodec_stream::Chunk, lowering: &mut Lowering<'_>| {
        if lines.macros.is_empty() {
            lines.lower(chunk, lowering)
        } else {
            // A macro may stand for any word: every line is parsed.
            lines.parse_and_lower(chunk.clone(), lowering, false)
        }
    };
    let mut next = 0;
    let mut ledger = PartLedger::default();
    gcodec_stream::map_chunks(
        chunks,
        workers,
        // The run (or `lower`'s writer) takes what this pass makes, in
        // order, and is the critical path: the workers fill the cores it
        // leaves rather than share its core.
        gcodec_stream::WorkerPriority::Background,
        |chunk| {
            // What the run is done with is freed here, where it was
            // allocated (see `spent.rs`).
            SpentBin::free_this_threads();
            let entry = if chunk.first_block > 0 {
                Entry::AfterOpenPart
            } else {
                Entry::ProgramStart
            };
            let mut lowering = Lowering::new(outline, profile, src, 0, entry);
            let parse_diagnostics = lower_part(chunk, &mut lowering);
            let spent = Some(SpentBin::of_this_thread());
            (chunk, lowering, parse_diagnostics, spent)
        },
        |(chunk, mut lowering, mut parse_diagnostics, mut spent)| {
            if chunk.first_block != next {
                return;
            }
            next = chunk.first_block + chunk.blocks;
            if !ledger.take(&mut lowering) {
                lowering = Lowering::new(outline, profile, src, 0, ledger.entry());
                parse_diagnostics = lower_part(chunk, &mut lowering);
                // Lowered on this thread, which frees its bin only when it
                // works a chunk itself: the run frees these.
                spent = None;
                // Lowered from a known state: nothing is left open.
                ledger.take(&mut lowering);
            }
            each(LoweredChunk {
                instructions: lowering.document.instructions,
                diagnostics: lowering.diagnostics,
                parse_diagnostics,
                spent,
            });
        },
    );
    let mut end = Lowering::new(outline, profile, src, 0, Entry::ProgramStart);
    end.end();
    each(LoweredChunk {
        instructions: end.document.instructions,
        diagnostics: end.diagnostics,
        parse_diagnostics: Diagnostics::new(),
        spent: None,
    });
}

/// A chunk's lines are lowered from their words while runs of other
/// lines come at most once in this many lines; past that, the rest of the
/// chunk is parsed and lowered block by block.
const LINES_A_RUN: usize = 32;

/// Where a line starts: its first byte and its block.
#[derive(Clone, Copy)]
struct LinePlace {
    byte: usize,
    block: usize,
}

impl LinePlace {
    /// The lines from this one up to `end` (not included), as a chunk.
    fn lines_to(self, end: LinePlace) -> gcodec_stream::Chunk {
        gcodec_stream::Chunk {
            bytes: self.byte..end.byte,
            first_block: self.block,
            blocks: end.block - self.block,
        }
    }
}

/// The lines of a program's chunks, parsed and lowered.
struct ChunkLines<'a> {
    src: &'a [u8],
    encoding: Encoding,
    macros: &'a Macros,
}

impl ChunkLines<'_> {
    /// Lowers the lines of `chunk` with no macros in force, and gives
    /// their parse diagnostics. A line of constant words is lowered
    /// straight from its bytes where lowering takes it so (most lines of
    /// large programs: building, lowering and dropping their blocks was
    /// half of a worker's time); its block, read from the same bytes,
    /// where not. The other lines are parsed a run at a time, as
    /// [`gcodec_parser::parse_chunk`] parses them; where such runs come
    /// often ([`LINES_A_RUN`]), the rest of the chunk is parsed so.
    fn lower(&self, chunk: &gcodec_stream::Chunk, lowering: &mut Lowering<'_>) -> Diagnostics {
        // Room for a motion's three instructions a line, at once.
        let reserve = capacity(chunk.blocks * 12 / 5);
        lowering.document.instructions.reserve(reserve);
        let mut diagnostics = Diagnostics::new();
        let mut line = WordLine::default();
        // Where the lines not read as words since the last that was start.
        let mut unread: Option<LinePlace> = None;
        let mut runs = 0;
        let chunk_end = LinePlace {
            byte: chunk.bytes.end,
            block: chunk.first_block + chunk.blocks,
        };
        let lines = gcodec_parser::lines_of(self.src, chunk.bytes.clone());
        for (index, (start, text_end, _)) in (chunk.first_block..).zip(lines) {
            let here = LinePlace {
                byte: start,
                block: index,
            };
            if line.read(self.src, start, text_end) {
                if let Some(from) = unread.take() {
                    let run = from.lines_to(here);
                    diagnostics.append(self.parse_and_lower(run, lowering, true));
                }
                if !lowering.word_line(index, &line) {
                    lowering.block(index, &line.block());
                }
            } else if unread.is_none() {
                if runs * LINES_A_RUN > index - chunk.first_block {
                    // Word lines and others mixed (comments, assignments,
                    // structures): parsed and lowered a run of a line or
                    // two at a time, the two paths' code took turns on the
                    // core and ran slower than the blocks of all lines in
                    // turn (a tenth more time on the generated program
                    // for the same instructions).
                    let rest = here.lines_to(chunk_end);
                    diagnostics.append(self.parse_and_lower(rest, lowering, false));
                    return diagnostics;
                }
                runs += 1;
                unread = Some(here);
            }
        }
        if let Some(from) = unread {
            diagnostics.append(self.parse_and_lower(from.lines_to(chunk_end), lowering, true));
        }
        diagnostics
    }

    /// Parses the lines of `run` and lowers their blocks; gives their
    /// parse diagnostics. `lexed`: none of the lines is a word line.
    fn parse_and_lower(
        &self,
        run: gcodec_stream::Chunk,
        lowering: &mut Lowering<'_>,
        lexed: bool,
    ) -> Diagnostics {
        let parse = if lexed {
            gcodec_parser::parse_chunk_of_lexed_lines
        } else {
            gcodec_parser::parse_chunk
        };
        let parsed = parse(self.src, self.encoding, &run, self.macros);
        lower_blocks(lowering, parsed.first_block, &parsed.blocks);
        parsed.diagnostics
    }
}

/// Lowers `blocks`, the program's blocks from index `first` on, with
/// room made for their instructions at once.
fn lower_blocks(lowering: &mut Lowering<'_>, first: usize, blocks: &[Block]) {
    let statements: usize = blocks.iter().map(|b| b.statements.len()).sum();
    lowering.document.instructions.reserve(capacity(statements));
    for (offset, block) in blocks.iter().enumerate() {
        lowering.block(first + offset, block);
    }
}

/// A lowering fed with the blocks of a program in order.
pub struct ChunkLowering<'a> {
    lowering: Lowering<'a>,
    /// The next block expected.
    next: usize,
}

/// The instructions of one chunk and what was wrong in it.
#[derive(Debug, Default)]
pub struct LoweredChunk {
    pub instructions: Vec<Instruction>,
    /// What lowering found wrong.
    pub diagnostics: Diagnostics,
    /// The chunk's lexical and syntax errors ([`lower_chunks`] only: a
    /// [`ChunkLowering`] is given parsed blocks).
    pub parse_diagnostics: Diagnostics,
    /// Where to give the instructions back when done with them: the bin
    /// of the worker that allocated them ([`lower_chunks`] only; not for
    /// a chunk lowered again on the thread that settles the parts, which
    /// would hold them until pass 2 ends).
    pub spent: Option<SpentBin>,
}

impl<'a> ChunkLowering<'a> {
    /// Lowers the program `src` that `outline` describes for the machine
    /// `profile` describes.
    pub fn new(outline: &'a Outline<'a>, profile: &'a Profile, src: &'a [u8]) -> Self {
        let lowering = Lowering::new(outline, profile, src, 0, Entry::ProgramStart);
        Self { lowering, next: 0 }
    }

    /// Lowers `blocks`, the program's blocks from index `first` on, which
    /// must follow the blocks lowered before (else nothing is lowered and
    /// `None` is returned).
    pub fn lower(&mut self, first: usize, blocks: &[Block]) -> Option<LoweredChunk> {
        if first != self.next {
            return None;
        }
        // The chunk's own copy of the file name (see `Lowering::file`).
        self.lowering.file = Arc::from(&*self.lowering.outline.file);
        lower_blocks(&mut self.lowering, first, blocks);
        self.next = first + blocks.len();
        Some(self.take())
    }

    /// The program's end instruction, after the last chunk.
    pub fn finish(mut self) -> LoweredChunk {
        self.lowering.end();
        self.take()
    }

    /// What was lowered since the last take.
    fn take(&mut self) -> LoweredChunk {
        LoweredChunk {
            instructions: std::mem::take(&mut self.lowering.document.instructions),
            diagnostics: std::mem::take(&mut self.lowering.diagnostics),
            parse_diagnostics: Diagnostics::new(),
            spent: None,
        }
    }
}
