//! The program loader (SPEC §11.x "Subprograms: the search path"): where
//! called programs are found, how names match files, what is cached, and
//! that no name reaches outside the search directories.
//!
//! Fixtures: `tests/fixtures/loader/main` (the calling program `MAIN.MPF`
//! and a few subprograms) and `tests/fixtures/loader/lib`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use gcodec_ail::Op;
use gcodec_driver::Definitions;
use gcodec_driver::loader::*;
use gcodec_driver::{ProgramKind, compile};
use gcodec_exec::event::EventKind;
use gcodec_exec::loader::*;
use gcodec_lang::MotionKind;
use gcodec_profile::Profile;
use gcodec_source::Severity;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/fixtures/loader")
}

fn main_dir() -> PathBuf {
    fixtures().join("main")
}

fn lib_dir() -> PathBuf {
    fixtures().join("lib")
}

/// The calling program's file, in `main`.
fn caller() -> String {
    main_dir().join("MAIN.MPF").display().to_string()
}

fn profile() -> Profile {
    gcodec_profile::builtin().expect("built-in profile")
}

fn loader(search: SearchPath) -> FileLoader {
    FileLoader::new(search, profile(), Definitions::new())
}

fn request<'a>(name: &'a str, caller_file: &'a str) -> LoadRequest<'a> {
    LoadRequest {
        name,
        by_path: name.starts_with('/'),
        external: false,
        caller_file,
    }
}

