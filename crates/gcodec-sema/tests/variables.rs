//! Variables in lowering: names must be defined (DEF, PROC parameters,
//! global user data, macros, axes), declared types are checked on
//! assignment, array indices against dimensions, system variables against
//! their index shapes; `REP` and lists of values are lowered; `REDEF` and
//! `DEFINE` are checked and say what is not built.

use gcodec_profile::Profile;
use gcodec_sema::{Definitions, Lowered, lower, lower_with};
use serde_json::json;

mod common;

use common::{codes, errors, ops};

const UNDEFINED: &str = "gcodec::lower::undefined_variable";
const TYPE_MISMATCH: &str = "gcodec::lower::type_mismatch";
const OUT_OF_RANGE: &str = "gcodec::lower::index_out_of_range";
const INDEX_COUNT: &str = "gcodec::lower::index_count";
const SYSVAR_INDEX: &str = "gcodec::lower::system_variable_index";
const MISPLACED: &str = "gcodec::lower::misplaced_definition";
const DUPLICATE: &str = "gcodec::lower::duplicate_definition";
const NOT_LOWERED: &str = "gcodec::lower::not_lowered";

fn parse(src: &str) -> gcodec_parser::ast::Program {
    let parsed = gcodec_parser::parse_bytes("test.mpf", src.as_bytes());
    assert!(
        parsed.diagnostics.is_empty(),
        "{src}: {:#?}",
        parsed.diagnostics
    );
    parsed.program
}

fn default_profile() -> Profile {
    common::profile("default.toml")
}

fn run(src: &str) -> Lowered {
    lower(&parse(src), &default_profile())
}

fn run_with(src: &str, definitions: &Definitions) -> Lowered {
    lower_with(&parse(src), &default_profile(), definitions)
}

/// The message of the only error, for checking what it says.
fn only_error(lowered: &Lowered) -> String {
    let errors: Vec<_> = lowered
        .diagnostics
        .iter()
        .filter(|d| d.is_error())
        .collect();
    assert_eq!(errors.len(), 1, "{errors:#?}");
    errors[0].message.to_string()
}

const MGUD: &str = "\
;global data
DEF CHAN STRING[32] GR_TOOL
DEF NCK REAL GR_TAPER[4]
DEF CHAN AXIS GR_AXIS = (Z)
DEF CHAN REAL GR_STEPS[6] = REP(0.1)
DEFINE M_STOP AS M5
M30
";

fn mgud() -> Definitions {
    let (definitions, diagnostics) = Definitions::from_source("MGUD.DEF", MGUD);
    assert!(diagnostics.is_empty(), "{diagnostics:#?}");
    definitions
}

// ---- names must be defined ----

#[test]
fn an_undefined_name_is_an_error() {
    let l = run("G1 X=LENGTH F100\n");
    assert_eq!(errors(&l), [UNDEFINED]);
    assert!(only_error(&l).contains("`LENGTH`"));
    // Read in a condition, written by an assignment, as a FOR counter,
    // as an index, as a call argument: all are uses.
    for src in [
        "IF COUNTER>3 GOTOF END\nEND:\n",
        "COUNTER=1\n",
        "FOR II=0 TO 3\nENDFOR\n",
        "R[IDX]=1\n",
        "MYCYCLE(DEPTH)\n",
    ] {
        let l = run(src);
        assert_eq!(errors(&l), [UNDEFINED], "{src}");
    }
}

#[test]
fn an_undefined_name_near_a_defined_one_is_suggested() {
    let l = run("DEF REAL DEPTH=5\nG1 Z=DEPHT F100\n");
    assert_eq!(errors(&l), [UNDEFINED]);
    let label = l.diagnostics[0].labels[0]
        .message
        .as_deref()
        .unwrap_or_default();
    assert_eq!(label, "unknown name: did you mean `DEPTH`?");
    // Global user data too; nothing near, nothing suggested.
    let l = run_with("R1=GR_TAPR[1]\nR2=QQQQ\n", &mgud());
    let labels: Vec<_> = l
        .diagnostics
        .iter()
        .map(|d| d.labels[0].message.as_deref().unwrap_or_default())
        .collect();
    assert_eq!(
        labels,
        ["unknown name: did you mean `GR_TAPER`?", "unknown name"]
    );
}

