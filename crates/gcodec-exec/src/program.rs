//! A program as the channel runs it: its lowered instructions, where they
//! come from, and the index of its jump targets.

use std::sync::Arc;

use gcodec_ail::{Document, Instruction, JumpSearch, Op};
use rustc_hash::FxHashMap;

/// One program (main program, subprogram or cycle), lowered and ready to
/// run. Shared (`Arc`) between the program levels that run it.
#[derive(Debug)]
pub struct Program {
    /// The name callers use, upper case, without extension (`CYCLE81`,
    /// `L100`, the main program's file stem).
    pub name: String,
    /// The file as given to gcodec or as found on the search path.
    pub file: Arc<str>,
    /// The source text, when the program was read from a file: the CSV
    /// trace takes block numbers from it.
    pub text: Option<Arc<[u8]>>,
    /// The byte offset of each line of `text`.
    line_starts: Vec<u32>,
    pub document: Document,
    /// Label name → index of the `label` instruction (the first of that
    /// name: lowering names labels uniquely, `<name>@<line>`).
    labels: FxHashMap<String, usize>,
    /// Every label in order: (name before `@`, upper case; instruction
    /// index), for computed jumps and `CALL … BLOCK`.
    label_list: Vec<(String, usize)>,
    /// The target of every `jump` and `skip_block` whose label exists, by
    /// the instruction's index: a loop pass then costs no string hashing.
    jump_targets: FxHashMap<usize, usize>,
}

impl Program {
    /// Indexes the labels of `document`.
    pub fn new(name: impl Into<String>, file: Arc<str>, document: Document) -> Self {
        let mut labels = FxHashMap::default();
        let mut label_list = Vec::new();
        for (index, instruction) in document.instructions.iter().enumerate() {
            if let Op::Label { name } = &instruction.op {
                labels.entry(name.clone()).or_insert(index);
                // `<name>@<line>` is a label or block number of the text;
                // lowering's own labels (`WHILE@7.end`, `SKIP@3.end`) have
                // a part after the line and are no jump targets.
                if let Some((base, line)) = name.split_once('@')
                    && line.bytes().all(|b| b.is_ascii_digit())
                {
                    label_list.push((base.to_ascii_uppercase(), index));
                }
            }
        }
        let jump_targets = document
            .instructions
            .iter()
            .enumerate()
            .filter_map(|(index, instruction)| {
                let target = match &instruction.op {
                    Op::Jump { target, .. } => target,
                    Op::SkipBlock { end, .. } => end,
                    _ => return None,
                };
                labels.get(target.as_str()).map(|&to| (index, to))
            })
            .collect();
        Self {
            name: name.into(),
            file,
            text: None,
            line_starts: Vec::new(),
            document,
            labels,
            label_list,
            jump_targets,
        }
    }

    /// The instruction index the `jump` or `skip_block` at `at` goes to,
    /// when its label exists.
    pub fn jump_target(&self, at: usize) -> Option<usize> {
        self.jump_targets.get(&at).copied()
    }

    /// With the source text.
    pub fn with_text(mut self, text: Arc<[u8]>) -> Self {
        self.line_starts = std::iter::once(0)
            .chain(
                text.iter()
                    .enumerate()
                    .filter(|(_, b)| **b == b'\n')
                    .map(|(i, _)| i as u32 + 1),
            )
            .collect();
        self.text = Some(text);
        self
    }

    /// The text of the 1-based `line` (without its line end), if the
    /// program has its text.
    pub fn line_text(&self, line: u32) -> Option<&[u8]> {
        let text = self.text.as_deref()?;
        let index = usize::try_from(line).ok()?.checked_sub(1)?;
        let start = *self.line_starts.get(index)? as usize;
        let end = self
            .line_starts
            .get(index + 1)
            .map_or(text.len(), |&e| e as usize);
        let line = text.get(start..end)?;
        Some(line.strip_suffix(b"\n").unwrap_or(line))
    }

    /// The block number (`N20`, `:20`) the `line` starts with, after a
    /// skip mark.
    pub fn block_number(&self, line: u32) -> Option<u32> {
        self.line_head(line)?
            .number
            .and_then(|n| u32::try_from(n).ok())
    }

    /// The block number and label the `line` starts with, after a skip
    /// mark (`/1 N20 LBL: …`).
    fn line_head(&self, line: u32) -> Option<LineHead<'_>> {
        let rest = self.line_text(line)?;
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
            number = std::str::from_utf8(&rest[i + 1..i + 1 + digits])
                .ok()
                .and_then(|d| d.parse::<u64>().ok());
            i += 1 + digits;
            skip_blanks(&mut i);
        }
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
        let lines = self.line_starts.len() as u32;
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
        if self.text.is_some() {
            let first = self.search_text(from, 0, search).ok_or(from)?;
            let last = self
                .search_text(to, first.saturating_sub(1), search)
                .ok_or(to)?;
            let start = self
                .document
                .instructions
                .partition_point(|i| i.source.line < first);
            return Ok((start, last));
        }
        let start = self
            .search_label(from, 0, JumpSearch::ForwardThenBackward)
            .ok_or(from)?;
        let end = self
            .search_label(to, start, JumpSearch::ForwardThenBackward)
            .ok_or(to)?;
        Ok((start, self.document.instructions[end].source.line))
    }

    pub fn instructions(&self) -> &[Instruction] {
        &self.document.instructions
    }

    /// The instruction index of the label `name` (as lowering named it).
    pub fn label(&self, name: &str) -> Option<usize> {
        self.labels.get(name).copied()
    }

    /// Searches a label or block number written in the program (`LBL`,
    /// `N100`; any case) from the instruction `from` the way `search`
    /// says, nearest first (reference §8.1): forward from the instruction
    /// after `from`'s block, backward from `from`'s block.
    ///
    /// With the program's text every label and block number of the text
    /// is found (lowering keeps labels only for the targets it knows, so
    /// `CALL … BLOCK` sections need the text); without it, the labels
    /// lowering kept. The index is the first instruction of the block, or
    /// of the next block with instructions.
    pub fn search_label(&self, target: &str, from: usize, search: JumpSearch) -> Option<usize> {
        let target = target.trim();
        let line = self
            .document
            .instructions
            .get(from)
            .map_or(0, |i| i.source.line);
        if self.text.is_some() {
            let found = self.search_text(target, line, search)?;
            let index = self
                .document
                .instructions
                .partition_point(|i| i.source.line < found);
            return Some(index.min(self.document.instructions.len().saturating_sub(1)));
        }
        let line_of = |index: usize| self.document.instructions[index].source.line;
        let matches = |(name, _): &&(String, usize)| name.eq_ignore_ascii_case(target);
        let forward = || {
            self.label_list
                .iter()
                .filter(|(_, i)| line_of(*i) > line)
                .find(matches)
                .map(|(_, i)| *i)
        };
        let backward = || {
            self.label_list
                .iter()
                .rev()
                .filter(|(_, i)| line_of(*i) <= line)
                .find(matches)
                .map(|(_, i)| *i)
        };
        match search {
            JumpSearch::Forward => forward(),
            JumpSearch::Backward => backward(),
            JumpSearch::ForwardThenBackward => forward().or_else(backward),
        }
    }
}

/// What a line starts with.
struct LineHead<'t> {
    number: Option<u64>,
    label: Option<&'t [u8]>,
}
