//! The path model: what the picture draws, built as the events come.
//!
//! Coordinates are kept in micrometres (integers): an element drawn once
//! already (the same stroke, tool and coordinates) is not kept again, so a
//! loop that passes over the same path a thousand times costs the memory
//! of one pass; a straight move continuing the one before it in the same
//! direction (same stroke and tool) lengthens it instead of adding one.
//! Nothing drawn is dropped: a merged run covers every move in it.

use gcodec_exec::event::Plane;
use indexmap::IndexSet;
use rustc_hash::FxBuildHasher;

use crate::geometry::{ArcPath, Point3};

/// The grid the model keeps coordinates on: 1 µm (mm × 1000).
const GRID: f64 = 1000.0;

/// How far (mm) the end of a straight move may lie off the line of the
/// run before it and still lengthen it: far below anything drawn.
const COLLINEAR: f64 = 1e-4;

/// How an element is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stroke {
    /// `G0`: dashed.
    Rapid,
    /// A feed move of the tool (its centre, under compensation): in the
    /// tool's colour.
    Feed,
    /// The programmed contour of a feed move under tool radius
    /// compensation: thin grey, beneath the tool's path.
    Contour,
}

/// A point on the model's grid.
pub type GridPoint = [i64; 3];

/// The geometry of an element, on the grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Shape {
    Line {
        from: GridPoint,
        to: GridPoint,
    },
    /// An arc or helix of `plane` about `centre` (its abscissa and
    /// ordinate).
    Arc {
        plane: Plane,
        from: GridPoint,
        to: GridPoint,
        centre: [i64; 2],
        clockwise: bool,
        turns: u32,
    },
}

impl Shape {
    /// The arc, resolved; `None` for a line.
    pub fn arc(&self) -> Option<ArcPath> {
        match *self {
            Self::Line { .. } => None,
            Self::Arc {
                plane,
                from,
                to,
                centre,
                clockwise,
                turns,
            } => Some(ArcPath::new(
                plane,
                mm(from),
                mm(to),
                (centre[0] as f64 / GRID, centre[1] as f64 / GRID),
                clockwise,
                turns,
            )),
        }
    }

    /// The start point in mm.
    pub fn from(&self) -> Point3 {
        match *self {
            Self::Line { from, .. } | Self::Arc { from, .. } => mm(from),
        }
    }

    /// The end point in mm.
    pub fn to(&self) -> Point3 {
        match *self {
            Self::Line { to, .. } | Self::Arc { to, .. } => mm(to),
        }
    }
}

/// One element of the picture.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Element {
    pub stroke: Stroke,
    /// The index of the tool in [`PathModel::tools`].
    pub tool: u32,
    pub shape: Shape,
}

/// The point on the grid nearest `p` (mm).
pub fn grid(p: Point3) -> GridPoint {
    // `as` saturates and makes NaN 0: no input panics.
    p.map(|c| (c * GRID).round() as i64)
}

/// A grid point in mm.
pub fn mm(p: GridPoint) -> Point3 {
    p.map(|c| c as f64 / GRID)
}

/// A straight run still open for merging.
#[derive(Clone, Copy, Debug)]
struct OpenLine {
    stroke: Stroke,
    tool: u32,
    from: Point3,
    to: Point3,
}

impl OpenLine {
    /// Whether the move `from` → `to` continues this run in its direction.
    fn continued_by(&self, stroke: Stroke, tool: u32, from: Point3, to: Point3) -> bool {
        if stroke != self.stroke || tool != self.tool || grid(from) != grid(self.to) {
            return false;
        }
        let run = sub(self.to, self.from);
        let next = sub(to, from);
        let run_length = dot(run, run).sqrt();
        if run_length == 0.0 || dot(run, next) <= 0.0 {
            return false;
        }
        // The distance of the new end from the run's line.
        let off = sub(to, self.from);
        let along = dot(off, run) / run_length;
        let across = (dot(off, off) - along * along).max(0.0).sqrt();
        across <= COLLINEAR
    }
}

/// What the legend says of a tool.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ToolFigures {
    /// The tool's name (`T1`, `DRILL_10`); `None`: no tool in the spindle.
    pub name: Option<String>,
    /// The length of its feed moves (the tool centre's path under
    /// compensation), mm.
    pub feed_length: f64,
    /// Of those, the length of the moves with a time: `G94`, a feed above
    /// zero.
    pub timed_length: f64,
    /// Their time, minutes: length / feed.
    pub feed_time: f64,
    /// The length of its rapid moves, mm.
    pub rapid_length: f64,
}

/// The picture's content: the elements in the order they were first
/// drawn, and the tools.
#[derive(Clone, Debug)]
pub struct PathModel {
    /// Hashed with Fx: an element is a handful of integers, and SipHash
    /// would be most of the cost of keeping one.
    elements: IndexSet<Element, FxBuildHasher>,
    /// The open run of the tool's path and of the contour (which merge
    /// independently: under compensation they alternate).
    open_path: Option<OpenLine>,
    open_contour: Option<OpenLine>,
    /// Index 0 is "no tool"; the others in the order the tools appeared.
    tools: Vec<ToolFigures>,
}

impl Default for PathModel {
    fn default() -> Self {
        Self {
            elements: IndexSet::default(),
            open_path: None,
            open_contour: None,
            tools: vec![ToolFigures::default()],
        }
    }
}

impl PathModel {
    pub fn new() -> Self {
        Self::default()
    }

