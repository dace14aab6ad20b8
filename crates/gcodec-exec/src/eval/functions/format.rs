//! `SPRINT`: text formatted from values, C's `printf` directives as the
//! control reads them.

use std::sync::Arc;

use gcodec_lang::types::MAX_STRING_LEN;
use gcodec_source::{codes, cp1252};

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
/// precision (`%.3F`, `%10.3F`), both at most 200 (a STRING's length) and
/// counting characters. Upper or lower case.
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
        let width = field_size(&mut chars, "width")?.unwrap_or(0);
        let mut precision = None;
        if chars.peek() == Some(&'.') {
            chars.next();
            precision = Some(field_size(&mut chars, "precision")?.unwrap_or(0));
        }
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
            'C' => cp1252(v.to_char()?).to_string(),
            'B' => if v.to_bool()? { "TRUE" } else { "FALSE" }.to_owned(),
            _ => {
                let t = v.to_text()?;
                match precision {
                    Some(p) => t.chars().take(p).collect(),
                    None => t,
                }
            }
        };
        // The width counts characters, as Rust's padding does.
        let _ = write!(out, "{field:>width$}");
    }
    Ok(out)
}

/// The digits of a width or precision at `chars`, consumed: `None` when
/// there are none. A field larger than a STRING holds
/// ([`MAX_STRING_LEN`] characters) is [`codes::run::FORMAT`], named as
/// written, rather than cut silently.
fn field_size(
    chars: &mut std::iter::Peekable<std::str::Chars<'_>>,
    what: &str,
) -> Result<Option<usize>, RunError> {
    let mut digits = String::new();
    while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
        digits.push(d);
        chars.next();
    }
    if digits.is_empty() {
        return Ok(None);
    }
    let max = usize::from(MAX_STRING_LEN);
    match digits.parse::<usize>() {
        Ok(n) if n <= max => Ok(Some(n)),
        _ => Err(RunError::new(
            codes::run::FORMAT,
            format!("`SPRINT`: the {what} {digits} is more than a STRING holds ({max} characters)"),
        )),
    }
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
