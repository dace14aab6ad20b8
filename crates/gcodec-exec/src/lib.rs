//! The executor: runs AIL the way a SINUMERIK channel would and emits
//! runtime events as they happen (SPEC §11).
//!
//! [`channel::Channel`] runs a [`program::Program`] with a machine profile,
//! a [`loader::ProgramLoader`] for the subprograms it calls, an
//! [`event::EventSink`] and a [`machine::Machine`] behind it; a
//! [`session::Session`] lets an application step the run and answer the
//! machine's pending actions. Its parts: runtime events and their sinks
//! ([`event`]), values, expressions and variables ([`value`], [`eval`],
//! [`vars`]), the budgets of work and memory a run draws on
//! ([`budget`]), circle geometry ([`geometry`]), programmable frames
//! ([`frames`]), and the toolchanger protocol with its simulated changer
//! ([`toolchanger`]).

pub mod budget;
pub mod channel;
pub mod eval;
pub mod event;
pub mod frames;
pub mod geometry;
pub mod loader;
pub mod machine;
pub mod path;
pub mod program;
pub mod tool_resolution;
pub mod toolchanger;
pub mod value;
pub mod vars;

pub use channel::session;
