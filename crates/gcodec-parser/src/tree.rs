//! The syntax tree of a parsed program as readable, indented text, one
//! line per block (`gcodec parse`).

use std::fmt::{self, Write};

use crate::ast::*;
use crate::grammar::operators::{binary_operator, is_word, unary_operator};
use gcodec_source::Span;

/// Writes one line per non-empty block: line number, block number and
/// label, then the statements, indented by control-structure depth.
pub fn write_tree(program: &Program, out: &mut impl Write) -> fmt::Result {
    writeln!(out, "program {}", program.file)?;
    if let Some(h) = &program.header {
        writeln!(out, "  header %{}", h.text)?;
    }
    if let Some(p) = &program.path {
        writeln!(out, "  path {}", p.path)?;
    }
    for (index, block) in program.blocks.iter().enumerate() {
        if block.statements.is_empty() && block.label.is_none() && block.number.is_none() {
            continue;
        }
        write!(out, "{:>5} ", index + 1)?;
        for _ in 0..block.depth.min(64) {
            out.write_str("  ")?;
        }
        if let Some(s) = &block.skip {
            write!(out, "/{} ", s.level)?;
        }
        if let Some(n) = &block.number {
            write!(out, "{}{} ", if n.main { ":" } else { "N" }, n.value)?;
        }
        if let Some(l) = &block.label {
            write!(out, "{}: ", l.name)?;
        }
        let mut first = true;
        for st in &block.statements {
            if !first {
                out.write_str(" | ")?;
            }
            first = false;
            write_statement(st, out)?;
        }
        out.write_char('\n')?;
    }
    Ok(())
}

