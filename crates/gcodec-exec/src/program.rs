//! A program as the channel runs it: its lowered instructions, where they
//! come from, and the index of its jump targets.
//!
//! A program is held whole (a subprogram, a document lowered in one go)
//! or streamed: its instructions arrive a page at a time from a
//! [`PageSource`] while it runs, and the pages the run cannot come back
//! to are forgotten (docs/ARCHITECTURE.md, "Streaming"), so memory
//! follows the program's longest loop, not its length.

use std::collections::VecDeque;
use std::ops::Deref;
use std::sync::{Arc, Mutex, PoisonError};

use gcodec_ail::{Document, Instruction, JumpSearch, Op, Source};
use gcodec_source::SourceFile;
use gcodec_stream::SpentBin;
use rustc_hash::FxHashMap;

/// One program (main program, subprogram or cycle), lowered and ready to
/// run. Shared (`Arc`) between the program levels that run it.
pub struct Program {
    /// The name callers use, upper case, without extension (`CYCLE81`,
    /// `L100`, the main program's file stem).
    pub name: String,
    /// The file as given to gcodec or as found on the search path.
    pub file: Arc<str>,
    /// The source: the CSV trace takes block numbers from it, computed
    /// jumps and `CALL … BLOCK` search their labels in it.
    source: Arc<SourceFile>,
    body: Body,
}

impl std::fmt::Debug for Program {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Program")
            .field("name", &self.name)
            .field("file", &self.file)
            .field("streamed", &matches!(self.body, Body::Streamed(_)))
            .finish_non_exhaustive()
    }
}

enum Body {
    Whole { page: Page, labels: Labels },
    Streamed(Mutex<Stream>),
}

/// A run of a program's consecutive instructions, shared with the run
/// loop that executes them.
#[derive(Clone, Debug)]
pub struct Page {
    /// The index of the first instruction in the program.
    base: usize,
    /// A vector rather than a slice: `Arc<[T]>` from a `Vec` copies every
    /// instruction once more.
    instructions: Arc<Vec<Instruction>>,
    /// Where the program has blocks with errors, by line, up to this
    /// page's last line (sorted): a run that reaches one stops there.
    errors: Arc<[Source]>,
    /// Where the instructions go when the page is forgotten.
    spent: Option<SpentBin>,
}

impl Page {
    fn empty() -> Self {
        Self {
            base: 0,
            instructions: Arc::new(Vec::new()),
            errors: Arc::from(Vec::new()),
            spent: None,
        }
    }

    /// The instruction at program index `pc`, if on this page.
    pub fn get(&self, pc: usize) -> Option<&Instruction> {
        self.instructions.get(pc.checked_sub(self.base)?)
    }

    /// The index after the page's last instruction.
    fn end(&self) -> usize {
        self.base + self.instructions.len()
    }

    fn last_line(&self) -> u32 {
        self.instructions.last().map_or(0, |i| i.source.line)
    }

    /// The first block with errors in lines `after + 1 ..= line` (`after`
    /// `None`: on `line` only).
    pub fn error_reached(&self, after: Option<u32>, line: u32) -> Option<&Source> {
        if self.errors.is_empty() {
            return None;
        }
        let from = after.map_or(line, |a| a.saturating_add(1));
        let i = self.errors.partition_point(|e| e.line < from);
        self.errors.get(i).filter(|e| e.line <= line)
    }
}

/// One instruction of a program, keeping its page alive.
#[derive(Clone, Debug)]
pub struct InstructionRef {
    page: Page,
    offset: usize,
}

impl Deref for InstructionRef {
    type Target = Instruction;
    fn deref(&self) -> &Instruction {
        &self.page.instructions[self.offset]
    }
}

/// What a streamed program's instructions come from, in program order.
pub trait PageSource: Send {
    /// The next page, or `None` after the last (which holds the `end`).
    fn next_page(&mut self) -> Option<SourcePage>;
}

/// A page as its source gives it.
#[derive(Debug, Default)]
pub struct SourcePage {
    /// The next instructions of the program; a page with none only
    /// carries errors.
    instructions: Vec<Instruction>,
    /// Where the blocks up to the page's last line that have errors are
    /// (where their first error is), in order; blocks without
    /// instructions included.
    errors: Vec<Source>,
    /// [`jump_marks`] of `instructions`.
    marks: Vec<u32>,
    spent: Option<SpentBin>,
}

