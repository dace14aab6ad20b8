//! Strings: `STRLEN`, `TOUPPER`, `TOLOWER`, `INDEX`, `RINDEX`, `MINDEX`,
//! `MATCH`, `SUBSTR`. Positions and lengths count characters of the
//! control's code page (`char`s, never UTF-8 bytes: SPEC §11.3) from 0,
//! −1 is "not found".

use std::sync::Arc;

use gcodec_lang::functions::Function as F;
use gcodec_source::{codes, cp1252};

use super::{Args, EvalContext};
use crate::value::{RtValue, RunError};

/// `STRLEN(s)`: the length in characters.
pub(super) fn strlen<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    Ok(count(a.string(0)?.chars().count()))
}

/// `TOUPPER(s)`, `TOLOWER(s)`.
pub(super) fn change_case<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let s = a.string(0)?;
    let t = if a.function == F::Toupper {
        s.to_ascii_uppercase()
    } else {
        s.to_ascii_lowercase()
    };
    Ok(RtValue::String(Arc::from(t.as_str())))
}

/// `INDEX(s, c)`, `RINDEX(s, c)`: the first, the last position of the
/// character `c`.
pub(super) fn index<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (s, c) = (a.string(0)?, cp1252(a.char(1)?));
    let at = if a.function == F::Index {
        s.chars().position(|x| x == c)
    } else {
        // Counted from the end, then turned into a position from the start.
        let from_end = s.chars().rev().position(|x| x == c);
        from_end.map(|k| s.chars().count() - 1 - k)
    };
    Ok(position(at))
}

/// `MINDEX(s, set)`: the first position of any character of `set`.
pub(super) fn mindex<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (s, set) = (a.string(0)?, a.string(1)?);
    let at = s.chars().position(|c| set.contains(c));
    Ok(position(at))
}

/// `MATCH(s, sub)`: the position of the string `sub`.
pub(super) fn find<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (s, sub) = (a.string(0)?, a.string(1)?);
    let at = s.find(&*sub).map(|byte| s[..byte].chars().count());
    Ok(position(at))
}

/// `SUBSTR(s, start)`, `SUBSTR(s, start, len)`.
pub(super) fn substr<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 3)?;
    let s = a.string(0)?;
    let start = a.int(1)?;
    let len = if a.present(2) { Some(a.int(2)?) } else { None };
    substring(&s, start, len)
}

fn position(at: Option<usize>) -> RtValue {
    at.map_or(RtValue::Int(-1), count)
}

/// A count or position as an INT (a string is far shorter than `i32::MAX`
/// characters; a longer one would be counted as `i32::MAX`).
fn count(n: usize) -> RtValue {
    RtValue::Int(i32::try_from(n).unwrap_or(i32::MAX))
}

/// `SUBSTR(s, start, len)`: the characters from `start` (0-based) on,
/// `len` of them or to the end; a part past the end is cut off (a start
/// at or past the end gives the empty string). A negative start or length
/// is [`codes::run::INDEX_OUT_OF_RANGE`].
fn substring(s: &str, start: i32, len: Option<i32>) -> Result<RtValue, RunError> {
    let bad = |what: &str, v: i32| {
        RunError::new(
            codes::run::INDEX_OUT_OF_RANGE,
            format!("`SUBSTR`: the {what} {v} is negative"),
        )
    };
    let start = usize::try_from(start).map_err(|_| bad("start", start))?;
    let len = match len {
        Some(n) => usize::try_from(n).map_err(|_| bad("length", n))?,
        None => usize::MAX,
    };
    let text: String = s.chars().skip(start).take(len).collect();
    Ok(RtValue::String(Arc::from(text.as_str())))
}
