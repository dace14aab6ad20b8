//! End-to-end tests of `gcodec plot`: where the picture goes, exit codes,
//! diagnostics as `run` reports them, and the README's picture. What is
//! drawn is tested in gcodec-plot.

use std::path::PathBuf;

mod common;

use common::{
    EXIT_CLEAN, EXIT_DIAGNOSTICS, EXIT_USAGE, code, gcodec, gcodec_in, stderr, stdout, temp_file,
};

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

#[test]
fn plot_writes_the_svg_to_the_file_named() {
    let out_file = temp_file("plot-o", "pocket.svg", "");
    let out = gcodec([
        "plot".as_ref(),
        repo().join("examples/pocket_mill.mpf").as_os_str(),
        "-o".as_ref(),
        out_file.as_os_str(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    assert_eq!(stdout(&out), "");
    // The run's summary, as `run` writes it beside jsonl.
    assert!(
        stderr(&out).contains("blocks executed: 81"),
        "{}",
        stderr(&out)
    );
    let svg = std::fs::read_to_string(&out_file).expect("the picture");
    assert!(
        svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""),
        "{svg}"
    );
    assert!(svg.contains("<title>pocket_mill.mpf</title>"));
    assert!(svg.trim_end().ends_with("</svg>"));
}

#[test]
fn without_o_the_svg_goes_to_stdout() {
    let out = gcodec([
        "plot".as_ref(),
        repo().join("examples/pocket_mill.mpf").as_os_str(),
        "--view".as_ref(),
        "iso".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let svg = stdout(&out);
    assert!(svg.starts_with("<svg"), "{svg}");
    assert!(svg.contains("(view iso)"), "{svg}");
}

#[test]
fn a_missing_file_is_exit_2() {
    let out = gcodec(["plot", "no_such_program.mpf"]);
    assert_eq!(code(&out), EXIT_USAGE, "{}", stderr(&out));
    assert_eq!(stdout(&out), "");
}

#[test]
fn an_unknown_view_is_a_usage_error() {
    let out = gcodec([
        "plot".as_ref(),
        repo().join("examples/pocket_mill.mpf").as_os_str(),
        "--view".as_ref(),
        "top".as_ref(),
    ]);
    assert_eq!(code(&out), EXIT_USAGE);
    assert!(
        stderr(&out).contains("`top` is not a view"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn an_alarm_is_reported_as_run_reports_it_and_the_path_up_to_it_drawn() {
    let file = temp_file(
        "plot-alarm",
        "alarm.mpf",
        "N10 G17 G0 X0 Y0\nN20 G1 X10 F100\nN30 G2 X20 Y0 CR=0\nN40 M30\n",
    );
    let dir = file.parent().expect("a folder");
    let plot = gcodec_in(dir, ["plot", "alarm.mpf"]);
    let run = gcodec_in(dir, ["run", "alarm.mpf"]);
    assert_eq!(code(&plot), EXIT_DIAGNOSTICS, "{}", stderr(&plot));
    assert_eq!(code(&run), EXIT_DIAGNOSTICS);
    assert!(
        stderr(&plot).contains("gcodec::run::circle_zero_radius"),
        "{}",
        stderr(&plot)
    );
    assert_eq!(stderr(&plot), stderr(&run));
    assert!(
        stdout(&plot).contains("class=\"feed t0\""),
        "{}",
        stdout(&plot)
    );
}

#[test]
fn a_program_that_does_not_parse_is_exit_1_with_run_s_diagnostics() {
    let file = temp_file("plot-parse", "broken.mpf", "N10 G1 X=\nN20 M30\n");
    let dir = file.parent().expect("a folder");
    let plot = gcodec_in(dir, ["plot", "broken.mpf", "--output-format", "concise"]);
    let run = gcodec_in(dir, ["run", "broken.mpf", "--output-format", "concise"]);
    assert_eq!(code(&plot), EXIT_DIAGNOSTICS, "{}", stderr(&plot));
    assert_eq!(stderr(&plot), stderr(&run));
    assert!(!stderr(&plot).is_empty());
}

/// The README's picture is what its command makes today:
/// `GCODEC_UPDATE_IMAGES=1 cargo test -p gcodec-cli --test plot`
/// regenerates it.
#[test]
fn the_readme_picture_is_current() {
    let checked_in = repo().join("docs/images/pocket_mill.svg");
    let readme = std::fs::read_to_string(repo().join("README.md")).expect("README");
    let command = "gcodec plot examples/pocket_mill.mpf -o docs/images/pocket_mill.svg";
    assert!(readme.contains(command), "the README shows `{command}`");
    assert!(readme.contains("](docs/images/pocket_mill.svg)"));
    let made = temp_file("plot-readme", "pocket_mill.svg", "");
    let out = gcodec_in(
        &repo(),
        [
            "plot".as_ref(),
            "examples/pocket_mill.mpf".as_ref(),
            "-o".as_ref(),
            made.as_os_str(),
        ],
    );
    assert_eq!(code(&out), EXIT_CLEAN, "{}", stderr(&out));
    let made = std::fs::read_to_string(&made).expect("the picture");
    if std::env::var_os("GCODEC_UPDATE_IMAGES").is_some() {
        std::fs::create_dir_all(checked_in.parent().expect("docs/images")).expect("a folder");
        std::fs::write(&checked_in, &made).expect("write the picture");
    }
    let current = std::fs::read_to_string(&checked_in).unwrap_or_default();
    assert!(
        current == made,
        "docs/images/pocket_mill.svg is stale: run \
         `GCODEC_UPDATE_IMAGES=1 cargo test -p gcodec-cli --test plot` and commit it"
    );
}
