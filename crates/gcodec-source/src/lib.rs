//! Source files, spans and diagnostics shared by every gcodec stage.
//!
//! Part programs are bytes, not text: SINUMERIK archives carry comments in
//! Latin-1, CP1252 or CP1251. Every span in gcodec is therefore a byte range
//! into the file as stored (after a UTF-8 byte-order mark); its 1-based line and byte column come from the
//! file's line table, and JSON dumps write them next to the offsets so that
//! a consumer never has to re-read the file to point at a construct.

mod bytes;
pub mod codes;
mod diagnostic;
mod encoding;
mod escape;
mod excerpt;
mod kept;
mod lines;
mod nearest;
mod read;
mod render;
mod source;
mod span;

pub use bytes::SourceBytes;
pub use codes::Code;
pub use diagnostic::{Diagnostic, Label, Severity};
pub use encoding::{Encoding, TextEncoding};
pub use escape::{EscapeControls, escape_controls, is_escaped};
pub use kept::{Diagnostics, MAX_KEPT_PER_BLOCK, MAX_KEPT_PER_FILE, Omitted};
pub use lines::{MAX_SOURCE_LEN, line_starts};
pub use nearest::nearest;
pub use read::{DEFAULT_MAX_FILE_SIZE, ReadError, UTF8_BOM};
pub use render::{RenderOptions, render_diagnostics, render_kept};
pub use source::{SourceFile, cp1252, cp1252_byte};
pub use span::{Span, line_col, with_line_starts};