impl SourcePage {
    /// A page of `instructions` and the places of the `errors` up to its
    /// last line. Its jump targets are found here, on the thread that
    /// makes the page, rather than by the run.
    pub fn new(instructions: Vec<Instruction>, errors: Vec<Source>) -> Self {
        let marks = jump_marks(&instructions);
        Self {
            instructions,
            errors,
            marks,
            spent: None,
        }
    }

    /// The page, whose instructions are given back to `spent` once the
    /// run has forgotten them (to be freed by the thread that allocated
    /// them).
    pub fn given_back_to(mut self, spent: Option<SpentBin>) -> Self {
        self.spent = spent;
        self
    }
}

/// The offsets of the labels, jumps and skipped blocks among
/// `instructions`: what [`Labels`] indexes.
fn jump_marks(instructions: &[Instruction]) -> Vec<u32> {
    instructions
        .iter()
        .enumerate()
        .filter(|(_, i)| {
            matches!(
                i.op,
                Op::Label { .. } | Op::Jump { .. } | Op::SkipBlock { .. }
            )
        })
        .map(|(offset, _)| offset as u32)
        .collect()
}

impl PageSource for std::sync::mpsc::Receiver<SourcePage> {
    fn next_page(&mut self) -> Option<SourcePage> {
        self.recv().ok()
    }
}

/// The label index of a program, built page by page.
#[derive(Default)]
struct Labels {
    /// Label name → index of the `label` instruction (the first of that
    /// name: lowering names labels uniquely, `<name>@<line>`).
    by_name: FxHashMap<String, usize>,
    /// The target of every `jump` and `skip_block` whose label exists, by
    /// the instruction's index: a loop pass then costs no string hashing.
    jump_targets: FxHashMap<usize, usize>,
    /// Jumps to labels not received yet, by label.
    waiting: FxHashMap<String, Vec<usize>>,
}

impl Labels {
    /// Indexes the labels and jumps of `instructions`, the program's
    /// from `base` on, at their `marks` ([`jump_marks`]).
    fn add(&mut self, base: usize, instructions: &[Instruction], marks: &[u32]) {
        let marked = || {
            marks
                .iter()
                .filter_map(|&offset| Some((offset as usize, instructions.get(offset as usize)?)))
        };
        for (offset, instruction) in marked() {
            if let Op::Label { name } = &instruction.op {
                let index = base + offset;
                self.by_name.entry(name.clone()).or_insert(index);
                for jump in self.waiting.remove(name).unwrap_or_default() {
                    self.jump_targets.insert(jump, index);
                }
            }
        }
        for (offset, instruction) in marked() {
            let target = match &instruction.op {
                Op::Jump { target, .. } => target,
                Op::SkipBlock { end, .. } => end,
                _ => continue,
            };
            let index = base + offset;
            match self.by_name.get(target.as_str()) {
                Some(&to) => {
                    self.jump_targets.insert(index, to);
                }
                None => self.waiting.entry(target.clone()).or_default().push(index),
            }
        }
    }
}

/// A streamed program's pages and what is known of the rest.
struct Stream {
    /// The pages held, in order.
    pages: VecDeque<Page>,
    /// The index after the last instruction received.
    received: usize,
    /// Where more pages come from; `None` once the last came.
    source: Option<Box<dyn PageSource>>,
    labels: Labels,
    /// Every block with errors received so far.
    errors: Arc<[Source]>,
    /// Where control can go back ([`Returns`]); `None`: anywhere, so no
    /// page is forgotten.
    returns: Option<Returns>,
}

/// The spans of lines (first, last) control can go back in, sorted by
/// their first line, with the furthest last line up to each.
struct Returns {
    spans: Vec<(u32, u32)>,
    reach: Vec<u32>,
}

impl Returns {
    fn new(mut spans: Vec<(u32, u32)>) -> Self {
        spans.sort_unstable();
        let reach = spans
            .iter()
            .scan(0, |max, &(_, last)| {
                *max = last.max(*max);
                Some(*max)
            })
            .collect();
        Self { spans, reach }
    }

    /// The first line a run at `line` can still come back to.
    fn keep_from(&self, line: u32) -> u32 {
        // The first span reaching `line` has the least first line of all
        // spans reaching it; it holds `line` if it starts at or before.
        let i = self.reach.partition_point(|&r| r < line);
        self.spans
            .get(i)
            .map_or(line, |&(first, _)| first.min(line))
    }
}

