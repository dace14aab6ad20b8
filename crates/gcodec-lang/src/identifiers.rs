//! The control's rules for the names a program gives (Fundamentals
//! 10/2004, p. 60): the first two characters are letters or `_`, and a
//! name is no keyword, G command or address of the language. The parser
//! judges declared names by them, lowering the names a program uses as
//! variables.

use crate::addresses::is_written_as_address;
use crate::{ggroups, keywords};

/// What is wrong with `name` as a name a program gives, and how to fix
/// it; `None` for a good name.
pub fn invalid_name(name: &str) -> Option<(String, &'static str)> {
    const RENAME: &str = "begin the name with two letters or `_`; Siemens recommends user names \
                          that begin with `U` (`U_COUNT`) or contain `_`";
    let bytes = name.as_bytes();
    if let [letter] = bytes {
        return Some((
            format!(
                "`{}` is an address letter and cannot name a variable",
                *letter as char
            ),
            RENAME,
        ));
    }
    // `R0` is R parameter 0: predefined (reference §7.2), never declared.
    if let [b'R' | b'r', digits @ ..] = bytes
        && digits.iter().all(u8::is_ascii_digit)
    {
        // Leading zeros are ignored (`R01` is `R1`, reference §1.8).
        let number = match name[1..].trim_start_matches('0') {
            "" => "0",
            number => number,
        };
        return Some((
            format!("`{name}` is R parameter {number}, predefined on the control, not a name"),
            "use the R parameter without a `DEF`, or give the variable a name that begins \
             with two letters or `_`",
        ));
    }
    if let Some(at) = bytes[..2]
        .iter()
        .position(|b| !(b.is_ascii_alphabetic() || *b == b'_'))
    {
        return Some((
            format!(
                "`{name}` is not a name: its first two characters must be letters or `_`, and \
                 `{}` is not",
                bytes[at] as char
            ),
            RENAME,
        ));
    }
    let what = if keywords::is_reserved(name) {
        "a keyword"
    } else if ggroups::lookup(name).is_some() {
        "a G command"
    } else if is_written_as_address(name) {
        "an address"
    } else {
        return None;
    };
    Some((
        format!("`{name}` is {what} of the NC language and cannot name a variable"),
        "choose another name; Siemens recommends user names that begin with `U` or contain `_`",
    ))
}

#[cfg(test)]
mod tests {
    use super::invalid_name;

    #[test]
    fn names_begin_with_two_letters_or_underscores() {
        for good in ["DEPTH", "_Z", "__1", "U_COUNT", "AB12"] {
            assert_eq!(invalid_name(good), None, "{good}");
        }
        for bad in ["I", "P1X", "R2D2", "K1", "N1", "_1LBL", "1A"] {
            assert!(invalid_name(bad).is_some(), "{bad}");
        }
    }

    #[test]
    fn r_parameters_are_predefined_not_names() {
        for (name, number) in [("R0", "0"), ("r12", "12"), ("R007", "7")] {
            let (message, _) = invalid_name(name).expect(name);
            assert_eq!(
                message,
                format!("`{name}` is R parameter {number}, predefined on the control, not a name")
            );
        }
        let (message, _) = invalid_name("R2D2").expect("R2D2");
        assert!(message.contains("first two characters"), "{message}");
    }

    #[test]
    fn keywords_g_commands_and_addresses_name_nothing() {
        for bad in ["IF", "endfor", "TRUE", "DIAMON", "CR", "SPOS"] {
            assert!(invalid_name(bad).is_some(), "{bad}");
        }
    }
}
