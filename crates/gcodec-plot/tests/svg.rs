//! The SVG of small programs, as snapshots: what each part of SPEC
//! §11.11 draws. Read a snapshot's paths against the program above it.

mod common;

use gcodec_driver::event::{InsertedElement, MotionKind, Plane};
use gcodec_plot::View;

use common::{about, compensated, event, inserted, motion, plot_program, run_on, tool_change, xyz};

fn svg(name: &str, text: &str, view: Option<View>) -> String {
    plot_program(name, text, view).to_svg(name)
}

#[test]
fn a_square_with_rapids() {
    let text = "N10 G17 G90 G94 T1 M6\n\
                N20 G0 X0 Y0 Z5\n\
                N30 G1 Z-1 F200\n\
                N40 X20 F500\n\
                N50 Y20\n\
                N60 X0\n\
                N70 Y0\n\
                N80 G0 Z5\n\
                N90 X30 Y30\n\
                N100 M30\n";
    insta::assert_snapshot!(svg("square.mpf", text, None));
}

#[test]
fn arcs_in_g17_clockwise_and_counter_clockwise() {
    // A clockwise half circle over the top, a counter-clockwise one
    // beneath, a counter-clockwise three-quarter arc (large-arc flag)
    // and a clockwise full circle (two halves).
    let text = "N10 G17 G90 G94 T1 M6\n\
                N20 G0 X0 Y0 Z0\n\
                N30 G2 X20 Y0 I10 F500\n\
                N40 G3 X40 Y0 I10\n\
                N50 G3 X50 Y10 I10\n\
                N60 G2 X50 Y10 J-5\n\
                N70 M30\n";
    insta::assert_snapshot!(svg("arcs_g17.mpf", text, None));
}

#[test]
fn an_arc_in_g18_is_seen_with_z_right_and_x_up() {
    // `G2` from Z0 to Z20 about Z10: clockwise seen from +Y, over the
    // top (X up to 10).
    let text = "N10 G18 G90 G94 T1 M6\n\
                N20 G0 X0 Z0\n\
                N30 G2 X0 Z20 K10 F500\n\
                N40 G1 X-5\n\
                N50 M30\n";
    insta::assert_snapshot!(svg("arc_g18.mpf", text, None));
}

#[test]
fn a_helix_is_a_polyline() {
    // Three turns of radius 10 with a lead of -2.
    let text = "N10 G17 G90 G94 T1 M6\n\
                N20 G0 X10 Y0 Z0\n\
                N30 G3 X10 Y0 Z-6 I-10 TURN=2 F300\n\
                N40 M30\n";
    let plot = plot_program("helix.mpf", text, None);
    insta::assert_snapshot!("helix_xy", plot.to_svg("helix.mpf"));
    let side = plot_program("helix.mpf", text, Some(View::Plane(Plane::G18)));
    insta::assert_snapshot!("helix_xz", side.to_svg("helix.mpf"));
}

#[test]
fn two_tools_have_two_colours_and_two_legend_rows() {
    let text = "N10 G17 G90 G94 T1 M6\n\
                N20 G0 X0 Y0 Z1\n\
                N30 G1 X30 F600\n\
                N40 G0 Z20\n\
                N50 T2 M6\n\
                N60 G0 X0 Y10\n\
                N70 G1 X30 F300\n\
                N80 M30\n";
    insta::assert_snapshot!(svg("two_tools.mpf", text, None));
}

#[test]
fn a_g18_program_plotted_in_xy() {
    // The G18 arc seen from above is a polyline along X; the straight
    // moves in Y are true length.
    let text = "N10 G18 G90 G94 T1 M6\n\
                N20 G0 X0 Y0 Z0\n\
                N30 G2 X0 Z20 K10 F500\n\
                N40 G1 Y10\n\
                N50 G1 X20\n\
                N60 M30\n";
    insta::assert_snapshot!(svg("g18_in_xy.mpf", text, Some(View::Plane(Plane::G17))));
}

#[test]
fn iso_view() {
    let text = "N10 G17 G90 G94 T1 M6\n\
                N20 G0 X0 Y0 Z5\n\
                N30 G1 Z0 F200\n\
                N40 X20\n\
                N50 G3 X20 Y20 J10\n\
                N60 G1 X0\n\
                N70 Y0\n\
                N80 M30\n";
    insta::assert_snapshot!(svg("iso.mpf", text, Some(View::Iso)));
}

