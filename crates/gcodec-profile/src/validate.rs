//! Checks a profile beyond its types: ranges, references between sections,
//! duplicates, overlaps. Every problem found is reported.

use std::collections::{BTreeMap, BTreeSet};

use gcodec_source::{Code, Diagnostic, MAX_SOURCE_LEN, codes};
use toml::Spanned;

use crate::group8::{group8_index, group8_range};
use crate::schema::*;
use crate::span;
/// Largest M value and T number (`0…2147483647`, per the M-function design).
const MAX_ADDRESS_VALUE: u32 = i32::MAX as u32;
/// The largest cutting edge number (`D32000`).
const MAX_EDGE: u32 = 32_000;

pub(crate) fn check(profile: &Profile) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    check_spindles(&profile.machine.spindles, &mut out);
    check_axes(&profile.axes, &mut out);
    check_modal_defaults(profile, &mut out);
    check_tools(profile, &mut out);
    check_m_functions(&profile.m_functions, &mut out);
    check_work_offsets(profile, &mut out);
    check_program(&profile.program, &mut out);
    check_g_codes(&profile.g_codes, &mut out);
    if let Some(toolchanger) = &profile.toolchanger {
        check_toolchanger(toolchanger, &profile.tools, &mut out);
    }
    crate::system_variables::check(profile, &mut out);
    out
}

/// The form of `[g_codes]` entries. Whether a name is a command of the
/// control is checked by the semantic stage, which owns the G-group
/// registry (`gcodec_sema::check_profile`, `gcodec::profile::unknown_g_code`).
fn check_g_codes(g: &GCodes, out: &mut Vec<Diagnostic>) {
    let mut seen = BTreeSet::new();
    for code in &g.unsupported {
        let name = code.get_ref();
        let valid = name.bytes().next().is_some_and(|b| b.is_ascii_alphabetic())
            && name.bytes().all(|b| b.is_ascii_alphanumeric())
            && name.len() <= 10;
        if !valid {
            out.push(
                error(
                    codes::profile::OUT_OF_RANGE,
                    code,
                    format!("`{name}` is not a G command"),
                    "here",
                )
                .with_help("write G commands as the program does, e.g. `\"G33\"`, `\"OEMIPO1\"`"),
            );
        }
        if !seen.insert(name.to_ascii_uppercase()) {
            out.push(error(
                codes::profile::DUPLICATE,
                code,
                format!("`{name}` is listed twice"),
                "again here",
            ));
        }
    }
    let mut groups = BTreeSet::new();
    for group in &g.unsupported_groups {
        if !(1..=64).contains(group.get_ref()) {
            out.push(not_a_group(group, ""));
        }
        if !groups.insert(*group.get_ref()) {
            out.push(error(
                codes::profile::DUPLICATE,
                group,
                format!("group {} is listed twice", group.get_ref()),
                "again here",
            ));
        }
    }
}

pub(crate) fn error<T>(
    code: &'static Code,
    at: &Spanned<T>,
    message: String,
    label: &'static str,
) -> Diagnostic {
    Diagnostic::new(code, message).with_label(span(at.span()), label)
}

/// A G group number outside 1…64; `example` ends the help.
fn not_a_group<T: std::fmt::Display>(group: &Spanned<T>, example: &str) -> Diagnostic {
    error(
        codes::profile::OUT_OF_RANGE,
        group,
        format!("`{}` is not a G group", group.get_ref()),
        "here",
    )
    .with_help(format!("G groups are numbered 1 to 64{example}"))
}

fn check_spindles(spindles: &[Spanned<u32>], out: &mut Vec<Diagnostic>) {
    let mut seen = BTreeSet::new();
    for spindle in spindles {
        if !(1..=99).contains(spindle.get_ref()) {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                spindle,
                "spindle numbers range over 1…99".into(),
                "here",
            ));
        }
        if !seen.insert(*spindle.get_ref()) {
            out.push(error(
                codes::profile::DUPLICATE,
                spindle,
                format!("spindle {} is listed twice", spindle.get_ref()),
                "again here",
            ));
        }
    }
}

/// Fixed points per axis (MD30600 `$MA_FIX_POINT_POS[0…3]`).
const MAX_FIXED_POINTS: usize = 4;

