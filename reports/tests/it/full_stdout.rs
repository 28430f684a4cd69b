//! A failed write to stdout (`> /dev/full`) after the work is done leaves
//! no new output: the folder or files are moved into place only after the
//! summary was printed (README: a failed run leaves no new files).

use serde_json::json;
use std::path::PathBuf;
use std::process::Command;

fn splinelab() -> Command {
    Command::new(env!("CARGO_BIN_EXE_splinelab"))
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("splinelab-full-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_full_stdout_leaves_no_new_compare_folder() {
    let dir = scratch("devfull");
    let base = dir.join("base.json");
    let summary = json!({"figures": [{"name": "s.e", "value": 1e-15, "kind": "accuracy",
        "unit": "relative error", "better": "lower", "tolerance": 1e-16}]});
    std::fs::write(&base, summary.to_string()).unwrap();
    let out_dir = dir.join("out");
    let run = splinelab()
        .args(["compare", "--baseline"])
        .arg(&base)
        .arg("--current")
        .arg(&base)
        .arg("--out")
        .arg(&out_dir)
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&run.stderr).contains("standard output"));
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(left, vec![std::ffi::OsString::from("base.json")]);
}

#[test]
fn a_full_stdout_leaves_no_new_deform_folder_or_file() {
    let dir = scratch("deformfull");
    for json in [false, true] {
        let out_dir = dir.join(format!("out{json}"));
        let run = splinelab()
            .args(["deform", "--example", "--out"])
            .arg(&out_dir)
            .args(if json { &["--json"][..] } else { &[][..] })
            .stdout(std::fs::File::create("/dev/full").unwrap())
            .output()
            .unwrap();
        assert_eq!(
            run.status.code(),
            Some(2),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        assert!(!out_dir.exists(), "deform left {}", out_dir.display());
    }
    // Into an existing folder: no file appears in it.
    let existing = dir.join("existing");
    std::fs::create_dir(&existing).unwrap();
    let run = splinelab()
        .args(["deform", "--example", "--out"])
        .arg(&existing)
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    assert_eq!(std::fs::read_dir(&existing).unwrap().count(), 0);
}
