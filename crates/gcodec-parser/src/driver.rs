//! Splits the token stream into blocks (lines) and runs the block grammar on
//! each, so that one malformed block never hides the rest of the program.

use std::mem::MaybeUninit;
use std::ops::Range;

use chumsky::input::Input as _;
use chumsky::span::SimpleSpan;
use compact_str::CompactString;
use gcodec_lexer::{Lexer, TokenKind};
use gcodec_source::{
    Diagnostic, Diagnostics, Encoding, SourceFile, Span, TextEncoding, UTF8_BOM, codes,
};

use crate::ast::*;
use crate::error::SyntaxError;
use crate::grammar::{self, Ctx, Spanned, operators};
use crate::macros::{Expanded, Macros};
use crate::misspelt::Misspelt;
use crate::plain_glance::plain_lines;
use crate::{fast, structure, word_line};
use gcodec_stream::{Chunk, WorkerPriority, map_chunks};

/// Deepest nesting of `(` and `[` accepted in one block. Deeper expressions
/// are reported instead of parsed, which bounds the recursion of every stage.
pub const MAX_EXPRESSION_DEPTH: usize = 64;

/// Most operators accepted in one block (the sign of a DIN constant such as
/// `X-10` does not count). Expression trees are as deep as their operator
/// chains; the bound keeps cloning, serialising and later stages' walks
/// within a 2 MiB thread stack even in debug builds. A SINUMERIK block has
/// at most 512 characters, so real programs stay far below it.
pub const MAX_OPERATORS_PER_BLOCK: usize = 1000;

/// Lines handed to one instance of the block grammar at a time (a
/// flush). The grammar borrows the token buffer, so the buffer is refilled
/// per flush rather than held for the whole file: memory stays
/// proportional to the AST.
const FLUSH_LINES: usize = 2048;

/// The bytes of a chunk whose tokens [`read_chunk_into`] makes room for at
/// the start (the flush comes after [`FLUSH_LINES`] lines, about 32 bytes
/// each in real programs); longer chunks grow the buffer.
const FLUSH_BYTES_BOUND: usize = FLUSH_LINES * 64;

/// The result of parsing: always a program, plus what was wrong with it.
#[derive(Clone, Debug)]
pub struct Parse {
    pub program: Program,
    pub diagnostics: Diagnostics,
}

impl Parse {
    /// True if any diagnostic, kept or not, is an error.
    pub fn has_errors(&self) -> bool {
        self.diagnostics.has_errors()
    }
}

/// Parses one source file.
pub fn parse(file: &SourceFile) -> Parse {
    parse_with_macros(file, &Macros::default())
}

/// Parses one source file with the macros of its definition files
/// expanded (see [`Macros`]).
pub fn parse_with_macros(file: &SourceFile, macros: &Macros) -> Parse {
    // The program quotes from the file's own bytes: no copy.
    let source = SourceText::shared(file.shared_bytes());
    let how = How {
        reading: Reading::Whole,
        macros,
        encoding: file.encoding(),
    };
    parse_with(file.name(), file.bytes(), how, Some(source))
}

/// Parses bytes under a file name. A leading UTF-8 byte-order mark is not
/// part of the program: the spans are into the bytes after it, the bytes
/// [`SourceFile::new`] holds for `src`, read in the encoding it gives
/// them (UTF-8 if they are valid UTF-8, else Windows-1252).
pub fn parse_bytes(name: &str, src: &[u8]) -> Parse {
    parse_with(
        name,
        src,
        How::plain(Reading::Whole, src, &Macros::default()),
        None,
    )
}

/// Parses with the grammar only, never the fast path for constant-word
/// blocks: the reference the fast path is tested against.
#[doc(hidden)]
pub fn parse_bytes_with_grammar_only(name: &str, src: &[u8]) -> Parse {
    parse_with(
        name,
        src,
        How::plain(Reading::GrammarOnly, src, &Macros::default()),
        None,
    )
}

/// Files at least this large are parsed on several threads, one chunk of
/// whole lines each (no token crosses a line end).
const PARALLEL_MIN_BYTES: usize = 4 << 20;

/// Parses in exactly `threads` chunks, one a thread, whatever the file
/// size: the reference for tests that the split does not change the
/// result.
#[doc(hidden)]
pub fn parse_bytes_in_chunks(name: &str, src: &[u8], threads: usize) -> Parse {
    let macros = Macros::default();
    let how = How::plain(Reading::Whole, src, &macros);
    let src = without_bom(src);
    let source = SourceText::new(src);
    parse_in_chunks(name, src, source, how, split(src, threads))
}

/// How the lines of a file are read: in full or skimmed, with which
/// macros expanded, in which encoding.
#[derive(Clone, Copy)]
struct How<'m> {
    reading: Reading,
    macros: &'m Macros,
    encoding: Encoding,
}

impl<'m> How<'m> {
    /// `macros` (none, for a bare file), and the encoding of `src` when no
    /// profile or option says otherwise.
    fn plain(reading: Reading, src: &[u8], macros: &'m Macros) -> Self {
        Self {
            reading,
            macros,
            encoding: TextEncoding::default().of(without_bom(src)),
        }
    }
}

/// Parses `src`, whose bytes after a byte-order mark are `source` where
/// the caller shares them (else they are copied).
fn parse_with(name: &str, src: &[u8], how: How<'_>, source: Option<SourceText>) -> Parse {
    let src = without_bom(src);
    let source = source.unwrap_or_else(|| SourceText::new(src));
    // Asking for the core count reads cgroup limits: only large files ask.
    let threads = if src.len() < PARALLEL_MIN_BYTES {
        1
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get().min(8))
    };
    parse_in_chunks(name, src, source, how, split(src, threads))
}

/// `src` without a leading UTF-8 byte-order mark, as a [`SourceFile`]
/// holds it, so that a parse's spans and its file's bytes agree.
fn without_bom(src: &[u8]) -> &[u8] {
    src.strip_prefix(UTF8_BOM).unwrap_or(src)
}

