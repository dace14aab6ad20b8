//! Values, expression evaluation and variables of the executor (SPEC
//! §11.x). Expected values are worked out by hand; where the control's
//! behaviour is a choice, the test names it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::borrow::Cow;
use std::cell::Cell;
use std::collections::HashMap;

use gcodec_ail::{Callee, Expr, Op, Value, VarKind, VarName};
use gcodec_exec::eval::{
    self, Env, NoMachine, RuntimeInterface, assign, assign_list, declare, eval, sprint,
};
use gcodec_exec::value::{RtValue, RunError};
use gcodec_exec::vars::{DEFAULT_R_PARAMETERS, Init, Scope, Variables};
use gcodec_lang::functions::Function;
use gcodec_lang::{BinaryOp as B, DataType, UnaryOp as U};
use gcodec_profile::Profile;
use gcodec_source::codes;

// ---------------------------------------------------------------------
// Counting allocations per thread

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

// ---------------------------------------------------------------------
// Building expressions

fn n(v: f64) -> Expr {
    Expr::Number { value: v }
}

fn s(v: &str) -> Expr {
    Expr::String {
        value: v.to_owned(),
    }
}

fn bool_(v: bool) -> Expr {
    Expr::Bool { value: v }
}

fn r(i: f64) -> Expr {
    Expr::Var {
        var_kind: VarKind::RParameter,
        name: VarName::Text(Cow::Borrowed("R")),
        indices: vec![n(i)],
    }
}

fn var(name: &str, indices: Vec<Expr>) -> Expr {
    Expr::Var {
        var_kind: VarKind::User,
        name: VarName::Text(Cow::Owned(name.to_owned())),
        indices,
    }
}

fn sys(name: &str, indices: Vec<Expr>) -> Expr {
    Expr::Var {
        var_kind: VarKind::System,
        name: VarName::named(Cow::Owned(name.to_owned())),
        indices,
    }
}

fn call(name: &str, args: Vec<Expr>) -> Expr {
    Expr::Call {
        name: Callee::named(name),
        args: args.into_iter().map(Some).collect(),
    }
}

fn bin(op: B, a: Expr, b: Expr) -> Expr {
    Expr::Binary {
        operator: op,
        lhs: Box::new(a),
        rhs: Box::new(b),
    }
}

fn un(op: U, a: Expr) -> Expr {
    Expr::Unary {
        operator: op,
        operand: Box::new(a),
    }
}

fn builtin() -> Profile {
    gcodec_profile::builtin().expect("built-in profile")
}

/// Evaluates with an empty store on the built-in profile.
fn ev(e: &Expr) -> Result<RtValue, RunError> {
    let vars = Variables::default();
    let profile = builtin();
    eval(&Env::new(&vars, &profile), e)
}

fn ok(e: Expr) -> RtValue {
    ev(&e).unwrap_or_else(|err| panic!("{e:?}: {err}"))
}

fn real(e: Expr) -> f64 {
    match ok(e) {
        RtValue::Real(x) => x,
        other => panic!("expected a REAL, got {other:?}"),
    }
}

fn err(e: Expr) -> RunError {
    match ev(&e) {
        Err(err) => err,
        Ok(v) => panic!("{e:?} gave {v:?}, expected an error"),
    }
}

