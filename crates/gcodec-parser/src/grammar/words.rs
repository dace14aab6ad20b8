//! Address words and the other statements led by one address letter: DIN
//! words (`X-1.5`, `M2=3`, `G[8]=2`, `X=IC(5)`), R-parameter assignments
//! (`R1=…`, `R[i]=…`) and subprogram calls by number (`L123`); and words
//! of multi-letter addresses (`CR=5`, `AX[X1]=10`). Extensions, values and
//! dimension modifiers (`IC(…)`, `AC(…)`) are read here.

use chumsky::prelude::*;
use gcodec_lang::DimensionMode;
use gcodec_lang::addresses::{is_written_as_address, letter_str};
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::expressions::{initializer, var_ref};
use super::numbers::number_value;
use super::{Ctx, Ex, In, args};

use crate::ast::*;
use crate::error::SyntaxError;

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
pub(super) enum LetterStatement {
    Word(Word),
    Assign(Assign),
    Call(Call),
    /// Malformed; a non-fatal error was emitted and the driver reports the
    /// block.
    Invalid,
}

/// Statements that start with a single address letter: DIN words,
/// R-parameter assignments and `L` calls.
pub(super) fn letter_statement<'t, 's: 't>(
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
        .map_with(
            move |((((((letter, sign), number), bracket), value), string), call_args), e| {
                let span: SimpleSpan = e.span();
                let parts = LetterParts {
                    span,
                    letter,
                    address: g.bytes(letter)[0].to_ascii_uppercase(),
                    sign,
                    number,
                    bracket,
                    value: complete_value(g, letter, value, span)?,
                    call_args,
                };
                parts.written_together(string)?;
                classify(g, parts)
            },
        )
        .validate(|r, _, emitter| match r {
            Ok(s) => s,
            Err(err) => {
                emitter.emit(err);
                LetterStatement::Invalid
            }
        })
}

/// The pieces of a statement led by a letter, read but not yet judged.
struct LetterParts {
    /// The whole statement.
    span: SimpleSpan,
    letter: SimpleSpan,
    /// The letter in upper case.
    address: u8,
    /// `true` for `-`.
    sign: Option<(bool, SimpleSpan)>,
    number: Option<SimpleSpan>,
    /// `[…]` and its span.
    bracket: Option<(Expr, SimpleSpan)>,
    /// What follows `=`.
    value: Option<Initializer>,
    call_args: Option<Vec<Option<Expr>>>,
}

/// The value after `=`, which must be complete: `X=` alone is an error.
fn complete_value(
    g: Ctx<'_>,
    letter: SimpleSpan,
    value: Option<(SimpleSpan, Option<Initializer>)>,
    span: SimpleSpan,
) -> Result<Option<Initializer>, SyntaxError> {
    match value {
        Some((eq, None)) => Err(SyntaxError::custom(
            SimpleSpan::from(eq.start..span.end.max(eq.end)),
            codes::parse::INVALID_VALUE,
            format!(
                "`{}=` is not followed by a complete value",
                g.text(SimpleSpan::from(letter.start..eq.start)).trim_end()
            ),
            Some("write an expression after `=`, e.g. `X=R1+5`; check brackets and operators"),
        )),
        Some((_, Some(v))) => Ok(Some(v)),
        None => Ok(None),
    }
}

impl LetterParts {
    fn addr(&self) -> &'static str {
        letter_str(self.address)
    }

    /// No string after the address (`T"DRILL"`), and the sign and digits
    /// touch the letter and each other.
    fn written_together(&self, string: Option<SimpleSpan>) -> Result<(), SyntaxError> {
        let addr = self.addr();
        if let Some(s) = string {
            return invalid_word(
                s,
                format!("a string after `{addr}` needs `=`"),
                "write the value as `T=\"NAME\"`",
            );
        }
        let mut next_start = self.letter.end;
        if let Some((_, s)) = self.sign {
            if s.start != next_start {
                return invalid_word(
                    self.span,
                    format!("blank between address `{addr}` and its value"),
                    "write the value directly after the address, e.g. `X-10`, or use `=`",
                );
            }
            next_start = s.end;
        }
        if let Some(n) = self.number {
            if n.start != next_start {
                return invalid_word(
                    self.span,
                    format!("blank between address `{addr}` and its value"),
                    "write the value directly after the address (`M5`), or use `=` (`M=5`)",
                );
            }
        } else if self.sign.is_some() {
            return invalid_word(
                self.span,
                format!("sign without a number after `{addr}`"),
                "write e.g. `X-10`",
            );
        }
        Ok(())
    }
}

/// A malformed word at `s`.
fn invalid_word<T>(s: SimpleSpan, msg: String, help: &'static str) -> Result<T, SyntaxError> {
    Err(SyntaxError::custom(
        s,
        codes::parse::INVALID_WORD,
        msg,
        Some(help),
    ))
}

