//! Feeds arbitrary bytes to the parser and checks what every parse must
//! satisfy: no panic, one block per line, every span in bounds with
//! `start <= end` and the true 1-based line and column of its start, every
//! diagnostic labelled in bounds; then renders the diagnostics, which
//! exercises the miette path (byte-offset mapping for non-UTF-8 sources).

#![no_main]

use gcodec_source::{RenderOptions, SourceFile, Span, render_diagnostics};
use libfuzzer_sys::fuzz_target;
use serde_json::Value;

fuzz_target!(|data: &[u8]| {
    let parse = gcodec_parser::parse_bytes("fuzz.mpf", data);
    let file = SourceFile::new("fuzz.mpf", data);

    let lines = data.iter().filter(|&&b| b == b'\n').count()
        + usize::from(data.last().is_some_and(|&b| b != b'\n'));
    assert_eq!(parse.program.blocks.len(), lines, "one block per line");

    let starts = file.line_starts();
    for (i, block) in parse.program.blocks.iter().enumerate() {
        check(&file, block.span, "block");
        assert_eq!(block.span.start, starts[i], "block {i} starts its line");
        for statement in &block.statements {
            check(&file, statement.span, "statement");
            assert!(
                statement.span.start >= block.span.start && statement.span.end <= block.span.end,
                "statement {:?} outside its block {:?}",
                statement.span,
                block.span
            );
        }
    }
    // Every span anywhere in the tree, found through its JSON form.
    let value = serde_json::to_value(&parse.program).expect("the tree serialises");
    let mut stack = vec![&value];
    while let Some(v) = stack.pop() {
        match v {
            Value::Object(map) => {
                let field = |k: &str| map.get(k).and_then(Value::as_u64).map(|n| n as u32);
                if let (4, Some(start), Some(end), Some(line), Some(col)) = (
                    map.len(),
                    field("start"),
                    field("end"),
                    field("line"),
                    field("col"),
                ) {
                    check(&file, Span::new(start, end, line, col), "tree");
                } else {
                    stack.extend(map.values());
                }
            }
            Value::Array(items) => stack.extend(items),
            _ => {}
        }
    }
    let blocks = parse.program.blocks.len() as u32;
    for s in &parse.program.structures {
        assert!(s.open < blocks && s.close.is_none_or(|c| c < blocks));
        assert!(s.middle.is_none_or(|m| m < blocks));
    }
    for d in &parse.diagnostics {
        assert!(!d.labels.is_empty(), "{} has no label", d.code);
        for label in &d.labels {
            check(&file, label.span, d.code);
        }
    }

    let rendered = render_diagnostics(&parse.diagnostics, Some(&file), RenderOptions::default());
    assert_eq!(rendered.is_empty(), parse.diagnostics.is_empty());
});

fn check(file: &SourceFile, span: Span, what: &str) {
    let len = file.bytes().len() as u32;
    assert!(
        span.start <= span.end && span.end <= len,
        "{what}: {span:?} out of bounds (len {len})"
    );
    assert!(
        span.line >= 1 && span.col >= 1,
        "{what}: {span:?} has line or column 0"
    );
    assert_eq!(
        file.line_col(span.start),
        (span.line, span.col),
        "{what}: {span:?} names the wrong line or column"
    );
}
