//! The parser's error type: cheap on the happy path (no allocation while
//! chumsky tries alternatives), precise when it is reported.

use std::borrow::Cow;

use chumsky::DefaultExpected;
use chumsky::error::LabelError;
use chumsky::input::Input;
use chumsky::span::SimpleSpan;
use chumsky::util::MaybeRef;
use gcodec_lexer::TokenKind;
use gcodec_source::Code;

/// A syntax error inside one block.
#[derive(Clone, Debug)]
pub struct SyntaxError {
    pub span: SimpleSpan,
    pub found: Option<TokenKind>,
    /// Token kinds that would have been accepted (a bit per kind).
    pub expected: u128,
    /// A name for what was expected (`expression`, `jump target`).
    pub label: Option<&'static str>,
    /// A specific diagnosis, which wins over "unexpected token".
    pub custom: Option<Box<CustomError>>,
}

/// A syntax error with its own code, message and help.
#[derive(Clone, Debug)]
pub struct CustomError {
    pub code: &'static Code,
    pub message: Cow<'static, str>,
    pub help: Option<Cow<'static, str>>,
}

impl SyntaxError {
    /// A specific error.
    pub fn custom(
        span: SimpleSpan,
        code: &'static Code,
        message: impl Into<Cow<'static, str>>,
        help: Option<&'static str>,
    ) -> Self {
        Self {
            span,
            found: None,
            expected: 0,
            label: None,
            custom: Some(Box::new(CustomError {
                code,
                message: message.into(),
                help: help.map(Cow::Borrowed),
            })),
        }
    }

    /// The token kinds that were expected, in declaration order.
    pub fn expected_kinds(&self) -> impl Iterator<Item = TokenKind> + '_ {
        TokenKind::ALL
            .iter()
            .copied()
            .filter(|k| self.expected & (1u128 << (*k as u8)) != 0)
    }
}

impl<'a, I> chumsky::error::Error<'a, I> for SyntaxError
where
    I: Input<'a, Token = TokenKind, Span = SimpleSpan>,
{
    fn merge(mut self, other: Self) -> Self {
        match (&self.custom, &other.custom) {
            (None, Some(_)) => return other,
            (Some(_), _) => return self,
            _ => {}
        }
        self.expected |= other.expected;
        self.label = self.label.or(other.label);
        self
    }
}

impl<'a, I> LabelError<'a, I, DefaultExpected<'a, TokenKind>> for SyntaxError
where
    I: Input<'a, Token = TokenKind, Span = SimpleSpan>,
{
    fn expected_found<E: IntoIterator<Item = DefaultExpected<'a, TokenKind>>>(
        expected: E,
        found: Option<MaybeRef<'a, TokenKind>>,
        span: SimpleSpan,
    ) -> Self {
        let mut bits = 0u128;
        for e in expected {
            if let DefaultExpected::Token(t) = e {
                bits |= 1u128 << (*t as u8);
            }
        }
        Self {
            span,
            found: found.map(|t| *t),
            expected: bits,
            label: None,
            custom: None,
        }
    }
}

impl<'a, I> LabelError<'a, I, &'static str> for SyntaxError
where
    I: Input<'a, Token = TokenKind, Span = SimpleSpan>,
{
    fn expected_found<E: IntoIterator<Item = &'static str>>(
        expected: E,
        found: Option<MaybeRef<'a, TokenKind>>,
        span: SimpleSpan,
    ) -> Self {
        Self {
            span,
            found: found.map(|t| *t),
            expected: 0,
            label: expected.into_iter().next(),
            custom: None,
        }
    }

    fn label_with(&mut self, label: &'static str) {
        if self.custom.is_none() {
            self.expected = 0;
            self.label = Some(label);
        }
    }
}