/// The one expression the `=` of the word at `span` takes.
fn single_value(span: SimpleSpan, addr: &str, v: Initializer) -> Result<Expr, SyntaxError> {
    match v {
        Initializer::Expr(e) => Ok(e),
        _ => Err(SyntaxError::custom(
            span,
            codes::parse::INVALID_VALUE,
            format!("address `{addr}` takes one value, not a list"),
            None,
        )),
    }
}

/// The numeric address extension (`2` in `M2=3`) or R-parameter number.
fn extension_number(g: Ctx<'_>, n: SimpleSpan) -> Result<u32, SyntaxError> {
    g.text(n).parse::<u32>().map_err(|_| {
        SyntaxError::custom(
            n,
            codes::parse::INVALID_WORD,
            format!("`{}` is not a valid address extension", g.text(n)),
            Some("an address extension is a whole number, e.g. `M2=3`, `X1=10`"),
        )
    })
}

/// Which statement the letter leads.
fn classify(g: Ctx<'_>, parts: LetterParts) -> Result<LetterStatement, SyntaxError> {
    if parts.address == b'R' && parts.sign.is_none() {
        return r_parameter(g, parts).map(LetterStatement::Assign);
    }
    if parts.address == b'L'
        && parts.sign.is_none()
        && parts.bracket.is_none()
        && parts.value.is_none()
        && let Some(n) = parts.number
    {
        return program_call(g, parts, n).map(LetterStatement::Call);
    }
    if parts.call_args.is_some() {
        return invalid_word(
            parts.span,
            format!("unexpected `(` after address `{}`", parts.addr()),
            "`(` groups expressions after `=`, e.g. `X=(R1+2)*3`",
        );
    }
    address_word(g, parts).map(LetterStatement::Word)
}

/// `R1=…`, `R[i]=…`.
fn r_parameter(g: Ctx<'_>, parts: LetterParts) -> Result<Assign, SyntaxError> {
    let LetterParts {
        span,
        letter,
        number,
        bracket,
        value,
        call_args,
        ..
    } = parts;
    let bracket_end = bracket.as_ref().map(|(_, b)| b.end);
    let index = match (number, bracket) {
        (Some(n), None) => {
            let v = extension_number(g, n)?;
            Expr {
                span: g.span(n),
                kind: ExprKind::Number {
                    value: v as f64,
                    integer: true,
                },
            }
        }
        (None, Some((idx, _))) => idx,
        (Some(_), Some((_, b))) => {
            return invalid_word(
                b,
                "an R parameter with a number takes no index".into(),
                "write `R10=4` or `R[10]=4`",
            );
        }
        (None, None) => {
            return invalid_word(
                span,
                "`R` needs a parameter number".into(),
                "write e.g. `R1=5` or `R[R2]=5`",
            );
        }
    };
    let Some(value) = value else {
        return invalid_word(
            span,
            "R parameter without assignment".into(),
            "assign a value, e.g. `R1=5`",
        );
    };
    if call_args.is_some() {
        return invalid_word(
            span,
            "unexpected `(` after an R-parameter assignment".into(),
            "separate statements with a blank",
        );
    }
    let target_end = bracket_end.or(number.map(|n| n.end)).unwrap_or(letter.end);
    Ok(Assign {
        target: VarRef {
            span: g.span(SimpleSpan::from(letter.start..target_end)),
            kind: VarKind::RParameter,
            name: "R".into(),
            indices: vec![index],
        },
        value,
    })
}

/// `L123`, `L123(args)`: a subprogram call by number.
fn program_call(g: Ctx<'_>, parts: LetterParts, n: SimpleSpan) -> Result<Call, SyntaxError> {
    let digits = g.text(n);
    if !digits.bytes().all(|b| b.is_ascii_digit()) {
        return invalid_word(
            n,
            format!("`L{digits}` is not a program number"),
            "program numbers are whole numbers, e.g. `L123`",
        );
    }
    Ok(Call {
        target: CallTarget::Number {
            span: g.span(SimpleSpan::from(parts.letter.start..n.end)),
            digits: digits.into(),
        },
        args: parts.call_args,
        passes: None,
    })
}

