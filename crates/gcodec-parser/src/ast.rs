//! The typed syntax tree of a SINUMERIK part program.
//!
//! The tree is *flat at block level*: a program is a list of blocks (one per
//! line), and control structures are statements that open or close a
//! structure (`If`, `Else`, `EndIf`, …). The pairing of openers and closers is
//! computed by the parser and recorded in [`Program::structures`] and in each
//! block's `depth`. This mirrors the control, which runs control structures
//! interpretively, keeps every block addressable by index for jumps, and
//! means no part of gcodec recurses over nesting depth.
//!
//! Every node carries a [`Span`]; names keep the spelling of the source, and
//! lookups are case-insensitive in later stages.

use std::borrow::Cow;
use std::sync::Arc;

use compact_str::CompactString;
use gcodec_lang::addresses::letter_str;
use gcodec_lang::{BinaryOp, DimensionMode, FrameOp, UnaryOp};
use gcodec_source::{SourceBytes, Span};
use serde::Serialize;

/// A name as written (case kept).
pub type Name = CompactString;

/// One parsed file.
///
/// Serialised, every span in the tree carries `line` and `col` besides its
/// byte offsets (see [`gcodec_source::with_line_starts`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// The file name as given to the parser.
    pub file: String,
    /// `%_N_NAME_MPF` / `%MPF123` header line, if the file has one.
    pub header: Option<Header>,
    /// `;$PATH=/_N_…_DIR` line, if the file has one.
    pub path: Option<PathDirective>,
    /// Every line of the file in order (blank and comment-only lines too).
    pub blocks: Vec<Block>,
    /// Control structures, each with the blocks that open, split and close it.
    pub structures: Vec<ControlStructure>,
    /// The bytes the program was parsed from: later stages quote from it
    /// what the program writes (a number out of range, named as written).
    pub source: SourceText,
}

/// The bytes a program was parsed from, shared: a clone of the program
/// does not copy them. Its `Debug` form gives their count, not every byte.
#[derive(Clone, Default, PartialEq)]
pub struct SourceText(Arc<SourceBytes>);

impl SourceText {
    /// A copy of `bytes`.
    pub fn new(bytes: &[u8]) -> Self {
        Self(Arc::new(bytes.to_vec().into()))
    }

    /// Bytes already shared, such as a [`gcodec_source::SourceFile`]'s.
    pub fn shared(bytes: Arc<SourceBytes>) -> Self {
        Self(bytes)
    }

    pub fn bytes(&self) -> &[u8] {
        &self.0
    }
}

impl std::fmt::Debug for SourceText {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "SourceText({} bytes)", self.0.len())
    }
}

impl Program {
    /// The byte offset at which each line starts: every line is a block.
    pub fn line_starts(&self) -> Vec<u32> {
        self.blocks.iter().map(|b| b.span.start).collect()
    }

    /// 1-based line and byte column of a byte offset in this program.
    pub fn line_col(&self, offset: u32) -> (u32, u32) {
        let line = self.blocks.partition_point(|b| b.span.start <= offset);
        let line_start = line.checked_sub(1).map_or(0, |i| self.blocks[i].span.start);
        (line.max(1) as u32, offset - line_start.min(offset) + 1)
    }
}

impl Serialize for Program {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        #[serde(rename = "Program")]
        struct Fields<'a> {
            file: &'a str,
            header: &'a Option<Header>,
            path: &'a Option<PathDirective>,
            blocks: &'a [Block],
            structures: &'a [ControlStructure],
        }
        let fields = Fields {
            file: &self.file,
            header: &self.header,
            path: &self.path,
            blocks: &self.blocks,
            structures: &self.structures,
        };
        gcodec_source::with_line_starts(self.line_starts(), || fields.serialize(serializer))
    }
}

/// An archive header line (`%_N_SHAFT_MPF`, `%MPF123`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Header {
    pub span: Span,
    /// The text after `%`.
    pub text: CompactString,
    /// The program name for `_N_<NAME>_<TYPE>` headers.
    pub program: Option<CompactString>,
    /// The file type (`MPF`, `SPF`, `DEF`, …) for `_N_<NAME>_<TYPE>` headers.
    pub file_type: Option<CompactString>,
}

/// A `;$PATH=` line giving the program's directory on the control.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PathDirective {
    pub span: Span,
    /// The path, e.g. `/_N_WKS_DIR/_N_PART_WPD`.
    pub path: CompactString,
}