fn check_axes(axes: &[Axis], out: &mut Vec<Diagnostic>) {
    let mut seen: BTreeMap<String, &Spanned<String>> = BTreeMap::new();
    for axis in axes {
        let name = axis.name.get_ref();
        let valid = name.len() <= 8
            && name.bytes().next().is_some_and(|b| b.is_ascii_alphabetic())
            && name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_');
        if !valid {
            out.push(
                error(codes::profile::OUT_OF_RANGE, &axis.name, format!("`{name}` is not an axis name"), "here")
                    .with_help("an axis name is a letter followed by up to 7 letters, digits or `_`, e.g. `X`, `C1`"),
            );
        }
        if let Some(first) = seen.insert(name.to_ascii_uppercase(), &axis.name) {
            out.push(
                error(
                    codes::profile::DUPLICATE,
                    &axis.name,
                    format!("axis `{name}` is listed twice"),
                    "again here",
                )
                .with_label(span(first.span()), "first here"),
            );
        }
        if axis.diameter && axis.kind != AxisKind::Linear {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                &axis.name,
                format!("the diameter axis `{name}` must be linear"),
                "rotary",
            ));
        }
        if !axis.reference_point.get_ref().is_finite() {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                &axis.reference_point,
                "a reference point is a finite position".into(),
                "here",
            ));
        }
        for (n, point) in axis.fixed_points.iter().enumerate() {
            if n == MAX_FIXED_POINTS {
                out.push(
                    error(
                        codes::profile::OUT_OF_RANGE,
                        point,
                        format!("axis `{name}` has more than {MAX_FIXED_POINTS} fixed points"),
                        "the fifth",
                    )
                    .with_help(
                        "MD30600 holds up to four fixed points per axis (`G75 FP=1`…`FP=4`)",
                    ),
                );
            }
            if !point.get_ref().is_finite() {
                out.push(error(
                    codes::profile::OUT_OF_RANGE,
                    point,
                    "a fixed point is a finite position".into(),
                    "here",
                ));
            }
        }
        if !(axis.rapid.get_ref().is_finite() && *axis.rapid.get_ref() > 0.0) {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                &axis.rapid,
                "a rapid rate must be above 0".into(),
                "here",
            ));
        }
    }
    let geometry = axes.iter().filter(|a| a.geometry).count();
    if geometry > 3
        && let Some(fourth) = axes.iter().filter(|a| a.geometry).nth(3)
    {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &fourth.name,
            "a channel has at most three geometry axes".into(),
            "the fourth",
        ));
    }
    if let Some(second) = axes.iter().filter(|a| a.diameter).nth(1) {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &second.name,
            "a channel has one diameter axis".into(),
            "a second one",
        ));
    }
}

fn check_modal_defaults(profile: &Profile, out: &mut Vec<Diagnostic>) {
    for (group, code) in &profile.modal_defaults {
        if !group
            .get_ref()
            .parse::<u8>()
            .is_ok_and(|g| (1..=64).contains(&g))
        {
            out.push(not_a_group(group, ", e.g. `8 = \"G54\"`"));
        }
        if code.get_ref().trim().is_empty() {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                code,
                "empty G code".into(),
                "here",
            ));
        }
    }
}

