//! The codes of area `definitions`: definition files of global user data and macros (`--definitions`).

super::codes! {
    "definitions", "definition files of global user data and macros (`--definitions`)";
    NOT_A_DEFINITION = not_a_definition, Error, "a statement in a definition file that defines nothing";
    DUPLICATE = duplicate, Error, "a name defined twice in the definition files";
}
