//! Parses one file and reports what it took: the measuring tool behind
//! `docs/performance.md`.
//!
//! ```text
//! cargo run --release -p gcodec-parser --example parse_file -- [--heap] FILE
//! cargo run --release -p gcodec-parser --example parse_file -- --generate BLOCKS FILE
//! cargo run --release -p gcodec-parser --example parse_file -- --sizes
//! ```
//!
//! The first form reads FILE, lexes it once on its own (for the lexer's
//! throughput), then parses it and prints the block count, the diagnostics
//! count and the elapsed times. Run it under `/usr/bin/time -v` for the whole
//! process's wall time and peak RSS. `--heap` also counts the bytes the
//! parser allocates (slower: use it for memory, not for time). `--generate` writes the benchmark's
//! deterministic program of BLOCKS lines to FILE; `--sizes` prints the size
//! of the main AST types.

use std::alloc::{GlobalAlloc, Layout, System};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

use gcodec_parser::ast::*;

#[path = "../benches/program/mod.rs"]
mod program;

/// The system allocator, counting the bytes requested when `--heap` is
/// given: live heap, its peak and the number of allocations (allocator
/// overhead is not included). Counting costs time (two cores update the
/// same counters), so timings are taken without it.
struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);
static CALLS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded to `System` unchanged; the counters are
// only statistics.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !COUNTING.load(Relaxed) {
            // SAFETY: forwarded with the caller's layout.
            return unsafe { System.alloc(layout) };
        }
        let live = LIVE.fetch_add(layout.size(), Relaxed) + layout.size();
        PEAK.fetch_max(live, Relaxed);
        CALLS.fetch_add(1, Relaxed);
        // SAFETY: forwarded with the caller's layout.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        if !COUNTING.load(Relaxed) {
            // SAFETY: forwarded with the caller's pointer and layout.
            return unsafe { System.dealloc(ptr, layout) };
        }
        LIVE.fetch_sub(layout.size(), Relaxed);
        // SAFETY: forwarded with the caller's pointer and layout.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if !COUNTING.load(Relaxed) {
            // SAFETY: forwarded with the caller's pointer, layout and size.
            return unsafe { System.realloc(ptr, layout, new_size) };
        }
        if new_size >= layout.size() {
            let live = LIVE.fetch_add(new_size - layout.size(), Relaxed) + new_size - layout.size();
            PEAK.fetch_max(live, Relaxed);
        } else {
            LIVE.fetch_sub(layout.size() - new_size, Relaxed);
        }
        CALLS.fetch_add(1, Relaxed);
        // SAFETY: forwarded with the caller's pointer, layout and size.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["--sizes"] => {
            sizes();
            ExitCode::SUCCESS
        }
        ["--generate", blocks, path] => {
            let Ok(blocks) = blocks.parse::<usize>() else {
                eprintln!("BLOCKS must be a whole number");
                return ExitCode::FAILURE;
            };
            let bytes = program::generate(blocks);
            if let Err(e) = std::fs::write(path, &bytes) {
                eprintln!("cannot write {path}: {e}");
                return ExitCode::FAILURE;
            }
            println!(
                "wrote {path}: {blocks} blocks, {} bytes ({:.1} bytes/block)",
                bytes.len(),
                bytes.len() as f64 / blocks.max(1) as f64
            );
            ExitCode::SUCCESS
        }
        [path] if !path.starts_with("--") => parse_file(path),
        ["--heap", path] => {
            COUNTING.store(true, Relaxed);
            parse_file(path)
        }
        _ => {
            eprintln!("usage: parse_file [--heap] FILE | --generate BLOCKS FILE | --sizes");
            ExitCode::FAILURE
        }
    }
}

fn parse_file(path: &str) -> ExitCode {
    let start = Instant::now();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) => {
            eprintln!("cannot read {path}: {e}");
            return ExitCode::FAILURE;
        }
    };
    let read = start.elapsed();
    let mb = bytes.len() as f64 / 1e6;

    let t = Instant::now();
    let tokens = gcodec_lexer::Lexer::new(&bytes).count();
    let lex = t.elapsed();

    let before = LIVE.load(Relaxed);
    PEAK.store(before, Relaxed);
    let calls = CALLS.load(Relaxed);
    let t = Instant::now();
    let parsed = gcodec_parser::parse_bytes(path, &bytes);
    let parse = t.elapsed();
    let retained = LIVE.load(Relaxed) - before;
    let peak = PEAK.load(Relaxed) - before;
    let calls = CALLS.load(Relaxed) - calls;

    println!("input:        {} bytes ({mb:.2} MB)", bytes.len());
    println!("tokens:       {tokens}");
    println!("blocks:       {}", parsed.program.blocks.len());
    println!("diagnostics:  {}", parsed.diagnostics.len());
    let blocks = &parsed.program.blocks;
    let statements: usize = blocks.iter().map(|b| b.statements.len()).sum();
    println!(
        "statements:   {statements} ({:.1} MB of statements; blocks: {:.1} MB)",
        (statements * size_of::<Statement>()) as f64 / 1e6,
        (blocks.capacity() * size_of::<Block>()) as f64 / 1e6
    );
    if COUNTING.load(Relaxed) {
        println!(
            "heap:         {:.1} MB kept by the AST ({:.1} bytes/block, {:.1}x input), {:.1} MB peak while parsing, {calls} allocations",
            retained as f64 / 1e6,
            retained as f64 / blocks.len().max(1) as f64,
            retained as f64 / bytes.len().max(1) as f64,
            peak as f64 / 1e6,
        );
    }
    println!("read:         {:.3} s", read.as_secs_f64());
    println!(
        "lex only:     {:.3} s ({:.1} MB/s)",
        lex.as_secs_f64(),
        mb / lex.as_secs_f64()
    );
    println!(
        "lex+parse:    {:.3} s ({:.1} MB/s)",
        parse.as_secs_f64(),
        mb / parse.as_secs_f64()
    );

    let t = Instant::now();
    drop(parsed);
    println!("drop AST:     {:.3} s", t.elapsed().as_secs_f64());
    println!("total:        {:.3} s", start.elapsed().as_secs_f64());
    ExitCode::SUCCESS
}

fn sizes() {
    macro_rules! size {
        ($($t:ty),* $(,)?) => {
            $(println!("{:<16} {:>4} bytes", stringify!($t), std::mem::size_of::<$t>());)*
        };
    }
    size!(
        Block,
        Statement,
        StatementKind,
        Word,
        WordValue,
        Extension,
        Expr,
        ExprKind,
        VarRef,
        Assign,
        Initializer,
        Comment,
        BlockNumber,
        Name,
        // StatementKind payloads: the largest sets the size of every statement.
        Def,
        Redef,
        Define,
        Proc,
        Extern,
        Call,
        IndirectCall,
        PCall,
        MCall,
        Ret,
        Jump,
        IfGoto,
        Condition,
        For,
        RepeatSection,
        Case,
        Frame,
        SyncAction,
        gcodec_source::Span,
        gcodec_source::Diagnostic,
    );
}
