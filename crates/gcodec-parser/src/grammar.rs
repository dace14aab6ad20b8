//! The chumsky grammar of one block's statements.
//!
//! The driver hands over the significant tokens of one line (blanks and the
//! comment removed); adjacency, which matters in SINUMERIK (`X1=` versus
//! `X1 A=`, `M5` versus `M 5`), is read from the byte spans.

use chumsky::input::MappedInput;
use chumsky::pratt::{infix, left, prefix};
use chumsky::prelude::*;
use compact_str::CompactString;
use gcodec_lang::addresses::letter_str;
use gcodec_lang::{BinaryOp, DimensionMode, UnaryOp};
use gcodec_lexer::TokenKind as T;
use gcodec_source::Span;

use crate::ast::*;
use crate::error::SyntaxError;

pub(crate) type Spanned = (T, SimpleSpan);
pub(crate) type In<'t> = MappedInput<'t, T, SimpleSpan, &'t [Spanned]>;
pub(crate) type Ex = extra::Err<SyntaxError>;

/// Everything a block holds besides its comment.
#[derive(Debug)]
pub(crate) struct BlockBody {
    pub skip: Option<SkipLevel>,
    pub number: Option<BlockNumber>,
    pub label: Option<LabelDef>,
    pub statements: Vec<Statement>,
}

/// Source access for the grammar's closures: the file bytes and the line
/// the current block sits on.
#[derive(Clone, Copy)]
pub(crate) struct Ctx<'s> {
    pub src: &'s [u8],
}

impl<'s> Ctx<'s> {
    pub fn span(&self, s: SimpleSpan) -> Span {
        Span::new(s.start as u32, s.end as u32)
    }

    pub fn bytes(&self, s: SimpleSpan) -> &'s [u8] {
        &self.src[s.start..s.end]
    }

    /// Token text; tokens other than strings and comments are ASCII.
    pub fn text(&self, s: SimpleSpan) -> &'s str {
        std::str::from_utf8(self.bytes(s)).unwrap_or("")
    }

    fn name(&self, s: SimpleSpan) -> CompactString {
        CompactString::from(self.text(s))
    }
}

const ERR_VALUE: &str = "gcodec::parse::invalid_value";
const ERR_WORD: &str = "gcodec::parse::invalid_word";
const ERR_NUMBER: &str = "gcodec::parse::invalid_number";

/// Single-letter addresses that take a numeric extension (`X1=`, `M2=`, `S1=`).
fn letter_takes_extension(c: u8) -> bool {
    matches!(
        c.to_ascii_uppercase(),
        b'A' | b'B'
            | b'C'
            | b'E'
            | b'H'
            | b'I'
            | b'J'
            | b'K'
            | b'M'
            | b'Q'
            | b'S'
            | b'T'
            | b'U'
            | b'V'
            | b'W'
            | b'X'
            | b'Y'
            | b'Z'
    )
}

/// Single-letter addresses that take a bracketed extension (`M[R1]=`,
/// `G[8]=`, `S[1]=`, `X[1]=`). `T[…]` and `F[…]` are rejected as the
/// control's syntax check does.
fn letter_takes_index(c: u8) -> bool {
    !matches!(
        c.to_ascii_uppercase(),
        b'T' | b'F' | b'N' | b'L' | b'P' | b'D'
    )
}

/// Multi-letter addresses written `NAME=value`; other names with `=` are
/// variable assignments (later stages may still resolve them as axes).
pub(crate) fn is_named_address(name: &str) -> bool {
    const NAMES: &[&str] = &[
        "ACC", "ADIS", "ADISPOS", "ANG", "AP", "AR", "AX", "CHF", "CHR", "CR", "DISC", "DITE",
        "DITS", "DL", "FA", "FB", "FL", "FP", "FZ", "LIMS", "OFFN", "OVR", "OVRA", "PL", "PO",
        "POS", "POSA", "PW", "RND", "RNDM", "RP", "RPL", "SD", "SF", "SPOS", "SPOSA", "TURN",
    ];
    NAMES.iter().any(|n| n.eq_ignore_ascii_case(name))
}

/// Keywords that are a whole statement by themselves. `REPEAT` is not
/// among them: it may be followed by the labels of a section.
pub(crate) fn structure_keyword(t: T) -> Option<StatementKind> {
    Some(match t {
        T::Else => StatementKind::Else,
        T::EndIf => StatementKind::EndIf,
        T::EndWhile => StatementKind::EndWhile,
        T::EndFor => StatementKind::EndFor,
        T::Loop => StatementKind::Loop,
        T::EndLoop => StatementKind::EndLoop,
        T::EndProc => StatementKind::EndProc,
        _ => return None,
    })
}

/// The value of a number token, `None` if it is out of range.
pub(crate) fn number_value(text: &str) -> Option<f64> {
    number_bytes_value(text.as_bytes())
}

/// [`number_value`] of a token's bytes, for callers that have not made a
/// `str` of them.
pub(crate) fn number_bytes_value(bytes: &[u8]) -> Option<f64> {
    if let Some(value) = short_decimal(bytes) {
        return value;
    }
    let text = std::str::from_utf8(bytes).ok()?;
    // `1.5EX-3`: the exponent marker is `EX` in any case. Rust's parser
    // reads `1.5e-3`, which rounds correctly where `1.5 * 10^-3` would not.
    let value: f64 = match text.bytes().position(|b| b == b'E' || b == b'e') {
        Some(pos) => {
            let exponent = text.get(pos + 2..)?;
            format!("{}e{}", &text[..pos], exponent).parse().ok()?
        }
        None => text.parse().ok()?,
    };
    value.is_finite().then_some(value)
}

/// Powers of ten that are exact in an `f64`.
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// `Some(value)` for the commonest numbers, `1600`, `12.345`,
/// `.5`, `5.`: at most 15 digits, at most 22 after the point, no exponent.
/// Such a number is an integer below 2^53 divided by an exact power of
/// ten, and IEEE division rounds correctly, so the result is the correctly
/// rounded value that `str::parse` gives (Clinger's fast path).
/// `None` when the text has another form.
fn short_decimal(text: &[u8]) -> Option<Option<f64>> {
    let mut mantissa: u64 = 0;
    let mut digits = 0;
    let mut point = None;
    for (i, &b) in text.iter().enumerate() {
        match b {
            b'0'..=b'9' => {
                mantissa = mantissa * 10 + u64::from(b - b'0');
                digits += 1;
                if digits > 15 {
                    return None;
                }
            }
            b'.' if point.is_none() => point = Some(i),
            _ => return None,
        }
    }
    if digits == 0 {
        return Some(None);
    }
    let fraction = point.map_or(0, |p| text.len() - p - 1);
    let power = EXACT_POWERS_OF_TEN.get(fraction)?;
    Some(Some(mantissa as f64 / power))
}

fn args<'t, 's: 't>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Option<Expr>>, Ex> + Clone + 't {
    expr.or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .map(|v| {
            if v.len() == 1 && v[0].is_none() {
                Vec::new()
            } else {
                v
            }
        })
        .delimited_by(just(T::LParen), just(T::RParen))
}

