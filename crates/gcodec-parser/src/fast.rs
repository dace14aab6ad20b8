//! A fast path for the commonest blocks: DIN words with constant values
//! (`N10 G1 Y2 F200 ; cut`), R-parameter assignments
//! (`R1=R1+0.5`), words with a value after `=` (`X=R1*2`, `CR=-20.5`),
//! `IF`/`WHILE`/`UNTIL` conditions, and structure keywords standing alone
//! (`ENDIF`).
//!
//! Most blocks of real programs have one of these shapes, and running the
//! full chumsky grammar on them costs several times more than reading them
//! directly. This module recognises exactly these shapes and builds the same
//! nodes the grammar would: expressions by precedence climbing over the
//! operator table the grammar's pratt parser reads (`grammar::operators`),
//! with numbers, R parameters, numbered axis names and parentheses as
//! operands. Anything else — names, calls, strings, brackets, lists, `L`
//! calls, labels, any value the grammar would diagnose — returns `None`
//! and the grammar parses the block. Its output is checked against
//! the grammar's by `tests/fast_path.rs`, on the corpus, the fixtures and
//! generated blocks.

use chumsky::span::SimpleSpan;
use compact_str::CompactString;
use gcodec_lang::FrameOp;
use gcodec_lang::addresses::{is_written_as_address, letter_str};
use gcodec_lexer::TokenKind as T;

use crate::ast::*;
use crate::grammar::operators::{self, Associativity};
use crate::grammar::{BlockBody, Ctx, Spanned, number_bytes_value, structure_keyword};

/// Parses `tokens` if every statement of the block has one of the shapes
/// above.
pub(crate) fn block(tokens: &[Spanned], g: &Ctx<'_>) -> Option<BlockBody> {
    let Prefix {
        skip,
        number,
        rest: i,
    } = prefix(tokens, g)?;
    // A structure keyword standing alone (`ENDIF`, `ELSE`, `LOOP`, …).
    if let [(kind, span)] = &tokens[i..] {
        // Alone on its block, `REPEAT` opens a REPEAT … UNTIL structure.
        let alone =
            structure_keyword(*kind).or((*kind == T::Repeat).then_some(StatementKind::Repeat));
        let Some(kind) = alone else {
            return statements_from(tokens, i, g, skip, number);
        };
        return Some(BlockBody {
            skip,
            number,
            label: None,
            statements: vec![Statement {
                span: g.span(*span),
                kind,
            }],
        });
    }
    statements_from(tokens, i, g, skip, number)
}

/// The skip mark and block number a block opens with.
pub(crate) struct Prefix {
    pub skip: Option<SkipLevel>,
    pub number: Option<BlockNumber>,
    /// The index of the first token after them.
    pub rest: usize,
}

/// The skip mark (`/`, `/0` … `/9`) and block number (`N10`) `tokens`
/// open with, as the grammar reads them; `None` where the grammar must
/// judge them: a skip level or block number that is not a plain whole
/// number, a number after a blank after `/` (`/ 5`, an error), or a block
/// number followed by `=`.
pub(crate) fn prefix(tokens: &[Spanned], g: &Ctx<'_>) -> Option<Prefix> {
    let mut i = 0;
    let mut skip = None;
    if let Some((T::Slash, slash)) = tokens.first() {
        match tokens.get(1) {
            Some((T::Number, n)) if n.start == slash.end => {
                let level = g.text(*n).parse::<u8>().ok().filter(|l| *l <= 9)?;
                skip = Some(SkipLevel {
                    span: g.span(SimpleSpan::from(slash.start..n.end)),
                    level,
                });
                i = 2;
            }
            // A number after a blank is an error the grammar reports.
            Some((T::Number, _)) => return None,
            _ => {
                skip = Some(SkipLevel {
                    span: g.span(*slash),
                    level: 0,
                });
                i = 1;
            }
        }
    }
    let mut number = None;
    if let (Some((T::Letter, l)), Some((T::Number, n))) = (tokens.get(i), tokens.get(i + 1))
        && g.bytes(*l)[0].eq_ignore_ascii_case(&b'N')
        && n.start == l.end
    {
        if matches!(tokens.get(i + 2), Some((T::Eq, _))) {
            return None;
        }
        let value = whole_number(g.bytes(*n))?;
        number = Some(BlockNumber {
            span: g.span(SimpleSpan::from(l.start..n.end)),
            main: false,
            value,
        });
        i += 2;
    }
    Some(Prefix {
        skip,
        number,
        rest: i,
    })
}

