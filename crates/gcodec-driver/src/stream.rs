//! A streamed run of a main program: it runs while it is lowered, and
//! neither its syntax tree nor all its instructions are ever held
//! (docs/ARCHITECTURE.md, "Streaming").
//!
//! Pass 1 skims the program chunk by chunk into its outline (structures,
//! jump targets, names, signatures), parsing only the blocks the outline
//! reads something of and dropping each tree. Pass 2, on a second
//! thread, has each chunk parsed and lowered against the outline by the
//! workers and hands its instructions to the run as a page through a
//! bounded channel; it lowers to the end even when the run stops early,
//! so every diagnostic is reported. A block with errors stops the run
//! with an alarm when the run reaches it (SPEC §11.9).

use std::sync::Arc;
use std::sync::mpsc::{SyncSender, sync_channel};

use gcodec_ail::{ByteRange, Source};
use gcodec_exec::program::{Program, SourcePage};
use gcodec_profile::Profile;
use gcodec_sema::{Definitions, LoweredChunk, ProgramKind, lower_chunks, outline_chunks};
use gcodec_source::{Diagnostic, Diagnostics, SourceFile};
use gcodec_stream::{SpentBin, chunks_at};

/// How a streamed run cuts its program.
#[derive(Clone, Copy, Debug)]
pub struct StreamOptions {
    /// Lines per chunk, and so per page of instructions.
    pub page_lines: usize,
    /// Threads that skim chunks for the outline (pass 1), and that parse
    /// and lower chunks (pass 2).
    pub workers: usize,
}

impl Default for StreamOptions {
    fn default() -> Self {
        Self {
            // Measured on the 1,000,000-block program (docs/performance.md):
            // smaller pages hold less in flight at the same speed.
            page_lines: 1024,
            workers: 2,
        }
    }
}

/// Pages the channel holds before pass 2 waits for the run: enough for
/// the two threads not to wait on each other at every page.
const PAGES_AHEAD: usize = 2;

/// Programs of at most this many chunks are lowered whole on the calling
/// thread before they run, their pages all held by the channel: starting
/// a thread for pass 2 (its stack, its allocator arena, the hand-over of
/// each page) cost more than lowering a short program takes, and most
/// programs a shop runs are short (issue 20, docs/performance.md).
const LOWERED_BEFORE_RUN: usize = 1;

/// Runs the program in `file` (called `name`, started as `kind`:
/// [`ProgramKind::Main`] but for a subprogram run on its own) streamed:
/// `run` gets the [`Program`] while pass 2 still lowers it. Returns what
/// `run` returned and all the program's own diagnostics (parse,
/// structure, outline, lowering) in source order.
pub fn run_streamed<R>(
    file: &Arc<SourceFile>,
    name: String,
    kind: ProgramKind,
    profile: &Profile,
    definitions: &Definitions,
    options: StreamOptions,
    run: impl FnOnce(Arc<Program>) -> R,
) -> (R, Diagnostics) {
    let src = file.bytes();
    let chunks = chunks_at(file.line_starts(), src.len(), options.page_lines);
    let (outline, structure_diagnostics) =
        outline_chunks(file, kind, &chunks, options.workers, profile, definitions);
    let outline_diagnostics = outline.diagnostics();
    let before_run = chunks.len() <= LOWERED_BEFORE_RUN;
    // Before the run, the channel holds every page: pass 1's errors, the
    // chunks' and the end's.
    let capacity = if before_run {
        chunks.len() + 2
    } else {
        PAGES_AHEAD
    };
    let (sender, receiver) = sync_channel::<SourcePage>(capacity);
    let program = Program::streamed(
        name,
        Arc::clone(file),
        Box::new(receiver),
        outline.returns(),
    );
    let program = Arc::new(program);
    let file_name = &program.file;
    // Pass 1's errors are known before the run starts.
    let known_errors = error_sources(
        file,
        file_name,
        structure_diagnostics.iter().chain(outline_diagnostics),
    );
    let pass2 = || {
        let mut pages = Pages {
            sender: Some(sender),
            file,
            name: file_name,
            parse_diagnostics: Diagnostics::new(),
            diagnostics: Diagnostics::new(),
        };
        // The errors pass 1 found go ahead of every page.
        pages.send(SourcePage::new(Vec::new(), known_errors));
        let workers = options.workers;
        lower_chunks(file, &chunks, workers, &outline, profile, |lowered| {
            pages.lowered(lowered);
        });
        (pages.parse_diagnostics, pages.diagnostics)
    };
    let (result, lowered) = if before_run {
        let lowered = pass2();
        let result = run(Arc::clone(&program));
        program.end_stream();
        // The pages the run gave back wait in this thread's bin, which
        // lives as long as the thread: an embedder running program after
        // program on it must not keep them all.
        SpentBin::free_this_threads();
        (result, lowered)
    } else {
        std::thread::scope(|scope| {
            let pass2 = scope.spawn(pass2);
            let result = run(Arc::clone(&program));
            // A run that stopped early leaves pages unread: pass 2 must
            // not wait for it to take them.
            program.end_stream();
            let lowered = pass2
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            (result, lowered)
        })
    };
    let (parse_diagnostics, lowering_diagnostics) = lowered;
    let diagnostics = in_program_order(
        src,
        definitions,
        structure_diagnostics,
        outline_diagnostics,
        parse_diagnostics,
        lowering_diagnostics,
    );
    (result, diagnostics)
}

