//! `--format csv`: [`BlockRow`], the state after one executed block, and
//! [`CsvWriter`], which writes a row for each block that moves or changes
//! what the columns show ([`CsvRows`]).

use std::borrow::Cow;
use std::io::{self, Write};
use std::sync::Arc;

use super::line_buffer::LineBuffer;
use super::numbers::write_u64;
use super::{AxisMap, AxisName, SpindleState, axis_names};
use gcodec_ail::write_fixed_point;

/// A modal group shown as a CSV column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ModalColumn {
    pub group: u8,
    /// The column's header.
    pub column: &'static str,
}

/// The modal groups of the CSV, in column order.
pub const MAIN_MODAL_GROUPS: [ModalColumn; 8] = [
    ModalColumn {
        group: 1,
        column: "motion",
    },
    ModalColumn {
        group: 6,
        column: "plane",
    },
    ModalColumn {
        group: 7,
        column: "radius_compensation",
    },
    ModalColumn {
        group: 8,
        column: "work_offset",
    },
    ModalColumn {
        group: 10,
        column: "path_mode",
    },
    ModalColumn {
        group: 13,
        column: "units",
    },
    ModalColumn {
        group: 14,
        column: "dimensions",
    },
    ModalColumn {
        group: 15,
        column: "feed_mode",
    },
];

/// Which blocks get a CSV row.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CsvRows {
    /// A block with a motion, a block after which a state column (a
    /// position, the tool, the edge, the feed, the spindle, a modal group)
    /// shows something else than the last row, and the run's last block.
    /// A loop's `WHILE` or a block that only computes writes no row; the
    /// `blocks` column says how many blocks ran.
    #[default]
    Changes,
    /// Every executed block: a trace of the control flow.
    EveryBlock,
}

/// The state after one executed block: one row of `--format csv`. The
/// executor keeps one row and refills it after every block (the maps and
/// strings keep their storage).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BlockRow {
    /// `N20`: 20; `None` for a block without a number.
    pub block_number: Option<u32>,
    pub file: Arc<str>,
    pub line: u32,
    /// The program level (0: main program).
    pub level: u32,
    /// The blocks executed so far, this one included.
    pub blocks: u64,
    /// Whether the block had a motion (even one that ends where it
    /// started): such a block always gets a row.
    pub moved: bool,
    /// The position at the block's end, in workpiece coordinates. Axes the
    /// writer's header names and the map lacks are empty cells.
    pub positions: AxisMap,
    /// The active tool (`T7`, or its name); `None`: no tool.
    pub tool: Option<String>,
    /// The active cutting edge (`D1`); 0: none.
    pub edge: u32,
    /// The feed in force, in the unit of group 15.
    pub feed: f64,
    /// The master spindle's programmed speed and state.
    pub spindle_speed: f64,
    pub spindle: SpindleState,
    /// The command of each group of [`MAIN_MODAL_GROUPS`], in that order
    /// (`G1`, `G17`, …; empty when unknown).
    pub modal: [Cow<'static, str>; MAIN_MODAL_GROUPS.len()],
    /// A promise that the state columns (positions to modal commands) are
    /// those of the row before, handed to the same writer: the writer
    /// then compares nothing. `false` promises nothing.
    pub unchanged: bool,
    /// The same promise for the state columns but the positions (tool to
    /// modal commands), which a motion leaves as they were: the writer
    /// then compares the positions only. Implied by `unchanged`.
    pub columns_unchanged: bool,
}

impl BlockRow {
    /// Sets the command of `group` if the CSV shows that group; false
    /// otherwise.
    pub fn set_modal(&mut self, group: u8, code: Cow<'static, str>) -> bool {
        match MAIN_MODAL_GROUPS.iter().position(|c| c.group == group) {
            Some(index) => {
                self.modal[index] = code;
                true
            }
            None => false,
        }
    }
}

/// `--format csv`: a header, then a row for each block [`CsvRows`]
/// selects.
///
/// Columns: `block,file,line,level,blocks`, one per axis (the order given
/// to [`CsvWriter::new`]), `tool,edge,feed,spindle_speed,spindle`, then the
/// [`MAIN_MODAL_GROUPS`]. Numbers are written exactly (the shortest text
/// that reads back as the same value); fields holding a comma, a quote or
/// a line break are quoted (RFC 4180). [`CsvWriter::finish`] writes the
/// last block's row if it was passed over.
pub struct CsvWriter<W: Write> {
    /// Rows are written straight into it.
    out: LineBuffer<W>,
    axes: Vec<AxisName>,
    rows: CsvRows,
    /// Where the last row passed over stands: its state columns are
    /// those of the last row written.
    passed_over: RowPlace,
    /// Whether `passed_over` is the last block's: [`CsvWriter::finish`]
    /// writes it then.
    last_passed_over: bool,
    /// The state columns of the last row written, and their text.
    state: StateText,
}

