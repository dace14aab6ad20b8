//! Named addresses (reference §2.2, §2.6, §2.7): `SPOS`, `FA[X]`, `ACC[X]`,
//! `OVR`, `LIMS`, `CHF`, `RND`, `PW`, `SD`, `DL`, `AX[X]`, `POS[C]`, …,
//! `H` auxiliary functions, the dimension-modifier rules of §2.5, dwell
//! (`G4`) and the checks of the profile's `[g_codes]`.
//!
//! What the executor interprets becomes an `address` instruction; what
//! belongs to the block's motion is attached to it (`AX[…]` targets, `PW`
//! and `PL` spline data, `CHF`/`CHR`/`RND` transitions, polar `AP`/`RP` and
//! `ANG` as targets).

use std::borrow::Cow;

use gcodec_ail::{Address, AxisValue, HFunction, IndirectAxisValue, MTiming, Op, Value};
use gcodec_lang::DimensionMode;
use gcodec_lang::addresses::{
    AddressRole, AddressScope, NamedAddress, Operand, TransitionKind, is_written_as_address,
};
use gcodec_lang::ggroups;
use gcodec_parser::ast::{self, Extension, StatementKind, Word, WordValue};
use gcodec_profile::AxisKind;
use gcodec_source::{Diagnostic, Span, codes};

use crate::{tools, values};

use super::{BlockPlan, Lowering};
/// Which dimension modifiers an address accepts (reference §2.5).
#[derive(Clone, Copy)]
pub(super) enum Modifiers {
    /// `F S M T D H G`, `CR`, `LIMS`, …
    None,
    /// `I J K`, `AP`, `RP`: `AC`, `IC`.
    AbsoluteIncremental,
    /// `SPOS`, `SPOSA`: `AC IC DC ACP ACN`.
    Spindle,
    /// An axis of the kind given, or unknown until run time.
    Axis(Option<AxisKind>),
}

/// The number of `TOFFL[1]`, `FMA[2,X]`.
pub(super) enum AddressNumber {
    Constant(u32),
    Computed(gcodec_ail::Expr),
}

/// Where the bracketed parts of a setting go in its instruction.
trait SettingParts {
    fn set_axis(&mut self, axis: AxisRef);
    fn set_number(&mut self, number: AddressNumber);
}

impl SettingParts for Address {
    fn set_axis(&mut self, axis: AxisRef) {
        match axis {
            AxisRef::Named(name) => self.axis = Some(name),
            AxisRef::Computed(expr) => self.axis_expr = Some(expr),
        }
    }

    fn set_number(&mut self, number: AddressNumber) {
        match number {
            AddressNumber::Constant(n) => self.extension = Some(n),
            AddressNumber::Computed(expr) => self.extension_expr = Some(expr),
        }
    }
}

/// How an axis is named in brackets (`FA[X]`, `AX[_Z]`).
pub(super) enum AxisRef {
    /// A name of the profile's axes, in upper case.
    Named(String),
    /// A variable or expression, resolved when the block runs.
    Computed(gcodec_ail::Expr),
}

/// A name that can only be an axis identifier: an axis letter with an
/// optional number (`X`, `C2`, `Q1`), as opposed to a variable (`_Z`).
fn looks_like_axis(name: &str) -> bool {
    let bytes = name.as_bytes();
    matches!(
        bytes.first().map(u8::to_ascii_uppercase),
        Some(b'A' | b'B' | b'C' | b'E' | b'Q' | b'U' | b'V' | b'W' | b'X' | b'Y' | b'Z')
    ) && bytes[1..].iter().all(u8::is_ascii_digit)
        && bytes.len() <= 3
}