/// Parses the whole of `src` (held by the program as `source`), each of
/// `chunks` on a thread of its own.
fn parse_in_chunks(
    name: &str,
    src: &[u8],
    source: SourceText,
    how: How<'_>,
    chunks: Vec<Chunk>,
) -> Parse {
    // One block per line: the program's blocks are allocated once, and each
    // chunk fills its own run of them, so no second copy of the tree is
    // ever alive (a merge would hold both at once).
    let total: usize = chunks.iter().map(|c| c.blocks).sum();
    let mut blocks: Vec<Block> = Vec::with_capacity(total);
    // Each chunk writes its blocks straight into its run of the vector's
    // spare capacity, so the first touch of those pages happens on the
    // chunk's own thread rather than in a serial fill beforehand.
    let mut slots = runs(&mut blocks.spare_capacity_mut()[..total], &chunks);
    let found: Vec<ChunkFindings> = if chunks.len() == 1 {
        let slot = slots.pop().unwrap_or_default();
        vec![read_chunk_into(src, &chunks[0], slot, how)]
    } else {
        std::thread::scope(|scope| {
            let handles: Vec<_> = chunks
                .iter()
                .zip(slots)
                .map(|(chunk, slot)| scope.spawn(move || read_chunk_into(src, chunk, slot, how)))
                .collect();
            handles
                .into_iter()
                // Parsing does not panic; if it ever did, the panic is the
                // caller's, as in the single-threaded case.
                .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
                .collect()
        })
    };
    // SAFETY: `blocks` has capacity for `total`, the runs cover the first
    // `total` slots, and `read_chunk_into` writes every slot of its run
    // before it returns. Had a chunk's thread panicked, `resume_unwind`
    // above would have left before this point and the written blocks would
    // only leak.
    unsafe { blocks.set_len(total) };
    let mut program = Program {
        file: name.to_owned(),
        header: None,
        path: None,
        blocks,
        structures: Vec::new(),
        source,
    };
    let mut diagnostics = Diagnostics::new();
    let mut structure_blocks = Vec::new();
    for findings in found {
        program.header = program.header.take().or(findings.header);
        program.path = program.path.take().or(findings.path);
        diagnostics.append(findings.diagnostics);
        structure_blocks.extend(findings.structure_blocks);
    }
    let mut structure_diagnostics = Vec::new();
    structure::pair(&mut program, &structure_blocks, &mut structure_diagnostics);
    diagnostics.append(structure_diagnostics.into());
    // Lexical errors are found while reading and syntax errors per flush:
    // report everything in source order.
    diagnostics.sort_by_start();
    Parse {
        program,
        diagnostics,
    }
}

/// One chunk, parsed: its blocks (depth not yet set: see
/// [`crate::Pairing`]) and what else it found.
#[derive(Debug)]
pub struct ParsedChunk {
    pub first_block: usize,
    pub blocks: Vec<Block>,
    /// Only the first chunk may hold the header and path lines.
    pub header: Option<Header>,
    pub path: Option<PathDirective>,
    /// Lexical and syntax errors, in the order found: not sorted, since
    /// whoever keeps them merges them with others and sorts once (by
    /// span start, a stable sort, as [`parse_bytes`] does).
    pub diagnostics: Diagnostics,
    /// The blocks holding a structure statement, by index in the program.
    pub structure_blocks: Vec<u32>,
}

/// Parses the lines of `chunk` of `src` as [`parse_bytes`] parses them in
/// the whole file: the same blocks, spans and diagnostics (those sorted
/// by span start, with a stable sort, once merged).
/// Macros are expanded as [`parse_with_macros`] expands them.
pub fn parse_chunk(src: &[u8], encoding: Encoding, chunk: &Chunk, macros: &Macros) -> ParsedChunk {
    let how = How {
        reading: Reading::Whole,
        macros,
        encoding,
    };
    read_chunk(src, chunk, how)
}

/// [`parse_chunk`] of lines none of which [`WordLine::read`] reads (the
/// caller has tried): the same blocks and diagnostics, without trying
/// each line again.
///
/// [`WordLine::read`]: crate::WordLine::read
pub fn parse_chunk_of_lexed_lines(
    src: &[u8],
    encoding: Encoding,
    chunk: &Chunk,
    macros: &Macros,
) -> ParsedChunk {
    let how = How {
        reading: Reading::Lexed,
        macros,
        encoding,
    };
    read_chunk(src, chunk, how)
}

/// Reads the lines of `chunk` of `src` for lowering's `Outline` of the
/// program (pass 1 of a streamed run), much faster than [`parse_chunk`]:
/// each block is the one [`parse_chunk`] gives, except a *plain* block
/// after a block that leaves the plain lines after it skimmable
/// ([`plain_lines_skimmable_after`]), with only such plain blocks between
/// them in the chunk. That block keeps its span, skip mark and block
/// number, and its statements and comment are left out.
///
/// A plain block holds no label, no keyword but the operators (`AND`,
/// `DIV`, `TRUE`, …), no `M` word and no skip mark or block number the
/// grammar must judge: only words, assignments, names, calls by name
/// and expressions. The plain lines after a block are skimmable when it
/// has statements and none of them defines, declares or ends anything
/// (`DEF`, `REDEF`, `DEFINE`, `PROC`, `EXTERN`, `ENDPROC`, `RET`, an `M`
/// word). So a block left out holds no structure, jump, definition,
/// declaration or program end, and changes nothing the block before the
/// plain ones has not already set. The chunk's diagnostics are not given
/// (`diagnostics` is empty): [`parse_chunk`] gives them. With macros,
/// every line is parsed: a plain line may use a macro that stands for a
/// structure keyword.
pub fn skim_chunk(src: &[u8], encoding: Encoding, chunk: &Chunk, macros: &Macros) -> ParsedChunk {
    let how = How {
        reading: Reading::Skim,
        macros,
        encoding,
    };
    let mut skimmed = read_chunk(src, chunk, how);
    skimmed.diagnostics.clear();
    skimmed
}

fn read_chunk(src: &[u8], chunk: &Chunk, how: How<'_>) -> ParsedChunk {
    let mut blocks: Vec<Block> = Vec::with_capacity(chunk.blocks);
    let found = read_chunk_into(
        src,
        chunk,
        &mut blocks.spare_capacity_mut()[..chunk.blocks],
        how,
    );
    // SAFETY: `read_chunk_into` wrote every one of the `chunk.blocks` slots
    // (one block per line; `chunks` counted the lines).
    unsafe { blocks.set_len(chunk.blocks) };
    ParsedChunk {
        first_block: chunk.first_block,
        blocks,
        header: found.header,
        path: found.path,
        diagnostics: found.diagnostics,
        structure_blocks: found.structure_blocks,
    }
}

/// [`skim_chunk`] of each of `chunks`, on `workers` threads, handed to
/// `each` in order ([`map_chunks`]).
pub fn skim_chunks(
    src: &[u8],
    encoding: Encoding,
    chunks: &[Chunk],
    workers: usize,
    macros: &Macros,
    each: impl FnMut(ParsedChunk),
) {
    let skim = |chunk: &Chunk| skim_chunk(src, encoding, chunk, macros);
    // The outline waits for the skim: nothing else runs beside it.
    map_chunks(chunks, workers, WorkerPriority::Normal, skim, each);
}

