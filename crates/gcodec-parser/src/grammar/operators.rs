//! The operator table of expressions: for every binary and unary operator
//! its token, its text, its binding power and how it associates. The
//! chumsky pratt parser ([`super::expressions`]), the fast path
//! (`crate::fast`), the driver's operator count and the text tree all read
//! it, so the precedence they apply cannot drift apart.
//!
//! Rows are keyed on [`BinaryOp`] and [`UnaryOp`] and follow the enums'
//! order (checked when the tables are built), so the row of an operator is
//! found by its discriminant and the table does not depend on where the
//! enums are defined.

use gcodec_lexer::TokenKind as T;

use gcodec_lang::{BinaryOp, UnaryOp};

/// How a chain of operators of one precedence class groups.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Associativity {
    /// `a-b-c` is `(a-b)-c`. Every SINUMERIK binary operator groups so;
    /// both parsers match on this, so a new kind must be handled by both.
    Left,
}

/// A precedence class of binary operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Precedence {
    /// Higher binds tighter; every class binds looser than [`PREFIX_POWER`].
    pub power: u8,
    pub associativity: Associativity,
}

const fn left(power: u8) -> Precedence {
    Precedence {
        power,
        associativity: Associativity::Left,
    }
}

const MULTIPLICATIVE: Precedence = left(11);
const ADDITIVE: Precedence = left(10);
const BIT_AND: Precedence = left(9);
const BIT_XOR: Precedence = left(8);
const BIT_OR: Precedence = left(7);
const AND: Precedence = left(6);
const XOR: Precedence = left(5);
const OR: Precedence = left(4);
const CONCATENATION: Precedence = left(3);
const COMPARISON: Precedence = left(2);
const CHAIN: Precedence = left(1);

/// The precedence classes, tightest first. The pratt parser tries one
/// operator parser per class, in this order.
pub(crate) const PRECEDENCES: [Precedence; 11] = [
    MULTIPLICATIVE,
    ADDITIVE,
    BIT_AND,
    BIT_XOR,
    BIT_OR,
    AND,
    XOR,
    OR,
    CONCATENATION,
    COMPARISON,
    CHAIN,
];

/// One binary operator.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BinaryOperator {
    pub op: BinaryOp,
    pub token: T,
    /// As written in a program (and in the text tree).
    pub text: &'static str,
    pub precedence: Precedence,
}

/// One prefix operator; all bind at [`PREFIX_POWER`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct UnaryOperator {
    pub op: UnaryOp,
    pub token: T,
    /// As written in a program (and in the text tree).
    pub text: &'static str,
}

const fn binary(
    op: BinaryOp,
    token: T,
    text: &'static str,
    precedence: Precedence,
) -> BinaryOperator {
    BinaryOperator {
        op,
        token,
        text,
        precedence,
    }
}

/// The binary operators in Siemens precedence, tightest first.
pub(crate) const BINARY: [BinaryOperator; 20] = [
    binary(BinaryOp::Mul, T::Star, "*", MULTIPLICATIVE),
    binary(BinaryOp::Div, T::Slash, "/", MULTIPLICATIVE),
    binary(BinaryOp::IntDiv, T::Div, "DIV", MULTIPLICATIVE),
    binary(BinaryOp::Mod, T::Mod, "MOD", MULTIPLICATIVE),
    binary(BinaryOp::Add, T::Plus, "+", ADDITIVE),
    binary(BinaryOp::Sub, T::Minus, "-", ADDITIVE),
    binary(BinaryOp::BAnd, T::BAnd, "B_AND", BIT_AND),
    binary(BinaryOp::BXor, T::BXor, "B_XOR", BIT_XOR),
    binary(BinaryOp::BOr, T::BOr, "B_OR", BIT_OR),
    binary(BinaryOp::And, T::And, "AND", AND),
    binary(BinaryOp::Xor, T::Xor, "XOR", XOR),
    binary(BinaryOp::Or, T::Or, "OR", OR),
    binary(BinaryOp::Concat, T::Concat, "<<", CONCATENATION),
    binary(BinaryOp::Eq, T::EqEq, "==", COMPARISON),
    binary(BinaryOp::Ne, T::Ne, "<>", COMPARISON),
    binary(BinaryOp::Lt, T::Lt, "<", COMPARISON),
    binary(BinaryOp::Gt, T::Gt, ">", COMPARISON),
    binary(BinaryOp::Le, T::Le, "<=", COMPARISON),
    binary(BinaryOp::Ge, T::Ge, ">=", COMPARISON),
    // `:` chains frames: `$P_PFRAME=CTRANS(X,10):CROT(Z,45)`.
    binary(BinaryOp::Chain, T::Colon, ":", CHAIN),
];

/// The prefix operators.
pub(crate) const UNARY: [UnaryOperator; 5] = [
    UnaryOperator {
        op: UnaryOp::Neg,
        token: T::Minus,
        text: "-",
    },
    UnaryOperator {
        op: UnaryOp::Plus,
        token: T::Plus,
        text: "+",
    },
    UnaryOperator {
        op: UnaryOp::Not,
        token: T::Not,
        text: "NOT",
    },
    UnaryOperator {
        op: UnaryOp::BNot,
        token: T::BNot,
        text: "B_NOT",
    },
    // `<<R1`: the value as a string.
    UnaryOperator {
        op: UnaryOp::ToString,
        token: T::Concat,
        text: "<<",
    },
];