fn text(e: Expr) -> String {
    match ok(e) {
        RtValue::String(t) => t.to_string(),
        other => panic!("expected a STRING, got {other:?}"),
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

// ---------------------------------------------------------------------
// Operators (reference §7.5)

#[test]
fn arithmetic_keeps_int_and_promotes_to_real() {
    assert_eq!(ok(bin(B::Add, n(2.0), n(3.0))), RtValue::Int(5));
    assert_eq!(ok(bin(B::Sub, n(2.0), n(3.0))), RtValue::Int(-1));
    assert_eq!(ok(bin(B::Mul, n(4.0), n(2.5))), RtValue::Real(10.0));
    // `/` is always REAL: 7/2 = 3.5, not 3.
    assert_eq!(ok(bin(B::Div, n(7.0), n(2.0))), RtValue::Real(3.5));
    // An INT result outside the INT range becomes REAL.
    assert_eq!(
        ok(bin(B::Mul, n(65536.0), n(65536.0))),
        RtValue::Real(4_294_967_296.0)
    );
    // BOOL and CHAR count as their numbers.
    assert_eq!(ok(bin(B::Add, bool_(true), n(1.0))), RtValue::Int(2));
    assert_eq!(ok(un(U::Neg, n(4.0))), RtValue::Int(-4));
    assert_eq!(ok(un(U::Neg, n(0.5))), RtValue::Real(-0.5));
}

#[test]
fn div_truncates_and_mod_takes_the_sign_of_the_dividend() {
    assert_eq!(ok(bin(B::IntDiv, n(7.0), n(2.0))), RtValue::Int(3));
    // DIV truncates towards zero: -7 DIV 2 = -3 (not -4).
    assert_eq!(ok(bin(B::IntDiv, n(-7.0), n(2.0))), RtValue::Int(-3));
    assert_eq!(ok(bin(B::IntDiv, n(7.5), n(2.0))), RtValue::Int(3));
    // Choice (reference §7.5 names MOD without a rule for negative
    // operands): the remainder of the truncating division, as DIV is
    // truncating, so that a == (a DIV b)*b + a MOD b. -7 MOD 3 = -1.
    assert_eq!(ok(bin(B::Mod, n(7.0), n(3.0))), RtValue::Int(1));
    assert_eq!(ok(bin(B::Mod, n(-7.0), n(3.0))), RtValue::Int(-1));
    assert_eq!(ok(bin(B::Mod, n(7.0), n(-3.0))), RtValue::Int(1));
    // REAL MOD: 7.5 MOD 2 = 1.5.
    assert_eq!(ok(bin(B::Mod, n(7.5), n(2.0))), RtValue::Real(1.5));
}

#[test]
fn division_by_zero_is_an_error_with_its_code() {
    for op in [B::Div, B::IntDiv, B::Mod] {
        let e = err(bin(op, n(1.0), n(0.0)));
        assert_eq!(e.code, codes::run::DIVISION_BY_ZERO, "{op:?}");
        assert_eq!(
            err(bin(op, n(1.5), n(0.0))).code,
            codes::run::DIVISION_BY_ZERO,
            "{op:?}"
        );
    }
    assert_eq!(
        codes::run::DIVISION_BY_ZERO,
        "gcodec::run::division_by_zero"
    );
}

#[test]
fn bitwise_and_logical_operators() {
    assert_eq!(ok(bin(B::BAnd, n(12.0), n(10.0))), RtValue::Int(8));
    assert_eq!(ok(bin(B::BOr, n(12.0), n(10.0))), RtValue::Int(14));
    assert_eq!(ok(bin(B::BXor, n(12.0), n(10.0))), RtValue::Int(6));
    assert_eq!(ok(un(U::BNot, n(0.0))), RtValue::Int(-1));
    assert_eq!(ok(un(U::BNot, n(5.0))), RtValue::Int(-6));
    assert_eq!(
        ok(bin(B::And, bool_(true), bool_(false))),
        RtValue::Bool(false)
    );
    assert_eq!(
        ok(bin(B::Or, bool_(true), bool_(false))),
        RtValue::Bool(true)
    );
    assert_eq!(
        ok(bin(B::Xor, bool_(true), bool_(true))),
        RtValue::Bool(false)
    );
    // Numbers are truth values: not 0 is TRUE.
    assert_eq!(ok(bin(B::And, n(2.0), n(0.5))), RtValue::Bool(true));
    assert_eq!(ok(un(U::Not, n(0.0))), RtValue::Bool(true));
    assert_eq!(
        err(bin(B::BAnd, s("A"), n(1.0))).code,
        codes::run::TYPE_MISMATCH
    );
}

#[test]
fn comparisons_of_reals_are_relative() {
    assert_eq!(ok(bin(B::Eq, n(3.0), n(3.0))), RtValue::Bool(true));
    assert_eq!(ok(bin(B::Lt, n(2.0), n(3.0))), RtValue::Bool(true));
    assert_eq!(ok(bin(B::Ge, n(2.0), n(3.0))), RtValue::Bool(false));
    assert_eq!(ok(bin(B::Ne, n(2.0), n(3.0))), RtValue::Bool(true));
    // 0.1 + 0.2 == 0.3 holds on the control (relative 1e-12) though not
    // in IEEE arithmetic; and 0.1 + 0.2 > 0.3 does not.
    let sum = bin(B::Add, n(0.1), n(0.2));
    assert_eq!(ok(bin(B::Eq, sum.clone(), n(0.3))), RtValue::Bool(true));
    assert_eq!(ok(bin(B::Gt, sum.clone(), n(0.3))), RtValue::Bool(false));
    assert_eq!(ok(bin(B::Le, sum, n(0.3))), RtValue::Bool(true));
    // A difference of 1e-9 is a difference.
    assert_eq!(ok(bin(B::Eq, n(1.000000001), n(1.0))), RtValue::Bool(false));
    // Strings compare by bytes; a CHAR is a one-character string.
    assert_eq!(ok(bin(B::Eq, s("AB"), s("AB"))), RtValue::Bool(true));
    assert_eq!(ok(bin(B::Lt, s("AB"), s("AC"))), RtValue::Bool(true));
    assert_eq!(
        err(bin(B::Eq, s("1"), n(1.0))).code,
        codes::run::TYPE_MISMATCH
    );
}

#[test]
fn concatenation_formats_numbers_as_the_control_does() {
    assert_eq!(text(bin(B::Concat, s("N"), n(10.0))), "N10");
    assert_eq!(text(bin(B::Concat, s("X="), n(1.5))), "X=1.5");
    assert_eq!(text(bin(B::Concat, s(""), n(-2.25))), "-2.25");
    // A REAL with at most 10 decimal places, trailing zeros left off.
    assert_eq!(
        text(bin(B::Concat, s(""), bin(B::Div, n(1.0), n(3.0)))),
        "0.3333333333"
    );
    assert_eq!(
        text(bin(B::Concat, s(""), bin(B::Div, n(6.0), n(2.0)))),
        "3"
    );
    // BOOL as 1/0.
    assert_eq!(text(bin(B::Concat, s("B"), bool_(true))), "B1");
    assert_eq!(text(un(U::ToString, n(42.0))), "42");
    assert_eq!(text(bin(B::Concat, n(1.0), n(2.0))), "12");
}

// ---------------------------------------------------------------------
// Built-in functions (reference §7.6)

#[test]
fn trigonometry_is_in_degrees() {
    assert_eq!(real(call("SIN", vec![n(30.0)])), 0.5);
    assert_eq!(real(call("COS", vec![n(60.0)])), 0.5);
    assert_eq!(real(call("COS", vec![n(90.0)])), 0.0);
    assert_eq!(real(call("SIN", vec![n(-90.0)])), -1.0);
    assert_eq!(real(call("SIN", vec![n(390.0)])), 0.5);
    assert!(close(real(call("TAN", vec![n(45.0)])), 1.0));
    assert!(close(
        real(call("SIN", vec![n(45.0)])),
        std::f64::consts::FRAC_1_SQRT_2
    ));
    assert_eq!(real(call("ATAN2", vec![n(1.0), n(1.0)])), 45.0);
    assert_eq!(real(call("ATAN2", vec![n(1.0), n(-1.0)])), 135.0);
    assert_eq!(real(call("ASIN", vec![n(0.5)])), 30.0);
    assert_eq!(real(call("ACOS", vec![n(0.5)])), 60.0);
    assert_eq!(err(call("ASIN", vec![n(2.0)])).code, codes::run::DOMAIN);
    assert_eq!(err(call("TAN", vec![n(90.0)])).code, codes::run::DOMAIN);
}

#[test]
fn arithmetic_functions() {
    assert_eq!(real(call("ABS", vec![n(-3.5)])), 3.5);
    assert_eq!(real(call("SQRT", vec![n(16.0)])), 4.0);
    assert_eq!(real(call("POT", vec![n(3.0)])), 9.0);
    assert_eq!(real(call("TRUNC", vec![n(-3.7)])), -3.0);
    assert_eq!(real(call("ROUND", vec![n(2.5)])), 3.0);
    assert_eq!(real(call("ROUND", vec![n(-2.5)])), -3.0);
    assert_eq!(real(call("ROUNDUP", vec![n(3.1)])), 4.0);
    assert_eq!(real(call("ROUNDUP", vec![n(-3.1)])), -3.0);
    assert_eq!(real(call("ROUNDUP", vec![n(3.0)])), 3.0);
    assert!(close(real(call("LN", vec![n(std::f64::consts::E)])), 1.0));
    assert_eq!(real(call("EXP", vec![n(0.0)])), 1.0);
    assert_eq!(real(call("MINVAL", vec![n(3.0), n(-1.0)])), -1.0);
    assert_eq!(real(call("MAXVAL", vec![n(3.0), n(-1.0)])), 3.0);
    assert_eq!(real(call("BOUND", vec![n(0.0), n(10.0), n(12.0)])), 10.0);
    assert_eq!(real(call("BOUND", vec![n(0.0), n(10.0), n(-2.0)])), 0.0);
    assert_eq!(real(call("BOUND", vec![n(0.0), n(10.0), n(4.0)])), 4.0);
    let e = err(call("SQRT", vec![n(-1.0)]));
    assert_eq!(e.code, codes::run::DOMAIN);
    assert!(e.message.contains("SQRT"), "{}", e.message);
    assert_eq!(err(call("LN", vec![n(0.0)])).code, codes::run::DOMAIN);
}

#[test]
fn conversion_functions() {
    assert_eq!(ok(call("RTOI", vec![n(2.5)])), RtValue::Int(3));
    assert_eq!(ok(call("RTOI", vec![n(-2.5)])), RtValue::Int(-3));
    assert_eq!(ok(call("RTOI", vec![n(2.4)])), RtValue::Int(2));
    assert_eq!(err(call("RTOI", vec![n(1e10)])).code, codes::run::OVERFLOW);
    assert_eq!(ok(call("ITOR", vec![n(2.0)])), RtValue::Real(2.0));
    assert_eq!(ok(call("RTOB", vec![n(0.0)])), RtValue::Bool(false));
    assert_eq!(ok(call("RTOB", vec![n(0.1)])), RtValue::Bool(true));
    assert_eq!(ok(call("ITOB", vec![n(-3.0)])), RtValue::Bool(true));
    assert_eq!(ok(call("BTOI", vec![bool_(true)])), RtValue::Int(1));
    assert_eq!(ok(call("BTOR", vec![bool_(false)])), RtValue::Real(0.0));
    assert_eq!(ok(call("NUMBER", vec![s(" -1.5 ")])), RtValue::Real(-1.5));
    assert_eq!(ok(call("NUMBER", vec![s("2EX3")])), RtValue::Real(2000.0));
    assert_eq!(
        err(call("NUMBER", vec![s("1.5MM")])).code,
        codes::run::INVALID_NUMBER
    );
    assert_eq!(ok(call("ISNUMBER", vec![s("12")])), RtValue::Bool(true));
    assert_eq!(ok(call("ISNUMBER", vec![s("inf")])), RtValue::Bool(false));
    assert_eq!(ok(call("ISNUMBER", vec![s("")])), RtValue::Bool(false));
    assert_eq!(ok(call("AXNAME", vec![s("y")])), RtValue::axis("Y"));
    assert_eq!(
        err(call("AXNAME", vec![s("Q")])).code,
        codes::run::UNKNOWN_AXIS
    );
    // An axis name as a value: `AXSTRING(Z)`.
    assert_eq!(text(call("AXSTRING", vec![var("Z", vec![])])), "Z");
    assert_eq!(
        err(call("AXSTRING", vec![n(1.0)])).code,
        codes::run::TYPE_MISMATCH
    );
}

#[test]
fn string_functions() {
    let t = || s("HELLO WORLD");
    assert_eq!(ok(call("STRLEN", vec![t()])), RtValue::Int(11));
    assert_eq!(ok(call("INDEX", vec![t(), s("O")])), RtValue::Int(4));
    assert_eq!(ok(call("RINDEX", vec![t(), s("O")])), RtValue::Int(7));
    assert_eq!(ok(call("INDEX", vec![t(), s("Q")])), RtValue::Int(-1));
    assert_eq!(ok(call("MINDEX", vec![t(), s("WL")])), RtValue::Int(2));
    assert_eq!(ok(call("MATCH", vec![t(), s("WOR")])), RtValue::Int(6));
    assert_eq!(ok(call("MATCH", vec![t(), s("XYZ")])), RtValue::Int(-1));
    assert_eq!(text(call("SUBSTR", vec![t(), n(6.0), n(3.0)])), "WOR");
    assert_eq!(text(call("SUBSTR", vec![t(), n(6.0)])), "WORLD");
    // Past the end is cut off.
    assert_eq!(text(call("SUBSTR", vec![t(), n(9.0), n(10.0)])), "LD");
    assert_eq!(
        err(call("SUBSTR", vec![t(), n(-1.0)])).code,
        codes::run::INDEX_OUT_OF_RANGE
    );
    assert_eq!(text(call("TOLOWER", vec![s("AbC1")])), "abc1");
    assert_eq!(text(call("TOUPPER", vec![s("AbC1")])), "ABC1");
    // A CHAR where a one-character string is needed.
    assert_eq!(
        err(call("INDEX", vec![t(), s("OR")])).code,
        codes::run::TYPE_MISMATCH
    );
}

#[test]
fn sprint_directives() {
    let v = |x: &[RtValue]| x.to_vec();
    assert_eq!(
        sprint("T=%D D=%D", &v(&[RtValue::Int(5), RtValue::Real(2.6)])).unwrap(),
        "T=5 D=3"
    );
    assert_eq!(sprint("%F", &v(&[RtValue::Real(1.5)])).unwrap(), "1.500000");
    assert_eq!(
        sprint("%.3F", &v(&[RtValue::Real(2.0 / 3.0)])).unwrap(),
        "0.667"
    );
    assert_eq!(
        sprint("[%8.2F]", &v(&[RtValue::Real(-12.345)])).unwrap(),
        "[  -12.35]"
    );
    assert_eq!(sprint("[%4D]", &v(&[RtValue::Int(42)])).unwrap(), "[  42]");
    assert_eq!(
        sprint("%E", &v(&[RtValue::Real(150.0)])).unwrap(),
        "1.500000e+02"
    );
    assert_eq!(
        sprint("%G", &v(&[RtValue::Real(0.0001)])).unwrap(),
        "0.0001"
    );
    assert_eq!(
        sprint("%G", &v(&[RtValue::Real(1234567.0)])).unwrap(),
        "1.23457e+06"
    );
    assert_eq!(
        sprint(
            "%S-%C-%B-%X",
            &v(&[
                RtValue::from("AB"),
                RtValue::Char(b'Z'),
                RtValue::Bool(true),
                RtValue::Int(255)
            ])
        )
        .unwrap(),
        "AB-Z-TRUE-FF"
    );
    assert_eq!(sprint("100%%", &[]).unwrap(), "100%");
    assert_eq!(
        sprint("%Q", &v(&[RtValue::Int(1)])).unwrap_err().code,
        codes::run::FORMAT
    );
    assert_eq!(
        sprint("%D %D", &v(&[RtValue::Int(1)])).unwrap_err().code,
        codes::run::ARGUMENT_COUNT
    );
    // Through the evaluator.
    assert_eq!(text(call("SPRINT", vec![s("R=%.1F"), n(2.25)])), "R=2.2");
}

#[test]
fn function_errors_have_codes() {
    let e = err(call("NOSUCH", vec![n(1.0)]));
    assert_eq!(e.code, "gcodec::run::unknown_function");
    assert!(e.message.contains("NOSUCH"));
    assert_eq!(err(call("SIN", vec![])).code, codes::run::ARGUMENT_COUNT);
    assert_eq!(
        err(call("SIN", vec![n(1.0), n(2.0)])).code,
        codes::run::ARGUMENT_COUNT
    );
    assert_eq!(
        err(call("SIN", vec![s("A")])).code,
        codes::run::TYPE_MISMATCH
    );
    let omitted = Expr::Call {
        name: Callee::named("ATAN2"),
        args: vec![Some(n(1.0)), None],
    };
    assert_eq!(err(omitted).code, codes::run::ARGUMENT_COUNT);
}

/// A runtime that provides one predefined function the evaluator does not
/// compute itself: the executor's hook for frame and tool-management
/// functions.
struct WithModaxval;

impl RuntimeInterface for WithModaxval {
    fn function(
        &self,
        function: Function,
        _args: &[Option<RtValue>],
    ) -> Option<Result<RtValue, RunError>> {
        (function == Function::Modaxval).then_some(Ok(RtValue::Real(10.0)))
    }
}

#[test]
fn the_runtime_provides_further_functions() {
    let vars = Variables::default();
    let e = call("MODAXVAL", vec![n(370.0)]);
    assert_eq!(
        eval(&Env::new(&vars, &WithModaxval), &e),
        Ok(RtValue::Real(10.0))
    );
    // Without the runtime's answer a predefined function is not simulated.
    assert_eq!(
        eval(&Env::new(&vars, &NoMachine), &e).unwrap_err().code,
        codes::run::NOT_SIMULATED
    );
    // A name the vocabulary does not list is no function of the runtime.
    let user = call("TWICE", vec![n(4.0)]);
    assert_eq!(
        eval(&Env::new(&vars, &WithModaxval), &user)
            .unwrap_err()
            .code,
        codes::run::UNKNOWN_FUNCTION
    );
}

// ---------------------------------------------------------------------
// Conversions (reference §7.1, SPEC §10.11 table)

#[test]
fn conversions_follow_the_control_table() {
    let int = DataType::Int;
    assert_eq!(RtValue::Real(2.5).convert_to(int), Ok(RtValue::Int(3)));
    assert_eq!(RtValue::Real(-2.5).convert_to(int), Ok(RtValue::Int(-3)));
    assert_eq!(RtValue::Real(2.49).convert_to(int), Ok(RtValue::Int(2)));
    assert_eq!(
        RtValue::Real(3e9).convert_to(int).unwrap_err().code,
        codes::run::OVERFLOW
    );
    assert_eq!(
        RtValue::Int(3).convert_to(DataType::Real),
        Ok(RtValue::Real(3.0))
    );
    assert_eq!(
        RtValue::Real(0.2).convert_to(DataType::Bool),
        Ok(RtValue::Bool(true))
    );
    assert_eq!(
        RtValue::Int(0).convert_to(DataType::Bool),
        Ok(RtValue::Bool(false))
    );
    assert_eq!(
        RtValue::Bool(true).convert_to(DataType::Real),
        Ok(RtValue::Real(1.0))
    );
    assert_eq!(
        RtValue::Int(65).convert_to(DataType::Char),
        Ok(RtValue::Char(b'A'))
    );
    assert_eq!(
        RtValue::Int(256)
            .convert_to(DataType::Char)
            .unwrap_err()
            .code,
        codes::run::OVERFLOW
    );
    let string = DataType::String { length: Some(5) };
    assert_eq!(
        RtValue::Char(b'A').convert_to(string),
        Ok(RtValue::from("A"))
    );
    assert_eq!(
        RtValue::from("ABCDEF").convert_to(string).unwrap_err().code,
        codes::run::STRING_TOO_LONG
    );
    // Nothing numeric into STRING, AXIS or FRAME.
    assert_eq!(
        RtValue::Int(1).convert_to(string).unwrap_err().code,
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        RtValue::Int(1).convert_to(DataType::Axis).unwrap_err().code,
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        RtValue::Int(1)
            .convert_to(DataType::Frame)
            .unwrap_err()
            .code,
        codes::run::TYPE_MISMATCH
    );
    // STRING into BOOL (empty is FALSE) and CHAR (one character).
    assert_eq!(
        RtValue::from("").convert_to(DataType::Bool),
        Ok(RtValue::Bool(false))
    );
    assert_eq!(
        RtValue::from("X").convert_to(DataType::Bool),
        Ok(RtValue::Bool(true))
    );
    assert_eq!(
        RtValue::from("X").convert_to(DataType::Char),
        Ok(RtValue::Char(b'X'))
    );
    assert_eq!(
        RtValue::from("XY")
            .convert_to(DataType::Char)
            .unwrap_err()
            .code,
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        RtValue::from("1").convert_to(int).unwrap_err().code,
        codes::run::TYPE_MISMATCH
    );
    assert_eq!(
        DataType::parse("STRING[12]"),
        Some(DataType::String { length: Some(12) })
    );
    assert_eq!(
        DataType::parse("string").and_then(DataType::string_capacity),
        Some(200)
    );
    assert_eq!(DataType::parse("STRING[0]"), None);
    assert_eq!(DataType::parse("DOUBLE"), None);
}

// ---------------------------------------------------------------------
// System variables from the profile

#[test]
fn system_variables_from_the_profile() {
    let profile = gcodec_testkit::machine(
        r#"
[work_offsets]
supported_group8_offsets = ["G500", "G54-G57"]
[work_offsets.values.G54]
X = -412.5
Z = 10.0
[[tools]]
number = 7
edges = [{ d = 1, length = 120.5, radius = 5.0 }]
"#,
    );
    let vars = Variables::default();
    let env = Env::new(&vars, &profile);
    let get = |e: Expr| eval(&env, &e);
    let comp = |n_: f64, axis: &str, c: &str| {
        sys("$P_UIFR", vec![n(n_), var(axis, vec![]), var(c, vec![])])
    };
    assert_eq!(get(comp(1.0, "X", "TR")), Ok(RtValue::Real(-412.5)));
    assert_eq!(get(comp(1.0, "Y", "TR")), Ok(RtValue::Real(0.0)));
    assert_eq!(get(comp(1.0, "X", "SC")), Ok(RtValue::Real(1.0)));
    assert_eq!(
        get(comp(7.0, "X", "TR")).unwrap_err().code,
        codes::run::INDEX_OUT_OF_RANGE
    );
    assert!(matches!(
        get(sys("$P_UIFR", vec![n(1.0)])),
        Ok(RtValue::Frame(_))
    ));
    assert_eq!(
        get(sys("$TC_DP3", vec![n(7.0), n(1.0)])),
        Ok(RtValue::Real(120.5))
    );
    assert_eq!(
        get(sys("$TC_DP6", vec![n(7.0), n(1.0)])),
        Ok(RtValue::Real(5.0))
    );
    assert_eq!(
        get(sys("$TC_DP12", vec![n(7.0), n(1.0)])),
        Ok(RtValue::Real(0.0))
    );
    assert_eq!(
        get(sys("$TC_DP3", vec![n(8.0), n(1.0)])).unwrap_err().code,
        codes::run::INDEX_OUT_OF_RANGE
    );
    assert_eq!(get(sys("$P_TOOLNO", vec![])), Ok(RtValue::Int(0)));
    assert_eq!(get(sys("$P_AXN3", vec![])), Ok(RtValue::axis("Z")));
    assert_eq!(
        get(sys("$MC_TOOL_CHANGE_MODE", vec![])),
        Ok(RtValue::Int(1))
    );
    assert_eq!(
        get(sys("$PI", vec![])),
        Ok(RtValue::Real(std::f64::consts::PI))
    );
    let e = get(sys("$AA_IM", vec![var("X", vec![])])).unwrap_err();
    assert_eq!(e.code, codes::run::SYSTEM_VARIABLE);
    assert!(e.message.contains("$AA_IM"), "{}", e.message);
    // `$R` are the R parameters.
    let mut vars = Variables::default();
    vars.set_r(4, 2.5).unwrap();
    let env = Env::new(&vars, &profile);
    assert_eq!(eval(&env, &sys("$R4", vec![])), Ok(RtValue::Real(2.5)));
    assert_eq!(eval(&env, &sys("$R", vec![n(4.0)])), Ok(RtValue::Real(2.5)));
    assert_eq!(
        eval(&env, &sys("$MC_MM_NUM_R_PARAM", vec![])),
        Ok(RtValue::Int(DEFAULT_R_PARAMETERS as i32))
    );
    // Without a machine only $PI.
    let env = Env::new(&vars, &NoMachine);
    assert_eq!(
        eval(&env, &sys("$P_TOOLNO", vec![])).unwrap_err().code,
        codes::run::SYSTEM_VARIABLE
    );
}

// ---------------------------------------------------------------------
// Variables

#[test]
fn r_parameters_have_the_default_count() {
    let profile = builtin();
    let mut vars = Variables::default();
    assert_eq!(vars.r_count(), 100);
    let target = r(99.0);
    assign(&mut vars, &mut builtin(), &target, &Value::Const(1.25)).unwrap();
    assert_eq!(vars.r(99), Ok(1.25));
    let e = assign(&mut vars, &mut builtin(), &r(100.0), &Value::Const(1.0)).unwrap_err();
    assert_eq!(e.code, codes::run::INDEX_OUT_OF_RANGE);
    assert!(e.message.contains("R100"), "{}", e.message);
    // R[R1+2]: a computed index.
    vars.set_r(1, 3.0).unwrap();
    vars.set_r(5, 7.0).unwrap();
    let idx = Expr::Var {
        var_kind: VarKind::RParameter,
        name: VarName::Text("R".into()),
        indices: vec![bin(B::Add, r(1.0), n(2.0))],
    };
    assert_eq!(
        eval(&Env::new(&vars, &profile), &idx),
        Ok(RtValue::Real(7.0))
    );
    // An R parameter is REAL: a string cannot be stored.
    let e = assign(
        &mut vars,
        &mut builtin(),
        &r(1.0),
        &Value::Expr(Box::new(s("A"))),
    )
    .unwrap_err();
    assert_eq!(e.code, codes::run::TYPE_MISMATCH);
}

#[test]
fn locals_are_per_level_and_globals_are_shared() {
    let profile = builtin();
    let mut vars = Variables::default();
    vars.declare(Scope::Global, "GCOUNT", DataType::Int, &[], Init::None)
        .unwrap();
    vars.declare(
        Scope::Local,
        "LOC",
        DataType::Real,
        &[],
        Init::List(&[Some(RtValue::Real(1.5))]),
    )
    .unwrap();
    let read = |vars: &Variables, name: &str| eval(&Env::new(vars, &profile), &var(name, vec![]));
    assert_eq!(read(&vars, "LOC"), Ok(RtValue::Real(1.5)));
    vars.push_level();
    assert_eq!(vars.level(), 2);
    // The caller's local is not seen from the subprogram…
    assert_eq!(
        read(&vars, "LOC").unwrap_err().code,
        codes::run::UNDEFINED_VARIABLE
    );
    // …the global is, and a write there is seen after the return.
    assign(
        &mut vars,
        &mut builtin(),
        &var("GCOUNT", vec![]),
        &Value::Const(4.0),
    )
    .unwrap();
    // A local of the same name in the subprogram hides nothing of the caller.
    vars.declare(
        Scope::Local,
        "LOC",
        DataType::Int,
        &[],
        Init::List(&[Some(RtValue::Int(9))]),
    )
    .unwrap();
    assert_eq!(read(&vars, "LOC"), Ok(RtValue::Int(9)));
    assert!(vars.pop_level());
    assert_eq!(read(&vars, "LOC"), Ok(RtValue::Real(1.5)));
    assert_eq!(read(&vars, "GCOUNT"), Ok(RtValue::Int(4)));
    assert!(!vars.pop_level(), "the main program's level stays");
    // With MD11120 the main program's variables are seen from below.
    vars.set_lud_extended_scope(true);
    vars.push_level();
    assert_eq!(read(&vars, "LOC"), Ok(RtValue::Real(1.5)));
    // Undefined names are errors naming them; an axis is a value.
    let e = read(&vars, "NOPE").unwrap_err();
    assert_eq!(e.code, codes::run::UNDEFINED_VARIABLE);
    assert!(e.message.contains("NOPE"));
    assert_eq!(read(&vars, "X"), Ok(RtValue::axis("X")));
}

#[test]
fn assignment_converts_to_the_declared_type() {
    let mut vars = Variables::default();
    let rt = &mut builtin();
    vars.declare(Scope::Local, "I", DataType::Int, &[], Init::None)
        .unwrap();
    vars.declare(Scope::Local, "FLAG", DataType::Bool, &[], Init::None)
        .unwrap();
    assign(&mut vars, rt, &var("I", vec![]), &Value::Const(2.5)).unwrap();
    assign(&mut vars, rt, &var("FLAG", vec![]), &Value::Const(3.0)).unwrap();
    assert_eq!(vars.read(VarKind::User, "I", &[]), Ok(RtValue::Int(3)));
    assert_eq!(
        vars.read(VarKind::User, "FLAG", &[]),
        Ok(RtValue::Bool(true))
    );
    let e = assign(
        &mut vars,
        rt,
        &var("I", vec![]),
        &Value::Expr(Box::new(s("A"))),
    )
    .unwrap_err();
    assert_eq!(e.code, codes::run::TYPE_MISMATCH);
    // Nothing was written.
    assert_eq!(vars.read(VarKind::User, "I", &[]), Ok(RtValue::Int(3)));
}

#[test]
fn strings_have_their_length_and_characters() {
    let mut vars = Variables::default();
    let rt = &mut builtin();
    vars.declare(
        Scope::Local,
        "TXT",
        DataType::String { length: Some(5) },
        &[],
        Init::List(&[Some(RtValue::from("ABC"))]),
    )
    .unwrap();
    // TXT[1] is the CHAR 'B'.
    let env_read = |vars: &Variables, e: Expr| eval(&Env::new(vars, &NoMachine), &e);
    assert_eq!(
        env_read(&vars, var("TXT", vec![n(1.0)])),
        Ok(RtValue::Char(b'B'))
    );
    assert_eq!(
        env_read(&vars, var("TXT", vec![n(3.0)])).unwrap_err().code,
        codes::run::INDEX_OUT_OF_RANGE
    );
    assign(
        &mut vars,
        rt,
        &var("TXT", vec![n(1.0)]),
        &Value::Expr(Box::new(s("X"))),
    )
    .unwrap();
    assert_eq!(
        vars.read(VarKind::User, "TXT", &[]),
        Ok(RtValue::from("AXC"))
    );
    let long = Value::Expr(Box::new(s("ABCDEF")));
    assert_eq!(
        assign(&mut vars, rt, &var("TXT", vec![]), &long)
            .unwrap_err()
            .code,
        codes::run::STRING_TOO_LONG
    );
    // A CHAR assigned to a STRING.
    assign(
        &mut vars,
        rt,
        &var("TXT", vec![]),
        &Value::Expr(Box::new(var("TXT", vec![n(2.0)]))),
    )
    .unwrap();
    assert_eq!(vars.read(VarKind::User, "TXT", &[]), Ok(RtValue::from("C")));
    // Concatenation builds the value written.
    let cat = bin(B::Concat, var("TXT", vec![]), n(12.0));
    assign(
        &mut vars,
        rt,
        &var("TXT", vec![]),
        &Value::Expr(Box::new(cat)),
    )
    .unwrap();
    assert_eq!(
        vars.read(VarKind::User, "TXT", &[]),
        Ok(RtValue::from("C12"))
    );
}

// ---------------------------------------------------------------------
// Lowered programs: declarations, arrays, lists, REP

/// Runs the variable instructions and jumps of a lowered program; the
/// other instructions are skipped.
fn run(src: &str) -> Variables {
    let profile = builtin();
    let lowered = gcodec_testkit::lower_clean("test.mpf", src.as_bytes(), &profile);
    assert!(!lowered.has_errors(), "{:#?}", lowered.diagnostics);
    run_document(&lowered.document, &profile)
}

fn run_document(doc: &gcodec_ail::Document, profile: &Profile) -> Variables {
    let mut rt = profile.clone();
    let mut vars = Variables::default();
    let labels: HashMap<&str, usize> = doc
        .instructions
        .iter()
        .enumerate()
        .filter_map(|(i, ins)| match &ins.op {
            Op::Label { name } => Some((name.as_str(), i)),
            _ => None,
        })
        .collect();
    let mut pc = 0;
    let mut steps = 0u64;
    while let Some(ins) = doc.instructions.get(pc) {
        pc += 1;
        steps += 1;
        assert!(steps < 20_000_000, "the program does not end");
        match &ins.op {
            Op::Declare(d) => declare(&mut vars, &rt, d, Scope::Local).unwrap(),
            Op::Assign { target, value } => assign(&mut vars, &mut rt, target, value).unwrap(),
            Op::AssignList(list) => assign_list(&mut vars, &rt, list).unwrap(),
            Op::Jump { target, condition } => {
                let jump = match condition {
                    None => true,
                    Some(c) => eval::eval_bool(&Env::new(&vars, &rt), c).unwrap(),
                };
                if jump {
                    pc = labels[target.as_str()];
                }
            }
            _ => {}
        }
    }
    vars
}

fn user(vars: &Variables, name: &str, indices: &[i32]) -> RtValue {
    vars.read(VarKind::User, name, indices).unwrap()
}

#[test]
fn declarations_with_lists_and_rep() {
    let vars = run("DEF INT MAT[2,3]=SET(1,2,3,4,5,6)\n\
         DEF REAL VEC[5]=REP(7,2)\n\
         DEF REAL ALL[3]=REP(1.5)\n\
         DEF INT GAP[4]=(1,,3)\n\
         DEF STRING[10] TXT=\"AB\"\n\
         M30\n");
    // Storage order: the last index runs fastest.
    assert_eq!(user(&vars, "MAT", &[0, 2]), RtValue::Int(3));
    assert_eq!(user(&vars, "MAT", &[1, 0]), RtValue::Int(4));
    assert_eq!(user(&vars, "MAT", &[1, 2]), RtValue::Int(6));
    assert_eq!(user(&vars, "VEC", &[1]), RtValue::Real(7.0));
    assert_eq!(user(&vars, "VEC", &[2]), RtValue::Real(0.0));
    assert_eq!(user(&vars, "ALL", &[2]), RtValue::Real(1.5));
    assert_eq!(user(&vars, "GAP", &[1]), RtValue::Int(0));
    assert_eq!(user(&vars, "GAP", &[2]), RtValue::Int(3));
    assert_eq!(user(&vars, "GAP", &[3]), RtValue::Int(0));
    assert_eq!(user(&vars, "TXT", &[]), RtValue::from("AB"));
    let e = vars.read(VarKind::User, "MAT", &[2, 0]).unwrap_err();
    assert_eq!(e.code, codes::run::INDEX_OUT_OF_RANGE);
    assert_eq!(
        vars.read(VarKind::User, "MAT", &[1]).unwrap_err().code,
        codes::run::INDEX_COUNT
    );
}

#[test]
fn list_assignments_and_rep_from_an_element_on() {
    let vars = run("DEF INT MAT[2,3]\n\
         DEF REAL VEC[6]=REP(1)\n\
         MAT[0,1]=SET(7,8,9)\n\
         VEC[2]=REP(5,3)\n\
         VEC[0]=(10,,12)\n\
         R10=SET(1,2,3)\n\
         M30\n");
    assert_eq!(user(&vars, "MAT", &[0, 0]), RtValue::Int(0));
    assert_eq!(user(&vars, "MAT", &[0, 1]), RtValue::Int(7));
    assert_eq!(user(&vars, "MAT", &[0, 2]), RtValue::Int(8));
    assert_eq!(user(&vars, "MAT", &[1, 0]), RtValue::Int(9));
    assert_eq!(user(&vars, "MAT", &[1, 1]), RtValue::Int(0));
    let vec: Vec<f64> = (0..6)
        .map(|i| user(&vars, "VEC", &[i]).to_real().unwrap())
        .collect();
    // (10,,12) leaves element 1 as REP(1) set it.
    assert_eq!(vec, [10.0, 1.0, 12.0, 5.0, 5.0, 1.0]);
    assert_eq!(vars.r(10), Ok(1.0));
    assert_eq!(vars.r(12), Ok(3.0));
}

#[test]
fn list_past_the_end_is_an_error_and_writes_nothing() {
    let mut vars = Variables::default();
    vars.declare(Scope::Local, "V", DataType::Int, &[3], Init::None)
        .unwrap();
    let values = [
        Some(RtValue::Int(1)),
        Some(RtValue::Int(2)),
        Some(RtValue::Int(3)),
    ];
    let e = vars
        .write_list(VarKind::User, "V", &[1], &values)
        .unwrap_err();
    assert_eq!(e.code, codes::run::INDEX_OUT_OF_RANGE);
    assert_eq!(vars.read(VarKind::User, "V", &[1]), Ok(RtValue::Int(0)));
    let e = vars
        .fill(VarKind::User, "V", &[2], &RtValue::Int(1), Some(2))
        .unwrap_err();
    assert_eq!(e.code, codes::run::INDEX_OUT_OF_RANGE);
    assert_eq!(
        vars.declare(Scope::Local, "W", DataType::Int, &[2, 2, 2, 2], Init::None)
            .unwrap_err()
            .code,
        codes::run::INVALID_DECLARATION
    );
}

#[test]
fn a_lowered_loop_computes() {
    let vars = run("DEF INT CNT\n\
         DEF REAL SUM\n\
         WHILE CNT < 100\n\
         CNT = CNT + 1\n\
         SUM = SUM + CNT * 0.5\n\
         ENDWHILE\n\
         R1 = CNT MOD 7\n\
         M30\n");
    assert_eq!(user(&vars, "CNT", &[]), RtValue::Int(100));
    // 0.5 * (1 + … + 100) = 2525.
    assert_eq!(user(&vars, "SUM", &[]), RtValue::Real(2525.0));
    assert_eq!(vars.r(1), Ok(2.0));
}

#[test]
fn a_long_loop_computes_exactly() {
    // WHILE R1 < 100000: R1 = R1 + 1, R2 = R2 + R1 * 0.5 - SIN(30). Its
    // speed is measured by `cargo bench -p gcodec-exec --bench run`
    // (docs/performance.md), not here.
    let profile = builtin();
    let src = "WHILE R1 < 100000\nR1 = R1 + 1\nR2 = R2 + R1 * 0.5 - SIN(30)\nENDWHILE\nM30\n";
    let lowered = gcodec_testkit::lower_clean("loop.mpf", src.as_bytes(), &profile);
    assert!(!lowered.has_errors());
    let vars = run_document(&lowered.document, &profile);
    assert_eq!(vars.r(1), Ok(100_000.0));
    // Σ (k/2 − 1/2) for k = 1 … 10⁵ = (10⁵·(10⁵+1)/2 − 10⁵)/2.
    assert_eq!(vars.r(2), Ok(2_499_975_000.0));
}

#[test]
fn deep_expressions_are_bounded_not_a_crash() {
    // 1000 nested additions (the parser's operator limit) evaluate…
    let mut e = n(0.0);
    for _ in 0..1000 {
        e = bin(B::Add, e, n(1.0));
    }
    let result = std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(move || {
            let ok = ev(&e);
            // …and far deeper ones are an error, not a stack overflow.
            let mut deep = e;
            for _ in 0..2000 {
                deep = un(U::Neg, deep);
            }
            let too_deep = ev(&deep);
            std::mem::forget(deep); // dropping 3000 nested boxes recursively is not under test
            (ok, too_deep)
        })
        .unwrap()
        .join()
        .unwrap();
    assert_eq!(result.0, Ok(RtValue::Int(1000)));
    assert_eq!(result.1.unwrap_err().code, codes::run::EXPRESSION_TOO_DEEP);
}

#[test]
fn numeric_evaluation_and_assignment_do_not_allocate() {
    let mut rt = builtin();
    let mut vars = Variables::default();
    vars.declare(Scope::Local, "CNT", DataType::Int, &[], Init::None)
        .unwrap();
    vars.declare(Scope::Local, "TAB", DataType::Real, &[10], Init::None)
        .unwrap();
    vars.push_level();
    vars.declare(Scope::Global, "GSUM", DataType::Real, &[], Init::None)
        .unwrap();
    vars.declare(Scope::Local, "CNT", DataType::Int, &[], Init::None)
        .unwrap();
    vars.declare(Scope::Local, "TAB", DataType::Real, &[10], Init::None)
        .unwrap();
    let cnt = var("CNT", vec![]);
    let step = Value::Expr(Box::new(bin(B::Add, cnt.clone(), n(1.0))));
    let tab = var("TAB", vec![bin(B::Mod, cnt.clone(), n(10.0))]);
    let sum = Value::Expr(Box::new(bin(
        B::Sub,
        bin(
            B::Add,
            var("GSUM", vec![]),
            bin(B::Mul, tab.clone(), n(0.5)),
        ),
        call("SIN", vec![r(1.0)]),
    )));
    let cond = bin(
        B::And,
        bin(B::Lt, cnt.clone(), n(1e6)),
        un(U::Not, bool_(false)),
    );
    let (gsum, r1) = (var("GSUM", vec![]), r(1.0));
    let before = allocations();
    for _ in 0..1000 {
        assign(&mut vars, &mut rt, &cnt, &step).unwrap();
        assign(&mut vars, &mut rt, &tab, &Value::Const(2.0)).unwrap();
        assign(&mut vars, &mut rt, &gsum, &sum).unwrap();
        assign(&mut vars, &mut rt, &r1, &step).unwrap();
        assert!(eval::eval_bool(&Env::new(&vars, &rt), &cond).unwrap());
    }
    assert_eq!(allocations() - before, 0, "allocations in 1000 iterations");
    assert_eq!(vars.read(VarKind::User, "CNT", &[]), Ok(RtValue::Int(1000)));
    // Calls and returns reuse the levels' tables.
    let before = allocations();
    for _ in 0..100 {
        vars.push_level();
        vars.pop_level();
    }
    assert_eq!(allocations() - before, 0, "allocations in 100 calls");
}

// ---------------------------------------------------------------------
// Strings are characters of the control's code page (issue 14)

#[test]
fn string_functions_count_characters_not_utf8_bytes() {
    let f = |name: &str, args: Vec<Expr>| ok(call(name, args));
    assert_eq!(f("STRLEN", vec![s("äbc")]), RtValue::Int(3));
    assert_eq!(
        f("SUBSTR", vec![s("äbc"), n(0.0), n(1.0)]),
        RtValue::string("ä")
    );
    assert_eq!(f("SUBSTR", vec![s("äöü€"), n(2.0)]), RtValue::string("ü€"));
    assert_eq!(f("INDEX", vec![s("xäb"), s("b")]), RtValue::Int(2));
    assert_eq!(f("INDEX", vec![s("xäb"), s("ä")]), RtValue::Int(1));
    assert_eq!(f("RINDEX", vec![s("äxä"), s("ä")]), RtValue::Int(2));
    assert_eq!(f("MINDEX", vec![s("€äb"), s("bä")]), RtValue::Int(1));
    assert_eq!(f("MATCH", vec![s("ääbc"), s("bc")]), RtValue::Int(2));
    assert_eq!(text(call("SPRINT", vec![s("%.1S"), s("äbc")])), "ä");
    assert_eq!(
        text(call("SPRINT", vec![s("%4S|%C"), s("äb"), s("€")])),
        "  äb|€"
    );
    // A CHAR is the character's byte in Windows-1252, both ways.
    assert_eq!(RtValue::string("€").to_char(), Ok(0x80));
    assert_eq!(RtValue::string("ä").to_char(), Ok(0xE4));
    assert_eq!(RtValue::Char(0xE4).to_text().unwrap(), "ä");
    assert_eq!(
        ok(bin(B::Eq, s("ä"), un(U::ToString, ok_char(0xE4)))),
        RtValue::Bool(true)
    );
    assert_eq!(
        RtValue::string("Ж").to_char().unwrap_err().code,
        codes::run::TYPE_MISMATCH
    );
    // `STRING[n]` counts characters too.
    assert!(
        RtValue::string("äöü")
            .convert_to(DataType::String { length: Some(3) })
            .is_ok()
    );
    assert_eq!(
        RtValue::string("äöü")
            .convert_to(DataType::String { length: Some(2) })
            .unwrap_err()
            .code,
        codes::run::STRING_TOO_LONG
    );
}

/// A CHAR constant as an expression (`"ä"[0]` has no AIL form).
fn ok_char(code: u8) -> Expr {
    call(
        "SUBSTR",
        vec![s(&RtValue::Char(code).to_text().unwrap()), n(0.0)],
    )
}

#[test]
fn string_indexing_reads_and_writes_characters() {
    let profile = builtin();
    let mut vars = Variables::default();
    vars.declare(
        Scope::Local,
        "TXT",
        DataType::String { length: Some(10) },
        &[],
        Init::List(&[Some(RtValue::string("äbc"))]),
    )
    .unwrap();
    let read = |vars: &Variables, i: f64| eval(&Env::new(vars, &profile), &var("TXT", vec![n(i)]));
    assert_eq!(read(&vars, 0.0), Ok(RtValue::Char(0xE4)));
    assert_eq!(read(&vars, 1.0), Ok(RtValue::Char(b'b')));
    let outside = read(&vars, 3.0).unwrap_err();
    assert_eq!(outside.code, codes::run::INDEX_OUT_OF_RANGE);
    assert!(
        outside.message.contains("3 characters"),
        "{}",
        outside.message
    );
    assign(
        &mut vars,
        &mut builtin(),
        &var("TXT", vec![n(2.0)]),
        &Value::Expr(Box::new(s("ö"))),
    )
    .unwrap();
    assert_eq!(
        eval(&Env::new(&vars, &profile), &var("TXT", vec![])),
        Ok(RtValue::string("äbö"))
    );
}

#[test]
fn sprint_widths_and_precisions_beyond_a_string_are_format_errors() {
    for format in ["%250D", "%.201S", "%99999999999999999999D"] {
        let e = err(call("SPRINT", vec![s(format), n(1.0)]));
        assert_eq!(e.code, codes::run::FORMAT, "{format}");
        let digits = format
            .trim_start_matches(['%', '.'])
            .trim_end_matches(['D', 'S']);
        assert!(e.message.contains(digits), "{format}: {}", e.message);
    }
    assert_eq!(
        text(call("SPRINT", vec![s("%200D"), n(1.0)]))
            .chars()
            .count(),
        200
    );
    assert_eq!(
        text(call("SPRINT", vec![s("%.20S"), s(&"x".repeat(30))])).len(),
        20
    );
}

proptest::proptest! {
    /// No string function panics on any text, and lengths and positions
    /// count characters.
    #[test]
    fn string_functions_never_panic_on_non_ascii_text(
        text in "[a-zäöü€Ж😀%.0-9]{0,12}",
        start in -2i32..14,
        len in -2i32..14,
    ) {
        let chars = text.chars().count();
        proptest::prop_assert_eq!(ok(call("STRLEN", vec![s(&text)])), RtValue::Int(chars as i32));
        let part = ev(&call("SUBSTR", vec![s(&text), n(f64::from(start)), n(f64::from(len))]));
        if let (Ok(from), Ok(take)) = (usize::try_from(start), usize::try_from(len)) {
            let expected: String = text.chars().skip(from).take(take).collect();
            proptest::prop_assert_eq!(part, Ok(RtValue::string(expected)));
        }
        for name in ["INDEX", "RINDEX"] {
            let at = ev(&call(name, vec![s(&text), s("ä")]));
            if let Ok(RtValue::Int(i)) = at {
                proptest::prop_assert!(i < chars as i32);
            }
        }
        let _ = ev(&call("MINDEX", vec![s(&text), s("€ü")]));
        let _ = ev(&call("MATCH", vec![s(&text), s(&text)]));
        let _ = ev(&call("SPRINT", vec![s(&text), s(&text), n(1.5)]));
        for precision in [0, 1, 3, 12] {
            let format = format!("%.{precision}S");
            let cut = ev(&call("SPRINT", vec![s(&format), s(&text)]));
            proptest::prop_assert_eq!(cut, Ok(RtValue::string(text.chars().take(precision).collect::<String>())));
        }
    }
}

// ---------------------------------------------------------------------
// Overflow is an alarm where it happens (issue 14)

#[test]
fn results_that_are_not_finite_are_overflow_where_computed() {
    let huge = || n(1e300);
    for (e, what) in [
        (bin(B::Mul, huge(), huge()), "`1e+300 * 1e+300`"),
        (bin(B::Div, huge(), n(1e-300)), "`1e+300 / 1e-300`"),
        (bin(B::Add, n(1.7e308), n(1.7e308)), "`1.7e+308 + 1.7e+308`"),
        (bin(B::IntDiv, huge(), n(1e-300)), "`1e+300 DIV 1e-300`"),
        (call("EXP", vec![n(1000.0)]), "`EXP`"),
        (call("POT", vec![huge()]), "`POT`"),
    ] {
        let e = err(e);
        assert_eq!(e.code, codes::run::OVERFLOW, "{what}");
        assert!(e.message.contains(what), "{what}: {}", e.message);
    }
    assert!(real(bin(B::Mul, n(1e150), n(1e150))).is_finite());
}
