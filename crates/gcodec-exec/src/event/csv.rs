//! `--format csv`: [`BlockRow`], the state after one executed block, and
//! [`CsvWriter`], which writes a row for each block that moves or changes
//! what the columns show ([`CsvRows`]).

use std::borrow::Cow;
use std::io::{self, Write};
use std::sync::Arc;

use super::line_buffer::LineBuffer;
use super::numbers::{CountText, write_u64};
use super::{AxisMap, AxisName, SpindleState, axis_names};
use gcodec_ail::{ShortNumberText, fixed_point_text, write_fixed_point};

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
    place_text: PlaceText,
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
/// a row copies the text of each position and of the other state columns
/// that are the same (the feed, the tool and the modal commands seldom
/// change; an axis the block does not move keeps its text).
#[derive(Default)]
struct StateText {
    /// Whether a row was written: the first row has none before it.
    written: bool,
    /// One per header axis, in the header's order.
    positions: Vec<PositionCell>,
    tool: Option<String>,
    edge: u32,
    feed: u64,
    spindle_speed: u64,
    spindle: SpindleState,
    modal: ModalRow,
    /// `,tool,edge,feed,spindle_speed,spindle` and the modal columns.
    rest_text: Vec<u8>,
    /// Where each of those columns' fields ends in `rest_text`.
    rest_ends: [usize; REST_COLUMNS],
    /// The fields after one being written again.
    rest_tail: Vec<u8>,
}

/// The state columns after the positions: `tool`, `edge`, `feed`,
/// `spindle_speed`, `spindle`, then [`MAIN_MODAL_GROUPS`].
const REST_COLUMNS: usize = 5 + MAIN_MODAL_GROUPS.len();

/// Writes `,` and `row`'s field of the `column`th column after the
/// positions.
fn write_rest_field(text: &mut Vec<u8>, row: &BlockRow, column: usize) {
    text.push(b',');
    match column {
        0 => write_csv_field(text, row.tool.as_deref().unwrap_or("")),
        1 => write_u64(text, u64::from(row.edge)),
        2 => write_f64_csv(text, row.feed),
        3 => write_f64_csv(text, row.spindle_speed),
        4 => text.extend_from_slice(row.spindle.name().as_bytes()),
        modal => write_csv_field(text, &row.modal[modal - 5]),
    }
}

/// One header axis's position in the last row written.
#[derive(Default)]
struct PositionCell {
    /// The value's bits (`-0` is written otherwise than `0`); `None`: the
    /// row had no value for the axis, an empty cell.
    bits: Option<u64>,
    /// The cell as written: most numbers fit a short text, copied with a
    /// copy of a fixed size; `long` holds the others.
    text: ShortNumberText,
    long: Option<Vec<u8>>,
}

impl PositionCell {
    /// Makes this the cell of `bits`.
    fn set(&mut self, bits: Option<u64>) {
        self.bits = bits;
        self.long = None;
        self.text.len = 0;
        if let Some(bits) = bits {
            let value = f64::from_bits(bits);
            if !fixed_point_text(&mut self.text, value, false) {
                let mut long = Vec::new();
                write_f64_display(&mut long, value);
                self.long = Some(long);
            }
        }
    }

    fn write_to(&self, line: &mut Vec<u8>) {
        match &self.long {
            None => self.text.write_to(line),
            Some(long) => line.extend_from_slice(long),
        }
    }
}

/// A row's positions in the header's order. The executor fills the map in
/// that order, with the header's names: then they are read in place with
/// no search, the names compared by address (a single letter is one
/// static text) or, for a longer name (`XV`), by its bytes.
struct HeaderPositions<'r> {
    row: &'r BlockRow,
    in_header_order: bool,
}

impl<'r> HeaderPositions<'r> {
    fn of(axes: &[AxisName], row: &'r BlockRow) -> Self {
        let entries = &row.positions.entries;
        let in_header_order = entries.len() == axes.len()
            && entries.iter().zip(axes).all(|((name, _), axis)| {
                std::ptr::eq(name.as_ref(), axis.as_ref()) || name == axis
            });
        Self {
            row,
            in_header_order,
        }
    }

