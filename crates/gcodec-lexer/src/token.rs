use logos::Logos;

/// Every kind of token in Siemens-mode syntax.
///
/// Keywords are matched case-insensitively (`IF`, `if`, `If`); identifiers
/// keep their spelling and are compared case-insensitively by later stages.
#[derive(Logos, Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[logos(utf8 = false)]
#[repr(u8)]
pub enum TokenKind {
    // ---- trivia -------------------------------------------------------
    /// Blanks, tabs, `&` (a format character with the effect of a blank),
    /// carriage returns and other control bytes the control treats as blanks.
    #[regex(b"[ \t\r\x0b\x0c&]+")]
    Whitespace,
    /// End of block.
    #[token(b"\n")]
    Newline,
    /// `;` to the end of the line, any bytes.
    #[regex(b";[^\n]*", allow_greedy = true)]
    Comment,
    /// `%_N_NAME_MPF`, `%MPF123`: archive header line.
    #[regex(b"%[^\n]*", allow_greedy = true)]
    Header,

    // ---- names ----------------------------------------------------------
    /// A name of two or more characters whose first two are letters or `_`:
    /// keywords not listed below, variables, labels, subprograms,
    /// multi-letter addresses.
    #[regex(b"[A-Za-z_][A-Za-z_][A-Za-z0-9_]*", priority = 1)]
    Ident,
    /// A single address letter (`G`, `X`, `R`…); digits that touch it are a
    /// separate [`TokenKind::Number`].
    #[regex(b"[A-Za-z]")]
    Letter,
    /// `$` system variable (`$P_UIFR`, `$AA_IM`, `$$SA_…`, `$PI`).
    #[regex(b"\\$\\$?[A-Za-z_0-9]+")]
    SystemVar,

    // ---- literals ---------------------------------------------------------
    /// Decimal number: `5`, `5.`, `.5`, `1.5EX-3`. The sign is an operator.
    #[regex(b"[0-9]+(\\.[0-9]*)?([Ee][Xx][+-]?[0-9]+)?")]
    #[regex(b"\\.[0-9]+([Ee][Xx][+-]?[0-9]+)?")]
    Number,
    /// `'H1F'`.
    #[regex(b"'[Hh][0-9A-Fa-f]+'")]
    HexNumber,
    /// `'B101'`.
    #[regex(b"'[Bb][01]+'")]
    BinNumber,
    /// A quoted constant that is neither valid hex nor binary, or is not
    /// closed on its line.
    #[regex(b"'[^'\n]*'?", priority = 1)]
    BadQuoted,
    /// `"text"`; no escapes, cannot span lines.
    #[regex(b"\"[^\"\n]*\"")]
    String,
    /// `"text` with no closing quote on its line.
    #[regex(b"\"[^\"\n]*", priority = 1)]
    UnclosedString,

    // ---- punctuation and operators ----------------------------------------
    #[token(b"=")]
    Eq,
    #[token(b"==")]
    EqEq,
    #[token(b"<>")]
    Ne,
    #[token(b"<")]
    Lt,
    #[token(b">")]
    Gt,
    #[token(b"<=")]
    Le,
    #[token(b">=")]
    Ge,
    #[token(b"<<")]
    Concat,
    #[token(b"+")]
    Plus,
    #[token(b"-")]
    Minus,
    #[token(b"*")]
    Star,
    #[token(b"/")]
    Slash,
    #[token(b"(")]
    LParen,
    #[token(b")")]
    RParen,
    #[token(b"[")]
    LBracket,
    #[token(b"]")]
    RBracket,
    #[token(b",")]
    Comma,
    #[token(b":")]
    Colon,

    // ---- word operators -----------------------------------------------------
    #[token(b"DIV", ignore(case))]
    Div,
    #[token(b"MOD", ignore(case))]
    Mod,
    #[token(b"AND", ignore(case))]
    And,
    #[token(b"OR", ignore(case))]
    Or,
    #[token(b"XOR", ignore(case))]
    Xor,
    #[token(b"NOT", ignore(case))]
    Not,
    #[token(b"B_AND", ignore(case))]
    BAnd,
    #[token(b"B_OR", ignore(case))]
    BOr,
    #[token(b"B_XOR", ignore(case))]
    BXor,
    #[token(b"B_NOT", ignore(case))]
    BNot,
    #[token(b"TRUE", ignore(case))]
    True,
    #[token(b"FALSE", ignore(case))]
    False,

