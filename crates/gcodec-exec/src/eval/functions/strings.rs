//! Strings: `STRLEN`, `TOUPPER`, `TOLOWER`, `INDEX`, `RINDEX`, `MINDEX`,
//! `MATCH`, `SUBSTR`. Positions count from 0, −1 is "not found".

use std::sync::Arc;

use gcodec_lang::functions::Function as F;
use gcodec_source::codes;

use super::{Args, EvalContext};
use crate::value::{RtValue, RunError};

/// `STRLEN(s)`: the length in characters (bytes).
pub(super) fn strlen<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    Ok(RtValue::Int(a.string(0)?.len() as i32))
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
    let (s, c) = (a.string(0)?, a.char(1)?);
    let bytes = s.as_bytes();
    let at = if a.function == F::Index {
        bytes.iter().position(|&b| b == c)
    } else {
        bytes.iter().rposition(|&b| b == c)
    };
    Ok(position(at))
}

/// `MINDEX(s, set)`: the first position of any character of `set`.
pub(super) fn mindex<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (s, set) = (a.string(0)?, a.string(1)?);
    let at = s.bytes().position(|b| set.as_bytes().contains(&b));
    Ok(position(at))
}

/// `MATCH(s, sub)`: the position of the string `sub`.
pub(super) fn find<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (s, sub) = (a.string(0)?, a.string(1)?);
    Ok(position(s.find(&*sub)))
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
    RtValue::Int(at.map_or(-1, |i| i as i32))
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
    let bytes = s.as_bytes();
    let from = start.min(bytes.len());
    let to = match len {
        Some(n) => from.saturating_add(usize::try_from(n).map_err(|_| bad("length", n))?),
        None => bytes.len(),
    }
    .min(bytes.len());
    let text: String = bytes[from..to].iter().map(|&b| char::from(b)).collect();
    Ok(RtValue::String(Arc::from(text.as_str())))
}