/// The expression grammar with Siemens precedence.
pub(crate) fn expr<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't {
    recursive(move |expr| {
        let mk = move |kind, s: SimpleSpan| Expr {
            span: g.span(s),
            kind,
        };
        // An out-of-range number is diagnosed but parsing goes on, so the
        // message names the number rather than the statement around it.
        let number = select! { T::Number => () }.validate(move |_, e, emitter| {
            let s: SimpleSpan = e.span();
            let text = g.text(s);
            let value = number_value(text).unwrap_or_else(|| {
                emitter.emit(SyntaxError::custom(
                    s,
                    ERR_NUMBER,
                    format!("number `{text}` is out of range"),
                    Some("REAL values range over about ±1.8·10^308"),
                ));
                0.0
            });
            mk(
                ExprKind::Number {
                    value,
                    integer: text.bytes().all(|b| b.is_ascii_digit()),
                },
                s,
            )
        });
        let radix = select! { T::HexNumber => 16, T::BinNumber => 2 }.try_map(
            move |radix, s: SimpleSpan| {
                let text = g.text(s);
                u64::from_str_radix(&text[2..text.len() - 1], radix)
                    .map(|v| {
                        mk(
                            ExprKind::Number {
                                value: v as f64,
                                integer: true,
                            },
                            s,
                        )
                    })
                    .map_err(|_| {
                        SyntaxError::custom(
                            s,
                            ERR_NUMBER,
                            format!("constant `{text}` is too large"),
                            None,
                        )
                    })
            },
        );
        let string = select! { T::String => () }.map_with(move |_, e| {
            let s: SimpleSpan = e.span();
            let bytes = g.bytes(s);
            let value = decode_text(&bytes[1..bytes.len() - 1]);
            mk(
                ExprKind::String {
                    value: Box::new(value),
                },
                s,
            )
        });
        let boolean = select! { T::True => true, T::False => false }
            .map_with(move |value, e| mk(ExprKind::Bool { value }, e.span()));
        let var = var_ref(g, expr.clone()).map(|var| Expr {
            span: var.span,
            kind: ExprKind::Var { var: Box::new(var) },
        });
        let call = select! { T::Ident => () }
            .map_with(|_, e| e.span())
            .then(args(expr.clone()))
            .map_with(move |(name_span, args), e| {
                mk(
                    ExprKind::Call(Box::new(CallExpr {
                        name: g.name(name_span),
                        name_span: g.span(name_span),
                        args,
                    })),
                    e.span(),
                )
            });
        let paren = expr
            .clone()
            .delimited_by(just(T::LParen), just(T::RParen))
            .map_with(move |mut inner: Expr, e| {
                // The span of a parenthesised expression includes the parentheses.
                inner.span = g.span(e.span());
                inner
            });
        let atom =
            choice((number, radix, string, boolean, call, var, paren)).labelled("expression");

        // One operator parser per precedence level: after every operand the
        // pratt loop tries each level once, so fewer levels means fewer
        // failed attempts on the hot path.
        let bin =
            move |l: Expr,
                  op: BinaryOp,
                  r: Expr,
                  e: &mut chumsky::input::MapExtra<'t, '_, In<'t>, Ex>| Expr {
                span: g.span(e.span()),
                kind: ExprKind::Binary(Box::new(BinaryExpr { op, lhs: l, rhs: r })),
            };
        let un =
            move |op: UnaryOp, r: Expr, e: &mut chumsky::input::MapExtra<'t, '_, In<'t>, Ex>| {
                Expr {
                    span: g.span(e.span()),
                    kind: ExprKind::Unary {
                        op,
                        operand: Box::new(r),
                    },
                }
            };
        atom.pratt((
            prefix(
                12,
                select! {
                    T::Minus => UnaryOp::Neg,
                    T::Plus => UnaryOp::Plus,
                    T::Not => UnaryOp::Not,
                    T::BNot => UnaryOp::BNot,
                    T::Concat => UnaryOp::ToString,
                },
                un,
            ),
            infix(
                left(11),
                select! {
                    T::Star => BinaryOp::Mul,
                    T::Slash => BinaryOp::Div,
                    T::Div => BinaryOp::IntDiv,
                    T::Mod => BinaryOp::Mod,
                },
                bin,
            ),
            infix(
                left(10),
                select! { T::Plus => BinaryOp::Add, T::Minus => BinaryOp::Sub },
                bin,
            ),
            infix(left(9), select! { T::BAnd => BinaryOp::BAnd }, bin),
            infix(left(8), select! { T::BXor => BinaryOp::BXor }, bin),
            infix(left(7), select! { T::BOr => BinaryOp::BOr }, bin),
            infix(left(6), select! { T::And => BinaryOp::And }, bin),
            infix(left(5), select! { T::Xor => BinaryOp::Xor }, bin),
            infix(left(4), select! { T::Or => BinaryOp::Or }, bin),
            infix(left(3), select! { T::Concat => BinaryOp::Concat }, bin),
            infix(
                left(2),
                select! {
                    T::EqEq => BinaryOp::Eq,
                    T::Ne => BinaryOp::Ne,
                    T::Lt => BinaryOp::Lt,
                    T::Gt => BinaryOp::Gt,
                    T::Le => BinaryOp::Le,
                    T::Ge => BinaryOp::Ge,
                },
                bin,
            ),
            infix(left(1), select! { T::Colon => BinaryOp::Chain }, bin),
        ))
    })
}

/// Program text decoded for display (see [`gcodec_source::decode`]); short
/// UTF-8 text is stored inline, without a temporary `String`.
pub(crate) fn decode_text(bytes: &[u8]) -> CompactString {
    match std::str::from_utf8(bytes) {
        Ok(text) => CompactString::from(text),
        Err(_) => CompactString::from(gcodec_source::decode(bytes)),
    }
}

/// `[a, b, c]` index list.
fn indices<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Expr>, Ex> + Clone + 't {
    expr.separated_by(just(T::Comma))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(just(T::LBracket), just(T::RBracket))
}