/// The binding power of every prefix operator, above every binary one.
pub(crate) const PREFIX_POWER: u8 = 12;

/// What the parsers look up per token kind, built from [`BINARY`] and
/// [`UNARY`] so that a lookup is one load: the operators a token stands
/// for (binary after an operand, prefix before one), whether it is an
/// operator and whether one spelt as a word.
struct TokenTables {
    binary: [Option<(BinaryOp, Precedence)>; T::ALL.len()],
    unary: [Option<UnaryOp>; T::ALL.len()],
    operator: [bool; T::ALL.len()],
    word: [bool; T::ALL.len()],
}

static TOKENS: TokenTables = {
    let mut tables = TokenTables {
        binary: [None; T::ALL.len()],
        unary: [None; T::ALL.len()],
        operator: [false; T::ALL.len()],
        word: [false; T::ALL.len()],
    };
    let mut i = 0;
    while i < BINARY.len() {
        let row = BINARY[i];
        // Rows follow the enum, so an operator's row is `BINARY[op as usize]`.
        assert!(row.op as usize == i);
        tables.binary[row.token as usize] = Some((row.op, row.precedence));
        tables.operator[row.token as usize] = true;
        tables.word[row.token as usize] = is_word(row.text);
        i += 1;
    }
    let mut i = 0;
    while i < UNARY.len() {
        let row = UNARY[i];
        assert!(row.op as usize == i);
        tables.unary[row.token as usize] = Some(row.op);
        tables.operator[row.token as usize] = true;
        tables.word[row.token as usize] = is_word(row.text);
        i += 1;
    }
    tables
};

/// The binary operator a token stands for after an operand, and how it
/// binds.
#[inline]
pub(crate) fn binary_token(kind: T) -> Option<(BinaryOp, Precedence)> {
    TOKENS.binary[kind as usize]
}

/// The prefix operator a token stands for before an operand.
#[inline]
pub(crate) fn unary_token(kind: T) -> Option<UnaryOp> {
    TOKENS.unary[kind as usize]
}

/// The row of `op`.
pub(crate) fn binary_operator(op: BinaryOp) -> &'static BinaryOperator {
    &BINARY[op as usize]
}

/// The row of `op`.
pub(crate) fn unary_operator(op: UnaryOp) -> &'static UnaryOperator {
    &UNARY[op as usize]
}

/// Whether a token is an operator, binary or prefix.
#[inline]
pub(crate) fn is_operator(kind: T) -> bool {
    TOKENS.operator[kind as usize]
}

/// An operator spelt as a word: `DIV`, `MOD`, `AND`, … `B_NOT`.
#[inline]
pub(crate) fn is_word_operator(kind: T) -> bool {
    TOKENS.word[kind as usize]
}

/// Whether an operator's text is a word (`AND`), not a symbol (`<>`).
pub(crate) const fn is_word(text: &str) -> bool {
    !text.is_empty() && text.as_bytes()[0].is_ascii_alphabetic()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operator's class is one the pratt parser tries, every class
    /// has an operator, and the classes are ordered tightest first.
    #[test]
    fn precedences_are_the_classes_of_the_table() {
        for row in BINARY {
            assert!(PRECEDENCES.contains(&row.precedence), "{:?}", row.op);
        }
        for class in PRECEDENCES {
            assert!(
                BINARY.iter().any(|row| row.precedence == class),
                "{class:?}"
            );
            assert!(class.power < PREFIX_POWER, "{class:?}");
        }
        assert!(PRECEDENCES.windows(2).all(|w| w[0].power > w[1].power));
    }

    /// The driver counts operators and tells names from word operators
    /// by these sets.
    #[test]
    fn operator_token_sets() {
        let words = [
            T::Div,
            T::Mod,
            T::And,
            T::Or,
            T::Xor,
            T::Not,
            T::BAnd,
            T::BOr,
            T::BXor,
            T::BNot,
        ];
        let symbols = [
            T::Star,
            T::Slash,
            T::Plus,
            T::Minus,
            T::Concat,
            T::EqEq,
            T::Ne,
            T::Lt,
            T::Gt,
            T::Le,
            T::Ge,
            T::Colon,
        ];
        for kind in T::ALL {
            assert_eq!(is_word_operator(kind), words.contains(&kind), "{kind:?}");
            let operator = words.contains(&kind) || symbols.contains(&kind);
            assert_eq!(is_operator(kind), operator, "{kind:?}");
        }
    }

    /// The text of each operator is what the lexer reads as its token.
    #[test]
    fn texts_lex_as_their_tokens() {
        let rows = BINARY
            .iter()
            .map(|row| (row.text, row.token))
            .chain(UNARY.iter().map(|row| (row.text, row.token)));
        for (text, token) in rows {
            let tokens: Vec<_> = gcodec_lexer::Lexer::new(text.as_bytes()).collect();
            assert_eq!(tokens.len(), 1, "{text}");
            assert_eq!(tokens[0].kind, token, "{text}");
        }
    }
}
