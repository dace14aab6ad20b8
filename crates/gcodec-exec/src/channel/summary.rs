//! What a run adds up to: blocks, path length, time estimate and the
//! bounding box, per tool.

use std::fmt;

use rustc_hash::FxHashMap;
use serde::Serialize;

use crate::geometry::BoundingBox;

/// The figures of one tool (or of no tool).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct ToolSummary {
    /// `T7`, the tool's name, or `null` for blocks run without a tool.
    pub tool: Option<String>,
    /// Blocks executed while this tool was active.
    pub blocks: u64,
    /// Path length at rapid traverse, mm (geometry axes, workpiece
    /// coordinates).
    pub rapid_length: f64,
    /// Path length at feed, mm.
    pub feed_length: f64,
    /// Time at rapid traverse, seconds (each block: the slowest axis at
    /// its profile rate).
    pub rapid_time: f64,
    /// Time at feed, seconds (path length / F under G94; per revolution
    /// under G95 with the spindle speed; dwell included).
    pub feed_time: f64,
    /// Time the machine took for its own actions while this tool was
    /// active, seconds: the toolchanger's cycles of a tool change (left
    /// out of the JSON while 0: a run without a toolchanger).
    #[serde(skip_serializing_if = "is_zero")]
    pub machine_time: f64,
    /// Of the geometry axes' end points and arc extremes, workpiece
    /// coordinates, mm; `null` when the tool did not move.
    pub bounding_box: Option<BoundingBox>,
}

/// The summary of a run.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RunSummary {
    /// Blocks executed in the whole run.
    pub blocks: u64,
    /// Per tool, in the order first used.
    tools: Vec<ToolSummary>,
    /// Where each tool's figures are in `tools`: a program may use a new
    /// tool in every pass of a loop, and a search of `tools` for each
    /// would make the run quadratic.
    #[serde(skip)]
    slots: FxHashMap<Box<str>, usize>,
    /// Where the figures of blocks run without a tool are.
    #[serde(skip)]
    no_tool_slot: Option<usize>,
}

impl ToolSummary {
    /// Adds a traversing motion: its length (mm) and time (s) at rapid
    /// traverse or at feed, and its extent.
    pub(super) fn add_motion(&mut self, rapid: bool, length: f64, time: f64, extent: BoundingBox) {
        self.bounding_box = Some(match self.bounding_box {
            Some(b) => b.union(&extent),
            None => extent,
        });
        if rapid {
            self.rapid_length += length;
            self.rapid_time += time;
        } else {
            self.feed_length += length;
            self.feed_time += time;
        }
    }
}

impl RunSummary {
    /// The figures per tool, in the order first used.
    pub fn tools(&self) -> &[ToolSummary] {
        &self.tools
    }

    /// The figures at `slot` (from [`RunSummary::slot`]).
    pub fn at(&mut self, slot: usize) -> &mut ToolSummary {
        &mut self.tools[slot]
    }

    /// The figures of `tool`, created on first use.
    pub fn tool(&mut self, tool: Option<&str>) -> &mut ToolSummary {
        let at = self.slot(tool);
        &mut self.tools[at]
    }

    /// The position of `tool`'s figures in `tools`, created on first use.
    pub fn slot(&mut self, tool: Option<&str>) -> usize {
        let known = match tool {
            Some(name) => self.slots.get(name).copied(),
            None => self.no_tool_slot,
        };
        if let Some(at) = known {
            return at;
        }
        let at = self.tools.len();
        self.tools.push(ToolSummary {
            tool: tool.map(str::to_owned),
            ..ToolSummary::default()
        });
        match tool {
            Some(name) => {
                self.slots.insert(Box::from(name), at);
            }
            None => self.no_tool_slot = Some(at),
        }
        at
    }