/// `slots` cut into consecutive runs, one per chunk of `chunks`, a slot
/// per block.
fn runs<'a, T>(mut slots: &'a mut [T], chunks: &[Chunk]) -> Vec<&'a mut [T]> {
    chunks
        .iter()
        .map(|chunk| {
            let (run, rest) = std::mem::take(&mut slots).split_at_mut(chunk.blocks);
            slots = rest;
            run
        })
        .collect()
}

/// The lines of `src[bytes]`: each one's start, its end before the line
/// end, and where the next starts.
pub fn lines_of(
    src: &[u8],
    bytes: Range<usize>,
) -> impl Iterator<Item = (usize, usize, usize)> + '_ {
    let mut start = bytes.start;
    std::iter::from_fn(move || {
        (start < bytes.end).then(|| {
            let line = line_at(src, start, bytes.end);
            start = line.2;
            line
        })
    })
}

/// The line of `src` starting at `start`, before `limit`: its start, its
/// end before the line end, and where the next starts.
fn line_at(src: &[u8], start: usize, limit: usize) -> (usize, usize, usize) {
    let end = memchr::memchr(b'\n', &src[start..limit]).map_or(limit, |p| start + p + 1);
    let text_end = if src[end - 1] == b'\n' { end - 1 } else { end };
    (start, text_end, end)
}

/// Whether every line of `src` is blank or a comment: nothing but blanks
/// ([`is_blank`]) before a line end or a `;`.
/// A chunk asks this of the lines before it when it meets a header: the
/// header is the file's only if nothing else came first, whichever chunk
/// it falls in. The scan stops at the first other line, mostly the first.
fn blank_or_comment_lines(src: &[u8]) -> bool {
    let mut at = 0;
    while at < src.len() {
        match src[at] {
            b'\n' => at += 1,
            b if is_blank(b) => at += 1,
            b';' => match memchr::memchr(b'\n', &src[at..]) {
                Some(end) => at += end + 1,
                None => return true,
            },
            _ => return false,
        }
    }
    true
}

/// Lines of `src`, counting a last line without a line end.
fn line_count(src: &[u8]) -> usize {
    memchr::memchr_iter(b'\n', src).count() + usize::from(src.last().is_some_and(|&b| b != b'\n'))
}

/// Cuts `src` into `threads` chunks of whole lines of about as many bytes
/// each (fewer where lines are long).
fn split(src: &[u8], threads: usize) -> Vec<Chunk> {
    let threads = threads.max(1);
    let mut chunks = Vec::with_capacity(threads);
    let mut start = 0usize;
    let mut first_block = 0usize;
    for i in 1..=threads {
        let end = if i == threads {
            src.len()
        } else {
            let target = (src.len() * i / threads).max(start);
            match src[target..].iter().position(|&b| b == b'\n') {
                Some(p) => target + p + 1,
                None => src.len(),
            }
        };
        if end > start {
            let blocks = line_count(&src[start..end]);
            chunks.push(Chunk {
                bytes: start..end,
                first_block,
                blocks,
            });
            first_block += blocks;
            start = end;
        }
    }
    if chunks.is_empty() {
        // No bytes: one empty chunk, as `gcodec_stream::chunks` gives.
        chunks.push(Chunk {
            bytes: 0..0,
            first_block: 0,
            blocks: 0,
        });
    }
    chunks
}

/// What reading a chunk found besides its blocks.
struct ChunkFindings {
    header: Option<Header>,
    path: Option<PathDirective>,
    diagnostics: Diagnostics,
    /// Blocks holding a structure statement, by index in the program.
    structure_blocks: Vec<u32>,
}

/// Reads the lines of `chunk` into `blocks`, one per line, and writes
/// every slot of `blocks`.
fn read_chunk_into(
    src: &[u8],
    chunk: &Chunk,
    blocks: &mut [MaybeUninit<Block>],
    How {
        reading,
        macros,
        encoding,
    }: How<'_>,
) -> ChunkFindings {
    let mut driver = Driver {
        src,
        macros,
        encoding,
        reading,
        plain_lines_skimmable: false,
        chunk_start: chunk.bytes.start,
        first_block: chunk.first_block as u32,
        blocks,
        filled: 0,
        content_seen: false,
        header: None,
        path: None,
        diagnostics: Diagnostics::new(),
        structure_blocks: Vec::new(),
        tokens: Vec::with_capacity(token_room(chunk, reading)),
        // A caller parsing a few lines at a time (`parse_chunk_of_lexed_lines`)
        // makes no room for more.
        lines: Vec::with_capacity(FLUSH_LINES.min(chunk.blocks)),
        line_ends: Vec::new(),
    };
    if reading == Reading::Skim {
        driver.run_skim(chunk.bytes.clone());
    } else {
        driver.run(chunk.bytes.clone());
    }
    debug_assert_eq!(driver.filled, driver.blocks.len(), "one block per line");
    // Should a chunk ever hold fewer blocks than lines, the rest are
    // empty blocks: every slot is written either way.
    for slot in &mut driver.blocks[driver.filled..] {
        slot.write(Block::default());
    }
    ChunkFindings {
        header: driver.header,
        path: driver.path,
        diagnostics: driver.diagnostics,
        structure_blocks: driver.structure_blocks,
    }
}

/// Room for a chunk's tokens up to its first flush: a token per three
/// bytes, as lines of short words (`G1 X1.5 Y2 F100`) have them (real
/// programs' lines mostly fewer); growing the buffer copies all of it. A
/// skim reads the lines it parses one at a time.
fn token_room(chunk: &Chunk, reading: Reading) -> usize {
    match reading {
        Reading::Skim => 64,
        _ => chunk.bytes.len().min(FLUSH_BYTES_BOUND) / 3 + 64,
    }
}

/// One line waiting for the grammar.
struct Line {
    tokens: std::ops::Range<usize>,
    start: u32,
    end: u32,
    comment: Option<(u32, u32)>,
    header: Option<(u32, u32)>,
    /// A lexical problem already reported: the grammar is not run.
    broken: bool,
    /// The block, where the line was read from its bytes
    /// ([`word_line`]) rather than lexed.
    read: Option<Block>,
}

/// How the driver reads each line.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Reading {
    /// With the block grammar only: the reference the fast path is
    /// tested against.
    GrammarOnly,
    /// With the fast path where it applies, else the grammar.
    Whole,
    /// As [`Reading::Whole`], for lines known to be no word lines: every
    /// line is lexed.
    Lexed,
    /// As [`skim_chunk`] reads it: a plain line after a block that leaves
    /// the plain lines after it skimmable is not lexed beyond its skip
    /// mark and number.
    Skim,
}

