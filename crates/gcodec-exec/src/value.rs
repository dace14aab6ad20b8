//! Run-time values and the conversions between their types, as the
//! control does them (reference §7.1, SPEC §10.11 and §11.x "Values,
//! expressions and variables at run time").
//!
//! A value is one of the control's types: `INT` (32 bits), `REAL` (IEEE
//! double), `BOOL`, `CHAR` (a byte 0…255), `STRING`, `AXIS` (an axis
//! identifier) and `FRAME`. Numbers, truth values and characters are held
//! inline, so that evaluating a numeric expression allocates nothing;
//! strings, axis names and frames are shared (`Arc`), so that copying a
//! value never copies text.
//!
//! A STRING is a sequence of characters of the control's 8-bit code page
//! (one byte per character on the control), held as Rust text: every
//! length, position and limit counts characters (`char`s), never UTF-8
//! bytes, whatever the file's encoding. A CHAR is the code of one
//! character in Windows-1252 ([`gcodec_source::cp1252`]).
//!
//! Conversions follow the control's table (alarm 14096): REAL, INT, BOOL
//! and CHAR convert into each other; CHAR and STRING into STRING; STRING
//! into BOOL (empty is FALSE) and into CHAR (exactly one character); AXIS
//! and FRAME only into themselves. REAL to INT (and CHAR) rounds half away
//! from zero (`2.5` → 3, `-2.5` → −3). A conversion that fails is a
//! [`RunError`] with a stable code (from the registry, [`codes::run`]).

use std::fmt;
use std::sync::Arc;

use gcodec_lang::DataType;
use gcodec_lang::types::MAX_STRING_LEN;
use gcodec_source::{Code, codes, cp1252, cp1252_byte};

/// A run-time error: a stable code (from [`codes::run`]) and a message naming what
/// failed. Never a panic: the executor reports it as a diagnostic event.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunError {
    pub code: &'static Code,
    pub message: String,
    /// How to fix it or what the control would do, where that is known.
    pub help: Option<&'static str>,
}

impl RunError {
    pub fn new(code: &'static Code, message: impl Into<String>) -> Self {
        Self {
            code,
            message: message.into(),
            help: None,
        }
    }

    pub fn with_help(mut self, help: &'static str) -> Self {
        self.help = Some(help);
        self
    }

    pub(crate) fn type_mismatch(from: &RtValue, to: &str) -> Self {
        Self::new(
            codes::run::TYPE_MISMATCH,
            format!("a {} value cannot be converted to {to}", from.type_name()),
        )
    }
}

impl fmt::Display for RunError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.code, self.message)
    }
}

impl std::error::Error for RunError {}

impl RtValue {
    /// The value a variable of this type starts with: 0, 0.0, FALSE,
    /// CHAR 0, the empty string, no axis (an empty name), the neutral
    /// frame.
    pub fn initial(ty: DataType) -> RtValue {
        match ty {
            DataType::Int => RtValue::Int(0),
            DataType::Real => RtValue::Real(0.0),
            DataType::Bool => RtValue::Bool(false),
            DataType::Char => RtValue::Char(0),
            DataType::String { .. } => RtValue::String(Arc::from("")),
            DataType::Axis => RtValue::Axis(Arc::from("")),
            DataType::Frame => RtValue::Frame(Arc::new(FrameValue::default())),
        }
    }
}

/// A frame (placeholder: the frame work fills in its operations): per
/// axis a translation, a fine translation, a rotation (degrees), a scale
/// and a mirroring, as `$P_UIFR[n, axis, TR|FI|RT|SC|MI]` address them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FrameValue {
    /// The axes with a component other than neutral, in the order first
    /// set.
    pub axes: Vec<FrameAxis>,
}

/// The components of a frame for one axis.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameAxis {
    /// The axis name, upper case.
    pub axis: Arc<str>,
    /// `TR`
    pub translation: f64,
    /// `FI`
    pub fine: f64,
    /// `RT`, degrees.
    pub rotation: f64,
    /// `SC`, 1 when neutral.
    pub scale: f64,
    /// `MI`
    pub mirror: bool,
}

