//! The `gcodec` command. Thin over the library crates: it reads files,
//! calls a stage, prints the result and renders diagnostics.

mod allocator;
mod baseline;
mod check;
mod commands;
mod diagnostic_formats;
mod exit;
mod interrupt;
mod output;
mod plot;
mod report;
mod run;
mod sarif;

use std::process::ExitCode;

use clap::Parser;

use crate::exit::{EXIT_CLEAN, EXIT_USAGE};

/// mimalloc: about a third of a large lowering went to glibc's malloc and
/// free. Built without transparent huge pages (the `no_thp` feature): a
/// fault on a huge page zeroes 2 MiB however little of it is used, which
/// cost a sixth of a streamed run of the 1,000,000-block program and
/// doubled its peak memory (docs/performance.md). Alignment is asked for
/// only where a layout needs it (`allocator.rs`).
#[global_allocator]
static ALLOCATOR: allocator::Mimalloc = allocator::Mimalloc;

fn main() -> ExitCode {
    #[cfg(not(target_os = "linux"))]
    allocator::set_options();
    let exit = match commands::Cli::try_parse() {
        Ok(cli) => commands::run(cli),
        Err(usage) => print_usage(&usage),
    };
    ExitCode::from(output::exit_code(exit))
}

/// What clap says instead of running a command: help and the version on
/// stdout (exit 0), a usage error on stderr (exit 2).
fn print_usage(usage: &clap::Error) -> u8 {
    if usage.use_stderr() {
        // A usage error may echo what was typed (`unexpected argument
        // '…'`): plain text with its control characters escaped, as in
        // every text output, so no argument can retitle the terminal.
        let text = usage.render().to_string();
        output::to_stderr(&gcodec_source::escape_controls(&text));
        return EXIT_USAGE;
    }
    output::after_output(EXIT_CLEAN, usage.print())
}
