//! Writes a [`Profile`] as the Rust expression that builds it, spans
//! included: how `generated.rs` is made from `profiles/default.toml`.
//! Test-only: the binary carries the generated code, not the generator.
//!
//! Every struct is written by destructuring it without `..`, so a field
//! added to the schema and not here is a compile error, not a field the
//! generated profile silently lacks.

use std::collections::BTreeMap;

use gcodec_lang::MClass;
use toml::Spanned;

use crate::schema::*;

/// Rust source text being written, with its indentation.
pub(crate) struct Writer {
    text: String,
    depth: usize,
}

impl Writer {
    pub(crate) fn new() -> Self {
        Self {
            text: String::new(),
            depth: 0,
        }
    }

    pub(crate) fn into_text(self) -> String {
        self.text
    }

    pub(crate) fn push(&mut self, text: &str) {
        self.text.push_str(text);
    }

    fn newline(&mut self) {
        self.text.push('\n');
        for _ in 0..self.depth {
            self.text.push_str("    ");
        }
    }

    pub(crate) fn open(&mut self, text: &str) {
        self.push(text);
        self.depth += 1;
    }

    pub(crate) fn close(&mut self, text: &str) {
        self.depth -= 1;
        self.newline();
        self.push(text);
    }

    fn field(&mut self, name: &str, value: &dyn RustLiteral) {
        self.newline();
        self.push(name);
        self.push(": ");
        value.write_rust(self);
        self.push(",");
    }

    /// `value` on a line of its own, as a block's tail expression.
    pub(crate) fn tail(&mut self, value: &dyn RustLiteral) {
        self.newline();
        value.write_rust(self);
    }

    fn item(&mut self, value: &dyn RustLiteral) {
        self.newline();
        value.write_rust(self);
        self.push(",");
    }
}

/// A value that can be written as the Rust expression that builds it.
pub(crate) trait RustLiteral {
    fn write_rust(&self, out: &mut Writer);
}

macro_rules! display_literal {
    ($($ty:ty),*) => {$(
        impl RustLiteral for $ty {
            fn write_rust(&self, out: &mut Writer) {
                out.push(&self.to_string());
            }
        }
    )*};
}

display_literal!(bool, u8, u32, u64, i64);

impl RustLiteral for f64 {
    fn write_rust(&self, out: &mut Writer) {
        // `{:?}` is the shortest text that reads back as the same value,
        // and always a float literal (`30000.0`, `1e-7`).
        let text = if self.is_nan() {
            "f64::NAN".to_owned()
        } else if self.is_infinite() {
            let sign = if *self < 0.0 { "-" } else { "" };
            format!("{sign}f64::INFINITY")
        } else {
            format!("{self:?}")
        };
        out.push(&text);
    }
}

impl RustLiteral for String {
    fn write_rust(&self, out: &mut Writer) {
        // A string's `{:?}` is a valid Rust string literal.
        out.push(&format!("String::from({self:?})"));
    }
}

impl<T: RustLiteral> RustLiteral for Option<T> {
    fn write_rust(&self, out: &mut Writer) {
        match self {
            None => out.push("None"),
            Some(value) => {
                out.push("Some(");
                value.write_rust(out);
                out.push(")");
            }
        }
    }
}

impl<T: RustLiteral> RustLiteral for Vec<T> {
    fn write_rust(&self, out: &mut Writer) {
        if self.is_empty() {
            out.push("Vec::new()");
            return;
        }
        out.open("vec![");
        for value in self {
            out.item(value);
        }
        out.close("]");
    }
}

impl<K: RustLiteral, V: RustLiteral> RustLiteral for BTreeMap<K, V> {
    fn write_rust(&self, out: &mut Writer) {
        if self.is_empty() {
            out.push("BTreeMap::new()");
            return;
        }
        out.open("BTreeMap::from([");
        for (key, value) in self {
            out.item(&Pair(key, value));
        }
        out.close("])");
    }
}

/// A map's entry, written as a tuple.
struct Pair<'a, K, V>(&'a K, &'a V);

