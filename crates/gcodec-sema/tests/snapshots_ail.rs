//! insta snapshots of the AIL: tool change, M functions and work offsets
//! (the lower fixture `tool_m_functions_offsets.mpf`) as the JSON
//! document, and the example programs as listings with their diagnostics.
//! The listings of the lower fixtures are `fixtures.rs`'s.

mod common;

use gcodec_source::SourceFile;

/// The program at `path` (relative to the repository root), lowered for
/// the shipped profile `profile`.
fn lower_file(path: &str, profile: &str) -> (SourceFile, gcodec_sema::Lowered) {
    let bytes = std::fs::read(common::repo().join(path)).expect("readable");
    let file = SourceFile::new(path, bytes);
    let lowered = gcodec_testkit::lower_clean(path, file.bytes(), &common::profile(profile));
    (file, lowered)
}

fn listing(path: &str, profile: &str) -> String {
    let (file, lowered) = lower_file(path, profile);
    common::listing(&file, &lowered)
}

#[test]
fn tool_m_functions_offsets_document() {
    let (_, lowered) = lower_file(
        "tests/fixtures/lower/tool_m_functions_offsets.mpf",
        "default.toml",
    );
    assert!(lowered.diagnostics.is_empty(), "{:#?}", lowered.diagnostics);
    insta::assert_json_snapshot!(lowered.document);
}

#[test]
fn example_pocket_mill() {
    insta::assert_snapshot!(listing("examples/pocket_mill.mpf", "default.toml"));
}

#[test]
fn example_lathe_shaft() {
    insta::assert_snapshot!(listing("examples/lathe_shaft.mpf", "lathe_828d.toml"));
}

#[test]
fn example_chamfer_edge() {
    insta::assert_snapshot!(listing("examples/chamfer_edge.spf", "default.toml"));
}
