//! [`PlotSink`]: the events of a run, turned into a [`PathModel`] as they
//! come.

use std::io;

use gcodec_exec::event::{
    AxisMap, Event, EventKind, EventSink, InsertedElement, MotionEvent, MotionKind, Plane, ToolArc,
};

use crate::geometry::{ArcPath, Point3};
use crate::model::{PathModel, Stroke};
use crate::view::View;

/// The geometry axes by index, as the events name them.
const AXES: [&str; 3] = ["X", "Y", "Z"];

/// mm per inch: positions and feeds under `G70`/`G700` are in inches.
const INCH: f64 = 25.4;

/// Collects the picture of a run: hand it every event (it is an
/// [`EventSink`]), then take the [`Plot`] with [`PlotSink::into_plot`].
/// It keeps the drawn geometry only ([`PathModel`]), never the events.
#[derive(Clone, Debug)]
pub struct PlotSink {
    model: PathModel,
    /// The view asked for; `None`: the plane of the first motion.
    view: Option<View>,
    first_plane: Option<Plane>,
    /// The tool in the spindle, an index into the model's tools.
    tool: u32,
    /// mm per unit of the positions: 1, or 25.4 under `G70`/`G700`.
    unit: f64,
    /// Under tool radius compensation, where the tool centre's path got
    /// to; `None` while compensation is off.
    tool_end: Option<Point3>,
    /// The direction the programmed path left off in (for `CT`).
    tangent: Option<Point3>,
}

/// A finished picture: the model and the view it is seen in.
#[derive(Clone, Debug)]
pub struct Plot {
    pub model: PathModel,
    pub view: View,
}

impl Default for PlotSink {
    fn default() -> Self {
        Self::new(None)
    }
}

impl PlotSink {
    /// A sink drawing in `view`; `None`: in the plane of the first motion
    /// (`G17` if there is none).
    pub fn new(view: Option<View>) -> Self {
        Self {
            model: PathModel::new(),
            view,
            first_plane: None,
            tool: 0,
            unit: 1.0,
            tool_end: None,
            tangent: None,
        }
    }

    /// Takes one event into the picture.
    pub fn plot(&mut self, event: &Event) {
        match &event.kind {
            EventKind::Motion(motion) => self.motion(motion),
            EventKind::ToolChange(change) if change.committed => {
                self.tool = self.model.tool(change.new_tool.as_deref());
            }
            EventKind::ModalChange(change) if change.group == 13 => {
                self.unit = match &*change.code {
                    "G70" | "G700" => INCH,
                    _ => 1.0,
                };
            }
            _ => {}
        }
    }

    /// The picture: the open runs closed, the view settled.
    pub fn into_plot(mut self) -> Plot {
        self.model.finish();
        let view = self
            .view
            .or(self.first_plane.map(View::Plane))
            .unwrap_or(View::Plane(Plane::G17));
        Plot {
            model: self.model,
            view,
        }
    }

    fn point(&self, axes: &AxisMap) -> Point3 {
        AXES.map(|axis| axes.get(axis).unwrap_or(0.0) * self.unit)
    }

    fn motion(&mut self, motion: &MotionEvent) {
        self.first_plane.get_or_insert(motion.plane);
        let from = self.point(&motion.from);
        let to = self.point(&motion.to);
        let stroke = match motion.motion {
            MotionKind::Rapid => Stroke::Rapid,
            _ => Stroke::Feed,
        };
        let arc = self.arc_of(motion, from, to);
        let contour_moves = !matches!(
            motion.inserted,
            Some(
                InsertedElement::TransitionCircle
                    | InsertedElement::CornerLine
                    | InsertedElement::TransitionCurve
            )
        );
        let length = match &motion.tool {
            Some(tool) => {
                let tool_from = self.tool_end.unwrap_or(from);
                let tool_to = self.point(&tool.tool_to);
                if stroke == Stroke::Feed && contour_moves {
                    self.draw(Stroke::Contour, from, to, arc);
                }
                // The tool centre's own circle (a `KONTT` approach or
                // retraction of a straight block), else the contour's
                // element, concentric.
                let tool_arc = match &tool.tool_arc {
                    Some(own) => self.own_arc(own, motion.plane),
                    None => arc,
                };
                self.tool_end = Some(tool_to);
                self.draw(stroke, tool_from, tool_to, tool_arc)
            }
            // The move that ends compensation starts where the tool
            // centre is.
            None => {
                let from = self.tool_end.take().unwrap_or(from);
                self.draw(stroke, from, to, arc)
            }
        };
        if contour_moves {
            self.tangent = end_tangent(from, to, arc.map(|a| a.path(from, to))).or(self.tangent);
        }
        let figures = self.model.figures_mut(self.tool);
        match stroke {
            Stroke::Rapid => figures.rapid_length += length,
            _ => {
                figures.feed_length += length;
                let feed = motion.feed.unwrap_or(0.0) * self.unit;
                if motion.feed_mode == "G94" && feed > 0.0 && length.is_finite() {
                    figures.timed_length += length;
                    figures.feed_time += length / feed;
                }
            }
        }
    }

