//! AIL, the executable instruction list — **not built yet** (the lowering
//! issue fills this crate). Nothing here has behaviour; this page is the
//! documented outline.
//!
//! # Planned schema
//!
//! A versioned document `{"ail_version": 1, "instructions": [...]}`. Every
//! instruction has `"kind"` and `"source": {"file", "line", "col", "span"}`.
//! Kinds include those of the seed designs exactly — `tool_select`
//! (`selector_kind`, `selector_value`, `timing`, spindle extension),
//! `tool_change` (`trigger`), `m_function` (`m_value`, `address_extension`,
//! `class`, `timing`, `raw`), `work_offset` (`group8_selected`,
//! `suppression`, `suppression_scope`) — plus motion, modal changes, feed,
//! spindle, dwell, frames, variable declarations and assignments, control
//! flow lowered to labels and conditional jumps, calls and returns,
//! messages, and stop/end. A JSON Schema generated from the types (schemars)
//! will be checked in under `docs/schema/` with a staleness test.
