//! The operators of NC expressions (reference §7.3), as the syntax tree,
//! the AIL and the executor all name them. How tightly each binds is the
//! parser's business (its operator table).

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

// The doc comments are the AIL schema's descriptions
// (`docs/schema/ail.schema.json`), so notes on single operators are plain
// comments.

/// Unary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum UnaryOp {
    Neg,
    Plus,
    Not,
    BNot,
    // `<<x`: converts `x` to a string (as in `SETAL(61000, <<R1)`).
    ToString,
}

/// Binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum BinaryOp {
    Mul,
    Div,
    IntDiv,
    Mod,
    Add,
    Sub,
    BAnd,
    BXor,
    BOr,
    And,
    Xor,
    Or,
    Concat,
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
    // `:` frame chaining.
    Chain,
}
