//! Machine profiles — **not built yet** (the lowering issue fills this
//! crate). Nothing here has behaviour; this page is the documented outline.
//!
//! # Planned API
//!
//! - `Profile::from_toml(source) -> Result<Profile, Vec<Diagnostic>>`: a
//!   typed TOML schema (unknown keys rejected) for the control (`840d_sl`,
//!   `828d`), channel axes, G-group reset defaults (MD20150), the tool-change
//!   model (`tool_change_mode = "direct" | "deferred_m6"`,
//!   `tool_management_enabled`, `on_unresolved_tool`, `allow_substitution`,
//!   `m6_without_pending_policy`, tool table), the M-function model
//!   (`max_m_per_block`, `unknown_mcode_policy`, `enable_extended_m_address`,
//!   `mcode_class_overrides`), work offsets (`default_group8_offset`,
//!   `supported_group8_offsets`, `legacy_aliases`,
//!   `duplicate_suppression_policy`, offset values), rapid and feed limits,
//!   skip levels, block-length limit and subprogram search paths.
//! - `Profile::builtin()`: the default 840D sl milling profile compiled into
//!   the binary, so `gcodec run file.mpf` works with no flags.
