//! Numbers as text, written by hand for the hand-written JSON and CSV
//! writers (`gcodec lower`'s instructions, the executor's JSONL and CSV):
//! the bytes serde_json and Rust's `{}` write, faster for the numbers
//! programs are made of.

use serde_json::ser::{CompactFormatter, Formatter};

/// Writes a number as serde_json writes an `f64`: `null` when not finite,
/// otherwise the shortest text that reads back as the same value, with
/// `.0` on whole numbers ([`write_fixed_point`] where it applies).
#[inline]
pub fn write_json_f64(out: &mut Vec<u8>, value: f64) {
    if !value.is_finite() {
        out.extend_from_slice(b"null");
    } else if !write_fixed_point(out, value, true) {
        write_shortest(out, value);
    }
}

/// Writes a finite `value` as serde_json does, the general way.
#[cold]
fn write_shortest(out: &mut Vec<u8>, value: f64) {
    // Writing into a vector does not fail.
    let _ = CompactFormatter.write_f64(out, value);
}

/// A short text built on the stack (a number's), copied into an output
/// with a copy of a fixed size: a copy of a length known only at run time
/// is a call, and several such calls per number cost more than its
/// digits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ShortNumberText {
    /// The text, from the first byte; the bytes after `len` are spare.
    pub bytes: [u8; SHORT_NUMBER_TEXT_SIZE],
    pub len: usize,
}

/// The room of a [`ShortNumberText`]: `u64::MAX` has 20 digits, a
/// fixed-point number at most 15 bytes.
pub const SHORT_NUMBER_TEXT_SIZE: usize = 24;

impl Default for ShortNumberText {
    /// Empty.
    fn default() -> Self {
        Self {
            bytes: [0; SHORT_NUMBER_TEXT_SIZE],
            len: 0,
        }
    }
}

impl ShortNumberText {
    /// Appends the text to `out`.
    #[inline]
    pub fn write_to(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.bytes);
        out.truncate(out.len() - SHORT_NUMBER_TEXT_SIZE + self.len);
    }
}

/// Writes `value` with at most 4 decimals when that is its shortest text,
/// a whole number (zero too) as `1.0` if `point_zero` (JSON) or `1`
/// (Rust's `{}`); false, writing nothing, when it is no such number
/// ([`fixed_point_text`]).
pub fn write_fixed_point(out: &mut Vec<u8>, value: f64, point_zero: bool) -> bool {
    let mut text = ShortNumberText::default();
    if !fixed_point_text(&mut text, value, point_zero) {
        return false;
    }
    text.write_to(out);
    true
}

/// Makes `text` the text of `value` with at most 4 decimals when that is
/// its shortest text, a whole number (zero too) as `1.0` if `point_zero`
/// (JSON) or `1` (Rust's `{}`); false, leaving `text` as it was, when it
/// is no such number.
///
/// Positions and feeds mostly have at most 4 decimals. When `n / 10^4`
/// reads back as `value` (IEEE division rounds correctly, so this is
/// exactly the round-trip test), that decimal is the shortest text: below
/// 1e9 an f64's spacing is far under 1e-4, so no other multiple of 1e-4
/// reads back as the same value.
#[inline]
pub fn fixed_point_text(text: &mut ShortNumberText, value: f64, point_zero: bool) -> bool {
    let bytes = &mut text.bytes;
    if value == 0.0 {
        // Zero is in most rows (an axis at 0, a stopped spindle): `-0` keeps
        // its sign, as `{}` and serde_json write it.
        let sign = usize::from(value.is_sign_negative());
        bytes[0] = b'-';
        bytes[sign..sign + 3].copy_from_slice(b"0.0");
        text.len = sign + if point_zero { 3 } else { 1 };
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
    // Digits go in fours from a table of pairs, and every copy into
    // `bytes` has a fixed size.
    let sign = usize::from(rounded < 0);
    bytes[0] = b'-';
    let magnitude = rounded.unsigned_abs();
    // Below 1e9 (tested above): nine digits at most.
    let whole = (magnitude / 10_000) as u32;
    let mut len = sign
        + if whole < 10_000 {
            write_short_whole(bytes, sign, whole)
        } else {
            write_long_whole(bytes, sign, whole)
        };
    let fraction = (magnitude % 10_000) as u32;
    if fraction != 0 {
        let digits = four_digits(fraction);
        // The trailing `0` digits are the high bytes of the little-endian
        // word: those that become zero bytes.
        let trailing_zeros = (u32::from_le_bytes(digits) ^ ZEROS).leading_zeros() / 8;
        bytes[len] = b'.';
        bytes[len + 1..len + 5].copy_from_slice(&digits);
        len += 5 - trailing_zeros as usize;
    } else if point_zero {
        bytes[len..len + 2].copy_from_slice(b".0");
        len += 2;
    }
    text.len = len;
    true
}

/// Four `0` digits as a little-endian word.
const ZEROS: u32 = u32::from_le_bytes(*b"0000");

/// Writes `whole` (below 10,000, as positions mostly are) at `bytes[at..]`
/// without leading zeros, as one copy of four bytes; gives its length.
#[inline]
fn write_short_whole(bytes: &mut [u8; SHORT_NUMBER_TEXT_SIZE], at: usize, whole: u32) -> usize {
    let digits = u32::from_le_bytes(four_digits(whole));
    // The leading `0` digits are the low bytes; one digit stays (`0.5`).
    let leading_zeros = ((digits ^ ZEROS).trailing_zeros() / 8).min(3);
    bytes[at..at + 4].copy_from_slice(&(digits >> (8 * leading_zeros)).to_le_bytes());
    4 - leading_zeros as usize
}

/// Writes `whole` (10,000 or more, below 1e9) at `bytes[at..]`; gives its
/// length.
#[cold]
fn write_long_whole(bytes: &mut [u8; SHORT_NUMBER_TEXT_SIZE], at: usize, mut whole: u32) -> usize {
    let whole_len = whole.checked_ilog10().map_or(1, |log| log as usize + 1);
    let mut end = at + whole_len;
    while whole >= 100 {
        end -= 2;
        bytes[end..end + 2].copy_from_slice(digit_pair(whole % 100));
        whole /= 100;
    }
    if whole >= 10 {
        bytes[end - 2..end].copy_from_slice(digit_pair(whole));
    } else {
        bytes[end - 1] = b'0' + whole as u8;
    }
    whole_len
}

/// The four digits of `n` (0…9999), leading zeros included.
#[inline]
fn four_digits(n: u32) -> [u8; 4] {
    let mut digits = [0u8; 4];
    digits[..2].copy_from_slice(digit_pair(n / 100 % 100));
    digits[2..].copy_from_slice(digit_pair(n % 100));
    digits
}

/// The two digits of `n` (0…99).
fn digit_pair(n: u32) -> &'static [u8] {
    const PAIRS: &[u8; 200] = b"\
        0001020304050607080910111213141516171819\
        2021222324252627282930313233343536373839\
        4041424344454647484950515253545556575859\
        6061626364656667686970717273747576777879\
        8081828384858687888990919293949596979899";
    let at = n as usize * 2;
    &PAIRS[at..at + 2]
}

