//! The JSON Schemas checked in under `docs/schema/`: each must be the one
//! its types generate.

/// Fails when `docs/schema/NAME` differs from `generated`; with
/// `GCODEC_UPDATE_SCHEMA` set it is written first. `regenerate` is the
/// command that does so, for the failure's message.
pub fn assert_schema_current(name: &str, generated: &str, regenerate: &str) {
    let path = crate::repo().join("docs/schema").join(name);
    if std::env::var_os("GCODEC_UPDATE_SCHEMA").is_some() {
        std::fs::write(&path, generated).expect("write the schema");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "docs/schema/{name} is stale: run `GCODEC_UPDATE_SCHEMA=1 {regenerate}` and commit it"
    );
}