    /// The bits of the value on the `index`th header axis, `axis`.
    #[inline]
    fn bits(&self, index: usize, axis: &AxisName) -> Option<u64> {
        if self.in_header_order {
            self.row
                .positions
                .entries
                .get(index)
                .map(|(_, v)| v.to_bits())
        } else {
            self.row.positions.get(axis).map(f64::to_bits)
        }
    }
}

impl StateText {
    /// Whether `row`'s positions on `axes` are the last row's.
    fn same_positions(&self, axes: &[AxisName], row: &BlockRow) -> bool {
        let values = HeaderPositions::of(axes, row);
        self.positions.len() == axes.len()
            && axes
                .iter()
                .zip(&self.positions)
                .enumerate()
                .all(|(index, (axis, cell))| cell.bits == values.bits(index, axis))
    }

    /// Whether `row`'s state columns but the positions are the last
    /// row's.
    fn same_rest(&self, row: &BlockRow) -> bool {
        row.columns_unchanged || !(0..REST_COLUMNS).any(|column| self.rest_differs(row, column))
    }

    /// Remembers `row`'s positions on `axes`: the cell of an axis whose
    /// value is the last row's stays (a cell not yet set is the empty one
    /// of no value).
    fn remember_positions(&mut self, axes: &[AxisName], row: &BlockRow) {
        let values = HeaderPositions::of(axes, row);
        self.positions
            .resize_with(axes.len(), PositionCell::default);
        for (index, (axis, cell)) in axes.iter().zip(&mut self.positions).enumerate() {
            let bits = values.bits(index, axis);
            if cell.bits != bits {
                cell.set(bits);
            }
        }
    }

    /// Remembers the state columns of `row` but the positions, and their
    /// text. Mostly one column changes (a feed, a modal command): only
    /// its field is written again.
    fn remember_rest(&mut self, row: &BlockRow) {
        if !self.written {
            for column in 0..REST_COLUMNS {
                write_rest_field(&mut self.rest_text, row, column);
                self.rest_ends[column] = self.rest_text.len();
            }
        } else {
            for column in 0..REST_COLUMNS {
                if self.rest_differs(row, column) {
                    self.replace_rest_field(row, column);
                }
            }
        }
        self.tool.clone_from(&row.tool);
        self.edge = row.edge;
        self.feed = row.feed.to_bits();
        self.spindle_speed = row.spindle_speed.to_bits();
        self.spindle = row.spindle;
        copy_modal(&mut self.modal, &row.modal);
    }

    /// Whether `row` shows something else than the last row written in
    /// the `column`th column after the positions.
    fn rest_differs(&self, row: &BlockRow, column: usize) -> bool {
        match column {
            0 => self.tool != row.tool,
            1 => self.edge != row.edge,
            2 => self.feed != row.feed.to_bits(),
            3 => self.spindle_speed != row.spindle_speed.to_bits(),
            4 => self.spindle != row.spindle,
            modal => !same_command(&self.modal[modal - 5], &row.modal[modal - 5]),
        }
    }

    /// Writes `row`'s field of the `column`th column after the positions
    /// in place of the last one's.
    fn replace_rest_field(&mut self, row: &BlockRow, column: usize) {
        let start = column
            .checked_sub(1)
            .map_or(0, |before| self.rest_ends[before]);
        let end = self.rest_ends[column];
        self.rest_tail.clear();
        self.rest_tail.extend_from_slice(&self.rest_text[end..]);
        self.rest_text.truncate(start);
        write_rest_field(&mut self.rest_text, row, column);
        let new_end = self.rest_text.len();
        self.rest_text.extend_from_slice(&self.rest_tail);
        for later_end in &mut self.rest_ends[column..] {
            *later_end = *later_end - end + new_end;
        }
    }