impl FrameAxis {
    /// Neutral components for `axis`.
    pub fn neutral(axis: &str) -> Self {
        Self {
            axis: Arc::from(axis),
            translation: 0.0,
            fine: 0.0,
            rotation: 0.0,
            scale: 1.0,
            mirror: false,
        }
    }
}

impl FrameValue {
    /// The components of `axis` (neutral ones when the frame has none).
    pub fn axis(&self, axis: &str) -> FrameAxis {
        self.axes
            .iter()
            .find(|a| a.axis.eq_ignore_ascii_case(axis))
            .cloned()
            .unwrap_or_else(|| FrameAxis::neutral(axis))
    }

    /// One component by its keyword (`TR`, `FI`, `RT`, `SC`, `MI`, any
    /// case); `None` for another keyword.
    pub fn component(&self, axis: &str, component: &str) -> Option<f64> {
        let component = Component::parse(component)?;
        Some(component.of(self.axes.iter().find(|a| a.axis.eq_ignore_ascii_case(axis))))
    }

    /// `$P_UIFR[n, axis, component]` read: the component named by the
    /// index value `component` (an AXIS or STRING carrying the keyword).
    pub(crate) fn component_of(&self, axis: &str, component: &RtValue) -> Result<f64, RunError> {
        let name = component_name(component)?;
        self.component(axis, name)
            .ok_or_else(|| not_a_component(name))
    }

    /// `$P_UIFR[n, axis, component] = value`: sets the component named by
    /// the index value `component` of `axis` (upper case; added with
    /// neutral components when the frame has none for it) to `value`.
    pub(crate) fn set_component(
        &mut self,
        axis: &str,
        component: &RtValue,
        value: &RtValue,
    ) -> Result<(), RunError> {
        let name = component_name(component)?;
        let value = value.to_real()?;
        let Some(component) = Component::parse(name) else {
            return Err(not_a_component(&name.to_ascii_uppercase()));
        };
        let at = match self
            .axes
            .iter()
            .position(|a| a.axis.eq_ignore_ascii_case(axis))
        {
            Some(at) => at,
            None => {
                self.axes.push(FrameAxis::neutral(axis));
                self.axes.len() - 1
            }
        };
        component.set(&mut self.axes[at], value);
        Ok(())
    }
}

/// A component of a frame for one axis, as `$P_UIFR[n, axis, component]`
/// names it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Component {
    Tr,
    Fi,
    Rt,
    Sc,
    Mi,
}

impl Component {
    /// The component with the keyword `text` (`TR`, `FI`, `RT`, `SC`,
    /// `MI`, any case).
    fn parse(text: &str) -> Option<Self> {
        [
            ("TR", Self::Tr),
            ("FI", Self::Fi),
            ("RT", Self::Rt),
            ("SC", Self::Sc),
            ("MI", Self::Mi),
        ]
        .into_iter()
        .find(|(keyword, _)| keyword.eq_ignore_ascii_case(text))
        .map(|(_, c)| c)
    }

    /// The component of `axis`; of [`FrameAxis::neutral`] (1 for `SC`, 0
    /// for the others) when there is none.
    fn of(self, axis: Option<&FrameAxis>) -> f64 {
        let Some(a) = axis else {
            return if self == Self::Sc { 1.0 } else { 0.0 };
        };
        match self {
            Self::Tr => a.translation,
            Self::Fi => a.fine,
            Self::Rt => a.rotation,
            Self::Sc => a.scale,
            Self::Mi => f64::from(u8::from(a.mirror)),
        }
    }

    /// Sets the component of `axis` (`MI`: mirrored when not 0).
    fn set(self, axis: &mut FrameAxis, value: f64) {
        match self {
            Self::Tr => axis.translation = value,
            Self::Fi => axis.fine = value,
            Self::Rt => axis.rotation = value,
            Self::Sc => axis.scale = value,
            Self::Mi => axis.mirror = value != 0.0,
        }
    }
}

