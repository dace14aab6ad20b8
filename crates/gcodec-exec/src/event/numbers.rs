//! The number texts the writers share: the exact fixed-point form of
//! JSONL and CSV numbers, the 4-decimal fraction of the text trace, and
//! unsigned integers.

/// Writes `value` with at most 4 decimals when that is its shortest text,
/// a whole number (zero too) as `1.0` if `point_zero` (JSON) or `1`
/// (Rust's `{}`); false, writing nothing, when it is no such number.
///
/// Positions and feeds mostly have at most 4 decimals. When `n / 10^4`
/// reads back as `value` (IEEE division rounds correctly, so this is
/// exactly the round-trip test), that decimal is the shortest text: below
/// 1e9 an f64's spacing is far under 1e-4, so no other multiple of 1e-4
/// reads back as the same value.
pub(super) fn write_fixed_point(out: &mut Vec<u8>, value: f64, point_zero: bool) -> bool {
    if value == 0.0 {
        // Zero is in most rows (an axis at 0, a stopped spindle): `-0` keeps
        // its sign, as `{}` and serde_json write it.
        if value.is_sign_negative() {
            out.push(b'-');
        }
        out.extend_from_slice(if point_zero { b"0.0" } else { b"0" });
        return true;
    }
    let scaled = value * 1e4;
    if value.is_nan() || value.abs() >= 1e9 {
        return false;
    }
    // |scaled| < 1e13: exact in i64. Rounding half away from zero by hand
    // (`f64::round` is a library call here); whatever it gives, the test
    // below only lets an exact text through.
    let rounded = (scaled + 0.5f64.copysign(scaled)) as i64;
    if rounded as f64 / 1e4 != value {
        return false;
    }
    // The whole text is built on the stack and copied once: several small
    // copies per number cost more than the digits.
    let mut text = [0u8; 24];
    let mut len = 0;
    if rounded < 0 {
        text[0] = b'-';
        len = 1;
    }
    let magnitude = rounded.unsigned_abs();
    let mut whole = itoa::Buffer::new();
    let whole = whole.format(magnitude / 10_000).as_bytes();
    text[len..len + whole.len()].copy_from_slice(whole);
    len += whole.len();
    match fraction_digit_bytes(magnitude % 10_000, &mut [0; 4]) {
        b"" if point_zero => {
            text[len..len + 2].copy_from_slice(b".0");
            len += 2;
        }
        b"" => {}
        fraction => {
            text[len] = b'.';
            text[len + 1..len + 1 + fraction.len()].copy_from_slice(fraction);
            len += 1 + fraction.len();
        }
    }
    // A copy of a fixed size is inlined; one of `len` bytes is a call.
    out.extend_from_slice(&text);
    out.truncate(out.len() - text.len() + len);
    true
}

/// `fraction` (0…9999) as 4 decimals without trailing zeros; empty for
/// 0.
pub(super) fn fraction_digits(fraction: u64, buffer: &mut [u8; 4]) -> &str {
    std::str::from_utf8(fraction_digit_bytes(fraction, buffer)).unwrap_or("")
}

/// [`fraction_digits`] as bytes (no UTF-8 check, for the JSONL writer).
fn fraction_digit_bytes(fraction: u64, buffer: &mut [u8; 4]) -> &[u8] {
    let fraction = fraction % 10_000;
    *buffer = [
        b'0' + (fraction / 1000) as u8,
        b'0' + (fraction / 100 % 10) as u8,
        b'0' + (fraction / 10 % 10) as u8,
        b'0' + (fraction % 10) as u8,
    ];
    let used = 4 - buffer.iter().rev().take_while(|d| **d == b'0').count();
    &buffer[..used]
}

pub(super) fn write_u64(out: &mut Vec<u8>, value: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(value).as_bytes());
}
