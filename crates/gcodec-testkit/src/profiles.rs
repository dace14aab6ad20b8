//! The shipped profiles and small test machines.

use gcodec_profile::Profile;

use crate::paths::repo;

/// A shipped profile of `profiles/`, by file name (`lathe_828d.toml`).
pub fn profile(name: &str) -> Profile {
    let text = std::fs::read_to_string(repo().join("profiles").join(name)).expect("profile");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{name}: {d:#?}"))
}

/// A profile of the given TOML sections after a `[machine]` header.
pub fn machine(sections: &str) -> Profile {
    let text = format!("[machine]\nname = \"test\"\ncontrol = \"840d_sl\"\n{sections}");
    gcodec_profile::load(&text).unwrap_or_else(|d| panic!("{d:#?}"))
}
