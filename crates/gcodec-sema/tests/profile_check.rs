//! `gcodec_sema::check_profile`: the profile checks that need the G-group
//! registry (`modal_defaults`, `[g_codes] unsupported`, `legacy_aliases`),
//! with spans into the TOML; every shipped profile passes; lowering stays
//! robust with a profile nobody checked.

use gcodec_profile::Profile;
use gcodec_sema::check_profile;
use gcodec_sema::modal::{ModalState, ModalStates, Start};
use gcodec_source::{Diagnostic, RenderOptions, SourceFile, render_diagnostics};

mod common;

const MACHINE: &str = "[machine]\nname = \"test\"\ncontrol = \"840d_sl\"\n";

/// `MACHINE` + `sections`, loaded (the form must be right).
fn text(sections: &str) -> String {
    format!("{MACHINE}{sections}")
}

fn load(text: &str) -> Profile {
    gcodec_profile::load(text).unwrap_or_else(|d| panic!("{text}\n{d:#?}"))
}

/// The diagnostics of `check_profile` for `MACHINE` + `sections`; each has
/// a label, and the first label's span lies inside the text.
fn check(sections: &str) -> (String, Vec<Diagnostic>) {
    let text = text(sections);
    let diagnostics = check_profile(&load(&text));
    for d in &diagnostics {
        assert!(!d.labels.is_empty(), "{d:#?}");
        for label in &d.labels {
            assert!(
                label.span.start < label.span.end && label.span.end as usize <= text.len(),
                "{d:#?}"
            );
        }
    }
    (text, diagnostics)
}

fn codes(sections: &str) -> Vec<&'static str> {
    check(sections).1.iter().map(|d| d.code.name()).collect()
}

/// The TOML text under the first label of the only diagnostic.
fn labelled(sections: &str) -> (String, Diagnostic) {
    let (text, diagnostics) = check(sections);
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let d = diagnostics.into_iter().next().expect("one");
    let s = d.labels[0].span;
    (text[s.start as usize..s.end as usize].to_owned(), d)
}

fn help(d: &Diagnostic) -> &str {
    d.help.as_deref().unwrap_or("")
}

fn render(text: &str, diagnostics: &[Diagnostic]) -> String {
    let file = SourceFile::new("bad.toml", text);
    render_diagnostics(
        diagnostics,
        Some(&file),
        RenderOptions {
            color: false,
            limit: None,
        },
    )
}

// ---- what passes ----

#[test]
fn every_shipped_profile_passes() {
    let mut names: Vec<String> = std::fs::read_dir(common::repo().join("profiles"))
        .expect("profiles/")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 6, "{names:?}");
    for name in &names {
        let profile = common::profile(name);
        let diagnostics = check_profile(&profile);
        assert!(diagnostics.is_empty(), "{name}: {diagnostics:#?}");
    }
}

#[test]
fn the_built_in_profile_passes() {
    let profile = gcodec_profile::builtin().expect("built-in profile");
    assert!(check_profile(&profile).is_empty());
}

/// The annotated example in profiles/README.md (as the profile crate's
/// test reads it).
#[test]
fn the_documented_example_passes() {
    let readme =
        std::fs::read_to_string(common::repo().join("profiles/README.md")).expect("README");
    let example = readme
        .split("```toml\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a toml block");
    let diagnostics = check_profile(&load(example));
    assert!(diagnostics.is_empty(), "{diagnostics:#?}");
}

#[test]
fn good_entries_pass() {
    for sections in [
        "",
        "[modal_defaults]\n1 = \"G0\"\n6 = \"G18\"\n15 = \"G95\"\n29 = \"DIAMON\"\n",
        // Case and leading zeros as the control reads them.
        "[modal_defaults]\n1 = \"G01\"\n6 = \"g18\"\n10 = \"g64\"\n",
        "[modal_defaults]\n8 = \"G500\"\n",
        "[modal_defaults]\n8 = \"G054\"\n[work_offsets]\ndefault_group8_offset = \"G54\"\n",
        "[g_codes]\nunsupported = [\"G33\", \"cip\", \"OEMIPO1\", \"G01\"]\nunsupported_groups = [35]\n",
        "[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\nlegacy_aliases = { G58 = \"G505\", G59 = \"G506\", G99 = \"G507\" }\n",
        // A default of a group the control keeps, next to ruled-out ones.
        "[modal_defaults]\n6 = \"G18\"\n[g_codes]\nunsupported = [\"G17\"]\nunsupported_groups = [35]\n",
    ] {
        assert_eq!(codes(sections), Vec::<&str>::new(), "{sections}");
    }
}

// ---- modal_defaults ----