/// One NC block: one line of the file.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Block {
    /// The line without its line end.
    pub span: Span,
    /// `/` or `/0`…`/9` at the start of the block.
    pub skip: Option<Box<SkipLevel>>,
    /// `N10` or `:10`.
    pub number: Option<BlockNumber>,
    /// `NAME:` jump label.
    pub label: Option<Box<LabelDef>>,
    /// The statements in source order.
    pub statements: Box<[Statement]>,
    /// `; …` to the end of the line.
    pub comment: Option<Comment>,
    /// How many control structures enclose this block.
    pub depth: u32,
}

/// A skip mark. `/` is level 0.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct SkipLevel {
    pub span: Span,
    pub level: u8,
}

/// `N<number>` (sub block) or `:<number>` (main block).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BlockNumber {
    pub span: Span,
    pub main: bool,
    pub value: u64,
}

/// A jump label definition `NAME:`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LabelDef {
    pub span: Span,
    pub name: Name,
}

/// A comment, text decoded for display (UTF-8, else CP1252).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Comment {
    pub span: Span,
    pub text: CompactString,
}

/// One statement of a block.
///
/// Serialised as one object: `span`, `kind` and the kind's fields.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    pub span: Span,
    pub kind: StatementKind,
}

impl Serialize for Statement {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        if let StatementKind::Word(word) = &self.kind {
            // A word's inner spans are derived from the statement's.
            let mut map = serializer.serialize_map(None)?;
            map.serialize_entry("span", &self.span)?;
            map.serialize_entry("kind", "word")?;
            word.serialize_fields(self.span, &mut map)?;
            return map.end();
        }
        #[derive(Serialize)]
        struct Fields<'a> {
            span: Span,
            #[serde(flatten)]
            kind: &'a StatementKind,
        }
        Fields {
            span: self.span,
            kind: &self.kind,
        }
        .serialize(serializer)
    }
}

/// What a statement is. Payloads larger than the commonest one, a
/// [`Word`], are boxed: a statement is 32 bytes, and a large program has
/// millions of them.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum StatementKind {
    /// An address word: `G1`, `X-10`, `X=R1+5`, `M2=3`, `G[8]=2`, `CR=5`.
    /// (Serialised by [`Statement`], which holds the word's span.)
    #[serde(skip)]
    Word(Word),
    /// `R1=5`, `A[2,3]=7`, `$P_UIFR[1,X,TR]=10`, `NAME=…`.
    Assign(Box<Assign>),
    /// `DEF …`.
    Def(Box<Def>),
    /// `REDEF name attributes`: kept for later stages.
    Redef(Box<Redef>),
    /// `DEFINE NAME AS …`.
    Define(Box<Define>),
    /// `PROC name(params) attributes`.
    Proc(Box<Proc>),
    /// `ENDPROC`.
    EndProc,
    /// `EXTERN name(types)`.
    Extern(Box<Extern>),
    /// A subprogram or procedure call by name or `L` number.
    Call(Box<Call>),
    /// `CALL <expr>` and `CALL … BLOCK … TO …`.
    IndirectCall(Box<IndirectCall>),
    /// `PCALL path(args)`.
    PCall(Box<PCall>),
    /// `MCALL name(args)` or `MCALL` alone (cancels the modal call).
    MCall(Box<MCall>),
    /// `RET` with optional arguments.
    Ret(Box<Ret>),
    /// `GOTO… target`.
    Goto(Box<Jump>),
    /// `IF cond GOTO… target` in one block.
    IfGoto(Box<IfGoto>),
    /// `IF cond` opening a structure.
    If(Box<Condition>),
    Else,
    EndIf,
    While(Box<Condition>),
    EndWhile,
    For(Box<For>),
    EndFor,
    Loop,
    EndLoop,
    /// `REPEAT` alone opening a REPEAT … UNTIL structure.
    Repeat,
    Until(Box<Condition>),
    /// `REPEAT label [label] [P=n]`, `REPEATB label [P=n]`.
    RepeatSection(Box<RepeatSection>),
    /// `CASE expr OF c GOTOF l … DEFAULT GOTOF l`.
    Case(Box<Case>),
    /// `TRANS X10`, `ROT RPL=45`, `MIRROR X0`, … (`words` empty = reset).
    Frame(Box<Frame>),
    /// `ID=1 WHEN cond DO actions` and friends.
    SyncAction(Box<SyncAction>),
}

