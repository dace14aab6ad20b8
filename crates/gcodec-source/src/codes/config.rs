//! The codes of area `config`: `gcodec.toml`, the configuration of
//! `gcodec check` (profiles and definition files per glob, rule levels,
//! excluded paths).

super::codes! {
    "config", "the check configuration `gcodec.toml` (profiles per glob, rule levels, excluded paths)";
    SYNTAX = syntax, Error, "a check configuration that is not TOML";
    SCHEMA = schema, Error, "a key or type the check configuration does not have";
    BAD_GLOB = bad_glob, Error, "a glob in the check configuration that does not parse";
    UNKNOWN_CODE = unknown_code, Error, "a rule level or ignore naming no diagnostic code or area";
    UNUSABLE_FILE = unusable_file, Error, "a profile, definition file or search path the configuration names that cannot be used";
}
