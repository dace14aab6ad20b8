//! Values and expressions in AIL: a constant where lowering could fold one,
//! otherwise an expression tree the executor evaluates.

use std::borrow::Cow;

use gcodec_lang::functions::Function;
use gcodec_lang::sysvars::SysVarId;
use gcodec_lang::{BinaryOp, UnaryOp};
use schemars::JsonSchema;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A number known when lowering, or an expression evaluated at run time.
/// In JSON a constant is a plain number.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum Value {
    Const(f64),
    Expr(Box<Expr>),
}

/// An expression evaluated at run time.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(tag = "op", rename_all = "snake_case")]
pub enum Expr {
    Number {
        value: f64,
    },
    String {
        value: String,
    },
    Bool {
        value: bool,
    },
    /// A variable, with its indices (`R1` is `R` with index 1).
    Var {
        var_kind: VarKind,
        /// The name in upper case (`R`, `COUNTER`, `$P_UIFR`); `R` is
        /// not allocated for each R parameter.
        #[schemars(with = "String")]
        name: VarName,
        indices: Vec<Expr>,
    },
    /// A built-in or user function.
    Call {
        #[schemars(with = "String")]
        name: Callee,
        args: Vec<Option<Expr>>,
    },
    Unary {
        operator: UnaryOp,
        operand: Box<Expr>,
    },
    Binary {
        operator: BinaryOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
    },
}

/// What a variable is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum VarKind {
    RParameter,
    /// A `DEF` variable or parameter.
    User,
    /// A `$` system variable.
    System,
    /// An axis name used as a value (`AX[X]`, frame functions).
    Axis,
}

/// What a call calls: a predefined function of the vocabulary, or a name
/// it does not list (a user function, or one the executor reports as
/// unknown). In JSON it is the name in upper case (`"SIN"`).
#[derive(Clone, Debug, PartialEq)]
pub enum Callee {
    Predefined(Function),
    Other(String),
}

impl Callee {
    /// The callee of the function named `name` (any case); another name
    /// is kept in upper case.
    pub fn named(name: &str) -> Self {
        match Function::named(name) {
            Some(function) => Callee::Predefined(function),
            None => Callee::Other(name.to_ascii_uppercase()),
        }
    }

    pub fn name(&self) -> &str {
        match self {
            Callee::Predefined(function) => function.name(),
            Callee::Other(name) => name,
        }
    }
}

impl Serialize for Callee {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Callee {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = std::borrow::Cow::<'de, str>::deserialize(deserializer)?;
        Ok(Callee::named(&name))
    }
}

/// The name of a variable: a system variable the vocabulary lists, by its
/// id, or the name as text (upper case): R, user variables, axes, and the
/// system variables written in another spelling (`$R5`, `$$SA_…`) or not
/// listed. In JSON it is the name either way.
#[derive(Clone, Debug, PartialEq)]
pub enum VarName {
    System(SysVarId),
    Text(Cow<'static, str>),
}

impl VarName {
    /// The name of the variable written `name` (upper case): the listed
    /// system variable spelled so, else the text.
    pub fn named(name: Cow<'static, str>) -> Self {
        match SysVarId::exactly(&name) {
            Some(id) => VarName::System(id),
            None => VarName::Text(name),
        }
    }

    /// The listed system variable, if it is one.
    pub fn system(&self) -> Option<SysVarId> {
        match self {
            VarName::System(id) => Some(*id),
            VarName::Text(_) => None,
        }
    }

    pub fn as_str(&self) -> &str {
        match self {
            VarName::System(id) => id.name(),
            VarName::Text(name) => name,
        }
    }
}

impl Serialize for VarName {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.as_str())
    }
}

impl<'de> Deserialize<'de> for VarName {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        String::deserialize(deserializer).map(|name| VarName::named(Cow::Owned(name)))
    }
}
