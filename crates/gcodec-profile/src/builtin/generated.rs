// @generated from profiles/default.toml by the tests of
// crates/gcodec-profile/src/builtin/mod.rs. Do not edit: regenerate with
//   GCODEC_UPDATE_BUILTIN_PROFILE=1 cargo test -p gcodec-profile --lib builtin
#![allow(unused_imports)]

use std::collections::BTreeMap;
use std::ops::Range;

use gcodec_lang::MClass;
use toml::Spanned;

use crate::schema::*;

fn s<T>(span: Range<usize>, value: T) -> Spanned<T> {
    Spanned::new(span, value)
}

/// `profiles/default.toml` as `crate::load` reads it.
pub(crate) fn profile() -> Profile {
    Profile {
        machine: Machine {
            name: String::from("840D sl vertical milling machine (built-in default)"),
            control: Control::Sinumerik840dSl,
            spindles: vec![
                s(365..366, 1),
            ],
        },
        axes: vec![
            Axis {
                name: s(385..388, String::from("X")),
                kind: AxisKind::Linear,
                geometry: true,
                diameter: false,
                rapid: s(429..436, 30000.0),
                reference_point: s(0..0, 0.0),
                fixed_points: Vec::new(),
            },
            Axis {
                name: s(454..457, String::from("Y")),
                kind: AxisKind::Linear,
                geometry: true,
                diameter: false,
                rapid: s(498..505, 30000.0),
                reference_point: s(0..0, 0.0),
                fixed_points: Vec::new(),
            },
            Axis {
                name: s(523..526, String::from("Z")),
                kind: AxisKind::Linear,
                geometry: true,
                diameter: false,
                rapid: s(567..574, 30000.0),
                reference_point: s(0..0, 0.0),
                fixed_points: Vec::new(),
            },
        ],
        modal_defaults: BTreeMap::from([
            (s(641..642, String::from("1")), s(645..649, String::from("G1"))),
            (s(752..754, String::from("13")), s(757..762, String::from("G71"))),
            (s(775..777, String::from("14")), s(780..785, String::from("G90"))),
            (s(800..802, String::from("15")), s(805..810, String::from("G94"))),
            (s(686..687, String::from("6")), s(690..695, String::from("G17"))),
            (s(711..712, String::from("8")), s(715..721, String::from("G500"))),
        ]),
        tool_change: ToolChange {
            tool_change_mode: ToolChangeMode::DeferredM6,
            change_m_code: s(896..897, 6),
            tool_management_enabled: false,
            on_unresolved_tool: UnresolvedToolPolicy::Error,
            allow_substitution: false,
            m6_without_pending_policy: Policy::Warning,
            pending_selection_scope: PendingSelectionScope::Channel,
            cutting_edge_default: s(1083..1084, 1),
            edge_without_tool: EdgeWithoutTool::NoOffset,
        },
        tools: Vec::new(),
        m_functions: MFunctions {
            max_m_per_block: s(1150..1151, 5),
            unknown_mcode_policy: Policy::Warning,
            enable_extended_m_address: true,
            mcode_class_overrides: BTreeMap::from([
                (s(1288..1289, String::from("7")), MClass::Custom),
                (s(1302..1303, String::from("8")), MClass::Custom),
                (s(1316..1317, String::from("9")), MClass::Custom),
            ]),
            auxiliary_groups: BTreeMap::from([
                (s(0..0, String::from("1")), vec![
                    s(0..0, 0),
                    s(0..0, 1),
                    s(0..0, 2),
                    s(0..0, 17),
                    s(0..0, 30),
                ]),
                (s(0..0, String::from("2")), vec![
                    s(0..0, 3),
                    s(0..0, 4),
                    s(0..0, 5),
                    s(0..0, 70),
                ]),
            ]),
        },
        work_offsets: WorkOffsets {
            default_group8_offset: s(1404..1410, String::from("G500")),
            supported_group8_offsets: vec![
                s(1439..1445, String::from("G500")),
                s(1447..1456, String::from("G54-G57")),
            ],
            legacy_aliases: BTreeMap::new(),
            duplicate_suppression_policy: DuplicateSuppressionPolicy::Warn,
            incremental_traverses_offset_change: true,
            values: BTreeMap::new(),
        },
        program: ProgramSettings {
            skip_levels: Vec::new(),
            max_block_length: s(1526..1529, 512),
            max_feed: s(1541..1548, 10000.0),
            subprogram_paths: Vec::new(),
            external_program_path: None,
            link_target_paths: Vec::new(),
            max_file_size: s(0..0, 1073741824),
            code_page: s(0..0, String::from("windows-1252")),
            max_variable_memory: s(0..0, 268435456),
            stop_at_m0: true,
            circle_error_const: s(0..0, 0.01),
            circle_error_factor: s(0..0, 0.001),
            cutcom_max_dummy_blocks: s(0..0, 3),
            cutcom_check_blocks: s(0..0, 4),
        },
        g_codes: GCodes {
            unsupported: Vec::new(),
            unsupported_groups: Vec::new(),
        },
        system_variables: BTreeMap::new(),
        toolchanger: None,
    }
}
