//! The picture as SVG text: the path, the box round it with its
//! dimensions, a scale bar, a legend per tool and a title.
//!
//! The same plot always gives the same bytes: coordinates are written to
//! 0.01 px ([`crate::number`]), elements in the order they were first
//! drawn, no date or random id.

use std::f64::consts::{PI, TAU};
use std::fmt::Write;

use crate::geometry::{ArcPath, Point3};
use crate::model::{Element, PathModel, Stroke};
use crate::number::write_fixed;
use crate::sink::Plot;
use crate::style::{CSS, scale_bar_length, tool_colour};
use crate::view::View;

/// The page's width, px.
const WIDTH: f64 = 800.0;
/// The space round everything, px.
const MARGIN: f64 = 20.0;
/// The band of the title, px.
const TITLE_BAND: f64 = 40.0;
/// The space between the box and the path in it, px.
const PADDING: f64 = 10.0;
/// The most the path is drawn high, px (it is drawn `WIDTH` wide or less).
const MAX_PATH_HEIGHT: f64 = 560.0;
/// The longest the scale bar is drawn, px.
const MAX_BAR: f64 = 120.0;
/// A row of the legend, px.
const ROW: f64 = 18.0;
/// The radius of the circle a move seen end on is drawn as, px.
const DOT: f64 = 1.0;
/// That circle from its centre, relative: two half circles.
const DOT_PATH: &str = " m-1 0 a1 1 0 1 0 2 0 a1 1 0 1 0 -2 0";
/// Coordinates in px are written to this many decimals.
const DECIMALS: u32 = 2;

/// The bounds of the path: on the page (horizontal, vertical up, mm) and
/// in space (mm).
#[derive(Clone, Copy, Debug)]
struct Bounds {
    page: [f64; 4],
    space: [Point3; 2],
}

impl Bounds {
    fn new() -> Self {
        Self {
            page: [
                f64::INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::NEG_INFINITY,
            ],
            space: [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]],
        }
    }

    fn add(&mut self, view: View, p: Point3) {
        let (u, v) = view.project(p);
        self.page = [
            self.page[0].min(u),
            self.page[1].min(v),
            self.page[2].max(u),
            self.page[3].max(v),
        ];
        let [low, high] = &mut self.space;
        for ((low, high), c) in low.iter_mut().zip(high.iter_mut()).zip(p) {
            *low = low.min(c);
            *high = high.max(c);
        }
    }

    fn is_empty(&self) -> bool {
        // Still infinite (NaN never reaches the bounds: the model keeps
        // finite points only).
        self.page[0] > self.page[2]
    }
}

/// How a path of the page maps model points to px.
#[derive(Clone, Copy, Debug)]
struct Page {
    view: View,
    /// px per mm.
    scale: f64,
    /// The page's top left of the path's bounds, in mm (horizontal, top).
    left: f64,
    top: f64,
    /// The px of that point.
    x0: f64,
    y0: f64,
}

impl Page {
    fn px(&self, p: Point3) -> (f64, f64) {
        let (u, v) = self.view.project(p);
        (
            self.x0 + (u - self.left) * self.scale,
            self.y0 + (self.top - v) * self.scale,
        )
    }
}

/// Writes the picture's path elements (`<path>`), one for each run of
/// elements drawn alike, continuing the path where an element starts at
/// the end of the one before.
struct PathWriter<'a> {
    out: &'a mut String,
    page: Page,
    /// The class of the open `<path>`.
    class: Option<(Stroke, u32)>,
    /// The end of the open path, px as written.
    at: Option<(i64, i64)>,
}

impl<'a> PathWriter<'a> {
    fn new(out: &'a mut String, page: Page) -> Self {
        Self {
            out,
            page,
            class: None,
            at: None,
        }
    }

