//! Trigonometry in degrees: `SIN`, `COS`, `TAN`, `ASIN`, `ACOS`,
//! `ATAN2`; exact at the angles programs use most (multiples of 30° and
//! 90°, results that are whole degrees).

use super::{Args, EvalContext, domain, real};
use crate::value::{RtValue, RunError};
use gcodec_lang::functions::Function as F;
use gcodec_source::codes;

/// `SIN`, `COS`, `TAN`, `ASIN` and `ACOS` of one REAL (the names
/// [`super::call`] sends here).
pub(super) fn of_one_real<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(1, 1)?;
    let x = a.real(0)?;
    match a.function {
        F::Sin => real(sin_deg(x)),
        F::Cos => real(sin_deg(x + 90.0)),
        F::Tan => {
            let c = sin_deg(x + 90.0);
            if c == 0.0 {
                Err(domain(a.name(), x, "the tangent of ±90° is infinite"))
            } else {
                real(sin_deg(x) / c)
            }
        }
        F::Asin | F::Acos if !(-1.0..=1.0).contains(&x) => {
            Err(domain(a.name(), x, "the argument must lie in −1…1"))
        }
        F::Asin => real(snap_degrees(x.asin().to_degrees())),
        _ => real(snap_degrees(x.acos().to_degrees())),
    }
}

/// `ATAN2(y, x)`: the angle of the direction (x, y).
pub(super) fn atan2<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    a.count(2, 2)?;
    let (y, x) = (a.real(0)?, a.real(1)?);
    if y == 0.0 && x == 0.0 {
        return Err(RunError::new(
            codes::run::DOMAIN,
            "`ATAN2(0, 0)`: no angle without a direction",
        ));
    }
    real(snap_degrees(y.atan2(x).to_degrees()))
}

/// A result of degrees within 1e-12 of a whole number is that number
/// (`ASIN(0.5)` = 30, not 30.000000000000004).
fn snap_degrees(x: f64) -> f64 {
    let r = x.round();
    if (x - r).abs() < 1e-12 { r } else { x }
}

/// Sine of degrees, exact at multiples of 30 and 90 degrees.
fn sin_deg(x: f64) -> f64 {
    let r = x.rem_euclid(360.0);
    let quadrant = (r / 90.0).floor();
    let rem = r - 90.0 * quadrant;
    let (s, c) = (sin_first(rem), sin_first(90.0 - rem));
    match quadrant as i32 {
        0 => s,
        1 => c,
        2 => -s,
        _ => -c,
    }
}

/// Sine of 0…90 degrees.
fn sin_first(d: f64) -> f64 {
    if d == 0.0 {
        0.0
    } else if d == 30.0 {
        0.5
    } else if d == 90.0 {
        1.0
    } else {
        d.to_radians().sin()
    }
}