fn check_tools(profile: &Profile, out: &mut Vec<Diagnostic>) {
    let change = &profile.tool_change;
    if *change.change_m_code.get_ref() > MAX_ADDRESS_VALUE {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &change.change_m_code,
            format!("M values range over 0…{MAX_ADDRESS_VALUE}"),
            "here",
        ));
    }
    let edge = *change.cutting_edge_default.get_ref();
    if !(-2..=i64::from(MAX_EDGE)).contains(&edge) {
        out.push(
            error(
                codes::profile::OUT_OF_RANGE,
                &change.cutting_edge_default,
                format!("`cutting_edge_default` ranges over -2…{MAX_EDGE}"),
                "here",
            )
            .with_help("MD20270: 0 no edge, n edge n, -1 the old edge number, -2 the old tool's offset until a `D`"),
        );
    }
    let mut numbers: BTreeMap<(u32, u32), &Spanned<u32>> = BTreeMap::new();
    let mut names: BTreeMap<(String, u32), &Spanned<String>> = BTreeMap::new();
    for tool in &profile.tools {
        let number = *tool.number.get_ref();
        if number == 0 || number > MAX_ADDRESS_VALUE {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                &tool.number,
                format!("tool numbers range over 1…{MAX_ADDRESS_VALUE} (T0 deselects)"),
                "here",
            ));
        }
        if let Some(first) = numbers.insert((number, tool.duplo), &tool.number) {
            out.push(
                error(
                    codes::profile::DUPLICATE,
                    &tool.number,
                    format!("tool {number} (duplo {}) is listed twice", tool.duplo),
                    "again here",
                )
                .with_label(span(first.span()), "first here"),
            );
        }
        match &tool.name {
            Some(name) => {
                if let Some(first) = names.insert((name.get_ref().to_ascii_uppercase(), tool.duplo), name) {
                    out.push(
                        error(codes::profile::DUPLICATE, name, format!("tool `{}` (duplo {}) is listed twice", name.get_ref(), tool.duplo), "again here")
                            .with_label(span(first.span()), "first here")
                            .with_help("sister tools share a name and differ in `duplo`"),
                    );
                }
            }
            None if change.tool_management_enabled => out.push(
                error(codes::profile::OUT_OF_RANGE, &tool.number, format!("tool {number} has no name"), "this tool")
                    .with_help("with `tool_management_enabled`, tools are selected by name: add `name = \"…\"`"),
            ),
            None => {}
        }
        let mut edges = BTreeSet::new();
        for edge in &tool.edges {
            let d = *edge.d.get_ref();
            if !(1..=MAX_EDGE).contains(&d) {
                out.push(error(
                    codes::profile::OUT_OF_RANGE,
                    &edge.d,
                    format!("cutting edges are D1…D{MAX_EDGE} (D0 deselects)"),
                    "here",
                ));
            }
            if let Some(tool_type) = &edge.tool_type
                && !(100..=999).contains(tool_type.get_ref())
            {
                out.push(error(
                    codes::profile::OUT_OF_RANGE,
                    tool_type,
                    "a tool type is 100…999 (1xx milling, 2xx drilling, 4xx grinding, 5xx turning, 7xx special, 9xx auxiliary)".to_owned(),
                    "here",
                ));
            }
            if *edge.position.get_ref() > 9 {
                out.push(error(
                    codes::profile::OUT_OF_RANGE,
                    &edge.position,
                    "a cutting edge position is 0…9 (0: none)".to_owned(),
                    "here",
                ));
            }
            if !edges.insert(d) {
                out.push(error(
                    codes::profile::DUPLICATE,
                    &edge.d,
                    format!("tool {number} has D{d} twice"),
                    "again here",
                ));
            }
        }
    }
}

fn check_m_functions(m: &MFunctions, out: &mut Vec<Diagnostic>) {
    check_auxiliary_groups(m, out);
    if !(1..=16).contains(m.max_m_per_block.get_ref()) {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &m.max_m_per_block,
            "`max_m_per_block` ranges over 1…16".into(),
            "here",
        ));
    }
    for value in m.mcode_class_overrides.keys() {
        if !value
            .get_ref()
            .parse::<u32>()
            .is_ok_and(|v| v <= MAX_ADDRESS_VALUE)
        {
            out.push(
                error(
                    codes::profile::OUT_OF_RANGE,
                    value,
                    format!("`{}` is not an M value", value.get_ref()),
                    "here",
                )
                .with_help("keys are M values, e.g. `100 = \"custom\"`"),
            );
        }
    }
}

