//! Helpers shared by the semantic stage's integration tests: the parser's
//! (where the repository and the corpus are) plus the shipped profiles.

#![allow(dead_code, unused_imports)]

#[path = "../../../gcodec-parser/tests/common/mod.rs"]
mod parser_common;

pub use parser_common::{all_programs, corpus_dir, programs, repo};

pub mod machines;

/// `path` as the corpus tests show it: relative to the corpus, with `/`.
pub fn shown(corpus: &std::path::Path, path: &std::path::Path) -> String {
    path.strip_prefix(corpus)
        .unwrap_or(path)
        .display()
        .to_string()
        .replace('\\', "/")
}

/// A shipped profile, by file name (`lathe_828d.toml`).
pub fn profile(name: &str) -> gcodec_profile::Profile {
    let text = std::fs::read_to_string(repo().join("profiles").join(name)).expect("profile");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"))
}

/// A profile of the given TOML sections after a `[machine]` header.
pub fn machine(sections: &str) -> gcodec_profile::Profile {
    let text = format!("[machine]\nname = \"test\"\ncontrol = \"840d_sl\"\n{sections}");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{d:#?}"))
}

/// Lowers `src` (which must parse cleanly) for `profile`.
pub fn lower_with(profile: &gcodec_profile::Profile, src: &str) -> gcodec_sema::Lowered {
    lower_named("test.mpf", profile, src)
}

/// [`lower_with`], the program in the file `file`.
pub fn lower_named(
    file: &str,
    profile: &gcodec_profile::Profile,
    src: &str,
) -> gcodec_sema::Lowered {
    let parsed = gcodec_parser::parse_bytes(file, src.as_bytes());
    assert!(
        parsed.diagnostics.is_empty(),
        "{src}: {:#?}",
        parsed.diagnostics
    );
    gcodec_sema::lower(&parsed.program, profile)
}

/// The instructions of `kind`, as JSON without their source.
pub fn ops(lowered: &gcodec_sema::Lowered, kind: &str) -> Vec<serde_json::Value> {
    lowered
        .document
        .instructions
        .iter()
        .filter_map(|i| {
            let mut v = serde_json::to_value(i).ok()?;
            (v["kind"] == kind).then(|| {
                v.as_object_mut().map(|m| m.remove("source"));
                v
            })
        })
        .collect()
}

/// The codes of all diagnostics, in order.
pub fn codes(lowered: &gcodec_sema::Lowered) -> Vec<&'static str> {
    lowered.diagnostics.iter().map(|d| d.code).collect()
}

/// The codes of the error diagnostics, in order.
pub fn errors(lowered: &gcodec_sema::Lowered) -> Vec<&'static str> {
    lowered
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code)
        .collect()
}

/// The motion kinds, in order.
pub fn motions(lowered: &gcodec_sema::Lowered) -> Vec<gcodec_lang::MotionKind> {
    lowered
        .document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            gcodec_ail::Op::Motion { motion, .. } => Some(*motion),
            _ => None,
        })
        .collect()
}

/// The Group 8 selection of each work offset instruction, in order.
pub fn selections(lowered: &gcodec_sema::Lowered) -> Vec<Option<String>> {
    lowered
        .document
        .instructions
        .iter()
        .filter_map(|i| match &i.op {
            gcodec_ail::Op::WorkOffset {
                group8_selected, ..
            } => Some(group8_selected.clone()),
            _ => None,
        })
        .collect()
}

/// The kinds of all instructions, in order.
pub fn kinds(lowered: &gcodec_sema::Lowered) -> Vec<String> {
    lowered
        .document
        .instructions
        .iter()
        .map(|i| {
            serde_json::to_value(i).unwrap()["kind"]
                .as_str()
                .unwrap()
                .to_owned()
        })
        .collect()
}