impl Stream {
    /// Takes in the next page from the source; `false` at the end.
    fn pull(&mut self) -> bool {
        loop {
            let Some(source) = self.source.as_mut() else {
                return false;
            };
            let Some(page) = source.next_page() else {
                self.source = None;
                return false;
            };
            if !page.errors.is_empty() {
                let mut errors = self.errors.to_vec();
                errors.extend(page.errors);
                errors.sort_by_key(|e| (e.line, e.col));
                self.errors = Arc::from(errors);
            }
            if page.instructions.is_empty() {
                continue;
            }
            let base = self.received;
            self.labels.add(base, &page.instructions, &page.marks);
            self.received += page.instructions.len();
            self.pages.push_back(Page {
                base,
                instructions: Arc::new(page.instructions),
                errors: Arc::clone(&self.errors),
                spent: page.spent,
            });
            return true;
        }
    }

    /// The page holding `pc`, pulling pages up to it.
    fn page(&mut self, pc: usize) -> Option<Page> {
        while pc >= self.received {
            if !self.pull() {
                return None;
            }
        }
        let first = self.pages.front()?.base;
        let at = self.pages.partition_point(|p| p.end() <= pc);
        let page = self.pages.get(at).filter(|_| pc >= first)?.clone();
        self.forget_before(at, page.get(pc).map_or(0, |i| i.source.line));
        Some(page)
    }

    /// Forgets the pages before page `at` (keeping the one just before
    /// it) that a run at `line` cannot come back to.
    fn forget_before(&mut self, at: usize, line: u32) {
        let Some(returns) = &self.returns else {
            return;
        };
        let keep_from = returns.keep_from(line);
        let mut forgettable = 0;
        while forgettable + 1 < at && self.pages[forgettable].last_line() < keep_from {
            forgettable += 1;
        }
        for page in self.pages.drain(..forgettable) {
            // Only a page nothing else holds can be given back whole.
            if let Some(spent) = page.spent
                && let Ok(instructions) = Arc::try_unwrap(page.instructions)
            {
                spent.give_back(instructions);
            }
        }
    }

    /// Pulls pages until `found` says yes or the source ends.
    fn pull_until(&mut self, mut found: impl FnMut(&Self) -> bool) -> bool {
        loop {
            if found(self) {
                return true;
            }
            if !self.pull() {
                return false;
            }
        }
    }
}

impl Program {
    /// The program `document` lowered from `source`; indexes its labels.
    pub fn new(name: impl Into<String>, source: Arc<SourceFile>, document: Document) -> Self {
        let mut labels = Labels::default();
        labels.add(
            0,
            &document.instructions,
            &jump_marks(&document.instructions),
        );
        let page = Page {
            base: 0,
            instructions: Arc::new(document.instructions),
            errors: Arc::from(Vec::new()),
            spent: None,
        };
        Self::with_body(name, source, Body::Whole { page, labels })
    }

    /// The program lowered from `source` whose instructions come from
    /// `pages` as it runs. `returns` are the spans of lines control can
    /// go back in (`gcodec_sema::Outline::returns`): the pages before
    /// them are forgotten once the run is past; `None` keeps every page.
    pub fn streamed(
        name: impl Into<String>,
        source: Arc<SourceFile>,
        pages: Box<dyn PageSource>,
        returns: Option<Vec<(u32, u32)>>,
    ) -> Self {
        let stream = Stream {
            pages: VecDeque::new(),
            received: 0,
            source: Some(pages),
            labels: Labels::default(),
            errors: Arc::from(Vec::new()),
            returns: returns.map(Returns::new),
        };
        Self::with_body(name, source, Body::Streamed(Mutex::new(stream)))
    }

    fn with_body(name: impl Into<String>, source: Arc<SourceFile>, body: Body) -> Self {
        Self {
            name: name.into(),
            file: Arc::from(source.name()),
            source,
            body,
        }
    }

    /// Stops taking pages: a run that ended leaves the rest to its
    /// source, which must not wait for it.
    pub fn end_stream(&self) {
        if let Body::Streamed(stream) = &self.body {
            Self::stream(stream, |s| s.source = None);
        }
    }

    /// Runs `f` on the stream of a streamed program.
    fn stream<T>(stream: &Mutex<Stream>, f: impl FnOnce(&mut Stream) -> T) -> T {
        // A panic while the lock was held cannot leave the stream half
        // updated in a way that matters more than the panic itself.
        f(&mut stream.lock().unwrap_or_else(PoisonError::into_inner))
    }

