//! The semantic stage: checks a parsed program against a machine profile
//! and lowers it to AIL ([`lower`]).
//!
//! Built on the vocabulary of `gcodec_lang` (the 64 G groups of the language
//! reference §3.2, M classes, data types, operators, the system variables with
//! their index shapes: an unknown `$` name is an error, as on the control):
//! lowering of G commands (unknown commands, two of one group, Group 8 against
//! the profile's offsets, G53/G153/SUPA with the duplicate policy), M
//! functions, tool selection and cutting edges, feed, spindle speeds (spindle
//! numbers against the profile), axis words (axes from the profile), motion
//! with circle data, assignments, declarations, `MSG` and `STOPRE`, calls by
//! name and number, `RET`, frame instructions, control structures and jumps,
//! and the block-length limit; variables ([`definitions`], [`types`]): names
//! must be defined (`DEF`, `PROC` parameters, global user data of definition
//! files, macros, axes), assignments are type-checked, array indices and
//! system-variable index shapes are checked, `REP` and lists of values are
//! lowered; the checks of a machine profile that need the G-group registry
//! ([`check_profile`]: `modal_defaults`, `[g_codes]` names, `legacy_aliases`
//! keys).
//!
//! Control flow (`IF` … `CASE`, jumps, `REPEAT` sections, skip marks), calls
//! (`CALL`, `PCALL`, `MCALL`, `PROC`/`EXTERN` signatures and arity) and the
//! modal state at every block ([`modal`]) are lowered too.
//!
//! Not lowered (SPEC §10.13): synchronized actions, `PO[…]`, `OEMIPO`, a
//! computed G group, macro expansion, `REDEF` attributes. Each such
//! construct gives the warning `gcodec::lower::not_lowered` rather than
//! being dropped in silence.

pub mod definitions;
mod flow;
pub mod lint;
mod lower;
mod mfunc;
pub mod modal;
mod policy;
mod profile_check;
mod tools;
pub mod types;
mod values;

pub use definitions::Definitions;
pub use lower::outline::{Outline, OutlineBuilder, ProgramKind, outline, outline_chunks};
pub use lower::stream::{ChunkLowering, LoweredChunk, lower_chunks};
pub use lower::{
    Lowered, lower, lower_by_the_general_path, lower_in_parts, lower_program, lower_with,
    resolve_from_dataflow,
};
pub use profile_check::check_profile;
