//! A long check tells its progress: the files found, then each checked,
//! from the threads that check them.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use gcodec_driver::check::{CheckConfig, Input, Progress, Selection, check_with_progress};

#[derive(Default)]
struct Counted {
    found: AtomicUsize,
    checked: AtomicUsize,
}

impl Progress for Counted {
    fn files_found(&self, files: usize) {
        self.found.fetch_add(files, Ordering::Relaxed);
    }

    fn file_checked(&self) {
        self.checked.fetch_add(1, Ordering::Relaxed);
    }
}

#[test]
fn every_file_found_is_reported_checked_once() {
    let dir = tempfile::tempdir().expect("temp dir");
    for n in 0..25 {
        let text = format!("N10 G0 X{n}\nN20 M30\n");
        std::fs::write(dir.path().join(format!("P{n}.MPF")), text).expect("write");
    }
    let config = CheckConfig::default_in(PathBuf::from(dir.path()));
    let progress = Counted::default();
    let report = check_with_progress(
        &config,
        vec![Input::Path(dir.path().to_path_buf())],
        &Selection::default(),
        &progress,
    )
    .expect("checked");
    assert_eq!(report.files.len(), 25);
    assert_eq!(progress.found.load(Ordering::Relaxed), 25);
    assert_eq!(progress.checked.load(Ordering::Relaxed), 25);
}
