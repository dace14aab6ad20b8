//! The static types of expressions: the data type a declaration names
//! (the types of system variables are the vocabulary's,
//! `gcodec_lang::sysvars::SysVar::data_type`).
//!
//! Also the case-insensitive name map the variable checks use: names are
//! upper-cased into a stack buffer for each lookup, so a lookup allocates
//! nothing.

use gcodec_lang::DataType;
use gcodec_parser::ast;
use gcodec_source::{Diagnostic, Span, codes};
use rustc_hash::FxHashMap;

/// The type a `DEF` or a `PROC` parameter names; the length of
/// `STRING[n]` when it is a constant.
pub fn from_ast(kind: &ast::TypeKind) -> DataType {
    match kind {
        ast::TypeKind::Int => DataType::Int,
        ast::TypeKind::Real => DataType::Real,
        ast::TypeKind::Bool => DataType::Bool,
        ast::TypeKind::Char => DataType::Char,
        ast::TypeKind::String { length } => DataType::String {
            length: length.as_deref().and_then(constant_count),
        },
        ast::TypeKind::Axis => DataType::Axis,
        ast::TypeKind::Frame => DataType::Frame,
    }
}

/// A constant, whole, positive count (an array dimension, a string
/// length): `10`, not `N` or `2.5`.
pub(crate) fn constant_count(expr: &ast::Expr) -> Option<u32> {
    let value = crate::values::constant(expr)?;
    // Whole and in 1…`u32::MAX`: the cast is exact.
    (value.fract() == 0.0 && value >= 1.0 && value <= f64::from(u32::MAX)).then_some(value as u32)
}

/// What is known of a value beyond its type when it is a constant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Constant {
    None,
    /// A string constant of this many bytes.
    String(usize),
    /// A number.
    Number(f64),
}

/// The diagnostic for assigning a value of type `found` (at `span`) to
/// `name` of type `target`, if the control rejects it: no conversion
/// exists (alarm 14096), a string constant is longer than `STRING[n]`, a
/// string constant for a CHAR is not one character, a constant for a
/// CHAR is outside 0…255 (named as the program `source` writes it).
pub(crate) fn mismatch(
    target: DataType,
    name: &str,
    found: DataType,
    constant: Constant,
    span: Span,
    source: &[u8],
) -> Option<Diagnostic> {
    if !found.converts_to(target) {
        let help = match target {
            DataType::Axis => {
                "an AXIS variable takes an axis name (`X`, `AX1`) or an AXIS value (`$P_AXN1`, `AXNAME(\"X\")`); to move the axis it names, write `AX[name]=value`"
            }
            DataType::Frame => {
                "a FRAME takes a frame (`CTRANS(X,10)`, another FRAME, a frame system variable); a component is written `name[X,TR]`"
            }
            DataType::String { .. } => {
                "numbers do not convert to STRING by assignment; concatenate to convert (`\"\"<<R1`)"
            }
            _ => {
                "the control has no conversion between these types (alarm 14096 \"illegal type conversion\")"
            }
        };
        return Some(
            Diagnostic::new(
                codes::lower::TYPE_MISMATCH,
                format!(
                    "{} {} value cannot be assigned to `{name}`, which is {}",
                    found.article(),
                    found.keyword(),
                    target.describe()
                ),
            )
            .with_label(span, found.keyword().to_owned())
            .with_help(help),
        );
    }
    let problem = match (target, constant) {
        (DataType::String { length: Some(n) }, Constant::String(len)) if len > n as usize => {
            format!("the string has {len} characters; `{name}` is STRING[{n}]")
        }
        (DataType::Char, Constant::String(len)) if len != 1 => {
            format!(
                "`{name}` is CHAR: a string converts to CHAR only if it has one character; this one has {len}"
            )
        }
        (DataType::Char, Constant::Number(v)) if !(0.0..=255.0).contains(&v) => {
            format!(
                "`{name}` is CHAR (0…255); {} is outside",
                crate::values::written(source, span)
            )
        }
        _ => return None,
    };
    Some(
        Diagnostic::new(codes::lower::TYPE_MISMATCH, problem)
            .with_label(span, "does not fit")
            .with_help("the control rejects the value (alarm 14096 \"illegal type conversion\"); shorten it or change the declaration"),
    )
}