    /// The page holding the instruction `pc`, or `None` past the end.
    pub fn page(&self, pc: usize) -> Option<Page> {
        match &self.body {
            Body::Whole { page, .. } => (pc < page.end()).then(|| page.clone()),
            Body::Streamed(stream) => Self::stream(stream, |s| s.page(pc)),
        }
    }

    /// A page to start a run loop with: it holds no instruction.
    pub fn no_page() -> Page {
        Page::empty()
    }

    /// Whether `pc` was an instruction of a streamed program that has
    /// been forgotten (the run should never come back to one).
    pub fn is_forgotten(&self, pc: usize) -> bool {
        match &self.body {
            Body::Whole { .. } => false,
            Body::Streamed(stream) => {
                Self::stream(stream, |s| s.pages.front().is_some_and(|p| pc < p.base))
            }
        }
    }

    /// The instruction `pc`.
    pub fn instruction(&self, pc: usize) -> Option<InstructionRef> {
        let page = self.page(pc)?;
        Some(InstructionRef {
            offset: pc - page.base,
            page,
        })
    }

    /// The last instruction held (of a streamed program: received).
    pub fn last_instruction(&self) -> Option<InstructionRef> {
        let page = match &self.body {
            Body::Whole { page, .. } => page.clone(),
            Body::Streamed(stream) => Self::stream(stream, |s| s.pages.back().cloned())?,
        };
        let offset = page.instructions.len().checked_sub(1)?;
        Some(InstructionRef { page, offset })
    }

    /// The program's first instruction that is not a label (its `PROC`,
    /// if it has one).
    pub fn first_statement(&self) -> Option<InstructionRef> {
        (0..)
            .map_while(|pc| self.instruction(pc))
            .find(|i| !matches!(i.op, Op::Label { .. }))
    }

    /// The instructions of a program held whole; `None` for a streamed
    /// one.
    pub fn whole_instructions(&self) -> Option<&[Instruction]> {
        match &self.body {
            Body::Whole { page, .. } => Some(&page.instructions),
            Body::Streamed(_) => None,
        }
    }

    /// The index of the first instruction on `line` or after, if any.
    fn index_at_line(&self, line: u32) -> Option<usize> {
        match &self.body {
            Body::Whole { page, .. } => {
                let index = page.instructions.partition_point(|i| i.source.line < line);
                (index < page.instructions.len()).then_some(index)
            }
            Body::Streamed(stream) => Self::stream(stream, |s| {
                s.pull_until(|s| s.pages.back().is_some_and(|p| p.last_line() >= line));
                let at = s.pages.partition_point(|p| p.last_line() < line);
                let page = s.pages.get(at)?;
                Some(page.base + page.instructions.partition_point(|i| i.source.line < line))
            }),
        }
    }

    /// The line of instruction `pc` (0 before the program).
    fn line_of(&self, pc: usize) -> u32 {
        self.instruction(pc).map_or(0, |i| i.source.line)
    }

    /// The instruction index the `jump` or `skip_block` at `at` goes to,
    /// when its label has been seen.
    pub fn jump_target(&self, at: usize) -> Option<usize> {
        match &self.body {
            Body::Whole { labels, .. } => labels.jump_targets.get(&at).copied(),
            Body::Streamed(stream) => {
                Self::stream(stream, |s| s.labels.jump_targets.get(&at).copied())
            }
        }
    }

    /// The program's source text.
    pub fn text(&self) -> &[u8] {
        self.source.bytes()
    }

    /// The text of the 1-based `line` (without its line end).
    pub fn line_text(&self, line: u32) -> Option<&[u8]> {
        let text = self.source.bytes();
        let line_starts = self.source.line_starts();
        let index = usize::try_from(line).ok()?.checked_sub(1)?;
        let start = *line_starts.get(index)? as usize;
        let end = line_starts
            .get(index + 1)
            .map_or(text.len(), |&e| e as usize);
        let line = text.get(start..end)?;
        Some(line.strip_suffix(b"\n").unwrap_or(line))
    }

    /// The block number (`N20`, `:20`) the `line` starts with, after a
    /// skip mark (asked for every block of a CSV trace: the label is not
    /// looked for).
    pub fn block_number(&self, line: u32) -> Option<u32> {
        let (number, _) = number_head(self.line_text(line)?);
        number.and_then(|n| u32::try_from(n).ok())
    }

