//! What every parse must satisfy, for any input: shared by the property
//! tests and the fuzz target (`fuzz/fuzz_targets/parse.rs` includes this
//! file by path).

#![allow(dead_code)]

use gcodec_parser::Parse;
use gcodec_source::{SourceFile, Span};
use serde_json::Value;

/// `b"…"` with escapes, for failure messages.
pub fn show(src: &[u8]) -> String {
    format!("b\"{}\"", src.escape_ascii())
}

/// Lines of a source, counting a last line without a line end.
pub fn line_count(src: &[u8]) -> usize {
    src.iter().filter(|&&b| b == b'\n').count()
        + usize::from(src.last().is_some_and(|&b| b != b'\n'))
}

/// A span is in bounds.
pub fn check_span(file: &SourceFile, span: Span, what: &str) -> Result<(), String> {
    let len = file.bytes().len() as u32;
    if span.start > span.end || span.end > len {
        return Err(format!("{what}: span {span:?} out of bounds (len {len})"));
    }
    Ok(())
}

/// A span as serialised: byte range, line and column.
#[derive(Clone, Copy, Debug)]
pub struct Located {
    pub span: Span,
    pub line: u32,
    pub col: u32,
}

/// A serialised span is in bounds and its line and column are those of its
/// start.
pub fn check_located(file: &SourceFile, at: Located, what: &str) -> Result<(), String> {
    check_span(file, at.span, what)?;
    let (line, col) = file.line_col(at.span.start);
    if (at.line, at.col) != (line, col) {
        return Err(format!(
            "{what}: span {:?} says line {}:{}, its start is at {line}:{col}",
            at.span, at.line, at.col
        ));
    }
    Ok(())
}

/// Every span object (`{start, end, line, col}`) in a serialised tree; a
/// span serialised without its line and column is an error. Iterative, so
/// deep trees cannot overflow the walk itself.
pub fn spans_in(value: &Value) -> Result<Vec<Located>, String> {
    let mut out = Vec::new();
    let mut stack = vec![value];
    while let Some(v) = stack.pop() {
        match v {
            Value::Object(map) => {
                let field = |k: &str| map.get(k).and_then(Value::as_u64).map(|n| n as u32);
                match (field("start"), field("end"), field("line"), field("col")) {
                    (Some(start), Some(end), Some(line), Some(col)) if map.len() == 4 => {
                        out.push(Located {
                            span: Span::new(start, end),
                            line,
                            col,
                        });
                    }
                    (Some(_), Some(_), _, _) if map.len() <= 4 => {
                        return Err(format!("span without line and column: {v}"));
                    }
                    _ => stack.extend(map.values()),
                }
            }
            Value::Array(items) => stack.extend(items),
            _ => {}
        }
    }
    Ok(out)
}

/// Everything a parse must satisfy, for any input.
pub fn check_parse_of(src: &[u8], parse: &Parse) -> Result<(), String> {
    let file = SourceFile::new("prop.mpf", src);
    let program = &parse.program;
    if program.blocks.len() != line_count(src) {
        return Err(format!(
            "{} blocks for {} lines",
            program.blocks.len(),
            line_count(src)
        ));
    }
    let starts = file.line_starts();
    let json = serde_json::to_value(program).map_err(|e| format!("program: {e}"))?;
    let blocks = json["blocks"].as_array().ok_or("no blocks in the JSON")?;
    for (i, block) in program.blocks.iter().enumerate() {
        let what = || format!("block {i} ({})", show(&src[block.span.range()]));
        check_span(&file, block.span, &what())?;
        if block.span.start != starts[i] {
            return Err(format!(
                "{}: span {:?} is not line {}",
                what(),
                block.span,
                i + 1
            ));
        }
        // Every span inside the block is in bounds, is serialised with its
        // true line and column, and lies on the block's line.
        for at in spans_in(&blocks[i]).map_err(|e| format!("{}: {e}", what()))? {
            check_located(&file, at, &what())?;
            if at.line as usize != i + 1 || at.span.end > block.span.end {
                return Err(format!(
                    "{}: span {:?} outside its block {:?}",
                    what(),
                    at.span,
                    block.span
                ));
            }
        }
    }
    if let Some(header) = &program.header {
        check_span(&file, header.span, "header")?;
    }
    if let Some(path) = &program.path {
        check_span(&file, path.span, "$PATH")?;
    }
    for s in &program.structures {
        let n = program.blocks.len() as u32;
        if s.open >= n || s.middle.is_some_and(|m| m >= n) || s.close.is_some_and(|c| c >= n) {
            return Err(format!("structure {s:?} names a block past {n}"));
        }
    }
    for d in &parse.diagnostics {
        if d.labels.is_empty() {
            return Err(format!("{}: diagnostic without a label", d.code));
        }
        if d.code.area() != "parse" {
            return Err(format!("{}: not a parse-stage code", d.code));
        }
        for label in &d.labels {
            check_span(&file, label.span, d.code.name())?;
        }
    }
    Ok(())
}