#[test]
fn def_makes_a_name_known_in_any_case() {
    let l = run("DEF REAL lAYER_HEIGHT\nLAYER_HEIGHT=2.5\nG1 Z=IC(layer_height) F100\n");
    assert_eq!(errors(&l), [] as [&str; 0]);
}

#[test]
fn a_name_is_known_from_its_def_on() {
    let l = run("DEF INT AA=BB\nDEF INT BB\n");
    assert_eq!(errors(&l), [UNDEFINED]);
    assert!(only_error(&l).contains("before its definition"));
    // Within one DEF, a later variable may use an earlier one.
    assert_eq!(errors(&run("DEF INT NN=6, MM=NN*2\n")), [] as [&str; 0]);
}

#[test]
fn proc_parameters_are_names_of_the_procedure() {
    let src =
        "PROC CONTOUR(REAL XS, VAR INT COUNT, REAL TAB[3])\nG1 X=XS F100\nCOUNT=TAB[2]\nRET\n";
    assert_eq!(errors(&run(src)), [] as [&str; 0]);
    // A second procedure has its own names.
    // (Whether a second `PROC` in one file is allowed is checked apart.)
    let src =
        "PROC ONE(REAL XS)\nG1 X=XS F100\nENDPROC\nPROC TWO(REAL YS)\nG1 X=XS Y=YS F100\nENDPROC\n";
    let l = run(src);
    let undefined: Vec<_> = l
        .diagnostics
        .iter()
        .filter(|d| d.code == UNDEFINED)
        .collect();
    assert_eq!(undefined.len(), 1, "{undefined:#?}");
    assert!(undefined[0].message.contains("`XS`"));
}

#[test]
fn axes_of_the_machine_and_machine_axis_names_are_known() {
    let l = run("DEF AXIS AXN=X\nDEF FRAME FR\nFR=CTRANS(X,10):CROT(Z,45)\nAXN=AX1\n");
    assert_eq!(errors(&l), [] as [&str; 0]);
    // An axis the default machine lacks is not.
    let l = run("DEF AXIS AXN\nAXN=WW\n");
    assert_eq!(errors(&l), [UNDEFINED]);
}

#[test]
fn global_user_data_come_from_definition_files() {
    let src = "GR_TOOL=\"WHEEL\"\nR1=GR_TAPER[3]+GR_STEPS[5]\nAX[GR_AXIS]=10\n";
    assert_eq!(errors(&run(src)), [UNDEFINED; 4]);
    let l = run_with(src, &mgud());
    assert_eq!(errors(&l), [] as [&str; 0]);
    // Their types and dimensions are checked too.
    let l = run_with("GR_TAPER[4]=1\nGR_TOOL=5\n", &mgud());
    assert_eq!(errors(&l), [OUT_OF_RANGE, TYPE_MISMATCH]);
}

#[test]
fn the_definition_file_is_read_as_the_control_reads_it() {
    let definitions = mgud();
    let tool = definitions.variable("gr_tool").expect("defined");
    assert_eq!(
        tool.data_type,
        gcodec_lang::DataType::String { length: Some(32) }
    );
    assert_eq!(tool.range, gcodec_sema::definitions::GlobalRange::Chan);
    let taper = definitions.variable("GR_TAPER").expect("defined");
    assert_eq!(taper.dims, [Some(4)]);
    assert_eq!(taper.range, gcodec_sema::definitions::GlobalRange::Nck);
    assert!(definitions.macro_named("m_stop").is_some());
    assert_eq!(definitions.len(), 4);
}

#[test]
fn a_bad_definition_file_gives_diagnostics() {
    let (_, d) = Definitions::from_source(
        "BAD.DEF",
        "DEF INT AA\nDEF REAL AA\nG1 X10\nREDEF QQ SYNR\n",
    );
    let codes: Vec<_> = d.iter().map(|d| d.code.name()).collect();
    assert_eq!(
        codes,
        [
            "gcodec::definitions::duplicate",
            "gcodec::definitions::not_a_definition",
            UNDEFINED
        ]
    );
    let (_, d) = Definitions::from_source("BAD.DEF", "DEF STRING[3] NAME=\"ABCDE\"\n");
    assert_eq!(
        d.iter().map(|d| d.code.name()).collect::<Vec<_>>(),
        [TYPE_MISMATCH]
    );
    // Parse errors come through.
    let (_, d) = Definitions::from_source("BAD.DEF", "DEF INT\n");
    assert!(d.iter().any(|d| d.is_error()));
}

