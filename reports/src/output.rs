//! Writing files without ever leaving one half-written.

use crate::error::CliError;
use std::path::{Path, PathBuf};

/// Writes `contents` to `path` atomically: into a temporary file beside it,
/// then renamed over it, so a reader sees the old file or the new one, never
/// a truncated mixture.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), CliError> {
    write_all_atomic(&[(path, contents)])
}

/// Writes several files as one step, as far as a file system allows: every
/// temporary file is written first (any failure removes them all and leaves
/// the targets untouched), and only then renamed into place.
pub fn write_all_atomic(files: &[(&Path, &[u8])]) -> Result<(), CliError> {
    let err = |path: &Path, source| CliError::Output {
        path: path.to_path_buf(),
        source,
    };
    // A folder in a target's place is the one thing that makes a rename fail
    // after the writes succeeded: refuse it before writing anything.
    if let Some((path, _)) = files.iter().find(|(path, _)| path.is_dir()) {
        return Err(err(
            path,
            std::io::Error::from(std::io::ErrorKind::IsADirectory),
        ));
    }
    let tmps: Vec<PathBuf> = files.iter().map(|(path, _)| temporary(path)).collect();
    let cleanup = |tmps: &[PathBuf]| tmps.iter().for_each(|t| drop(std::fs::remove_file(t)));
    for ((path, contents), tmp) in files.iter().zip(&tmps) {
        if let Err(e) = std::fs::write(tmp, contents) {
            cleanup(&tmps);
            return Err(err(path, e));
        }
    }
    for (k, ((path, _), tmp)) in files.iter().zip(&tmps).enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            cleanup(&tmps[k..]);
            return Err(err(path, e));
        }
    }
    Ok(())
}

/// `DIR/.NAME.tmpPID`, beside `path`.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp{}", std::process::id()))
}

/// Prints a JSON value to stdout, pretty-printed. A closed pipe (`| head`)
/// is not worth a panic: the reader already has what it wanted.
pub fn print_json(value: &serde_json::Value) {
    use std::io::Write;
    let text = serde_json::to_string_pretty(value).unwrap_or_else(|_| value.to_string());
    let _ = writeln!(std::io::stdout().lock(), "{text}");
}
