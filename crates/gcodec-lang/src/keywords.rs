//! The reserved words of the NC language: the keywords of control
//! structures, declarations and calls, and the operators and constants
//! written as words. The lexer's tokens must list them themselves (logos
//! needs literal patterns); its tests check that both lists agree.

/// The keywords of control structures, jumps, declarations, calls and
/// synchronized actions, in upper case (the control ignores case).
pub const KEYWORDS: &[&str] = &[
    "IF", "ELSE", "ENDIF", "WHILE", "ENDWHILE", "FOR", "TO", "ENDFOR", "LOOP", "ENDLOOP", "REPEAT",
    "REPEATB", "UNTIL", "CASE", "OF", "DEFAULT", "GOTO", "GOTOF", "GOTOB", "GOTOC", "GOTOS", "DEF",
    "REDEF", "DEFINE", "AS", "PROC", "ENDPROC", "VAR", "RET", "EXTERN", "CALL", "PCALL", "MCALL",
    "BLOCK", "SET", "REP", "ID", "IDS", "WHEN", "WHENEVER", "EVERY", "FROM", "DO",
];

/// The operators written as words (reference §7.3).
pub const WORD_OPERATORS: &[&str] = &[
    "DIV", "MOD", "AND", "OR", "XOR", "NOT", "B_AND", "B_OR", "B_XOR", "B_NOT",
];

/// The constants written as words.
pub const WORD_CONSTANTS: &[&str] = &["TRUE", "FALSE"];

/// Whether `name` is a keyword, a word operator or a word constant, in
/// any case.
pub fn is_reserved(name: &str) -> bool {
    [KEYWORDS, WORD_OPERATORS, WORD_CONSTANTS]
        .iter()
        .flat_map(|list| list.iter())
        .any(|word| word.eq_ignore_ascii_case(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reserved_words_are_upper_case_and_distinct() {
        let mut all: Vec<&str> = [KEYWORDS, WORD_OPERATORS, WORD_CONSTANTS].concat();
        assert!(
            all.iter()
                .all(|w| !w.bytes().any(|b| b.is_ascii_lowercase()))
        );
        let count = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), count);
        assert!(is_reserved("endif") && is_reserved("B_and") && !is_reserved("ENDIFX"));
    }
}