#[test]
fn a_code_of_another_group_names_the_right_one() {
    let (at, d) = labelled("[modal_defaults]\n1 = \"G17\"\n");
    assert_eq!(d.code, "gcodec::profile::not_in_group");
    assert_eq!(at, "\"G17\"");
    assert!(d.message.contains("group 1"), "{}", d.message);
    assert!(help(&d).contains("group 6"), "{}", help(&d));
    assert!(help(&d).contains("6 = \"G17\""), "{}", help(&d));
    // The second label is the group.
    assert_eq!(d.labels.len(), 2);
    let (text, _) = check("[modal_defaults]\n1 = \"G17\"\n");
    let key = d.labels[1].span;
    assert_eq!(&text[key.start as usize..key.end as usize], "1");

    assert_eq!(
        codes("[modal_defaults]\n8 = \"G17\"\n15 = \"DIAMON\"\n"),
        [
            "gcodec::profile::not_in_group",
            "gcodec::profile::not_in_group"
        ]
    );
}

#[test]
fn an_unknown_code_lists_the_group() {
    let (at, d) = labelled("[modal_defaults]\n6 = \"G999\"\n");
    assert_eq!(d.code, "gcodec::profile::unknown_g_code");
    assert_eq!(at, "\"G999\"");
    assert!(help(&d).contains("`G17`, `G18`, `G19`"), "{}", help(&d));
    // A long group is shortened.
    let (_, d) = labelled("[modal_defaults]\n8 = \"G5000\"\n");
    assert!(help(&d).contains("100 commands"), "{}", help(&d));
    let (_, d) = labelled("[modal_defaults]\n1 = \"\\u00e9\"\n");
    assert_eq!(d.code, "gcodec::profile::unknown_g_code");
}

#[test]
fn non_modal_and_unassigned_groups_have_no_reset_default() {
    for (group, code) in [
        (2, "G4"),
        (3, "TRANS"),
        (9, "G53"),
        (11, "G9"),
        (62, "RMBBL"),
    ] {
        let (at, d) = labelled(&format!("[modal_defaults]\n{group} = \"{code}\"\n"));
        assert_eq!(d.code, "gcodec::profile::not_modal", "{group}");
        assert_eq!(at, group.to_string());
    }
    for group in [5, 63] {
        let (at, d) = labelled(&format!("[modal_defaults]\n{group} = \"G1\"\n"));
        assert_eq!(d.code, "gcodec::profile::unassigned_group", "{group}");
        assert_eq!(at, group.to_string());
    }
}

#[test]
fn a_group_given_twice_is_a_duplicate() {
    let (text, diagnostics) = check("[modal_defaults]\n6 = \"G18\"\n06 = \"G17\"\n");
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    assert_eq!(diagnostics[0].code, "gcodec::profile::duplicate");
    assert_eq!(diagnostics[0].labels.len(), 2);
    let rendered = render(&text, &diagnostics);
    assert!(rendered.contains("group 6 is given twice"), "{rendered}");
}

#[test]
fn a_default_the_profile_rules_out() {
    let (at, d) =
        labelled("[modal_defaults]\n29 = \"DIAMON\"\n[g_codes]\nunsupported_groups = [29]\n");
    assert_eq!(d.code, "gcodec::profile::unsupported_default");
    assert_eq!(at, "\"DIAMON\"");
    assert!(help(&d).contains("unsupported_groups"), "{}", help(&d));
    let (_, d) =
        labelled("[modal_defaults]\n29 = \"DIAMON\"\n[g_codes]\nunsupported = [\"diamon\"]\n");
    assert_eq!(d.code, "gcodec::profile::unsupported_default");
    assert!(help(&d).contains("unsupported`"), "{}", help(&d));
}

#[test]
fn group_8_must_agree_with_the_default_offset() {
    // `default_group8_offset` not written: it is G500.
    let (at, d) = labelled("[modal_defaults]\n8 = \"G54\"\n");
    assert_eq!(d.code, "gcodec::profile::conflicting_defaults");
    assert_eq!(at, "\"G54\"");
    assert_eq!(d.labels.len(), 1);
    assert!(help(&d).contains("G500"), "{}", help(&d));
    // Written: both are labelled.
    let (text, diagnostics) =
        check("[modal_defaults]\n8 = \"G500\"\n[work_offsets]\ndefault_group8_offset = \"G54\"\n");
    assert_eq!(diagnostics.len(), 1, "{diagnostics:#?}");
    let d = &diagnostics[0];
    assert_eq!(d.code, "gcodec::profile::conflicting_defaults");
    assert_eq!(d.labels.len(), 2);
    let other = d.labels[1].span;
    assert_eq!(&text[other.start as usize..other.end as usize], "\"G54\"");
    // The contradiction the lathe profile once had: G54 is what counts.
    let lathe = common::profile("lathe_828d.toml");
    let group8: Vec<_> = lathe
        .modal_defaults
        .iter()
        .filter(|(g, _)| g.get_ref() == "8")
        .map(|(_, c)| c.get_ref().as_str())
        .collect();
    assert_eq!(group8, ["G54"]);
    assert_eq!(lathe.work_offsets.default_group8_offset.get_ref(), "G54");
}

