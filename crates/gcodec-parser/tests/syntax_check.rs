//! `SYNTAX_CHECK.SPF` from deathaxe/sublime-s840d annotates each line with
//! the control's verdict. Each annotated line is parsed on its own.

use std::path::PathBuf;

use gcodec_parser::parse_bytes;

fn syntax_check_file() -> Option<PathBuf> {
    let path =
        gcodec_testkit::corpus_dir()?.join("real/deathaxe+sublime-s840d/examples/SYNTAX_CHECK.SPF");
    path.is_file().then_some(path)
}

/// Verdicts the parser owns. Machine-dependent ones (`invalid S-No`,
/// `unsupported M-group`, `known`/`unknown` variables) belong to lowering.
#[derive(Debug, PartialEq)]
enum Verdict {
    Ok,
    Error,
}

fn verdict(comment: &str) -> Option<Verdict> {
    let c = comment.trim().to_ascii_lowercase();
    if c == "ok" || c.starts_with("ok ") {
        Some(Verdict::Ok)
    } else if ["syntax error", "dez error", "hex error", "bin error"]
        .iter()
        .any(|v| c.starts_with(v))
    {
        Some(Verdict::Error)
    } else {
        None
    }
}

/// Lines the file marks as errors that are valid syntax for gcodec:
/// `T10 = 50` is the indexed tool selector of the tool-change design
/// (`T<n>=<number>`), rejected by lowering with the default profile.
const VALID_SYNTAX_DESPITE_ANNOTATION: &[&str] = &["T10     = 50"];

#[test]
fn each_annotated_line_gets_its_verdict() {
    let Some(path) = syntax_check_file() else {
        return;
    };
    let bytes = std::fs::read(&path).expect("readable");
    let text = String::from_utf8_lossy(&bytes);
    let mut checked = 0;
    let mut wrong = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let Some((code, comment)) = line.split_once(';') else {
            continue;
        };
        if code.trim().is_empty() {
            continue;
        }
        let Some(mut expected) = verdict(comment) else {
            continue;
        };
        if VALID_SYNTAX_DESPITE_ANNOTATION.contains(&code.trim_end()) {
            expected = Verdict::Ok;
        }
        let parsed = parse_bytes("line", line.as_bytes());
        let errors: Vec<_> = parsed.diagnostics.iter().filter(|d| d.is_error()).collect();
        let got = if errors.is_empty() {
            Verdict::Ok
        } else {
            Verdict::Error
        };
        if let Some(d) = errors.first() {
            assert!(
                d.span().is_some_and(|s| s.end as usize <= line.len()),
                "line {}",
                i + 1
            );
        }
        if got != expected {
            wrong.push(format!(
                "line {}: `{}` expected {:?}, got {:?} {:?}",
                i + 1,
                code.trim(),
                expected,
                got,
                errors.iter().map(|d| d.code.name()).collect::<Vec<_>>()
            ));
        }
        checked += 1;
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    // 47 lines carry a parser verdict in the file as published.
    assert!(checked >= 45, "only {checked} annotated lines found");
}
