//! Helpers shared by the semantic stage's integration tests; where the
//! programs are, the shipped profiles and the compile set-up are
//! `gcodec_testkit`'s.

#![allow(dead_code, unused_imports)]

pub use gcodec_testkit::{all_programs, corpus_dir, machine, profile, programs, repo, shown};

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
    gcodec_testkit::lower_clean(file, src.as_bytes(), profile)
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
    lowered.diagnostics.iter().map(|d| d.code.name()).collect()
}

/// The codes of the error diagnostics, in order.
pub fn errors(lowered: &gcodec_sema::Lowered) -> Vec<&'static str> {
    lowered
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .map(|d| d.code.name())
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
            } => Some(group8_selected.map(|code| code.to_string())),
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

/// The listing of a lowered program, then one line per diagnostic: code
/// and line.
pub fn listing(file: &gcodec_source::SourceFile, lowered: &gcodec_sema::Lowered) -> String {
    let mut out = String::new();
    gcodec_ail::write_listing(&lowered.document, &mut out).unwrap();
    for d in &lowered.diagnostics {
        let line = d.span().map_or(0, |s| file.line_col(s.start).0);
        out.push_str(&format!(
            "{:?} {} at line {line}: {}\n",
            d.severity, d.code, d.message
        ));
    }
    out
}
