//! The exit codes of every command.

/// Exit code: no error diagnostics.
pub const EXIT_CLEAN: u8 = 0;
/// Exit code: at least one error diagnostic in a program.
pub const EXIT_DIAGNOSTICS: u8 = 1;
/// Exit code: usage, IO or profile error.
pub const EXIT_USAGE: u8 = 2;
