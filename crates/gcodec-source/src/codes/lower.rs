//! The codes of area `lower`: checking a program against the machine and lowering it to AIL (`gcodec lower`).

super::codes! {
    "lower", "checking a program against the machine and lowering it to AIL (`gcodec lower`)";
    NOT_LOWERED = not_lowered, Warning, "a construct lowering does not translate yet";
    UNKNOWN_G = unknown_g, Error, "a G command the control does not have";
    UNSUPPORTED_G = unsupported_g, Error, "a G command this machine's control lacks";
    COMPUTED_G = computed_g, Error, "a computed G command without its group";
    INVALID_INDIRECT_G = invalid_indirect_g, Error, "an indirect G command with a group or value that does not exist";
    G_GROUP_CONFLICT = g_group_conflict, Error, "two commands of one G group in one block";
    UNSUPPORTED_OFFSET = unsupported_offset, Error, "a settable work offset the machine does not have";
    DUPLICATE_SUPPRESSION = duplicate_suppression, Warning, "more than one frame suppression in one block";
    UNKNOWN_M_FUNCTION = unknown_m_function, Warning, "an M function the machine does not know";
    TOO_MANY_M_FUNCTIONS = too_many_m_functions, Error, "more M functions in one block than the machine allows";
    M_EXTENSION_FORBIDDEN = m_extension_forbidden, Error, "an address extension on an M function that takes none";
    TOOL_SELECTOR_FORM = tool_selector_form, Error, "a tool selection the machine does not accept";
    UNRESOLVED_TOOL = unresolved_tool, Error, "a tool not in the machine's tool table";
    UNKNOWN_ADDRESS = unknown_address, Error, "an address the machine does not have";
    UNKNOWN_SPINDLE = unknown_spindle, Error, "a spindle the machine does not have";
    MODIFIER_NOT_ALLOWED = modifier_not_allowed, Error, "a dimension modifier the address does not take";
    EXTENSION_NOT_ALLOWED = extension_not_allowed, Error, "an address extension the address does not take";
    MISSING_AXIS = missing_axis, Error, "an address that needs an axis and names none";
    ADDRESS_REPEATED = address_repeated, Error, "an address programmed twice in one block";
    RESERVED_ADDRESS = reserved_address, Warning, "a reserved address of the control (`E`)";
    AXIS_NUMBER = axis_number, Warning, "an axis named by a number in brackets";
    REPEATED_AXIS = repeated_axis, Error, "an axis programmed twice in one block";
    MISSING_CIRCLE_DATA = missing_circle_data, Error, "a circle without centre, radius or opening angle";
    DWELL_NOT_ALONE = dwell_not_alone, Error, "`G4` with other words in its block";
    DWELL_WITHOUT_TIME = dwell_without_time, Error, "`G4` without a dwell time";
    FRAME_NOT_ALONE = frame_not_alone, Error, "a frame instruction with other statements in its block";
    BLOCK_TOO_LONG = block_too_long, Error, "a block longer than the control accepts";
    INVALID_VALUE = invalid_value, Error, "a value an address or statement does not take";
    UNKNOWN_SYSTEM_VARIABLE = unknown_system_variable, Error, "a system variable the control does not have";
    SYSTEM_VARIABLE_INDEX = system_variable_index, Error, "a system variable index of the wrong number or kind";
    UNDEFINED_VARIABLE = undefined_variable, Error, "a name that is no variable where it is used";
    DUPLICATE_DEFINITION = duplicate_definition, Error, "a variable defined twice";
    MISPLACED_DEFINITION = misplaced_definition, Error, "a `DEF` after the first executable statement";
    INDEX_COUNT = index_count, Error, "a variable with the wrong number of indices";
    INDEX_OUT_OF_RANGE = index_out_of_range, Error, "a constant index outside the variable's dimension";
    TYPE_MISMATCH = type_mismatch, Error, "a value of a type that cannot be converted to the one needed";
    MISSING_JUMP_TARGET = missing_jump_target, Warning, "a jump or repetition whose target is not in the program";
    DUPLICATE_LABEL = duplicate_label, Advice, "a label defined more than once";
    CASE_VALUE_NOT_CONSTANT = case_value_not_constant, Error, "a `CASE` arm that compares with something other than a constant";
    LABEL_IN_STRUCTURE_BLOCK = label_in_structure_block, Error, "a label on a block with a control-structure keyword";
    SKIPPED_STRUCTURE_BLOCK = skipped_structure_block, Error, "a skip mark on a block with a control-structure keyword";
    TOO_MANY_ARGUMENTS = too_many_arguments, Error, "a call with more arguments than the called program takes";
    ARGUMENT_NOT_VARIABLE = argument_not_variable, Error, "a value passed for a `VAR` parameter, which needs a variable";
    PROC_NOT_FIRST = proc_not_first, Error, "`PROC` after other statements";
}
