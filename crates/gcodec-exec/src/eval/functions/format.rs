//! `SPRINT`: text formatted from values, C's `printf` directives as the
//! control reads them.

use std::sync::Arc;

use gcodec_source::codes;

use super::{Args, EvalContext};
use crate::value::{RtValue, RunError};

/// `SPRINT(format, values…)`, its arguments evaluated in order.
pub(super) fn sprint_call<C: EvalContext + ?Sized>(a: &Args<'_, C>) -> Result<RtValue, RunError> {
    if a.args.is_empty() {
        a.count(1, usize::MAX)?;
    }
    let format = a.string(0)?;
    let mut values = Vec::with_capacity(a.args.len() - 1);
    for i in 1..a.args.len() {
        values.push(a.value(i)?);
    }
    sprint(&format, &values).map(|t| RtValue::String(Arc::from(t.as_str())))
}

/// `SPRINT(format, values…)`: the directives `%D` (INT), `%F` (REAL, 6
/// decimals), `%E`, `%G`, `%S` (the value as `<<` writes it), `%C`
/// (CHAR), `%B` (BOOL as `TRUE`/`FALSE`), `%X` (INT in hexadecimal) and
/// `%%`, each with an optional width (`%5D`, blanks on the left) and
/// precision (`%.3F`, `%10.3F`). Upper or lower case.
pub fn sprint(format: &str, values: &[RtValue]) -> Result<String, RunError> {
    use std::fmt::Write as _;
    let mut out = String::new();
    let mut next = values.iter();
    let mut chars = format.chars().peekable();
    while let Some(c) = chars.next() {
        if c != '%' {
            out.push(c);
            continue;
        }
        if chars.peek() == Some(&'%') {
            chars.next();
            out.push('%');
            continue;
        }
        let mut width = String::new();
        while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
            width.push(d);
            chars.next();
        }
        let mut precision = None;
        if chars.peek() == Some(&'.') {
            chars.next();
            let mut p = String::new();
            while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                p.push(d);
                chars.next();
            }
            precision = Some(p.parse::<usize>().unwrap_or(0).min(16));
        }
        let width: usize = width.parse::<usize>().unwrap_or(0).min(200);
        let Some(directive) = chars.next() else {
            return Err(RunError::new(
                codes::run::FORMAT,
                "`SPRINT`: the format ends in the middle of a directive",
            ));
        };
        let directive = directive.to_ascii_uppercase();
        if !"DFEGSCBX".contains(directive) {
            return Err(RunError::new(
                codes::run::FORMAT,
                format!("`SPRINT`: `%{directive}` is not a format directive"),
            ));
        }
        let Some(v) = next.next() else {
            return Err(RunError::new(
                codes::run::ARGUMENT_COUNT,
                format!("`SPRINT`: no value for the directive `%{directive}`"),
            ));
        };
        let field = match directive {
            'D' => v.to_int()?.to_string(),
            'X' => format!("{:X}", v.to_int()?),
            'F' => format!("{:.*}", precision.unwrap_or(6), v.to_real()?),
            'E' => c_exponent(v.to_real()?, precision.unwrap_or(6)),
            'G' => c_general(v.to_real()?, precision.unwrap_or(6)),
            'C' => char::from(v.to_char()?).to_string(),
            'B' => if v.to_bool()? { "TRUE" } else { "FALSE" }.to_owned(),
            _ => {
                let mut t = v.to_text()?;
                if let Some(p) = precision {
                    t.truncate(p.min(t.len()));
                }
                t
            }
        };
        let _ = write!(out, "{field:>width$}");
    }
    Ok(out)
}

/// C's `%.*e`: `1.500000e+02`.
fn c_exponent(x: f64, precision: usize) -> String {
    let text = format!("{x:.precision$e}");
    match text.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => text,
    }
}

/// C's `%.*g`: `precision` significant digits, trailing zeros removed,
/// exponent form for very small or large numbers.
fn c_general(x: f64, precision: usize) -> String {
    let p = precision.max(1);
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 { "0".into() } else { format!("{x}") };
    }
    let exp = x.abs().log10().floor() as i32;
    let trim = |mut s: String| {
        if s.contains('.') {
            while s.ends_with('0') {
                s.pop();
            }
            if s.ends_with('.') {
                s.pop();
            }
        }
        s
    };
    if exp < -4 || exp >= p as i32 {
        let text = c_exponent(x, p - 1);
        match text.split_once('e') {
            Some((m, e)) => format!("{}e{e}", trim(m.to_owned())),
            None => text,
        }
    } else {
        let decimals = (p as i32 - 1 - exp).max(0) as usize;
        trim(format!("{x:.decimals$}"))
    }
}
