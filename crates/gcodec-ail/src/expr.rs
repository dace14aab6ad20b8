//! Values and expressions in AIL: a constant where lowering could fold one,
//! otherwise an expression tree the executor evaluates.

use std::borrow::Cow;

use gcodec_lang::functions::Function;
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
        name: Cow<'static, str>,
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
