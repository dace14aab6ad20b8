//! Numbers as the picture writes them: a fixed precision, trailing zeros
//! left out, never `-0`, so that the same run always gives the same text.

use std::fmt::Write;

/// Writes `value` rounded to `decimals` (at most 6) places, without
/// trailing zeros (`12.5`, `3`, `-0.25`). A value too large for the
/// precision is written clamped; a non-finite one as 0.
pub fn write_fixed(out: &mut String, value: f64, decimals: u32) {
    let decimals = decimals.min(6);
    let unit = 10_i64.pow(decimals);
    let scaled = (value * unit as f64).round();
    // `as` saturates; NaN becomes 0.
    let scaled = if scaled.is_finite() { scaled as i64 } else { 0 };
    let whole = scaled / unit;
    let mut fraction = (scaled % unit).unsigned_abs();
    if scaled < 0 {
        out.push('-');
    }
    let mut digits = itoa::Buffer::new();
    out.push_str(digits.format(whole.unsigned_abs()));
    if fraction == 0 {
        return;
    }
    let mut width = decimals as usize;
    while fraction.is_multiple_of(10) {
        fraction /= 10;
        width -= 1;
    }
    let _ = write!(out, ".{fraction:0width$}");
}

/// [`write_fixed`] into a new string.
pub fn fixed(value: f64, decimals: u32) -> String {
    let mut out = String::new();
    write_fixed(&mut out, value, decimals);
    out
}

#[cfg(test)]
mod tests {
    use super::fixed;

    #[test]
    fn rounds_to_the_precision_and_drops_trailing_zeros() {
        assert_eq!(fixed(12.5, 2), "12.5");
        assert_eq!(fixed(3.0, 2), "3");
        assert_eq!(fixed(-0.254, 2), "-0.25");
        assert_eq!(fixed(-0.004, 2), "0");
        assert_eq!(fixed(0.056, 2), "0.06");
        assert_eq!(fixed(-1.005_1, 2), "-1.01");
        assert_eq!(fixed(f64::NAN, 2), "0");
        assert_eq!(fixed(1.234_567, 3), "1.235");
    }
}