    /// The block number and label the `line` starts with, after a skip
    /// mark (`/1 N20 LBL: …`).
    fn line_head(&self, line: u32) -> Option<LineHead<'_>> {
        let rest = self.line_text(line)?;
        let (number, i) = number_head(rest);
        // A label: a name and `:` (not `:=`, not a main-block number).
        let name_len = rest[i.min(rest.len())..]
            .iter()
            .take_while(|b| b.is_ascii_alphanumeric() || **b == b'_')
            .count();
        let label = (name_len > 0
            && rest.get(i + name_len) == Some(&b':')
            && rest.get(i + name_len + 1) != Some(&b'='))
        .then(|| &rest[i..i + name_len]);
        Some(LineHead { number, label })
    }

    /// The line of the nearest block labelled or numbered `target` in the
    /// text, searched from `line` as `search` says.
    pub fn search_text(&self, target: &str, line: u32, search: JumpSearch) -> Option<u32> {
        let lines = self.source.line_starts().len() as u32;
        let matches = |l: u32| self.line_is(l, target);
        let forward = || (line + 1..=lines).find(|&l| matches(l));
        let backward = || (1..=line.min(lines)).rev().find(|&l| matches(l));
        match search {
            JumpSearch::Forward => forward(),
            JumpSearch::Backward => backward(),
            JumpSearch::ForwardThenBackward => forward().or_else(backward),
        }
    }

    /// Whether `line` carries the label or block number `target` (`SEC`,
    /// `N40`, any case; block numbers compare by value).
    fn line_is(&self, line: u32, target: &str) -> bool {
        let Some(head) = self.line_head(line) else {
            return false;
        };
        let wanted_number = target
            .strip_prefix(['N', 'n'])
            .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|d| d.parse::<u64>().ok());
        (wanted_number.is_some() && head.number == wanted_number)
            || head
                .label
                .is_some_and(|label| label.eq_ignore_ascii_case(target.as_bytes()))
    }

    /// `CALL … BLOCK from TO to`: the first instruction of the section and
    /// the line of its last block; `Err` names the label not found. Both
    /// are searched from the program's start (`to` from `from` on).
    pub fn section<'t>(&self, from: &'t str, to: &'t str) -> Result<(usize, u32), &'t str> {
        let search = JumpSearch::Forward;
        let first = self.search_text(from, 0, search).ok_or(from)?;
        let last = self
            .search_text(to, first.saturating_sub(1), search)
            .ok_or(to)?;
        let start = self.index_at_line(first).ok_or(from)?;
        Ok((start, last))
    }

    /// The instruction index of the label `name` (as lowering named it).
    pub fn label(&self, name: &str) -> Option<usize> {
        match &self.body {
            Body::Whole { labels, .. } => labels.by_name.get(name).copied(),
            Body::Streamed(stream) => Self::stream(stream, |s| {
                let mut found = None;
                s.pull_until(|s| {
                    found = s.labels.by_name.get(name).copied();
                    found.is_some()
                });
                found
            }),
        }
    }

    /// Searches a label or block number written in the program (`LBL`,
    /// `N100`; any case) from the instruction `from` the way `search`
    /// says, nearest first (reference §8.1): forward from the instruction
    /// after `from`'s block, backward from `from`'s block.
    ///
    /// Every label and block number of the text is found (lowering keeps
    /// labels only for the targets it knows). The index is the first
    /// instruction of the block, or of the next block with instructions.
    pub fn search_label(&self, target: &str, from: usize, search: JumpSearch) -> Option<usize> {
        let found = self.search_text(target.trim(), self.line_of(from), search)?;
        self.index_at_line(found)
            .or_else(|| self.last_instruction().map(|i| i.page.base + i.offset))
    }
}

/// The label `name` as written in the program: lowering names labels
/// `<name>@<line>` (a structure's `<KEYWORD>@<line>.<part>`).
pub fn written_label(name: &str) -> &str {
    name.split_once('@').map_or(name, |(written, _)| written)
}

