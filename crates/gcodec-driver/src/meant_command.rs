//! The G command a call of a program that is not found probably meant:
//! `GO X10` is a call of `GO` (the letter O), written for `G0`.

use gcodec_lang::ggroups::{G_GROUPS, GCommand};

/// The help of a program not found, led by the G command its name is
/// near, if any.
pub(crate) fn not_found_help(name: &str, otherwise: String) -> String {
    match meant_g_command(name) {
        Some(command) => format!(
            "did you mean the G command `{command}`? The name is read as a call of a program; \
             else {otherwise}"
        ),
        None => otherwise,
    }
}

/// The name with the letter O read as the digit 0, where that is a G
/// command; else the G command nearest to it.
fn meant_g_command(name: &str) -> Option<&'static str> {
    let zeros: String = name
        .chars()
        .map(|c| if c.eq_ignore_ascii_case(&'o') { '0' } else { c })
        .collect();
    let commands = G_GROUPS
        .iter()
        .flat_map(|g| g.members.iter().copied())
        .filter(|m| !m.is_empty());
    GCommand::named(&zeros)
        .map(GCommand::name)
        .or_else(|| gcodec_source::nearest(name, commands))
}

#[cfg(test)]
mod tests {
    use super::meant_g_command;

    #[test]
    fn a_letter_o_for_a_zero_or_a_near_name_is_a_g_command() {
        assert_eq!(meant_g_command("GO"), Some("G0"));
        assert_eq!(meant_g_command("g9O"), Some("G90"));
        assert_eq!(meant_g_command("DIAMNO"), Some("DIAMON"));
        assert_eq!(meant_g_command("MY_SUB"), None);
    }
}
