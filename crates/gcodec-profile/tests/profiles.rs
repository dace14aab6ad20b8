//! The shipped profiles load; bad profiles give diagnostics that point
//! into the TOML (snapshots of the rendered diagnostics).

use std::path::PathBuf;

use gcodec_profile::*;
use gcodec_source::{RenderOptions, SourceFile, render_diagnostics};

fn profiles_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../profiles")
}

fn load_file(name: &str) -> Profile {
    let text = std::fs::read_to_string(profiles_dir().join(name)).expect("readable");
    load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"))
}

/// The rendered diagnostics of a bad profile.
fn rejected(text: &str) -> String {
    let diagnostics = load(text).expect_err("the profile is rejected");
    assert!(
        diagnostics.iter().all(|d| !d.labels.is_empty()),
        "{diagnostics:#?}"
    );
    let file = SourceFile::new("bad.toml", text);
    render_diagnostics(
        &diagnostics,
        Some(&file),
        RenderOptions {
            color: false,
            limit: None,
        },
    )
}

#[test]
fn every_shipped_profile_loads() {
    let mut names: Vec<_> = std::fs::read_dir(profiles_dir())
        .expect("profiles/")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "default.toml",
            "grinder_fb422.toml",
            "lathe_828d.toml",
            "mill_5axis.toml",
            "mill_g505_g599.toml",
            "mill_tool_management.toml"
        ]
    );
    for name in names {
        load_file(&name);
    }
}

#[test]
fn the_builtin_profile_is_the_default_file() {
    let builtin = builtin().expect("the built-in profile loads");
    assert_eq!(
        BUILTIN_TOML,
        std::fs::read_to_string(profiles_dir().join("default.toml")).unwrap()
    );
    assert_eq!(builtin.machine.control, Control::Sinumerik840dSl);
    assert_eq!(
        builtin.tool_change.tool_change_mode,
        ToolChangeMode::DeferredM6
    );
    assert!(!builtin.tool_change.tool_management_enabled);
    assert_eq!(*builtin.tool_change.change_m_code.get_ref(), 6);
    assert_eq!(builtin.work_offsets.default_group8_offset.get_ref(), "G500");
}

#[test]
fn the_shipped_profiles_say_what_they_promise() {
    let tm = load_file("mill_tool_management.toml");
    assert!(tm.tool_change.tool_management_enabled);
    assert!(tm.tools.iter().all(|t| t.name.is_some()));
    let lathe = load_file("lathe_828d.toml");
    assert_eq!(lathe.machine.control, Control::Sinumerik828d);
    assert_eq!(lathe.tool_change.tool_change_mode, ToolChangeMode::Direct);
    assert!(
        lathe
            .axes
            .iter()
            .any(|a| a.diameter && a.name.get_ref() == "X")
    );
    let defaults: Vec<(&str, &str)> = lathe
        .modal_defaults
        .iter()
        .map(|(g, c)| (g.get_ref().as_str(), c.get_ref().as_str()))
        .collect();
    for pair in [("6", "G18"), ("15", "G95"), ("29", "DIAMON")] {
        assert!(defaults.contains(&pair), "{pair:?} in {defaults:?}");
    }
    let wide = load_file("mill_g505_g599.toml");
    let ranges: Vec<_> = wide
        .work_offsets
        .supported_group8_offsets
        .iter()
        .map(|r| group8_range(r.get_ref()).unwrap())
        .collect();
    assert_eq!(ranges, [(0, 0), (1, 4), (5, 99)]);
}

#[test]
fn defaults_fill_what_a_profile_leaves_out() {
    let p = load("[machine]\nname = \"m\"\ncontrol = \"828d\"\n").expect("minimal profile");
    assert_eq!(p.axes.len(), 3);
    assert_eq!(*p.m_functions.max_m_per_block.get_ref(), 5);
    assert_eq!(p.m_functions.unknown_mcode_policy, Policy::Warning);
    assert_eq!(
        p.work_offsets.duplicate_suppression_policy,
        DuplicateSuppressionPolicy::Warn
    );
    assert_eq!(*p.program.max_block_length.get_ref(), 512);
}

const MACHINE: &str = "[machine]\nname = \"m\"\ncontrol = \"840d_sl\"\n";

