//! The lower fixtures of `tests/fixtures/lower/`, one test a file: adding
//! a file is the whole test (`tests/fixtures/README.md`).
//!
//! Each fixture, one construct family, lowers without an error or a
//! warning for the profile its `; lower:` line names (the built-in one
//! without); its listing is its snapshot `lower@FILE.snap`. Accept changed
//! ones with `INSTA_UPDATE=always cargo test -p gcodec-sema --test fixtures`.

mod common;

use std::path::Path;

use gcodec_source::Severity;
use gcodec_testkit::Fixture;

fn lowers_cleanly(path: &Path) -> datatest_stable::Result<()> {
    let fixture = Fixture::read("lower", path);
    let header = fixture.header();
    assert!(
        header.options.is_empty(),
        "{}: a lower fixture names its profile only, not {:?}",
        fixture.relative,
        header.options
    );
    let file = &fixture.file;
    let lowered = gcodec_testkit::lower_clean(file.name(), file.bytes(), &header.profile);
    let listing = common::listing(file, &lowered);
    assert!(
        lowered
            .diagnostics
            .iter()
            .all(|d| d.severity == Severity::Advice),
        "{}: the family fixtures lower cleanly:\n{listing}",
        fixture.relative
    );
    fixture
        .snapshot_settings()
        .bind(|| insta::assert_snapshot!(fixture.kind, listing));
    Ok(())
}

datatest_stable::harness! {
    {
        test = lowers_cleanly,
        root = gcodec_testkit::fixtures::root("lower"),
        pattern = r"\.(mpf|spf)$",
    },
}