    fn element(&mut self, element: &Element) {
        let class = (element.stroke, element.tool);
        let shape = &element.shape;
        let (x, y) = self.page.px(shape.from());
        let start = key(x, y);
        let end_on = shape.arc().is_none() && {
            let (u, v) = self.page.px(shape.to());
            start == key(u, v)
        };
        // A move seen end on (a plunge, a drilled hole in the plan) is a
        // dot where the path is not drawn already; a rapid's dot says
        // nothing.
        if end_on
            && (element.stroke == Stroke::Rapid
                || (self.class == Some(class) && self.at == Some(start)))
        {
            return;
        }
        if self.class != Some(class) {
            self.close();
            self.out.push_str("<path class=\"");
            self.out.push_str(&class_name(element.stroke, element.tool));
            self.out.push_str("\" d=\"");
            self.class = Some(class);
        }
        self.move_to(shape.from());
        match shape.arc() {
            None if end_on => self.dot(shape.from()),
            None => self.line_to(shape.to()),
            Some(arc) if Some(arc.plane) == self.page.view.plane() && arc.is_flat() => {
                self.arc_to(&arc, shape.to());
            }
            Some(arc) => {
                for p in arc.polyline().skip(1) {
                    self.line_to(p);
                }
            }
        }
    }

    fn close(&mut self) {
        if self.class.take().is_some() {
            self.out.push_str("\"/>\n");
        }
        self.at = None;
    }

    fn move_to(&mut self, p: Point3) {
        let (x, y) = self.page.px(p);
        let key = key(x, y);
        if self.at != Some(key) {
            if self.at.is_some() {
                self.out.push(' ');
            }
            self.out.push('M');
            self.point(x, y);
            self.at = Some(key);
        }
    }

    /// A dot at `p`: a circle of `DOT` px radius, which the stroke
    /// fills (a zero-length line's round caps are not drawn by every
    /// renderer).
    fn dot(&mut self, p: Point3) {
        let (x, y) = self.page.px(p);
        self.out.push_str(DOT_PATH);
        self.at = Some(key(x - DOT, y));
    }

    fn line_to(&mut self, p: Point3) {
        let (x, y) = self.page.px(p);
        self.out.push_str(" L");
        self.point(x, y);
        self.at = Some(key(x, y));
    }

    /// An arc in the page's plane: SVG's `A`, whose y axis points down,
    /// so that a clockwise arc (a negative sweep) has sweep flag 1. A
    /// full circle is two halves (one `A` cannot close a circle).
    fn arc_to(&mut self, arc: &ArcPath, end: Point3) {
        if arc.sweep.abs() >= TAU - 1e-9 {
            let half = ArcPath {
                sweep: arc.sweep / 2.0,
                ..*arc
            };
            self.arc_segment(&half, arc.point_at(0.5));
            self.arc_segment(&half, end);
        } else {
            self.arc_segment(arc, end);
        }
    }

    fn arc_segment(&mut self, arc: &ArcPath, end: Point3) {
        let radius = arc.radius * self.page.scale;
        let (x, y) = self.page.px(end);
        self.out.push_str(" A");
        write_fixed(self.out, radius, DECIMALS);
        self.out.push(' ');
        write_fixed(self.out, radius, DECIMALS);
        self.out.push_str(" 0 ");
        self.out.push(if arc.sweep.abs() > PI { '1' } else { '0' });
        self.out.push(' ');
        self.out.push(if arc.sweep < 0.0 { '1' } else { '0' });
        self.out.push(' ');
        self.point(x, y);
        self.at = Some(key(x, y));
    }

    fn point(&mut self, x: f64, y: f64) {
        write_fixed(self.out, x, DECIMALS);
        self.out.push(' ');
        write_fixed(self.out, y, DECIMALS);
    }
}

/// A px point as written, to compare.
fn key(x: f64, y: f64) -> (i64, i64) {
    ((x * 100.0).round() as i64, (y * 100.0).round() as i64)
}

