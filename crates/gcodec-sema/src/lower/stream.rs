//! Lowering a program a chunk of blocks at a time, in order, against its
//! [`Outline`]: what a streamed run needs, which never holds the syntax
//! tree or the instructions of the whole program.
//!
//! The chunks' instructions, one after the other, followed by
//! [`ChunkLowering::finish`]'s end, are the instructions lowering the whole
//! program in one part gives, before the modal refinement (`refine`): a
//! motion after a join says `modal`, which the executor settles from its
//! own state. A test checks this for every fixture and corpus program.

use gcodec_ail::Instruction;
use gcodec_parser::ast::Block;
use gcodec_profile::Profile;
use gcodec_source::Diagnostic;

use super::Lowering;
use super::outline::Outline;

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
    pub diagnostics: Vec<Diagnostic>,
}

impl<'a> ChunkLowering<'a> {
    /// Lowers the program `outline` describes for the machine `profile`
    /// describes.
    pub fn new(outline: &'a Outline<'a>, profile: &'a Profile) -> Self {
        let mut lowering = Lowering::new(outline, profile, 0, false);
        if outline.subprogram {
            // A subprogram starts in its caller's state.
            lowering.forget_modal_state();
        }
        Self { lowering, next: 0 }
    }

    /// Lowers `blocks`, the program's blocks from index `first` on, which
    /// must follow the blocks lowered before (else nothing is lowered and
    /// `None` is returned).
    pub fn lower(&mut self, first: usize, blocks: &[Block]) -> Option<LoweredChunk> {
        if first != self.next {
            return None;
        }
        let statements: usize = blocks.iter().map(|b| b.statements.len()).sum();
        self.lowering
            .document
            .instructions
            .reserve(statements * 5 / 4 + 16);
        for (offset, block) in blocks.iter().enumerate() {
            self.lowering.block(first + offset, block);
        }
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
        }
    }
}