/// An address word: `G1`, `X-10`, `X=R1+5`, `M2=3`, `G[8]=2`, `CR=5`.
///
/// A word does not store its own span: it is always held with one (by its
/// [`Statement`] or as a [`SpannedWord`]), and the spans of its parts are
/// derived from it where they can be. That keeps the commonest word, a
/// single letter with a constant touching it (`X10`, `G1`, `F200`), at 16
/// bytes; every other word keeps its parts, spans included, in one box.
#[derive(Clone, Debug, PartialEq)]
pub struct Word(WordRepr);

#[derive(Clone, Debug, PartialEq)]
enum WordRepr {
    /// An upper-case letter at the start of the word and a constant from
    /// the next byte to the end of the word.
    Letter {
        letter: u8,
        integer: bool,
        value: f64,
    },
    Parts(Box<WordParts>),
}

#[derive(Clone, Debug, PartialEq)]
struct WordParts {
    address: Name,
    address_span: Span,
    extension: Option<Extension>,
    value: WordValue,
}

impl Word {
    /// The word written at `span`: its address in upper case, where the
    /// address is written, its extension and its value.
    pub fn new(
        span: Span,
        address: &str,
        address_span: Span,
        extension: Option<Extension>,
        value: WordValue,
    ) -> Self {
        if let (Some(&letter), None, WordValue::Constant(n)) =
            (address.as_bytes().first(), &extension, &value)
        {
            let compact = address.len() == 1
                && letter.is_ascii_uppercase()
                && address_span == Span::new(span.start, span.start + 1)
                && n.span == Span::new(span.start + 1, span.end);
            if compact {
                return Word(WordRepr::Letter {
                    letter,
                    integer: n.integer,
                    value: n.value,
                });
            }
        }
        Word(WordRepr::Parts(Box::new(WordParts {
            address: Name::from(address),
            address_span,
            extension,
            value,
        })))
    }

    /// The address in upper case: `X`, `G`, `CR`, `SPOS`, `AX`.
    pub fn address(&self) -> &str {
        match &self.0 {
            WordRepr::Letter { letter, .. } => letter_str(*letter),
            WordRepr::Parts(parts) => &parts.address,
        }
    }

    /// The upper-case letter, value and wholeness of a word written as a
    /// letter with a constant touching it (`X10`, `g1`, `F200.5`); `None`
    /// for any other word.
    pub fn letter_constant(&self) -> Option<(u8, f64, bool)> {
        match self.0 {
            WordRepr::Letter {
                letter,
                integer,
                value,
            } => Some((letter, value, integer)),
            WordRepr::Parts(_) => None,
        }
    }

    /// Where the address is written, given the span of the word.
    pub fn address_span(&self, span: Span) -> Span {
        match &self.0 {
            WordRepr::Letter { .. } => Span::new(span.start, span.start + 1),
            WordRepr::Parts(parts) => parts.address_span,
        }
    }

    /// `M2=`, `X1=` (numeric) or `M[R1]=`, `AX[X1]=` (bracketed).
    pub fn extension(&self) -> Option<&Extension> {
        match &self.0 {
            WordRepr::Letter { .. } => None,
            WordRepr::Parts(parts) => parts.extension.as_ref(),
        }
    }

    /// The value, given the span of the word.
    pub fn value(&self, span: Span) -> Cow<'_, WordValue> {
        match &self.0 {
            &WordRepr::Letter { integer, value, .. } => {
                Cow::Owned(WordValue::Constant(NumberLit {
                    span: Span::new(span.start + 1, span.end),
                    value,
                    integer,
                }))
            }
            WordRepr::Parts(parts) => Cow::Borrowed(&parts.value),
        }
    }

    /// Writes `address`, `address_span`, `extension` and `value`.
    fn serialize_fields<M: serde::ser::SerializeMap>(
        &self,
        span: Span,
        map: &mut M,
    ) -> Result<(), M::Error> {
        map.serialize_entry("address", self.address())?;
        map.serialize_entry("address_span", &self.address_span(span))?;
        map.serialize_entry("extension", &self.extension())?;
        map.serialize_entry("value", &self.value(span))
    }
}

/// A word that is part of another statement (`TRANS X10`, the `P3` of a
/// call), with the span it is written at.
#[derive(Clone, Debug, PartialEq)]
pub struct SpannedWord {
    pub span: Span,
    pub word: Word,
}