/// A variable reference: `R1`, `R[i]`, `NAME`, `NAME[i,j]`, `$SYS[…]`, and
/// axis names inside expressions (`X`, `X1`).
pub(crate) fn var_ref<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, VarRef, Ex> + Clone + 't {
    let r_or_axis = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()).or_not())
        .then(indices(expr.clone()).or_not())
        .try_map(move |((letter, digits), idx), span| {
            let l = g.bytes(letter)[0].to_ascii_uppercase();
            let digits = digits.filter(|d| d.start == letter.end);
            match (l, digits, idx) {
                (b'R', Some(d), None) => {
                    let text = g.text(d);
                    if !text.bytes().all(|b| b.is_ascii_digit()) {
                        return Err(SyntaxError::custom(
                            d,
                            ERR_WORD,
                            format!("R parameter number `{text}` is not an integer"),
                            None,
                        ));
                    }
                    Ok(VarRef {
                        span: g.span(span),
                        kind: VarKind::RParameter,
                        name: "R".into(),
                        indices: vec![Expr {
                            span: g.span(d),
                            kind: ExprKind::Number {
                                value: number_value(text).unwrap_or(0.0),
                                integer: true,
                            },
                        }],
                    })
                }
                (b'R', None, Some(idx)) => Ok(VarRef {
                    span: g.span(span),
                    kind: VarKind::RParameter,
                    name: "R".into(),
                    indices: idx,
                }),
                (_, Some(_), Some(_)) => Err(SyntaxError::custom(
                    span,
                    ERR_WORD,
                    format!(
                        "`{}` cannot be indexed: a numbered address takes no `[…]`",
                        g.text(SimpleSpan::from(letter.start..letter.end + 1))
                    ),
                    None,
                )),
                (_, Some(d), None) => {
                    // An axis name with a number (`X1`) inside an expression.
                    let text = g.text(d);
                    if !text.bytes().all(|b| b.is_ascii_digit()) {
                        return Err(SyntaxError::custom(span, ERR_WORD, "a number cannot follow an address letter inside an expression", Some("write `=` values as expressions: `X=R1+5`; numbered axes need an integer, e.g. `X1`")));
                    }
                    Ok(VarRef {
                        span: g.span(span),
                        kind: VarKind::Name,
                        name: g.name(SimpleSpan::from(letter.start..d.end)),
                        indices: Vec::new(),
                    })
                }
                (_, None, idx) => Ok(VarRef {
                    span: g.span(span),
                    kind: VarKind::Name,
                    name: g.name(letter),
                    indices: idx.unwrap_or_default(),
                }),
            }
        });
    let named = select! { T::Ident => VarKind::Name, T::SystemVar => VarKind::System }
        .map_with(|k, e| (k, e.span()))
        .then(indices(expr).or_not())
        .map_with(move |((kind, name), idx), e| VarRef {
            span: g.span(e.span()),
            kind,
            name: g.name(name),
            indices: idx.unwrap_or_default(),
        });
    choice((r_or_axis, named))
}

/// The right side of `=`: an expression, `(a, b)`, `SET(…)` or `REP(…)`.
fn initializer<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Initializer, Ex> + Clone + 't {
    let list_items = expr
        .clone()
        .or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .delimited_by(just(T::LParen), just(T::RParen));
    let set = just(T::Set)
        .ignore_then(list_items.clone())
        .map_with(move |items, e| Initializer::List {
            span: g.span(e.span()),
            set: true,
            items,
        });
    let rep = just(T::Rep)
        .ignore_then(
            expr.clone()
                .separated_by(just(T::Comma))
                .at_least(1)
                .collect::<Vec<_>>()
                .delimited_by(just(T::LParen), just(T::RParen)),
        )
        .map_with(move |args, e| Initializer::Rep {
            span: g.span(e.span()),
            args,
        });
    // `(a, b, …)` with at least one comma is a list; `(a)` is an expression.
    let paren_list = list_items
        .filter(|items: &Vec<Option<Expr>>| items.len() > 1)
        .map_with(move |items, e| Initializer::List {
            span: g.span(e.span()),
            set: false,
            items,
        });
    choice((set, rep, paren_list, expr.map(Initializer::Expr)))
}

/// Wraps a word's `=` value, lifting a dimension modifier (`IC(5)`) out.
fn assigned_value(expr: Expr) -> WordValue {
    let Expr { span, kind } = expr;
    let kind = match kind {
        ExprKind::Call(mut call) if call.args.len() == 1 => {
            match (
                DimensionMode::from_name(&call.name),
                call.args.pop().flatten(),
            ) {
                (Some(kind), Some(inner)) => {
                    return WordValue::Assigned {
                        modifier: Some(DimensionModifier {
                            span: call.name_span.cover(span),
                            kind,
                        }),
                        expr: Box::new(inner),
                    };
                }
                (_, inner) => {
                    call.args.push(inner);
                    ExprKind::Call(call)
                }
            }
        }
        kind => kind,
    };
    WordValue::Assigned {
        modifier: None,
        expr: Box::new(Expr { span, kind }),
    }
}

/// What the word grammar produced before classification.
enum LetterStatement {
    Word(Word),
    Assign(Assign),
    Call(Call),
    /// Malformed; a non-fatal error was emitted and the driver reports the
    /// block.
    Invalid,
}