/// The statements from token `i` on.
fn statements_from(
    tokens: &[Spanned],
    i: usize,
    g: &Ctx<'_>,
    skip: Option<SkipLevel>,
    number: Option<BlockNumber>,
) -> Option<BlockBody> {
    // Every statement starts with one of these; in blocks of constant
    // words, the count is exact.
    let starts = tokens[i..]
        .iter()
        .filter(|(k, _)| matches!(k, T::Letter | T::Ident | T::If | T::While | T::Until))
        .count();
    let mut statements = Vec::with_capacity(starts);
    let mut c = Cursor { tokens, i, g };
    while c.i < tokens.len() {
        statements.push(statement(&mut c)?);
    }
    Some(BlockBody {
        skip,
        number,
        label: None,
        statements,
    })
}

/// A position in a block's tokens.
struct Cursor<'a, 's> {
    tokens: &'a [Spanned],
    i: usize,
    g: &'a Ctx<'s>,
}

impl Cursor<'_, '_> {
    fn kind(&self) -> Option<T> {
        self.tokens.get(self.i).map(|t| t.0)
    }

    fn kind_at(&self, ahead: usize) -> Option<T> {
        self.tokens.get(self.i + ahead).map(|t| t.0)
    }

    /// The span of the token `ahead` of the cursor.
    fn span_at(&self, ahead: usize) -> Option<SimpleSpan> {
        self.tokens.get(self.i + ahead).map(|t| t.1)
    }

    /// The end of the last token taken.
    fn end(&self) -> usize {
        self.tokens[self.i - 1].1.end
    }

    fn span_from(&self, start: usize) -> gcodec_source::Span {
        self.g.span(SimpleSpan::from(start..self.end()))
    }
}

fn statement(c: &mut Cursor<'_, '_>) -> Option<Statement> {
    let start = c.span_at(0)?;
    let kind = match c.kind()? {
        T::Letter => return letter_statement(c),
        T::Ident => return named_word(c),
        T::If => {
            c.i += 1;
            let condition = expr(c, 0)?;
            // `IF cond GOTOF label` is a jump, for the grammar.
            if matches!(
                c.kind(),
                Some(T::Goto | T::GotoF | T::GotoB | T::GotoC | T::GotoS)
            ) {
                return None;
            }
            StatementKind::If(Box::new(Condition { condition }))
        }
        T::While => {
            c.i += 1;
            StatementKind::While(Box::new(Condition {
                condition: expr(c, 0)?,
            }))
        }
        T::Until => {
            c.i += 1;
            StatementKind::Until(Box::new(Condition {
                condition: expr(c, 0)?,
            }))
        }
        _ => return None,
    };
    Some(Statement {
        span: c.span_from(start.start),
        kind,
    })
}

/// `X10`, `X-1.5`, `X=R1*2`, `R1=R2+1`.
fn letter_statement(c: &mut Cursor<'_, '_>) -> Option<Statement> {
    let g = c.g;
    let letter = c.span_at(0)?;
    let address = g.bytes(letter)[0].to_ascii_uppercase();
    if matches!(address, b'L' | b'N') {
        return None;
    }
    match (c.kind_at(1), c.span_at(1)) {
        // `R1=…`
        (Some(T::Number), Some(n)) if address == b'R' => {
            if n.start != letter.end || c.kind_at(2) != Some(T::Eq) {
                return None;
            }
            let index = u32::try_from(whole_number(g.bytes(n))?).ok()?;
            c.i += 3;
            let value = value(c)?;
            let target = VarRef {
                span: g.span(SimpleSpan::from(letter.start..n.end)),
                kind: VarKind::RParameter,
                name: CompactString::const_new("R"),
                indices: vec![Expr {
                    span: g.span(n),
                    kind: ExprKind::Number {
                        value: f64::from(index),
                        integer: true,
                    },
                }],
            };
            Some(Statement {
                span: c.span_from(letter.start),
                kind: StatementKind::Assign(Box::new(Assign {
                    target,
                    value: Initializer::Expr(value),
                })),
            })
        }
        (Some(T::Eq), _) if address != b'R' => assigned_word(c, letter_str(address), letter),
        _ if address != b'R' => constant_word(c, letter, address),
        _ => None,
    }
}

