//! The machinery of a streamed run, in one place below every stage that
//! streams (the parser, lowering and the executor's pages):
//!
//! - [`Chunk`], [`chunks`], [`chunks_at`]: a source cut into runs of
//!   whole lines, the unit a streamed run parses, lowers and runs at a
//!   time;
//! - [`map_chunks`]: the ordered worker pipeline both passes of a
//!   streamed run go through, its workers at a [`WorkerPriority`];
//! - [`SpentBin`]: what the run is done with, freed on the thread that
//!   allocated it.

mod chunk;
mod pipeline;
mod priority;
mod spent;

pub use chunk::{Chunk, chunks, chunks_at};
pub use pipeline::map_chunks;
pub use priority::{BACKGROUND_NICE, WorkerPriority};
pub use spent::SpentBin;