    /// Draws `from` → `to` along `arc` if one; its length.
    fn draw(&mut self, stroke: Stroke, from: Point3, to: Point3, arc: Option<ArcOf>) -> f64 {
        let tool = self.tool;
        match arc {
            Some(arc) => {
                self.model.arc(
                    stroke,
                    tool,
                    arc.plane,
                    from,
                    to,
                    arc.centre,
                    arc.clockwise,
                    arc.turns,
                );
                arc.path(from, to).length()
            }
            None => {
                self.model.line(stroke, tool, from, to);
                distance(from, to)
            }
        }
    }

    /// The circle a motion goes along, if it is an arc the event gives the
    /// centre of.
    fn arc_of(&self, motion: &MotionEvent, from: Point3, to: Point3) -> Option<ArcOf> {
        let plane = motion.plane;
        let (h, v, _) = plane.axes();
        let centres = motion.centre.as_ref()?;
        let centre = (
            centres.get(AXES[h])? * self.unit,
            centres.get(AXES[v])? * self.unit,
        );
        let clockwise = match motion.motion {
            MotionKind::ArcCw => true,
            MotionKind::ArcCcw => false,
            // `CT` leaves the start along the previous path: the centre is
            // on the left of that tangent for a counter-clockwise arc.
            MotionKind::ArcTangential => {
                let t = self.tangent?;
                cross(t[h], t[v], centre.0 - from[h], centre.1 - from[v]) < 0.0
            }
            // The event does not say which way a `CIP` circle turns: the
            // shorter way round.
            MotionKind::ArcThroughPoint => {
                cross(
                    from[h] - centre.0,
                    from[v] - centre.1,
                    to[h] - centre.0,
                    to[v] - centre.1,
                ) < 0.0
            }
            _ => return None,
        };
        Some(ArcOf {
            plane,
            centre,
            clockwise,
            turns: motion.turns,
        })
    }
}

impl PlotSink {
    /// The tool centre's own circle of an element, in `plane`; `None`
    /// (a straight piece) if the event names no centre in the plane.
    fn own_arc(&self, own: &ToolArc, plane: Plane) -> Option<ArcOf> {
        let (h, v, _) = plane.axes();
        let centre = (
            own.centre.get(AXES[h])? * self.unit,
            own.centre.get(AXES[v])? * self.unit,
        );
        let clockwise = match own.motion {
            MotionKind::ArcCw => true,
            MotionKind::ArcCcw => false,
            _ => return None,
        };
        Some(ArcOf {
            plane,
            centre,
            clockwise,
            turns: 0,
        })
    }
}

impl EventSink for PlotSink {
    fn event(&mut self, event: &Event) -> io::Result<()> {
        self.plot(event);
        Ok(())
    }
}

/// The circle of an arc motion, its end points aside.
#[derive(Clone, Copy, Debug)]
struct ArcOf {
    plane: Plane,
    centre: (f64, f64),
    clockwise: bool,
    turns: u32,
}

impl ArcOf {
    fn path(&self, from: Point3, to: Point3) -> ArcPath {
        ArcPath::new(
            self.plane,
            from,
            to,
            self.centre,
            self.clockwise,
            self.turns,
        )
    }
}

/// The direction a path leaves off in at its end; `None` for no motion.
fn end_tangent(from: Point3, to: Point3, arc: Option<ArcPath>) -> Option<Point3> {
    let (p, q) = match arc {
        Some(arc) => (arc.point_at(1.0 - 1e-6), arc.point_at(1.0)),
        None => (from, to),
    };
    let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
    (d != [0.0; 3]).then_some(d)
}

fn cross(ax: f64, ay: f64, bx: f64, by: f64) -> f64 {
    ax * by - ay * bx
}

fn distance(a: Point3, b: Point3) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}