/// Groups numbered 1…64, M values of the address range, each in one group.
fn check_auxiliary_groups(m: &MFunctions, out: &mut Vec<Diagnostic>) {
    let mut seen: Vec<(u32, &str)> = Vec::new();
    for (group, values) in &m.auxiliary_groups {
        if !group
            .get_ref()
            .parse::<u8>()
            .is_ok_and(|g| (1..=64).contains(&g))
        {
            out.push(
                error(
                    codes::profile::OUT_OF_RANGE,
                    group,
                    format!("`{}` is not an auxiliary-function group", group.get_ref()),
                    "here",
                )
                .with_help("groups are numbered 1…64, e.g. `2 = [3, 4, 5, 70]`"),
            );
        }
        for value in values {
            let v = *value.get_ref();
            if v > MAX_ADDRESS_VALUE {
                out.push(error(
                    codes::profile::OUT_OF_RANGE,
                    value,
                    format!("`{v}` is not an M value"),
                    "here",
                ));
            } else if let Some((_, other)) = seen.iter().find(|(seen, _)| *seen == v) {
                out.push(
                    error(
                        codes::profile::DUPLICATE,
                        value,
                        format!("M{v} is in group {other} already"),
                        "again here",
                    )
                    .with_help("an M function belongs to one auxiliary-function group"),
                );
            } else {
                seen.push((v, group.get_ref()));
            }
        }
    }
}

fn check_work_offsets(profile: &Profile, out: &mut Vec<Diagnostic>) {
    let w = &profile.work_offsets;
    let mut supported: Vec<(u8, u8, &Spanned<String>)> = Vec::new();
    for entry in &w.supported_group8_offsets {
        match group8_range(entry.get_ref()) {
            Ok((lo, hi)) => {
                if let Some((_, _, other)) = supported.iter().find(|(a, b, _)| lo <= *b && *a <= hi)
                {
                    out.push(
                        error(
                            codes::profile::OVERLAPPING_RANGES,
                            entry,
                            format!("`{}` overlaps `{}`", entry.get_ref(), other.get_ref()),
                            "this range",
                        )
                        .with_label(span(other.span()), "overlaps this one"),
                    );
                }
                supported.push((lo, hi, entry));
            }
            Err(message) => out.push(
                error(codes::profile::OUT_OF_RANGE, entry, message, "here").with_help(
                    "write codes or ranges such as `\"G500\"`, `\"G54-G57\"`, `\"G505-G599\"`",
                ),
            ),
        }
    }
    let is_supported = |code: &str| {
        group8_index(code)
            .is_some_and(|i| supported.iter().any(|(lo, hi, _)| (*lo..=*hi).contains(&i)))
    };
    let unsupported = |at: &Spanned<String>, what: &str| {
        error(
            codes::profile::UNKNOWN_REFERENCE,
            at,
            format!(
                "{what} `{}` is not among `supported_group8_offsets`",
                at.get_ref()
            ),
            "here",
        )
    };
    if !is_supported(w.default_group8_offset.get_ref()) {
        out.push(unsupported(&w.default_group8_offset, "the default offset"));
    }
    for (alias, target) in &w.legacy_aliases {
        let name = alias.get_ref();
        let is_g_code = name
            .strip_prefix(['G', 'g'])
            .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()));
        if !is_g_code {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                alias,
                format!("`{name}` is not a G code"),
                "here",
            ));
        }
        if group8_index(name).is_some() {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                alias,
                format!("`{name}` is a Group 8 code itself"),
                "here",
            ));
        }
        if !is_supported(target.get_ref()) {
            out.push(unsupported(target, "the alias target"));
        }
    }
    let axes: BTreeSet<String> = profile
        .axes
        .iter()
        .map(|a| a.name.get_ref().to_ascii_uppercase())
        .collect();
    for (offset, values) in &w.values {
        if !is_supported(offset.get_ref()) {
            out.push(unsupported(offset, "the offset"));
        }
        for axis in values.keys() {
            if !axes.contains(&axis.get_ref().to_ascii_uppercase()) {
                out.push(error(
                    codes::profile::UNKNOWN_REFERENCE,
                    axis,
                    format!("`{}` is not an axis of this profile", axis.get_ref()),
                    "here",
                ));
            }
        }
    }
}

