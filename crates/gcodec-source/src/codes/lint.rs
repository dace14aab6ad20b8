//! The codes of area `lint`: the rules `gcodec check` adds to what
//! lowering reports, about programs the control accepts but that would
//! surprise on the machine. Lowering and the run never report them.

super::codes! {
    "lint", "the rules of `gcodec check`: programs the control accepts that would surprise on the machine";
    CHANGE_WITHOUT_TOOL = change_without_tool, Warning, scope Paths, "a tool change M function with no tool selected before it";
    TOOL_WITHOUT_EDGE = tool_without_edge, Warning, scope Paths, "a feed motion with a changed tool and no cutting edge";
    COMPENSATION_LEFT_ACTIVE = compensation_left_active, Warning, scope Paths, "tool radius compensation left on at a tool change or at the program end";
    UNREACHABLE_CODE = unreachable_code, Warning, scope Paths, "blocks that no path through the program reaches";
    MISSING_PROGRAM_END = missing_program_end, Warning, scope Paths, "a main program that can run past its last block without `M30` or `M2`";
    SPINDLE_WITHOUT_SPEED = spindle_without_speed, Warning, scope Paths, "a spindle started with no speed `S` set before";
    MOTION_WITHOUT_FEED = motion_without_feed, Warning, scope Paths, "a feed motion with no feed `F` set before";
    UNUSED_LABEL = unused_label, Advice, scope Text, "a label no jump, section or repetition names";
    JUMP_INTO_STRUCTURE = jump_into_structure, Warning, scope Text, "a jump from outside a loop or `IF` into its body";
    DUPLICATE_BLOCK_NUMBER = duplicate_block_number, Warning, scope Text, "a block number given to more than one block";
}
