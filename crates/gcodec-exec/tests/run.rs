//! Golden event streams, one test a fixture: every main program of
//! `tests/fixtures/run/` runs with the profile and options its `; run:`
//! line names (`; run: profile=mill.toml no-stop skip=1 max-steps=20`),
//! and its text trace with the run's summary is its snapshot
//! `run@FILE.snap`; adding a file is the whole test
//! (`tests/fixtures/README.md`). Subprograms are found next to the
//! fixture. The numbers were checked by hand when the snapshots were
//! accepted (see the fixtures' comments).

mod common;

use std::path::Path;

use common::golden::{Output, golden};
use gcodec_testkit::Fixture;

fn golden_stream(path: &Path) -> datatest_stable::Result<()> {
    let fixture = Fixture::read("run", path);
    let stream = golden(&fixture, Output::Text);
    fixture
        .snapshot_settings()
        .bind(|| insta::assert_snapshot!(fixture.kind, stream));
    Ok(())
}

datatest_stable::harness! {
    {
        test = golden_stream,
        root = gcodec_testkit::fixtures::root("run"),
        pattern = r"\.mpf$",
    },
}
