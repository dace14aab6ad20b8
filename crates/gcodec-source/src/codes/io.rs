//! The codes of area `io`: files and output of the command line.

super::codes! {
    "io", "files and output of the command line";
    READ = read, Error, "a file that cannot be read";
    WRITE = write, Error, "output that cannot be written";
}
