//! The codes of area `parse`: the syntax of a part program (`gcodec parse` and every later stage).

super::codes! {
    "parse", "the syntax of a part program (`gcodec parse` and every later stage)";
    UNEXPECTED_TOKEN = unexpected_token, Error, "a token the grammar does not allow where it stands";
    INVALID_WORD = invalid_word, Error, "a malformed address word";
    INVALID_NAME = invalid_name, Error, "a declared name that is no identifier, or a keyword or address";
    INVALID_VALUE = invalid_value, Error, "an incomplete value, or a list where one value belongs";
    INVALID_NUMBER = invalid_number, Error, "a number or quoted constant that cannot be read";
    UNCLOSED_STRING = unclosed_string, Error, "a string not closed on its line";
    INVALID_OPERATOR = invalid_operator, Error, "an operator of another language (`=<`, `=>`, `!=`)";
    INVALID_CHARACTER = invalid_character, Error, "a character that is no part of the NC language";
    MISSING_SEPARATOR = missing_separator, Error, "a value after `=` touching the next word";
    MISSING_JUMP_TARGET = missing_jump_target, Error, "a jump without a target";
    INVALID_SKIP_LEVEL = invalid_skip_level, Error, "a skip level above 9";
    SEPARATED_SKIP_LEVEL = separated_skip_level, Error, "a blank between the skip mark and its level";
    INVALID_BLOCK_NUMBER = invalid_block_number, Error, "a main-block number that is not a whole number";
    MISPLACED_HEADER = misplaced_header, Error, "a `%` program header elsewhere than on the first line";
    NESTING_TOO_DEEP = nesting_too_deep, Error, "brackets nested more than 64 deep in one block";
    BLOCK_TOO_COMPLEX = block_too_complex, Error, "more than 1000 operators in one block";
    MACRO_EXPANSION = macro_expansion, Error, "a macro that expands without end, or to a block too long";
    UNCLOSED_STRUCTURE = unclosed_structure, Error, "a control structure opened and never closed";
    UNMATCHED_END = unmatched_end, Error, "a structure's closer without its opener, or a second `ELSE`";
    DEEP_NESTING = deep_nesting, Warning, "control structures nested deeper than the control's 16";
}