/// The columns of a row that say which block it is: all a passed-over
/// row has of its own, since its state columns are the last row's.
#[derive(Default)]
struct RowPlace {
    block_number: Option<u32>,
    file: Arc<str>,
    /// `file` as a CSV field: the same file in most rows, written once.
    file_field: Vec<u8>,
    line: u32,
    level: u32,
    blocks: u64,
}

impl RowPlace {
    fn of(&mut self, row: &BlockRow) {
        self.block_number = row.block_number;
        if !Arc::ptr_eq(&self.file, &row.file) {
            self.file = Arc::clone(&row.file);
            self.file_field.clear();
            write_csv_field(&mut self.file_field, &self.file);
        }
        self.line = row.line;
        self.level = row.level;
        self.blocks = row.blocks;
    }
}

/// The state columns of the last row written, as values and as text: a
/// row whose state is the same is passed over ([`CsvRows::Changes`]), and
/// a row whose positions or other state columns are the same copies
/// their text (the feed, the tool and the modal commands seldom change).
#[derive(Default)]
struct StateText {
    /// Whether a row was written: the first row has none before it.
    written: bool,
    /// The bits of each header axis's value (`None`: the row had none):
    /// `-0` is written otherwise than `0`.
    positions: Vec<Option<u64>>,
    /// The same for the row at hand, before it is compared.
    next_positions: Vec<Option<u64>>,
    /// The text of each of `positions`: an axis that did not move keeps it.
    position_cells: Vec<Vec<u8>>,
    positions_text: Vec<u8>,
    tool: Option<String>,
    edge: u32,
    feed: u64,
    spindle_speed: u64,
    spindle: SpindleState,
    modal: ModalRow,
    /// `,tool,edge,feed,spindle_speed,spindle` and the modal columns.
    rest_text: Vec<u8>,
}

impl StateText {
    /// Whether `row`'s positions on `axes`, and its other state columns,
    /// are the last row's.
    fn compare(&mut self, axes: &[AxisName], row: &BlockRow) -> (bool, bool) {
        self.next_positions.clear();
        let entries = &row.positions.entries;
        // The executor fills the map in the header's order, with the same
        // static names: compared by address, no search.
        let in_header_order = entries.len() == axes.len()
            && entries
                .iter()
                .zip(axes)
                .all(|((name, _), axis)| std::ptr::eq(name.as_ref(), axis.as_ref()));
        if in_header_order {
            self.next_positions
                .extend(entries.iter().map(|(_, value)| Some(value.to_bits())));
        } else {
            self.next_positions.extend(
                axes.iter()
                    .map(|axis| row.positions.get(axis).map(f64::to_bits)),
            );
        }
        if !self.written {
            return (false, false);
        }
        let positions = self.next_positions == self.positions;
        let rest = row.columns_unchanged
            || self.edge == row.edge
                && self.feed == row.feed.to_bits()
                && self.spindle_speed == row.spindle_speed.to_bits()
                && self.spindle == row.spindle
                && self.tool == row.tool
                && same_modal(&self.modal, &row.modal);
        (positions, rest)
    }

