//! The Group 8 (settable work offset) codes profiles name and the ranges
//! they name them by, as `$P_UIFR` indices ([`WorkOffsetCode::index`]).

use gcodec_lang::WorkOffsetCode;

/// The index of a Group 8 code (`G500`, `G54`, `g505`), if it is one.
pub fn group8_index(code: &str) -> Option<u8> {
    let digits = code.strip_prefix(['G', 'g'])?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.len() > 3 {
        return None;
    }
    WorkOffsetCode(digits.parse().ok()?).index()
}

/// An inclusive range of Group 8 indices, from `"G54"` or `"G505-G599"`.
pub fn group8_range(text: &str) -> Result<(u8, u8), String> {
    let (first, last) = match text.split_once('-') {
        Some((a, b)) => (a.trim(), b.trim()),
        None => (text.trim(), text.trim()),
    };
    let index = |code: &str| {
        group8_index(code)
            .ok_or_else(|| format!("`{code}` is not a Group 8 offset (G500, G54…G57, G505…G599)"))
    };
    let (lo, hi) = (index(first)?, index(last)?);
    if lo > hi {
        return Err(format!("the range `{text}` runs backwards"));
    }
    Ok((lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_follow_p_uifr() {
        assert_eq!(group8_index("G500"), Some(0));
        assert_eq!(group8_index("g54"), Some(1));
        assert_eq!(group8_index("G57"), Some(4));
        assert_eq!(group8_index("G505"), Some(5));
        assert_eq!(group8_index("G599"), Some(99));
        for not in ["G53", "G58", "G504", "G600", "G", "X54", "G5x", "G0054"] {
            assert_eq!(group8_index(not), None, "{not}");
        }
        for i in 0..100 {
            let code = WorkOffsetCode::of_index(i).unwrap().to_string();
            assert_eq!(group8_index(&code), Some(i), "{code}");
        }
    }

    #[test]
    fn ranges_are_inclusive_and_forwards() {
        assert_eq!(group8_range("G54"), Ok((1, 1)));
        assert_eq!(group8_range("G54-G57"), Ok((1, 4)));
        assert_eq!(group8_range("G505 - G599"), Ok((5, 99)));
        assert!(group8_range("G57-G54").is_err());
        assert!(group8_range("G54-G58").is_err());
    }
}