/// The diagnostics of a program read in passes (the structure's, the
/// outline's, the parser's and the lowering's), in the order the whole
/// program's parse and lowering give them: a stable sort keeps the
/// parser's ahead of the pairing's, the outline's and the lowering's at
/// one place. Those inside macro expansions name the macro.
pub(crate) fn in_program_order(
    src: &[u8],
    definitions: &Definitions,
    structure: Vec<Diagnostic>,
    outline: &Diagnostics,
    parse: Diagnostics,
    mut lowering: Diagnostics,
) -> Diagnostics {
    let mut outline = outline.clone();
    let macros = definitions.macros();
    macros.label_expansions(src, &mut outline);
    macros.label_expansions(src, &mut lowering);
    let mut diagnostics = parse;
    diagnostics.append(structure.into());
    diagnostics.append(outline);
    diagnostics.append(lowering);
    diagnostics.sort_by_start();
    diagnostics
}

/// The pages pass 2 sends, while the run takes them, and the parser's
/// and the lowering's diagnostics.
struct Pages<'a> {
    sender: Option<SyncSender<SourcePage>>,
    file: &'a SourceFile,
    name: &'a Arc<str>,
    /// Bounded per file, as they are gathered.
    parse_diagnostics: Diagnostics,
    diagnostics: Diagnostics,
}

impl Pages<'_> {
    /// Sends a lowered chunk, with the places of its errors.
    fn lowered(&mut self, chunk: LoweredChunk) {
        let errors = error_sources(
            self.file,
            self.name,
            chunk.parse_diagnostics.iter().chain(&chunk.diagnostics),
        );
        self.parse_diagnostics.append(chunk.parse_diagnostics);
        self.diagnostics.append(chunk.diagnostics);
        self.send(SourcePage::new(chunk.instructions, errors).given_back_to(chunk.spent));
    }

    fn send(&mut self, page: SourcePage) {
        if let Some(sender) = &self.sender
            && sender.send(page).is_err()
        {
            // The run has ended: lowering goes on for the diagnostics.
            self.sender = None;
        }
    }
}

/// Where the errors among `diagnostics` are, in line order; an error
/// without a place counts as one on the first line.
fn error_sources<'d>(
    file: &SourceFile,
    name: &Arc<str>,
    diagnostics: impl IntoIterator<Item = &'d Diagnostic>,
) -> Vec<Source> {
    let mut errors: Vec<Source> = diagnostics
        .into_iter()
        .filter(|d| d.is_error())
        .map(|d| {
            let span = d.span().unwrap_or_default();
            let (line, col) = file.line_col(span.start);
            Source {
                file: Arc::clone(name),
                line,
                col,
                span: ByteRange {
                    start: span.start,
                    end: span.end,
                },
            }
        })
        .collect();
    errors.sort_by_key(|e| (e.line, e.col));
    errors
}