impl Lowering<'_> {
    /// `G<n>` is ruled out by the profile's `[g_codes]`.
    pub(super) fn g_unsupported(&self, group: u8, member: &str) -> Option<&'static str> {
        let g = &self.profile.g_codes;
        if g.unsupported_groups.iter().any(|n| *n.get_ref() == group) {
            return Some("unsupported_groups");
        }
        if g.unsupported.iter().any(|c| {
            ggroups::lookup(c.get_ref()).and_then(|(gr, i)| ggroups::member(gr, i)) == Some(member)
        }) {
            return Some("unsupported");
        }
        None
    }

    /// The modifiers `address` accepts.
    pub(super) fn modifiers_for(&self, word: &Word) -> Modifiers {
        let address = word.address();
        match address {
            "I" | "J" | "K" | "AP" | "RP" => Modifiers::AbsoluteIncremental,
            "SPOS" | "SPOSA" => Modifiers::Spindle,
            "AX" | "POS" | "POSA" => match word.extension() {
                Some(Extension::Index { index, .. }) => match &index.kind {
                    ast::ExprKind::Var { var } if var.indices.is_empty() => {
                        Modifiers::Axis(self.axis_kind(&var.name))
                    }
                    _ => Modifiers::Axis(None),
                },
                _ => Modifiers::Axis(None),
            },
            _ if NamedAddress::named(address).is_some() => Modifiers::None,
            "E" => Modifiers::Axis(self.axis_kind("E")),
            _ if address.len() == 1
                && matches!(
                    address.as_bytes()[0],
                    b'A' | b'B' | b'C' | b'Q' | b'U' | b'V' | b'W' | b'X' | b'Y' | b'Z'
                ) =>
            {
                let name = self.axis_word_name(word);
                Modifiers::Axis(self.axis_kind(&name))
            }
            _ => Modifiers::None,
        }
    }

    /// The axis an axis-letter word names: `X`, or `X1` for `X1=…`.
    pub(super) fn axis_word_name(&self, word: &Word) -> String {
        match word.extension() {
            Some(Extension::Number { value, .. }) => format!("{}{value}", word.address()),
            _ => word.address().to_owned(),
        }
    }

    pub(super) fn axis_kind(&self, name: &str) -> Option<AxisKind> {
        self.profile
            .axes
            .iter()
            .find(|a| a.name.get_ref().eq_ignore_ascii_case(name))
            .map(|a| a.kind)
    }

    /// The help of an axis the machine lacks: its axes, and the one
    /// nearest to `name` where one is near.
    pub(super) fn axes_help(&self, name: &str) -> String {
        let axes: Vec<&str> = self
            .profile
            .axes
            .iter()
            .map(|a| a.name.get_ref().as_str())
            .collect();
        let listed = axes
            .iter()
            .map(|a| format!("`{a}`"))
            .collect::<Vec<_>>()
            .join(", ");
        match gcodec_source::nearest(name, axes.iter().copied()) {
            Some(near) => format!(
                "did you mean `{near}`? This machine's axes (the profile's `[[axes]]`) are {listed}"
            ),
            None => format!("this machine's axes (the profile's `[[axes]]`) are {listed}"),
        }
    }

    /// Reports a dimension modifier the address does not take (reference
    /// §2.5); `false` when the word is rejected.
    pub(super) fn check_modifier(&mut self, word: &Word, value: &WordValue) -> bool {
        let WordValue::Assigned {
            modifier: Some(modifier),
            ..
        } = value
        else {
            return true;
        };
        use DimensionMode::*;
        let kind = modifier.kind;
        let address = word.address();
        let (allowed, help): (bool, Cow<'static, str>) = match self.modifiers_for(word) {
            Modifiers::None => (
                false,
                format!("`{address}` takes a plain value; AC and IC apply to axes, I J K, AP, RP and SPOS, DC, ACP and ACN to rotary axes and SPOS/SPOSA").into(),
            ),
            Modifiers::AbsoluteIncremental => (
                matches!(kind, Ac | Ic),
                format!("`{address}` takes AC or IC").into(),
            ),
            Modifiers::Spindle => (
                matches!(kind, Ac | Ic | Dc | Acp | Acn),
                "spindle positions take AC, IC, DC, ACP or ACN".into(),
            ),
            Modifiers::Axis(axis) => match kind {
                Dc | Acp | Acn => (
                    axis != Some(AxisKind::Linear),
                    "DC, ACP and ACN position rotary axes (and spindles); the profile's `[[axes]]` makes this axis linear".into(),
                ),
                Dac | Dic | Rac | Ric => (
                    axis != Some(AxisKind::Rotary),
                    "diameter and radius programming (DAC, DIC, RAC, RIC) applies to linear axes".into(),
                ),
                _ => (true, "".into()),
            },
        };
        if allowed {
            return true;
        }
        self.diagnostics.push(
            Diagnostic::new(
                codes::lower::MODIFIER_NOT_ALLOWED,
                format!("`{}` is not allowed on `{address}`", kind.keyword()),
            )
            .with_label(modifier.span, "dimension modifier")
            .with_help(help),
        );
        false
    }

    /// An axis named in brackets (`FA[X]`, `AX[_Z]`): a constant axis name
    /// must be one of the profile's; a variable is resolved when the block
    /// runs. `None` when the word is rejected (diagnostic pushed).
    pub(super) fn bracket_axis(&mut self, word: &Word, span: Span) -> Option<AxisRef> {
        let address = word.address();
        let index = match word.extension() {
            Some(Extension::Index { index, .. }) => index,
            Some(Extension::Number { span: at, .. }) => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::EXTENSION_NOT_ALLOWED,
                        format!("`{address}` takes its axis in brackets"),
                    )
                    .with_label(*at, "a number")
                    .with_help(format!("write `{address}[X]=…` with the axis name")),
                );
                return None;
            }
            None => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::MISSING_AXIS,
                        format!("`{address}` needs an axis"),
                    )
                    .with_label(word.address_span(span), "no axis")
                    .with_help(format!("write `{address}[X]=…` with the axis name")),
                );
                return None;
            }
        };
        self.axis_in_brackets(address, index)
    }

    /// The axis `index` names in `address[index]`: a constant axis name
    /// must be one of the profile's; a variable is resolved when the block
    /// runs. `None` when rejected (diagnostic pushed).
    fn axis_in_brackets(&mut self, address: &str, index: &ast::Expr) -> Option<AxisRef> {
        match &index.kind {
            ast::ExprKind::Var { var }
                if var.indices.is_empty() && var.kind == ast::VarKind::Name =>
            {
                let name = var.name.to_ascii_uppercase();
                if self.is_axis(&name) {
                    return Some(AxisRef::Named(name.to_string()));
                }
                if name == "E" {
                    self.reserved_e(var.span);
                    return None;
                }
                if looks_like_axis(&name) {
                    self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::UNKNOWN_ADDRESS,
                            format!("`{name}` is not an axis of this machine"),
                        )
                        .with_label(var.span, "unknown axis")
                        .with_help(self.axes_help(&name)),
                    );
                    return None;
                }
                // `AX[_Z]`: an AXIS variable or parameter.
                self.check_variables(index);
                Some(AxisRef::Computed(values::tree(index)))
            }
            ast::ExprKind::Number { .. } => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::AXIS_NUMBER,
                        format!("`{address}[{}]` names an axis by a number", values::source_text(index)),
                    )
                    .with_label(index.span, "not an axis name")
                    .with_help("SINUMERIK names axes (`ACC[X]`, `ACC[AX4]`); the control rejects a number here. Left out of the instruction list"),
                );
                None
            }
            _ => {
                self.check_variables(index);
                Some(AxisRef::Computed(values::tree(index)))
            }
        }
    }

    /// `E`: reserved on the control (MD20060 forbids it as an axis name);
    /// the CEAD interpreter's programs use it as the extruder axis.
    pub(super) fn reserved_e(&mut self, span: Span) {
        self.diagnostics.push(
            Diagnostic::new(codes::lower::RESERVED_ADDRESS, "`E` is a reserved address of the control")
                .with_label(span, "reserved")
                .with_help("SINUMERIK reserves `E` (no axis may be named E, MD20060) and rejects it; programs for the CEAD interpreter use it as the extruder axis. Left out of the instruction list; a profile with an axis `E` lowers it as that axis"),
        );
    }

    /// A spindle number in brackets or digits (`SPOS[2]=`, `SPOS2=`):
    /// checked against the profile when constant. `Err` when rejected.
    fn spindle_extension(
        &mut self,
        address: &str,
        extension: Option<&Extension>,
    ) -> Result<(Option<u32>, Option<gcodec_ail::Expr>), ()> {
        match extension {
            None => Ok((None, None)),
            Some(Extension::Number { value, span }) => self.spindle_number(*value, *span),
            Some(Extension::Index { index, span }) => match values::constant(index) {
                Some(n) if n >= 0.0 && n.fract() == 0.0 && n <= 99.0 => {
                    self.spindle_number(n as u32, *span)
                }
                Some(_) => {
                    let written = values::written(self.source, *span);
                    self.diagnostics.push(crate::tools::not_a_spindle_number(
                        address, &written, "0…99", *span,
                    ));
                    Err(())
                }
                None => {
                    self.check_variables(index);
                    Ok((None, Some(values::tree(index))))
                }
            },
        }
    }

    fn spindle_number(
        &mut self,
        n: u32,
        span: Span,
    ) -> Result<(Option<u32>, Option<gcodec_ail::Expr>), ()> {
        // Extension 0 is the master spindle (reference §4.2).
        if n != 0 && !tools::spindle_exists(self.profile, n) {
            self.diagnostics.push(tools::unknown_spindle(n, span));
            return Err(());
        }
        Ok((Some(n), None))
    }

    /// A named address word (`SPOS=90`, `FA[X]=400`, `CHF=2`); `false`
    /// when `address` is none of them.
    pub(super) fn named_address(
        &mut self,
        word: &Word,
        value: &WordValue,
        span: Span,
        plan: &mut BlockPlan,
    ) -> bool {
        let Some(address) = NamedAddress::named(word.address()) else {
            return false;
        };
        let (v, mode) = values::word_value(value);
        self.place_address(address, word.extension(), v, mode, word, span, plan);
        true
    }

    #[allow(clippy::too_many_arguments)]
    fn place_address(
        &mut self,
        address: NamedAddress,
        extension: Option<&Extension>,
        value: Value,
        mode: Option<DimensionMode>,
        word: &Word,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let role = address.role();
        let name = address.name();
        let takes_extension = matches!(
            role,
            AddressRole::IndirectAxis
                | AddressRole::Setting {
                    operand: Operand::Axis | Operand::Spindle | Operand::Number,
                    ..
                }
        );
        if let AddressRole::Setting {
            operand: Operand::NumberAxis | Operand::AxisPair,
            ..
        } = role
        {
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::MISSING_AXIS,
                    format!("`{name}` takes two values in brackets"),
                )
                .with_label(span, "here")
                .with_help(format!(
                    "write `{name}[…,X]=…`, the axis last (reference §2.2)"
                )),
            );
        }
        if !takes_extension && let Some(ext) = extension {
            let at = match ext {
                Extension::Number { span, .. } | Extension::Index { span, .. } => *span,
            };
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::EXTENSION_NOT_ALLOWED,
                    format!("`{name}` takes no address extension"),
                )
                .with_label(at, "extension")
                .with_help(
                    "extensions are for axes, I J K, S, SPOS, SPOSA, M, H and T (reference §2.2); axial addresses take an axis in brackets (`FA[X]=`)",
                ),
            );
        }
        match role {
            AddressRole::Setting { scope, operand } => {
                let mut setting = Address {
                    mode,
                    ..Address::new(address, value, scope)
                };
                match operand {
                    Operand::Axis => match self.bracket_axis(word, span) {
                        Some(axis) => setting.set_axis(axis),
                        None => return,
                    },
                    Operand::Spindle => match self.spindle_extension(name, extension) {
                        Ok((ext, ext_expr)) => {
                            setting.extension = ext;
                            setting.extension_expr = ext_expr;
                        }
                        Err(()) => return,
                    },
                    Operand::Number => match extension {
                        Some(Extension::Number { value, .. }) => setting.extension = Some(*value),
                        Some(Extension::Index { index, span }) => {
                            match self.address_number(name, index, *span) {
                                Some(number) => setting.set_number(number),
                                None => return,
                            }
                        }
                        None => {}
                    },
                    Operand::None | Operand::NumberAxis | Operand::AxisPair => {}
                }
                self.push_setting(setting, span, plan);
            }
            AddressRole::AdditiveOffset => {
                let ok = match &value {
                    Value::Const(d) => *d >= 0.0 && d.fract() == 0.0,
                    Value::Expr(_) => true,
                };
                if !ok {
                    return self.diagnostics.push(
                        Diagnostic::new(
                            codes::lower::INVALID_VALUE,
                            "`DL` takes a whole number ≥ 0",
                        )
                        .with_label(span, "not a DL number"),
                    );
                }
                let key = (address, None, None);
                if let Some((_, first)) = plan.address_keys.iter().find(|(k, _)| *k == key) {
                    return self.repeated(name, span, *first);
                }
                plan.address_keys.push((key, span));
                plan.after_edge.push((
                    Op::Address(Box::new(Address::new(address, value, AddressScope::Modal))),
                    span,
                ));
            }
            AddressRole::Target => plan.add_target(
                AxisValue {
                    axis: Cow::Borrowed(name),
                    value,
                    mode,
                },
                span,
            ),
            AddressRole::IndirectAxis => match self.bracket_axis(word, span) {
                Some(AxisRef::Named(name)) => plan.add_target(
                    AxisValue {
                        axis: Cow::Owned(name),
                        value,
                        mode,
                    },
                    span,
                ),
                Some(AxisRef::Computed(axis)) => {
                    plan.indirect_targets
                        .push(IndirectAxisValue { axis, value, mode });
                    plan.motion_span.get_or_insert(span);
                }
                None => {}
            },
            AddressRole::Transition(kind) => {
                if let Some((_, first)) = &plan.transition {
                    return self.repeated("CHF/CHR/RND", span, *first);
                }
                plan.transition = Some((gcodec_ail::Transition { kind, value }, span));
            }
            AddressRole::Weight | AddressRole::Interval => {
                let slot = if role == AddressRole::Weight {
                    &mut plan.spline.weight
                } else {
                    &mut plan.spline.interval
                };
                if slot.is_some() {
                    return self.repeated(name, span, span);
                }
                *slot = Some(value);
                plan.spline_span.get_or_insert(span);
            }
        }
    }

    /// An `address` instruction of a setting, unless the block wrote it
    /// already (same axis and extension).
    fn push_setting(&mut self, setting: Address, span: Span, plan: &mut BlockPlan) {
        let constant = setting.axis_expr.is_none()
            && setting.extension_expr.is_none()
            && setting.leading_axis_expr.is_none();
        if constant {
            let key = (setting.address, setting.axis.clone(), setting.extension);
            if let Some((_, first)) = plan.address_keys.iter().find(|(k, _)| *k == key) {
                return self.repeated(setting.address.name(), span, *first);
            }
            plan.address_keys.push((key, span));
        }
        plan.addresses.push((Op::Address(Box::new(setting)), span));
    }

    /// The number in `TOFFL[1]`, `FMA[2,X]`: a whole number ≥ 0, or
    /// computed when the block runs.
    fn address_number(
        &mut self,
        name: &str,
        index: &ast::Expr,
        span: Span,
    ) -> Option<AddressNumber> {
        match values::constant(index) {
            Some(n) if n >= 0.0 && n.fract() == 0.0 && n <= f64::from(u32::MAX) => {
                Some(AddressNumber::Constant(n as u32))
            }
            Some(_) => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::INVALID_VALUE,
                        format!(
                            "`{name}[{}]` takes a whole number ≥ 0 in brackets",
                            values::source_text(index)
                        ),
                    )
                    .with_label(span, "not a whole number ≥ 0"),
                );
                None
            }
            None => {
                self.check_variables(index);
                Some(AddressNumber::Computed(values::tree(index)))
            }
        }
    }

    /// `FMA[2,X]=…`, `CPLNUM[X,Y]=…`: a setting with two values in
    /// brackets, a number or the following axis, then an axis.
    fn place_two_index_setting(
        &mut self,
        address: NamedAddress,
        (first, second): (&ast::Expr, &ast::Expr),
        value: Value,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let AddressRole::Setting { scope, operand } = address.role() else {
            return;
        };
        let name = address.name();
        let mut setting = Address::new(address, value, scope);
        match operand {
            Operand::NumberAxis => {
                let number = self.address_number(name, first, first.span);
                let axis = self.axis_in_brackets(name, second);
                let (Some(number), Some(axis)) = (number, axis) else {
                    return;
                };
                setting.set_number(number);
                setting.set_axis(axis);
            }
            Operand::AxisPair => {
                let following = self.axis_in_brackets(name, first);
                let leading = self.axis_in_brackets(name, second);
                let (Some(following), Some(leading)) = (following, leading) else {
                    return;
                };
                setting.set_axis(following);
                match leading {
                    AxisRef::Named(axis) => setting.leading_axis = Some(axis),
                    AxisRef::Computed(axis) => setting.leading_axis_expr = Some(axis),
                }
            }
            _ => {
                return self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::EXTENSION_NOT_ALLOWED,
                        format!("`{name}` takes at most one value in brackets"),
                    )
                    .with_label(second.span, "second value")
                    .with_help("only `FMA[n,axis]` and the generic coupling's `CPL…[following,leading]` take two (reference §2.2)"),
                );
            }
        }
        self.push_setting(setting, span, plan);
    }

    fn repeated(&mut self, address: &str, span: Span, first: Span) {
        let mut d = Diagnostic::new(
            codes::lower::ADDRESS_REPEATED,
            format!("`{address}` is programmed twice in one block"),
        )
        .with_label(span, "again");
        if first != span {
            d = d.with_label(first, "first");
        }
        self.diagnostics
            .push(d.with_help("the control allows an address once per block (alarm 12010)"));
    }

    /// `XV=10`, `XV=IC(5)`: an axis target of the block.
    fn axis_assignment(
        &mut self,
        axis: AxisKind,
        target: &ast::VarRef,
        expr: &ast::Expr,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        self.check_variables(expr);
        let (value, mode) = match &expr.kind {
            ast::ExprKind::Call(call) if call.args.len() == 1 => {
                match (DimensionMode::from_name(&call.name), &call.args[0]) {
                    (Some(kind), Some(arg)) => {
                        use DimensionMode::*;
                        let allowed = match kind {
                            Dc | Acp | Acn => axis != AxisKind::Linear,
                            Dac | Dic | Rac | Ric => axis != AxisKind::Rotary,
                            _ => true,
                        };
                        if !allowed {
                            return self.diagnostics.push(
                                Diagnostic::new(
                                    codes::lower::MODIFIER_NOT_ALLOWED,
                                    format!(
                                        "`{}` is not allowed on `{}`",
                                        kind.keyword(),
                                        target.name
                                    ),
                                )
                                .with_label(call.name_span, "dimension modifier")
                                .with_help("DC, ACP and ACN position rotary axes; DAC, DIC, RAC and RIC apply to linear axes"),
                            );
                        }
                        (values::value(arg), Some(kind))
                    }
                    _ => (values::value(expr), None),
                }
            }
            _ => (values::value(expr), None),
        };
        plan.add_target(
            AxisValue {
                axis: Cow::Owned(target.name.to_ascii_uppercase().to_string()),
                value,
                mode,
            },
            span,
        );
    }

    /// `FAD=5`, `SPOS2=90`: named addresses the parser reads as
    /// assignments to a name (it knows no `FAD`, and `SPOS2=` is not one
    /// of its extension forms). `false` when the statement is something
    /// else.
    pub(super) fn address_assignment(
        &mut self,
        assign: &ast::Assign,
        span: Span,
        plan: &mut BlockPlan,
    ) -> bool {
        let target = &assign.target;
        if target.kind != ast::VarKind::Name {
            return false;
        }
        // `XV=10`: an axis whose name is longer than a letter and a number
        // reads as an assignment too.
        if target.indices.is_empty()
            && let ast::Initializer::Expr(expr) = &assign.value
            && let Some(axis) = self.axis_kind(&target.name)
        {
            self.axis_assignment(axis, target, expr, span, plan);
            return true;
        }
        let upper = target.name.to_ascii_uppercase();
        let (named, spindle) = match NamedAddress::named(&upper) {
            Some(named) if !is_written_as_address(&upper) => (named, None),
            _ => {
                let digits_at = upper
                    .find(|c: char| c.is_ascii_digit())
                    .unwrap_or(upper.len());
                let (head, digits) = upper.split_at(digits_at);
                // `SPOS2=90`; `FA2=400`, a number where the address takes
                // an axis in brackets (`extension_not_allowed`).
                let numbered = |named: NamedAddress| {
                    matches!(
                        named.role(),
                        AddressRole::Setting {
                            operand: Operand::Spindle | Operand::Axis,
                            ..
                        }
                    )
                };
                match (NamedAddress::named(head), digits.parse::<u32>()) {
                    (Some(named), Ok(n))
                        if numbered(named) && digits.len() <= 2 && target.indices.is_empty() =>
                    {
                        (named, Some(n))
                    }
                    _ => return false,
                }
            }
        };
        // A variable of the program's own named like an address (`DEF
        // REAL OSE` in a definition file) stays that variable.
        if self.outline.names.declares(&target.name, target.span.start) {
            return false;
        }
        let address = named.name();
        let ast::Initializer::Expr(expr) = &assign.value else {
            // `MEASA[X]=(1,1,-1)`: a list of values.
            self.not_lowered(span, &format!("the list of values of `{address}`"));
            return true;
        };
        match target.indices.as_slice() {
            [] | [_] => {}
            [first, second] => {
                self.check_variables(expr);
                let value = values::value(expr);
                self.place_two_index_setting(named, (first, second), value, span, plan);
                return true;
            }
            [_, _, third, ..] => {
                self.diagnostics.push(
                    Diagnostic::new(
                        codes::lower::EXTENSION_NOT_ALLOWED,
                        format!("`{address}` takes at most two values in brackets"),
                    )
                    .with_label(third.span, "third value"),
                );
                return true;
            }
        }
        self.check_variables(expr);
        // `SPOS2=DC(90)`: the modifier is a call in an assignment.
        let (value, mode) = match &expr.kind {
            ast::ExprKind::Call(call) if call.args.len() == 1 => {
                match (DimensionMode::from_name(&call.name), &call.args[0]) {
                    (Some(kind), Some(arg)) => {
                        if spindle.is_none() {
                            self.diagnostics.push(
                                Diagnostic::new(
                                    codes::lower::MODIFIER_NOT_ALLOWED,
                                    format!("`{}` is not allowed on `{address}`", kind.keyword()),
                                )
                                .with_label(call.name_span, "dimension modifier")
                                .with_help(format!("`{address}` takes a plain value")),
                            );
                            return true;
                        }
                        if !matches!(
                            kind,
                            DimensionMode::Ac
                                | DimensionMode::Ic
                                | DimensionMode::Dc
                                | DimensionMode::Acp
                                | DimensionMode::Acn
                        ) {
                            self.diagnostics.push(
                                Diagnostic::new(
                                    codes::lower::MODIFIER_NOT_ALLOWED,
                                    format!("`{}` is not allowed on `{address}`", kind.keyword()),
                                )
                                .with_label(call.name_span, "dimension modifier")
                                .with_help("spindle positions take AC, IC, DC, ACP or ACN"),
                            );
                            return true;
                        }
                        (values::value(arg), Some(kind))
                    }
                    _ => (values::value(expr), None),
                }
            }
            _ => (values::value(expr), None),
        };
        let extension = match target.indices.first() {
            Some(index) => Some(Extension::Index {
                span: index.span,
                index: Box::new(index.clone()),
            }),
            None => spindle.map(|value| Extension::Number { span, value }),
        };
        let word = Word::new(
            span,
            address,
            target.span,
            extension.clone(),
            WordValue::Assigned {
                modifier: None,
                expr: Box::new(expr.clone()),
            },
        );
        self.place_address(named, extension.as_ref(), value, mode, &word, span, plan);
        true
    }

    /// `H5`, `H2=5`, `H[I]=5`, `H=QU(7)` (reference §4.5).
    pub(super) fn h_word(
        &mut self,
        word: &Word,
        value: &WordValue,
        span: Span,
        plan: &mut BlockPlan,
    ) {
        let out_of_range = |at: Span| {
            Diagnostic::new(
                codes::lower::INVALID_VALUE,
                format!(
                    "H extension {} is out of range",
                    values::written(self.source, at)
                ),
            )
            .with_label(at, "out of range")
            .with_help("H extensions are 0…99")
        };
        let (extension, extension_expr) = match word.extension() {
            None => (None, None),
            Some(Extension::Number { value, span: at }) => {
                if *value > 99 {
                    return self.diagnostics.push(out_of_range(*at));
                }
                (Some(*value), None)
            }
            Some(Extension::Index { index, span: at }) => match values::constant(index) {
                // Whole and in 0…99: the cast is exact.
                Some(n) if (0.0..=99.0).contains(&n) && n.fract() == 0.0 => (Some(n as u32), None),
                Some(_) => return self.diagnostics.push(out_of_range(*at)),
                None => {
                    self.check_variables(index);
                    (None, Some(values::tree(index)))
                }
            },
        };
        // `H=QU(7)`: quick output of the value.
        let (expr, quick) = match value {
            WordValue::Assigned { expr, .. } => match &expr.kind {
                ast::ExprKind::Call(call)
                    if call.name.eq_ignore_ascii_case("QU") && call.args.len() == 1 =>
                {
                    match &call.args[0] {
                        Some(arg) => (Some(arg), true),
                        None => (Some(&**expr), false),
                    }
                }
                _ => (Some(&**expr), false),
            },
            WordValue::Constant(_) => (None, false),
        };
        let (h_value, h_expr) = match (value, expr) {
            (WordValue::Constant(n), _) => (Some(n.value), None),
            (_, Some(e)) => match values::constant(e) {
                Some(v) => (Some(v), None),
                None => (None, Some(values::tree(e))),
            },
            _ => (None, None),
        };
        if h_value.is_some_and(|v| v.abs() > f64::from(f32::MAX)) {
            let written = match expr {
                Some(e) => values::written(self.source, e.span),
                None => values::written_number(self.source, value),
            };
            return self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::INVALID_VALUE,
                    format!("H value {written} is out of range"),
                )
                .with_label(span, "out of range")
                .with_help("H values range over ±3.4028e38"),
            );
        }
        let ext_text = match (&extension, word.extension()) {
            (Some(n), _) => n.to_string(),
            (None, Some(Extension::Index { index, .. })) => {
                format!("[{}]", values::source_text(index))
            }
            _ => String::new(),
        };
        let value_text = match (h_value, expr) {
            (_, Some(e)) if quick => format!("QU({})", values::source_text(e)),
            (Some(v), _) => v.to_string(),
            (None, Some(e)) => values::source_text(e),
            (None, None) => String::new(),
        };
        let raw = if ext_text.is_empty() && !quick && h_expr.is_none() {
            format!("H{value_text}")
        } else {
            format!("H{ext_text}={value_text}")
        };
        plan.h_functions.push((
            Op::HFunction(Box::new(HFunction {
                h_value,
                h_expr,
                address_extension: extension,
                address_extension_expr: extension_expr,
                quick,
                timing: MTiming::InBlock,
                raw,
            })),
            span,
        ));
    }

    /// `PW=`, `PL=`, `CHF=`, `CHR=`, `RND=` in a block without motion:
    /// `address` instructions of block scope, for the executor to judge.
    pub(super) fn unattached_motion_data(
        &mut self,
        index: usize,
        spline_span: Option<Span>,
        transition: Option<(gcodec_ail::Transition, Span)>,
        spline: Option<gcodec_ail::SplineData>,
    ) {
        let span = spline_span.unwrap_or_default();
        let address = |address: NamedAddress, value: Value| {
            Op::Address(Box::new(Address::new(address, value, AddressScope::Block)))
        };
        if let Some(spline) = spline {
            if let Some(v) = spline.weight {
                self.emit(index, span, address(NamedAddress::Pw, v));
            }
            if let Some(v) = spline.interval {
                self.emit(index, span, address(NamedAddress::Pl, v));
            }
        }
        if let Some((t, at)) = transition {
            let named = match t.kind {
                TransitionKind::Chamfer => NamedAddress::Chf,
                TransitionKind::ChamferLeg => NamedAddress::Chr,
                TransitionKind::Rounding => NamedAddress::Rnd,
            };
            self.emit(index, at, address(named, t.value));
        }
    }

    /// `G4 F…` / `G4 S…`: the dwell of a block with `G4`, taking the
    /// block's F and S values (which then are no feed or speed). `G4`
    /// needs a block of its own (reference §2.7).
    pub(super) fn dwell(&mut self, block: &ast::Block, g4: Span, plan: &mut BlockPlan) -> Op {
        let mut others = Vec::new();
        for statement in &block.statements {
            let StatementKind::Word(word) = &statement.kind else {
                others.push(statement.span);
                continue;
            };
            let ok = match word.address() {
                "G" => statement.span == g4,
                "F" => true,
                "S" => word.extension().is_none(),
                _ => false,
            };
            if !ok {
                others.push(statement.span);
            }
        }
        if !others.is_empty() {
            let mut d = Diagnostic::new(
                codes::lower::DWELL_NOT_ALONE,
                "`G4` must be alone in its block",
            )
            .with_label(g4, "dwell");
            for at in others {
                d = d.with_label(at, "also in the block");
            }
            self.diagnostics.push(d.with_help(
                "the control programs a dwell in a block of its own: `G4 F<seconds>` or `G4 S<revolutions>`",
            ));
        }
        let seconds = plan.feed.take().map(|(v, _)| v);
        let revolutions = match plan
            .spindle
            .iter()
            .position(|s| s.0.is_none() && s.1.is_none())
        {
            Some(i) => Some(plan.spindle.remove(i).2),
            None => None,
        };
        if seconds.is_none() && revolutions.is_none() {
            self.diagnostics.push(
                Diagnostic::new(
                    codes::lower::DWELL_WITHOUT_TIME,
                    "`G4` without a dwell time",
                )
                .with_label(g4, "dwell")
                .with_help("write `G4 F<seconds>` or `G4 S<revolutions of the master spindle>`"),
            );
        }
        Op::Dwell {
            seconds,
            revolutions,
        }
    }
}
