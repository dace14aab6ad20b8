use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::{Parser, Subcommand, ValueEnum};
use gcodec_source::{codes, escape_controls};

use crate::diagnostic_formats::DiagnosticFormat;
use crate::exit::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE};
use crate::output::{Stdout, after_output, to_stderr};
use crate::report::{
    ConfigOption, DiagnosticOptions, EncodingOption, ProgramSetup, Reading, Reporter,
    load_definitions, load_profile, read,
};

/// Compile and simulate SINUMERIK 840D sl / 828D part programs.
#[derive(Debug, Parser)]
#[command(name = "gcodec", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The commands, each one's arguments built only when it is the one
/// run (`defer`): building every command's arguments was an eighth of a
/// short program's run (issue 20, docs/performance.md). The argument
/// structs have plain comments, not doc comments: clap takes a doc
/// comment there as the command's about, which, deferred, would replace
/// the command's own in its `--help`.
#[derive(Debug, Subcommand)]
#[command(defer = true)]
enum Command {
    /// Parse programs and print their syntax tree.
    Parse {
        /// `.mpf` / `.spf` files to parse.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// A definition file (`SMAC.DEF`, `MGUD.DEF`) whose macros the
        /// programs use: they are parsed with them expanded. Repeat for
        /// several files.
        #[arg(long = "definitions", value_name = "FILE.DEF")]
        definitions: Vec<PathBuf>,
        /// Output: the syntax tree as indented text, or as JSON.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        #[command(flatten)]
        encoding: EncodingOption,
        #[command(flatten)]
        diagnostics: DiagnosticOptions,
    },
    /// Lower programs to AIL, the executable instruction list, checked
    /// against a machine profile.
    Lower {
        /// `.mpf` / `.spf` file to lower.
        file: PathBuf,
        /// The machine profile (TOML); the built-in one if omitted.
        #[arg(long)]
        profile: Option<PathBuf>,
        /// A definition file (`MGUD.DEF`, `SMAC.DEF`): global user data
        /// and macros the program may use. Repeat for several files.
        #[arg(long = "definitions", value_name = "FILE.DEF")]
        definitions: Vec<PathBuf>,
        /// Output: a listing, one instruction a line, or the AIL document
        /// as JSON.
        #[arg(long, value_enum, default_value_t = Format::Text)]
        format: Format,
        /// How the diagnostics are written on stderr: `full` renders each
        /// as it comes; the others write one document of them all at the
        /// end, alone on stderr.
        #[arg(long, value_enum, default_value_t = DiagnosticFormat::Full)]
        output_format: DiagnosticFormat,
        #[command(flatten)]
        config: ConfigOption,
        #[command(flatten)]
        encoding: EncodingOption,
        #[command(flatten)]
        diagnostics: DiagnosticOptions,
    },
    /// Check part programs and definition files, as CI does before they
    /// reach a machine: each parsed and lowered against the profile and
    /// definition files `gcodec.toml` assigns it.
    Check(crate::check::CheckArgs),
    /// Run a program on the machine a profile describes and stream its
    /// events: motions, modal changes, M functions, tool changes, calls…
    Run(crate::run::RunArgs),
    /// Run a program and draw its path as an SVG picture: rapids dashed,
    /// feed moves in a colour per tool, a legend, a scale bar.
    Plot(crate::plot::PlotArgs),
    /// Check or show machine profiles.
    #[command(subcommand)]
    Profile(ProfileCommand),
    /// Explain a diagnostic code: what it means, why it is reported, how
    /// to fix it, with examples.
    #[command(arg_required_else_help = true)]
    Explain {
        /// The code: `gcodec::parse::invalid_word`, `parse::invalid_word`
        /// or, where it is unique, `invalid_word`.
        #[arg(required_unless_present = "list", conflicts_with = "list")]
        code: Option<String>,
        /// List every code with its level and summary instead.
        #[arg(long)]
        list: bool,
    },
}

