//! The SINUMERIK vocabulary: the names and closed sets of the NC language
//! that every stage shares, defined once.
//!
//! The G groups and their commands ([`ggroups`]), the standard classes of
//! M functions ([`mfunctions`]), the group count of the modal state
//! ([`modal`]), the data types ([`types`]), the operators
//! ([`operators`]), the dimension modes ([`dimension`]), the motion a
//! group 1 command makes ([`motion`]), the address letters and named
//! addresses ([`addresses`]), the frame instructions ([`frames`]), the system
//! variables ([`sysvars`]), the built-in functions ([`functions`]), the
//! predefined procedures ([`procedures`]), the keywords ([`keywords`]) and
//! the Group 8 work offsets ([`work_offsets`]). The tests check every table against the
//! control's catalogue of names (`tests/catalogue.rs`). The syntax tree,
//! the semantic stage, the AIL and the executor use these types, so no
//! boundary converts one spelling of a word into another.
//!
//! Depends on no other gcodec crate: it sits below the profile and the AIL.

pub mod addresses;
pub mod dimension;
pub mod frames;
pub mod functions;
pub mod ggroups;
pub mod interrupts;
pub mod keywords;
pub mod mfunctions;
pub mod modal;
pub mod motion;
mod names;
pub mod operators;
pub mod procedures;
pub mod sysvars;
pub mod types;
pub mod work_offsets;

pub use dimension::DimensionMode;
pub use frames::FrameOp;
pub use mfunctions::MClass;
pub use motion::MotionKind;
pub use operators::{BinaryOp, UnaryOp};
pub use types::DataType;
pub use work_offsets::WorkOffsetCode;