/// Loads `name` called from `caller_file`; panics when it is not found.
fn load(loader: &mut impl ProgramLoader, name: &str, caller_file: &str) -> Loaded {
    loader
        .load(&request(name, caller_file))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn load_err(loader: &mut impl ProgramLoader, name: &str, caller_file: &str) -> LoadError {
    match loader.load(&request(name, caller_file)) {
        Ok(loaded) => panic!("{name:?} found: {}", loaded.program.file),
        Err(e) => e,
    }
}

/// The file a program came from, relative to the fixtures.
fn found(loaded: &Loaded) -> String {
    let file = Path::new(&*loaded.program.file);
    file.strip_prefix(fixtures())
        .unwrap_or(file)
        .display()
        .to_string()
}

/// The motion kinds of a program, in order.
fn motions(loaded: &Loaded) -> Vec<MotionKind> {
    loaded
        .program
        .whole_instructions()
        .expect("a loaded program is whole")
        .iter()
        .filter_map(|i| match &i.op {
            Op::Motion { motion, .. } => Some(*motion),
            _ => None,
        })
        .collect()
}

fn with_lib() -> SearchPath {
    SearchPath::new().with_dirs([lib_dir()])
}

#[test]
fn a_program_next_to_the_caller_is_found() {
    let mut loader = loader(SearchPath::new());
    let loaded = load(&mut loader, "NEAR", &caller());
    assert_eq!(found(&loaded), "main/Near.SPF");
    assert_eq!(loaded.program.name, "NEAR");
    assert!(!loaded.has_errors);
    assert!(loaded.diagnostics.is_empty(), "{:?}", loaded.diagnostics);
    assert_eq!(
        loaded.program.text(),
        &b"; next to MAIN.MPF\nG1 X1 F100\nM17\n"[..]
    );
    // Not on the search path: only the caller's directory is searched.
    let error = load_err(&mut loader, "FAR", &caller());
    assert_eq!(error.code, "gcodec::run::program_not_found");
    assert_eq!(error.searched, [main_dir()]);
}

#[test]
fn a_program_on_a_later_directory_is_found() {
    let mut loader = loader(with_lib());
    let loaded = load(&mut loader, "FAR", &caller());
    assert_eq!(found(&loaded), "lib/Far.spf");
    assert_eq!(loaded.program.name, "FAR");
    // The instructions name the file as found.
    assert!(
        loaded
            .program
            .whole_instructions()
            .expect("a loaded program is whole")
            .iter()
            .all(|i| i.source.file == loaded.program.file)
    );
}

#[test]
fn the_caller_directory_comes_first_then_the_profile_then_the_command_line() {
    // BOTH is in main and lib.
    let mut profile = profile();
    profile.program.subprogram_paths = vec!["lib".to_owned()];
    // Relative to the profile's file (which need not exist for this).
    let profile_file = fixtures().join("machine.toml");

    // A caller in main: main first, whatever the rest says.
    let search = SearchPath::new()
        .with_profile(&profile, Some(&profile_file))
        .with_dirs([main_dir()]);
    let mut from_main = FileLoader::new(search.clone(), profile.clone(), Definitions::new());
    assert_eq!(
        found(&load(&mut from_main, "BOTH", &caller())),
        "main/BOTH.SPF"
    );

    // A caller elsewhere: the profile's `lib` before `--subprogram-path main`.
    let elsewhere = fixtures().join("nowhere/CALLER.MPF").display().to_string();
    assert_eq!(
        search.for_caller(&elsewhere),
        [fixtures().join("nowhere"), lib_dir(), main_dir()]
    );
    let mut loader = FileLoader::new(search, profile.clone(), Definitions::new());
    assert_eq!(
        found(&load(&mut loader, "BOTH", &elsewhere)),
        "lib/BOTH.SPF"
    );

    // Without the profile's path, the command line's `main`.
    let mut loader = loader_with_dirs([main_dir(), lib_dir()]);
    assert_eq!(
        found(&load(&mut loader, "BOTH", &elsewhere)),
        "main/BOTH.SPF"
    );
    let mut loader = loader_with_dirs([lib_dir(), main_dir()]);
    assert_eq!(
        found(&load(&mut loader, "BOTH", &elsewhere)),
        "lib/BOTH.SPF"
    );
}

fn loader_with_dirs<const N: usize>(dirs: [PathBuf; N]) -> FileLoader {
    loader(SearchPath::new().with_dirs(dirs))
}

#[test]
fn relative_profile_paths_without_a_profile_file_are_against_the_current_directory() {
    let mut profile = profile();
    profile.program.subprogram_paths = vec!["sub".to_owned(), "/abs/dir".to_owned()];
    let search = SearchPath::new().with_profile(&profile, None);
    let dirs: Vec<&Path> = search.dirs().collect();
    assert_eq!(dirs, [Path::new("sub"), Path::new("/abs/dir")]);
    let search = SearchPath::new().with_profile(&profile, Some(Path::new("cfg/m.toml")));
    let dirs: Vec<&Path> = search.dirs().collect();
    assert_eq!(dirs, [Path::new("cfg/sub"), Path::new("/abs/dir")]);
}

#[test]
fn a_directory_met_twice_is_searched_once() {
    let mut loader = loader(SearchPath::new().with_dirs([main_dir(), lib_dir(), main_dir()]));
    let error = load_err(&mut loader, "NOPE", &caller());
    assert_eq!(error.searched, [main_dir(), lib_dir()]);
}

#[test]
fn names_match_files_in_any_case() {
    let mut loader = loader(with_lib());
    let upper = load(&mut loader, "FAR", &caller());
    for name in ["far", "Far", "fAR"] {
        let loaded = load(&mut loader, name, &caller());
        assert!(Arc::ptr_eq(&loaded.program, &upper.program), "{name}");
    }
    // The extension's case does not matter either (`ONLYMAIN.mpf`).
    assert_eq!(
        found(&load(&mut loader, "ONLYMAIN", &caller())),
        "lib/ONLYMAIN.mpf"
    );
}

#[test]
fn an_spf_comes_before_an_mpf_of_the_same_name() {
    let mut loader = loader(with_lib());
    assert_eq!(found(&load(&mut loader, "DUAL", &caller())), "lib/DUAL.SPF");
    // The type asked for explicitly.
    for name in [
        "DUAL_MPF",
        "_N_DUAL_MPF",
        "DUAL.MPF",
        "/_N_MPF_DIR/_N_DUAL_MPF",
    ] {
        assert_eq!(
            found(&load(&mut loader, name, &caller())),
            "lib/DUAL.MPF",
            "{name}"
        );
    }
    for name in ["DUAL_SPF", "_N_DUAL_SPF", "_N_DUAL"] {
        assert_eq!(
            found(&load(&mut loader, name, &caller())),
            "lib/DUAL.SPF",
            "{name}"
        );
    }
    // Only an MPF: found by its name, not as an SPF.
    assert_eq!(
        found(&load(&mut loader, "ONLYMAIN", &caller())),
        "lib/ONLYMAIN.mpf"
    );
    let error = load_err(&mut loader, "_N_ONLYMAIN_SPF", &caller());
    assert_eq!(
        error.help.as_deref(),
        Some(
            "pass the directory holding ONLYMAIN.SPF with --subprogram-path (`gcodec check`: list it in gcodec.toml's `search_paths`)"
        )
    );
}

#[test]
fn the_controls_internal_file_names_hold_programs() {
    let mut loader = loader(with_lib());
    let loaded = load(&mut loader, "INTERN", &caller());
    assert_eq!(found(&loaded), "lib/_N_INTERN_SPF");
    assert_eq!(loaded.program.name, "INTERN");
    assert!(!loaded.has_errors, "{:?}", loaded.diagnostics);
    // Lowered as a subprogram: `X10` moves in the caller's motion mode,
    // which is not known before the call.
    assert_eq!(motions(&loaded), [MotionKind::Modal]);
    // The instructions keep the file's real name.
    assert!(
        loaded
            .program
            .whole_instructions()
            .expect("a loaded program is whole")
            .iter()
            .all(|i| *i.source.file == *loaded.program.file)
    );
    // So is an MPF that is called.
    let main = load(&mut loader, "ONLYMAIN", &caller());
    assert_eq!(motions(&main), [MotionKind::Modal]);
    // Not called (a main program), the same file starts in the profile's
    // reset state, which settles the motion.
    let file = gcodec_source::SourceFile::read(&lib_dir().join("_N_INTERN_SPF")).expect("read");
    let uncalled = compile(
        Arc::new(file),
        ProgramKind::Main,
        &profile(),
        &Definitions::new(),
    )
    .into_loaded("INTERN");
    assert_ne!(motions(&uncalled), [MotionKind::Modal]);
    assert_eq!(motions(&uncalled).len(), 1);
}

#[test]
fn leading_zeros_of_l_numbers_are_significant() {
    let mut loader = loader(with_lib());
    assert_eq!(found(&load(&mut loader, "L7", &caller())), "main/L7.SPF");
    assert_eq!(found(&load(&mut loader, "L007", &caller())), "lib/L007.SPF");
    assert_eq!(load(&mut loader, "L007", &caller()).program.name, "L007");
    let error = load_err(&mut loader, "L07", &caller());
    assert!(error.message.contains("`L07`"), "{}", error.message);
}

#[test]
fn a_pcall_path_is_looked_up_by_its_last_component() {
    let mut loader = loader(with_lib());
    let by_name = load(&mut loader, "INTERN", &caller());
    for path in [
        "/_N_WKS_DIR/_N_W_WPD/_N_INTERN_SPF",
        "/_N_SPF_DIR/_N_INTERN_SPF",
        "/_N_CUS_DIR/INTERN_SPF",
    ] {
        let loaded = load(&mut loader, path, &caller());
        assert!(Arc::ptr_eq(&loaded.program, &by_name.program), "{path}");
    }
    assert_eq!(
        found(&load(&mut loader, "/_N_SPF_DIR/_N_FAR_SPF", &caller())),
        "lib/Far.spf"
    );
    // `CALL "/_N_CUS_DIR/L" << 7 << "_SPF"`.
    assert_eq!(
        found(&load(&mut loader, "/_N_CUS_DIR/L7_SPF", &caller())),
        "main/L7.SPF"
    );
    let error = load_err(&mut loader, "/_N_SPF_DIR/_N_NOPE_SPF", &caller());
    assert_eq!(
        error.message,
        format!(
            "program path `/_N_SPF_DIR/_N_NOPE_SPF` (looked up as `NOPE`, SPF) is not on the \
             search path (searched: {}, {})",
            main_dir().display(),
            lib_dir().display()
        )
    );
}

#[test]
fn not_found_names_every_directory_searched() {
    let missing = fixtures().join("does-not-exist");
    let mut loader = loader(SearchPath::new().with_dirs([lib_dir(), missing.clone()]));
    let error = load_err(&mut loader, "CYCLE81", &caller());
    assert_eq!(error.code, "gcodec::run::program_not_found");
    assert_eq!(error.searched, [main_dir(), lib_dir(), missing.clone()]);
    assert_eq!(
        error.message,
        format!(
            "subprogram `CYCLE81` is not on the search path (searched: {}, {}, {} (does not \
             exist))",
            main_dir().display(),
            lib_dir().display(),
            missing.display()
        )
    );
    assert_eq!(
        error.help.as_deref(),
        Some(
            "pass the directory holding CYCLE81.SPF with --subprogram-path (`gcodec check`: list it in gcodec.toml's `search_paths`)"
        )
    );
    assert_eq!(error.to_string(), error.message);
    let diagnostic = error.to_diagnostic();
    assert_eq!(diagnostic.code, "gcodec::run::program_not_found");
    assert_eq!(diagnostic.severity, Severity::Error);

    // The caller's directory is `.` for a bare file name.
    let error = load_err(&mut loader, "CYCLE81", "MAIN.MPF");
    assert_eq!(error.searched[0], Path::new("."));
}

#[test]
fn no_name_reaches_outside_the_search_path() {
    let mut loader = loader(SearchPath::new());
    let lib_far = lib_dir().join("Far.spf").display().to_string();
    let huge = "A".repeat(1 << 20);
    let long_path = format!("/{}", "_N_X_DIR/".repeat(10_000));
    for name in [
        "../lib/FAR",
        "../lib/Far.spf",
        "..",
        "./NEAR",
        "main/../NEAR",
        "/etc/passwd",
        "/etc/passwd\0",
        lib_far.as_str(),
        "FAR\0",
        "NEAR\0",
        "NEAR\0.SPF",
        "NE\nAR",
        "NEAR ",
        "lib\\FAR",
        "C:\\lib\\FAR",
        "",
        "/",
        "//",
        "Néar",
        huge.as_str(),
        long_path.as_str(),
    ] {
        let error = load_err(&mut loader, name, &caller());
        assert_eq!(error.code, "gcodec::run::program_not_found", "{name:?}");
        assert!(error.message.len() < 600, "{name:?}: {}", error.message);
    }
    // A path inside the search directory is looked up by its last
    // component there, not followed: `lib/FAR` is not `lib/Far.spf`.
    let error = load_err(&mut loader, "lib/FAR", &caller());
    assert_eq!(error.searched, [main_dir()]);
    // Odd callers do not panic either.
    for caller_file in ["", "/", "\0", "../../../../../../", "a/\0/b"] {
        let _ = loader.load(&request("NEAR", caller_file));
    }
}

#[test]
fn a_program_is_read_parsed_and_lowered_once() {
    let mut loader = loader(with_lib());
    let first = load(&mut loader, "FAR", &caller());
    let broken = load(&mut loader, "BROKEN", &caller());
    assert!(!broken.diagnostics.is_empty());
    for _ in 0..1000 {
        let again = load(&mut loader, "FAR", &caller());
        assert!(Arc::ptr_eq(&again.program, &first.program));
        assert!(again.diagnostics.is_empty());
        let again = load(&mut loader, "BROKEN", &caller());
        assert!(Arc::ptr_eq(&again.program, &broken.program));
        assert!(again.diagnostics.is_empty());
        assert!(again.has_errors);
    }
    // Another name and another caller: the same file, the same program.
    let lib_caller = lib_dir().join("X.MPF").display().to_string();
    for (name, from) in [("_N_FAR_SPF", caller()), ("far", lib_caller)] {
        let again = load(&mut loader, name, &from);
        assert!(Arc::ptr_eq(&again.program, &first.program), "{name}");
        assert!(again.diagnostics.is_empty());
    }
}

/// A directory of its own under the system's temporary directory.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("gcodec-loader-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("temporary directory");
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[test]
fn directories_are_listed_once_and_misses_are_cached() {
    let temp = TempDir::new("cache");
    let caller_file = temp.0.join("MAIN.MPF").display().to_string();
    let mut loader = loader(SearchPath::new());
    let miss = load_err(&mut loader, "LATE", &caller_file);
    // The file appears after the first look: the run does not see it.
    std::fs::write(temp.0.join("LATE.SPF"), "M17\n").expect("write");
    for name in ["LATE", "late", "_N_LATE_SPF"] {
        let again = load_err(&mut loader, name, &caller_file);
        assert_eq!(again.searched, miss.searched);
    }
    // A new loader sees it.
    let mut fresh = self::loader(SearchPath::new());
    assert_eq!(load(&mut fresh, "LATE", &caller_file).program.name, "LATE");
}

#[cfg(unix)]
#[test]
fn a_file_that_cannot_be_read_is_an_error_of_its_own() {
    let temp = TempDir::new("unreadable");
    std::os::unix::fs::symlink(temp.0.join("gone"), temp.0.join("LOST.SPF")).expect("symlink");
    // A directory named like a program is no program.
    std::fs::create_dir(temp.0.join("FOLDER.SPF")).expect("mkdir");
    let caller_file = temp.0.join("MAIN.MPF").display().to_string();
    let mut loader = loader(SearchPath::new());
    let error = load_err(&mut loader, "LOST", &caller_file);
    assert_eq!(error.code, "gcodec::run::program_unreadable");
    assert!(error.message.contains("LOST.SPF"), "{}", error.message);
    assert_eq!(error.searched, std::slice::from_ref(&temp.0));
    assert_eq!(load_err(&mut loader, "LOST", &caller_file), error);
    let error = load_err(&mut loader, "FOLDER", &caller_file);
    assert_eq!(error.code, "gcodec::run::program_not_found");
}

/// Writes `text` to `path`, making its directory.
fn write(path: &Path, text: impl AsRef<[u8]>) {
    std::fs::create_dir_all(path.parent().expect("a directory")).expect("mkdir");
    std::fs::write(path, text).expect("write");
}

#[cfg(unix)]
#[test]
fn links_are_followed_only_into_the_search_path_and_the_link_targets() {
    use std::os::unix::fs::symlink;
    let temp = TempDir::new("links");
    let (sp, other, shared) = (
        temp.0.join("sp"),
        temp.0.join("other"),
        temp.0.join("shared"),
    );
    write(&sp.join("REAL.SPF"), "M17\n");
    write(&sp.join("sub/DEEP.SPF"), "M17\n");
    write(&shared.join("X.SPF"), "NEXT\nM17\n");
    for dir in [&sp, &other, &shared] {
        write(&dir.join("NEXT.SPF"), "M17\n");
    }
    symlink(sp.join("REAL.SPF"), sp.join("ALIAS.SPF")).expect("symlink");
    symlink("sub/DEEP.SPF", sp.join("DEEPER.SPF")).expect("symlink");
    symlink("/etc/passwd", sp.join("PASSWD.SPF")).expect("symlink");
    for machine in [&sp, &other] {
        symlink(shared.join("X.SPF"), machine.join("LINKED.SPF")).expect("symlink");
    }
    let from_sp = sp.join("MAIN.MPF").display().to_string();
    let from_other = other.join("MAIN.MPF").display().to_string();

    // Inside the search path (at any depth): followed, named by the link.
    let mut loader = loader(SearchPath::new());
    let alias = load(&mut loader, "ALIAS", &from_sp);
    assert_eq!(Path::new(&*alias.program.file), sp.join("ALIAS.SPF"));
    assert_eq!(alias.program.text(), b"M17\n");
    load(&mut loader, "DEEPER", &from_sp);
    // Outside: refused, naming the link and its target.
    for (name, target) in [
        ("LINKED", shared.join("X.SPF")),
        ("PASSWD", "/etc/passwd".into()),
    ] {
        let error = load_err(&mut loader, name, &from_sp);
        assert_eq!(error.code, "gcodec::io::outside_search_path", "{name}");
        let link = sp.join(format!("{name}.SPF"));
        assert!(
            error.message.contains(&format!("`{}`", link.display())),
            "{}",
            error.message
        );
        assert!(
            error.message.contains(&target.display().to_string()),
            "{}",
            error.message
        );
        assert_eq!(error.searched, std::slice::from_ref(&sp));
        assert_eq!(load_err(&mut loader, name, &from_sp), error, "cached");
    }
    // A target in a later directory of the search path is inside it.
    let mut loader = self::loader(SearchPath::new().with_dirs([&shared]));
    load(&mut loader, "LINKED", &from_sp);

    // The profile's link targets, relative to its file.
    let mut profile = profile();
    profile.program.link_target_paths = vec!["shared".to_owned()];
    let search = SearchPath::new().with_profile(&profile, Some(&temp.0.join("machine.toml")));
    assert_eq!(search.link_dirs().collect::<Vec<_>>(), [shared.as_path()]);
    let mut loader = FileLoader::new(search, profile, Definitions::new());
    assert_eq!(
        load_err(&mut loader, "PASSWD", &from_sp).code,
        "gcodec::io::outside_search_path"
    );
    // Each link is a program of its own, named by the link, and calls
    // from it search the link's directory.
    for machine in [&sp, &other] {
        let caller = if machine == &sp {
            &from_sp
        } else {
            &from_other
        };
        let linked = load(&mut loader, "LINKED", caller);
        assert_eq!(Path::new(&*linked.program.file), machine.join("LINKED.SPF"));
        let next = load(&mut loader, "NEXT", &linked.program.file);
        assert_eq!(Path::new(&*next.program.file), machine.join("NEXT.SPF"));
    }
    let first = load(&mut loader, "LINKED", &from_sp);
    let second = load(&mut loader, "LINKED", &from_other);
    assert!(!Arc::ptr_eq(&first.program, &second.program));
}

#[cfg(unix)]
#[test]
fn special_large_and_utf16_files_are_refused_and_a_byte_order_mark_dropped() {
    let temp = TempDir::new("special");
    let caller_file = temp.0.join("MAIN.MPF").display().to_string();
    let fifo = temp.0.join("FIFO.SPF");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    write(&temp.0.join("BIG.SPF"), "G1 X1 F100\n".repeat(4));
    write(&temp.0.join("WIDE.SPF"), b"\xFF\xFEM\x001\x007\x00\n\x00");
    write(&temp.0.join("MARKED.SPF"), b"\xEF\xBB\xBFG1 X1 F100\nM17\n");
    let toml =
        gcodec_profile::BUILTIN_TOML.replace("\n[program]\n", "\n[program]\nmax_file_size = 40\n");
    let profile = gcodec_profile::load(&toml).expect("the built-in profile, limited");
    assert_eq!(*profile.program.max_file_size.get_ref(), 40);
    // On a thread, so that a FIFO that blocked would fail the test.
    let (sender, receiver) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let mut loader = FileLoader::new(SearchPath::new(), profile, Definitions::new());
        let results: Vec<_> = ["FIFO", "BIG", "WIDE", "MARKED"]
            .into_iter()
            .map(|name| loader.load(&request(name, &caller_file)))
            .collect();
        let _ = sender.send(results);
    });
    let results = receiver
        .recv_timeout(std::time::Duration::from_secs(30))
        .expect("the loader does not block on a FIFO");
    let [fifo, big, wide, marked] = &results[..] else {
        panic!("{results:?}");
    };
    let code = |result: &Result<Loaded, LoadError>| result.as_ref().err().map(|e| e.code);
    assert_eq!(code(fifo), Some(gcodec_source::codes::io::NOT_A_FILE));
    assert_eq!(code(big), Some(gcodec_source::codes::io::TOO_LARGE));
    assert_eq!(code(wide), Some(gcodec_source::codes::io::UTF16));
    let marked = marked.as_ref().expect("a byte-order mark is dropped");
    assert_eq!(marked.program.text(), b"G1 X1 F100\nM17\n");
    assert!(!marked.has_errors, "{:?}", marked.diagnostics);
}