#[test]
fn file_size_limit_and_link_targets() {
    let p = load(MACHINE).expect("minimal profile");
    assert_eq!(
        *p.program.max_file_size.get_ref(),
        gcodec_source::DEFAULT_MAX_FILE_SIZE
    );
    assert!(*p.program.max_file_size.get_ref() >= 256 << 20);
    assert!(p.program.link_target_paths.is_empty());
    let p = load(&format!(
        "{MACHINE}[program]\nmax_file_size = 4294967294\nlink_target_paths = [\"/shop/cycles\"]\n"
    ))
    .expect("the largest limit");
    assert_eq!(p.program.link_target_paths, ["/shop/cycles"]);
    for bad in ["0", "4294967295", "-1"] {
        let diagnostics =
            load(&format!("{MACHINE}[program]\nmax_file_size = {bad}\n")).expect_err(bad);
        assert!(
            diagnostics.iter().all(|d| !d.labels.is_empty()),
            "{bad}: {diagnostics:#?}"
        );
    }
}

#[test]
fn toml_syntax_error() {
    insta::assert_snapshot!(rejected("[machine\nname = 1\n"));
}

#[test]
fn unknown_key() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[tool_change]\ntool_chnage_mode = \"direct\"\n"
    )));
}

#[test]
fn wrong_type() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[m_functions]\nmax_m_per_block = \"five\"\n"
    )));
}

#[test]
fn unknown_policy_value() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[m_functions]\nunknown_mcode_policy = \"loud\"\n"
    )));
}

#[test]
fn out_of_range_values_are_all_reported() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[m_functions]\nmax_m_per_block = 0\n[program]\nskip_levels = [1, 12]\n[modal_defaults]\n65 = \"G1\"\n"
    )));
}

#[test]
fn overlapping_offset_ranges() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[work_offsets]\nsupported_group8_offsets = [\"G500\", \"G54-G57\", \"G56\", \"G505-G599\"]\n"
    )));
}

#[test]
fn references_to_missing_offsets_and_axes() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[work_offsets]\ndefault_group8_offset = \"G505\"\nlegacy_aliases = {{ G58 = \"G599\" }}\n[work_offsets.values.G54]\nW = 5.0\n"
    )));
}

#[test]
fn duplicate_tools_and_unnamed_tools_under_tool_management() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[tool_change]\ntool_management_enabled = true\n[[tools]]\nnumber = 1\nname = \"DRILL\"\n[[tools]]\nnumber = 1\nname = \"drill\"\n[[tools]]\nnumber = 2\nedges = [{{ d = 1 }}, {{ d = 1 }}]\n"
    )));
}

/// MD20270 is −2…32000 (−2 and −1 keep the old edge or offset, 0 none).
#[test]
fn a_cutting_edge_default_below_minus_two_or_beyond_the_edges() {
    for edge in [-3, 32_001] {
        let text = format!("{MACHINE}[tool_change]\ncutting_edge_default = {edge}\n");
        assert!(
            rejected(&text).contains("`cutting_edge_default` ranges over -2…32000"),
            "{edge}"
        );
    }
    for edge in [-2, -1, 0, 32_000] {
        let text = format!("{MACHINE}[tool_change]\ncutting_edge_default = {edge}\n");
        let profile = load(&text).unwrap_or_else(|d| panic!("{edge}: {d:#?}"));
        assert_eq!(*profile.tool_change.cutting_edge_default.get_ref(), edge);
    }
}

#[test]
fn duplicate_and_misdeclared_axes() {
    insta::assert_snapshot!(rejected(&format!(
        "{MACHINE}[[axes]]\nname = \"X\"\nkind = \"linear\"\n[[axes]]\nname = \"x\"\nkind = \"linear\"\n[[axes]]\nname = \"C\"\nkind = \"rotary\"\ndiameter = true\nrapid = 0.0\n"
    )));
}

/// The annotated example in profiles/README.md is a valid profile, so the
/// schema documentation cannot drift from the code.
#[test]
fn the_documented_example_loads() {
    let readme = std::fs::read_to_string(profiles_dir().join("README.md")).expect("README");
    let example = readme
        .split("```toml\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a toml block");
    let p = load(example).unwrap_or_else(|d| panic!("{d:#?}"));
    assert_eq!(p.m_functions.mcode_class_overrides.len(), 1);
    assert_eq!(p.work_offsets.legacy_aliases.len(), 1);
    assert_eq!(p.tools.len(), 1);
}