struct Driver<'s, 'b> {
    src: &'s [u8],
    /// The macros each line is expanded with.
    macros: &'b Macros,
    /// What the bytes of comments and strings are read in.
    encoding: Encoding,
    reading: Reading,
    /// The last block parsed leaves the plain lines after it skimmable
    /// ([`plain_lines_skimmable_after`]).
    plain_lines_skimmable: bool,
    /// Where the chunk starts in the file: a header in a later chunk is
    /// the file's only if every line before the chunk is blank or a
    /// comment, as in the first ([`blank_or_comment_lines`]).
    chunk_start: usize,
    /// The index in the program of the chunk's first block.
    first_block: u32,
    /// Slots for this chunk's blocks, one per line, written in order:
    /// the first `filled` are initialised.
    blocks: &'b mut [MaybeUninit<Block>],
    filled: usize,
    /// A line other than a blank line or a comment has been seen: words,
    /// a label, a skip mark, anything with an error.
    content_seen: bool,
    header: Option<Header>,
    path: Option<PathDirective>,
    diagnostics: Diagnostics,
    structure_blocks: Vec<u32>,
    tokens: Vec<Spanned>,
    lines: Vec<Line>,
    /// The line ends of a run of plain lines being skimmed.
    line_ends: Vec<u32>,
}

