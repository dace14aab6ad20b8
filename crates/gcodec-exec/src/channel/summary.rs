//! What a run adds up to: blocks, path length, time estimate and the
//! bounding box, per tool.

use std::fmt;

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
    pub tools: Vec<ToolSummary>,
}

impl RunSummary {
    /// The figures of `tool`, created on first use.
    pub fn tool(&mut self, tool: Option<&str>) -> &mut ToolSummary {
        let at = self.slot(tool);
        &mut self.tools[at]
    }

    /// The position of `tool`'s figures in `tools`, created on first use.
    pub fn slot(&mut self, tool: Option<&str>) -> usize {
        let at = self.tools.iter().position(|t| t.tool.as_deref() == tool);
        at.unwrap_or_else(|| {
            self.tools.push(ToolSummary {
                tool: tool.map(str::to_owned),
                ..ToolSummary::default()
            });
            self.tools.len() - 1
        })
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
                "{name:<14} blocks {:>9}  path {:>11.3} mm (rapid {:.3}, feed {:.3})  time {} (rapid {}, feed {})",
                t.blocks,
                t.rapid_length + t.feed_length,
                t.rapid_length,
                t.feed_length,
                duration(t.rapid_time + t.feed_time),
                duration(t.rapid_time),
                duration(t.feed_time),
            )?;
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
        assert_eq!(s.tools.len(), 2);
        assert_eq!(s.tools[0].blocks, 4);
        assert_eq!(s.total().blocks, 6);
    }
}