// ---- [g_codes] and legacy_aliases ----

#[test]
fn unsupported_names_are_commands_of_the_registry() {
    let (at, d) = labelled("[g_codes]\nunsupported = [\"G33\", \"G999\", \"OEMIPO1\"]\n");
    assert_eq!(d.code, "gcodec::profile::unknown_g_code");
    assert_eq!(at, "\"G999\"");
    assert_eq!(
        codes("[g_codes]\nunsupported = [\"NOSUCH\", \"G333\"]\n"),
        [
            "gcodec::profile::unknown_g_code",
            "gcodec::profile::unknown_g_code"
        ]
    );
}

#[test]
fn an_alias_may_not_redefine_a_command_of_another_group() {
    let aliases =
        "[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G505-G599\"]\n";
    let (at, d) = labelled(&format!("{aliases}legacy_aliases = {{ G1 = \"G505\" }}\n"));
    assert_eq!(d.code, "gcodec::profile::alias_conflict");
    assert_eq!(at, "G1");
    assert!(d.message.contains("group 1"), "{}", d.message);
    assert_eq!(
        codes(&format!(
            "{aliases}legacy_aliases = {{ G58 = \"G505\", G60 = \"G506\", G17 = \"G507\" }}\n"
        )),
        [
            "gcodec::profile::alias_conflict",
            "gcodec::profile::alias_conflict"
        ]
    );
}

#[test]
fn diagnostics_come_in_text_order_and_render_into_the_toml() {
    let (text, diagnostics) =
        check("[modal_defaults]\n1 = \"G17\"\n2 = \"G4\"\n[g_codes]\nunsupported = [\"G999\"]\n");
    let codes: Vec<_> = diagnostics.iter().map(|d| d.code.name()).collect();
    assert_eq!(
        codes,
        [
            "gcodec::profile::not_in_group",
            "gcodec::profile::not_modal",
            "gcodec::profile::unknown_g_code"
        ]
    );
    let rendered = render(&text, &diagnostics);
    assert!(rendered.contains("bad.toml:5:5"), "{rendered}");
    assert!(rendered.contains("bad.toml:6:1"), "{rendered}");
    assert!(rendered.contains("bad.toml:8:16"), "{rendered}");
}

// ---- unchecked profiles ----

/// A library user may skip the check: lowering and the modal analysis
/// must cope with any entry, and the reset state keeps its defaults.
#[test]
fn an_unchecked_profile_neither_panics_nor_changes_the_reset_state() {
    let mut profile = load(&text(
        "[modal_defaults]\n1 = \"G17\"\n2 = \"G4\"\n5 = \"G1\"\n6 = \"G999\"\n9 = \"G53\"\n\
         [g_codes]\nunsupported = [\"G999\"]\n",
    ));
    // Keys `load` itself rejects, put in behind its back.
    let template = profile
        .modal_defaults
        .iter()
        .next()
        .map(|(k, v)| (k.clone(), v.clone()))
        .expect("an entry");
    for (group, code) in [
        ("0", "G1"),
        ("65", "G1"),
        ("255", "G0"),
        ("x", "G0"),
        ("", ""),
    ] {
        let (mut k, mut v) = template.clone();
        *k.get_mut() = group.to_owned();
        *v.get_mut() = code.to_owned();
        profile.modal_defaults.insert(k, v);
    }
    let _ = check_profile(&profile);
    let reset = ModalState::reset(&profile);
    let builtin = ModalState::reset(&gcodec_profile::builtin().expect("built-in"));
    assert_eq!(reset.get(1), Some("G1"));
    assert_eq!(reset.get(2), None);
    assert_eq!(reset.get(6), Some("G17"));
    assert_eq!(reset.get(9), None);
    for group in 1..=64 {
        assert_eq!(reset.get(group), builtin.get(group), "group {group}");
    }
    let parsed = gcodec_parser::parse_bytes("t.mpf", b"G1 X1\nG4 F1\nG17 G53 X0\nM30\n");
    let lowered = gcodec_sema::lower(&parsed.program, &profile);
    assert!(!lowered.has_errors(), "{:#?}", lowered.diagnostics);
    let states = ModalStates::analyse(&lowered.document, Start::Reset(&profile));
    assert!(states.state_at_line(1).is_some());
}