    /// Writes the state columns remembered last.
    #[inline]
    fn write(&self, line: &mut Vec<u8>) {
        for cell in &self.positions {
            line.push(b',');
            cell.write_to(line);
        }
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
            place_text: PlaceText::default(),
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
        // Written or passed over (and then kept in case it is the last
        // block), the row stands here.
        self.passed_over.of(row);
        let state = &mut self.state;
        // The row before was written or passed over as the same as the
        // last written: either way this one is the same as that.
        let unchanged = row.unchanged && state.written;
        let same_rest = state.written && (unchanged || state.same_rest(row));
        if self.rows == CsvRows::Changes
            && !row.moved
            && same_rest
            && (unchanged || state.same_positions(&self.axes, row))
        {
            self.last_passed_over = true;
            return Ok(());
        }
        self.last_passed_over = false;
        if !same_rest {
            state.remember_rest(row);
        }
        state.remember_positions(&self.axes, row);
        state.written = true;
        self.write_row()
    }

    /// Writes the row of `passed_over` and the state columns remembered.
    fn write_row(&mut self) -> io::Result<()> {
        let line = &mut self.out.lines;
        self.place_text.write(line, &self.passed_over);
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

/// The text of a row's `block`, `line`, `level` and `blocks` columns,
/// kept from row to row.
#[derive(Default)]
struct PlaceText {
    block_number: CountText,
    line: CountText,
    level: CountText,
    blocks: CountText,
}

impl PlaceText {
    /// Starts a row with the columns `block,file,line,level,blocks`.
    fn write(&mut self, line: &mut Vec<u8>, place: &RowPlace) {
        if let Some(number) = place.block_number {
            self.block_number.write(line, u64::from(number));
        }
        line.push(b',');
        line.extend_from_slice(&place.file_field);
        line.push(b',');
        self.line.write(line, u64::from(place.line));
        line.push(b',');
        self.level.write(line, u64::from(place.level));
        line.push(b',');
        self.blocks.write(line, place.blocks);
    }
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

    /// The position cells of rows with `positions` on the axes `X`, `Y`
    /// and `Z` (given in another order than the header's, or missing),
    /// every block written.
    fn position_cells(positions: &[&[(&'static str, f64)]]) -> Vec<String> {
        let axes = ["X", "Y", "Z"].map(Cow::Borrowed);
        let mut csv = CsvWriter::new(Vec::new(), axes)
            .expect("header")
            .with_rows(CsvRows::EveryBlock);
        for (index, row_positions) in positions.iter().enumerate() {
            let mut row = BlockRow {
                blocks: index as u64 + 1,
                ..BlockRow::default()
            };
            for (axis, value) in *row_positions {
                row.positions.insert(Cow::Borrowed(axis), *value);
            }
            csv.row(&row).expect("row");
        }
        let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
        text.lines()
            .skip(1)
            .map(|l| l.split(',').skip(5).take(3).collect::<Vec<_>>().join(","))
            .collect()
    }

    #[test]
    fn position_cells_follow_every_value_short_long_or_missing() {
        let huge = 1.5e300;
        let rows: [&[(&str, f64)]; 6] = [
            &[("X", 1.0), ("Y", -0.0), ("Z", huge)],
            &[("X", 1.0), ("Y", 0.0), ("Z", huge)],
            &[("Z", 0.125), ("X", 1.0)],
            &[("X", 100.037), ("Z", 0.125)],
            &[("X", 1e-7), ("Y", huge), ("Z", 0.125)],
            &[("X", 1e-7), ("Y", huge), ("Z", 0.125)],
        ];
        let long = format!("{huge}");
        assert_eq!(
            position_cells(&rows),
            [
                format!("1,-0,{long}"),
                format!("1,0,{long}"),
                "1,,0.125".to_owned(),
                "100.037,,0.125".to_owned(),
                format!("0.0000001,{long},0.125"),
                format!("0.0000001,{long},0.125"),
            ]
        );
    }

    #[test]
    fn position_cells_of_longer_axis_names_in_or_out_of_the_headers_order() {
        let header = [Cow::Borrowed("X"), Cow::Owned("XV".to_owned())];
        let mut csv = CsvWriter::new(Vec::new(), header)
            .expect("header")
            .with_rows(CsvRows::EveryBlock);
        for entries in [
            [("X", 1.5), ("XV", 2.0)],
            [("XV", 3.0), ("X", 1.5)],
            [("X", 4.0), ("XV", 3.0)],
        ] {
            let mut row = BlockRow::default();
            for (axis, value) in entries {
                // A name of its own allocation, as a profile's would be.
                let name = match axis {
                    "X" => Cow::Borrowed("X"),
                    other => Cow::Owned(other.to_owned()),
                };
                row.positions.insert(name, value);
            }
            csv.row(&row).expect("row");
        }
        let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
        let cells: Vec<String> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').skip(5).take(2).collect::<Vec<_>>().join(","))
            .collect();
        assert_eq!(cells, ["1.5,2", "1.5,3", "4,3"]);
    }

    #[test]
    fn state_columns_follow_changes_one_several_or_all_at_once() {
        let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X")])
            .expect("header")
            .with_rows(CsvRows::EveryBlock);
        let mut row = BlockRow::default();
        let mut expected = Vec::new();
        let mut step = |row: &BlockRow, tail: &str| {
            csv.row(row).expect("row");
            expected.push(tail.to_owned());
        };
        step(&row, ",0,0,0,stopped,,,,,,,,");
        row.feed = 1000.0;
        step(&row, ",0,1000,0,stopped,,,,,,,,");
        row.modal[0] = Cow::Borrowed("G1");
        row.modal[7] = Cow::Borrowed("G94");
        step(&row, ",0,1000,0,stopped,G1,,,,,,,G94");
        row.tool = Some("DRILL, 8 MM".to_owned());
        row.edge = 12;
        row.spindle_speed = 2500.5;
        row.spindle = SpindleState::Cw;
        row.modal[3] = Cow::Owned("G54".to_owned());
        step(&row, "\"DRILL, 8 MM\",12,1000,2500.5,cw,G1,,,G54,,,,G94");
        row.tool = None;
        row.modal[0] = Cow::Borrowed("G0");
        step(&row, ",12,1000,2500.5,cw,G0,,,G54,,,,G94");
        row.edge = 1;
        row.feed = 0.25;
        row.spindle_speed = 0.0;
        row.spindle = SpindleState::Stopped;
        row.modal = Default::default();
        step(&row, ",1,0.25,0,stopped,,,,,,,,");
        let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
        let tails: Vec<&str> = text
            .lines()
            .skip(1)
            .map(|l| l.splitn(7, ',').nth(6).unwrap_or(""))
            .collect();
        assert_eq!(tails, expected);
    }

    #[test]
    fn place_columns_count_up_down_and_across_digits() {
        let mut csv = CsvWriter::new(Vec::new(), [Cow::Borrowed("X")])
            .expect("header")
            .with_rows(CsvRows::EveryBlock);
        let places = [(None, 1, 0, 1), (Some(10), 9, 0, 9), (Some(11), 10, 1, 10)];
        let places = places.into_iter().chain([
            (Some(99), 99, 1, 99),
            (Some(100), 100, 0, 100),
            (None, 7, 0, u64::MAX),
            (Some(u32::MAX), u32::MAX, u32::MAX, 3),
        ]);
        let mut expected = Vec::new();
        for (block_number, line, level, blocks) in places {
            let row = BlockRow {
                block_number,
                line,
                level,
                blocks,
                file: "a,b.mpf".into(),
                ..BlockRow::default()
            };
            csv.row(&row).expect("row");
            let number = block_number.map(|n| n.to_string()).unwrap_or_default();
            expected.push(format!("{number},\"a,b.mpf\",{line},{level},{blocks}"));
        }
        let text = String::from_utf8(csv.into_inner().expect("flushes")).expect("UTF-8");
        let rows: Vec<String> = text
            .lines()
            .skip(1)
            .map(|l| l.splitn(7, ',').take(6).collect::<Vec<_>>().join(","))
            .collect();
        assert_eq!(rows, expected);
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