/// The keyword a `$P_UIFR` component index carries: an AXIS or STRING
/// value.
fn component_name(component: &RtValue) -> Result<&str, RunError> {
    match component {
        RtValue::Axis(c) | RtValue::String(c) => Ok(c),
        v => Err(RunError::type_mismatch(v, "a frame component")),
    }
}

fn not_a_component(name: &str) -> RunError {
    RunError::new(
        codes::run::TYPE_MISMATCH,
        format!("`{name}` is not a frame component (TR, FI, RT, SC, MI)"),
    )
}

/// A value at run time.
#[derive(Clone, Debug, PartialEq)]
pub enum RtValue {
    Int(i32),
    Real(f64),
    Bool(bool),
    /// A code 0…255 of the control's code page (Windows-1252).
    Char(u8),
    String(Arc<str>),
    /// An axis identifier, upper case. An empty name is "no axis".
    Axis(Arc<str>),
    Frame(Arc<FrameValue>),
}

impl From<i32> for RtValue {
    fn from(v: i32) -> Self {
        Self::Int(v)
    }
}

impl From<f64> for RtValue {
    fn from(v: f64) -> Self {
        Self::Real(v)
    }
}

impl From<bool> for RtValue {
    fn from(v: bool) -> Self {
        Self::Bool(v)
    }
}

impl From<&str> for RtValue {
    fn from(v: &str) -> Self {
        Self::String(Arc::from(v))
    }
}

impl RtValue {
    /// A string value.
    pub fn string(text: impl AsRef<str>) -> Self {
        Self::String(Arc::from(text.as_ref()))
    }

    /// An axis value (the name in upper case).
    pub fn axis(name: &str) -> Self {
        Self::Axis(Arc::from(name.to_ascii_uppercase().as_str()))
    }

