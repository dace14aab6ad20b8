//! What a rendered diagnostic shows: the position gcodec gives, the
//! program's control characters escaped, and a bounded snippet.

use gcodec_source::{Diagnostic, RenderOptions, SourceFile, Span, codes, render_diagnostics};

fn render(file: &SourceFile, diagnostic: Diagnostic) -> String {
    render_diagnostics(&[diagnostic], Some(file), RenderOptions::default())
}

/// The `[file:line:col]` header of a rendered report.
fn header(rendered: &str) -> &str {
    let start = rendered.find('[').expect("a header") + 1;
    &rendered[start..start + rendered[start..].find(']').expect("its end")]
}

/// A lone CR is a blank inside its line (SPEC §1, §2), so the header
/// gives the position gcodec gives, and the CR is shown escaped.
#[test]
fn a_lone_cr_does_not_end_the_line_in_the_header() {
    let file = SourceFile::new("cr.mpf", "G0 X1 \rG1 X= \nM30\n");
    let at = 11;
    assert_eq!(file.line_col(at), (1, 12));
    let rendered = render(
        &file,
        Diagnostic::new(codes::parse::INVALID_VALUE, "incomplete")
            .with_label(Span::new(at, at + 1), "here"),
    );
    assert_eq!(header(&rendered), "cr.mpf:1:12");
    assert!(rendered.contains(" 1 │ G0 X1 \\x0dG1 X= \n"), "{rendered}");
    assert!(rendered.contains(" 2 │ M30\n"), "{rendered}");
}

/// Lines end with LF or CR LF, and a line after CR LF has the line
/// number gcodec gives.
#[test]
fn a_cr_before_lf_belongs_to_the_line_end() {
    let file = SourceFile::new("crlf.mpf", "G0 X1\r\nG1 X=\r\nM30\r\n");
    let rendered = render(
        &file,
        Diagnostic::new(codes::parse::INVALID_VALUE, "incomplete")
            .with_label(Span::new(10, 12), "here"),
    );
    assert_eq!(header(&rendered), "crlf.mpf:2:4");
    assert!(
        !rendered.contains("\\x0d") && !rendered.contains('\r'),
        "{rendered}"
    );
}

/// The column is the byte column also where a Latin-1 byte is shown as
/// a two-byte character.
#[test]
fn the_column_counts_the_bytes_stored() {
    let file = SourceFile::new("latin1.mpf", b"MSG(\"\xfc\") X=\n".to_vec());
    let rendered = render(
        &file,
        Diagnostic::new(codes::parse::INVALID_VALUE, "incomplete")
            .with_label(Span::new(9, 11), "here"),
    );
    assert_eq!(header(&rendered), "latin1.mpf:1:10");
    assert!(rendered.contains("MSG(\"ü\") X="), "{rendered}");
}

/// ESC, BEL and CR from the program reach the terminal escaped, in the
/// message, the labels, the help, the snippet and the file name; the
/// report itself holds no control character but line ends.
#[test]
fn control_characters_are_escaped_everywhere_in_a_report() {
    let file = SourceFile::new("t\u{1b}]0;x\u{7}.mpf", "MSG(\"\u{1b}[2J\u{7}\") ?\n");
    let quoted = "\u{1b}[2J\u{7}\r";
    let diagnostic = Diagnostic::new(codes::parse::INVALID_CHARACTER, format!("after `{quoted}`"))
        .with_label(Span::new(13, 14), format!("not `{quoted}`"))
        .with_help(format!("drop `{quoted}`"));
    let rendered = render(&file, diagnostic);
    assert!(
        !rendered.chars().any(|c| c.is_control() && c != '\n'),
        "{rendered:?}"
    );
    for shown in [
        "after `\\x1b[2J\\x07\\x0d`",
        "not `\\x1b[2J\\x07\\x0d`",
        "drop `\\x1b[2J\\x07\\x0d`",
        "MSG(\"\\x1b[2J\\x07\") ?",
        "[t\\x1b]0;x\\x07.mpf:1:14]",
    ] {
        assert!(rendered.contains(shown), "{shown} in {rendered}");
    }
}

/// A label over a line of a million bytes (`block_too_long`) shows a
/// few dozen bytes of it, not the line.
#[test]
fn a_label_over_a_long_line_renders_a_bounded_snippet() {
    let line = format!("G1{}", " X1".repeat(350_000));
    let file = SourceFile::new("long.mpf", format!("{line}\nM30\n"));
    let rendered = render(
        &file,
        Diagnostic::new(codes::lower::BLOCK_TOO_LONG, "too long")
            .with_label(Span::new(0, line.len() as u32), "this block"),
    );
    assert!(
        rendered.len() < 1_000,
        "{} bytes: {rendered}",
        rendered.len()
    );
    assert_eq!(header(&rendered), "long.mpf:1:1");
}
