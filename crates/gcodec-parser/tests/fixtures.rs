//! The parse fixtures of `tests/fixtures/parse/`, one test a file: adding
//! a file is the whole test (`tests/fixtures/README.md`).
//!
//! A program outside `errors/` must parse without any diagnostic; its
//! syntax tree is its JSON snapshot. A program in `errors/` must yield at
//! least one error; its rendered diagnostics are its snapshot. Either way
//! it has one block a line. Snapshots are `parse@RELATIVE.snap`, the file
//! named relative to the repository root so that they hold no absolute
//! path; accept changed ones with
//! `INSTA_UPDATE=always cargo test -p gcodec-parser --test fixtures`.

mod common;

use std::path::Path;

use common::invariants::line_count;
use gcodec_parser::{Parse, parse};
use gcodec_source::{RenderOptions, render_diagnostics};
use gcodec_testkit::Fixture;

fn parses_cleanly(path: &Path) -> datatest_stable::Result<()> {
    let fixture = Fixture::read("parse", path);
    let parsed = parse_one_block_a_line(&fixture);
    assert!(
        parsed.diagnostics.is_empty(),
        "{} should parse cleanly:\n{}",
        fixture.relative,
        rendered(&fixture, &parsed)
    );
    fixture
        .snapshot_settings()
        .bind(|| insta::assert_json_snapshot!(fixture.kind, parsed.program));
    Ok(())
}

fn reports_errors(path: &Path) -> datatest_stable::Result<()> {
    let fixture = Fixture::read("parse", path);
    let parsed = parse_one_block_a_line(&fixture);
    assert!(
        parsed.has_errors(),
        "{} should yield at least one error",
        fixture.relative
    );
    let rendered = rendered(&fixture, &parsed);
    fixture
        .snapshot_settings()
        .bind(|| insta::assert_snapshot!(fixture.kind, rendered));
    Ok(())
}

/// The parse of the fixture, which has one block a line, also with errors.
fn parse_one_block_a_line(fixture: &Fixture) -> Parse {
    let parsed = parse(&fixture.file);
    assert_eq!(
        parsed.program.blocks.len(),
        line_count(fixture.file.bytes()),
        "{}: one block per line",
        fixture.relative
    );
    parsed
}

fn rendered(fixture: &Fixture, parsed: &Parse) -> String {
    render_diagnostics(
        &parsed.diagnostics,
        Some(&fixture.file),
        RenderOptions {
            color: false,
            limit: None,
        },
    )
}

datatest_stable::harness! {
    {
        test = parses_cleanly,
        root = gcodec_testkit::fixtures::root("parse"),
        pattern = r"^(?!errors/).*\.(mpf|spf)$",
    },
    {
        test = reports_errors,
        root = gcodec_testkit::fixtures::root("parse"),
        pattern = r"^errors/.*\.(mpf|spf)$",
    },
}
