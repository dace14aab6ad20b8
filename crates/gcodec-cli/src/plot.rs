//! `gcodec plot`: runs a program as `run` does and draws its path as an
//! SVG picture (SPEC §11.11), to a file or stdout.

use std::io::Write;
use std::path::{Path, PathBuf};

use gcodec_driver::RunReport;
use gcodec_plot::{PlotSink, View};

use crate::exit::EXIT_USAGE;
use crate::output::{Stdout, after_output};
use crate::report::Reporter;
use crate::run::{RunInputs, conclude, prepare, run_events, summary_to_stderr};

// The options of `gcodec plot`.
#[derive(Debug, clap::Args)]
pub struct PlotArgs {
    #[command(flatten)]
    pub inputs: RunInputs,
    /// Where the SVG goes; stdout if omitted.
    #[arg(short, long, value_name = "OUT.svg")]
    pub output: Option<PathBuf>,
    /// The view: `xy` (G17: X right, Y up), `xz` (G18: Z right, X up),
    /// `yz` (G19: Y right, Z up) or `iso` (south-west isometric); the
    /// plane of the program's first motion if omitted.
    #[arg(long, value_name = "VIEW")]
    pub view: Option<View>,
}

pub fn plot(args: PlotArgs) -> u8 {
    let reporter = Reporter::new(args.inputs.diagnostics, args.inputs.output_format);
    let exit = plot_with(&args, &reporter);
    reporter.finish();
    exit
}

fn plot_with(args: &PlotArgs, reporter: &Reporter) -> u8 {
    let prepared = match prepare(&args.inputs, reporter) {
        Ok(prepared) => prepared,
        Err(code) => return code,
    };
    let mut sink = PlotSink::new(args.view);
    let RunReport {
        outcome,
        diagnostics,
    } = run_events(&prepared, &mut sink, None, reporter);
    let (outcome, exit) = match conclude(&prepared, outcome, &diagnostics, reporter) {
        Ok(concluded) => concluded,
        Err(code) => return code,
    };
    // The picture of what ran, an alarm or not: the path up to it.
    let name = prepared.file.name();
    let title = Path::new(name)
        .file_name()
        .map_or_else(|| name.into(), |n| n.to_string_lossy());
    let svg = sink.into_plot().to_svg(&title);
    let written = match &args.output {
        Some(path) => std::fs::write(path, svg.as_bytes()),
        None => {
            let mut out = Stdout::data();
            out.write_all(svg.as_bytes()).and_then(|()| out.flush())
        }
    };
    let exit = after_output(exit, written);
    if exit != EXIT_USAGE {
        summary_to_stderr(&outcome, reporter);
    }
    exit
}
