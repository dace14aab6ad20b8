//! End-to-end tests of how the `gcodec` binary reads files (SPEC §1,
//! §11.8): only regular files, at most the profile's size, a UTF-8
//! byte-order mark dropped, UTF-16 named, and no symbolic link on the
//! search path followed out of it.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

mod common;

use common::{EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec, stderr, stdout};

/// A directory of its own for one test, emptied first.
fn temp_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("gcodec-files-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

fn write(dir: &Path, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.join(name);
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).expect("mkdir");
    }
    std::fs::write(&path, bytes).expect("write");
    path
}

fn mkfifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", path.display());
}

/// Runs `gcodec` with `args`; fails instead of waiting past `limit` (a
/// FIFO read would block forever), killing it.
fn gcodec_within<I, S>(args: I, limit: Duration) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    let mut child = Command::new(env!("CARGO_BIN_EXE_gcodec"))
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("gcodec starts");
    let started = Instant::now();
    while child.try_wait().expect("wait").is_none() {
        if started.elapsed() > limit {
            let _ = child.kill();
            panic!("gcodec still runs after {limit:?}: it blocks on the file");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("output")
}

const LIMIT: Duration = Duration::from_secs(30);

/// Stderr with the renderer's line wrapping undone: one line per
/// diagnostic line, whatever the width of the paths in it.
fn flat_stderr(out: &Output) -> String {
    stderr(out)
        .lines()
        .map(|line| line.trim_start().trim_start_matches('│').trim())
        .collect::<Vec<_>>()
        .join(" ")
}

/// Asserts that `out` exited with `exit` and that its stderr says each
/// of `fragments`; the stderr, unwrapped.
fn assert_reported(out: &Output, exit: i32, fragments: &[&str]) -> String {
    let err = flat_stderr(out);
    assert_eq!(code(out), exit, "{err}");
    for fragment in fragments {
        assert!(err.contains(fragment), "no {fragment:?} in: {err}");
    }
    err
}

/// The built-in profile with `settings` at the start of its `[program]`
/// section, in `dir`.
fn profile_with(dir: &Path, settings: &str) -> PathBuf {
    let builtin = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../profiles/default.toml"),
    )
    .expect("the built-in profile");
    assert!(builtin.contains("\n[program]\n"));
    let text = builtin.replace("\n[program]\n", &format!("\n[program]\n{settings}\n"));
    write(dir, "machine.toml", text)
}