fn class_name(stroke: Stroke, tool: u32) -> String {
    match stroke {
        Stroke::Rapid => "rapid".to_owned(),
        Stroke::Contour => "contour".to_owned(),
        Stroke::Feed => format!("feed t{tool}"),
    }
}

/// The bounds of every element seen in `view`.
fn bounds(model: &PathModel, view: View) -> Bounds {
    let mut bounds = Bounds::new();
    for element in model.elements() {
        match element.shape.arc() {
            None => {
                bounds.add(view, element.shape.from());
                bounds.add(view, element.shape.to());
            }
            // The exact extremes serve the bounds in space and in the
            // arc's own plane; any other projection bounds its polyline.
            Some(arc) if view.plane() == Some(arc.plane) => {
                for p in arc.extremes() {
                    bounds.add(view, p);
                }
            }
            Some(arc) => {
                for p in arc.extremes().chain(arc.polyline()) {
                    bounds.add(view, p);
                }
            }
        }
    }
    bounds
}

/// Escapes text for XML, replacing the control characters XML 1.0 does
/// not allow.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c if c.is_control() => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

impl Plot {
    /// The picture as SVG text, titled `title` (the program's file name).
    pub fn to_svg(&self, title: &str) -> String {
        let model = &self.model;
        let view = self.view;
        let bounds = bounds(model, view);
        let (width, height) = if bounds.is_empty() {
            (0.0, 0.0)
        } else {
            (
                bounds.page[2] - bounds.page[0],
                bounds.page[3] - bounds.page[1],
            )
        };
        let room = WIDTH - 2.0 * (MARGIN + PADDING);
        let scale = match (width > 0.0, height > 0.0) {
            (true, true) => (room / width).min(MAX_PATH_HEIGHT / height),
            (true, false) => room / width,
            (false, true) => MAX_PATH_HEIGHT / height,
            (false, false) => 1.0,
        };
        let page = Page {
            view,
            scale,
            left: bounds.page[0],
            top: bounds.page[3],
            x0: MARGIN + PADDING,
            y0: TITLE_BAND + PADDING,
        };
        let box_height = height * scale + 2.0 * PADDING;
        let tools: Vec<(u32, &crate::model::ToolFigures)> = model
            .tools()
            .iter()
            .enumerate()
            .filter(|(_, t)| t.feed_length > 0.0 || t.rapid_length > 0.0)
            .map(|(i, t)| (i as u32, t))
            .collect();
        let has_contour = model.elements().any(|e| e.stroke == Stroke::Contour);
        let rows = tools.len() + 1 + usize::from(has_contour);
        let below = TITLE_BAND + box_height + 12.0;
        let page_height = (below + 30.0 + rows as f64 * ROW + MARGIN).ceil();

        let mut out = String::with_capacity(4096 + model.elements().len() * 32);
        let _ = writeln!(
            out,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\" font-family=\"sans-serif\" font-size=\"12px\">",
            w = WIDTH,
            h = page_height
        );
        let title = escape(title);
        let _ = writeln!(out, "<title>{title}</title>");
        out.push_str("<style>");
        out.push_str(CSS);
        for (index, _) in &tools {
            let _ = write!(out, ".t{index}{{stroke:{}}}", tool_colour(*index));
        }
        out.push_str("</style>\n");
        let _ = writeln!(
            out,
            "<rect width=\"{WIDTH}\" height=\"{page_height}\" fill=\"#ffffff\"/>"
        );
        let _ = writeln!(
            out,
            "<text class=\"title\" x=\"{MARGIN}\" y=\"26\">{title} (view {view})</text>"
        );
        if bounds.is_empty() {
            let _ = writeln!(
                out,
                "<text x=\"{MARGIN}\" y=\"{}\">no motion</text>",
                TITLE_BAND + 16.0
            );
        } else {
            out.push_str("<rect class=\"box\" x=\"");
            write_fixed(&mut out, MARGIN, DECIMALS);
            out.push_str("\" y=\"");
            write_fixed(&mut out, TITLE_BAND, DECIMALS);
            out.push_str("\" width=\"");
            write_fixed(&mut out, width * scale + 2.0 * PADDING, DECIMALS);
            out.push_str("\" height=\"");
            write_fixed(&mut out, box_height, DECIMALS);
            out.push_str("\"/>\n");
            for (name, contour) in [("contour", true), ("path", false)] {
                if contour && !has_contour {
                    continue;
                }
                let _ = writeln!(out, "<g id=\"{name}\">");
                let mut paths = PathWriter::new(&mut out, page);
                for element in model
                    .elements()
                    .filter(|e| (e.stroke == Stroke::Contour) == contour)
                {
                    paths.element(element);
                }
                paths.close();
                out.push_str("</g>\n");
            }
            let [low, high] = bounds.space;
            let _ = writeln!(
                out,
                "<text x=\"{MARGIN}\" y=\"{}\">bounding box X {:.3} × Y {:.3} × Z {:.3} mm</text>",
                fixed_px(below + 4.0),
                high[0] - low[0],
                high[1] - low[1],
                high[2] - low[2],
            );
            if let Some(length) = scale_bar_length(scale, MAX_BAR) {
                let right = WIDTH - MARGIN;
                let left = right - length * scale;
                let y = below;
                let mut bar = String::new();
                bar.push('M');
                for (x, y) in [(left, y - 4.0), (left, y), (right, y), (right, y - 4.0)] {
                    write_fixed(&mut bar, x, DECIMALS);
                    bar.push(' ');
                    write_fixed(&mut bar, y, DECIMALS);
                    bar.push_str(" L");
                }
                bar.truncate(bar.len() - 2);
                let _ = writeln!(out, "<path class=\"bar\" d=\"{bar}\"/>");
                let _ = writeln!(
                    out,
                    "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{} mm</text>",
                    fixed_px(left - 6.0),
                    fixed_px(y + 4.0),
                    crate::number::fixed(length, 6),
                );
            }
        }
        legend(&mut out, &tools, has_contour, below + 30.0);
        out.push_str("</svg>\n");
        out
    }
}

