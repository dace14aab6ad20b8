//! insta snapshots of the AIL: the seed features as the JSON document,
//! and the example programs as listings with their diagnostics.

mod common;

use std::path::PathBuf;

fn repo(path: &str) -> PathBuf {
    common::repo().join(path)
}

fn lower_file(path: &str, profile: &str) -> gcodec_sema::Lowered {
    let file = gcodec_source::SourceFile::read(&repo(path)).expect("readable");
    let parsed = gcodec_parser::parse_bytes(path, file.bytes());
    assert!(
        parsed.diagnostics.is_empty(),
        "{path}: {:#?}",
        parsed.diagnostics
    );
    gcodec_sema::lower(&parsed.program, &common::profile(profile))
}

/// The listing, then one line per diagnostic: code and line.
fn listing(path: &str, profile: &str) -> String {
    let lowered = lower_file(path, profile);
    let mut out = String::new();
    gcodec_ail::write_listing(&lowered.document, &mut out).unwrap();
    let file = gcodec_source::SourceFile::read(&repo(path)).unwrap();
    for d in &lowered.diagnostics {
        let line = d.span().map_or(0, |s| file.line_col(s.start).0);
        out.push_str(&format!(
            "{:?} {} at line {line}: {}\n",
            d.severity, d.code, d.message
        ));
    }
    out
}

#[test]
fn seed_features_document() {
    let lowered = lower_file("tests/fixtures/lower/seed_features.mpf", "default.toml");
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

/// One fixture per construct family, each with the profile of its machine.
const FAMILIES: &[(&str, &str)] = &[
    ("control_flow.mpf", "default.toml"),
    ("calls.mpf", "default.toml"),
    ("procedure.spf", "default.toml"),
    ("addresses.mpf", "default.toml"),
    ("variables.mpf", "default.toml"),
    ("frames.mpf", "mill_5axis.toml"),
];

#[test]
fn construct_families() {
    for (file, profile) in FAMILIES {
        let path = format!("tests/fixtures/lower/{file}");
        let text = listing(&path, profile);
        assert!(
            !text.contains("Error ") && !text.contains("Warning "),
            "{file}: the family fixtures lower cleanly:\n{text}"
        );
        insta::assert_snapshot!(format!("family_{file}").replace('.', "_"), text);
    }
}