/// Statements that start with a single address letter: DIN words,
/// R-parameter assignments and `L` calls.
fn letter_statement<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, LetterStatement, Ex> + Clone + 't {
    let letter = select! { T::Letter => () }.map_with(|_, e| e.span());
    let sign = select! { T::Plus => false, T::Minus => true }
        .map_with(|neg, e| -> (bool, SimpleSpan) { (neg, e.span()) });
    let number = select! { T::Number => () }.map_with(|_, e| e.span());
    let bracket = expr
        .clone()
        .delimited_by(just(T::LBracket), just(T::RBracket))
        .map_with(|x, e| -> (Expr, SimpleSpan) { (x, e.span()) });
    let string_after = select! { T::String => () }.map_with(|_, e| e.span());
    let args_p = args(expr.clone());
    letter
        .then(sign.or_not())
        .then(number.or_not())
        .then(bracket.or_not())
        .then(
            just(T::Eq)
                .map_with(|_, e| -> SimpleSpan { e.span() })
                .then(initializer(g, expr).or_not())
                .or_not(),
        )
        .then(string_after.or_not())
        .then(args_p.or_not())
        .map_with(move |((((((letter, sign), num), bracket), value), string), call_args), e| {
            let span: SimpleSpan = e.span();
            let classify = || -> Result<LetterStatement, SyntaxError> {
            // `X=` must be followed by a complete value.
            let value = match value {
                Some((eq, None)) => {
                    return Err(SyntaxError::custom(
                        SimpleSpan::from(eq.start..span.end.max(eq.end)),
                        ERR_VALUE,
                        format!(
                            "`{}=` is not followed by a complete value",
                            g.text(SimpleSpan::from(letter.start..eq.start)).trim_end()
                        ),
                        Some("write an expression after `=`, e.g. `X=R1+5`; check brackets and operators"),
                    ));
                }
                Some((_, Some(v))) => Some(v),
                None => None,
            };
            let l = g.bytes(letter)[0].to_ascii_uppercase();
            let addr = letter_str(l);
            let err = |s: SimpleSpan, msg: String, help: &'static str| {
                Err(SyntaxError::custom(s, ERR_WORD, msg, Some(help)))
            };
            if let Some(s) = string {
                return err(
                    s,
                    format!("a string after `{addr}` needs `=`"),
                    "write the value as `T=\"NAME\"`",
                );
            }
            // The sign and digits must touch the letter and each other.
            let mut next_start = letter.end;
            if let Some((_, s)) = sign {
                if s.start != next_start {
                    return err(
                        span,
                        format!("blank between address `{addr}` and its value"),
                        "write the value directly after the address, e.g. `X-10`, or use `=`",
                    );
                }
                next_start = s.end;
            }
            if let Some(n) = num {
                if n.start != next_start {
                    return err(
                        span,
                        format!("blank between address `{addr}` and its value"),
                        "write the value directly after the address (`M5`), or use `=` (`M=5`)",
                    );
                }
            } else if sign.is_some() {
                return err(span, format!("sign without a number after `{addr}`"), "write e.g. `X-10`");
            }
            let a_span = g.span(letter);
            let value_expr = |v: Initializer| -> Result<Expr, SyntaxError> {
                match v {
                    Initializer::Expr(e) => Ok(e),
                    _ => Err(SyntaxError::custom(
                        span,
                        ERR_VALUE,
                        format!("address `{addr}` takes one value, not a list"),
                        None,
                    )),
                }
            };
            let int_digits = |n: SimpleSpan| -> Result<u32, SyntaxError> {
                g.text(n).parse::<u32>().map_err(|_| {
                    SyntaxError::custom(
                        n,
                        ERR_WORD,
                        format!("`{}` is not a valid address extension", g.text(n)),
                        Some("an address extension is a whole number, e.g. `M2=3`, `X1=10`"),
                    )
                })
            };
            // R parameters: `R1=…`, `R[i]=…`.
            if l == b'R' && sign.is_none() {
                let bracket_end = bracket.as_ref().map(|(_, b)| b.end);
                let index = match (num, bracket) {
                    (Some(n), None) => {
                        let v = int_digits(n)?;
                        Expr {
                            span: g.span(n),
                            kind: ExprKind::Number { value: v as f64, integer: true },
                        }
                    }
                    (None, Some((idx, _))) => idx,
                    (Some(_), Some((_, b))) => {
                        return err(b, "an R parameter with a number takes no index".into(), "write `R10=4` or `R[10]=4`");
                    }
                    (None, None) => {
                        return err(span, "`R` needs a parameter number".into(), "write e.g. `R1=5` or `R[R2]=5`");
                    }
                };
                let Some(value) = value else {
                    return err(span, "R parameter without assignment".into(), "assign a value, e.g. `R1=5`");
                };
                if call_args.is_some() {
                    return err(span, "unexpected `(` after an R-parameter assignment".into(), "separate statements with a blank");
                }
                let target_end = bracket_end.or(num.map(|n| n.end)).unwrap_or(letter.end);
                return Ok(LetterStatement::Assign(Assign {
                    target: VarRef {
                        span: g.span(SimpleSpan::from(letter.start..target_end)),
                        kind: VarKind::RParameter,
                        name: "R".into(),
                        indices: vec![index],
                    },
                    value,
                }));
            }
            // `L123`, `L123(args)`: subprogram call by number.
            if l == b'L'
                && sign.is_none()
                && bracket.is_none()
                && value.is_none()
                && let Some(n) = num
            {
                let digits = g.text(n);
                if !digits.bytes().all(|b| b.is_ascii_digit()) {
                    return err(n, format!("`L{digits}` is not a program number"), "program numbers are whole numbers, e.g. `L123`");
                }
                return Ok(LetterStatement::Call(Call {
                    target: CallTarget::Number {
                        span: g.span(SimpleSpan::from(letter.start..n.end)),
                        digits: digits.into(),
                    },
                    args: call_args,
                    passes: None,
                }));
            }
            if call_args.is_some() {
                return err(span, format!("unexpected `(` after address `{addr}`"), "`(` groups expressions after `=`, e.g. `X=(R1+2)*3`");
            }
            let word = match (sign, num, bracket, value) {
                // X10, X-10, X.5
                (_, Some(n), None, None) => {
                    let text = g.text(n);
                    let Some(mut v) = number_value(text) else {
                        return err(n, format!("number `{text}` is out of range"), "REAL values range over about ±1.8·10^308");
                    };
                    let start = sign.map(|(_, s)| s).unwrap_or(n);
                    if sign.is_some_and(|(neg, _)| neg) {
                        v = -v;
                    }
                    Word::new(
                        g.span(span),
                        addr,
                        a_span,
                        None,
                        WordValue::Constant(NumberLit {
                            span: g.span(SimpleSpan::from(start.start..n.end)),
                            value: v,
                            integer: text.bytes().all(|b| b.is_ascii_digit()),
                        }),
                    )
                }
                // X1=10, M2=3
                (None, Some(n), None, Some(v)) => {
                    if !letter_takes_extension(l) {
                        return err(span, format!("address `{addr}` takes no numeric extension"), "only axes, I/J/K, M, H, S and T take an extension such as `M2=3`");
                    }
                    let ext = int_digits(n)?;
                    Word::new(
                        g.span(span),
                        addr,
                        a_span,
                        Some(Extension::Number { span: g.span(n), value: ext }),
                        assigned_value(value_expr(v)?),
                    )
                }
                // X=…
                (None, None, None, Some(v)) => {
                    Word::new(g.span(span), addr, a_span, None, assigned_value(value_expr(v)?))
                }
                // G[8]=2, M[R1]=3
                (None, None, Some((idx, bs)), Some(v)) => {
                    if !letter_takes_index(l) {
                        return err(bs, format!("address `{addr}` takes no `[…]` extension"), "write the plain form, e.g. `T=10` or `F=1000`");
                    }
                    Word::new(
                        g.span(span),
                        addr,
                        a_span,
                        Some(Extension::Index { span: idx.span, index: Box::new(idx) }),
                        assigned_value(value_expr(v)?),
                    )
                }
                (_, Some(n), Some((_, bs)), _) => {
                    return err(bs, format!("a numbered address `{addr}{}` takes no `[…]`", g.text(n)), "use either the number (`M2=3`) or the index (`M[2]=3`)");
                }
                (_, _, Some(_), None) => {
                    return err(span, format!("`{addr}[…]` needs `=` and a value"), "write e.g. `M[2]=3`");
                }
                (Some(_), Some(_), None, Some(_)) => {
                    return err(span, "a signed number cannot be an address extension".into(), "write e.g. `X1=-10`");
                }
                (_, None, None, None) | (Some(_), None, _, _) => {
                    return err(span, format!("address `{addr}` without a value"), "write a value directly after the address (`X10`) or after `=` (`X=R1`)");
                }
            };
            Ok(LetterStatement::Word(word))
            };
            classify()
        })
        .validate(|r, _, emitter| match r {
            Ok(s) => s,
            Err(err) => {
                emitter.emit(err);
                LetterStatement::Invalid
            }
        })
}

/// A jump target: label, block number or string expression.
fn jump_target<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, JumpTarget, Ex> + Clone + 't {
    let label = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then_ignore(
            // A label is a plain name; a name followed by an operator or
            // parenthesis is an expression.
            one_of([T::LParen, T::LBracket, T::Concat]).not().rewind(),
        )
        .map(move |s| JumpTarget::Label {
            span: g.span(s),
            name: g.name(s),
        });
    let block_number = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            let is_n = g.bytes(l)[0].eq_ignore_ascii_case(&b'N') && n.start == l.end;
            match g.text(n).parse::<u64>() {
                Ok(value) if is_n => Ok(JumpTarget::BlockNumber {
                    span: g.span(span),
                    value,
                }),
                _ => Err(SyntaxError::custom(
                    span,
                    ERR_WORD,
                    "a jump target is a label, a block number `N…` or a string",
                    None,
                )),
            }
        });
    choice((label, block_number, expr.map(JumpTarget::Expr))).labelled("jump target")
}

