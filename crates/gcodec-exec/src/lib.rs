//! The executor: runs AIL the way a SINUMERIK channel would and emits
//! runtime events as they happen.
//!
//! Built so far (issue 4 in progress): the runtime events and their sinks
//! ([`event`]), values, expressions and variables ([`value`], [`eval`],
//! [`vars`]), and circle geometry ([`geometry`]). Not built yet: the
//! channel itself (modal state, positions, frames, control flow, calls)
//! and `gcodec run`.

pub mod channel;
pub mod eval;
pub mod event;
pub mod frames;
pub mod geometry;
pub mod loader;
pub mod program;
pub mod value;
pub mod vars;