#[test]
fn two_files_for_one_program_are_reported() {
    let mut loader = loader(with_lib());
    let loaded = load(&mut loader, "TWIN", &caller());
    // Byte order: `TWIN.SPF` before `_N_TWIN_SPF`.
    assert_eq!(found(&loaded), "lib/TWIN.SPF");
    let [warning] = loaded.diagnostics.as_slice() else {
        panic!("{:?}", loaded.diagnostics);
    };
    let EventKind::Diagnostic(diagnostic) = &warning.kind else {
        panic!("{warning:?}");
    };
    assert_eq!(diagnostic.code, "gcodec::run::program_ambiguous");
    assert_eq!(diagnostic.severity, Severity::Warning);
    assert!(
        diagnostic.message.contains("TWIN.SPF, _N_TWIN_SPF"),
        "{}",
        diagnostic.message
    );
    assert!(!loaded.has_errors);
}

#[test]
fn a_program_with_errors_is_returned_with_its_diagnostics() {
    let mut loader = loader(with_lib());
    let loaded = load(&mut loader, "BROKEN", &caller());
    assert!(loaded.has_errors);
    let errors: Vec<_> = loaded
        .diagnostics
        .iter()
        .filter_map(|event| match &event.kind {
            EventKind::Diagnostic(d) if d.severity == Severity::Error => Some((d, event)),
            _ => None,
        })
        .collect();
    let [(diagnostic, event)] = errors.as_slice() else {
        panic!("{:?}", loaded.diagnostics);
    };
    assert!(
        diagnostic.code.name().starts_with("gcodec::"),
        "{}",
        diagnostic.code
    );
    assert!(
        diagnostic.message.contains("G999"),
        "{}",
        diagnostic.message
    );
    assert_eq!(event.source.file, loaded.program.file);
    assert_eq!((event.source.line, event.source.col), (3, 4));
    assert_eq!(event.source.level, 0);
    // The rest of the program is there.
    assert!(
        loaded
            .program
            .whole_instructions()
            .is_some_and(|i| !i.is_empty())
    );
}