impl<'s> Driver<'s, '_> {
    /// The grammar's view of the file's own bytes.
    fn ctx(&self) -> Ctx<'s> {
        Ctx::new(self.src, self.encoding)
    }

    /// Skims the lines of `bytes` (see [`skim_chunk`]): a plain line while
    /// plain lines are skimmable becomes a block of its span, skip mark
    /// and number; every other line is parsed, one at a time, since
    /// whether it leaves the plain lines after it skimmable decides how
    /// the next is read.
    fn run_skim(&mut self, bytes: Range<usize>) {
        let src = self.src;
        let mut at = bytes.start;
        while at < bytes.end {
            let skimmable = self.plain_lines_skimmable && self.macros.is_empty();
            if skimmable {
                // The lines up to the first that may not be plain are
                // judged at once.
                let mut line_ends = std::mem::take(&mut self.line_ends);
                line_ends.clear();
                let plain_end = at + plain_lines(&src[at..bytes.end], &mut line_ends);
                let skimmed =
                    (plain_end > at).then(|| self.skim_plain_lines(at, plain_end, &line_ends));
                self.line_ends = line_ends;
                if let Some(stopped) = skimmed {
                    at = stopped;
                    continue;
                }
            }
            let (start, text_end, end) = line_at(src, at, bytes.end);
            let line = &src[start..text_end];
            let left_out = (skimmable && is_plain(line))
                .then(|| self.plain_block(start, text_end))
                .flatten();
            match left_out {
                Some(block) => self.skimmed(block),
                None => self.run(start..end),
            }
            at = end;
        }
    }

    /// Skims the lines from `start` to `end`, each plain, while plain
    /// lines are skimmable; `line_ends` holds their line ends' offsets
    /// from `start` (the last line may have none). Returns where it
    /// stopped: `end`, or the end of a line whose skip mark or number was
    /// not plain, parsed (which may leave the lines after it not
    /// skimmable).
    fn skim_plain_lines(&mut self, start: usize, end: usize, line_ends: &[u32]) -> usize {
        let lines = line_ends.iter().map(|&line_end| {
            let line_end = start + line_end as usize;
            (line_end, line_end + 1)
        });
        // A last line without a line end.
        let last = line_ends.last().map_or(start, |&e| start + e as usize + 1);
        let last = (last < end).then_some((end, end));
        let mut line_start = start;
        for (text_end, next) in lines.chain(last) {
            match self.plain_block(line_start, text_end) {
                Some(block) => self.skimmed(block),
                None => {
                    self.run(line_start..next);
                    return next;
                }
            }
            line_start = next;
        }
        end
    }

    /// The next slot takes a skimmed block, which leaves
    /// `plain_lines_skimmable` as it was.
    fn skimmed(&mut self, block: Block) {
        if let Some(slot) = self.blocks.get_mut(self.filled) {
            slot.write(block);
            self.filled += 1;
        }
    }

    /// The block of the plain line `start..end`, lexed only as far as its
    /// skip mark and block number; `None` where those are not plain.
    fn plain_block(&self, start: usize, end: usize) -> Option<Block> {
        let src = self.src;
        let block = |skip: Option<SkipLevel>, number| Block {
            span: Span::new(start as u32, trim_cr(src, start as u32, end as u32)),
            skip: skip.map(Box::new),
            number,
            label: None,
            statements: Box::default(),
            comment: None,
            depth: 0,
        };
        match simple_number(&src[start..end]) {
            Some(Simple::Nothing) => return Some(block(None, None)),
            Some(Simple::Number { at, len, value }) => {
                let span = Span::new((start + at) as u32, (start + at + len) as u32);
                let number = BlockNumber {
                    span,
                    main: false,
                    value,
                };
                return Some(block(None, Some(number)));
            }
            None => {}
        }
        // The prefix is at most `/`, a level, `N`, a number and a `=`.
        let mut tokens = [(TokenKind::Error, SimpleSpan::from(0..0)); 5];
        let mut count = 0;
        for token in Lexer::new(&src[start..end])
            .filter(|t| kept(t.kind))
            .take(5)
        {
            let (s, e) = (start + token.start as usize, start + token.end as usize);
            tokens[count] = (token.kind, SimpleSpan::from(s..e));
            count += 1;
        }
        let prefix = fast::prefix(&tokens[..count], &self.ctx())?;
        Some(block(prefix.skip, prefix.number))
    }

    /// Parses the lines of `bytes`.
    fn run(&mut self, bytes: Range<usize>) {
        // Macros may stand for anything, even a letter's word.
        if self.reading == Reading::Whole && self.macros.is_empty() {
            self.read_word_lines(bytes);
        } else {
            self.lex_lines(bytes);
        }
        self.flush();
    }

    /// Reads the lines of `bytes` that hold only constant DIN words
    /// straight from their bytes ([`word_line`]) and lexes the others, a
    /// run of them at a time; the lines wait for the flush in order.
    fn read_word_lines(&mut self, bytes: Range<usize>) {
        let src = self.src;
        let mut unlexed = bytes.start;
        for (start, text_end, end) in lines_of(src, bytes.clone()) {
            if let Some(block) = word_line::read(src, start, text_end) {
                if unlexed < start {
                    self.lex_lines(unlexed..start);
                }
                self.lines.push(Line {
                    tokens: self.tokens.len()..self.tokens.len(),
                    start: start as u32,
                    end: text_end as u32,
                    comment: None,
                    header: None,
                    broken: false,
                    read: Some(block),
                });
                if self.lines.len() >= FLUSH_LINES {
                    self.flush();
                }
                unlexed = end;
            }
        }
        if unlexed < bytes.end {
            self.lex_lines(unlexed..bytes.end);
        }
    }

    /// Lexes the lines of `bytes` into the waiting lines, flushing them
    /// when there are [`FLUSH_LINES`].
    fn lex_lines(&mut self, bytes: Range<usize>) {
        let src = self.src;
        let base = bytes.start as u32;
        // Lines read from their bytes may wait before these: the tokens
        // are appended to the buffer as it is.
        let first_token = self.tokens.len();
        let mut line = Line {
            tokens: first_token..first_token,
            start: base,
            end: base,
            comment: None,
            header: None,
            broken: false,
            read: None,
        };
        for mut tok in Lexer::new(&src[bytes.start..bytes.end]) {
            tok.start += base;
            tok.end += base;
            match tok.kind {
                TokenKind::Whitespace => {}
                TokenKind::Comment => {
                    line.comment = Some((tok.start, trim_cr(src, tok.start, tok.end)))
                }
                TokenKind::Newline => {
                    line.end = tok.start;
                    line.tokens.end = self.tokens.len();
                    let next = Line {
                        tokens: self.tokens.len()..self.tokens.len(),
                        start: tok.end,
                        end: tok.end,
                        comment: None,
                        header: None,
                        broken: false,
                        read: None,
                    };
                    self.lines.push(std::mem::replace(&mut line, next));
                    if self.lines.len() >= FLUSH_LINES {
                        self.flush();
                        // The buffer starts afresh for the line just begun.
                        line.tokens = 0..0;
                    }
                }
                TokenKind::Header if self.tokens.len() == line.tokens.start && !line.broken => {
                    line.header = Some((tok.start, trim_cr(src, tok.start, tok.end)));
                }
                TokenKind::Error
                | TokenKind::Header
                | TokenKind::BadQuoted
                | TokenKind::UnclosedString => {
                    if !line.broken {
                        let span = Span::new(tok.start, tok.end);
                        let error = lexical_error(tok.kind, span, src, self.encoding);
                        self.diagnostics.push(error);
                        line.broken = true;
                    }
                }
                // Nothing follows a header on its line: the lexer reads the
                // header to the line end.
                kind => {
                    self.tokens
                        .push((kind, SimpleSpan::from(tok.start as usize..tok.end as usize)));
                }
            }
        }
        // The last line has no line end.
        line.end = bytes.end as u32;
        line.tokens.end = self.tokens.len();
        if line.start < line.end {
            self.lines.push(line);
        }
    }

    /// The expansion of the macros in a lexed line, if it uses any (a
    /// line with a lexical problem is not expanded).
    fn expansion(
        &self,
        line: &Line,
        line_tokens: &[Spanned],
    ) -> Option<Result<Expanded, crate::macros::ExpansionError>> {
        if line.broken {
            return None;
        }
        Expanded::line(self.src, (line.start, line.end), line_tokens, self.macros)
    }

    /// Parses the buffered lines and empties the buffers.
    fn flush(&mut self) {
        let mut lines = std::mem::take(&mut self.lines);
        let mut tokens = std::mem::take(&mut self.tokens);
        {
            let ctx = self.ctx();
            // Built only when a block needs it: most take the fast path,
            // and a skim flushes line by line.
            let parser = std::cell::LazyCell::new(|| grammar::block(ctx));
            for line in &mut lines {
                let line_tokens = &tokens[line.tokens.clone()];
                // A header line is no content: a second header is
                // misplaced because of the first.
                self.content_seen |= line.read.is_some() || !line_tokens.is_empty() || line.broken;
                let block = if let Some(block) = line.read.take() {
                    block
                } else if let Some(expanded) = self.expansion(line, line_tokens) {
                    self.parse_expanded_line(line, line_tokens, expanded)
                } else {
                    self.parse_line(line, line_tokens, &ctx, &parser, line.end as usize)
                };
                if block
                    .statements
                    .iter()
                    .any(|s| structure::is_paired_statement(&s.kind))
                {
                    self.structure_blocks
                        .push(self.first_block + self.filled as u32);
                }
                if self.reading == Reading::Skim {
                    self.plain_lines_skimmable = plain_lines_skimmable_after(&block);
                }
                if let Some(slot) = self.blocks.get_mut(self.filled) {
                    slot.write(block);
                    self.filled += 1;
                }
            }
        }
        lines.clear();
        tokens.clear();
        self.lines = lines;
        self.tokens = tokens;
    }

    /// A line whose macros are expanded: parsed from its expansion, with
    /// each diagnostic inside an expansion naming the macro. A line whose
    /// expansion does not end is reported and parsed as a block in error.
    fn parse_expanded_line(
        &mut self,
        line: &Line,
        line_tokens: &[Spanned],
        expanded: Result<Expanded, crate::macros::ExpansionError>,
    ) -> Block {
        let expanded = match expanded {
            Ok(expanded) => expanded,
            Err(error) => {
                self.diagnostics.push(error.diagnostic());
                let broken = Line {
                    tokens: line.tokens.clone(),
                    broken: true,
                    read: None,
                    ..*line
                };
                let ctx = self.ctx();
                let parser = std::cell::LazyCell::new(|| grammar::block(ctx));
                return self.parse_line(&broken, line_tokens, &ctx, &parser, line.end as usize);
            }
        };
        let first = self.diagnostics.len();
        if let Some(&(kind, span)) = expanded.tokens.iter().find(|t| is_lexical_error(t.0)) {
            let mut d = lexical_error(
                kind,
                Span::new(span.start as u32, span.end as u32),
                &expanded.bytes,
                self.encoding,
            );
            for label in &mut d.labels {
                label.span = expanded.map_span(SimpleSpan::from(label.span.range()));
            }
            self.diagnostics.push(d);
        }
        let broken = self.diagnostics.len() > first;
        let ctx = Ctx::expanded(&expanded, self.encoding);
        let parser = std::cell::LazyCell::new(|| grammar::block(ctx));
        let this = Line {
            tokens: line.tokens.clone(),
            broken,
            read: None,
            ..*line
        };
        let mut eoi = expanded.bytes.len();
        if expanded.bytes.last() == Some(&b'\r') {
            eoi -= 1;
        }
        let block = self.parse_line(&this, &expanded.tokens, &ctx, &parser, eoi);
        for d in &mut self.diagnostics[first..] {
            let note = d.span().and_then(|span| expanded.note(span, self.macros));
            if let Some((at, note)) = note {
                d.labels.push(gcodec_source::Label {
                    span: at,
                    message: Some(note.into()),
                });
            }
        }
        block
    }

    fn parse_line<'t, P>(
        &mut self,
        line: &Line,
        tokens: &'t [Spanned],
        ctx: &Ctx<'_>,
        parser: &impl std::ops::Deref<Target = P>,
        eoi: usize,
    ) -> Block
    where
        P: chumsky::Parser<'t, grammar::In<'t>, grammar::BlockBody, grammar::Ex>,
    {
        let mut end = line.end;
        if end > line.start && self.src[end as usize - 1] == b'\r' {
            end -= 1;
        }
        let mut block = Block {
            span: Span::new(line.start, end),
            skip: None,
            number: None,
            label: None,
            statements: Box::default(),
            comment: line.comment.map(|(s, e)| Comment {
                span: Span::new(s, e),
                text: self
                    .ctx()
                    .decode_text(&self.src[s as usize + 1..e as usize]),
            }),
            depth: 0,
        };
        if let Some(c) = &block.comment {
            self.note_path_directive(c);
        }
        if let Some((s, e)) = line.header {
            self.note_header(Span::new(s, e));
        }
        if line.broken || tokens.is_empty() {
            return with_prefix(block, tokens, ctx);
        }
        if let Some(op) = too_many_operators(tokens) {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::parse::BLOCK_TOO_COMPLEX,
                    format!("more than {MAX_OPERATORS_PER_BLOCK} operators in one block"),
                )
                .with_label(ctx.span(op), "this operator is over the limit")
                .with_help(
                    "split the calculation over several blocks using intermediate variables",
                ),
            );
            return with_prefix(block, tokens, ctx);
        }
        if let Some(deep) = too_deep(tokens) {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::parse::NESTING_TOO_DEEP,
                    format!("brackets nested more than {MAX_EXPRESSION_DEPTH} deep in one block"),
                )
                .with_label(ctx.span(deep), "this bracket is too deep")
                .with_help("split the expression using intermediate variables"),
            );
            return with_prefix(block, tokens, ctx);
        }
        if let Some(misspelt) = Misspelt::in_tokens(tokens, ctx) {
            self.diagnostics.push(misspelt.diagnostic());
            return with_prefix(block, tokens, ctx);
        }
        if self.reading != Reading::GrammarOnly
            && let Some(body) = fast::block(tokens, ctx)
        {
            block.skip = body.skip.map(Box::new);
            block.number = body.number;
            block.statements = self.checked(body.statements);
            return block;
        }
        let eoi = SimpleSpan::from(eoi..eoi);
        let (body, errors) = parser
            .parse(tokens.split_token_span(eoi))
            .into_output_errors();
        // A specific diagnosis (emitted by `validate`) explains more than
        // the generic error it may have caused further on.
        let first = errors.iter().position(|e| e.custom.is_some()).unwrap_or(0);
        match (body, errors.into_iter().nth(first)) {
            (Some(body), None) => {
                block.skip = body.skip.map(Box::new);
                block.number = body.number;
                block.label = body.label.map(Box::new);
                block.statements = self.checked(body.statements);
            }
            (_, Some(error)) => {
                self.diagnostics.push(syntax_diagnostic(error, ctx));
                block = with_prefix(block, tokens, ctx);
            }
            (None, None) => {}
        }
        block
    }

    fn note_header(&mut self, span: Span) {
        let text = self
            .encoding
            .decode(&self.src[span.start as usize + 1..span.end as usize]);
        let text = text.trim_end();
        if self.header.is_some()
            || self.content_seen
            || !blank_or_comment_lines(&self.src[..self.chunk_start])
        {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::parse::MISPLACED_HEADER,
                    "a `%` program header may only open the file",
                )
                .with_label(span, "header after the program started")
                .with_help("one file holds one program; split the file or remove the line"),
            );
            return;
        }
        let (program, file_type) = split_internal_name(text);
        self.header = Some(Header {
            span,
            text: text.into(),
            program,
            file_type,
        });
    }

    fn note_path_directive(&mut self, comment: &Comment) {
        let text = comment.text.trim_end();
        let is_path = text
            .get(..6)
            .is_some_and(|p| p.eq_ignore_ascii_case("$PATH="));
        if self.path.is_none() && is_path {
            self.path = Some(PathDirective {
                span: comment.span,
                path: text[6..].into(),
            });
        }
    }

    /// Checks that need a block's whole statement list.
    /// Checks a block's statements and stores them at their exact size.
    fn checked(&mut self, mut statements: Vec<Statement>) -> Box<[Statement]> {
        self.check_statements(&mut statements);
        statements.into_boxed_slice()
    }

    fn check_statements(&mut self, statements: &mut Vec<Statement>) {
        // A value after `=` ends at a blank: `R3=200G0` is not two statements.
        for pair in statements.windows(2) {
            let ends_in_value = match &pair[0].kind {
                StatementKind::Assign(_) => true,
                StatementKind::Word(w) => {
                    matches!(*w.value(pair[0].span), WordValue::Assigned { .. })
                }
                _ => false,
            };
            if ends_in_value && pair[1].span.start == pair[0].span.end {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::parse::MISSING_SEPARATOR,
                        "a value after `=` must be followed by a blank before the next word",
                    )
                    .with_label(pair[1].span, "touches the value before it")
                    .with_help("insert a blank, e.g. `R3=200 G0`"),
                );
            }
        }
        // `NAME P3`, `L12 P=2`: the P word counts the call's passes.
        let calls = statements
            .iter()
            .filter(|s| matches!(s.kind, StatementKind::Call(_)))
            .count();
        if calls == 1 {
            let p = statements.iter().position(|s| {
                matches!(&s.kind, StatementKind::Word(w) if w.address() == "P" && w.extension().is_none())
            });
            if let Some(p) = p {
                let word = statements.remove(p);
                let word_span = word.span;
                if let (StatementKind::Word(w), Some(call)) = (
                    word.kind,
                    statements
                        .iter_mut()
                        .find(|s| matches!(s.kind, StatementKind::Call(_))),
                ) {
                    call.span = call.span.cover(word_span);
                    if let StatementKind::Call(c) = &mut call.kind {
                        c.passes = Some(Box::new(SpannedWord {
                            span: word_span,
                            word: w,
                        }));
                    }
                }
            }
        }
    }
}