    /// The index of the tool named `name`, added if new.
    pub fn tool(&mut self, name: Option<&str>) -> u32 {
        let index = match self.tools.iter().position(|t| t.name.as_deref() == name) {
            Some(index) => index,
            None => {
                self.tools.push(ToolFigures {
                    name: name.map(str::to_owned),
                    ..ToolFigures::default()
                });
                self.tools.len() - 1
            }
        };
        index as u32
    }

    /// The tools, "no tool" first, then in the order they appeared.
    pub fn tools(&self) -> &[ToolFigures] {
        &self.tools
    }

    /// The figures of tool `tool`, to add to.
    pub fn figures_mut(&mut self, tool: u32) -> &mut ToolFigures {
        let last = self.tools.len() - 1;
        &mut self.tools[(tool as usize).min(last)]
    }

    /// Draws a straight move (mm); a move of no length on the grid draws
    /// nothing.
    pub fn line(&mut self, stroke: Stroke, tool: u32, from: Point3, to: Point3) {
        if grid(from) == grid(to) || !finite(from) || !finite(to) {
            return;
        }
        let slot = self.slot(stroke);
        if let Some(open) = slot
            && open.continued_by(stroke, tool, from, to)
        {
            open.to = to;
            return;
        }
        let previous = slot.replace(OpenLine {
            stroke,
            tool,
            from,
            to,
        });
        if let Some(previous) = previous {
            self.close(previous);
        }
    }

    /// Draws an arc or helix of `plane` about `centre` (mm).
    #[allow(clippy::too_many_arguments)]
    pub fn arc(
        &mut self,
        stroke: Stroke,
        tool: u32,
        plane: Plane,
        from: Point3,
        to: Point3,
        centre: (f64, f64),
        clockwise: bool,
        turns: u32,
    ) {
        if !finite(from) || !finite(to) || !centre.0.is_finite() || !centre.1.is_finite() {
            return;
        }
        if let Some(previous) = self.slot(stroke).take() {
            self.close(previous);
        }
        let centre = grid([centre.0, centre.1, 0.0]);
        self.elements.insert(Element {
            stroke,
            tool,
            shape: Shape::Arc {
                plane,
                from: grid(from),
                to: grid(to),
                centre: [centre[0], centre[1]],
                clockwise,
                turns,
            },
        });
    }

    /// Closes the open runs: call once the events have ended.
    pub fn finish(&mut self) {
        for open in [self.open_path.take(), self.open_contour.take()]
            .into_iter()
            .flatten()
        {
            self.close(open);
        }
    }

    /// The elements, in the order they were first drawn (open runs not
    /// yet [`PathModel::finish`]ed left out).
    pub fn elements(&self) -> impl ExactSizeIterator<Item = &Element> + '_ {
        self.elements.iter()
    }

    fn slot(&mut self, stroke: Stroke) -> &mut Option<OpenLine> {
        match stroke {
            Stroke::Contour => &mut self.open_contour,
            Stroke::Rapid | Stroke::Feed => &mut self.open_path,
        }
    }

    fn close(&mut self, line: OpenLine) {
        self.elements.insert(Element {
            stroke: line.stroke,
            tool: line.tool,
            shape: Shape::Line {
                from: grid(line.from),
                to: grid(line.to),
            },
        });
    }
}

fn finite(p: Point3) -> bool {
    p.iter().all(|c| c.is_finite())
}

fn sub(a: Point3, b: Point3) -> Point3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: Point3, b: Point3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(model: &PathModel) -> Vec<(GridPoint, GridPoint)> {
        model
            .elements()
            .map(|e| match e.shape {
                Shape::Line { from, to } => (from, to),
                Shape::Arc { .. } => panic!("an arc"),
            })
            .collect()
    }

    #[test]
    fn a_straight_run_is_one_element_and_a_corner_starts_another() {
        let mut model = PathModel::new();
        for x in 0..10 {
            let x = f64::from(x);
            model.line(Stroke::Feed, 0, [x, 0.0, 0.0], [x + 1.0, 0.0, 0.0]);
        }
        model.line(Stroke::Feed, 0, [10.0, 0.0, 0.0], [10.0, 5.0, 0.0]);
        model.finish();
        assert_eq!(
            lines(&model),
            [
                ([0, 0, 0], [10_000, 0, 0]),
                ([10_000, 0, 0], [10_000, 5_000, 0])
            ]
        );
    }

    #[test]
    fn a_run_does_not_merge_across_strokes_tools_or_a_reversal() {
        let mut model = PathModel::new();
        model.line(Stroke::Feed, 0, [0.0; 3], [1.0, 0.0, 0.0]);
        model.line(Stroke::Rapid, 0, [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]);
        model.line(Stroke::Rapid, 1, [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]);
        model.line(Stroke::Rapid, 1, [3.0, 0.0, 0.0], [2.5, 0.0, 0.0]);
        model.finish();
        assert_eq!(model.elements().len(), 4);
    }

    #[test]
    fn a_path_passed_over_again_is_kept_once() {
        let mut model = PathModel::new();
        for _ in 0..1000 {
            model.line(Stroke::Feed, 0, [0.0; 3], [1.0, 0.0, 0.0]);
            model.line(Stroke::Feed, 0, [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]);
            model.line(Stroke::Rapid, 0, [1.0, 1.0, 0.0], [0.0, 0.0, 0.0]);
        }
        model.finish();
        assert_eq!(model.elements().len(), 3);
    }
}