#[test]
fn the_memory_loader_matches_names_as_the_file_loader_does() {
    let mut loader = MemoryLoader::new(profile(), Definitions::new())
        .with_program("SUB.SPF", "G1 X1 F100\nM17\n")
        .with_program("_N_SUB_MPF", "G1 X2 F100\nM30\n")
        .with_program("L7", "X7\nM17\n")
        .with_program("L007.SPF", "G1 G999 X7\nM17\n");
    let sub = load(&mut loader, "SUB", "MAIN.MPF");
    assert_eq!(&*sub.program.file, "SUB.SPF");
    assert_eq!(sub.program.name, "SUB");
    assert!(sub.diagnostics.is_empty() && !sub.has_errors);
    let again = load(&mut loader, "/_N_SPF_DIR/_N_SUB_SPF", "elsewhere/X.MPF");
    assert!(Arc::ptr_eq(&again.program, &sub.program));
    assert_eq!(
        &*load(&mut loader, "SUB_MPF", "").program.file,
        "_N_SUB_MPF"
    );

    let l7 = load(&mut loader, "L7", "");
    assert_eq!(&*l7.program.file, "L7");
    assert_eq!(motions(&l7), [MotionKind::Modal]);
    let l007 = load(&mut loader, "L007", "");
    assert!(l007.has_errors);
    let event = &l007.diagnostics[0];
    assert_eq!((&*event.source.file, event.source.line), ("L007.SPF", 1));
    let l007 = load(&mut loader, "L007", "");
    assert!(l007.has_errors && l007.diagnostics.is_empty());

    let error = load_err(&mut loader, "L0007", "");
    assert_eq!(error.code, "gcodec::run::program_not_found");
    assert!(error.searched.is_empty());
    let error = load_err(&mut loader, "../SUB", "");
    assert_eq!(error.code, "gcodec::run::program_not_found");

    // A program given again replaces the first.
    loader.insert("SUB.SPF", "G1 X9 F100\nM17\n");
    let replaced = load(&mut loader, "SUB", "");
    assert!(!Arc::ptr_eq(&replaced.program, &sub.program));
}

