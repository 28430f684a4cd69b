//! Writing files without ever leaving one half-written.

use crate::error::CliError;
use std::path::Path;

/// Writes `contents` to `path` atomically: into a temporary file beside it,
/// then renamed over it, so a reader sees the old file or the new one, never
/// a truncated mixture.
pub fn write_atomic(path: &Path, contents: &[u8]) -> Result<(), CliError> {
    let err = |source| CliError::Output {
        path: path.to_path_buf(),
        source,
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.tmp{}", std::process::id()));
    std::fs::write(&tmp, contents).map_err(err)?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        err(e)
    })
}

/// Prints a JSON value to stdout, pretty-printed. A closed pipe (`| head`)
/// is not worth a panic: the reader already has what it wanted.
pub fn print_json(value: &serde_json::Value) {
    use std::io::Write;
    let text = serde_json::to_string_pretty(value).unwrap_or_else(|_| value.to_string());
    let _ = writeln!(std::io::stdout().lock(), "{text}");
}
