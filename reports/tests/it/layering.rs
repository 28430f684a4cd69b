//! The crate's layers run one way: command line (`cli`) → report
//! (`report`) → presentation (charts, HTML, array I/O) → verify. No file of
//! the report or presentation layers may name the command line.

use std::path::{Path, PathBuf};

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("readable source folder") {
        let path = entry.expect("directory entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn report_and_presentation_never_import_the_command_line() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = vec![];
    rust_files(&src, &mut files);
    let lower: Vec<&PathBuf> = files
        .iter()
        .filter(|p| {
            !p.starts_with(src.join("cli")) && !p.ends_with("main.rs") && !p.ends_with("lib.rs")
        })
        .collect();
    assert!(
        lower.len() >= 10,
        "found only {} files below the command line",
        lower.len()
    );
    let offenders: Vec<String> = lower
        .iter()
        .filter_map(|p| {
            let text = std::fs::read_to_string(p).expect("readable source");
            text.lines()
                .position(|l| l.contains("crate::cli") || l.contains("super::cli"))
                .map(|i| format!("{}:{}", p.display(), i + 1))
        })
        .collect();
    assert!(
        offenders.is_empty(),
        "the report or presentation layer names the command line at {offenders:?}"
    );
}