/// `block`, whose statements could not be read, with the skip mark, block
/// number and label its tokens open with, as the grammar reads them
/// (SPEC §7): a jump to the number or label finds the block (and the run
/// stops there, at the error), as the control's search finds it.
fn with_prefix(mut block: Block, tokens: &[Spanned], ctx: &Ctx<'_>) -> Block {
    use TokenKind as T;
    let prefix = fast::prefix(tokens, ctx).or_else(|| {
        // A skip mark in error (`/ 5`, `/12`): what follows still counts.
        let [(T::Slash, _), (T::Number, _), after @ ..] = tokens else {
            return None;
        };
        let mut prefix = fast::prefix(after, ctx)?;
        prefix.rest += 2;
        Some(prefix)
    });
    let Some(prefix) = prefix else {
        return block;
    };
    block.skip = prefix.skip.map(Box::new);
    block.number = prefix.number;
    let mut rest = &tokens[prefix.rest..];
    if block.number.is_none()
        && let [(T::Colon, colon), (T::Number, n), after @ ..] = rest
    {
        let Ok(value) = ctx.text(*n).parse::<u64>() else {
            return block;
        };
        block.number = Some(BlockNumber {
            span: ctx.span(SimpleSpan::from(colon.start..n.end)),
            main: true,
            value,
        });
        rest = after;
    }
    if let [(T::Ident, name), (T::Colon, colon), ..] = rest {
        block.label = Some(Box::new(LabelDef {
            span: ctx.span(SimpleSpan::from(name.start..colon.end)),
            name: CompactString::from(ctx.text(*name)),
        }));
    }
    block
}

