//! The number texts the executor's writers share besides
//! `gcodec_ail::write_fixed_point`: the 4-decimal fraction of the text
//! trace, unsigned integers, and counts kept as text ([`CountText`]).

use gcodec_ail::ShortNumberText;

/// `fraction` (0…9999) as 4 decimals without trailing zeros; empty for
/// 0.
pub(super) fn fraction_digits(fraction: u64, buffer: &mut [u8; 4]) -> &str {
    let fraction = fraction % 10_000;
    *buffer = [
        b'0' + (fraction / 1000) as u8,
        b'0' + (fraction / 100 % 10) as u8,
        b'0' + (fraction / 10 % 10) as u8,
        b'0' + (fraction % 10) as u8,
    ];
    let used = 4 - buffer.iter().rev().take_while(|d| **d == b'0').count();
    std::str::from_utf8(&buffer[..used]).unwrap_or("")
}

pub(super) fn write_u64(out: &mut Vec<u8>, value: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(value).as_bytes());
}

/// The decimal text of a count that mostly stays or goes up by one from
/// row to row (a CSV row's line and executed blocks, a JSONL event's
/// line): the next value's text is the last one's with a digit carried,
/// not written anew, and it is copied with a copy of a fixed size (with
/// `itoa` and a copy of its text, the three counts of a row were a
/// quarter of the CSV writer).
pub(super) struct CountText {
    value: u64,
    text: ShortNumberText,
}

impl Default for CountText {
    fn default() -> Self {
        let mut text = ShortNumberText::default();
        text.bytes[0] = b'0';
        text.len = 1;
        Self { value: 0, text }
    }
}

impl CountText {
    /// Writes `value` to `out`.
    #[inline]
    pub(super) fn write(&mut self, out: &mut Vec<u8>, value: u64) {
        if value != self.value {
            self.set(value);
        }
        self.text.write_to(out);
    }

    fn set(&mut self, value: u64) {
        let next = self.value.checked_add(1) == Some(value);
        self.value = value;
        if next {
            for digit in self.text.bytes[..self.text.len].iter_mut().rev() {
                if *digit == b'9' {
                    *digit = b'0';
                } else {
                    *digit += 1;
                    return;
                }
            }
            // 9…9 + 1: one digit more.
        }
        let mut buffer = itoa::Buffer::new();
        let digits = buffer.format(value).as_bytes();
        self.text.bytes[..digits.len()].copy_from_slice(digits);
        self.text.len = digits.len();
    }
}

#[cfg(test)]
mod tests {
    use super::CountText;

    #[test]
    fn count_text_is_the_decimal_of_every_value_it_is_given() {
        let mut count = CountText::default();
        let values = (0..2_000u64)
            .chain([9_999, 10_000, 10_001, 7, 99, 100, 0, u64::MAX - 1])
            .chain([u64::MAX, 0, 1, 10, 9, 10, 11]);
        for value in values {
            let mut out = b"row,".to_vec();
            count.write(&mut out, value);
            assert_eq!(out, format!("row,{value}").into_bytes());
        }
    }
}
