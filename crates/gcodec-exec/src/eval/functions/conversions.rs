//! Conversions: between the number types (`ITOR`, `BTOR`, `RTOI`,
//! `RTOB`, `ITOB`, `BTOI`), from text to number (`NUMBER`, `ISNUMBER`)
//! and between AXIS and STRING (`AXNAME`, `AXSTRING`).

use std::sync::Arc;

use gcodec_lang::functions::Function as F;
use gcodec_source::codes;

use super::{Args, EvalContext, real};
use crate::value::{RtValue, RunError, real_to_int};

/// `ITOR`, `BTOR`, `RTOI`, `RTOB`, `ITOB` and `BTOI` of one value (the
/// functions [`super::call`] sends here).
pub(super) fn between_types<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    match a.function {
        F::Itor => real(f64::from(a.int(0)?)),
        F::Btor => real(if a.bool(0)? { 1.0 } else { 0.0 }),
        F::Rtoi => Ok(RtValue::Int(real_to_int(a.real(0)?)?)),
        F::Rtob => Ok(RtValue::Bool(a.real(0)? != 0.0)),
        F::Itob => Ok(RtValue::Bool(a.int(0)? != 0)),
        _ => Ok(RtValue::Int(i32::from(a.bool(0)?))),
    }
}

/// `NUMBER(s)`: the number `s` writes; `ISNUMBER(s)`: whether it writes
/// one.
pub(super) fn number<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let s = a.string(0)?;
    let parsed = parse_number(&s);
    if a.function == F::Isnumber {
        return Ok(RtValue::Bool(parsed.is_some()));
    }
    parsed.map(RtValue::Real).ok_or_else(|| {
        RunError::new(
            codes::run::INVALID_NUMBER,
            format!("`NUMBER`: \"{s}\" is not a number"),
        )
    })
}

/// `AXNAME(s)`: the axis named `s` (any case, blanks around).
pub(super) fn axname<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let s = a.string(0)?;
    let upper = s.trim().to_ascii_uppercase();
    if a.ctx.runtime().is_axis(&upper) {
        Ok(RtValue::Axis(Arc::from(upper.as_str())))
    } else {
        Err(RunError::new(
            codes::run::UNKNOWN_AXIS,
            format!("`AXNAME`: \"{s}\" is not an axis of the machine"),
        ))
    }
}

/// `AXSTRING(axis)`: the axis's name.
pub(super) fn axstring<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    match a.value(0)? {
        RtValue::Axis(n) => Ok(RtValue::String(n)),
        v => Err(a.wrong_type(0, &v, "an AXIS")),
    }
}

/// A number as `NUMBER` reads it: blanks around, a sign, digits with an
/// optional point, an optional exponent `E`/`EX` with a sign (`1.5`,
/// `-3`, `.5`, `2EX3`, `1e-4`).
fn parse_number(text: &str) -> Option<f64> {
    let t = text.trim();
    let b = t.as_bytes();
    let mut i = 0;
    if matches!(b.first(), Some(b'+' | b'-')) {
        i += 1;
    }
    let mut digits = 0;
    while i < b.len() && b[i].is_ascii_digit() {
        i += 1;
        digits += 1;
    }
    if i < b.len() && b[i] == b'.' {
        i += 1;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
            digits += 1;
        }
    }
    if digits == 0 {
        return None;
    }
    let mantissa = &t[..i];
    let mut exponent = 0i32;
    if i < b.len() && b[i].eq_ignore_ascii_case(&b'E') {
        i += 1;
        if i < b.len() && b[i].eq_ignore_ascii_case(&b'X') {
            i += 1;
        }
        let sign_at = i;
        if matches!(b.get(i), Some(b'+' | b'-')) {
            i += 1;
        }
        let exp_digits = i;
        while i < b.len() && b[i].is_ascii_digit() {
            i += 1;
        }
        if i == exp_digits {
            return None;
        }
        exponent = t[sign_at..i].parse().ok()?;
    }
    if i != b.len() {
        return None;
    }
    let value: f64 = format!("{mantissa}e{exponent}").parse().ok()?;
    value.is_finite().then_some(value)
}