    /// Remembers the state columns of `row`, and their text, after
    /// [`StateText::compare`] said which are the same.
    fn remember(&mut self, row: &BlockRow, (positions, rest): (bool, bool)) {
        if !positions {
            let cells = &mut self.position_cells;
            cells.resize_with(self.next_positions.len(), Vec::new);
            let text = &mut self.positions_text;
            text.clear();
            for (k, bits) in self.next_positions.iter().enumerate() {
                let cell = &mut cells[k];
                if self.positions.get(k) != Some(bits) {
                    cell.clear();
                    if let Some(bits) = bits {
                        write_f64_csv(cell, f64::from_bits(*bits));
                    }
                }
                text.push(b',');
                text.extend_from_slice(cell);
            }
            std::mem::swap(&mut self.positions, &mut self.next_positions);
        }
        if !rest {
            self.tool.clone_from(&row.tool);
            self.edge = row.edge;
            self.feed = row.feed.to_bits();
            self.spindle_speed = row.spindle_speed.to_bits();
            self.spindle = row.spindle;
            copy_modal(&mut self.modal, &row.modal);
            let text = &mut self.rest_text;
            text.clear();
            text.push(b',');
            write_csv_field(text, row.tool.as_deref().unwrap_or(""));
            text.push(b',');
            write_u64(text, u64::from(row.edge));
            text.push(b',');
            write_f64_csv(text, row.feed);
            text.push(b',');
            write_f64_csv(text, row.spindle_speed);
            text.push(b',');
            text.extend_from_slice(row.spindle.name().as_bytes());
            for code in &row.modal {
                text.push(b',');
                write_csv_field(text, code);
            }
        }
        self.written = true;
    }

    /// Writes the state columns remembered last.
    fn write(&self, line: &mut Vec<u8>) {
        line.extend_from_slice(&self.positions_text);
        line.extend_from_slice(&self.rest_text);
    }
}

/// A row's modal commands, in [`MAIN_MODAL_GROUPS`] order.
type ModalRow = [Cow<'static, str>; MAIN_MODAL_GROUPS.len()];

/// Makes `to` hold the commands of `from`; the registry's static names
/// are copied as references, and only a command that differs is copied.
fn copy_modal(to: &mut ModalRow, from: &ModalRow) {
    for (slot, code) in to.iter_mut().zip(from) {
        if !same_command(slot, code) {
            slot.clone_from(code);
        }
    }
}

/// Whether two rows' modal commands are the same.
fn same_modal(a: &ModalRow, b: &ModalRow) -> bool {
    a.iter().zip(b).all(|(a, b)| same_command(a, b))
}

/// Whether two modal commands are the same text. The registry's names are
/// static: one address is one text, and no bytes need comparing (a
/// comparison of the eight columns' bytes after every block was a sixth
/// of a CSV run without motion). An owned text may reuse a freed one's
/// address, so it is compared by its bytes.
#[expect(
    clippy::ptr_arg,
    reason = "the variant says whether the address stands for the text"
)]
fn same_command(a: &Cow<'static, str>, b: &Cow<'static, str>) -> bool {
    match (a, b) {
        (Cow::Borrowed(a), Cow::Borrowed(b)) if std::ptr::eq(*a, *b) => true,
        _ => a == b,
    }
}

impl<W: Write> CsvWriter<W> {
    /// Writes the header for the channel's `axes`.
    pub fn new(writer: W, axes: impl IntoIterator<Item = AxisName>) -> io::Result<Self> {
        let mut csv = Self {
            out: LineBuffer::new(writer),
            axes: axes.into_iter().collect(),
            rows: CsvRows::default(),
            passed_over: RowPlace::default(),
            last_passed_over: false,
            state: StateText::default(),
        };
        let header = &mut csv.out.lines;
        header.extend_from_slice(b"block,file,line,level,blocks");
        for axis in &csv.axes {
            header.push(b',');
            write_csv_field(header, axis);
        }
        header.extend_from_slice(b",tool,edge,feed,spindle_speed,spindle");
        for column in &MAIN_MODAL_GROUPS {
            header.push(b',');
            header.extend_from_slice(column.column.as_bytes());
        }
        header.push(b'\n');
        csv.out.line_done()?;
        Ok(csv)
    }

    /// Writes the header for the channel axes of `profile`.
    pub fn for_profile(writer: W, profile: &gcodec_profile::Profile) -> io::Result<Self> {
        Self::new(writer, axis_names(profile))
    }

    /// Which blocks get a row; [`CsvRows::Changes`] unless set.
    pub fn with_rows(mut self, rows: CsvRows) -> Self {
        self.rows = rows;
        self
    }

    /// Takes the row of the next executed block and writes it if
    /// [`CsvRows`] selects it.
    pub fn row(&mut self, row: &BlockRow) -> io::Result<()> {
        // The row before was written or passed over as the same as the
        // last written: either way this one is the same as that.
        let same = if row.unchanged && self.state.written {
            (true, true)
        } else {
            self.state.compare(&self.axes, row)
        };
        if self.rows == CsvRows::Changes && !row.moved && same == (true, true) {
            // Kept in case it is the last block.
            self.passed_over.of(row);
            self.last_passed_over = true;
            return Ok(());
        }
        self.last_passed_over = false;
        self.write(row, same)
    }