#[derive(Debug, Subcommand)]
enum ProfileCommand {
    /// Check a profile: every problem is reported; exit 0 if it is valid,
    /// 2 if not.
    Check {
        /// The profile (TOML).
        file: PathBuf,
        #[command(flatten)]
        diagnostics: DiagnosticOptions,
    },
    /// Print the effective profile, defaults filled in (the built-in
    /// profile when no file is given).
    Show {
        /// The profile (TOML); the built-in one if omitted.
        file: Option<PathBuf>,
        /// Output format.
        #[arg(long, value_enum, default_value_t = ProfileFormat::Toml)]
        format: ProfileFormat,
        #[command(flatten)]
        diagnostics: DiagnosticOptions,
    },
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ProfileFormat {
    Toml,
    Json,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum Format {
    Text,
    Json,
}

impl Format {
    fn stdout(self) -> Stdout {
        match self {
            Self::Text => Stdout::text(),
            Self::Json => Stdout::data(),
        }
    }
}

pub fn run(cli: Cli) -> u8 {
    match cli.command {
        Command::Parse {
            files,
            definitions,
            format,
            encoding,
            diagnostics,
        } => parse(
            &files,
            &definitions,
            format,
            Reading::builtin(encoding),
            &Reporter::full(diagnostics),
        ),
        Command::Lower {
            file,
            profile,
            definitions,
            format,
            output_format,
            config,
            encoding,
            diagnostics,
        } => {
            let reporter = Reporter::new(diagnostics, output_format);
            let exit =
                match ProgramSetup::of(&config, &file, profile.as_deref(), &definitions, &reporter)
                {
                    Ok(setup) => lower(&file, &setup, encoding, format, &reporter),
                    Err(code) => code,
                };
            reporter.finish();
            exit
        }
        Command::Run(args) => crate::run::run(args),
        Command::Plot(args) => crate::plot::plot(args),
        Command::Check(args) => crate::check::check(args),
        Command::Explain { code, list } => explain(code.as_deref(), list),
        Command::Profile(ProfileCommand::Check { file, diagnostics }) => {
            match load_profile(Some(&file), &Reporter::full(diagnostics)) {
                Ok(_) => EXIT_CLEAN,
                Err(code) => code,
            }
        }
        Command::Profile(ProfileCommand::Show {
            file,
            format,
            diagnostics,
        }) => match load_profile(file.as_deref(), &Reporter::full(diagnostics)) {
            Ok(profile) => show_profile(&profile, format),
            Err(code) => code,
        },
    }
}

/// `gcodec explain`: a code's explanation or, with `--list`, every code;
/// an unknown code is a usage error, with the code meant if one is close.
fn explain(code: Option<&str>, list: bool) -> u8 {
    let text = match code {
        Some(name) if !list => match codes::find(name) {
            Some(code) => codes::explain(code),
            None => {
                let hint = codes::suggest(name)
                    .map(|code| format!("; did you mean `{code}`?"))
                    .unwrap_or_default();
                to_stderr(&format!(
                    "gcodec: `{}` is not a diagnostic code{hint}\n\
                     `gcodec explain --list` lists them\n",
                    escape_controls(name)
                ));
                return EXIT_USAGE;
            }
        },
        _ => codes::list(),
    };
    let mut out = Stdout::text();
    let written = out.write_all(text.as_bytes()).and_then(|()| out.flush());
    after_output(EXIT_CLEAN, written)
}

fn show_profile(profile: &gcodec_profile::Profile, format: ProfileFormat) -> u8 {
    let text = match format {
        ProfileFormat::Toml => toml::to_string_pretty(profile).map_err(|e| e.to_string()),
        ProfileFormat::Json => serde_json::to_string_pretty(profile)
            .map(|s| s + "\n")
            .map_err(|e| e.to_string()),
    };
    match text {
        Ok(text) => {
            let mut out = Stdout::data();
            let written = out.write_all(text.as_bytes()).and_then(|()| out.flush());
            after_output(EXIT_CLEAN, written)
        }
        Err(e) => {
            to_stderr(&format!("gcodec: cannot write the profile: {e}\n"));
            EXIT_USAGE
        }
    }
}

fn parse(
    files: &[PathBuf],
    definitions: &[PathBuf],
    format: Format,
    reading: Reading,
    reporter: &Reporter,
) -> u8 {
    let mut exit = EXIT_CLEAN;
    let mut json = Vec::new();
    let mut out = format.stdout();
    let mut written = Ok(());
    let definitions = match load_definitions(definitions, reading, reporter) {
        Ok(d) => d,
        Err(code) => return code,
    };
    for path in files {
        let Ok(file) = read(path, reading, reporter) else {
            exit = EXIT_USAGE;
            continue;
        };
        let parsed = gcodec_driver::parse_with(&file, &definitions);
        reporter.report(&parsed.diagnostics, Some(&file), file.name());
        if parsed.has_errors() && exit == EXIT_CLEAN {
            exit = EXIT_DIAGNOSTICS;
        }
        match format {
            Format::Text => {
                let mut tree = FmtToIo::new(&mut out);
                let _ = gcodec_driver::write_tree(&parsed.program, &mut tree);
                written = tree.finish();
                if written.is_err() {
                    break;
                }
            }
            Format::Json => json.push(parsed.program),
        }
    }
    if let (Format::Json, Ok(())) = (format, &written) {
        let result = if json.len() == 1 {
            serde_json::to_writer_pretty(&mut out, &json[0])
        } else {
            serde_json::to_writer_pretty(&mut out, &json)
        };
        written = result
            .map_err(std::io::Error::from)
            .and_then(|()| writeln!(out));
    }
    after_output(exit, written.and_then(|()| out.flush()))
}

fn lower(
    path: &Path,
    setup: &ProgramSetup,
    encoding: EncodingOption,
    format: Format,
    reporter: &Reporter,
) -> u8 {
    let profile = match load_profile(setup.profile.as_deref(), reporter) {
        Ok(p) => p,
        Err(code) => return code,
    };
    let reading = Reading::new(&profile, encoding);
    let mut definitions = match load_definitions(&setup.definitions, reading, reporter) {
        Ok(d) => d,
        Err(code) => return code,
    };
    for name in &setup.assume_defined {
        definitions.assume_defined(name);
    }
    let file = match read(path, reading, reporter) {
        Ok(f) => f,
        Err(code) => return code,
    };
    let file = Arc::new(file);
    let kind = gcodec_driver::ProgramKind::of_file(file.name());
    let options = gcodec_driver::StreamOptions::default();
    // The instructions are written as they are made; the diagnostics,
    // all known only at the end, follow on stderr.
    let (written, diagnostics) =
        gcodec_driver::lower_streamed(&file, kind, &profile, &definitions, options, |pages| {
            let mut out = format.stdout();
            match format {
                Format::Text => gcodec_driver::lower::write_listing(pages, &mut out),
                Format::Json => gcodec_driver::lower::write_json(pages, &mut out),
            }
            .and_then(|()| out.flush())
        });
    let has_errors = reporter.report(&diagnostics, Some(&file), file.name());
    let exit = if has_errors {
        EXIT_DIAGNOSTICS
    } else {
        EXIT_CLEAN
    };
    after_output(exit, written)
}

/// Writes formatted text straight to an `io::Write` (the listing of a
/// large program is not built in memory first), keeping the first IO error.
struct FmtToIo<'a, W: Write> {
    out: &'a mut W,
    error: Option<std::io::Error>,
}

impl<'a, W: Write> FmtToIo<'a, W> {
    fn new(out: &'a mut W) -> Self {
        Self { out, error: None }
    }

    fn finish(self) -> std::io::Result<()> {
        self.error.map_or(Ok(()), Err)
    }
}

impl<W: Write> std::fmt::Write for FmtToIo<'_, W> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.out.write_all(s.as_bytes()).map_err(|e| {
            self.error.get_or_insert(e);
            std::fmt::Error
        })
    }
}