    /// The type keyword (`INT`, `REAL`, …).
    pub fn type_name(&self) -> &'static str {
        match self {
            Self::Int(_) => "INT",
            Self::Real(_) => "REAL",
            Self::Bool(_) => "BOOL",
            Self::Char(_) => "CHAR",
            Self::String(_) => "STRING",
            Self::Axis(_) => "AXIS",
            Self::Frame(_) => "FRAME",
        }
    }

    /// INT, REAL, BOOL or CHAR.
    pub fn is_numeric(&self) -> bool {
        matches!(
            self,
            Self::Int(_) | Self::Real(_) | Self::Bool(_) | Self::Char(_)
        )
    }

    /// As a REAL: INT and CHAR as their number, BOOL as 1 or 0.
    pub fn to_real(&self) -> Result<f64, RunError> {
        match *self {
            Self::Int(i) => Ok(f64::from(i)),
            Self::Real(r) => Ok(r),
            Self::Bool(b) => Ok(if b { 1.0 } else { 0.0 }),
            Self::Char(c) => Ok(f64::from(c)),
            _ => Err(RunError::type_mismatch(self, "REAL")),
        }
    }

    /// As an INT: a REAL rounded half away from zero (alarm when outside
    /// the INT range), BOOL 1 or 0, CHAR its code.
    pub fn to_int(&self) -> Result<i32, RunError> {
        match *self {
            Self::Int(i) => Ok(i),
            Self::Real(r) => real_to_int(r),
            Self::Bool(b) => Ok(i32::from(b)),
            Self::Char(c) => Ok(i32::from(c)),
            _ => Err(RunError::type_mismatch(self, "INT")),
        }
    }

    /// As a BOOL: a number is TRUE when not 0; a STRING when not empty.
    pub fn to_bool(&self) -> Result<bool, RunError> {
        match self {
            Self::Int(i) => Ok(*i != 0),
            Self::Real(r) => Ok(*r != 0.0),
            Self::Bool(b) => Ok(*b),
            Self::Char(c) => Ok(*c != 0),
            Self::String(s) => Ok(!s.is_empty()),
            _ => Err(RunError::type_mismatch(self, "BOOL")),
        }
    }

    /// As a CHAR: a number 0…255 (a REAL rounded), BOOL 1 or 0, a STRING
    /// of exactly one character.
    pub fn to_char(&self) -> Result<u8, RunError> {
        let code = match self {
            Self::Char(c) => return Ok(*c),
            Self::Bool(b) => return Ok(u8::from(*b)),
            Self::Int(_) | Self::Real(_) => self.to_int()?,
            Self::String(s) => {
                let mut chars = s.chars();
                return match (chars.next(), chars.next()) {
                    (Some(c), None) => char_code(c),
                    _ => Err(RunError::new(
                        codes::run::TYPE_MISMATCH,
                        format!(
                            "the string \"{s}\" has {} characters: a CHAR is one",
                            s.chars().count()
                        ),
                    )),
                };
            }
            _ => return Err(RunError::type_mismatch(self, "CHAR")),
        };
        u8::try_from(code).map_err(|_| {
            RunError::new(
                codes::run::OVERFLOW,
                format!("{code} is outside the range of a CHAR (0…255)"),
            )
        })
    }

    /// As an AXIS: only an AXIS.
    pub fn to_axis(&self) -> Result<Arc<str>, RunError> {
        match self {
            Self::Axis(a) => Ok(a.clone()),
            _ => Err(RunError::type_mismatch(self, "AXIS")),
        }
    }

    /// The value converted for a variable of type `ty` (an assignment):
    /// the control's table, a string checked against `STRING[n]`.
    pub fn convert_to(&self, ty: DataType) -> Result<RtValue, RunError> {
        Ok(match ty {
            DataType::Int => Self::Int(self.to_int()?),
            DataType::Real => Self::Real(self.to_real()?),
            DataType::Bool => Self::Bool(self.to_bool()?),
            DataType::Char => Self::Char(self.to_char()?),
            DataType::String { length } => {
                let max_len = length.unwrap_or(u32::from(MAX_STRING_LEN));
                let s: Arc<str> = match self {
                    Self::String(s) => s.clone(),
                    Self::Char(c) => Arc::from(char_text(*c).as_str()),
                    _ => return Err(RunError::type_mismatch(self, "STRING")),
                };
                let len = s.chars().count();
                if len > max_len as usize {
                    return Err(RunError::new(
                        codes::run::STRING_TOO_LONG,
                        format!("a string of {len} characters does not fit a STRING[{max_len}]"),
                    ));
                }
                Self::String(s)
            }
            DataType::Axis => Self::Axis(self.to_axis()?),
            DataType::Frame => match self {
                Self::Frame(f) => Self::Frame(f.clone()),
                _ => return Err(RunError::type_mismatch(self, "FRAME")),
            },
        })
    }

    /// The text `<<` makes of the value: a string as it is, a CHAR as its
    /// character, an INT in decimal, a REAL by [`format_real`], a BOOL as
    /// `1` or `0`, an AXIS as its name. A FRAME has none.
    pub fn to_text(&self) -> Result<String, RunError> {
        let mut out = String::new();
        self.write_text(&mut out)?;
        Ok(out)
    }

    /// [`to_text`](Self::to_text) appended to `out`.
    pub fn write_text(&self, out: &mut String) -> Result<(), RunError> {
        use std::fmt::Write as _;
        match self {
            Self::Int(i) => {
                let _ = write!(out, "{i}");
            }
            Self::Real(r) => format_real(*r, out),
            Self::Bool(b) => out.push(if *b { '1' } else { '0' }),
            Self::Char(c) => out.push(cp1252(*c)),
            Self::String(s) | Self::Axis(s) => out.push_str(s),
            Self::Frame(_) => return Err(RunError::type_mismatch(self, "STRING")),
        }
        Ok(())
    }
}

/// A REAL rounded half away from zero to an INT; out of range is
/// [`codes::run::OVERFLOW`].
pub fn real_to_int(r: f64) -> Result<i32, RunError> {
    let rounded = r.round();
    if rounded.is_nan() || rounded < f64::from(i32::MIN) || rounded > f64::from(i32::MAX) {
        Err(RunError::new(
            codes::run::OVERFLOW,
            format!("{r} is outside the range of an INT"),
        ))
    } else {
        Ok(rounded as i32)
    }
}