    // ---- keywords -------------------------------------------------------------
    #[token(b"IF", ignore(case))]
    If,
    #[token(b"ELSE", ignore(case))]
    Else,
    #[token(b"ENDIF", ignore(case))]
    EndIf,
    #[token(b"WHILE", ignore(case))]
    While,
    #[token(b"ENDWHILE", ignore(case))]
    EndWhile,
    #[token(b"FOR", ignore(case))]
    For,
    #[token(b"TO", ignore(case))]
    To,
    #[token(b"ENDFOR", ignore(case))]
    EndFor,
    #[token(b"LOOP", ignore(case))]
    Loop,
    #[token(b"ENDLOOP", ignore(case))]
    EndLoop,
    #[token(b"REPEAT", ignore(case))]
    Repeat,
    #[token(b"REPEATB", ignore(case))]
    RepeatB,
    #[token(b"UNTIL", ignore(case))]
    Until,
    #[token(b"CASE", ignore(case))]
    Case,
    #[token(b"OF", ignore(case))]
    Of,
    #[token(b"DEFAULT", ignore(case))]
    Default,
    #[token(b"GOTO", ignore(case))]
    Goto,
    #[token(b"GOTOF", ignore(case))]
    GotoF,
    #[token(b"GOTOB", ignore(case))]
    GotoB,
    #[token(b"GOTOC", ignore(case))]
    GotoC,
    #[token(b"GOTOS", ignore(case))]
    GotoS,
    #[token(b"DEF", ignore(case))]
    Def,
    #[token(b"REDEF", ignore(case))]
    Redef,
    #[token(b"DEFINE", ignore(case))]
    Define,
    #[token(b"AS", ignore(case))]
    As,
    #[token(b"PROC", ignore(case))]
    Proc,
    #[token(b"ENDPROC", ignore(case))]
    EndProc,
    #[token(b"VAR", ignore(case))]
    Var,
    #[token(b"RET", ignore(case))]
    Ret,
    #[token(b"EXTERN", ignore(case))]
    Extern,
    #[token(b"CALL", ignore(case))]
    Call,
    #[token(b"PCALL", ignore(case))]
    PCall,
    #[token(b"MCALL", ignore(case))]
    MCall,
    #[token(b"BLOCK", ignore(case))]
    Block,
    #[token(b"SET", ignore(case))]
    Set,
    #[token(b"REP", ignore(case))]
    Rep,
    #[token(b"ID", ignore(case))]
    Id,
    #[token(b"IDS", ignore(case))]
    Ids,
    #[token(b"WHEN", ignore(case))]
    When,
    #[token(b"WHENEVER", ignore(case))]
    Whenever,
    #[token(b"EVERY", ignore(case))]
    Every,
    #[token(b"FROM", ignore(case))]
    From,
    #[token(b"DO", ignore(case))]
    Do,

    /// A byte that starts no token (reserved `?`, `!`, a lone `$`…).
    Error,
}

impl TokenKind {
    /// Every kind in declaration order (`ALL[k as usize] == k`), for sets of
    /// kinds kept as bit masks.
    pub const ALL: [TokenKind; 87] = [
        TokenKind::Whitespace,
        TokenKind::Newline,
        TokenKind::Comment,
        TokenKind::Header,
        TokenKind::Ident,
        TokenKind::Letter,
        TokenKind::SystemVar,
        TokenKind::Number,
        TokenKind::HexNumber,
        TokenKind::BinNumber,
        TokenKind::BadQuoted,
        TokenKind::String,
        TokenKind::UnclosedString,
        TokenKind::Eq,
        TokenKind::EqEq,
        TokenKind::Ne,
        TokenKind::Lt,
        TokenKind::Gt,
        TokenKind::Le,
        TokenKind::Ge,
        TokenKind::Concat,
        TokenKind::Plus,
        TokenKind::Minus,
        TokenKind::Star,
        TokenKind::Slash,
        TokenKind::LParen,
        TokenKind::RParen,
        TokenKind::LBracket,
        TokenKind::RBracket,
        TokenKind::Comma,
        TokenKind::Colon,
        TokenKind::Div,
        TokenKind::Mod,
        TokenKind::And,
        TokenKind::Or,
        TokenKind::Xor,
        TokenKind::Not,
        TokenKind::BAnd,
        TokenKind::BOr,
        TokenKind::BXor,
        TokenKind::BNot,
        TokenKind::True,
        TokenKind::False,
        TokenKind::If,
        TokenKind::Else,
        TokenKind::EndIf,
        TokenKind::While,
        TokenKind::EndWhile,
        TokenKind::For,
        TokenKind::To,
        TokenKind::EndFor,
        TokenKind::Loop,
        TokenKind::EndLoop,
        TokenKind::Repeat,
        TokenKind::RepeatB,
        TokenKind::Until,
        TokenKind::Case,
        TokenKind::Of,
        TokenKind::Default,
        TokenKind::Goto,
        TokenKind::GotoF,
        TokenKind::GotoB,
        TokenKind::GotoC,
        TokenKind::GotoS,
        TokenKind::Def,
        TokenKind::Redef,
        TokenKind::Define,
        TokenKind::As,
        TokenKind::Proc,
        TokenKind::EndProc,
        TokenKind::Var,
        TokenKind::Ret,
        TokenKind::Extern,
        TokenKind::Call,
        TokenKind::PCall,
        TokenKind::MCall,
        TokenKind::Block,
        TokenKind::Set,
        TokenKind::Rep,
        TokenKind::Id,
        TokenKind::Ids,
        TokenKind::When,
        TokenKind::Whenever,
        TokenKind::Every,
        TokenKind::From,
        TokenKind::Do,
        TokenKind::Error,
    ];

