//! The checks of a machine profile that need the G-group registry
//! ([`ggroups`]), which the profile crate sits below and cannot see:
//! `modal_defaults` (a group with commands, modal, and a code of that
//! group), the names of `[g_codes] unsupported`, and `legacy_aliases` keys
//! that the control already uses.
//!
//! [`check_profile`] runs after [`gcodec_profile::load`]; its diagnostics
//! point into the same TOML text and use the same `gcodec::profile::…`
//! codes. Lowering does not rely on it: with an unchecked profile, names
//! the registry does not know simply match nothing.

use std::ops::Range;

use gcodec_profile::Profile;
use gcodec_source::{Code, Diagnostic, Span, codes};

use gcodec_lang::ggroups::{self, Effect, GGroup};
/// Checks `profile` against the G-group registry. Every problem found is
/// reported, in the order of the TOML text, with labelled spans into it.
///
/// Meant for a profile [`gcodec_profile::load`] returned; the two together
/// are the whole profile check (`gcodec profile check`).
pub fn check_profile(profile: &Profile) -> Vec<Diagnostic> {
    let mut out = Vec::new();
    check_modal_defaults(profile, &mut out);
    check_unsupported(profile, &mut out);
    check_legacy_aliases(profile, &mut out);
    out.sort_by_key(|d| d.span().map_or(0, |s| s.start));
    out
}

/// A byte range of the TOML as a span (saturating: TOML text over 4 GiB
/// is not read, but a span must never panic).
fn span(range: Range<usize>) -> Span {
    let clamp = |n: usize| u32::try_from(n).unwrap_or(u32::MAX);
    Span::new(clamp(range.start), clamp(range.end))
}

fn error(
    code: &'static Code,
    at: Range<usize>,
    message: String,
    label: &'static str,
) -> Diagnostic {
    Diagnostic::new(code, message).with_label(span(at), label)
}

/// A group as messages name it: `group 6 (Plane selection)`.
fn describe(group: &GGroup) -> String {
    format!("group {} ({})", group.number, group.title)
}

/// The commands of a group for a help text, the first few of a long one.
fn members(group: &GGroup) -> String {
    const SHOWN: usize = 8;
    let names: Vec<&str> = group
        .members
        .iter()
        .copied()
        .filter(|m| !m.is_empty())
        .collect();
    let mut text = names
        .iter()
        .take(SHOWN)
        .map(|m| format!("`{m}`"))
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > SHOWN {
        text.push_str(&format!(", … ({} commands)", names.len()));
    }
    text
}

/// Whether `[g_codes]` rules out the command at (`group`, `index`).
fn ruled_out(profile: &Profile, group: u8, index: u8) -> Option<&'static str> {
    let g = &profile.g_codes;
    if g.unsupported_groups.iter().any(|n| *n.get_ref() == group) {
        return Some("unsupported_groups");
    }
    if g.unsupported
        .iter()
        .any(|c| ggroups::lookup(c.get_ref()) == Some((group, index)))
    {
        return Some("unsupported");
    }
    None
}

/// `modal_defaults`: a group 1…64 that has commands, is modal, listed
/// once; a code that is a command of that group and that the profile does
/// not rule out; group 8 agreeing with `default_group8_offset`.
fn check_modal_defaults(profile: &Profile, out: &mut Vec<Diagnostic>) {
    let mut seen: Vec<(u8, Range<usize>)> = Vec::new();
    for (key, code) in &profile.modal_defaults {
        let Some(group) = key.get_ref().parse::<u8>().ok().and_then(ggroups::group) else {
            out.push(
                error(
                    codes::profile::OUT_OF_RANGE,
                    key.span(),
                    format!("`{}` is not a G group", key.get_ref()),
                    "here",
                )
                .with_help("G groups are numbered 1 to 64, e.g. `6 = \"G18\"`"),
            );
            continue;
        };
        // `6` and `06` are different TOML keys but the same group.
        if let Some((_, first)) = seen.iter().find(|(n, _)| *n == group.number) {
            out.push(
                error(
                    codes::profile::DUPLICATE,
                    key.span(),
                    format!("group {} is given twice", group.number),
                    "again here",
                )
                .with_label(span(first.clone()), "first here"),
            );
            continue;
        }
        seen.push((group.number, key.span()));
        if group.members.is_empty() {
            out.push(
                error(
                    codes::profile::UNASSIGNED_GROUP,
                    key.span(),
                    format!("group {} is not assigned: it has no commands", group.number),
                    "no such group",
                )
                .with_help("leave the group out"),
            );
            continue;
        }
        if group.effect == Effect::NonModal {
            out.push(
                error(
                    codes::profile::NOT_MODAL,
                    key.span(),
                    format!(
                        "{} is not modal: its commands act only in their block, so it has no reset default",
                        describe(group)
                    ),
                    "non-modal group",
                )
                .with_help("the non-modal groups are 2, 3, 9, 11 and 62; leave the group out"),
            );
            continue;
        }
        let name = code.get_ref();
        let Some((found, index)) = ggroups::lookup(name) else {
            out.push(
                error(
                    codes::profile::UNKNOWN_G_CODE,
                    code.span(),
                    format!("`{name}` is not a G command of the control"),
                    "unknown G command",
                )
                .with_help(format!("{} has {}", describe(group), members(group))),
            );
            continue;
        };
        if found != group.number {
            let right = ggroups::group(found).map_or_else(|| format!("group {found}"), describe);
            out.push(
                error(
                    codes::profile::NOT_IN_GROUP,
                    code.span(),
                    format!("`{name}` is not a command of {}", describe(group)),
                    "a command of another group",
                )
                .with_label(span(key.span()), "this group")
                .with_help(format!(
                    "`{name}` belongs to {right}: write `{found} = \"{name}\"`"
                )),
            );
            continue;
        }
        if let Some(list) = ruled_out(profile, found, index) {
            out.push(
                error(
                    codes::profile::UNSUPPORTED_DEFAULT,
                    code.span(),
                    format!("the reset default `{name}` is a command the profile's `[g_codes]` rules out"),
                    "ruled out",
                )
                .with_help(format!(
                    "a control resets into commands it has: drop the entry here or in `[g_codes] {list}`"
                )),
            );
        }
        if found == 8 {
            check_group8_default(profile, code.span(), name, index, out);
        }
    }
}

