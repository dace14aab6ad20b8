use super::*;
use TokenKind::*;

fn kinds(src: &str) -> Vec<(TokenKind, &str)> {
    lex(src.as_bytes())
        .into_iter()
        .map(|t| (t.kind, &src[t.range()]))
        .filter(|(k, _)| *k != Whitespace)
        .collect()
}

#[test]
fn din_words_without_blanks_split_at_letters() {
    assert_eq!(
        kinds("G53G0Z-205"),
        vec![
            (Letter, "G"),
            (Number, "53"),
            (Letter, "G"),
            (Number, "0"),
            (Letter, "Z"),
            (Minus, "-"),
            (Number, "205")
        ]
    );
    assert_eq!(
        kinds("N10G0X.20Z30.4"),
        vec![
            (Letter, "N"),
            (Number, "10"),
            (Letter, "G"),
            (Number, "0"),
            (Letter, "X"),
            (Number, ".20"),
            (Letter, "Z"),
            (Number, "30.4")
        ]
    );
}

#[test]
fn identifiers_need_two_leading_letters() {
    assert_eq!(kinds("CYCLE81"), vec![(Ident, "CYCLE81")]);
    assert_eq!(kinds("_MM0:"), vec![(Ident, "_MM0"), (Colon, ":")]);
    assert_eq!(kinds("HH2"), vec![(Ident, "HH2")]);
    assert_eq!(kinds("SPOS=90")[0], (Ident, "SPOS"));
}

#[test]
fn keywords_are_case_insensitive_and_longest_match_wins() {
    assert_eq!(kinds("IF if If")[..], [(If, "IF"), (If, "if"), (If, "If")]);
    assert_eq!(
        kinds("ENDIF ENDIFX")[..],
        [(EndIf, "ENDIF"), (Ident, "ENDIFX")]
    );
    assert_eq!(kinds("B_AND b_or")[..], [(BAnd, "B_AND"), (BOr, "b_or")]);
}

/// The lexer's keyword tokens are `gcodec_lang`'s reserved words, no more
/// and no fewer: each word lexes as one token of its own, named by it.
#[test]
fn keyword_tokens_are_the_vocabulary_reserved_words() {
    use gcodec_lang::keywords::{KEYWORDS, WORD_CONSTANTS, WORD_OPERATORS};
    let word_of = |kind: TokenKind| kind.describe().trim_matches('`');
    for (words, of_kind) in [
        (KEYWORDS, TokenKind::is_keyword as fn(TokenKind) -> bool),
        (WORD_OPERATORS, |k| {
            matches!(
                k,
                Div | Mod | And | Or | Xor | Not | BAnd | BOr | BXor | BNot
            )
        }),
        (WORD_CONSTANTS, |k| matches!(k, True | False)),
    ] {
        for word in words {
            let lower = word.to_ascii_lowercase();
            let tokens = kinds(&lower);
            assert_eq!(tokens.len(), 1, "{word}");
            assert!(of_kind(tokens[0].0), "{word}: {:?}", tokens[0].0);
            assert_eq!(word_of(tokens[0].0), *word);
        }
        let lexed: Vec<&str> = TokenKind::ALL
            .iter()
            .copied()
            .filter(|k| of_kind(*k))
            .map(word_of)
            .collect();
        assert_eq!(lexed, words);
    }
}

#[test]
fn numbers_in_all_forms() {
    for n in ["5", "5.", ".5", "0.5", "1.5EX-3", "10ex5", ".1EX+3"] {
        assert_eq!(kinds(n), vec![(Number, n)], "{n}");
    }
    assert_eq!(kinds("'H1F'"), vec![(HexNumber, "'H1F'")]);
    assert_eq!(kinds("'B101'"), vec![(BinNumber, "'B101'")]);
    assert_eq!(kinds("'H0125ANMNOA'"), vec![(BadQuoted, "'H0125ANMNOA'")]);
    assert_eq!(kinds("'B11012'"), vec![(BadQuoted, "'B11012'")]);
}

#[test]
fn strings_keep_case_and_unclosed_strings_stop_at_line_end() {
    assert_eq!(kinds("\"Drill_10\""), vec![(String, "\"Drill_10\"")]);
    assert_eq!(
        kinds("\"abc\nX1"),
        vec![
            (UnclosedString, "\"abc"),
            (Newline, "\n"),
            (Letter, "X"),
            (Number, "1")
        ]
    );
}

#[test]
fn system_variables_and_operators() {
    assert_eq!(
        kinds("$P_UIFR[1,X,TR]")[..3],
        [(SystemVar, "$P_UIFR"), (LBracket, "["), (Number, "1")]
    );
    assert_eq!(kinds("$$SA_X")[0], (SystemVar, "$$SA_X"));
    assert_eq!(
        kinds("== <> <= >= << < >")
            .into_iter()
            .map(|t| t.0)
            .collect::<Vec<_>>(),
        vec![EqEq, Ne, Le, Ge, Concat, Lt, Gt]
    );
}

#[test]
fn latin1_and_cp1251_comments_lex() {
    let src = b"G0 ; Gr\xfc\xdfe \xcf\xf0\xe8\xe2\xe5\xf2\nX1";
    let toks = lex(src);
    assert!(toks.iter().any(|t| t.kind == Comment));
    assert!(toks.iter().all(|t| t.kind != Error));
}

#[test]
fn tokens_cover_the_input_exactly() {
    let src = b"N10 G1 X=R1+5 ; c\r\n/1 IF R1==2 GOTOF L1 ?!";
    let toks = lex(src);
    let mut pos = 0;
    for t in &toks {
        assert_eq!(t.start, pos);
        pos = t.end;
    }
    assert_eq!(pos as usize, src.len());
    assert_eq!(toks.iter().filter(|t| t.kind == Error).count(), 2);
}

#[test]
fn all_lists_every_kind_in_order() {
    for (i, kind) in TokenKind::ALL.iter().enumerate() {
        assert_eq!(*kind as usize, i, "{kind:?}");
    }
    assert_eq!(TokenKind::ALL.last(), Some(&Error));
    // The parser keeps expected-token sets in a u128.
    assert!(TokenKind::ALL.len() <= 128);
}