fn write_statement(st: &Statement, out: &mut impl Write) -> fmt::Result {
    use StatementKind as S;
    match &st.kind {
        S::Word(w) => write_word(w, st.span, out),
        S::Assign(a) => {
            write_var(&a.target, out)?;
            out.write_str(" = ")?;
            write_init(&a.value, out)
        }
        S::Def(d) => {
            out.write_str("DEF ")?;
            for a in &d.attributes {
                write!(out, "{} ", a.name)?;
            }
            write_type(&d.ty, out)?;
            for (i, v) in d.vars.iter().enumerate() {
                out.write_str(if i == 0 { " " } else { ", " })?;
                out.write_str(&v.name)?;
                write_dims(&v.dims, out)?;
                if let Some(init) = &v.init {
                    out.write_str(" = ")?;
                    write_init(init, out)?;
                }
            }
            Ok(())
        }
        S::Redef(r) => write!(out, "REDEF {}", r.name),
        S::Define(d) => write!(out, "DEFINE {} AS {}", d.name, d.body),
        S::Proc(p) => {
            write!(out, "PROC {}(", p.name)?;
            for (i, param) in p.params.iter().enumerate() {
                if i > 0 {
                    out.write_str(", ")?;
                }
                if param.by_reference {
                    out.write_str("VAR ")?;
                }
                write_type(&param.ty, out)?;
                write!(out, " {}", param.name)?;
                write_dims(&param.dims, out)?;
            }
            out.write_char(')')?;
            for a in &p.attributes {
                write!(out, " {}", a.name)?;
            }
            Ok(())
        }
        S::EndProc => out.write_str("ENDPROC"),
        S::Extern(e) => {
            write!(out, "EXTERN {}(", e.name)?;
            for (i, p) in e.params.iter().enumerate() {
                if i > 0 {
                    out.write_str(", ")?;
                }
                if p.by_reference {
                    out.write_str("VAR ")?;
                }
                write_type(&p.ty, out)?;
                if !p.dims.is_empty() {
                    write_args(&p.dims, out)?;
                }
            }
            out.write_char(')')
        }
        S::Call(c) => write_call(c, out),
        S::IndirectCall(c) => {
            out.write_str("CALL")?;
            if let Some(p) = &c.program {
                out.write_char(' ')?;
                write_expr(p, out)?;
            }
            if let Some((a, b)) = &c.section {
                out.write_str(" BLOCK ")?;
                write_target(a, out)?;
                out.write_str(" TO ")?;
                write_target(b, out)?;
            }
            Ok(())
        }
        S::PCall(p) => {
            write!(out, "PCALL {}", p.path)?;
            if let Some(args) = &p.args {
                write_args(args, out)?;
            }
            Ok(())
        }
        S::MCall(m) => {
            out.write_str("MCALL")?;
            if let Some(c) = &m.call {
                out.write_char(' ')?;
                write_call(c, out)?;
            }
            Ok(())
        }
        S::Ret(r) => {
            out.write_str("RET")?;
            if let Some(args) = &r.args {
                write_args(args, out)?;
            }
            Ok(())
        }
        S::Goto(j) => write_jump(j, out),
        S::IfGoto(i) => {
            out.write_str("IF ")?;
            write_expr(&i.condition, out)?;
            out.write_char(' ')?;
            write_jump(&i.jump, out)
        }
        S::If(c) => write_cond("IF", c, out),
        S::Else => out.write_str("ELSE"),
        S::EndIf => out.write_str("ENDIF"),
        S::While(c) => write_cond("WHILE", c, out),
        S::EndWhile => out.write_str("ENDWHILE"),
        S::For(f) => {
            out.write_str("FOR ")?;
            write_var(&f.var, out)?;
            out.write_str(" = ")?;
            write_expr(&f.start, out)?;
            out.write_str(" TO ")?;
            write_expr(&f.end, out)
        }
        S::EndFor => out.write_str("ENDFOR"),
        S::Loop => out.write_str("LOOP"),
        S::EndLoop => out.write_str("ENDLOOP"),
        S::Repeat => out.write_str("REPEAT"),
        S::Until(c) => write_cond("UNTIL", c, out),
        S::RepeatSection(r) => {
            out.write_str(if r.single_block {
                "REPEATB "
            } else {
                "REPEAT "
            })?;
            write_target(&r.start, out)?;
            if let Some(e) = &r.end {
                out.write_char(' ')?;
                write_target(e, out)?;
            }
            if let Some(p) = &r.passes {
                out.write_char(' ')?;
                write_word(&p.word, p.span, out)?;
            }
            Ok(())
        }
        S::Case(c) => {
            out.write_str("CASE ")?;
            write_expr(&c.selector, out)?;
            out.write_str(" OF")?;
            for arm in &c.arms {
                out.write_char(' ')?;
                write_expr(&arm.value, out)?;
                out.write_char(' ')?;
                write_jump(&arm.jump, out)?;
            }
            if let Some(d) = &c.default {
                out.write_str(" DEFAULT ")?;
                write_jump(d, out)?;
            }
            Ok(())
        }
        S::Frame(f) => {
            out.write_str(f.op.keyword())?;
            for w in &f.words {
                out.write_char(' ')?;
                write_word(&w.word, w.span, out)?;
            }
            Ok(())
        }
        S::SyncAction(s) => {
            if let Some(id) = &s.id {
                out.write_str(if id.is_static { "IDS=" } else { "ID=" })?;
                write_expr(&id.value, out)?;
                out.write_char(' ')?;
            }
            if let Some(t) = &s.trigger {
                write!(out, "{} ", t.kind.keyword())?;
                write_expr(&t.condition, out)?;
                out.write_char(' ')?;
            }
            out.write_str("DO")?;
            for a in &s.actions {
                out.write_char(' ')?;
                write_statement(a, out)?;
            }
            Ok(())
        }
    }
}

fn write_cond(kw: &str, c: &Condition, out: &mut impl Write) -> fmt::Result {
    write!(out, "{kw} ")?;
    write_expr(&c.condition, out)
}

fn write_call(c: &Call, out: &mut impl Write) -> fmt::Result {
    match &c.target {
        CallTarget::Name { name, .. } => out.write_str(name)?,
        CallTarget::Number { digits, .. } => write!(out, "L{digits}")?,
    }
    if let Some(args) = &c.args {
        write_args(args, out)?;
    }
    if let Some(p) = &c.passes {
        out.write_char(' ')?;
        write_word(&p.word, p.span, out)?;
    }
    Ok(())
}

fn write_jump(j: &Jump, out: &mut impl Write) -> fmt::Result {
    out.write_str(j.goto.keyword())?;
    if let Some(t) = &j.target {
        out.write_char(' ')?;
        write_target(t, out)?;
    }
    Ok(())
}

fn write_target(t: &JumpTarget, out: &mut impl Write) -> fmt::Result {
    match t {
        JumpTarget::Label { name, .. } => out.write_str(name),
        JumpTarget::BlockNumber { value, .. } => write!(out, "N{value}"),
        JumpTarget::Expr(e) => write_expr(e, out),
    }
}