/// Lowering and the modal analysis take the Group 8 reset state from
/// `default_group8_offset`; a `modal_defaults` entry for group 8 that
/// names another code would be ignored, so it is an error.
fn check_group8_default(
    profile: &Profile,
    at: Range<usize>,
    name: &str,
    index: u8,
    out: &mut Vec<Diagnostic>,
) {
    let offset = &profile.work_offsets.default_group8_offset;
    // Not a Group 8 code: `gcodec_profile::load` reports it.
    let Some(uifr) = gcodec_profile::group8_index(offset.get_ref()) else {
        return;
    };
    if u16::from(uifr) + 1 == u16::from(index) {
        return;
    }
    let mut d = error(
        codes::profile::CONFLICTING_DEFAULTS,
        at,
        format!(
            "the Group 8 reset default `{name}` contradicts `default_group8_offset = \"{}\"`",
            offset.get_ref()
        ),
        "group 8 resets to this",
    );
    let offset_span = offset.span();
    if offset_span.is_empty() {
        d = d.with_help(format!(
            "`default_group8_offset` is not written, so it is `{}`: set it to `\"{name}\"` or change this entry",
            offset.get_ref()
        ));
    } else {
        d = d
            .with_label(span(offset_span), "but the default offset is this")
            .with_help("the reset state of group 8 is `default_group8_offset`: make the two agree");
    }
    out.push(d);
}

/// `[g_codes] unsupported`: commands of the registry.
fn check_unsupported(profile: &Profile, out: &mut Vec<Diagnostic>) {
    for code in &profile.g_codes.unsupported {
        if ggroups::lookup(code.get_ref()).is_none() {
            out.push(
                error(
                    codes::profile::UNKNOWN_G_CODE,
                    code.span(),
                    format!("`{}` is not a G command of the control", code.get_ref()),
                    "unknown G command",
                )
                .with_help(
                    "list commands of the G-group table (reference §3.2), e.g. `\"G33\"`, `\"OEMIPO1\"`",
                ),
            );
        }
    }
}

/// `legacy_aliases` keys: codes the control has no other use for. `G58`
/// and `G59` (group 3, the axial programmable offsets) may be aliased, and
/// so may codes that are not commands at all; a command of another group
/// would lose its meaning.
fn check_legacy_aliases(profile: &Profile, out: &mut Vec<Diagnostic>) {
    for alias in profile.work_offsets.legacy_aliases.keys() {
        let name = alias.get_ref();
        let Some((found, _)) = ggroups::lookup(name) else {
            continue;
        };
        // Group 8 codes are reported by `gcodec_profile::load`.
        if found == 3 || found == 8 {
            continue;
        }
        let group = ggroups::group(found).map_or_else(|| format!("group {found}"), describe);
        out.push(
            error(
                codes::profile::ALIAS_CONFLICT,
                alias.span(),
                format!("`legacy_aliases` redefines `{name}`, a command of {group}"),
                "a G command of the control",
            )
            .with_help(
                "only codes the control has no other use for (such as `G58`, `G59`) can stand for a settable offset",
            ),
        );
    }
}
