//! The compile set-up of lowering tests: parse, check the parse is clean,
//! lower for a profile.

use gcodec_profile::Profile;
use gcodec_sema::Lowered;

/// Parses `src` as the file `name` and lowers it for `profile`; the
/// program must parse without a diagnostic (a test of lowering is not a
/// test of parsing).
pub fn lower_clean(name: &str, src: &[u8], profile: &Profile) -> Lowered {
    let parsed = gcodec_parser::parse_bytes(name, src);
    assert!(
        parsed.diagnostics.is_empty(),
        "{name}:\n{}\n{:#?}",
        String::from_utf8_lossy(src),
        parsed.diagnostics
    );
    gcodec_sema::lower(&parsed.program, profile)
}
