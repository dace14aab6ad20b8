//! The `gcodec` command. Thin over the library crates: it reads files,
//! calls a stage, prints the result and renders diagnostics.

mod commands;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = commands::Cli::parse();
    ExitCode::from(commands::run(cli))
}
