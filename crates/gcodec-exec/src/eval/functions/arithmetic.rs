//! Arithmetic and rounding: `ABS`, `SQRT`, `POT`, `TRUNC`, `ROUND`,
//! `ROUNDUP`, `LN`, `EXP`, `MINVAL`, `MAXVAL`, `BOUND`; REAL results.

use super::{Args, EvalContext, domain, real};
use crate::value::{RtValue, RunError};
use gcodec_lang::functions::Function as F;
use gcodec_source::codes;

/// `ABS`, `SQRT`, `POT`, `TRUNC`, `ROUND`, `ROUNDUP`, `LN` and `EXP` of
/// one REAL (the functions [`super::call`] sends here).
pub(super) fn of_one_real<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let x = a.real(0)?;
    match a.function {
        F::Abs => real(x.abs()),
        F::Sqrt if x < 0.0 => Err(domain(a.name(), x, "the square root of a negative number")),
        F::Sqrt => real(x.sqrt()),
        F::Pot => real(x * x),
        F::Trunc => real(x.trunc()),
        F::Round => real(x.round()),
        F::Roundup => real(x.ceil()),
        F::Ln if x <= 0.0 => Err(domain(a.name(), x, "the logarithm needs a positive number")),
        F::Ln => real(x.ln()),
        _ => real(x.exp()),
    }
}

/// `MINVAL(x, y)`, `MAXVAL(x, y)`.
pub(super) fn min_max<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (x, y) = (a.real(0)?, a.real(1)?);
    real(if a.function == F::Minval {
        x.min(y)
    } else {
        x.max(y)
    })
}

/// `BOUND(min, max, x)`: `x` limited to `min…max`.
pub(super) fn bound<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(3, 3)?;
    let (lo, hi, x) = (a.real(0)?, a.real(1)?, a.real(2)?);
    if lo > hi {
        return Err(RunError::new(
            codes::run::DOMAIN,
            format!("`BOUND({lo}, {hi}, …)`: the minimum is above the maximum"),
        ));
    }
    real(x.clamp(lo, hi))
}