    /// The sum over all tools.
    pub fn total(&self) -> ToolSummary {
        let mut total = ToolSummary::default();
        for t in &self.tools {
            total.blocks += t.blocks;
            total.rapid_length += t.rapid_length;
            total.feed_length += t.feed_length;
            total.rapid_time += t.rapid_time;
            total.feed_time += t.feed_time;
            total.machine_time += t.machine_time;
            total.bounding_box = match (total.bounding_box, t.bounding_box) {
                (Some(a), Some(b)) => Some(a.union(&b)),
                (a, b) => a.or(b),
            };
        }
        total
    }
}

impl fmt::Display for RunSummary {
    /// The text summary `gcodec run` prints: one line per tool and a total.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "blocks executed: {}", self.blocks)?;
        let line = |f: &mut fmt::Formatter<'_>, name: &str, t: &ToolSummary| {
            write!(
                f,
                "{name:<14} blocks {:>9}  path {:>11.3} mm (rapid {:.3}, feed {:.3})  time {} (rapid {}, feed {}",
                t.blocks,
                t.rapid_length + t.feed_length,
                t.rapid_length,
                t.feed_length,
                duration(t.rapid_time + t.feed_time + t.machine_time),
                duration(t.rapid_time),
                duration(t.feed_time),
            )?;
            if t.machine_time > 0.0 {
                write!(f, ", tool changes {}", duration(t.machine_time))?;
            }
            write!(f, ")")?;
            match &t.bounding_box {
                Some(b) => writeln!(
                    f,
                    "  box X {:.3}…{:.3} Y {:.3}…{:.3} Z {:.3}…{:.3}",
                    b.min[0], b.max[0], b.min[1], b.max[1], b.min[2], b.max[2]
                ),
                None => writeln!(f),
            }
        };
        for t in &self.tools {
            line(f, t.tool.as_deref().unwrap_or("(no tool)"), t)?;
        }
        if self.tools.len() > 1 {
            line(f, "total", &self.total())?;
        }
        Ok(())
    }
}

fn is_zero(seconds: &f64) -> bool {
    *seconds == 0.0
}

/// `1h02m03.4s`, `2m03.4s`, `3.4s`.
fn duration(seconds: f64) -> String {
    if !seconds.is_finite() {
        return "∞".to_owned();
    }
    let hours = (seconds / 3600.0).floor();
    let minutes = ((seconds - hours * 3600.0) / 60.0).floor();
    let rest = seconds - hours * 3600.0 - minutes * 60.0;
    if hours > 0.0 {
        format!("{hours}h{minutes:02}m{rest:04.1}s")
    } else if minutes > 0.0 {
        format!("{minutes}m{rest:04.1}s")
    } else {
        format!("{rest:.1}s")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_read_as_clock_times() {
        assert_eq!(duration(3.44), "3.4s");
        assert_eq!(duration(123.4), "2m03.4s");
        assert_eq!(duration(3723.4), "1h02m03.4s");
    }

    #[test]
    fn tools_are_kept_in_the_order_first_used() {
        let mut s = RunSummary::default();
        s.tool(Some("T2")).blocks += 1;
        s.tool(None).blocks += 2;
        s.tool(Some("T2")).blocks += 3;
        assert_eq!(s.tools().len(), 2);
        assert_eq!(s.tools()[0].blocks, 4);
        assert_eq!(s.total().blocks, 6);
    }

    /// `T=CNT` in a loop: a new tool per pass. Each is found again by the
    /// index, the table holds each tool once, in the order first used.
    #[test]
    fn many_tools_are_indexed_in_the_order_first_used() {
        let mut s = RunSummary::default();
        let names: Vec<String> = (0..100_000).map(|n| format!("T{n}")).collect();
        for (n, name) in names.iter().enumerate() {
            assert_eq!(s.slot(Some(name)), n);
        }
        assert_eq!(s.slot(None), 100_000);
        for (n, name) in names.iter().enumerate().rev() {
            assert_eq!(s.slot(Some(name)), n);
        }
        assert_eq!(s.tools().len(), 100_001);
        assert_eq!(s.slots.len(), 100_000);
        assert_eq!(s.tools()[99_999].tool.as_deref(), Some("T99999"));
    }
}