/// A label or block number (REPEAT sections take no string expressions,
/// which keeps `REPEAT A B P=3` unambiguous).
fn section_target<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, JumpTarget, Ex> + Clone + 't {
    let never = select! { T::Error => () }
        .try_map(|_, s| Err::<Expr, _>(SyntaxError::custom(s, ERR_WORD, "unreachable", None)));
    jump_target(g, never).labelled("label")
}

fn goto_kind<'t>() -> impl Parser<'t, In<'t>, GotoKind, Ex> + Clone + 't {
    select! {
        T::Goto => GotoKind::Goto,
        T::GotoF => GotoKind::GotoF,
        T::GotoB => GotoKind::GotoB,
        T::GotoC => GotoKind::GotoC,
        T::GotoS => GotoKind::GotoS,
    }
}

fn jump<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Jump, Ex> + Clone + 't {
    goto_kind()
        .then(jump_target(g, expr).or_not())
        .try_map(|(goto, target), span| match (goto, &target) {
            (GotoKind::GotoS, Some(_)) => Err(SyntaxError::custom(
                span,
                ERR_WORD,
                "`GOTOS` takes no target",
                Some("GOTOS jumps back to the program start"),
            )),
            (GotoKind::GotoS, None) | (_, Some(_)) => Ok(Jump { goto, target }),
            (_, None) => Err(SyntaxError::custom(
                span,
                "gcodec::parse::missing_jump_target",
                "jump without a target",
                Some("name a label, a block number (`N100`) or a string expression"),
            )),
        })
}

/// A type name (`INT`, `REAL`, `STRING`, …) and its span.
fn type_name<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, (TypeKind, SimpleSpan), Ex> + Clone + 't {
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .try_map(move |s, _| {
            TypeKind::from_name(g.text(s))
                .map(|k| (k, s))
                .ok_or(SyntaxError {
                    span: s,
                    found: Some(T::Ident),
                    expected: 0,
                    label: Some("data type"),
                    custom: None,
                })
        })
}

/// A data type: `INT`, `REAL`, `STRING[32]`, …
fn type_spec<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, TypeSpec, Ex> + Clone + 't {
    type_name(g)
        .then(
            expr.delimited_by(just(T::LBracket), just(T::RBracket))
                .or_not(),
        )
        .try_map(move |((kind, s), len), span| match (kind, len) {
            (TypeKind::String { .. }, length) => Ok(TypeSpec {
                span: g.span(span),
                kind: TypeKind::String {
                    length: length.map(Box::new),
                },
            }),
            (kind, None) => Ok(TypeSpec {
                span: g.span(s),
                kind,
            }),
            (_, Some(_)) => Err(SyntaxError::custom(
                span,
                ERR_WORD,
                "only STRING takes a length in `[…]`",
                Some("array dimensions follow the variable name: `DEF REAL A[3]`"),
            )),
        })
}

/// A declared name: an identifier, or a letter with digits touching it
/// (`R0`, `X1`; such names shadow addresses and are judged by later stages).
fn name_token<'t>() -> impl Parser<'t, In<'t>, SimpleSpan, Ex> + Clone + 't {
    let ident = select! { T::Ident => () }.map_with(|_, e| e.span());
    let letter = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(
            select! { T::Number => () }
                .map_with(|_, e| e.span())
                .or_not(),
        )
        .try_map(|(l, n): (SimpleSpan, Option<SimpleSpan>), span| match n {
            None => Ok(l),
            Some(n) if n.start == l.end => Ok(span),
            Some(_) => Err(SyntaxError::custom(
                span,
                ERR_WORD,
                "a name cannot contain a blank",
                None,
            )),
        });
    ident.or(letter)
}

/// Which names an attribute list accepts.
#[derive(Clone, Copy)]
enum AttributeNames {
    /// `PROC … SAVE DISPLOF`, `REDEF name …`: any name.
    Any,
    /// Before the type in `DEF`: any name that is not a type.
    BeforeType,
    /// After the type in `DEF` (`PHU 1 LLI 0 ULI 10 APWP 3`): only known
    /// attributes, since the variable name follows.
    AfterType,
}

impl AttributeNames {
    fn accepts(self, name: &str) -> bool {
        const AFTER_TYPE: &[&str] = &[
            "PHU", "LLI", "ULI", "APR", "APW", "APRP", "APWP", "APRB", "APWB", "APX", "SYNR",
            "SYNW", "SYNRW", "INIPO", "INIRE", "INICF", "PRLOC", "DCM", "DCI", "DCU",
        ];
        match self {
            AttributeNames::Any => true,
            AttributeNames::BeforeType => TypeKind::from_name(name).is_none(),
            AttributeNames::AfterType => AFTER_TYPE.iter().any(|k| k.eq_ignore_ascii_case(name)),
        }
    }
}

/// Attributes such as `NCK`, `SYNR`, `LLI 0`, `DISPLOF`, each with the
/// number that follows it, if any.
fn attributes<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
    names: AttributeNames,
) -> impl Parser<'t, In<'t>, Vec<Attribute>, Ex> + Clone + 't {
    let value = select! { T::Number => (), T::Minus => (), T::HexNumber => () }
        .rewind()
        .ignore_then(expr);
    select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .filter(move |s: &SimpleSpan| names.accepts(g.text(*s)))
        .then(value.or_not())
        .map_with(move |(name, value), e| Attribute {
            span: g.span(e.span()),
            name: g.name(name),
            value,
        })
        .repeated()
        .collect()
}

fn dims<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Expr>, Ex> + Clone + 't {
    indices(expr).or_not().map(Option::unwrap_or_default)
}

fn def<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let var = name_token()
        .then(dims(expr.clone()))
        .then(
            just(T::Eq)
                .ignore_then(initializer(g, expr.clone()))
                .or_not(),
        )
        .map_with(move |((name, dims), init), e| DefVar {
            span: g.span(e.span()),
            name: g.name(name),
            dims,
            init,
        });
    just(T::Def)
        .ignore_then(attributes(g, expr.clone(), AttributeNames::BeforeType))
        .then(type_spec(g, expr.clone()))
        .then(attributes(g, expr, AttributeNames::AfterType))
        .then(var.separated_by(just(T::Comma)).at_least(1).collect())
        .map(|(((mut attributes, ty), after), vars)| {
            attributes.extend(after);
            StatementKind::Def(Box::new(Def {
                attributes,
                ty,
                vars,
            }))
        })
}

