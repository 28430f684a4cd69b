//! Error messages stay readable whatever the user gave: a file name that is
//! not UTF-8 is shown with its bytes escaped (`\xFF`), not as U+FFFD, and a
//! mistyped JSON input is quoted in at most about 80 characters.

use std::ffi::OsString;
use std::os::unix::ffi::OsStringExt;
use std::process::Command;

/// Writes `text` to `path`, runs `splinelab flatten --tol 1e-3 --input
/// path`, and returns its exit code and standard error.
fn flatten_file(path: &std::path::Path, text: &str) -> (Option<i32>, String) {
    std::fs::write(path, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_splinelab"))
        .args(["flatten", "--tol", "1e-3", "--input"])
        .arg(path)
        .output()
        .unwrap();
    (out.status.code(), String::from_utf8(out.stderr).unwrap())
}

#[test]
fn a_path_that_is_not_utf8_is_printed_with_escaped_bytes() {
    let dir = std::env::temp_dir().join(format!("sl_msg_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut name = dir.into_os_string().into_vec();
    name.extend(b"/\xff\xfe.json");
    let path = std::path::PathBuf::from(OsString::from_vec(name));
    let (code, stderr) = flatten_file(&path, "{\"points\": [[0, 0], [1, 1]");
    assert_eq!(code, Some(2));
    assert!(
        stderr.contains("/\\xFF\\xFE.json: truncated JSON"),
        "{stderr}"
    );
    assert!(!stderr.contains('\u{fffd}'), "{stderr}");
    std::fs::remove_file(&path).unwrap();
}

#[test]
fn a_mistyped_json_value_is_quoted_in_at_most_about_80_characters() {
    let dir = std::env::temp_dir().join(format!("sl_msg_long_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let long_point = format!("{{\"x\": [{}]}}", vec!["1.25"; 800].join(", "));
    let long_string = format!("\"{}\"", "not a number ".repeat(300));
    for (k, bad) in [long_point, long_string].iter().enumerate() {
        let path = dir.join(format!("p{k}.json"));
        let (code, stderr) = flatten_file(&path, &format!("{{\"points\": [[0, 0], {bad}]}}"));
        assert_eq!(code, Some(2), "{stderr}");
        let quoted = stderr.len() - path.to_str().unwrap().len();
        assert!(quoted < 220, "{} characters: {stderr}", stderr.len());
        assert!(
            stderr.contains("points[1]") && stderr.contains("characters]"),
            "{stderr}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
