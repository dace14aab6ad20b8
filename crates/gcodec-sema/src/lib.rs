//! Semantic checks and the modal engine — **not built yet** (the lowering
//! issue fills this crate). Nothing here has behaviour; this page is the
//! documented outline that the lowering work implements.
//!
//! # Planned API
//!
//! - `analyze(program: &gcodec_parser::ast::Program, profile: &gcodec_profile::Profile)
//!    -> Analysis` — never fails; returns the checked program plus diagnostics.
//! - A G-group registry with all 64 groups of the language reference §3.2:
//!   members in index order, modal or one-shot, reset defaults from the
//!   profile. Two commands of one group in a block, an unknown G, or a G the
//!   profile does not support are diagnostics (`gcodec::sema::…`).
//! - M functions per the M-function design: `M<value>` and `M<ext>=<value>`,
//!   range 0…2147483647, extended address forbidden for M0 M1 M2 M17 M30,
//!   per-block limit, classes, unknown-code policy.
//! - Tool selection per the tool-change design, normalised into one selector
//!   model (kind, value, spindle extension, raw form) with `immediate` or
//!   `deferred_until_m6` timing.
//! - Work offsets per the work-offset design: Group 8 codes against the
//!   profile's supported set; G53/G153/SUPA as block-scope suppression.
//! - Addresses (axes from the profile, `=` rules, where AC/IC/DC/ACP/ACN are
//!   allowed), labels and jump targets, `PROC` signatures and call arity,
//!   `DEF` before use, system variables against a registry of known names.
//! - The modal state at every block of straight-line code.
//!
//! `gcodec parse` already reports everything that is a matter of syntax;
//! the checks above need a machine profile and belong here.