fn args<'a>(words: &'a [&'a str], paths: &'a [&'a Path]) -> Vec<&'a OsStr> {
    let mut all: Vec<&OsStr> = words.iter().map(OsStr::new).collect();
    all.extend(paths.iter().map(|p| p.as_os_str()));
    all
}

#[cfg(unix)]
#[test]
fn a_fifo_or_a_device_given_as_file_is_refused_without_reading_it() {
    let dir = temp_dir("fifo-main");
    let fifo = dir.join("FIFO.MPF");
    mkfifo(&fifo);
    let link = dir.join("ZERO.MPF");
    std::os::unix::fs::symlink("/dev/zero", &link).expect("symlink");
    for file in [fifo.as_path(), Path::new("/dev/zero"), &link] {
        for command in ["parse", "lower", "run"] {
            let out = gcodec_within(args(&[command], &[file]), LIMIT);
            let fragments = ["gcodec::io::not_a_file", "not a regular file"];
            assert_reported(&out, EXIT_USAGE, &fragments);
        }
    }
}

#[test]
fn a_file_larger_than_the_profile_allows_is_refused_before_it_is_read() {
    let dir = temp_dir("too-large");
    let profile = profile_with(&dir, "max_file_size = 64");
    let program = write(&dir, "BIG.MPF", "G1 X1 F100\n".repeat(10));
    let fits = write(&dir, "FITS.MPF", "G1 X1 F100\nM30\n");
    for command in ["lower", "run"] {
        let out = gcodec(args(&[command, "--profile"], &[&profile, &program]));
        let fragments = [
            "gcodec::io::too_large",
            "110 bytes, more than the 64 allowed",
            "max_file_size",
        ];
        assert_reported(&out, EXIT_USAGE, &fragments);
        let out = gcodec(args(&[command, "--profile"], &[&profile, &fits]));
        assert_eq!(code(&out), EXIT_CLEAN, "{command}: {}", stderr(&out));
    }
    // The built-in profile's limit (1 GiB) admits it.
    assert_eq!(code(&gcodec(args(&["parse"], &[&program]))), EXIT_CLEAN);
    // A called program is held to the same limit, at the call.
    let main = write(&dir, "MAIN.MPF", "N10 G1 X1 F100\nN20 BIGSUB\nN30 M30\n");
    write(&dir, "BIGSUB.SPF", "G1 X1 F100\n".repeat(10));
    let out = gcodec(args(&["run", "--profile"], &[&profile, &main]));
    // Labelled at the call.
    let fragments = ["gcodec::io::too_large", "N20 BIGSUB"];
    assert_reported(&out, EXIT_DIAGNOSTICS, &fragments);
}

#[test]
fn a_utf8_byte_order_mark_changes_nothing() {
    let dir = temp_dir("bom");
    // Over a page of lines, so that the streamed run reads several chunks,
    // with an error after the first page and a jump back over the start.
    let mut text = String::from("N10 G1 X1 F100 ; Grüße\r\n");
    for i in 0..1500 {
        text.push_str(&format!("X{i}\r\n"));
    }
    text.push_str("R1=R1+1\r\nIF R1<2 GOTOB N10\r\nG1 X=1+\r\nM30\r\n");
    let plain = write(&dir, "PLAIN.MPF", &text);
    let marked = write(
        &dir,
        // As long a name as `PLAIN.MPF`: the rendered reports wrap alike.
        "MARKD.MPF",
        [b"\xEF\xBB\xBF", text.as_bytes()].concat(),
    );
    for command in [
        &["parse"][..],
        &["parse", "--format", "json"],
        &["lower"],
        &["lower", "--format", "json"],
        &["run"],
        &["run", "--format", "text"],
    ] {
        let without = gcodec(args(command, &[&plain]));
        let with = gcodec(args(command, &[&marked]));
        assert_eq!(code(&with), code(&without), "{command:?}");
        assert_eq!(
            stdout(&with).replace("MARKD", "PLAIN"),
            stdout(&without),
            "{command:?}"
        );
        let err = stderr(&with);
        assert!(!err.contains("invalid_character"), "{command:?}: {err}");
        assert_eq!(
            err.replace("MARKD", "PLAIN"),
            stderr(&without),
            "{command:?}"
        );
    }
    // The error is found where it is, counted from the byte after the mark.
    let out = gcodec(args(&["parse"], &[&marked]));
    assert_reported(&out, EXIT_DIAGNOSTICS, &["MARKD.MPF:1504:"]);
}

#[test]
fn a_utf16_file_is_named_as_such() {
    let dir = temp_dir("utf16");
    let text = "N10 G1 X1 F100\r\nN20 M30\r\n";
    let little: Vec<u8> = text.encode_utf16().flat_map(u16::to_le_bytes).collect();
    let big: Vec<u8> = text.encode_utf16().flat_map(u16::to_be_bytes).collect();
    for (name, bytes, what) in [
        (
            "LE_BOM.MPF",
            [&b"\xFF\xFE"[..], &little].concat(),
            "little-endian, with",
        ),
        (
            "BE_BOM.MPF",
            [&b"\xFE\xFF"[..], &big].concat(),
            "big-endian, with",
        ),
        ("LE.MPF", little.clone(), "little-endian, without"),
    ] {
        let file = write(&dir, name, bytes);
        for command in ["parse", "lower", "run"] {
            let out = gcodec(args(&[command], &[&file]));
            let named = format!("UTF-16 text ({what}");
            let err = assert_reported(&out, EXIT_USAGE, &["gcodec::io::utf16", &named]);
            assert!(!err.contains("invalid_character"), "{err}");
        }
    }
    // A called program, at the call.
    let main = write(&dir, "MAIN.MPF", "N10 WIDE\nN20 M30\n");
    write(&dir, "WIDE.SPF", [&b"\xFF\xFE"[..], &little].concat());
    let out = gcodec(args(&["run"], &[&main]));
    assert_reported(&out, EXIT_DIAGNOSTICS, &["gcodec::io::utf16", "N10 WIDE"]);
}

#[cfg(unix)]
/// A shop's layout: the machine's folder `sp`, with links into a shared
/// cycle folder `shared` and beyond.
struct Shop {
    dir: PathBuf,
    main: PathBuf,
}

#[cfg(unix)]
impl Shop {
    fn new(test: &str, call: &str) -> Self {
        let dir = temp_dir(test);
        let main = write(
            &dir,
            "sp/MAIN.MPF",
            format!("N10 G1 X1 F100\nN20 {call}\nN30 M30\n"),
        );
        // The shared cycle calls NEXT: the machine's own, next to the link.
        write(&dir, "shared/X.SPF", "G1 X2 F100\nNEXT\nM17\n");
        write(&dir, "shared/NEXT.SPF", "MSG(\"the shared NEXT\")\nM17\n");
        write(&dir, "sp/NEXT.SPF", "MSG(\"the machine's NEXT\")\nM17\n");
        std::os::unix::fs::symlink(dir.join("shared/X.SPF"), dir.join("sp/LINKED.SPF"))
            .expect("symlink");
        std::os::unix::fs::symlink("/etc/passwd", dir.join("sp/PASSWD.SPF")).expect("symlink");
        Self { dir, main }
    }

    fn profile(&self, settings: &str) -> PathBuf {
        profile_with(&self.dir, settings)
    }
}

#[cfg(unix)]
#[test]
fn a_link_out_of_the_search_path_is_refused_naming_it() {
    for (call, target) in [("LINKED", "shared/X.SPF"), ("PASSWD", "/etc/passwd")] {
        let shop = Shop::new(&format!("link-{call}"), call);
        let out = gcodec(args(&["run"], &[&shop.main]));
        let link = format!("{call}.SPF`, a symbolic link to");
        // Labelled at the call.
        let at_call = format!("N20 {call}");
        let fragments = [
            "gcodec::io::outside_search_path",
            &link,
            target,
            "link_target_paths",
            &at_call,
        ];
        let err = assert_reported(&out, EXIT_DIAGNOSTICS, &fragments);
        assert!(!stdout(&out).contains("the shared NEXT"), "{call}");
        assert!(!err.contains("root:"), "{err}");
    }
}

#[cfg(unix)]
#[test]
fn a_link_into_the_profiles_link_target_paths_runs_and_calls_from_its_folder() {
    let shop = Shop::new("link-allowed", "LINKED");
    // Relative to the profile's folder.
    let profile = shop.profile("link_target_paths = [\"shared\"]");
    let out = gcodec(args(
        &["run", "--format", "text", "--profile"],
        &[&profile, &shop.main],
    ));
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let trace = stdout(&out);
    assert!(trace.contains("the machine's NEXT"), "{trace}");
    assert!(!trace.contains("the shared NEXT"), "{trace}");
    // The rest of the file system is still out of reach.
    let shop = Shop::new("link-allowed-passwd", "PASSWD");
    let profile = shop.profile("link_target_paths = [\"shared\"]");
    let out = gcodec(args(&["run", "--profile"], &[&profile, &shop.main]));
    assert_reported(&out, EXIT_DIAGNOSTICS, &["gcodec::io::outside_search_path"]);
}

#[cfg(unix)]
#[test]
fn a_fifo_on_the_search_path_is_an_error_at_the_call_not_a_hang() {
    let dir = temp_dir("fifo-call");
    let main = write(&dir, "MAIN.MPF", "N10 G1 X1 F100\nN20 FIFO\nN30 M30\n");
    mkfifo(&dir.join("FIFO.SPF"));
    let out = gcodec_within(args(&["run"], &[&main]), LIMIT);
    // Labelled at the call.
    let fragments = [
        "gcodec::io::not_a_file",
        "a FIFO (named pipe), not a regular file",
        "N20 FIFO",
    ];
    assert_reported(&out, EXIT_DIAGNOSTICS, &fragments);
}

#[cfg(unix)]
#[test]
fn a_called_program_that_cannot_be_read_is_unreadable_not_missing() {
    let dir = temp_dir("unreadable");
    let main = write(&dir, "MAIN.MPF", "N10 G1 X1 F100\nN20 LOST\nN30 M30\n");
    // A link to nothing, and a link to itself: found, not readable.
    std::os::unix::fs::symlink(dir.join("gone"), dir.join("LOST.SPF")).expect("symlink");
    let looped = write(&dir, "LOOPED.MPF", "N10 SELF\nN20 M30\n");
    std::os::unix::fs::symlink("SELF.SPF", dir.join("SELF.SPF")).expect("symlink");
    let mut cases = vec![(main, "LOST"), (looped, "SELF")];
    // A file without read permission, where permissions hold (not for root).
    let locked = write(&dir, "LOCKED.SPF", "M17\n");
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o000)).expect("chmod");
    if std::fs::read(&locked).is_err() {
        cases.push((
            write(&dir, "CALLS_LOCKED.MPF", "N10 LOCKED\nN20 M30\n"),
            "LOCKED",
        ));
    }
    for (main, call) in cases {
        let out = gcodec(args(&["run"], &[&main]));
        let unread = format!("{call}.SPF`, which cannot be read");
        let fragments = ["gcodec::run::program_unreadable", &unread];
        let err = assert_reported(&out, EXIT_DIAGNOSTICS, &fragments);
        assert!(!err.contains("program_not_found"), "{call}: {err}");
    }
}