fn check_program(p: &ProgramSettings, out: &mut Vec<Diagnostic>) {
    for level in &p.skip_levels {
        if *level.get_ref() > 9 {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                level,
                "skip levels are 0…9".into(),
                "here",
            ));
        }
    }
    if *p.max_block_length.get_ref() == 0 {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &p.max_block_length,
            "a block length must be above 0".into(),
            "here",
        ));
    }
    if !(1..=MAX_SOURCE_LEN as u64).contains(p.max_file_size.get_ref()) {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &p.max_file_size,
            format!("a file size limit is 1…{MAX_SOURCE_LEN} bytes"),
            "here",
        ));
    }
    if gcodec_source::Encoding::for_label(p.code_page.get_ref()).is_none() {
        out.push(
            error(
                codes::profile::OUT_OF_RANGE,
                &p.code_page,
                format!("`{}` is not a code page program text can be in", p.code_page.get_ref()),
                "not a code page",
            )
            .with_help("name an ASCII-compatible encoding by its WHATWG label: `windows-1252` (the default), `windows-1251`, `iso-8859-2`, `utf-8`"),
        );
    }
    if !(p.max_feed.get_ref().is_finite() && *p.max_feed.get_ref() > 0.0) {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &p.max_feed,
            "a feed limit must be above 0".into(),
            "here",
        ));
    }
    for tolerance in [&p.circle_error_const, &p.circle_error_factor] {
        if !(tolerance.get_ref().is_finite() && *tolerance.get_ref() >= 0.0) {
            out.push(error(
                codes::profile::OUT_OF_RANGE,
                tolerance,
                "a circle tolerance must be 0 or more".into(),
                "here",
            ));
        }
    }
}

