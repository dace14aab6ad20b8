//! Addresses: the letters of DIN words.

/// An upper-case ASCII letter as a string (`?` for any other byte).
pub fn letter_str(letter: u8) -> &'static str {
    const LETTERS: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    match letter {
        b'A'..=b'Z' => {
            let i = usize::from(letter - b'A');
            &LETTERS[i..i + 1]
        }
        _ => "?",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn letters_are_themselves() {
        for letter in b'A'..=b'Z' {
            assert_eq!(letter_str(letter), (letter as char).to_string());
        }
        assert_eq!(letter_str(b'a'), "?");
        assert_eq!(letter_str(b'1'), "?");
    }
}