fn proc_def<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let param = just(T::Var)
        .or_not()
        .then(type_spec(g, expr.clone()))
        .then(name_token())
        .then(dims(expr.clone()))
        .then(just(T::Eq).ignore_then(expr.clone()).or_not())
        .map_with(move |((((by_ref, ty), name), dims), default), e| Param {
            span: g.span(e.span()),
            by_reference: by_ref.is_some(),
            ty,
            name: g.name(name),
            dims,
            default,
        });
    just(T::Proc)
        .ignore_then(name_token())
        .then(
            param
                .separated_by(just(T::Comma))
                .collect::<Vec<_>>()
                .delimited_by(just(T::LParen), just(T::RParen))
                .or_not(),
        )
        .then(attributes(g, expr, AttributeNames::Any))
        .map(move |((name, params), attributes)| {
            StatementKind::Proc(Box::new(Proc {
                name: g.name(name),
                name_span: g.span(name),
                params: params.unwrap_or_default(),
                attributes,
            }))
        })
}

fn extern_decl<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    // Array dimensions in EXTERN may be left empty: `REAL[,]`. For STRING
    // the first bracket is the length: `STRING[32]`, `STRING[32][3]`.
    let ext_dims = expr
        .clone()
        .or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .delimited_by(just(T::LBracket), just(T::RBracket));
    let param = just(T::Var)
        .or_not()
        .then(type_name(g))
        .then(ext_dims.clone().or_not())
        .then(ext_dims.or_not())
        .try_map(move |(((by_ref, (kind, ts)), first), second), span| {
            let (ty, dims) = match kind {
                TypeKind::String { .. } => {
                    let length = match first {
                        Some(mut l) if l.len() == 1 && l[0].is_some() => {
                            l.pop().flatten().map(Box::new)
                        }
                        None => None,
                        Some(_) => {
                            return Err(SyntaxError::custom(
                                span,
                                ERR_WORD,
                                "a STRING length is one number, e.g. `STRING[32]`",
                                None,
                            ));
                        }
                    };
                    (TypeKind::String { length }, second.unwrap_or_default())
                }
                kind => {
                    if second.is_some() {
                        return Err(SyntaxError::custom(
                            span,
                            ERR_WORD,
                            "only STRING takes a length before its dimensions",
                            None,
                        ));
                    }
                    (kind, first.unwrap_or_default())
                }
            };
            let ts_end = span.end;
            Ok(ExternParam {
                span: g.span(span),
                by_reference: by_ref.is_some(),
                ty: TypeSpec {
                    span: g.span(SimpleSpan::from(ts.start..ts_end)),
                    kind: ty,
                },
                dims,
            })
        });
    just(T::Extern)
        .ignore_then(name_token())
        .then(
            param
                .separated_by(just(T::Comma))
                .collect::<Vec<_>>()
                .delimited_by(just(T::LParen), just(T::RParen))
                .or_not(),
        )
        .map(move |(name, params)| {
            StatementKind::Extern(Box::new(Extern {
                name: g.name(name),
                params: params.unwrap_or_default(),
            }))
        })
}

/// A subprogram call by name (for `MCALL`): `NAME`, `NAME(args)`, `L12`.
fn named_call<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Call, Ex> + Clone + 't {
    let by_name = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .map(move |s| CallTarget::Name {
            span: g.span(s),
            name: g.name(s),
        });
    let by_number = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            if g.bytes(l)[0].eq_ignore_ascii_case(&b'L')
                && n.start == l.end
                && g.bytes(n).iter().all(u8::is_ascii_digit)
            {
                Ok(CallTarget::Number {
                    span: g.span(span),
                    digits: g.name(n),
                })
            } else {
                Err(SyntaxError::custom(
                    span,
                    ERR_WORD,
                    "expected a program name or `L` number",
                    None,
                ))
            }
        });
    choice((by_name, by_number))
        .then(args(expr).or_not())
        .map(|(target, args)| Call {
            target,
            args,
            passes: None,
        })
}

/// `P3` / `P=3` after REPEAT (`None` when the word was malformed and its
/// error already emitted).
fn passes_word<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Option<SpannedWord>, Ex> + Clone + 't {
    letter_statement(g, expr).try_map(move |s, span| match s {
        LetterStatement::Word(w) if w.address() == "P" && w.extension().is_none() => {
            Ok(Some(SpannedWord {
                span: g.span(span),
                word: w,
            }))
        }
        LetterStatement::Invalid => Ok(None),
        _ => Err(SyntaxError::custom(
            span,
            ERR_WORD,
            "expected the number of passes `P=n`",
            None,
        )),
    })
}

