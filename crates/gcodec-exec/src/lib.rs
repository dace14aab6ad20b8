//! The executor — **not built yet** (the executor issue fills this crate).
//! Nothing here has behaviour; this page is the documented outline.
//!
//! # Planned API
//!
//! - `Executor::new(profile, runtime: impl RuntimeInterface)` running AIL the
//!   way a SINUMERIK channel would: modal state, positions in workpiece and
//!   machine coordinates, work offsets and programmable frames, feed,
//!   spindle, tools, M-function timing, variables, control flow, subprogram
//!   calls up to 16 levels, skip levels, step and call-depth limits.
//! - An `EventSink` trait receiving runtime events as they happen (`motion`,
//!   `modal_change`, `m_function`, `tool_select`, `tool_change`, `spindle`,
//!   `dwell`, `message`, `call`, `return`, `stop`, `program_end`,
//!   `diagnostic`), each with its source file, line, column and program
//!   level; memory does not grow with program length or iteration count.