#[test]
fn a_name_assumed_defined_is_known_without_checks() {
    let mut definitions = Definitions::new();
    definitions.assume_defined("Tab_Values");
    let l = run_with("R1=TAB_VALUES[1,2,3]\nTAB_VALUES=\"x\"\n", &definitions);
    assert_eq!(errors(&l), [] as [&str; 0]);
}

#[test]
fn addresses_written_like_variables_are_not_undefined() {
    let l = run("ACC[X]=50\nMEAS=1 G1 X10 F100\n");
    assert_eq!(errors(&l), [] as [&str; 0]);
}

// ---- the definition part ----

#[test]
fn a_def_after_an_executable_statement_is_an_error() {
    let l = run("DEF INT AA\nG1 X10 F100\nDEF INT BB\nBB=AA\n");
    assert_eq!(errors(&l), [MISPLACED]);
    // Comments, blank lines, block numbers, DEFINE and EXTERN do not end
    // the definition part.
    let src =
        "; header\n\nN10 DEF INT AA\nDEFINE MM AS 5\nEXTERN SUB(REAL)\nN20 DEF REAL BB\nBB=AA\n";
    assert_eq!(errors(&run(src)), [] as [&str; 0]);
}

#[test]
fn a_def_after_the_end_of_a_procedure_starts_a_new_program_part() {
    // A procedure, then a main program in the same file.
    let src = "PROC MYPROC(INT ARG1)\nIF ARG1>10\nG0 X=ARG1\nENDIF\nRET\n\nDEF INT TYPTH\nTYPTH=1\nMYPROC(TYPTH)\nM30\n";
    let l = run(src);
    assert_eq!(errors(&l), [] as [&str; 0]);
    // A RET inside a structure does not end the part.
    let src = "DEF INT AA\nIF AA==1\nRET\nENDIF\nDEF INT BB\n";
    assert_eq!(errors(&run(src)), [MISPLACED]);
    // The new part does not see the procedure's parameters.
    let src = "PROC P1(INT ARG1)\nRET\nDEF INT BB\nBB=ARG1\n";
    assert_eq!(errors(&run(src)), [UNDEFINED]);
}

#[test]
fn a_name_defined_twice_is_an_error() {
    assert_eq!(errors(&run("DEF INT AA\nDEF REAL aa\n")), [DUPLICATE]);
    assert_eq!(
        errors(&run("PROC P1(INT AA)\nDEF REAL AA\nRET\n")),
        [DUPLICATE]
    );
}

#[test]
fn a_name_that_is_an_axis_of_the_machine_is_an_error() {
    const NAME_IS_AXIS: &str = "gcodec::lower::name_is_axis";
    let grinder = common::profile("grinder_fb422.toml");
    let l = lower(&parse("DEF REAL XV=3\nXV=4\n"), &grinder);
    assert_eq!(errors(&l), [NAME_IS_AXIS]);
    assert!(only_error(&l).contains("`XV` is an axis of this machine"));
    let l = lower(&parse("PROC TST(REAL xv)\nRET\n"), &grinder);
    assert_eq!(errors(&l), [NAME_IS_AXIS]);
    // Machine axis names are axes on every machine; `XV` is none on the
    // default one.
    assert_eq!(errors(&run("DEF INT AX2\n")), [NAME_IS_AXIS]);
    assert_eq!(errors(&run("DEF REAL XV=3\n")), [] as [&str; 0]);
}

// ---- types ----

#[test]
fn incompatible_assignments_are_errors() {
    let cases = [
        (
            "DEF REAL AA\nAA=\"text\"\n",
            "a STRING value cannot be assigned to `AA`, which is REAL",
        ),
        (
            "DEF AXIS AA\nAA=5\n",
            "an INT value cannot be assigned to `AA`, which is AXIS",
        ),
        (
            "DEF INT AA\nAA=$P_AXN1\n",
            "an AXIS value cannot be assigned to `AA`, which is INT",
        ),
        (
            "DEF FRAME FR\nFR=1.5\n",
            "a REAL value cannot be assigned to `FR`, which is FRAME",
        ),
        (
            "DEF STRING[10] SS\nSS=1+2\n",
            "an INT value cannot be assigned to `SS`, which is STRING[10]",
        ),
        (
            "DEF REAL AA\nAA=CTRANS(X,1)\n",
            "a FRAME value cannot be assigned to `AA`, which is REAL",
        ),
        (
            "R1=\"x\"\n",
            "a STRING value cannot be assigned to `R1`, which is REAL",
        ),
        (
            "$P_UBFR=5\n",
            "an INT value cannot be assigned to `$P_UBFR`, which is FRAME",
        ),
        (
            "DEF REAL AA=\"x\"\n",
            "a STRING value cannot be assigned to `AA`, which is REAL",
        ),
        (
            "DEF STRING[3] SS=\"ABCD\"\n",
            "the string has 4 characters; `SS` is STRING[3]",
        ),
        (
            "DEF CHAR CC=\"AB\"\n",
            "`CC` is CHAR: a string converts to CHAR only if it has one character; this one has 2",
        ),
    ];
    for (src, message) in cases {
        let l = run(src);
        assert_eq!(errors(&l), [TYPE_MISMATCH], "{src}");
        assert_eq!(only_error(&l), message, "{src}");
    }
}

