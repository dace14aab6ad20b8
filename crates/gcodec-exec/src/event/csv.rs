//! `--format csv`: [`BlockRow`], the state after one executed block, and
//! [`CsvWriter`], which writes one row per block.

use std::borrow::Cow;
use std::fmt;
use std::io::{self, BufWriter, Write};
use std::sync::Arc;

use super::numbers::{write_fixed_point, write_u64};
use super::{AxisMap, AxisName, SpindleState, axis_names};

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

/// `--format csv`: a header, then one row per executed block.
///
/// Columns: `block,file,line,level`, one per axis (the order given to
/// [`CsvWriter::new`]), `tool,edge,feed,spindle_speed,spindle`, then the
/// [`MAIN_MODAL_GROUPS`]. Numbers are written exactly (the shortest text
/// that reads back as the same value); fields holding a comma, a quote or
/// a line break are quoted (RFC 4180).
pub struct CsvWriter<W: Write> {
    out: BufWriter<W>,
    axes: Vec<AxisName>,
    /// The row being built, reused.
    line: Vec<u8>,
}

impl<W: Write> CsvWriter<W> {
    /// Writes the header for the channel's `axes`.
    pub fn new(writer: W, axes: impl IntoIterator<Item = AxisName>) -> io::Result<Self> {
        let mut csv = Self {
            out: BufWriter::with_capacity(1 << 16, writer),
            axes: axes.into_iter().collect(),
            line: Vec::with_capacity(256),
        };
        csv.out.write_all(b"block,file,line,level")?;
        for axis in &csv.axes {
            write!(csv.out, ",{}", CsvField(axis))?;
        }
        csv.out
            .write_all(b",tool,edge,feed,spindle_speed,spindle")?;
        for column in &MAIN_MODAL_GROUPS {
            write!(csv.out, ",{}", column.column)?;
        }
        csv.out.write_all(b"\n")?;
        Ok(csv)
    }

    /// Writes the header for the channel axes of `profile`.
    pub fn for_profile(writer: W, profile: &gcodec_profile::Profile) -> io::Result<Self> {
        Self::new(writer, axis_names(profile))
    }

    /// Writes one row.
    pub fn row(&mut self, row: &BlockRow) -> io::Result<()> {
        let line = &mut self.line;
        line.clear();
        if let Some(number) = row.block_number {
            write_u64(line, u64::from(number));
        }
        line.push(b',');
        write_csv_field(line, &row.file);
        line.push(b',');
        write_u64(line, u64::from(row.line));
        line.push(b',');
        write_u64(line, u64::from(row.level));
        for axis in &self.axes {
            line.push(b',');
            if let Some(value) = row.positions.get(axis) {
                write_f64_csv(line, value);
            }
        }
        line.push(b',');
        write_csv_field(line, row.tool.as_deref().unwrap_or(""));
        line.push(b',');
        write_u64(line, u64::from(row.edge));
        line.push(b',');
        write_f64_csv(line, row.feed);
        line.push(b',');
        write_f64_csv(line, row.spindle_speed);
        line.push(b',');
        line.extend_from_slice(row.spindle.name().as_bytes());
        for code in &row.modal {
            line.push(b',');
            write_csv_field(line, code);
        }
        line.push(b'\n');
        self.out.write_all(line)
    }

    /// Flushes.
    pub fn finish(&mut self) -> io::Result<()> {
        self.out.flush()
    }

    /// Flushes and gives the writer back.
    pub fn into_inner(self) -> io::Result<W> {
        self.out
            .into_inner()
            .map_err(io::IntoInnerError::into_error)
    }
}

/// A number as Rust's `{}` writes it (shortest text that reads back, no
/// exponent, no `.0`), through [`write_fixed_point`] where it applies.
fn write_f64_csv(out: &mut Vec<u8>, value: f64) {
    if !write_fixed_point(out, value, false) {
        // Writing into a vector does not fail.
        let _ = write!(out, "{value}");
    }
}

fn write_csv_field(out: &mut Vec<u8>, field: &str) {
    // Writing into a vector does not fail.
    let _ = write!(out, "{}", CsvField(field));
}

/// A CSV field, quoted when it must be.
struct CsvField<'a>(&'a str);

impl fmt::Display for CsvField<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !self.0.contains([',', '"', '\n', '\r']) {
            return f.write_str(self.0);
        }
        f.write_str("\"")?;
        for (index, part) in self.0.split('"').enumerate() {
            if index > 0 {
                f.write_str("\"\"")?;
            }
            f.write_str(part)?;
        }
        f.write_str("\"")
    }
}