impl Serialize for SpannedWord {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("span", &self.span)?;
        self.word.serialize_fields(self.span, &mut map)?;
        map.end()
    }
}

/// The extension of an extended address.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum Extension {
    /// `M2=3`: digits touching the address, then `=`.
    Number { span: Span, value: u32 },
    /// `M[R1]=3`, `AX[X1]=10`.
    Index { span: Span, index: Box<Expr> },
}

/// The value of a word.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum WordValue {
    /// `X10`, `X-10`, `S.5`: a constant touching the address.
    Constant(NumberLit),
    /// `X=…`: a value after `=`, with its dimension modifier if one wraps it.
    Assigned {
        modifier: Option<DimensionModifier>,
        expr: Box<Expr>,
    },
}

/// A numeric literal.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NumberLit {
    pub span: Span,
    pub value: f64,
    /// Written without decimal point or exponent.
    pub integer: bool,
}

/// `AC(…)`, `IC(…)`, `DC(…)`, `ACP(…)`, `ACN(…)` (and the indexing and
/// diameter forms) wrapping a word's value.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DimensionModifier {
    pub span: Span,
    pub kind: DimensionMode,
}

/// An assignment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Assign {
    pub target: VarRef,
    pub value: Initializer,
}

/// A reference to a variable: R parameter, user variable or system variable,
/// possibly indexed.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VarRef {
    pub span: Span,
    pub kind: VarKind,
    /// The name as written (`R` for R parameters, `$P_UIFR`, `COUNTER`).
    pub name: Name,
    /// `R1` has index `1`; `A[i,j]` has two.
    pub indices: Vec<Expr>,
}

/// What kind of variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum VarKind {
    /// `R1`, `R[expr]`.
    RParameter,
    /// A user variable, constant or axis name (resolved by later stages).
    Name,
    /// `$…`.
    System,
}

/// The right side of `=` in an assignment or `DEF`.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum Initializer {
    Expr(Expr),
    /// `(a, b, c)` or `SET(a, , c)`: one value per element, omitted ones empty.
    List {
        span: Span,
        set: bool,
        items: Vec<Option<Expr>>,
    },
    /// `REP(value [, count])`.
    Rep {
        span: Span,
        args: Vec<Expr>,
    },
}

/// `DEF [NCK|CHAN] [attributes] TYPE name[dims]=init, …`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Def {
    /// Attributes before the type (`NCK`, `CHAN`, `SYNR`, `LLI 0`, …).
    pub attributes: Vec<Attribute>,
    pub ty: TypeSpec,
    pub vars: Vec<DefVar>,
}

/// A definition attribute, with its value where it takes one.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Attribute {
    pub span: Span,
    pub name: Name,
    pub value: Option<Expr>,
}

/// A data type.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TypeSpec {
    pub span: Span,
    pub kind: TypeKind,
}

/// The data types of the NC language.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "UPPERCASE")]
pub enum TypeKind {
    Int,
    Real,
    Bool,
    Char,
    /// `STRING[n]`.
    String {
        length: Option<Box<Expr>>,
    },
    Axis,
    Frame,
}

impl TypeKind {
    /// The type named `name` (case-insensitive), without a string length.
    pub fn from_name(name: &str) -> Option<Self> {
        const NAMES: [&str; 7] = ["INT", "REAL", "BOOL", "CHAR", "STRING", "AXIS", "FRAME"];
        let index = NAMES.iter().position(|n| n.eq_ignore_ascii_case(name))?;
        Some(match index {
            0 => TypeKind::Int,
            1 => TypeKind::Real,
            2 => TypeKind::Bool,
            3 => TypeKind::Char,
            4 => TypeKind::String { length: None },
            5 => TypeKind::Axis,
            _ => TypeKind::Frame,
        })
    }
}

/// One variable of a `DEF`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DefVar {
    pub span: Span,
    pub name: Name,
    /// Array dimensions (up to three).
    pub dims: Vec<Expr>,
    pub init: Option<Initializer>,
}

/// `REDEF name attributes`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Redef {
    pub name: Name,
    pub attributes: Vec<Attribute>,
}

/// `DEFINE NAME AS text`: the text is kept as written.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Define {
    pub name: Name,
    pub body: CompactString,
    pub body_span: Span,
}