fn fixed_px(value: f64) -> String {
    crate::number::fixed(value, DECIMALS)
}

/// A row per tool (its colour, name, feed length and time), then the
/// rapids and, under compensation, the contour.
fn legend(
    out: &mut String,
    tools: &[(u32, &crate::model::ToolFigures)],
    has_contour: bool,
    top: f64,
) {
    let mut y = top;
    let mut row = |out: &mut String, class: &str, text: String| {
        let _ = writeln!(
            out,
            "<path class=\"{class}\" d=\"M{MARGIN} {sy} L{end} {sy}\"/>\
             <text x=\"{tx}\" y=\"{ty}\">{text}</text>",
            sy = fixed_px(y - 4.0),
            end = MARGIN + 24.0,
            tx = MARGIN + 32.0,
            ty = fixed_px(y),
        );
        y += ROW;
    };
    let mut rapid_length = 0.0;
    for (index, figures) in tools {
        rapid_length += figures.rapid_length;
        let name = figures
            .name
            .as_deref()
            .map_or_else(|| "no tool".to_owned(), escape);
        let mut text = format!("{name}: feed {:.1} mm", figures.feed_length);
        if figures.timed_length > 0.0 {
            let _ = write!(text, ", {:.2} min", figures.feed_time);
        }
        let untimed = figures.feed_length - figures.timed_length;
        if untimed > 1e-9 * figures.feed_length.max(1.0) {
            let _ = write!(text, " ({untimed:.1} mm without a G94 feed)");
        }
        row(out, &format!("feed t{index}"), text);
    }
    row(
        out,
        "rapid",
        format!("rapid traverse: {rapid_length:.1} mm"),
    );
    if has_contour {
        row(
            out,
            "contour",
            "programmed contour (the tool centre's path is coloured)".to_owned(),
        );
    }
}