/// The block number the line `rest` starts with after its skip mark,
/// and where the text after them and their blanks starts.
fn number_head(rest: &[u8]) -> (Option<u64>, usize) {
    let mut i = 0;
    let skip_blanks = |i: &mut usize| {
        while rest.get(*i).is_some_and(|b| *b == b' ' || *b == b'\t') {
            *i += 1;
        }
    };
    skip_blanks(&mut i);
    if rest.get(i) == Some(&b'/') {
        i += 1;
        while rest.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        skip_blanks(&mut i);
    }
    let mut number = None;
    if matches!(rest.get(i), Some(b'N' | b'n' | b':'))
        && rest.get(i + 1).is_some_and(u8::is_ascii_digit)
    {
        let digits = rest[i + 1..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .count();
        // `None` past `u64::MAX`, as parsing the digits gives.
        number = rest[i + 1..i + 1 + digits].iter().try_fold(0u64, |n, d| {
            n.checked_mul(10)?.checked_add(u64::from(d - b'0'))
        });
        i += 1 + digits;
        skip_blanks(&mut i);
    }
    (number, i)
}

/// What a line starts with.
struct LineHead<'t> {
    number: Option<u64>,
    label: Option<&'t [u8]>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use gcodec_ail::ByteRange;

    /// The block number as parsing its digits gives it, after skip marks
    /// and blanks, and where the rest starts.
    #[test]
    fn block_numbers_read_from_the_line_head() {
        for (line, number, rest) in [
            ("N20 G1 X1", Some(20), "G1 X1"),
            ("  /1  N20\tLBL: G0", Some(20), "LBL: G0"),
            ("/ n7", Some(7), ""),
            (":30 M30", Some(30), "M30"),
            ("N18446744073709551615", Some(u64::MAX), ""),
            ("N18446744073709551616 G1", None, "G1"),
            ("N99999999999999999999999", None, ""),
            ("N007", Some(7), ""),
            ("N G1", None, "N G1"),
            ("G1 N20", None, "G1 N20"),
            ("", None, ""),
        ] {
            let (found, at) = number_head(line.as_bytes());
            assert_eq!(found, number, "{line:?}");
            assert_eq!(&line[at..], rest, "{line:?}");
        }
    }

    /// Pages of one instruction per line, lines `1..=lines`.
    struct Lines {
        next: u32,
        lines: u32,
    }

    impl PageSource for Lines {
        fn next_page(&mut self) -> Option<SourcePage> {
            (self.next <= self.lines).then(|| {
                let line = self.next;
                self.next += 1;
                let source = Source {
                    file: Arc::from("t.mpf"),
                    line,
                    col: 1,
                    span: ByteRange { start: 0, end: 0 },
                };
                SourcePage::new(
                    vec![Instruction {
                        source,
                        op: Op::Label {
                            name: format!("L@{line}"),
                        },
                    }],
                    Vec::new(),
                )
            })
        }
    }

    fn held(program: &Program) -> usize {
        match &program.body {
            Body::Streamed(stream) => Program::stream(stream, |s| s.pages.len()),
            Body::Whole { .. } => 1,
        }
    }

    fn streamed(returns: Option<Vec<(u32, u32)>>) -> Program {
        let source = Box::new(Lines {
            next: 1,
            lines: 100,
        });
        let text: String = (1..=100).map(|l| format!("L{l}:\n")).collect();
        let file = Arc::new(SourceFile::new("t.mpf", text));
        Program::streamed("T", file, source, returns)
    }

    #[test]
    fn pages_behind_the_run_are_forgotten_unless_control_can_come_back() {
        // No way back: the page before the run's is all that is kept.
        let program = streamed(Some(Vec::new()));
        for pc in 0..100 {
            assert!(program.page(pc).is_some());
            assert!(held(&program) <= 2, "{} pages held at {pc}", held(&program));
        }
        assert!(program.is_forgotten(0));
        assert!(program.page(0).is_none());
        // A loop over lines 10..=60 keeps line 10 on until the run is
        // past line 60.
        let program = streamed(Some(vec![(10, 60)]));
        for pc in 0..100 {
            assert!(program.page(pc).is_some());
            let line = pc as u32 + 1;
            if (10..=60).contains(&line) {
                assert!(!program.is_forgotten(9), "line 10 forgotten at {line}");
            }
        }
        assert!(program.is_forgotten(9));
        // Anywhere: nothing is forgotten.
        let program = streamed(None);
        for pc in 0..100 {
            assert!(program.page(pc).is_some());
        }
        assert_eq!(held(&program), 100);
    }

    #[test]
    fn labels_ahead_are_found_by_pulling_pages() {
        let program = streamed(Some(Vec::new()));
        assert_eq!(program.label("L@50"), Some(49));
        assert_eq!(program.label("L@500"), None);
        assert!(program.page(99).is_some());
        assert!(program.page(100).is_none());
        assert!(!program.is_forgotten(100));
    }
}
