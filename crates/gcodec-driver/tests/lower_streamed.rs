//! `gcodec lower` streamed writes the bytes lowering the whole program
//! writes: the listing and the JSON document of every fixture, example
//! and corpus program, cut into chunks of a few lines so that chunk ends
//! fall everywhere, and the same diagnostics in the same order.

use std::sync::Arc;

use gcodec_driver::lower::{Page, write_json, write_listing};
use gcodec_driver::{Definitions, ProgramKind, StreamOptions, compile, lower_streamed};
use gcodec_profile::Profile;
use gcodec_source::{Diagnostics, SourceFile};
use gcodec_testkit::corpus::{definitions, machine_profile};
use gcodec_testkit::{all_programs, corpus_dir, shown};

/// What the whole program's lowering writes: the listing and the JSON.
fn whole(file: &Arc<SourceFile>, profile: &Profile, definitions: &Definitions) -> Written {
    let kind = ProgramKind::of_file(file.name());
    let compiled = compile(Arc::clone(file), kind, profile, definitions);
    let mut listing = String::new();
    gcodec_driver::write_listing(&compiled.document, &mut listing).expect("listing");
    let mut json = serde_json::to_vec_pretty(&compiled.document).expect("json");
    json.push(b'\n');
    Written {
        listing: listing.into_bytes(),
        json,
        diagnostics: compiled.diagnostics,
    }
}

struct Written {
    listing: Vec<u8>,
    json: Vec<u8>,
    diagnostics: Diagnostics,
}

/// What the streamed lowering writes with `options`, and how many pages
/// it handed on.
fn streamed(
    file: &Arc<SourceFile>,
    profile: &Profile,
    definitions: &Definitions,
    options: StreamOptions,
) -> (Written, usize) {
    let kind = ProgramKind::of_file(file.name());
    let mut pages = 0;
    let write = |written: &mut dyn FnMut(&mut dyn Iterator<Item = Page>) -> std::io::Result<()>| {
        let ((), diagnostics) = lower_streamed(file, kind, profile, definitions, options, |p| {
            written(p).expect("written to memory");
        });
        diagnostics
    };
    let mut listing = Vec::new();
    write(&mut |p| write_listing(p.inspect(|_| pages += 1), &mut listing));
    let mut json = Vec::new();
    let diagnostics = write(&mut |p| write_json(p, &mut json));
    let written = Written {
        listing,
        json,
        diagnostics,
    };
    (written, pages)
}

fn assert_streamed_agrees(
    name: &str,
    file: SourceFile,
    profile: &Profile,
    definitions: &Definitions,
) {
    let file = Arc::new(file);
    let expected = whole(&file, profile, definitions);
    for page_lines in [1, 3, 7] {
        for workers in [1, 2] {
            let options = StreamOptions {
                page_lines,
                workers,
            };
            let place = format!("{name}, chunks of {page_lines} lines, {workers} workers");
            let (written, _) = streamed(&file, profile, definitions, options);
            assert!(
                written.listing == expected.listing,
                "{place}: the listing differs:\n{}",
                first_difference(&written.listing, &expected.listing)
            );
            assert!(
                written.json == expected.json,
                "{place}: the JSON differs:\n{}",
                first_difference(&written.json, &expected.json)
            );
            assert_eq!(
                written.diagnostics[..],
                expected.diagnostics[..],
                "{place}: the diagnostics differ"
            );
            assert_eq!(written.diagnostics.total(), expected.diagnostics.total());
            assert_eq!(
                written.diagnostics.has_errors(),
                expected.diagnostics.has_errors()
            );
        }
    }
}

/// The lines around where `a` and `b` first differ.
fn first_difference(a: &[u8], b: &[u8]) -> String {
    let (a, b) = (String::from_utf8_lossy(a), String::from_utf8_lossy(b));
    let at = a
        .lines()
        .zip(b.lines())
        .position(|(x, y)| x != y)
        .unwrap_or_else(|| a.lines().count().min(b.lines().count()));
    let around = |s: &str| {
        s.lines()
            .skip(at.saturating_sub(3))
            .take(7)
            .collect::<Vec<_>>()
            .join("\n")
    };
    format!(
        "line {}:\nstreamed:\n{}\nwhole:\n{}",
        at + 1,
        around(&a),
        around(&b)
    )
}

#[test]
fn fixtures_examples_and_corpus_lower_the_same_streamed() {
    let builtin = gcodec_profile::builtin().expect("built-in profile");
    let corpus = corpus_dir();
    let all = all_programs();
    assert!(all.len() >= 30, "found only {} programs", all.len());
    let mut from_corpus = 0;
    for path in all {
        let bytes = std::fs::read(&path).expect("readable");
        let in_corpus = corpus.as_deref().filter(|c| path.starts_with(c));
        let (profile, definitions, name) = match in_corpus {
            Some(corpus) => {
                from_corpus += 1;
                let name = shown(corpus, &path);
                let (_, profile) = machine_profile(&name);
                (profile, definitions(corpus, &name), name)
            }
            None => (
                builtin.clone(),
                Definitions::new(),
                path.display().to_string(),
            ),
        };
        let file = SourceFile::new(path.display().to_string(), bytes);
        assert_streamed_agrees(&name, file, &profile, &definitions);
    }
    if corpus.is_some() {
        assert!(from_corpus > 0, "no corpus program found");
    }
}

/// A motion after a join whose command only the dataflow over the whole
/// program knows: what comes before it is streamed a page a chunk, the
/// rest is held and handed on filled in, as one page.
#[test]
fn the_instructions_from_the_first_open_one_on_are_held() {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    let definitions = Definitions::new();
    let straight = "G1 X0 F100\nX1\nX2\nX3\nX4\nM30\n";
    let joined = "G1 X0 F100\nX1\nLBL:\nX2\nR1=R1+1\nIF R1<3 GOTOB LBL\nX3\nM30\n";
    let options = StreamOptions {
        page_lines: 1,
        workers: 2,
    };
    let lower = |name: &str, text: &str| {
        let file = SourceFile::new(name, text);
        assert_streamed_agrees(name, file.clone(), &profile, &definitions);
        streamed(&Arc::new(file), &profile, &definitions, options).1
    };
    // Six chunks and the end.
    assert_eq!(lower("straight.mpf", straight), 7);
    // The motion after `LBL:` (line 4) is open: lines 1–3 are three
    // pages, what line 4 has before it a fourth, and the rest, held, one.
    let held = lower("joined.mpf", joined);
    assert_eq!(held, 5);
    // The whole program fills in the motion at line 4: lowering left it
    // open.
    let file = Arc::new(SourceFile::new("joined.mpf", joined));
    let compiled = compile(Arc::clone(&file), ProgramKind::Main, &profile, &definitions);
    let motion = compiled
        .document
        .instructions
        .iter()
        .find(|i| i.source.line == 4 && matches!(i.op, gcodec_ail::Op::Motion { .. }))
        .expect("a motion at line 4");
    assert!(
        matches!(&motion.op, gcodec_ail::Op::Motion { motion, .. } if *motion == gcodec_lang::MotionKind::Linear),
        "{motion:?}"
    );
}