/// `X10`, `X-1.5`: a letter with a constant touching it.
fn constant_word(c: &mut Cursor<'_, '_>, letter: SimpleSpan, address: u8) -> Option<Statement> {
    let g = c.g;
    let mut j = c.i + 1;
    let mut sign = None;
    if let Some(&(kind @ (T::Plus | T::Minus), s)) = c.tokens.get(j) {
        if s.start != letter.end {
            return None;
        }
        sign = Some((kind == T::Minus, s));
        j += 1;
    }
    let &(T::Number, n) = c.tokens.get(j)? else {
        return None;
    };
    let expected_start = sign.map_or(letter.end, |(_, s)| s.end);
    if n.start != expected_start {
        return None;
    }
    j += 1;
    // `X1=`, `M5[`, `X1(`, `T1"…"` mean something else.
    if matches!(
        c.tokens.get(j),
        Some((T::Eq | T::LBracket | T::LParen | T::String, _))
    ) {
        return None;
    }
    c.i = j;
    let text = g.bytes(n);
    let mut value = number_bytes_value(text)?;
    if sign.is_some_and(|(negative, _)| negative) {
        value = -value;
    }
    let value_start = sign.map_or(n.start, |(_, s)| s.start);
    let span = g.span(SimpleSpan::from(letter.start..n.end));
    Some(Statement {
        span,
        kind: StatementKind::Word(Word::new(
            span,
            letter_str(address),
            g.span(letter),
            None,
            WordValue::Constant(NumberLit {
                span: g.span(SimpleSpan::from(value_start..n.end)),
                value,
                integer: text.iter().all(u8::is_ascii_digit),
            }),
        )),
    })
}

/// `CR=-20.5`, `TURN=R2`: a multi-letter address with a value after `=`.
fn named_word(c: &mut Cursor<'_, '_>) -> Option<Statement> {
    let name = c.span_at(0)?;
    let text = c.g.text(name);
    if c.kind_at(1) != Some(T::Eq)
        || !is_written_as_address(text)
        || FrameOp::from_name(text).is_some()
    {
        return None;
    }
    assigned_word(c, &text.to_ascii_uppercase(), name)
}

/// The word whose address (`address`, written at `written`) is under the
/// cursor, followed by `=` and a value.
fn assigned_word(c: &mut Cursor<'_, '_>, address: &str, written: SimpleSpan) -> Option<Statement> {
    c.i += 2;
    let value = value(c)?;
    let span = c.span_from(written.start);
    Some(Statement {
        span,
        kind: StatementKind::Word(Word::new(
            span,
            address,
            c.g.span(written),
            None,
            WordValue::Assigned {
                modifier: None,
                expr: Box::new(value),
            },
        )),
    })
}

/// The value after `=`: one expression (a `,` after it makes a list, which
/// the grammar reads).
fn value(c: &mut Cursor<'_, '_>) -> Option<Expr> {
    let value = expr(c, 0)?;
    (c.kind() != Some(T::Comma)).then_some(value)
}

/// The value of a block number or R-parameter number: digits only, as
/// `str::parse::<u64>` reads them, `None` if it does not fit.
pub(crate) fn whole_number(digits: &[u8]) -> Option<u64> {
    if digits.is_empty() {
        return None;
    }
    digits.iter().try_fold(0u64, |n, &b| {
        let digit = char::from(b).to_digit(10)?;
        n.checked_mul(10)?.checked_add(u64::from(digit))
    })
}

/// An expression whose operators all bind tighter than `min`. Recursion is
/// bounded: the driver rejects blocks with more than
/// [`crate::MAX_OPERATORS_PER_BLOCK`] operators or brackets nested deeper
/// than [`crate::MAX_EXPRESSION_DEPTH`] before any parser runs.
fn expr(c: &mut Cursor<'_, '_>, min: u8) -> Option<Expr> {
    let start = c.span_at(0)?.start;
    let mut lhs = match operators::unary_token(c.kind()?) {
        Some(op) => {
            c.i += 1;
            let operand = expr(c, operators::PREFIX_POWER)?;
            Expr {
                span: c.span_from(start),
                kind: ExprKind::Unary {
                    op,
                    operand: Box::new(operand),
                },
            }
        }
        None => operand(c)?,
    };
    while let Some((op, precedence)) = c.kind().and_then(operators::binary_token) {
        let power = precedence.power;
        if power <= min {
            break;
        }
        c.i += 1;
        // The right operand takes only tighter operators, so a chain of
        // one class groups to the left.
        let rhs_min = match precedence.associativity {
            Associativity::Left => power,
        };
        let rhs = expr(c, rhs_min)?;
        lhs = Expr {
            span: c.span_from(start),
            kind: ExprKind::Binary(Box::new(BinaryExpr { op, lhs, rhs })),
        };
    }
    Some(lhs)
}