/// Whether a skim may leave out the statements of the plain lines after
/// `block` (see [`skim_chunk`]): it has statements, and none of them
/// defines, declares or ends anything.
pub fn plain_lines_skimmable_after(block: &Block) -> bool {
    !block.statements.is_empty()
        && block.statements.iter().all(|s| match &s.kind {
            StatementKind::Def(_)
            | StatementKind::Redef(_)
            | StatementKind::Define(_)
            | StatementKind::Proc(_)
            | StatementKind::EndProc
            | StatementKind::Extern(_)
            | StatementKind::Ret(_) => false,
            StatementKind::Word(w) => w.address() != "M",
            _ => true,
        })
}

/// Whether `line` (without its line end) is plain (see [`skim_chunk`]),
/// judged from its bytes alone: a label, keyword, `M` word, string or
/// system variable shows in the bytes before its first `;`. A keyword is
/// a whole run of letters there, since the lexer starts a name only after
/// a byte that is no letter and ends it only before one.
pub(crate) fn is_plain(line: &[u8]) -> bool {
    // The line ends at the comment's `;`, found in the same pass.
    let mut i = 0;
    while i < line.len() {
        match PLAIN_BYTES[usize::from(line[i])] {
            Plain::Yes => i += 1,
            Plain::Comment => return true,
            Plain::Name => {
                let start = i;
                while i < line.len() && PLAIN_BYTES[usize::from(line[i])] == Plain::Name {
                    i += 1;
                }
                let plain = match &line[start..i] {
                    [b'M' | b'm' | b'_'] => false,
                    [_] => true,
                    name => is_plain_name(name) && !is_misspelt_closer(name),
                };
                if !plain {
                    return false;
                }
            }
            // A point belongs to a number: `1.5`, `.5`, `1.`.
            Plain::Point => {
                let digit = |j: usize| line.get(j).is_some_and(u8::is_ascii_digit);
                if !(i > 0 && digit(i - 1) || digit(i + 1)) {
                    return false;
                }
                i += 1;
            }
            Plain::No => return false,
        }
    }
    true
}

/// What a byte is to [`is_plain`].
#[derive(Clone, Copy, PartialEq, Eq)]
enum Plain {
    /// A digit, blank or operator.
    Yes,
    /// A letter or `_`: part of a name or keyword.
    Name,
    /// `.`: plain in a number.
    Point,
    /// `;`: the rest is a comment.
    Comment,
    /// A label's `:`, a string, a system variable, a header, or a byte
    /// that starts no token.
    No,
}

const PLAIN_BYTES: [Plain; 256] = {
    let mut table = [Plain::No; 256];
    let mut b = 0;
    while b < 256 {
        let c = b as u8;
        table[b] = if c.is_ascii_alphabetic() || c == b'_' {
            Plain::Name
        } else if c == b'.' {
            Plain::Point
        } else if c == b';' {
            Plain::Comment
        } else if c.is_ascii_digit()
            || is_blank(c)
            || matches!(
                c,
                b'=' | b'<' | b'>' | b'+' | b'-' | b'*' | b'/' | b'(' | b')' | b'[' | b']' | b','
            )
        {
            Plain::Yes
        } else {
            Plain::No
        };
        b += 1;
    }
    table
};

/// A byte the lexer reads as a blank (`TokenKind::Whitespace`).
const fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | 0x0b | 0x0c | b'&')
}

/// How a plain line opens, read from its bytes where that is plain to
/// see (else [`Driver::plain_block`] lexes it).
enum Simple {
    /// Neither a skip mark nor a block number: the first byte after the
    /// blanks starts neither `/` nor `N`.
    Nothing,
    /// `N<digits>`, ended by a blank, `;` or the line's end, and not
    /// followed by `=`: at `at`, `len` bytes long.
    Number { at: usize, len: usize, value: u64 },
}

/// The common openings of a plain line, as the lexer and
/// [`fast::prefix`] read them; `None` for any other.
fn simple_number(line: &[u8]) -> Option<Simple> {
    let at = line
        .iter()
        .position(|&b| !is_blank(b))
        .unwrap_or(line.len());
    match line.get(at) {
        Some(b'N' | b'n') => {}
        Some(b'/') => return None,
        _ => return Some(Simple::Nothing),
    }
    let digits = line[at + 1..]
        .iter()
        .take_while(|b| b.is_ascii_digit())
        .count();
    let after = at + 1 + digits;
    // A point or exponent would continue the number; a letter after `N`
    // makes a name.
    if digits == 0 || !line.get(after).is_none_or(|&b| is_blank(b) || b == b';') {
        return None;
    }
    let next = line[after..]
        .iter()
        .position(|&b| !is_blank(b))
        .map(|p| after + p);
    if let Some(p) = next
        && line[p] == b'='
        && line.get(p + 1) != Some(&b'=')
    {
        return None;
    }
    let value = fast::whole_number(&line[at + 1..after])?;
    Some(Simple::Number {
        at,
        len: 1 + digits,
        value,
    })
}

/// Whether a run of two or more letters is a name or an operator, not a
/// keyword of statements.
fn is_plain_name(name: &[u8]) -> bool {
    use TokenKind as T;
    let mut tokens = Lexer::new(name);
    let Some(token) = tokens.next() else {
        return false;
    };
    token.end as usize == name.len()
        && (matches!(token.kind, T::Ident | T::True | T::False)
            || operators::is_word_operator(token.kind))
}

/// A name that misspells a closer (`ENDIFF`) is no plain line's: pairing
/// must see it to name it when its structure is left unclosed.
fn is_misspelt_closer(name: &[u8]) -> bool {
    std::str::from_utf8(name)
        .ok()
        .and_then(structure::near_closer)
        .is_some()
}

