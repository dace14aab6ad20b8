//! The verdicts on the example programs of the peer interpreter (CEAD's
//! nc-gcode-interpreter, the corpus's `peer-cead/`) as issue 20 compares
//! against it: each runs as `scripts/bench-peer/run.sh` runs it, `gcodec
//! run --config scripts/bench-peer/gcodec.toml --no-stop` (the machine an
//! example needs, nothing assumed defined: the peer runs each file on its
//! own too). `gcodec-cli/tests/peer_examples.rs` requires exactly these
//! rejections and a clean run of every other example.

use gcodec_source::{Code, codes};

/// The folder of the corpus that holds the peer's examples.
pub const EXAMPLES: &str = "peer-cead";

/// The configuration the examples run with: the profile of the machine
/// each needs (`edge_cases`, `for_loop`, `repeat` move `A`; `tool` selects
/// a tool by name). Relative to the checkout.
pub const CONFIG: &str = "scripts/bench-peer/gcodec.toml";

/// An example gcodec rejects: the first error of its run (the alarm
/// `block_with_errors` that stops a run at a block with errors aside) and
/// why the control rejects the program too.
#[derive(Debug)]
pub struct Rejection {
    pub file: &'static str,
    pub line: u32,
    pub code: &'static Code,
    pub reason: &'static str,
}

/// The examples gcodec rejects, by file name.
pub const REJECTIONS: &[Rejection] = &[
    Rejection {
        file: "arrays.mpf",
        line: 8,
        code: codes::lower::UNDEFINED_VARIABLE,
        reason: "`FOR nn=…` counts with `nn`, which nothing defines (the peer creates a variable \
                 on its first assignment; the control raises alarm 12550), and the inner loops \
                 count with `m` and `o`, address letters, which name no variable",
    },
    Rejection {
        file: "axis_index_assignment.mpf",
        line: 4,
        code: codes::lower::NOT_A_VARIABLE,
        reason: "`ACC[E]` is the acceleration of the peer's extruder `E`, a reserved address on \
                 the control that no axis may be named (MD20060); the peer rejects the file too",
    },
    Rejection {
        file: "custom_vars.mpf",
        line: 1,
        code: codes::lower::UNDEFINED_VARIABLE,
        reason: "`aa` and `bb` are defined by the peer's `defaults.mpf`, another program; on the \
                 control they would be global user data of a definition file (alarm 12550 \
                 without one); the peer rejects the file on its own too",
    },
    Rejection {
        file: "edge_cases.mpf",
        line: 18,
        code: codes::lower::UNDEFINED_VARIABLE,
        reason: "on the five-axis mill (for its `A B C`), `ELX=…` moves an axis of the peer's \
                 printer that no machine here has (alarm 12550); further on it assigns \
                 `E_MULTIPLIER` and `F_MULTI` without `DEF` and declares `DEPTH` after motion \
                 blocks (alarm 14500)",
    },
    Rejection {
        file: "function_calls.mpf",
        line: 1,
        code: codes::run::CYCLE_ALARM,
        reason: "`SETAL(12345)` raises an alarm, which ends the run on the control; the peer \
                 passes over the call",
    },
    Rejection {
        file: "multiple_m_codes.mpf",
        line: 4,
        code: codes::lower::M_GROUP_CONFLICT,
        reason: "`M3 M4 M5` in one block: three functions of the master spindle's \
                 auxiliary-function group 2 (alarm 14760)",
    },
    Rejection {
        file: "r_param.mpf",
        line: 1,
        code: codes::parse::INVALID_NAME,
        reason: "`DEF REAL R0` declares R parameter 0, which is predefined and no name (a name \
                 begins with two letters or `_`); the rest, `X=R0` and `R0 = 10`, is valid and \
                 runs without that line",
    },
    Rejection {
        file: "simple.mpf",
        line: 2,
        code: codes::lower::MISSING_CIRCLE_DATA,
        reason: "`G2 X3 Z100` gives no centre, radius or opening angle, so the control cannot \
                 build the circle; the next block, `G3 X1 X=3 …`, programs `X` twice (alarm \
                 12010)",
    },
];