/// A REAL result that is not a finite number, as an overflow makes
/// (`1EX300*1EX300`, `EXP(1000)`), is [`codes::run::OVERFLOW`] where it is
/// computed, so that no infinity or NaN reaches a variable, position,
/// feed or speed; `what` names the computation.
pub(crate) fn finite_real(r: f64, what: impl FnOnce() -> String) -> Result<f64, RunError> {
    if r.is_finite() {
        Ok(r)
    } else {
        Err(RunError::new(
            codes::run::OVERFLOW,
            format!(
                "{} is outside the range of a REAL (about ±1.8e+308)",
                what()
            ),
        ))
    }
}

/// A character code as text: its character in the control's code page
/// (Windows-1252, SPEC §11.3).
pub(crate) fn char_text(c: u8) -> String {
    cp1252(c).to_string()
}

/// The code of the character `c` in the control's code page: a CHAR;
/// a character the code page lacks is [`codes::run::TYPE_MISMATCH`].
pub(crate) fn char_code(c: char) -> Result<u8, RunError> {
    cp1252_byte(c).ok_or_else(|| {
        RunError::new(
            codes::run::TYPE_MISMATCH,
            format!("`{c}` is not a character of the control's code page (Windows-1252)"),
        )
    })
}

/// A REAL as `<<` writes it: fixed point with at most 10 decimal places,
/// trailing zeros and a trailing point left off (`1.5`, `3`, `0.3333333333`,
/// `-2`); `-0` is `0`; magnitudes of 1e15 and more, or below 1e-10, in
/// exponent form (`1e+20`, `1.5e-12`).
pub fn format_real(r: f64, out: &mut String) {
    use std::fmt::Write as _;
    if r == 0.0 {
        out.push('0');
        return;
    }
    if !r.is_finite() {
        let _ = write!(out, "{r}");
        return;
    }
    let magnitude = r.abs();
    if !(1e-10..1e15).contains(&magnitude) {
        let text = format!("{r:e}");
        // Rust writes `1e20`, `1.5e-12`: add the sign of the exponent.
        match text.split_once('e') {
            Some((m, e)) if !e.starts_with('-') => {
                let _ = write!(out, "{m}e+{e}");
            }
            _ => out.push_str(&text),
        }
        return;
    }
    let start = out.len();
    let _ = write!(out, "{r:.10}");
    if out[start..].contains('.') {
        while out.ends_with('0') {
            out.pop();
        }
        if out.ends_with('.') {
            out.pop();
        }
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_components_read_and_write_by_keyword() {
        let mut f = FrameValue::default();
        let set = |f: &mut FrameValue, c: &str, v: f64| {
            f.set_component("X", &RtValue::string(c), &RtValue::Real(v))
        };
        assert_eq!(f.component("Q", "sc"), Some(1.0));
        assert_eq!(f.component("Q", "Tr"), Some(0.0));
        assert_eq!(f.component("Q", "XX"), None);
        set(&mut f, "tr", 5.0).unwrap();
        set(&mut f, "MI", 2.0).unwrap();
        assert_eq!(f.axes.len(), 1);
        assert_eq!(f.component("x", "TR"), Some(5.0));
        assert_eq!(f.component("X", "mi"), Some(1.0));
        assert_eq!(
            set(&mut f, "xx", 1.0).unwrap_err().message,
            "`XX` is not a frame component (TR, FI, RT, SC, MI)"
        );
        assert_eq!(
            f.component_of("X", &RtValue::string("xx"))
                .unwrap_err()
                .message,
            "`xx` is not a frame component (TR, FI, RT, SC, MI)"
        );
        assert_eq!(
            f.component_of("X", &RtValue::Int(1)).unwrap_err().code,
            "gcodec::run::type_mismatch"
        );
    }
}