/// `PROC name(params) attributes`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Proc {
    pub name: Name,
    pub name_span: Span,
    pub params: Vec<Param>,
    /// `SAVE`, `DISPLOF`, `SBLOF`, …
    pub attributes: Vec<Attribute>,
}

/// A formal parameter.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Param {
    pub span: Span,
    /// `VAR`: passed by reference.
    pub by_reference: bool,
    pub ty: TypeSpec,
    pub name: Name,
    pub dims: Vec<Expr>,
    pub default: Option<Expr>,
}

/// `EXTERN name(types)`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Extern {
    pub name: Name,
    pub params: Vec<ExternParam>,
}

/// A parameter type in an `EXTERN` declaration.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExternParam {
    pub span: Span,
    pub by_reference: bool,
    pub ty: TypeSpec,
    /// One entry per array dimension; `REAL[,]` has two empty ones.
    pub dims: Vec<Option<Expr>>,
}

/// A call of a subprogram, cycle or predefined procedure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Call {
    pub target: CallTarget,
    /// `None` when written without parentheses. Omitted arguments are `null`.
    pub args: Option<Vec<Option<Expr>>>,
    /// `P3` / `P=3` in the same block: number of passes.
    pub passes: Option<Box<SpannedWord>>,
}

/// What a call names.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum CallTarget {
    /// `CONTOUR`, `CYCLE81`, `MSG`, `STOPRE`.
    Name { span: Span, name: Name },
    /// `L123`: the digits as written (`L007` is not `L7`).
    Number { span: Span, digits: CompactString },
}

/// `CALL <expr>` / `CALL [<expr>] BLOCK <start> TO <end>`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IndirectCall {
    pub program: Option<Expr>,
    pub section: Option<(JumpTarget, JumpTarget)>,
}

/// `PCALL /path/_N_NAME_SPF(args)`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PCall {
    pub path: CompactString,
    pub path_span: Span,
    pub args: Option<Vec<Option<Expr>>>,
}

/// `MCALL [call]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MCall {
    pub call: Option<Call>,
}

/// `RET [(args)]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Ret {
    pub args: Option<Vec<Option<Expr>>>,
}

/// Which jump.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum GotoKind {
    Goto,
    GotoF,
    GotoB,
    GotoC,
    GotoS,
}

impl GotoKind {
    /// The keyword as the control spells it.
    pub const fn keyword(self) -> &'static str {
        match self {
            GotoKind::Goto => "GOTO",
            GotoKind::GotoF => "GOTOF",
            GotoKind::GotoB => "GOTOB",
            GotoKind::GotoC => "GOTOC",
            GotoKind::GotoS => "GOTOS",
        }
    }
}

/// A jump.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Jump {
    pub goto: GotoKind,
    /// `None` only for `GOTOS`.
    pub target: Option<JumpTarget>,
}

/// Where a jump goes.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "form", rename_all = "snake_case")]
pub enum JumpTarget {
    Label {
        span: Span,
        name: Name,
    },
    BlockNumber {
        span: Span,
        value: u64,
    },
    /// A STRING expression naming a label or block number.
    Expr(Expr),
}

/// `IF cond GOTO… target`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct IfGoto {
    pub condition: Expr,
    pub jump: Jump,
}

/// The condition of `IF`, `WHILE`, `UNTIL`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Condition {
    pub condition: Expr,
}

/// `FOR var = start TO end`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct For {
    pub var: VarRef,
    pub start: Expr,
    pub end: Expr,
}

/// `REPEAT start [end] [P=n]`, `REPEATB label [P=n]`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RepeatSection {
    /// `REPEATB`: repeat the one block carrying the label.
    pub single_block: bool,
    pub start: JumpTarget,
    pub end: Option<JumpTarget>,
    pub passes: Option<Box<SpannedWord>>,
}

/// `CASE expr OF …`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Case {
    pub selector: Expr,
    pub arms: Vec<CaseArm>,
    pub default: Option<Jump>,
}

/// `<constant> GOTO… <target>` inside `CASE`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseArm {
    pub value: Expr,
    pub jump: Jump,
}

/// A frame statement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Frame {
    pub op: FrameOp,
    pub words: Vec<SpannedWord>,
}

/// A synchronous action.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SyncAction {
    /// `ID=n` (modal, program-local) or `IDS=n` (static).
    pub id: Option<SyncId>,
    /// `WHEN`, `WHENEVER`, `EVERY`, `FROM` with its condition.
    pub trigger: Option<SyncTrigger>,
    /// The statements after `DO`.
    pub actions: Vec<Statement>,
}

