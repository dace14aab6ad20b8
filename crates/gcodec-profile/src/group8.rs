//! Group 8 (settable work offset) codes and the ranges profiles name them
//! by. The index is the control's own: `$P_UIFR[n]` and `$P_UIFRNUM` count
//! `G500` as 0, `G54`…`G57` as 1…4 and `G505`…`G599` as 5…99.

/// The index of a Group 8 code (`G500`, `G54`, `g505`), if it is one.
pub fn group8_index(code: &str) -> Option<u8> {
    let digits = code.strip_prefix(['G', 'g'])?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) || digits.len() > 3 {
        return None;
    }
    group8_number_index(digits.parse::<u16>().ok()?)
}

/// The index of the Group 8 command `G<number>` (`54` → 1), if it is one.
pub fn group8_number_index(number: u16) -> Option<u8> {
    match number {
        500 => Some(0),
        n @ 54..=57 => Some((n - 53) as u8),
        n @ 505..=599 => Some((n - 500) as u8),
        _ => None,
    }
}

/// The code of a Group 8 index (`0` → `G500`, `1` → `G54`, `5` → `G505`).
pub fn group8_code(index: u8) -> Option<String> {
    match index {
        0 => Some("G500".to_owned()),
        1..=4 => Some(format!("G{}", 53 + u16::from(index))),
        5..=99 => Some(format!("G{}", 500 + u16::from(index))),
        _ => None,
    }
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
            let code = group8_code(i).unwrap();
            assert_eq!(group8_index(&code), Some(i), "{code}");
        }
        assert_eq!(group8_code(100), None);
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
