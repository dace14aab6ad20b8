//! A picture of a run: `gcodec plot`.
//!
//! [`PlotSink`] is an [`EventSink`](gcodec_exec::event::EventSink) that
//! turns a run's events into a [`PathModel`] as they come: straight runs
//! in one direction merged, a path passed over again kept once, so memory
//! grows with the distinct geometry drawn, not with the length of the run.
//! [`Plot::to_svg`] renders it: rapids dashed, feed moves in a colour per
//! tool, arcs of the view's plane as SVG arcs, everything else as
//! polylines; under tool radius compensation the programmed contour thin
//! grey beneath the tool centre's path. SPEC §11.11 says what is drawn.
//!
//! Only the public event types are read: nothing of the executor.

mod geometry;
mod model;
mod number;
mod sink;
mod style;
mod svg;
mod view;

pub use geometry::{ArcPath, CHORD_TOLERANCE, Point3};
pub use model::{Element, PathModel, Shape, Stroke, ToolFigures};
pub use sink::{Plot, PlotSink};
pub use style::{NO_TOOL, PALETTE, tool_colour};
pub use view::{UnknownView, View};