/// `ID=`/`IDS=` of a synchronous action.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SyncId {
    pub span: Span,
    pub is_static: bool,
    pub value: Expr,
}

/// The trigger of a synchronous action.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SyncTrigger {
    pub span: Span,
    pub kind: SyncTriggerKind,
    pub condition: Expr,
}

/// Which trigger.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum SyncTriggerKind {
    When,
    Whenever,
    Every,
    From,
}

impl SyncTriggerKind {
    /// The keyword as the control spells it.
    pub const fn keyword(self) -> &'static str {
        match self {
            SyncTriggerKind::When => "WHEN",
            SyncTriggerKind::Whenever => "WHENEVER",
            SyncTriggerKind::Every => "EVERY",
            SyncTriggerKind::From => "FROM",
        }
    }
}

/// An expression.
///
/// Serialised as one object: `span`, `kind` and the variant's fields
/// (written by hand because `#[serde(flatten)]` buffers
/// every level, which is slow and deep on the stack for long chains).
#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub span: Span,
    pub kind: ExprKind,
}

impl Serialize for Expr {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = serializer.serialize_map(None)?;
        map.serialize_entry("span", &self.span)?;
        match &self.kind {
            ExprKind::Number { value, integer } => {
                map.serialize_entry("kind", "number")?;
                map.serialize_entry("value", value)?;
                map.serialize_entry("integer", integer)?;
            }
            ExprKind::String { value } => {
                map.serialize_entry("kind", "string")?;
                map.serialize_entry("value", value)?;
            }
            ExprKind::Bool { value } => {
                map.serialize_entry("kind", "bool")?;
                map.serialize_entry("value", value)?;
            }
            ExprKind::Var { var } => {
                map.serialize_entry("kind", "var")?;
                map.serialize_entry("var", var)?;
            }
            ExprKind::Call(call) => {
                map.serialize_entry("kind", "call")?;
                map.serialize_entry("name", &call.name)?;
                map.serialize_entry("name_span", &call.name_span)?;
                map.serialize_entry("args", &call.args)?;
            }
            ExprKind::Unary { op, operand } => {
                map.serialize_entry("kind", "unary")?;
                map.serialize_entry("op", op)?;
                map.serialize_entry("operand", operand)?;
            }
            ExprKind::Binary(binary) => {
                map.serialize_entry("kind", "binary")?;
                map.serialize_entry("op", &binary.op)?;
                map.serialize_entry("lhs", &binary.lhs)?;
                map.serialize_entry("rhs", &binary.rhs)?;
            }
        }
        map.end()
    }
}

/// What an expression is. Variants hold at most 16 bytes (larger parts
/// are boxed) so that an [`Expr`] is 32 bytes: expressions are moved around
/// a lot while parsing.
#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// Decimal, `'H…'` or `'B…'` constant.
    Number {
        value: f64,
        integer: bool,
    },
    String {
        value: Box<CompactString>,
    },
    Bool {
        value: bool,
    },
    Var {
        var: Box<VarRef>,
    },
    /// `SIN(30)`, `AC(5)`, `CTRANS(X,10)`, `USERFUNC(…)`.
    Call(Box<CallExpr>),
    Unary {
        op: UnaryOp,
        operand: Box<Expr>,
    },
    Binary(Box<BinaryExpr>),
}

/// A function call inside an expression.
#[derive(Clone, Debug, PartialEq)]
pub struct CallExpr {
    pub name: Name,
    pub name_span: Span,
    /// Omitted arguments are `None`.
    pub args: Vec<Option<Expr>>,
}

/// A binary operation.
#[derive(Clone, Debug, PartialEq)]
pub struct BinaryExpr {
    pub op: BinaryOp,
    pub lhs: Expr,
    pub rhs: Expr,
}

/// A matched control structure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ControlStructure {
    pub kind: StructureKind,
    /// Index of the opening block in [`Program::blocks`].
    pub open: u32,
    /// Index of the `ELSE` block.
    pub middle: Option<u32>,
    /// Index of the closing block; `None` if the structure is never closed
    /// (a diagnostic says so).
    pub close: Option<u32>,
}

/// Which structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StructureKind {
    If,
    While,
    For,
    Loop,
    Repeat,
}
