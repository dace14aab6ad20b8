//! Where every command writes: its result to stdout, diagnostics and
//! messages to stderr, and what a failed write makes of the exit code.
//! Nothing here panics (the printing macros do when a write fails).
//!
//! A reader that closes stdout early (`gcodec run … | head`) ends the
//! command quietly with exit 0. Any other failure to write stdout (a full
//! disk) is reported as `gcodec::io::write` and is exit 2; a failure to
//! write stderr cannot be reported, and is exit 2 silently.

use std::io::{self, BufWriter, Write};
use std::sync::atomic::{AtomicBool, Ordering};

use gcodec_source::{Diagnostic, EscapeControls, codes, render_diagnostics};

use crate::exit::{EXIT_CLEAN, EXIT_USAGE};

/// Set once a write to stderr failed: stderr is the process's, and so is
/// this.
static STDERR_FAILED: AtomicBool = AtomicBool::new(false);

/// Writes `text` to stderr, remembering a failure for [`exit_code`].
pub fn to_stderr(text: &str) {
    let mut stderr = io::stderr().lock();
    stderr_written(
        stderr
            .write_all(text.as_bytes())
            .and_then(|()| stderr.flush()),
    );
}

/// Remembers a failed write to stderr for [`exit_code`].
pub fn stderr_written(written: io::Result<()>) {
    if written.is_err() {
        STDERR_FAILED.store(true, Ordering::Relaxed);
    }
}

/// A command's result on stdout, buffered.
pub struct Stdout(Box<dyn Write>);

impl Stdout {
    /// For a format a person reads (a syntax tree, a listing, a trace):
    /// control characters from the program are escaped.
    pub fn text() -> Self {
        Self(Box::new(BufWriter::new(EscapeControls::new(
            io::stdout().lock(),
        ))))
    }

    /// For a data format (JSON, JSONL, CSV, TOML), which escapes by its
    /// own rules: written as it is.
    pub fn data() -> Self {
        Self(Box::new(BufWriter::new(io::stdout().lock())))
    }
}

impl Write for Stdout {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.0.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.0.write_all(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.0.flush()
    }
}

/// The exit code of a command that would exit with `exit` and whose
/// output on stdout ended with `written`: a closed pipe is a quiet end
/// (0); any other failure is reported and is 2.
pub fn after_output(exit: u8, written: io::Result<()>) -> u8 {
    match written {
        Ok(()) => exit,
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => EXIT_CLEAN,
        Err(e) => {
            let d = Diagnostic::new(codes::io::WRITE, format!("cannot write the output: {e}"));
            to_stderr(&render_diagnostics(&[d], None, Default::default()));
            EXIT_USAGE
        }
    }
}

/// The process's exit code for a command that ended with `exit`: 2 if
/// anything could not be written to stderr.
pub fn exit_code(exit: u8) -> u8 {
    if STDERR_FAILED.load(Ordering::Relaxed) {
        EXIT_USAGE
    } else {
        exit
    }
}