#[test]
fn compensation_draws_the_contour_and_the_tool_centre() {
    // A hand-built stream (compensation is not simulated yet): G42 with
    // a radius-5 tool round the outside of a square's corner (20, 0): an
    // approach that starts compensation, a straight side, the transition
    // circle of the tool centre round the corner (the contour stands),
    // the next side, then G40 off.
    use MotionKind::{ArcCcw, Linear, Rapid};
    let events = [
        tool_change(1, "T7"),
        event(2, motion(Rapid, xyz(0.0, 0.0, 0.0), xyz(-10.0, -10.0, 0.0))),
        event(
            3,
            compensated(
                motion(Linear, xyz(-10.0, -10.0, 0.0), xyz(0.0, 0.0, 0.0)),
                xyz(0.0, -5.0, 0.0),
                5.0,
            ),
        ),
        event(
            4,
            compensated(
                motion(Linear, xyz(0.0, 0.0, 0.0), xyz(20.0, 0.0, 0.0)),
                xyz(20.0, -5.0, 0.0),
                5.0,
            ),
        ),
        event(
            4,
            inserted(
                compensated(
                    about(
                        motion(ArcCcw, xyz(20.0, 0.0, 0.0), xyz(20.0, 0.0, 0.0)),
                        20.0,
                        0.0,
                        0.0,
                    ),
                    xyz(25.0, 0.0, 0.0),
                    5.0,
                ),
                InsertedElement::TransitionCircle,
            ),
        ),
        event(
            5,
            compensated(
                motion(Linear, xyz(20.0, 0.0, 0.0), xyz(20.0, 20.0, 0.0)),
                xyz(25.0, 20.0, 0.0),
                5.0,
            ),
        ),
        event(
            6,
            motion(Linear, xyz(20.0, 20.0, 0.0), xyz(30.0, 30.0, 0.0)),
        ),
    ];
    let mut sink = gcodec_plot::PlotSink::new(None);
    for event in &events {
        sink.plot(event);
    }
    let plot = sink.into_plot();
    let figures = &plot.model.tools()[1];
    // The tool centre's path: (-10, -10) → (0, -5), 20, a quarter of
    // 2π·5 round the corner, 20, and from the tool centre (25, 20) to
    // (30, 30) as compensation ends.
    let expected = 2.0 * 125_f64.sqrt() + 40.0 + std::f64::consts::PI * 2.5;
    assert!((figures.feed_length - expected).abs() < 1e-9, "{figures:?}");
    insta::assert_snapshot!(plot.to_svg("compensated.mpf"));
}

#[test]
fn a_compensated_program_draws_its_contour_beneath_the_tool_centre() {
    // The executor's fixture machine (a radius-5 T1): a 40 × 30 block
    // milled round its outside with G41 G450, a rounding at one corner.
    // Each outside corner is a transition circle of the tool centre; the
    // contour (grey) has the rounding and no circles.
    let text = "N10 G17 G90 G54 T1 D1 M6\n\
                N20 G0 X-20 Y-10 Z2\n\
                N30 G1 Z-2 F300\n\
                N40 G41 G450 G1 X0 Y0\n\
                N50 Y30 RND=5\n\
                N60 X40\n\
                N70 Y0\n\
                N80 X0\n\
                N90 G40 G1 X-20 Y-10\n\
                N100 G0 Z50\n\
                M30\n";
    let svg = plot_on_fixture_machine("compensated_run.mpf", text);
    let contour = group(&svg, "contour");
    assert_eq!(contour.matches(" A").count(), 1, "the rounding: {contour}");
    insta::assert_snapshot!(svg);
}

/// The SVG of `text` run on the executor's fixture machine
/// (`tests/fixtures/run/mill.toml`: T1 has radius 5).
fn plot_on_fixture_machine(name: &str, text: &str) -> String {
    let path = gcodec_testkit::repo().join("tests/fixtures/run/mill.toml");
    let profile_text = std::fs::read_to_string(path).expect("the fixture machine");
    let profile = gcodec_profile::load(&profile_text).expect("a valid profile");
    let mut sink = gcodec_plot::PlotSink::new(None);
    for event in &run_on(profile, name, text) {
        sink.plot(event);
    }
    sink.into_plot().to_svg(name)
}

/// The `<path>` data of the group `id`; empty if there is none.
fn group<'a>(svg: &'a str, id: &str) -> &'a str {
    svg.split(&format!("<g id=\"{id}\">"))
        .nth(1)
        .and_then(|rest| rest.split("</g>").next())
        .unwrap_or_default()
}

#[test]
fn a_kontt_approach_is_the_tool_centre_s_own_circle() {
    // The executor's fixture `compensation_kontt.mpf`: the approach and
    // the retraction are straight blocks whose tool centre goes along a
    // circle of its own (`tool_arc`).
    let text = "N10 G17 G90 G54 T1 D1 M6\n\
                N20 G0 X20 Y-20 Z2\n\
                N30 G1 Z-2 F300\n\
                N40 KONTT G41 G1 X0 Y0\n\
                N50 Y30\n\
                N60 X30\n\
                N70 G40 G1 X40 Y10\n\
                N80 G0 Z50\n\
                M30\n";
    let svg = plot_on_fixture_machine("kontt.mpf", text);
    assert_eq!(group(&svg, "contour").matches(" A").count(), 0);
    // The approach's and the retraction's circles, and the transition
    // circle round the outside corner (X0 Y30) between them.
    assert_eq!(group(&svg, "path").matches(" A").count(), 3, "{svg}");
    insta::assert_snapshot!(svg);
}
