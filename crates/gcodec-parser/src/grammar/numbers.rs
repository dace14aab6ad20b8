//! The values of number tokens: decimal constants as the control reads
//! them, with the exponent marker `EX`.

/// The value of a number token, `None` if it is out of range.
pub(crate) fn number_value(text: &str) -> Option<f64> {
    number_bytes_value(text.as_bytes())
}

/// [`number_value`] of a token's bytes, for callers that have not made a
/// `str` of them.
pub(crate) fn number_bytes_value(bytes: &[u8]) -> Option<f64> {
    if let Some(value) = short_decimal(bytes) {
        return value;
    }
    let text = std::str::from_utf8(bytes).ok()?;
    // `1.5EX-3`: the exponent marker is `EX` in any case. Rust's parser
    // reads `1.5e-3`, which rounds correctly where `1.5 * 10^-3` would not.
    let value: f64 = match text.bytes().position(|b| b == b'E' || b == b'e') {
        Some(pos) => {
            let exponent = text.get(pos + 2..)?;
            format!("{}e{}", &text[..pos], exponent).parse().ok()?
        }
        None => text.parse().ok()?,
    };
    value.is_finite().then_some(value)
}

/// Powers of ten that are exact in an `f64`.
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `Some(value)` for the commonest numbers, `1600`, `12.345`,
/// `.5`, `5.`: at most 15 digits, at most 22 after the point, no exponent.
/// Such a number is an integer below 2^53 divided by an exact power of
/// ten, and IEEE division rounds correctly, so the result is the correctly
/// rounded value that `str::parse` gives (Clinger's fast path).
/// `None` when the text has another form.
fn short_decimal(text: &[u8]) -> Option<Option<f64>> {
    let mut mantissa: u64 = 0;
    let mut digits = 0;
    let mut point = None;
    for (i, &b) in text.iter().enumerate() {
        match b {
            b'0'..=b'9' => {
                mantissa = mantissa * 10 + u64::from(b - b'0');
                digits += 1;
                if digits > 15 {
                    return None;
                }
            }
            b'.' if point.is_none() => point = Some(i),
            _ => return None,
        }
    }
    if digits == 0 {
        return Some(None);
    }
    let fraction = point.map_or(0, |p| text.len() - p - 1);
    Some(Some(short_decimal_value(mantissa, fraction)?))
}

/// The value of a decimal of at most 15 digits, `mantissa`, of which
/// `fraction` follow the point; `None` beyond 22 after the point (see
/// [`short_decimal`]).
pub(crate) fn short_decimal_value(mantissa: u64, fraction: usize) -> Option<f64> {
    debug_assert!(mantissa < 1 << 53, "at most 15 digits");
    // Below 2^53, so exact as a signed integer too, which converts in one
    // instruction (an unsigned one takes six).
    let value = mantissa as i64 as f64;
    if fraction == 0 {
        // A whole number (`G1`, `F1000`): no division to wait for.
        return Some(value);
    }
    let power = EXACT_POWERS_OF_TEN.get(fraction)?;
    Some(value / power)
}

#[cfg(test)]
mod tests {
    use super::number_value;

    #[test]
    fn numbers_are_read_exactly() {
        assert_eq!(number_value("1600"), Some(1600.0));
        assert_eq!(number_value("5."), Some(5.0));
        assert_eq!(number_value(".5"), Some(0.5));
        assert_eq!(number_value("1.5EX-3"), Some(1.5e-3));
        assert_eq!(number_value("0.01EX-11"), Some(1e-13));
        assert_eq!(number_value("10ex5"), Some(1e6));
        assert_eq!(number_value("1EX400"), None);
        assert_eq!(number_value("0EX400"), Some(0.0));
        assert_eq!(number_value("1EX"), None);
        assert_eq!(number_value("99999999999999999999"), Some(1e20));
        assert_eq!(number_value("."), None);
        assert_eq!(number_value("1.2.3"), None);
        assert_eq!(number_value("0.1"), Some(0.1));
        assert_eq!(number_value("123456789012345"), Some(123456789012345.0));
        assert_eq!(number_value("0.0000000000000000000001"), Some(1e-22));
    }

    /// The short-decimal path agrees with the standard library's correctly
    /// rounded parser on every form it takes.
    #[test]
    fn short_decimals_round_as_the_standard_parser() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let digits = (seed >> 60) as usize + 1;
            let mantissa = (seed >> 8) % 10u64.pow(digits.min(15) as u32);
            let text = format!("{mantissa:0digits$}");
            let point = (seed >> 4) as usize % (text.len() + 1);
            let text = format!("{}.{}", &text[..point], &text[point..]);
            let expected = text.parse::<f64>().ok();
            assert_eq!(number_value(&text), expected, "{text}");
        }
    }
}