impl<K: RustLiteral, V: RustLiteral> RustLiteral for Pair<'_, K, V> {
    fn write_rust(&self, out: &mut Writer) {
        out.push("(");
        self.0.write_rust(out);
        out.push(", ");
        self.1.write_rust(out);
        out.push(")");
    }
}

impl<T: RustLiteral> RustLiteral for Spanned<T> {
    fn write_rust(&self, out: &mut Writer) {
        let span = self.span();
        out.push(&format!("s({}..{}, ", span.start, span.end));
        self.get_ref().write_rust(out);
        out.push(")");
    }
}

/// A struct literal of every field, by name.
macro_rules! struct_literal {
    ($ty:ident { $($field:ident),* $(,)? }) => {
        impl RustLiteral for $ty {
            fn write_rust(&self, out: &mut Writer) {
                let $ty { $($field),* } = self;
                out.open(concat!(stringify!($ty), " {"));
                $(out.field(stringify!($field), $field);)*
                out.close("}");
            }
        }
    };
}

/// A unit variant by its derived `Debug` name, which is the variant's.
macro_rules! unit_enum_literal {
    ($($ty:ident),* $(,)?) => {$(
        impl RustLiteral for $ty {
            fn write_rust(&self, out: &mut Writer) {
                out.push(&format!(concat!(stringify!($ty), "::{:?}"), self));
            }
        }
    )*};
}

unit_enum_literal!(
    Control,
    AxisKind,
    ToolChangeMode,
    UnresolvedToolPolicy,
    Policy,
    PendingSelectionScope,
    EdgeWithoutTool,
    ToolState,
    DuplicateSuppressionPolicy,
    MClass,
);

impl RustLiteral for SystemValue {
    fn write_rust(&self, out: &mut Writer) {
        let (variant, value): (&str, &dyn RustLiteral) = match self {
            SystemValue::Bool(v) => ("Bool", v),
            SystemValue::Int(v) => ("Int", v),
            SystemValue::Real(v) => ("Real", v),
            SystemValue::Text(v) => ("Text", v),
        };
        out.push(&format!("SystemValue::{variant}("));
        value.write_rust(out);
        out.push(")");
    }
}

struct_literal!(Profile {
    machine,
    axes,
    modal_defaults,
    tool_change,
    tools,
    m_functions,
    work_offsets,
    program,
    g_codes,
    system_variables,
    toolchanger,
});
struct_literal!(ToolchangerSettings {
    support_start_change,
    random,
    cycle_time,
    timeout_cycles,
});
struct_literal!(GCodes {
    unsupported,
    unsupported_groups,
});
struct_literal!(Machine {
    name,
    control,
    spindles,
});
struct_literal!(Axis {
    name,
    kind,
    geometry,
    diameter,
    rapid,
    reference_point,
    fixed_points,
});
struct_literal!(ToolChange {
    tool_change_mode,
    change_m_code,
    tool_management_enabled,
    on_unresolved_tool,
    allow_substitution,
    m6_without_pending_policy,
    pending_selection_scope,
    cutting_edge_default,
    edge_without_tool,
});
struct_literal!(Tool {
    number,
    name,
    duplo,
    location,
    state,
    edges,
});
struct_literal!(Edge {
    d,
    length,
    radius,
    position,
    tool_type,
});
struct_literal!(MFunctions {
    max_m_per_block,
    unknown_mcode_policy,
    enable_extended_m_address,
    mcode_class_overrides,
    auxiliary_groups,
});
struct_literal!(WorkOffsets {
    default_group8_offset,
    supported_group8_offsets,
    legacy_aliases,
    duplicate_suppression_policy,
    incremental_traverses_offset_change,
    values,
});
struct_literal!(ProgramSettings {
    skip_levels,
    max_block_length,
    max_feed,
    subprogram_paths,
    external_program_path,
    link_target_paths,
    max_file_size,
    code_page,
    max_variable_memory,
    stop_at_m0,
    circle_error_const,
    circle_error_factor,
    cutcom_max_dummy_blocks,
    cutcom_check_blocks,
});