fn write_type(t: &TypeSpec, out: &mut impl Write) -> fmt::Result {
    match &t.kind {
        TypeKind::Int => out.write_str("INT"),
        TypeKind::Real => out.write_str("REAL"),
        TypeKind::Bool => out.write_str("BOOL"),
        TypeKind::Char => out.write_str("CHAR"),
        TypeKind::Axis => out.write_str("AXIS"),
        TypeKind::Frame => out.write_str("FRAME"),
        TypeKind::String { length } => {
            out.write_str("STRING")?;
            if let Some(l) = length {
                out.write_char('[')?;
                write_expr(l, out)?;
                out.write_char(']')?;
            }
            Ok(())
        }
    }
}

fn write_dims(dims: &[Expr], out: &mut impl Write) -> fmt::Result {
    if dims.is_empty() {
        return Ok(());
    }
    out.write_char('[')?;
    for (i, d) in dims.iter().enumerate() {
        if i > 0 {
            out.write_char(',')?;
        }
        write_expr(d, out)?;
    }
    out.write_char(']')
}

fn write_word(w: &Word, span: Span, out: &mut impl Write) -> fmt::Result {
    out.write_str(w.address())?;
    match w.extension() {
        Some(Extension::Number { value, .. }) => write!(out, "{value}")?,
        Some(Extension::Index { index, .. }) => {
            out.write_char('[')?;
            write_expr(index, out)?;
            out.write_char(']')?;
        }
        None => {}
    }
    match &*w.value(span) {
        WordValue::Constant(n) => write!(out, "{}", n.value),
        WordValue::Assigned { modifier, expr } => {
            out.write_char('=')?;
            match modifier {
                Some(m) => {
                    write!(out, "{}(", m.kind.keyword())?;
                    write_expr(expr, out)?;
                    out.write_char(')')
                }
                None => write_expr(expr, out),
            }
        }
    }
}

fn write_init(i: &Initializer, out: &mut impl Write) -> fmt::Result {
    match i {
        Initializer::Expr(e) => write_expr(e, out),
        Initializer::List { set, items, .. } => {
            if *set {
                out.write_str("SET")?;
            }
            write_args(items, out)
        }
        Initializer::Rep { args, .. } => {
            out.write_str("REP(")?;
            for (i, a) in args.iter().enumerate() {
                if i > 0 {
                    out.write_str(", ")?;
                }
                write_expr(a, out)?;
            }
            out.write_char(')')
        }
    }
}

fn write_args(args: &[Option<Expr>], out: &mut impl Write) -> fmt::Result {
    out.write_char('(')?;
    for (i, a) in args.iter().enumerate() {
        if i > 0 {
            out.write_str(", ")?;
        }
        if let Some(a) = a {
            write_expr(a, out)?;
        }
    }
    out.write_char(')')
}

fn write_var(v: &VarRef, out: &mut impl Write) -> fmt::Result {
    out.write_str(&v.name)?;
    if !v.indices.is_empty() {
        out.write_char('[')?;
        for (i, d) in v.indices.iter().enumerate() {
            if i > 0 {
                out.write_char(',')?;
            }
            write_expr(d, out)?;
        }
        out.write_char(']')?;
    }
    Ok(())
}

/// Writes an expression fully parenthesised, as the text tree shows it:
/// the brackets show how precedence grouped it.
pub fn write_expr(e: &Expr, out: &mut impl Write) -> fmt::Result {
    match &e.kind {
        ExprKind::Number { value, .. } => write!(out, "{value}"),
        ExprKind::String { value } => write!(out, "\"{value}\""),
        ExprKind::Bool { value } => out.write_str(if *value { "TRUE" } else { "FALSE" }),
        ExprKind::Var { var } => write_var(var, out),
        ExprKind::Call(call) => {
            out.write_str(&call.name)?;
            write_args(&call.args, out)
        }
        ExprKind::Unary { op, operand } => {
            out.write_char('(')?;
            let text = unary_operator(*op).text;
            out.write_str(text)?;
            // `(NOT R1)`: a word needs a blank before its operand.
            if is_word(text) {
                out.write_char(' ')?;
            }
            write_expr(operand, out)?;
            out.write_char(')')
        }
        ExprKind::Binary(b) => {
            out.write_char('(')?;
            write_expr(&b.lhs, out)?;
            write!(out, " {} ", binary_operator(b.op).text)?;
            write_expr(&b.rhs, out)?;
            out.write_char(')')
        }
    }
}