#[cfg(test)]
mod tests {
    use super::write_fixed_point;
    use proptest::prelude::*;

    /// What `write_fixed_point` writes, or `None` where it declines.
    fn fixed(value: f64, point_zero: bool) -> Option<String> {
        let mut out = b"<".to_vec();
        let written = write_fixed_point(&mut out, value, point_zero);
        let text = String::from_utf8(out).expect("ASCII");
        let text = text.strip_prefix('<').expect("kept what was there");
        if written {
            Some(text.to_owned())
        } else {
            assert_eq!(text, "", "declined, but wrote something");
            None
        }
    }

    /// The text the general writers give: Rust's `{}` for CSV, serde_json
    /// for JSON.
    fn general(value: f64, point_zero: bool) -> String {
        if point_zero {
            serde_json::to_string(&value).expect("finite")
        } else {
            format!("{value}")
        }
    }

    /// Whether `value`'s shortest text has at most 4 decimals and it is
    /// below 1e9: the numbers the fixed-point writer must take.
    fn must_take(value: f64) -> bool {
        let text = format!("{value}");
        let decimals = text.split_once('.').map_or(0, |(_, f)| f.len());
        value.abs() < 1e9 && decimals <= 4
    }

    /// The fixed-point text is the general writers' wherever it is
    /// written, and it is written wherever it can be.
    fn check(value: f64) {
        for point_zero in [false, true] {
            match fixed(value, point_zero) {
                Some(text) => assert_eq!(text, general(value, point_zero), "{value:?}"),
                None => assert!(!must_take(value), "declined {value:?}"),
            }
        }
    }

    #[test]
    fn edge_numbers_are_written_as_the_general_writers_write_them() {
        let edges = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            0.5,
            -0.5,
            0.0001,
            -0.0001,
            0.00005,
            0.1,
            0.25,
            1.5,
            10.0,
            100.037,
            -100.037,
            1000.0,
            9.9999,
            99_999.999_9,
            123_456_789.0,
            999_999_999.999_9,
            1e9,
            -1e9,
            1e8,
            1e-5,
            1e-300,
            2.0f64.powi(52),
            0.1 + 0.2,
            1.0 / 3.0,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
        ];
        for value in edges {
            check(value);
        }
        assert_eq!(fixed(f64::NAN, true), None);
        assert_eq!(fixed(f64::INFINITY, false), None);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(20_000))]

        #[test]
        fn decimals_are_written_as_the_general_writers_write_them(
            units in -9_999_999_999_999i64..9_999_999_999_999i64,
            shift in 0i32..=6,
        ) {
            // Decimals of up to 4 places (taken) and of 5 and 6 (declined),
            // whole numbers and fractions of every length.
            check(units as f64 / 10f64.powi(shift));
        }

        #[test]
        fn any_number_is_written_as_the_general_writers_write_it(bits in any::<u64>()) {
            let value = f64::from_bits(bits);
            if value.is_finite() {
                check(value);
            } else {
                prop_assert_eq!(fixed(value, true), None);
            }
        }
    }
}
