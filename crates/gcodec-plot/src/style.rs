//! The picture's fixed colours and strokes, and its scale bar's length.

/// The colours of the tools' feed moves, in the order the tools appear
/// in the run (the tool of the first tool change first), repeated from
/// the start after the ninth (Tableau 10 without its grey, which is the
/// rapids' and the contour's).
pub const PALETTE: [&str; 9] = [
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#bcbd22",
    "#17becf",
];

/// The feed moves made with no tool in the spindle (before the first
/// tool change, after `T0`).
pub const NO_TOOL: &str = "#000000";

/// The CSS of the picture: every path unfilled; rapids dashed grey; the
/// programmed contour under compensation thin light grey; the box round
/// the path dotted.
pub const CSS: &str = "path{fill:none;stroke-linecap:round;stroke-linejoin:round}\
.feed{stroke-width:1.5}\
.rapid{stroke:#7f7f7f;stroke-width:0.75;stroke-dasharray:4 3}\
.contour{stroke:#a6a6a6;stroke-width:0.75}\
.box{fill:none;stroke:#c8c8c8;stroke-width:0.5;stroke-dasharray:1 2}\
.bar{stroke:#000000;stroke-width:1}\
.title{font-size:16px;font-weight:bold}";

/// The colour of tool `index` (0: no tool; then in order of appearance).
pub fn tool_colour(index: u32) -> &'static str {
    match index {
        0 => NO_TOOL,
        n => PALETTE[(n as usize - 1) % PALETTE.len()],
    }
}

/// The scale bar's length: the longest 1, 2 or 5 × 10ⁿ mm that is drawn
/// at most `max_pixels` long at `scale` pixels per mm.
pub fn scale_bar_length(scale: f64, max_pixels: f64) -> Option<f64> {
    let longest = max_pixels / scale;
    if !(longest.is_finite() && longest > 0.0) {
        return None;
    }
    let decade = 10_f64.powf(longest.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|length| *length <= longest * (1.0 + 1e-12))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_bar_is_a_round_length_that_fits() {
        assert_eq!(scale_bar_length(1.0, 120.0), Some(100.0));
        assert_eq!(scale_bar_length(10.0, 120.0), Some(10.0));
        assert_eq!(scale_bar_length(4.0, 120.0), Some(20.0));
        assert_eq!(scale_bar_length(0.2, 120.0), Some(500.0));
        assert_eq!(scale_bar_length(5000.0, 120.0), Some(0.02));
        assert_eq!(scale_bar_length(0.0, 120.0), None);
    }

    #[test]
    fn tools_take_the_palette_in_turn() {
        assert_eq!(tool_colour(0), NO_TOOL);
        assert_eq!(tool_colour(1), PALETTE[0]);
        assert_eq!(tool_colour(10), PALETTE[0]);
    }
}
