//! Declarations: `DEF` (variables with their type and attributes),
//! `REDEF`, `DEFINE … AS` macros, `PROC` (a subprogram's signature) and
//! `EXTERN` (another program's signature).

use chumsky::prelude::*;
use gcodec_lexer::TokenKind as T;
use gcodec_source::codes;

use super::expressions::initializer;
use super::names::declared_name;
use super::{Ctx, Ex, In, indices, name_token};
use crate::ast::*;
use crate::error::SyntaxError;

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
                codes::parse::INVALID_WORD,
                "only STRING takes a length in `[…]`",
                Some("array dimensions follow the variable name: `DEF REAL TAB[3]`"),
            )),
        })
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

/// Array dimensions `[a, b]`, if any.
fn dims<'t>(
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, Vec<Expr>, Ex> + Clone + 't {
    indices(expr).or_not().map(Option::unwrap_or_default)
}

/// `DEF [attributes] type [attributes] name[dims][=value], …`.
pub(super) fn def<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let var = declared_name(g)
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

/// `PROC name(params) [attributes]`.
pub(super) fn proc_def<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    let param = just(T::Var)
        .or_not()
        .then(type_spec(g, expr.clone()))
        .then(declared_name(g))
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

/// `EXTERN name(param types)`.
pub(super) fn extern_decl<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::Extern)
        .ignore_then(name_token())
        .then(
            extern_param(g, expr)
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

/// One parameter type of `EXTERN`: `[VAR] type[dims]`.
fn extern_param<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, ExternParam, Ex> + Clone + 't {
    // Array dimensions in EXTERN may be left empty: `REAL[,]`. For STRING
    // the first bracket is the length: `STRING[32]`, `STRING[32][3]`.
    let ext_dims = expr
        .or_not()
        .separated_by(just(T::Comma))
        .collect::<Vec<_>>()
        .delimited_by(just(T::LBracket), just(T::RBracket));
    just(T::Var)
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
                                codes::parse::INVALID_WORD,
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
                            codes::parse::INVALID_WORD,
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
        })
}

/// `REDEF name attributes`.
pub(super) fn redef<'t, 's: 't>(
    g: Ctx<'s>,
    expr: impl Parser<'t, In<'t>, Expr, Ex> + Clone + 't,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::Redef)
        .ignore_then(name_token())
        .then(attributes(g, expr, AttributeNames::Any))
        .map(move |(name, attributes)| {
            StatementKind::Redef(Box::new(Redef {
                name: g.name(name),
                attributes,
            }))
        })
}

/// `DEFINE name AS body`: the body is kept as text, to the end of the block.
pub(super) fn define<'t, 's: 't>(
    g: Ctx<'s>,
) -> impl Parser<'t, In<'t>, StatementKind, Ex> + Clone + 't {
    just(T::Define)
        .ignore_then(name_token())
        .then_ignore(just(T::As))
        .then(any().repeated().at_least(1).to_span())
        .map(move |(name, body): (SimpleSpan, SimpleSpan)| {
            StatementKind::Define(Box::new(Define {
                name: g.name(name),
                body: g.decode_text(g.bytes(body)),
                body_span: g.span(body),
            }))
        })
}