/// A number, `R1`, `X1` or a parenthesised expression.
fn operand(c: &mut Cursor<'_, '_>) -> Option<Expr> {
    let g = c.g;
    let (kind, s) = *c.tokens.get(c.i)?;
    match kind {
        T::Number => {
            let text = g.bytes(s);
            let value = number_bytes_value(text)?;
            c.i += 1;
            Some(Expr {
                span: g.span(s),
                kind: ExprKind::Number {
                    value,
                    integer: text.iter().all(u8::is_ascii_digit),
                },
            })
        }
        T::LParen => {
            c.i += 1;
            let mut inner = expr(c, 0)?;
            if c.kind()? != T::RParen {
                return None;
            }
            c.i += 1;
            // The span of a parenthesised expression includes the parentheses.
            inner.span = c.span_from(s.start);
            Some(inner)
        }
        T::Letter => {
            let digits = c.span_at(1).filter(|d| d.start == s.end)?;
            if c.kind_at(1) != Some(T::Number)
                || c.kind_at(2) == Some(T::LBracket)
                || !g.bytes(digits).iter().all(u8::is_ascii_digit)
            {
                return None;
            }
            let var = if g.bytes(s)[0].eq_ignore_ascii_case(&b'R') {
                VarRef {
                    span: g.span(SimpleSpan::from(s.start..digits.end)),
                    kind: VarKind::RParameter,
                    name: CompactString::const_new("R"),
                    indices: vec![Expr {
                        span: g.span(digits),
                        kind: ExprKind::Number {
                            value: number_bytes_value(g.bytes(digits))?,
                            integer: true,
                        },
                    }],
                }
            } else {
                VarRef {
                    span: g.span(SimpleSpan::from(s.start..digits.end)),
                    kind: VarKind::Name,
                    name: CompactString::from(g.text(SimpleSpan::from(s.start..digits.end))),
                    indices: Vec::new(),
                }
            };
            c.i += 2;
            Some(Expr {
                span: var.span,
                kind: ExprKind::Var { var: Box::new(var) },
            })
        }
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use chumsky::span::SimpleSpan;
    use gcodec_lexer::{Lexer, TokenKind};

    use super::block;
    use crate::grammar::Ctx;

    /// Whether the fast path takes the one-line block `src`.
    fn taken(src: &str) -> bool {
        let tokens: Vec<_> = Lexer::new(src.as_bytes())
            .filter(|t| !matches!(t.kind, TokenKind::Whitespace | TokenKind::Comment))
            .map(|t| (t.kind, SimpleSpan::from(t.start as usize..t.end as usize)))
            .collect();
        block(
            &tokens,
            &Ctx::new(src.as_bytes(), gcodec_source::Encoding::UTF_8),
        )
        .is_some()
    }

    /// The shapes the fast path exists for must not fall through to the
    /// grammar (the comparison tests would still pass, only slower).
    #[test]
    fn common_blocks_take_the_fast_path() {
        for src in [
            "N10 G1 X-1.5 Y2 Z.5 F200",
            "/2 N20 G0 X0 Y0",
            "G2 X10 Y5 CR=-20.5",
            "R1=R1+0.5",
            "N30 R4=(R5+R6)/2",
            "R2=R3*2-1.25 G1 X=R2",
            "IF (R13<=R14) AND (R15<>0)",
            "WHILE R1<5",
            "UNTIL R1>=10",
            "TURN=2*R1",
            "ENDIF",
            "N40 ELSE",
        ] {
            assert!(taken(src), "`{src}` should take the fast path");
        }
    }

    #[test]
    fn other_blocks_are_left_to_the_grammar() {
        for src in [
            "LBL: G1 X1",
            "L10 P3",
            "R1=SIN(30)",
            "R[1]=5",
            "X=IC(5)",
            "M2=3",
            "IF R1==1 GOTOF LBL",
            "R1=(1,2)",
            "T=\"DRILL\"",
            "COUNTER=5",
            "TRANS X10",
            "R1=1EX999",
        ] {
            assert!(!taken(src), "`{src}` should be left to the grammar");
        }
    }
}