/// The type and constant of a literal, if the expression is one.
pub(crate) fn literal(expr: &ast::Expr) -> Option<(DataType, Constant)> {
    match &expr.kind {
        // A string's length counts characters of the control's code page,
        // not the UTF-8 bytes that hold them (SPEC §11.3).
        ast::ExprKind::String { value } => {
            let len = value.chars().count();
            Some((
                DataType::String {
                    length: u32::try_from(len).ok(),
                },
                Constant::String(len),
            ))
        }
        ast::ExprKind::Bool { .. } => Some((DataType::Bool, Constant::None)),
        _ => {
            let value = crate::values::constant(expr)?;
            Some((
                if number_is_integer(expr) {
                    DataType::Int
                } else {
                    DataType::Real
                },
                Constant::Number(value),
            ))
        }
    }
}

/// Whether a signed number literal (`-5`) is written as an integer.
fn number_is_integer(expr: &ast::Expr) -> bool {
    match &expr.kind {
        ast::ExprKind::Number { integer, .. } => *integer,
        ast::ExprKind::Unary { operand, .. } => number_is_integer(operand),
        _ => false,
    }
}

/// Calls `f` with `name` in upper case, without allocating for names of
/// up to 64 bytes (the control's names have at most 32 characters).
pub(crate) fn with_upper<R>(name: &str, f: impl FnOnce(&str) -> R) -> R {
    let mut buf = [0u8; 64];
    if name.len() <= buf.len() {
        for (d, s) in buf.iter_mut().zip(name.bytes()) {
            *d = s.to_ascii_uppercase();
        }
        // Upper-casing ASCII bytes keeps UTF-8 valid.
        f(std::str::from_utf8(&buf[..name.len()]).unwrap_or_default())
    } else {
        f(&name.to_ascii_uppercase())
    }
}

/// A map from names to values, case-insensitive.
#[derive(Clone, Debug)]
pub(crate) struct NameMap<V> {
    map: FxHashMap<Box<str>, V>,
}

impl<V> Default for NameMap<V> {
    fn default() -> Self {
        Self {
            map: FxHashMap::default(),
        }
    }
}

impl<V> NameMap<V> {
    pub(crate) fn get(&self, name: &str) -> Option<&V> {
        if self.map.is_empty() {
            return None;
        }
        with_upper(name, |key| self.map.get(key))
    }

    pub(crate) fn get_mut(&mut self, name: &str) -> Option<&mut V> {
        with_upper(name, |key| self.map.get_mut(key))
    }

    pub(crate) fn contains(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    /// Inserts `value` unless the name is taken; returns the value already
    /// there, if any.
    pub(crate) fn insert_new(&mut self, name: &str, value: V) -> Option<&V> {
        let key: Box<str> = name.to_ascii_uppercase().into();
        match self.map.entry(key) {
            std::collections::hash_map::Entry::Occupied(e) => Some(e.into_mut()),
            std::collections::hash_map::Entry::Vacant(e) => {
                e.insert(value);
                None
            }
        }
    }

    pub(crate) fn len(&self) -> usize {
        self.map.len()
    }

    pub(crate) fn values(&self) -> impl Iterator<Item = &V> {
        self.map.values()
    }

    /// The names with their values, in upper case, in no particular
    /// order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (&str, &V)> {
        self.map.iter().map(|(name, value)| (&**name, value))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn name_map_ignores_case() {
        let mut map = NameMap::default();
        assert!(map.insert_new("Gr_Tool", 1).is_none());
        assert_eq!(map.get("GR_TOOL"), Some(&1));
        assert_eq!(map.get("gr_tool"), Some(&1));
        assert_eq!(map.insert_new("GR_TOOL", 2), Some(&1));
        let long = "A".repeat(100);
        assert!(map.insert_new(&long, 3).is_none());
        assert_eq!(map.get(&long.to_ascii_lowercase()), Some(&3));
    }
}