/// A string's length is counted in characters, and the message says so:
/// `ÄÖÜß` is 4 characters (8 bytes of UTF-8), which `STRING[4]` holds.
#[test]
fn a_string_length_is_counted_and_reported_in_characters() {
    let fits = run("DEF STRING[4] SS=\"ÄÖÜß\"\n");
    assert!(errors(&fits).is_empty(), "{:?}", errors(&fits));
    let long = run("DEF STRING[3] SS=\"ÄÖÜß\"\n");
    assert_eq!(errors(&long), [TYPE_MISMATCH]);
    assert_eq!(
        only_error(&long),
        "the string has 4 characters; `SS` is STRING[3]"
    );
}

#[test]
fn allowed_conversions_and_unknown_types_are_not_errors() {
    let src = "\
DEF INT II=2.5
DEF REAL RR=II
DEF BOOL BB=RR
DEF CHAR CC=\"A\"
DEF STRING[10] SS=CC
DEF BOOL BB2=SS
DEF STRING[20] SS2=\"N=\"<<II
DEF AXIS AXN=AXNAME(\"X\")
DEF FRAME FR=CTRANS(X,1):CROT(Z,2)
DEF REAL RR2=MYFUNC(1)
DEF INT II2=$A_IN[1]
DEF STRING[8] SS3=STRLEN(SS)<>0
RR=SIN(30)*II+R1 DIV 2
II=STRLEN(SS)
SS[0]=\"B\"
FR[X,TR]=5
";
    let l = run(src);
    // `STRLEN(SS)<>0` is BOOL, which does not convert to STRING.
    assert_eq!(errors(&l), [TYPE_MISMATCH]);
    assert!(only_error(&l).contains("`SS3`"));
}

// ---- arrays ----

#[test]
fn indices_are_checked_against_the_dimensions() {
    assert_eq!(
        errors(&run("DEF REAL TT[3,4]\nTT[2,3]=1\nTT[0,0]=TT[1,1]\n")),
        [] as [&str; 0]
    );
    let l = run("DEF REAL TT[3,4]\nTT[3,0]=1\n");
    assert_eq!(errors(&l), [OUT_OF_RANGE]);
    assert_eq!(
        only_error(&l),
        "index 3 is outside `TT`: the first indices run from 0 to 2"
    );
    assert_eq!(
        errors(&run("DEF REAL TT[3,4]\nR1=TT[0,-1]\n")),
        [OUT_OF_RANGE]
    );
    let l = run("DEF REAL TT[3,4]\nTT[1]=1\n");
    assert_eq!(errors(&l), [INDEX_COUNT]);
    assert_eq!(errors(&run("DEF REAL SC\nSC[1]=1\n")), [INDEX_COUNT]);
    // Computed indices are checked when they run.
    assert_eq!(
        errors(&run("DEF REAL TT[3]\nDEF INT II\nTT[II+5]=1\n")),
        [] as [&str; 0]
    );
}

// ---- system variables ----

#[test]
fn system_variable_index_shapes_are_checked() {
    let ok = "\
$P_UIFR[1]=CTRANS(X,10)
$P_UIFR[1,X,TR]=10
$P_UBFR[Y,TR]=5
R1=$P_ACTFRAME[Z,SC]+$AA_IM[X]+$A_IN[1]+$TC_DP1[1,1]+$P_TOOLNO
";
    assert_eq!(errors(&run(ok)), [] as [&str; 0]);
    for (src, needle) in [
        ("R1=$AA_IM\n", "`$AA_IM` takes one axis index"),
        ("R1=$TC_DP1[1]\n", "`$TC_DP1` takes two number indices"),
        ("R1=$P_TOOLNO[1]\n", "`$P_TOOLNO` takes no index"),
        ("$P_UIFR[1,X]=3\n", "`$P_UIFR` takes `[n]`"),
        ("R1=$AA_IM[1]\n", "must be an axis"),
        ("R1=$A_IN[X]\n", "must be a number"),
        ("$P_UIFR[1,X,QQ]=3\n", "must be a frame component"),
    ] {
        let l = run(src);
        assert_eq!(errors(&l), [SYSVAR_INDEX], "{src}");
        assert!(only_error(&l).contains(needle), "{src}: {}", only_error(&l));
    }
}

#[test]
fn every_system_variable_of_the_controls_lists_is_known() {
    // Unknown before the catalogue was in the vocabulary (issue 16).
    let ok = "\
R1=$VA_IM[X]+$AA_MM[X]+$P_S[1]+$AC_PARAM[3]+$TC_MPP1[1,2]
IF $P_SEARCH OR $P_ISTEST GOTOF END
END: M30
";
    assert_eq!(codes(&run(ok)), [] as [&str; 0]);
    // The catalogue counts the indices: the kind of index is not checked.
    let l = run("R1=$VA_IM\n");
    assert_eq!(errors(&l), [SYSVAR_INDEX]);
    assert!(
        only_error(&l).contains("`$VA_IM` takes one index"),
        "{}",
        only_error(&l)
    );
}

#[test]
fn an_unknown_system_variable_suggests_the_nearest_name() {
    let l = run("IF $P_ISTST GOTOF END\nEND: M30\n");
    assert_eq!(errors(&l), ["gcodec::lower::unknown_system_variable"]);
    let help = l.diagnostics[0].help.as_deref().unwrap_or_default();
    assert!(help.starts_with("did you mean `$P_ISTEST`?"), "{help}");
    let l = run("R1=$QQQQQ_QQQ\n");
    let help = l.diagnostics[0].help.as_deref().unwrap_or_default();
    assert!(help.starts_with("check the spelling"), "{help}");
}

// ---- REP and lists of values ----

#[test]
fn rep_initialisers_are_lowered() {
    let l = run("DEF INT FELD[2,3,4] = REP(1,24)\nDEF REAL BB[9]=REP(0)\n");
    assert_eq!(codes(&l), [] as [&str; 0]);
    let declares = ops(&l, "declare");
    assert_eq!(
        declares[0],
        json!({"kind": "declare", "name": "FELD", "data_type": "INT",
               "dims": [2.0, 3.0, 4.0], "init": [],
               "init_repeat": {"value": 1.0, "count": 24.0}})
    );
    assert_eq!(
        declares[1]["init_repeat"],
        json!({"value": 0.0, "count": null})
    );
    // Too many, a single value, a bad count, the wrong type.
    assert_eq!(errors(&run("DEF INT FF[2,3]=REP(1,7)\n")), [OUT_OF_RANGE]);
    assert_eq!(errors(&run("DEF INT FF=REP(1)\n")), [TYPE_MISMATCH]);
    assert_eq!(
        errors(&run("DEF INT FF[3]=REP(1,0)\n")),
        ["gcodec::lower::invalid_value"]
    );
    assert_eq!(errors(&run("DEF REAL FF[3]=REP(\"x\")\n")), [TYPE_MISMATCH]);
}

#[test]
fn set_initialisers_fit_the_array() {
    let l = run("DEF REAL FELD1[10,3]=SET(0,,,9,0,1)\n");
    assert_eq!(codes(&l), [] as [&str; 0]);
    assert_eq!(
        ops(&l, "declare")[0]["init"],
        json!([0.0, null, null, 9.0, 0.0, 1.0])
    );
    assert_eq!(errors(&run("DEF REAL FF[2]=(1,2,3)\n")), [OUT_OF_RANGE]);
    assert_eq!(errors(&run("DEF REAL FF=(1,2)\n")), [TYPE_MISMATCH]);
}

#[test]
fn lists_of_values_are_assigned() {
    let l = run("DEF REAL TT[3,4]\nTT[1,0]=SET(1,2,3)\nTT[2,0]=(4,,6)\nTT[0,2]=REP(7,3)\n");
    assert_eq!(codes(&l), [] as [&str; 0]);
    let lists = ops(&l, "assign_list");
    assert_eq!(lists.len(), 3);
    assert_eq!(
        lists[0],
        json!({"kind": "assign_list",
               "target": {"op": "var", "var_kind": "user", "name": "TT", "indices": [
                   {"op": "number", "value": 1.0}, {"op": "number", "value": 0.0}]},
               "values": [1.0, 2.0, 3.0]})
    );
    assert_eq!(lists[1]["values"], json!([4.0, null, 6.0]));
    assert_eq!(lists[2]["values"], json!([]));
    assert_eq!(lists[2]["repeat"], json!({"value": 7.0, "count": 3.0}));
    // Element 9 on, four values: past the 12 elements.
    let l = run("DEF REAL TT[3,4]\nTT[2,1]=SET(1,2,3,4)\n");
    assert_eq!(errors(&l), [OUT_OF_RANGE]);
    assert_eq!(
        only_error(&l),
        "4 values from element 9 on do not fit in `TT`, which has 12 elements"
    );
    assert_eq!(
        errors(&run("DEF REAL TT[3]\nTT[0]=SET(1,\"x\")\n")),
        [TYPE_MISMATCH]
    );
    assert_eq!(errors(&run("DEF REAL SC\nSC=SET(1,2)\n")), [TYPE_MISMATCH]);
    // R parameters take lists too.
    assert_eq!(codes(&run("R[10]=SET(1,2,3)\n")), [] as [&str; 0]);
}

// ---- REDEF and DEFINE ----

#[test]
fn redef_checks_the_name_and_says_what_is_not_built() {
    let l = run("DEF INT AA\nREDEF AA INIRE\n");
    assert_eq!(codes(&l), [NOT_LOWERED]);
    assert!(l.diagnostics[0].message.contains("`REDEF AA INIRE`"));
    let l = run("REDEF QQ INIRE\n");
    assert_eq!(codes(&l), [UNDEFINED, NOT_LOWERED]);
    // Global user data and system variables may be redefined.
    assert_eq!(
        errors(&run_with("REDEF GR_TOOL APW 2\n", &mgud())),
        [] as [&str; 0]
    );
}

#[test]
fn define_makes_the_macro_name_known() {
    let l = run("DEFINE DEPTH AS 5\nR1=DEPTH\n");
    assert_eq!(errors(&l), [] as [&str; 0]);
    assert_eq!(codes(&l), [NOT_LOWERED]);
    assert!(
        l.diagnostics[0]
            .message
            .contains("macro `DEPTH` is not expanded")
    );
    // Macros of definition files too.
    assert_eq!(
        errors(&run_with("M=M_STOP\nR1=M_STOP\n", &mgud())),
        [] as [&str; 0]
    );
}

// ---- robustness ----

#[test]
fn odd_names_and_deep_expressions_do_not_panic() {
    let long = "A".repeat(200);
    let utf8 = "ÄÖÜ_NAME";
    for src in [
        format!("{long}=1\n"),
        format!("R1={utf8}\n"),
        format!("DEF REAL {long}[1,2,3,4]\n{long}[0,0,0,0]=1\n"),
        format!("R1={}1{}\n", "(".repeat(30), ")".repeat(30)),
        "DEF REAL TT[99999999999]\nTT[99999999998]=1\n".to_owned(),
        "DEF INT AA[2]=REP()\n".to_owned(),
    ] {
        let parsed = gcodec_parser::parse_bytes("odd.mpf", src.as_bytes());
        let _ = lower(&parsed.program, &default_profile());
    }
}

/// A name no program can define, used as a variable (`FOR m=…` of an
/// interpreter that creates variables on first use), is
/// `not_a_variable`, never `undefined_variable` with its advice to pass a
/// definition file.
#[test]
fn a_word_of_the_language_used_as_a_variable_is_not_a_missing_definition() {
    for (src, message) in [
        (
            "FOR m=0 TO 2\nENDFOR\n",
            "`m` is an address letter and cannot name a variable",
        ),
        (
            "R1=E\n",
            "`E` is an address letter and cannot name a variable",
        ),
    ] {
        let l = run(src);
        assert_eq!(errors(&l), ["gcodec::lower::not_a_variable"], "{src}");
        assert_eq!(only_error(&l), message, "{src}");
    }
    assert_eq!(errors(&run("R1=UNKNOWN_NAME\n")), [UNDEFINED]);
}
