//! The SVG is valid: usvg parses it and resvg draws the path in its
//! tool's colour.

mod common;

use common::plot_program;

/// How much of `colour` over white `pixel` is (a stroke's edge covers a
/// pixel only in part): the same share in every channel, or `None`.
fn over_white(colour: [u8; 3], pixel: [u8; 3]) -> Option<f64> {
    let mut shares = colour.iter().zip(pixel).filter_map(|(&c, p)| {
        let room = 255.0 - f64::from(c);
        // A channel the colour has full is white's too: it says nothing.
        (room > 30.0).then(|| (255.0 - f64::from(p)) / room)
    });
    let first = shares.next()?;
    let white_ok = colour.iter().zip(pixel).all(|(&c, p)| c < 225 || p >= 225);
    (white_ok && shares.all(|s| (s - first).abs() <= 0.1)).then_some(first)
}

/// How many pixels of `svg` rendered are `rgb`, in full or over white in
/// part, and the picture's size.
fn pixels_near(svg: &str, rgb: [u8; 3]) -> (usize, (u32, u32)) {
    let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default())
        .expect("usvg parses the SVG");
    let size = tree.size().to_int_size();
    let mut pixmap =
        resvg::tiny_skia::Pixmap::new(size.width(), size.height()).expect("a picture of its size");
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::default(),
        &mut pixmap.as_mut(),
    );
    let near = pixmap
        .pixels()
        .iter()
        .filter(|p| {
            let p = p.demultiply();
            over_white(rgb, [p.red(), p.green(), p.blue()]).is_some_and(|a| a >= 0.3)
        })
        .count();
    (near, (size.width(), size.height()))
}

#[test]
fn the_square_renders_in_the_first_tools_colour() {
    let text = "N10 G17 G90 G94 T1 M6\nN20 G0 X0 Y0 Z5\nN30 G1 Z-1 F200\n\
                N40 X20 F500\nN50 Y20\nN60 X0\nN70 Y0\nN80 G0 Z5\nN90 M30\n";
    let svg = plot_program("square.mpf", text, None).to_svg("square.mpf");
    let (blue, size) = pixels_near(&svg, [0x1f, 0x77, 0xb4]);
    assert_eq!(size.0, 800);
    // Four sides of 560 px at 1.5 px: well over a thousand pixels.
    assert!(blue > 1000, "{blue} pixels of T1's colour");
    // Nothing in the second tool's colour: the count tells colours apart.
    let (orange, _) = pixels_near(&svg, [0xff, 0x7f, 0x0e]);
    assert_eq!(orange, 0);
}

#[test]
fn a_second_tool_renders_in_the_second_colour() {
    let text = "N10 G17 G90 G94 T1 M6\nN20 G0 X0 Y0 Z1\nN30 G1 X30 F600\n\
                N40 G0 Z20\nN50 T2 M6\nN60 G0 X0 Y10\nN70 G2 X30 Y10 I15 F300\nN80 M30\n";
    let svg = plot_program("two_tools.mpf", text, None).to_svg("two_tools.mpf");
    let (orange, _) = pixels_near(&svg, [0xff, 0x7f, 0x0e]);
    assert!(orange > 500, "{orange} pixels of T2's colour");
}