/// A DIN word: `X10`, `X1=10`, `X=…`, `G[8]=2`.
fn address_word(g: Ctx<'_>, parts: LetterParts) -> Result<Word, SyntaxError> {
    let addr = parts.addr();
    let LetterParts {
        span,
        letter,
        address,
        sign,
        number,
        bracket,
        value,
        ..
    } = parts;
    let assigned = |extension: Option<Extension>, v: Initializer| -> Result<Word, SyntaxError> {
        Ok(Word::new(
            g.span(span),
            addr,
            g.span(letter),
            extension,
            assigned_value(single_value(span, addr, v)?),
        ))
    };
    match (sign, number, bracket, value) {
        // X10, X-10, X.5
        (_, Some(n), None, None) => constant_word(g, span, (addr, letter), sign, n),
        // X1=10, M2=3
        (None, Some(n), None, Some(v)) => {
            if !letter_takes_extension(address) {
                return invalid_word(
                    span,
                    format!("address `{addr}` takes no numeric extension"),
                    "only axes, I/J/K, M, H, S and T take an extension such as `M2=3`",
                );
            }
            let value = extension_number(g, n)?;
            assigned(
                Some(Extension::Number {
                    span: g.span(n),
                    value,
                }),
                v,
            )
        }
        // X=…
        (None, None, None, Some(v)) => assigned(None, v),
        // G[8]=2, M[R1]=3
        (None, None, Some((idx, bs)), Some(v)) => {
            if !letter_takes_index(address) {
                return invalid_word(
                    bs,
                    format!("address `{addr}` takes no `[…]` extension"),
                    "write the plain form, e.g. `T=10` or `F=1000`",
                );
            }
            let extension = Extension::Index {
                span: idx.span,
                index: Box::new(idx),
            };
            assigned(Some(extension), v)
        }
        (_, Some(n), Some((_, bs)), _) => invalid_word(
            bs,
            format!("a numbered address `{addr}{}` takes no `[…]`", g.text(n)),
            "use either the number (`M2=3`) or the index (`M[2]=3`)",
        ),
        (_, _, Some(_), None) => invalid_word(
            span,
            format!("`{addr}[…]` needs `=` and a value"),
            "write e.g. `M[2]=3`",
        ),
        (Some(_), Some(_), None, Some(_)) => invalid_word(
            span,
            "a signed number cannot be an address extension".into(),
            "write e.g. `X1=-10`",
        ),
        (_, None, None, None) | (Some(_), None, _, _) => invalid_word(
            span,
            format!("address `{addr}` without a value"),
            "write a value directly after the address (`X10`) or after `=` (`X=R1`)",
        ),
    }
}

/// `X10`, `X-10`: the address, written at `letter`, with a constant
/// touching it.
fn constant_word(
    g: Ctx<'_>,
    span: SimpleSpan,
    (addr, letter): (&'static str, SimpleSpan),
    sign: Option<(bool, SimpleSpan)>,
    n: SimpleSpan,
) -> Result<Word, SyntaxError> {
    let text = g.text(n);
    let Some(mut v) = number_value(text) else {
        return invalid_word(
            n,
            format!("number `{text}` is out of range"),
            "REAL values range over about ±1.8·10^308",
        );
    };
    let start = sign.map(|(_, s)| s).unwrap_or(n);
    if sign.is_some_and(|(neg, _)| neg) {
        v = -v;
    }
    Ok(Word::new(
        g.span(span),
        addr,
        g.span(letter),
        None,
        WordValue::Constant(NumberLit {
            span: g.span(SimpleSpan::from(start.start..n.end)),
            value: v,
            integer: text.bytes().all(|b| b.is_ascii_digit()),
        }),
    ))
}

/// `CR=5`, `SPOS=90`, `AX[X1]=10` inside frame statements.
pub(super) fn named_word<'t, 's: 't>(
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
                            codes::parse::INVALID_VALUE,
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
    if target.kind != VarKind::Name || !is_written_as_address(&target.name) {
        return None;
    }
    let Initializer::Expr(e) = value else {
        return Some(Err(SyntaxError::custom(
            span,
            codes::parse::INVALID_VALUE,
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
                codes::parse::INVALID_WORD,
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

/// A statement led by a letter; `None` for a malformed word, whose error
/// was emitted (the driver reports the block).
pub(super) fn word_statement<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Option<StatementKind>, Ex> + Clone + 't {
    letter_statement(g, expr).map(|s| match s {
        LetterStatement::Word(w) => Some(StatementKind::Word(w)),
        LetterStatement::Assign(a) => Some(StatementKind::Assign(Box::new(a))),
        LetterStatement::Call(c) => Some(StatementKind::Call(Box::new(c))),
        LetterStatement::Invalid => None,
    })
}

/// `NAME=…`, `NAME[i]=…`, `$SYS=…`: a word when NAME is a multi-letter
/// address (`CR=5`), an assignment otherwise.
pub(super) fn assignment_or_named_word<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    var_ref(g, expr.clone())
        .then_ignore(just(T::Eq))
        .then(initializer(g, expr))
        .try_map(move |(target, value), span| {
            named_address_word(g, &target, &value, span).map_or_else(
                || Ok(StatementKind::Assign(Box::new(Assign { target, value }))),
                |w| w.map(StatementKind::Word),
            )
        })
}

/// A letter statement that must be one word `accept` takes (`None` when
/// the word was malformed and its error already emitted); anything else
/// is `invalid_word` with `message` and `help`.
pub(super) fn word_only<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
    accept: fn(&Word) -> bool,
    message: &'static str,
    help: Option<&'static str>,
) -> impl Parser<'t, In<'t>, Option<SpannedWord>, Ex> + Clone + 't {
    letter_statement(g, expr).try_map(move |s, span| match s {
        LetterStatement::Word(w) if accept(&w) => Ok(Some(SpannedWord {
            span: g.span(span),
            word: w,
        })),
        LetterStatement::Invalid => Ok(None),
        _ => Err(SyntaxError::custom(
            span,
            codes::parse::INVALID_WORD,
            message,
            help,
        )),
    })
}
