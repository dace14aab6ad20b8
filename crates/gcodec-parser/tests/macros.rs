//! Macros of the definition files (`DEFINE NAME AS text`) are expanded
//! before a line is parsed and structures are paired: a macro may stand
//! for a value, an M code, a keyword or whole words, and what its text
//! produces is placed at its use.

use gcodec_parser::ast::{Initializer, Program, StatementKind};
use gcodec_parser::{Macro, Macros, Parse, parse_with_macros, write_tree};
use gcodec_source::{RenderOptions, SourceFile, Span, render_diagnostics};

/// The macros of a `UMAC.DEF`, one a line.
fn umac(list: &[(&str, &str)]) -> Macros {
    let mut macros = Macros::default();
    for (i, (name, body)) in list.iter().enumerate() {
        assert!(macros.insert(Macro {
            name: (*name).into(),
            body: (*body).into(),
            file: "UMAC.DEF".into(),
            line: i as u32 + 1,
        }));
    }
    macros
}

fn parse(src: &str, macros: &Macros) -> (SourceFile, Parse) {
    let file = SourceFile::new("MAIN.MPF", src);
    let parsed = parse_with_macros(&file, macros);
    (file, parsed)
}

fn tree(program: &Program) -> String {
    let mut out = String::new();
    write_tree(program, &mut out).unwrap();
    out
}

#[test]
fn a_macro_for_a_value_or_an_m_code_is_its_text() {
    let macros = umac(&[("MAXN", "100"), ("LIFT_ON", "M17")]);
    let (_, parsed) = parse("N10 R1=MAXN\nN20 lift_on\n", &macros);
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    let text = tree(&parsed.program);
    assert!(text.contains("R[1] = 100"), "{text}");
    assert!(text.contains("M17"), "{text}");
    // What the macro's text produced is at the use of the macro.
    let StatementKind::Assign(assign) = &parsed.program.blocks[0].statements[0].kind else {
        panic!("{text}");
    };
    let Initializer::Expr(value) = &assign.value else {
        panic!("{text}");
    };
    assert_eq!(value.span, Span::new(7, 11));
    assert_eq!(
        parsed.program.blocks[1].statements[0].span,
        Span::new(16, 23)
    );
}

#[test]
fn structures_are_paired_after_expansion() {
    let macros = umac(&[("WHEN_DEEP", "IF R1>5"), ("DONE", "ENDIF")]);
    let (_, parsed) = parse("WHEN_DEEP\nG1 X1 F100\nDONE\nM30\n", &macros);
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    assert_eq!(parsed.program.structures.len(), 1);
    // Without the macros, `DONE` is a call and the `IF` is no structure.
    let (_, parsed) = parse("WHEN_DEEP\nG1 X1 F100\nDONE\nM30\n", &Macros::default());
    assert!(parsed.program.structures.is_empty());
}

#[test]
fn macros_in_macros_expand_and_a_cycle_is_an_error() {
    let macros = umac(&[("PLANE", "G17 LINE"), ("LINE", "G1")]);
    let (_, parsed) = parse("PLANE X1 F100\n", &macros);
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    let text = tree(&parsed.program);
    assert!(text.contains("G17 | G1 | X1 | F100"), "{text}");
    let macros = umac(&[("LIFT_ON", "LIFT_OFF"), ("LIFT_OFF", "LIFT_ON")]);
    let (_, parsed) = parse("N10 LIFT_ON\nM30\n", &macros);
    let codes: Vec<_> = parsed.diagnostics.iter().map(|d| d.code.name()).collect();
    assert_eq!(codes, ["gcodec::parse::macro_expansion"]);
    assert_eq!(parsed.program.blocks[0].number.as_ref().unwrap().value, 10);
    assert!(parsed.program.blocks[0].statements.is_empty());
}

#[test]
fn an_error_inside_an_expansion_points_at_the_use_and_names_the_macro() {
    let macros = umac(&[("BAD_FEED", "F=")]);
    let (file, parsed) = parse("G1 X10 BAD_FEED\n", &macros);
    let rendered = render_diagnostics(&parsed.diagnostics, Some(&file), RenderOptions::default());
    assert_eq!(parsed.diagnostics.len(), 1, "{rendered}");
    let labels = &parsed.diagnostics[0].labels;
    assert!(
        labels.iter().any(|l| l.span == Span::new(7, 15)),
        "{rendered}"
    );
    assert!(
        rendered.contains("in the expansion of the macro `BAD_FEED` (UMAC.DEF:1: `F=`)"),
        "{rendered}"
    );
}

#[test]
fn a_definition_line_is_not_expanded() {
    let macros = umac(&[("MAXN", "100")]);
    let (_, parsed) = parse("DEFINE MAXN AS 100\n", &macros);
    assert!(parsed.diagnostics.is_empty(), "{:#?}", parsed.diagnostics);
    assert!(matches!(
        parsed.program.blocks[0].statements[0].kind,
        StatementKind::Define(_)
    ));
}
