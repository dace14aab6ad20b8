//! The codes of area `scenario`: toolchanger scenario files (the simulated
//! changer's behaviour and the faults to inject, `--toolchanger`).

super::codes! {
    "scenario", "toolchanger scenario files (the simulated changer's behaviour and injected faults)";
    SYNTAX = syntax, Error, "a toolchanger scenario that is not TOML";
    SCHEMA = schema, Error, "a key, type or name the scenario format does not have";
    OUT_OF_RANGE = out_of_range, Error, "a scenario value outside the range it may take";
    MISSING_VALUE = missing_value, Error, "a scenario entry without the value its action needs";
    KEY_NOT_APPLICABLE = key_not_applicable, Error, "a scenario key that the entry's action or place does not use";
    UNKNOWN_TOOL = unknown_tool, Error, "a scenario's initial tool that the profile's tool table lacks";
}
