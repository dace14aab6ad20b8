//! The lint fixtures of `tests/fixtures/lint/`, one test a file: adding a
//! file is the whole test (`tests/fixtures/README.md`).
//!
//! A fixture is named after the rule it is about: one in `triggers/`
//! makes the rule `gcodec::lint::<file stem>` report, one in `clean/`
//! makes no lint rule report at all (the same construct written as it
//! should be, or a case the rule must not take for a finding). Its
//! snapshot `lint@FOLDER__FILE.snap` is every lint finding, rendered.
//! Accept changed ones with `INSTA_UPDATE=always cargo test -p
//! gcodec-sema --test lint`.

use std::path::Path;

use gcodec_sema::{Definitions, ProgramKind};
use gcodec_source::{RenderOptions, render_diagnostics};
use gcodec_testkit::Fixture;

fn lint_fixture(path: &Path) -> datatest_stable::Result<()> {
    let fixture = Fixture::read("lint", path);
    let header = fixture.header();
    let file = &fixture.file;
    let parsed = gcodec_parser::parse_bytes(file.name(), file.bytes());
    assert!(
        parsed.diagnostics.is_empty(),
        "{}: a lint fixture parses cleanly: {:#?}",
        fixture.relative,
        parsed.diagnostics
    );
    let kind = ProgramKind::of_file(file.name());
    let lowered =
        gcodec_sema::lower_program(&parsed.program, kind, &header.profile, &Definitions::new());
    assert!(
        !lowered.has_errors(),
        "{}: a lint fixture lowers without an error: {:#?}",
        fixture.relative,
        lowered.diagnostics
    );
    let found = gcodec_sema::lint::lint(&parsed.program, &lowered.document, kind, &header.profile)
        .into_iter()
        .collect::<Vec<_>>();
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .expect("a fixture's name");
    let rule = format!("gcodec::lint::{stem}");
    let codes: Vec<&str> = found.iter().map(|d| d.code.name()).collect();
    if fixture.relative.starts_with("triggers/") {
        assert!(
            codes.contains(&rule.as_str()),
            "{}: {rule} does not report: {codes:?}",
            fixture.relative
        );
    } else {
        assert!(
            fixture.relative.starts_with("clean/"),
            "{}: a lint fixture is in `triggers/` or `clean/`",
            fixture.relative
        );
        assert!(
            gcodec_source::codes::find(&rule).is_some(),
            "{}: no rule `{rule}`",
            fixture.relative
        );
        assert!(
            codes.is_empty(),
            "{}: a clean fixture makes no rule report: {codes:?}",
            fixture.relative
        );
    }
    let rendered = render_diagnostics(&found, Some(file), RenderOptions::default());
    fixture
        .snapshot_settings()
        .bind(|| insta::assert_snapshot!(fixture.kind, rendered));
    Ok(())
}

datatest_stable::harness! {
    {
        test = lint_fixture,
        root = gcodec_testkit::fixtures::root("lint"),
        pattern = r"\.(mpf|spf)$",
    },
}