/// All statements that may follow a block's number and label.
pub(crate) fn statements<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, Vec<Statement>, Ex> + 't {
    let expr = expr(g).boxed();
    let st = move |kind: StatementKind, s: SimpleSpan| Statement {
        span: g.span(s),
        kind,
    };

    let cond = expr.clone().map(|condition| Condition { condition });
    let if_stmt = just(T::If)
        .ignore_then(expr.clone())
        .then(jump(g, expr.clone()).or_not())
        .map(|(condition, jump)| match jump {
            Some(jump) => StatementKind::IfGoto(Box::new(IfGoto { condition, jump })),
            None => StatementKind::If(Box::new(Condition { condition })),
        });
    let simple_kw = any().try_map(|t: T, span| {
        structure_keyword(t).ok_or(SyntaxError {
            span,
            found: Some(t),
            expected: 0,
            label: None,
            custom: None,
        })
    });
    let while_stmt = just(T::While)
        .ignore_then(cond.clone())
        .map(|c| StatementKind::While(Box::new(c)));
    let until = just(T::Until)
        .ignore_then(cond.clone())
        .map(|c| StatementKind::Until(Box::new(c)));
    let for_stmt = just(T::For)
        .ignore_then(var_ref(g, expr.clone()))
        .then_ignore(just(T::Eq))
        .then(expr.clone())
        .then_ignore(just(T::To))
        .then(expr.clone())
        .map(|((var, start), end)| StatementKind::For(Box::new(For { var, start, end })));
    let repeat_section = select! { T::Repeat => false, T::RepeatB => true }
        .then(section_target(g))
        .then(section_target(g).or_not())
        .then(passes_word(g, expr.clone()).or_not())
        .map(|(((single_block, start), end), passes)| {
            StatementKind::RepeatSection(Box::new(RepeatSection {
                single_block,
                start,
                end,
                passes: passes.flatten().map(Box::new),
            }))
        });
    let repeat = just(T::Repeat).to(StatementKind::Repeat);
    let case_value = expr.clone();
    let case = just(T::Case)
        .ignore_then(expr.clone())
        .then_ignore(just(T::Of))
        .then(
            case_value
                .then(jump(g, expr.clone()))
                .map(|(value, jump)| CaseArm { value, jump })
                .repeated()
                .collect::<Vec<_>>(),
        )
        .then(just(T::Default).ignore_then(jump(g, expr.clone())).or_not())
        .map(|((selector, arms), default)| {
            StatementKind::Case(Box::new(Case {
                selector,
                arms,
                default,
            }))
        });
    let goto = jump(g, expr.clone()).map(|j| StatementKind::Goto(Box::new(j)));
    let redef = just(T::Redef)
        .ignore_then(name_token())
        .then(attributes(g, expr.clone(), AttributeNames::Any))
        .map(move |(name, attributes)| {
            StatementKind::Redef(Box::new(Redef {
                name: g.name(name),
                attributes,
            }))
        });
    let define = just(T::Define)
        .ignore_then(name_token())
        .then_ignore(just(T::As))
        .then(any().repeated().at_least(1).to_span())
        .map(move |(name, body): (SimpleSpan, SimpleSpan)| {
            StatementKind::Define(Box::new(Define {
                name: g.name(name),
                body: decode_text(g.bytes(body)),
                body_span: g.span(body),
            }))
        });
    let ret = just(T::Ret)
        .ignore_then(args(expr.clone()).or_not())
        .map(|args| StatementKind::Ret(Box::new(Ret { args })));
    let call_section = just(T::Block)
        .ignore_then(jump_target(g, expr.clone()))
        .then_ignore(just(T::To))
        .then(jump_target(g, expr.clone()));
    let indirect_call = just(T::Call)
        .ignore_then(
            just(T::Block)
                .not()
                .rewind()
                .ignore_then(expr.clone())
                .or_not(),
        )
        .then(call_section.or_not())
        .try_map(|(program, section), span| {
            if program.is_none() && section.is_none() {
                Err(SyntaxError::custom(
                    span,
                    ERR_WORD,
                    "`CALL` needs a program name or `BLOCK … TO …`",
                    Some("write e.g. `CALL \"PART1\"`"),
                ))
            } else {
                Ok(StatementKind::IndirectCall(Box::new(IndirectCall {
                    program,
                    section,
                })))
            }
        });
    let pcall = just(T::PCall)
        .ignore_then(
            select! { T::Slash => (), T::Ident => (), T::Letter => (), T::Number => () }
                .repeated()
                .at_least(1)
                .to_span(),
        )
        .then(args(expr.clone()).or_not())
        .map(move |(path, args): (SimpleSpan, _)| {
            StatementKind::PCall(Box::new(PCall {
                path: g.name(path),
                path_span: g.span(path),
                args,
            }))
        });
    let mcall = just(T::MCall)
        .ignore_then(named_call(g, expr.clone()).or_not())
        .map(|call| StatementKind::MCall(Box::new(MCall { call })));

    // Statements led by a name.
    let frame = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .try_map(move |s, _| {
            FrameOp::from_name(g.text(s)).ok_or(SyntaxError {
                span: s,
                found: Some(T::Ident),
                expected: 0,
                label: None,
                custom: None,
            })
        })
        .then(
            letter_statement(g, expr.clone())
                .try_map(move |s, span| match s {
                    LetterStatement::Word(w) => Ok(Some(SpannedWord {
                        span: g.span(span),
                        word: w,
                    })),
                    LetterStatement::Invalid => Ok(None),
                    _ => Err(SyntaxError::custom(
                        span,
                        ERR_WORD,
                        "frame instructions take axis words only",
                        Some("write e.g. `TRANS X10 Y5` in a block of its own"),
                    )),
                })
                .or(named_word(g, expr.clone()).map_with(move |word, e| {
                    Some(SpannedWord {
                        span: g.span(e.span()),
                        word,
                    })
                }))
                .repeated()
                .collect::<Vec<_>>(),
        )
        .map(|(op, words)| {
            StatementKind::Frame(Box::new(Frame {
                op,
                words: words.into_iter().flatten().collect(),
            }))
        });
    let assign_or_named = var_ref(g, expr.clone())
        .then_ignore(just(T::Eq))
        .then(initializer(g, expr.clone()))
        .try_map(move |(target, value), span| {
            named_address_word(g, &target, &value, span).map_or_else(
                || Ok(StatementKind::Assign(Box::new(Assign { target, value }))),
                |w| w.map(StatementKind::Word),
            )
        });
    let call = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then(args(expr.clone()).or_not())
        .map(move |(s, args)| {
            StatementKind::Call(Box::new(Call {
                target: CallTarget::Name {
                    span: g.span(s),
                    name: g.name(s),
                },
                args,
                passes: None,
            }))
        });
    // A malformed word yields no statement: its error was emitted, and the
    // driver reports the block.
    let letter = letter_statement(g, expr.clone()).map(|s| match s {
        LetterStatement::Word(w) => Some(StatementKind::Word(w)),
        LetterStatement::Assign(a) => Some(StatementKind::Assign(Box::new(a))),
        LetterStatement::Call(c) => Some(StatementKind::Call(Box::new(c))),
        LetterStatement::Invalid => None,
    });

    // Synchronous actions: `[ID=n] [WHEN cond] DO actions`.
    let action = choice((
        letter.clone(),
        assign_or_named.clone().map(Some),
        call.clone().map(Some),
    ))
    .map_with(move |kind, e| kind.map(|kind| st(kind, e.span())));
    let sync_id = select! { T::Id => false, T::Ids => true }
        .then_ignore(just(T::Eq))
        .then(expr.clone())
        .map_with(move |(is_static, value), e| SyncId {
            span: g.span(e.span()),
            is_static,
            value,
        });
    let trigger = select! {
        T::When => SyncTriggerKind::When,
        T::Whenever => SyncTriggerKind::Whenever,
        T::Every => SyncTriggerKind::Every,
        T::From => SyncTriggerKind::From,
    }
    .then(expr.clone())
    .map_with(move |(kind, condition), e| SyncTrigger {
        span: g.span(e.span()),
        kind,
        condition,
    });
    let sync = sync_id
        .or_not()
        .then(trigger.or_not())
        .then_ignore(just(T::Do))
        .then(action.repeated().at_least(1).collect::<Vec<_>>())
        .map(|((id, trigger), actions)| {
            StatementKind::SyncAction(Box::new(SyncAction {
                id,
                trigger,
                actions: actions.into_iter().flatten().collect(),
            }))
        });

    // Statements led by a keyword token; tried only when one is next.
    let keyword_statement = choice((
        if_stmt,
        simple_kw,
        while_stmt,
        until,
        for_stmt,
        repeat_section,
        repeat,
        case,
        goto,
        def(g, expr.clone()),
        redef,
        define,
        proc_def(g, expr.clone()),
        extern_decl(g, expr.clone()),
        ret,
        indirect_call,
        pcall,
        mcall,
        sync,
    ));
    let starts_with_keyword = any().filter(|t: &T| t.is_keyword()).rewind();
    // Most statements are address words: try them first.
    let statement = choice((
        letter,
        frame.map(Some),
        assign_or_named.map(Some),
        call.map(Some),
        starts_with_keyword.ignore_then(keyword_statement).map(Some),
    ))
    .map_with(move |kind, e| kind.map(|kind| st(kind, e.span())));

    statement
        .repeated()
        .collect::<Vec<_>>()
        .map(|statements| statements.into_iter().flatten().collect())
}

