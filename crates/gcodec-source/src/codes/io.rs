//! The codes of area `io`: files and output of the command line.

super::codes! {
    "io", "files and output of the command line";
    READ = read, Error, "a file that cannot be read";
    NOT_A_FILE = not_a_file, Error, "a FIFO, a device or a socket where a program's file is read";
    TOO_LARGE = too_large, Error, "a program's file larger than the profile allows";
    UTF16 = utf16, Error, "a program's file in UTF-16";
    OUTSIDE_SEARCH_PATH = outside_search_path, Error, "a symbolic link on the search path to a file outside it";
    WRITE = write, Error, "output that cannot be written";
}