    fn write(&mut self, row: &BlockRow, same: (bool, bool)) -> io::Result<()> {
        self.passed_over.of(row);
        self.state.remember(row, same);
        self.write_row()
    }

    /// Writes the row of `passed_over` and the state columns remembered.
    fn write_row(&mut self) -> io::Result<()> {
        let line = &mut self.out.lines;
        write_place(line, &self.passed_over);
        self.state.write(line);
        line.push(b'\n');
        self.out.line_done()
    }

    /// Writes the last block's row if it was passed over, and flushes.
    pub fn finish(&mut self) -> io::Result<()> {
        self.write_passed_over()?;
        self.out.flush()
    }

    fn write_passed_over(&mut self) -> io::Result<()> {
        if !std::mem::take(&mut self.last_passed_over) {
            return Ok(());
        }
        self.write_row()
    }

    /// Writes the last block's row if it was passed over, flushes, and
    /// gives the writer back.
    pub fn into_inner(mut self) -> io::Result<W> {
        self.write_passed_over()?;
        self.out.into_inner()
    }
}

/// Starts a row with the columns `block,file,line,level,blocks`.
fn write_place(line: &mut Vec<u8>, place: &RowPlace) {
    if let Some(number) = place.block_number {
        write_u64(line, u64::from(number));
    }
    line.push(b',');
    line.extend_from_slice(&place.file_field);
    line.push(b',');
    write_u64(line, u64::from(place.line));
    line.push(b',');
    write_u64(line, u64::from(place.level));
    line.push(b',');
    write_u64(line, place.blocks);
}

/// A number as Rust's `{}` writes it (shortest text that reads back, no
/// exponent, no `.0`), through [`write_fixed_point`] where it applies.
#[inline]
fn write_f64_csv(out: &mut Vec<u8>, value: f64) {
    if !write_fixed_point(out, value, false) {
        write_f64_display(out, value);
    }
}

/// A number as Rust's `{}` writes it, the general way.
#[cold]
fn write_f64_display(out: &mut Vec<u8>, value: f64) {
    // Writing into a vector does not fail.
    let _ = write!(out, "{value}");
}

/// Writes `field`, quoted when it holds a comma, a quote or a line break
/// (RFC 4180). Byte by byte rather than through `fmt`: the file name and
/// eight modal commands are in every row.
fn write_csv_field(out: &mut Vec<u8>, field: &str) {
    let bytes = field.as_bytes();
    if !bytes
        .iter()
        .any(|b| matches!(b, b',' | b'"' | b'\n' | b'\r'))
    {
        out.extend_from_slice(bytes);
        return;
    }
    out.push(b'"');
    for &b in bytes {
        if b == b'"' {
            out.push(b'"');
        }
        out.push(b);
    }
    out.push(b'"');
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows of `modal` commands (one axis, nothing else changing), every
    /// block written.
    fn modal_rows(modals: &[ModalRow]) -> Vec<String> {
        let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X")])
            .expect("header")
            .with_rows(CsvRows::EveryBlock);
        for modal in modals {
            let row = BlockRow {
                modal: modal.clone(),
                ..BlockRow::default()
            };
            csv.row(&row).expect("row");
        }
        let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
        text.lines()
            .skip(1)
            .map(|l| l.splitn(12, ',').nth(11).unwrap_or("").to_owned())
            .collect()
    }

    #[test]
    fn modal_columns_follow_every_change_static_or_owned() {
        let mut modal: ModalRow = Default::default();
        let mut modals = Vec::new();
        for code in ["G1", "G0", "G0"] {
            modal[0] = Cow::Borrowed(code);
            modals.push(modal.clone());
        }
        // Owned texts of one length, likely at one address in turn.
        for code in ["G54", "G55", "G55"] {
            modal[3] = Cow::Owned(code.to_owned());
            modals.push(modal.clone());
        }
        modal[3] = Cow::Borrowed("a,b");
        modals.push(modal.clone());
        assert_eq!(
            modal_rows(&modals),
            [
                "G1,,,,,,,",
                "G0,,,,,,,",
                "G0,,,,,,,",
                "G0,,,G54,,,,",
                "G0,,,G55,,,,",
                "G0,,,G55,,,,",
                "G0,,,\"a,b\",,,,",
            ]
        );
    }
}