#[test]
fn a_loader_is_usable_as_a_trait_object() {
    let mut boxed: Box<dyn ProgramLoader> = Box::new(loader(with_lib()));
    assert_eq!(found(&load(&mut boxed, "FAR", &caller())), "lib/Far.spf");
    let by_ref: &mut dyn ProgramLoader = &mut *boxed;
    assert_eq!(
        found(&load(&mut &mut *by_ref, "FAR", &caller())),
        "lib/Far.spf"
    );
}

#[test]
fn the_corpus_cycles_load_from_their_directory() {
    let Some(corpus) = gcodec_testkit::corpus_dir() else {
        return;
    };
    let root = corpus.join("real/PDubovikov+SinumerikLanguage/SinumerikLanguage");
    if !root.is_dir() {
        eprintln!("notice: {} absent; skipped", root.display());
        return;
    }
    // `test/holes2_test.mpf` calls HOLES2 (and CYCLE82 modally); the
    // cycles are in `Sub`, which the user passes with --subprogram-path.
    let caller_file = root.join("test/holes2_test.mpf").display().to_string();
    let mut loader = loader(SearchPath::new().with_dirs([root.join("Sub")]));
    for (name, file) in [
        ("CYCLE81", "CYCLE81.SPF"),
        ("HOLES2", "HOLES2.SPF"),
        ("KANAVKA_SFERA", "KANAVKA_SFERA.spf"),
    ] {
        let loaded = load(&mut loader, name, &caller_file);
        assert_eq!(
            Path::new(&*loaded.program.file),
            root.join("Sub").join(file),
            "{name}"
        );
        assert_eq!(loaded.program.name, name);
        assert!(!loaded.has_errors, "{name}: {:?}", loaded.diagnostics);
        // A cycle opens with its PROC.
        let first = loaded
            .program
            .whole_instructions()
            .expect("a loaded program is whole")
            .iter()
            .find_map(|i| match &i.op {
                Op::Procedure(proc) => Some(proc.name.clone()),
                _ => None,
            });
        assert_eq!(first.as_deref(), Some(name), "{name}");
    }
    let error = load_err(&mut loader, "CYCLE82", &caller_file);
    assert_eq!(error.searched, [root.join("test"), root.join("Sub")]);
}

#[test]
fn extcall_looks_in_the_external_program_path_first_then_on_the_search_path() {
    // BOTH is in main and lib; the external program path is lib.
    let mut profile = profile();
    profile.program.external_program_path = Some("lib".to_owned());
    let search = SearchPath::new().with_profile(&profile, Some(&fixtures().join("machine.toml")));
    assert_eq!(search.for_external_call(&caller()), [lib_dir(), main_dir()]);
    let mut loader = FileLoader::new(search, profile, Definitions::new());
    let caller = caller();
    let external_load = |loader: &mut FileLoader, name: &str| {
        let request = LoadRequest {
            external: true,
            ..request(name, &caller)
        };
        found(
            &loader
                .load(&request)
                .unwrap_or_else(|e| panic!("{name}: {e}")),
        )
    };
    assert_eq!(external_load(&mut loader, "BOTH"), "lib/BOTH.SPF");
    // Not there: the search path, as for any call.
    assert_eq!(external_load(&mut loader, "NEAR"), "main/Near.SPF");
    // A plain call of the same name keeps the caller's directory first.
    assert_eq!(found(&load(&mut loader, "BOTH", &caller)), "main/BOTH.SPF");
}
