//! The predefined functions the simulation does not evaluate: what each
//! returns on the control, for the error that a value is needed
//! ([`codes::run::NOT_SIMULATED`]).

use gcodec_lang::functions::Function;
use gcodec_source::codes;

use crate::value::RunError;

/// The error for a call of `function`, which the simulation cannot
/// answer: it names what the control would return. `None` for a function
/// the evaluator or the runtime computes.
pub(super) fn not_simulated(function: Function) -> Option<RunError> {
    would_return(function).map(|returns| returning(function, returns))
}

/// What `ISFILE` returns, where the simulation cannot tell.
pub(super) const ISFILE_RETURNS: &str = "whether the file exists in the control's file system";

/// The error that `function`, which returns `returns` on the control, is
/// not simulated.
pub(super) fn returning(function: Function, returns: &str) -> RunError {
    RunError::new(
        codes::run::NOT_SIMULATED,
        format!(
            "`{}` is not simulated: on the control it returns {returns}",
            function.name()
        ),
    )
    .with_help("the simulation has no value for it; give the program the value it expects another way, e.g. in an R parameter set at the start")
}

/// What `function` returns on the control, if the simulation does not
/// compute it.
fn would_return(function: Function) -> Option<&'static str> {
    use Function as F;
    Some(match function {
        F::Addframe => "the status of adding a measured frame to the frame chain",
        F::Axtospi => "the spindle number of an axis",
        F::Calcdat => "whether a circle's centre and radius could be computed from points",
        F::Calcposi => "the status of checking a travel against the software limits",
        F::Checksum => "the checksum of a global variable array",
        F::Chkdm => "the status of checking D numbers in a magazine for uniqueness",
        F::Chkdno => "whether D numbers are unique across tools",
        F::Collpair => "the state of a collision pair of the protection model",
        F::Corrtc => "the status of correcting a tool carrier",
        F::Corrtrafo => "the status of correcting a transformation's data",
        F::Crpl | F::Crots => "a frame of a rotation in the plane or of solid angles",
        F::Ctab | F::Ctabinv => "a value of a curve table (leading or following axis)",
        F::Ctabexists
        | F::Ctabfno
        | F::Ctabfpol
        | F::Ctabfseg
        | F::Ctabid
        | F::Ctabislock
        | F::Ctabmemtyp
        | F::Ctabmpol
        | F::Ctabmseg
        | F::Ctabno
        | F::Ctabnomem
        | F::Ctabperiod
        | F::Ctabpol
        | F::Ctabpolid
        | F::Ctabseg
        | F::Ctabsegid => "a number of the curve tables' memory or of a curve table",
        F::Ctabsev
        | F::Ctabssv
        | F::Ctabtep
        | F::Ctabtev
        | F::Ctabtmax
        | F::Ctabtmin
        | F::Ctabtsp
        | F::Ctabtsv => "a start or end value of a curve table or of one of its segments",
        F::Deldl | F::Delmlowner | F::Delmlres | F::Delobj | F::Deltoolenv => {
            "the status of deleting tool or magazine data"
        }
        F::Getactt | F::Getacttd => "the T number of the active tool of a tool group",
        F::Getdno | F::Setdno => {
            "a D number of a tool's cutting edge, or the status of setting one"
        }
        F::Gettcor | F::Settcor => "the status of reading or setting tool lengths and offsets",
        F::Gettenv | F::Toolenv => "the status of reading or saving a tool environment",
        F::Getvarap | F::Getvardft | F::Getvardim | F::Getvarlim | F::Getvarphu | F::Getvartyp => {
            "an attribute of a variable (access right, default, dimension, limit, unit or type)"
        }
        F::Gp => "a position with its attributes, for indirect programming",
        F::Intersec => "whether two contour elements intersect, and where",
        F::Isfile => ISFILE_RETURNS,
        F::Lentoax => "the tool lengths as the axes see them",
        F::Meaframe => "a frame computed from measured points",
        F::Measure => "the result of a measurement",
        F::Modaxval => "the modulo position of a rotary axis",
        F::Nametoint => "the system variable index of a name",
        F::Newmt | F::Newt => "the T number of a tool it creates",
        F::Orisolh => "the orientation of a solution for the tool",
        F::Pm | F::Pr => "a feed per minute or per revolution for a positioning axis",
        F::Posrange => "whether an axis is within a window around a position",
        F::Protd => "the distance between two protection areas",
        F::Sirelay => "the status of the safe relay function",
        F::Spi => "the axis of a spindle number",
        F::Stringis => "what a string is in the NC language (a keyword, a variable, a number, …)",
        F::Toolgnt => "the number of tools of a tool group",
        F::Toolgt => "the T number of a tool of a tool group",
        _ => return None,
    })
}