/// Whether the driver keeps a token of `kind` for the grammar.
fn kept(kind: TokenKind) -> bool {
    !matches!(
        kind,
        TokenKind::Whitespace
            | TokenKind::Newline
            | TokenKind::Comment
            | TokenKind::Header
            | TokenKind::Error
            | TokenKind::BadQuoted
            | TokenKind::UnclosedString
    )
}

/// The end of a to-end-of-line token without the CR of a CRLF line end.
fn trim_cr(src: &[u8], start: u32, end: u32) -> u32 {
    if end > start && src[end as usize - 1] == b'\r' {
        end - 1
    } else {
        end
    }
}

/// `_N_SHAFT_MPF` → (`SHAFT`, `MPF`); `MPF123` → (None, None).
fn split_internal_name(text: &str) -> (Option<CompactString>, Option<CompactString>) {
    let Some(rest) = text
        .get(..3)
        .filter(|p| p.eq_ignore_ascii_case("_N_"))
        .map(|_| &text[3..])
    else {
        return (None, None);
    };
    match rest.rfind('_') {
        Some(i) if i > 0 && i + 1 < rest.len() => (
            Some(rest[..i].into()),
            Some(rest[i + 1..].to_ascii_uppercase().into()),
        ),
        _ => (Some(rest.into()), None),
    }
}

/// The first operator past [`MAX_OPERATORS_PER_BLOCK`], if any.
fn too_many_operators(tokens: &[Spanned]) -> Option<SimpleSpan> {
    use TokenKind as T;
    let mut count = 0;
    for (i, (kind, span)) in tokens.iter().enumerate() {
        let is_operator = match kind {
            // `X-10`: a sign touching its letter and number is part of a word.
            T::Plus | T::Minus => {
                let after_letter =
                    i > 0 && tokens[i - 1].0 == T::Letter && tokens[i - 1].1.end == span.start;
                let before_number = tokens
                    .get(i + 1)
                    .is_some_and(|(k, s)| *k == T::Number && s.start == span.end);
                !(after_letter && before_number)
            }
            kind => operators::is_operator(*kind),
        };
        if is_operator {
            count += 1;
            if count > MAX_OPERATORS_PER_BLOCK {
                return Some(*span);
            }
        }
    }
    None
}

/// The first bracket deeper than [`MAX_EXPRESSION_DEPTH`], if any.
fn too_deep(tokens: &[Spanned]) -> Option<SimpleSpan> {
    let mut depth = 0usize;
    for (kind, span) in tokens {
        match kind {
            TokenKind::LParen | TokenKind::LBracket => {
                depth += 1;
                if depth > MAX_EXPRESSION_DEPTH {
                    return Some(*span);
                }
            }
            TokenKind::RParen | TokenKind::RBracket => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

/// Tokens that cannot be part of any block (see [`lexical_error`]).
fn is_lexical_error(kind: TokenKind) -> bool {
    matches!(
        kind,
        TokenKind::Error | TokenKind::Header | TokenKind::BadQuoted | TokenKind::UnclosedString
    )
}

/// Diagnoses a token that cannot be part of any block; the block is then
/// reported without running the grammar.
fn lexical_error(kind: TokenKind, span: Span, src: &[u8], encoding: Encoding) -> Diagnostic {
    let text = encoding.decode(&src[span.range()]);
    match kind {
        TokenKind::UnclosedString => Diagnostic::new(
            codes::parse::UNCLOSED_STRING,
            "string is not closed on its line",
        )
        .with_label(span, "opened here")
        .with_help("add the closing `\"`; strings cannot span blocks"),
        TokenKind::BadQuoted => {
            let (what, help) = match text.as_bytes().get(1).map(u8::to_ascii_uppercase) {
                Some(b'H') => (
                    "hex constant",
                    "hex constants are written 'H' followed by the digits 0-9 and A-F, e.g. 'H1F'",
                ),
                Some(b'B') => (
                    "binary constant",
                    "binary constants are written 'B' followed by 0 and 1, e.g. 'B101'",
                ),
                _ => (
                    "constant",
                    "quoted constants are hex ('H1F') or binary ('B101'); strings use double quotes",
                ),
            };
            Diagnostic::new(
                codes::parse::INVALID_NUMBER,
                format!("malformed {what} `{text}`"),
            )
            .with_label(span, "here")
            .with_help(help)
        }
        TokenKind::Header => Diagnostic::new(
            codes::parse::MISPLACED_HEADER,
            "`%` may only start a program header line",
        )
        .with_label(span, "here")
        .with_help("a header line looks like `%_N_NAME_MPF` and stands alone on the first line"),
        _ => {
            let byte = src.get(span.start as usize).copied().unwrap_or(0);
            if byte == b'!'
                && let Some(misspelt) = Misspelt::around_bang(src, span.start as usize)
            {
                return misspelt.diagnostic();
            }
            let shown = if byte.is_ascii_graphic() {
                format!("`{}`", byte as char)
            } else {
                format!("byte 0x{byte:02X}")
            };
            let help = match byte {
                b'?' | b'!' => "`?` and `!` are reserved characters in SINUMERIK programs",
                b'$' => "system variables are written `$` followed by their name, e.g. `$P_UIFR`",
                b'_' => "names are at least two characters long, e.g. `_A`",
                _ => "comments start with `;`; this character is not part of the NC language",
            };
            Diagnostic::new(
                codes::parse::INVALID_CHARACTER,
                format!("invalid character {shown}"),
            )
            .with_label(span, "not allowed here")
            .with_help(help)
        }
    }
}

fn syntax_diagnostic(error: SyntaxError, ctx: &Ctx<'_>) -> Diagnostic {
    let span = ctx.span(error.span);
    if let Some(custom) = error.custom {
        let mut d = Diagnostic::new(custom.code, custom.message).with_label(span, "here");
        d.help = custom.help;
        return d;
    }
    let found = match error.found {
        Some(kind) => format!("unexpected {}", kind.describe()),
        None => "unexpected end of block".to_owned(),
    };
    let expected: Vec<&str> = error
        .label
        .into_iter()
        .chain(error.expected_kinds().map(TokenKind::describe))
        .collect();
    let label = if expected.is_empty() {
        "not valid here".to_owned()
    } else {
        format!("expected {}", join_or(&expected))
    };
    Diagnostic::new(codes::parse::UNEXPECTED_TOKEN, found)
        .with_label(span, label)
        .with_help("each block holds words (`G1 X10`), assignments (`R1=5`), one control statement or calls; see SPEC.md")
}

fn join_or(items: &[&str]) -> String {
    match items {
        [] => String::new(),
        [one] => (*one).to_owned(),
        [init @ .., last] => format!("{} or {}", init.join(", "), last),
    }
}