    /// Blanks and comments: tokens the grammar never sees.
    pub const fn is_trivia(self) -> bool {
        matches!(self, Self::Whitespace | Self::Comment)
    }

    /// Keywords that can also name things in real programs; the parser
    /// accepts them where a name is expected.
    pub const fn is_keyword(self) -> bool {
        (self as u8) >= (Self::If as u8) && (self as u8) < (Self::Error as u8)
    }

    /// How the token is named in diagnostics.
    pub const fn describe(self) -> &'static str {
        use TokenKind::*;
        match self {
            Whitespace => "blank",
            Newline => "end of block",
            Comment => "comment",
            Header => "program header",
            Ident => "name",
            Letter => "address letter",
            SystemVar => "system variable",
            Number => "number",
            HexNumber => "hex constant",
            BinNumber => "binary constant",
            BadQuoted => "malformed constant",
            String => "string",
            UnclosedString => "unclosed string",
            Eq => "`=`",
            EqEq => "`==`",
            Ne => "`<>`",
            Lt => "`<`",
            Gt => "`>`",
            Le => "`<=`",
            Ge => "`>=`",
            Concat => "`<<`",
            Plus => "`+`",
            Minus => "`-`",
            Star => "`*`",
            Slash => "`/`",
            LParen => "`(`",
            RParen => "`)`",
            LBracket => "`[`",
            RBracket => "`]`",
            Comma => "`,`",
            Colon => "`:`",
            Div => "`DIV`",
            Mod => "`MOD`",
            And => "`AND`",
            Or => "`OR`",
            Xor => "`XOR`",
            Not => "`NOT`",
            BAnd => "`B_AND`",
            BOr => "`B_OR`",
            BXor => "`B_XOR`",
            BNot => "`B_NOT`",
            True => "`TRUE`",
            False => "`FALSE`",
            If => "`IF`",
            Else => "`ELSE`",
            EndIf => "`ENDIF`",
            While => "`WHILE`",
            EndWhile => "`ENDWHILE`",
            For => "`FOR`",
            To => "`TO`",
            EndFor => "`ENDFOR`",
            Loop => "`LOOP`",
            EndLoop => "`ENDLOOP`",
            Repeat => "`REPEAT`",
            RepeatB => "`REPEATB`",
            Until => "`UNTIL`",
            Case => "`CASE`",
            Of => "`OF`",
            Default => "`DEFAULT`",
            Goto => "`GOTO`",
            GotoF => "`GOTOF`",
            GotoB => "`GOTOB`",
            GotoC => "`GOTOC`",
            GotoS => "`GOTOS`",
            Def => "`DEF`",
            Redef => "`REDEF`",
            Define => "`DEFINE`",
            As => "`AS`",
            Proc => "`PROC`",
            EndProc => "`ENDPROC`",
            Var => "`VAR`",
            Ret => "`RET`",
            Extern => "`EXTERN`",
            Call => "`CALL`",
            PCall => "`PCALL`",
            MCall => "`MCALL`",
            Block => "`BLOCK`",
            Set => "`SET`",
            Rep => "`REP`",
            Id => "`ID`",
            Ids => "`IDS`",
            When => "`WHEN`",
            Whenever => "`WHENEVER`",
            Every => "`EVERY`",
            From => "`FROM`",
            Do => "`DO`",
            Error => "invalid character",
        }
    }
}
