//! The codes of area `profile`: machine profiles (`gcodec profile check`, `--profile`).

super::codes! {
    "profile", "machine profiles (`gcodec profile check`, `--profile`)";
    SYNTAX = syntax, Error, "a profile that is not TOML";
    SCHEMA = schema, Error, "a key, type or policy name the profile schema does not have";
    OUT_OF_RANGE = out_of_range, Error, "a profile value outside the range the control allows";
    DUPLICATE = duplicate, Error, "a profile entry given twice";
    OVERLAPPING_RANGES = overlapping_ranges, Error, "overlapping ranges of settable work offsets";
    UNKNOWN_REFERENCE = unknown_reference, Error, "a work offset the profile names but does not provide";
    NOT_MODAL = not_modal, Error, "a reset default for a G group that is not modal";
    UNASSIGNED_GROUP = unassigned_group, Error, "a reset default for a G group that has no commands";
    NOT_IN_GROUP = not_in_group, Error, "a reset default that is a command of another group";
    UNKNOWN_G_CODE = unknown_g_code, Error, "a G command name the control does not have";
    UNSUPPORTED_DEFAULT = unsupported_default, Error, "a reset default the profile says the control lacks";
    CONFLICTING_DEFAULTS = conflicting_defaults, Error, "a group 8 reset default other than `default_group8_offset`";
    UNKNOWN_SYSTEM_VARIABLE = unknown_system_variable, Error, "a `[system_variables]` key that is no system variable of the control";
    ALIAS_CONFLICT = alias_conflict, Error, "a legacy alias for a command of another group than 3";
}