/// `CR=5`, `SPOS=90`, `AX[X1]=10` inside frame statements.
fn named_word<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Word, Ex> + Clone + 't {
    var_ref(g, expr.clone())
        .then_ignore(just(T::Eq))
        .then(initializer(g, expr))
        .try_map(move |(target, value), span| {
            named_address_word(g, &target, &value, span).unwrap_or_else(|| {
                let value = match value {
                    Initializer::Expr(e) => assigned_value(e),
                    _ => {
                        return Err(SyntaxError::custom(
                            span,
                            ERR_VALUE,
                            "a word takes one value, not a list",
                            None,
                        ));
                    }
                };
                Ok(Word::new(
                    g.span(span),
                    &target.name.to_ascii_uppercase(),
                    target.span,
                    None,
                    value,
                ))
            })
        })
}

/// Turns `NAME=…` / `NAME[i]=…` into a word when NAME is a multi-letter
/// address; `None` for ordinary assignments.
fn named_address_word(
    g: Ctx<'_>,
    target: &VarRef,
    value: &Initializer,
    span: SimpleSpan,
) -> Option<Result<Word, SyntaxError>> {
    if target.kind != VarKind::Name || !is_named_address(&target.name) {
        return None;
    }
    let Initializer::Expr(e) = value else {
        return Some(Err(SyntaxError::custom(
            span,
            ERR_VALUE,
            format!("address `{}` takes one value, not a list", target.name),
            None,
        )));
    };
    let extension = match target.indices.as_slice() {
        [] => None,
        [one] => Some(Extension::Index {
            span: one.span,
            index: Box::new(one.clone()),
        }),
        _ => {
            return Some(Err(SyntaxError::custom(
                span,
                ERR_WORD,
                format!("address `{}` takes one index", target.name),
                None,
            )));
        }
    };
    let name_len = target.name.len() as u32;
    let mut address_span = target.span;
    address_span.end = address_span.start + name_len;
    Some(Ok(Word::new(
        g.span(span),
        &target.name.to_ascii_uppercase(),
        address_span,
        extension,
        assigned_value(e.clone()),
    )))
}

/// The block prefix: skip mark, block number, label.
pub(crate) fn block<'t, 's: 't>(g: Ctx<'s>) -> impl Parser<'t, In<'t>, BlockBody, Ex> + 't {
    let skip = just(T::Slash)
        .map_with(|_, e| e.span())
        .then(
            select! { T::Number => () }
                .map_with(|_, e| e.span())
                .or_not(),
        )
        .try_map(
            move |(slash, level): (SimpleSpan, Option<SimpleSpan>), span: SimpleSpan| match level {
                None => Ok(SkipLevel {
                    span: g.span(slash),
                    level: 0,
                }),
                // `/ 5`: level 0 or 5? Nothing documents the control's
                // reading, and the two skip under different switches.
                Some(n) if n.start != slash.end => Err(SyntaxError::custom(
                    span,
                    "gcodec::parse::separated_skip_level",
                    format!(
                        "a blank between the skip mark `/` and the number `{}`",
                        g.text(n)
                    ),
                    Some("write the level against the mark (`/5`), or `/` alone for level 0"),
                )),
                Some(n) => match g.text(n).parse::<u8>() {
                    Ok(level) if level <= 9 => Ok(SkipLevel {
                        span: g.span(span),
                        level,
                    }),
                    _ => Err(SyntaxError::custom(
                        span,
                        "gcodec::parse::invalid_skip_level",
                        format!("skip level `/{}` is not 0 to 9", g.text(n)),
                        Some("skip levels are `/` and `/0` … `/9`"),
                    )),
                },
            },
        );
    let number = select! { T::Letter => () }
        .map_with(|_, e| e.span())
        .then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |(l, n): (SimpleSpan, SimpleSpan), span| {
            if !g.bytes(l)[0].eq_ignore_ascii_case(&b'N') || n.start != l.end {
                return Err(SyntaxError {
                    span,
                    found: Some(T::Letter),
                    expected: 0,
                    label: None,
                    custom: None,
                });
            }
            g.text(n)
                .parse::<u64>()
                .map(|value| BlockNumber {
                    span: g.span(span),
                    main: false,
                    value,
                })
                .map_err(|_| {
                    SyntaxError::custom(
                        span,
                        "gcodec::parse::invalid_block_number",
                        format!("block number `N{}` is not a whole number", g.text(n)),
                        None,
                    )
                })
        })
        .then_ignore(just(T::Eq).not().rewind());
    let main_number = just(T::Colon)
        .ignore_then(select! { T::Number => () }.map_with(|_, e| e.span()))
        .try_map(move |n, span| {
            g.text(n)
                .parse::<u64>()
                .map(|value| BlockNumber {
                    span: g.span(span),
                    main: true,
                    value,
                })
                .map_err(|_| {
                    SyntaxError::custom(
                        span,
                        "gcodec::parse::invalid_block_number",
                        format!("main block number `:{}` is not a whole number", g.text(n)),
                        None,
                    )
                })
        });
    let label = select! { T::Ident => () }
        .map_with(|_, e| e.span())
        .then_ignore(just(T::Colon))
        .map_with(move |name, e| LabelDef {
            span: g.span(e.span()),
            name: g.name(name),
        });
    skip.or_not()
        .then(choice((number, main_number)).or_not())
        .then(label.or_not())
        .then(statements(g))
        .map(|(((skip, number), label), statements)| BlockBody {
            skip,
            number,
            label,
            statements,
        })
}

#[cfg(test)]
mod tests {
    use super::number_value;

    #[test]
    fn numbers_are_read_exactly() {
        assert_eq!(number_value("1600"), Some(1600.0));
        assert_eq!(number_value("5."), Some(5.0));
        assert_eq!(number_value(".5"), Some(0.5));
        assert_eq!(number_value("1.5EX-3"), Some(1.5e-3));
        assert_eq!(number_value("0.01EX-11"), Some(1e-13));
        assert_eq!(number_value("10ex5"), Some(1e6));
        assert_eq!(number_value("1EX400"), None);
        assert_eq!(number_value("0EX400"), Some(0.0));
        assert_eq!(number_value("1EX"), None);
        assert_eq!(number_value("99999999999999999999"), Some(1e20));
        assert_eq!(number_value("."), None);
        assert_eq!(number_value("1.2.3"), None);
        assert_eq!(number_value("0.1"), Some(0.1));
        assert_eq!(number_value("123456789012345"), Some(123456789012345.0));
        assert_eq!(number_value("0.0000000000000000000001"), Some(1e-22));
    }

    /// The short-decimal path agrees with the standard library's correctly
    /// rounded parser on every form it takes.
    #[test]
    fn short_decimals_round_as_the_standard_parser() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        for _ in 0..200_000 {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let digits = (seed >> 60) as usize + 1;
            let mantissa = (seed >> 8) % 10u64.pow(digits.min(15) as u32);
            let text = format!("{mantissa:0digits$}");
            let point = (seed >> 4) as usize % (text.len() + 1);
            let text = format!("{}.{}", &text[..point], &text[point..]);
            let expected = text.parse::<f64>().ok();
            assert_eq!(number_value(&text), expected, "{text}");
        }
    }
}