/// A cycle time and a timeout that a changer can run with; on a random
/// changer, one tool per pocket (iov2 warns "Attempt to assign multiple
/// toolno.s to pocket" and the swap would lose a tool).
fn check_toolchanger(t: &ToolchangerSettings, tools: &[Tool], out: &mut Vec<Diagnostic>) {
    if !(t.cycle_time.get_ref().is_finite() && *t.cycle_time.get_ref() > 0.0) {
        out.push(error(
            codes::profile::OUT_OF_RANGE,
            &t.cycle_time,
            "a cycle time is a number of seconds above 0".into(),
            "here",
        ));
    }
    if *t.timeout_cycles.get_ref() == 0 {
        out.push(
            error(
                codes::profile::OUT_OF_RANGE,
                &t.timeout_cycles,
                "a timeout is at least one cycle".into(),
                "here",
            )
            .with_help("every acknowledgement takes a cycle at least; the default is 100"),
        );
    }
    if !t.random {
        return;
    }
    let mut pockets: BTreeMap<u32, &Spanned<u32>> = BTreeMap::new();
    for tool in tools {
        let Some(pocket) = tool.location else {
            continue;
        };
        if let Some(first) = pockets.insert(pocket, &tool.number) {
            out.push(
                error(
                    codes::profile::DUPLICATE,
                    &tool.number,
                    format!("pocket {pocket} holds two tools of a random changer"),
                    "this tool",
                )
                .with_label(span(first.span()), "and this one")
                .with_help("a random changer swaps a tool into the pocket of the one it takes out: one tool a pocket (pocket 0 is the spindle)"),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    fn codes(sections: &str) -> Vec<&'static str> {
        let text = format!("[machine]\nname = \"t\"\ncontrol = \"828d\"\n{sections}");
        match crate::load(&text) {
            Ok(_) => Vec::new(),
            Err(d) => d.iter().map(|d| d.code.name()).collect(),
        }
    }

    #[test]
    fn an_axis_has_at_most_four_finite_fixed_points() {
        let axis = |points: &str| {
            format!("[[axes]]\nname = \"X\"\nkind = \"linear\"\nfixed_points = {points}\n")
        };
        assert!(codes(&axis("[1.0, 2.0, 3.0, 4.0]")).is_empty());
        assert_eq!(
            codes(&axis("[1.0, 2.0, 3.0, 4.0, 5.0]")),
            ["gcodec::profile::out_of_range"]
        );
        assert_eq!(codes(&axis("[nan]")), ["gcodec::profile::out_of_range"]);
        assert_eq!(
            codes("[[axes]]\nname = \"X\"\nkind = \"linear\"\nreference_point = inf\n"),
            ["gcodec::profile::out_of_range"]
        );
    }

    #[test]
    fn cutting_edge_positions_are_0_to_9() {
        let tool = |position: u8| {
            format!(
                "[[tools]]\nnumber = 1\nedges = [{{ d = 1, radius = 0.8, position = {position} }}]\n"
            )
        };
        assert_eq!(codes(&tool(10)), ["gcodec::profile::out_of_range"]);
        assert!(codes(&tool(9)).is_empty());
        let typed = |tool_type: u32| {
            format!("[[tools]]\nnumber = 1\nedges = [{{ d = 1, type = {tool_type} }}]\n")
        };
        assert_eq!(codes(&typed(5)), ["gcodec::profile::out_of_range"]);
        assert!(codes(&typed(500)).is_empty());
    }

    #[test]
    fn only_turning_tools_place_their_tip_by_the_edge_position() {
        let edge = |extra: &str| {
            let text = format!(
                "[machine]\nname = \"t\"\ncontrol = \"828d\"\n[[tools]]\nnumber = 1\nedges = [{{ d = 1, position = 3{extra} }}]\n"
            );
            let profile = crate::load(&text).expect("valid");
            profile.tools[0].edges[0].is_turning()
        };
        assert!(edge(""));
        assert!(edge(", type = 510"));
        assert!(!edge(", type = 120"));
    }

    #[test]
    fn circle_tolerances_are_not_negative() {
        assert_eq!(
            codes("[program]\ncircle_error_const = -0.1\ncircle_error_factor = 0.001\n"),
            ["gcodec::profile::out_of_range"]
        );
        assert!(codes("[program]\ncircle_error_const = 0.05\nstop_at_m0 = false\n").is_empty());
    }

    #[test]
    fn the_toolchanger_table_has_defaults_and_is_checked() {
        let profile = crate::load("[machine]\nname = \"t\"\ncontrol = \"828d\"\n[toolchanger]\n")
            .expect("loads");
        let t = profile.toolchanger.expect("the table is there");
        assert!(!t.support_start_change && !t.random);
        assert_eq!(*t.cycle_time.get_ref(), 0.1);
        assert_eq!(*t.timeout_cycles.get_ref(), 100);
        assert!(crate::builtin().expect("loads").toolchanger.is_none());
        assert_eq!(
            codes("[toolchanger]\ncycle_time = 0.0\ntimeout_cycles = 0\n"),
            [
                "gcodec::profile::out_of_range",
                "gcodec::profile::out_of_range"
            ]
        );
        assert_eq!(
            codes("[toolchanger]\ncycle_time = nan\n"),
            ["gcodec::profile::out_of_range"]
        );
        assert_eq!(
            codes("[toolchanger]\nrandom_pockets = true\n"),
            ["gcodec::profile::schema"]
        );
        let tools = "[[tools]]\nnumber = 5\nlocation = 3\n[[tools]]\nnumber = 10\nlocation = 3\n";
        assert!(codes(&format!("[toolchanger]\n{tools}")).is_empty());
        assert_eq!(
            codes(&format!("[toolchanger]\nrandom = true\n{tools}")),
            ["gcodec::profile::duplicate"]
        );
    }

    #[test]
    fn g_codes_defaults_to_everything_supported() {
        let profile = crate::load("[machine]\nname = \"t\"\ncontrol = \"828d\"\n").unwrap();
        assert!(profile.g_codes.unsupported.is_empty());
        assert!(profile.g_codes.unsupported_groups.is_empty());
    }

    #[test]
    fn g_codes_entries_are_checked() {
        assert!(
            codes("[g_codes]\nunsupported = [\"G33\", \"OEMIPO1\"]\nunsupported_groups = [35]")
                .is_empty()
        );
        assert_eq!(
            codes("[g_codes]\nunsupported = [\"G 33\"]"),
            ["gcodec::profile::out_of_range"]
        );
        assert_eq!(
            codes("[g_codes]\nunsupported = [\"G33\", \"g33\"]"),
            ["gcodec::profile::duplicate"]
        );
        assert_eq!(
            codes("[g_codes]\nunsupported_groups = [0, 65]"),
            [
                "gcodec::profile::out_of_range",
                "gcodec::profile::out_of_range"
            ]
        );
        assert_eq!(
            codes("[g_codes]\nunsupported_groups = [35, 35]"),
            ["gcodec::profile::duplicate"]
        );
        assert_eq!(codes("[g_codes]\nunknown = 1"), ["gcodec::profile::schema"]);
    }
}
