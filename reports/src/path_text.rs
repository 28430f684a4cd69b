//! A path as text for messages and JSON.

use std::path::Path;

/// A path as text for messages and JSON: as it is when it is UTF-8, else
/// with each byte that is not part of valid UTF-8 written `\xNN` (serde
/// refuses non-UTF-8 paths, `json!` would panic on them, and a lossy
/// conversion prints U+FFFD and loses which file was meant). Control
/// characters are escaped too, so a name cannot move the terminal's cursor.
pub fn path_text(path: &Path) -> String {
    use std::os::unix::ffi::OsStrExt;
    let mut out = String::new();
    for chunk in path.as_os_str().as_bytes().utf8_chunks() {
        for c in chunk.valid().chars() {
            if c.is_control() {
                out.extend(c.escape_default());
            } else {
                out.push(c);
            }
        }
        for b in chunk.invalid() {
            out.push_str(&format!("\\x{b:02X}"));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_that_are_not_utf8_are_shown_with_escaped_bytes() {
        use std::os::unix::ffi::OsStrExt;
        let p = Path::new(std::ffi::OsStr::from_bytes(b"/tmp/\xff\xfeA\x1b.json"));
        assert_eq!(path_text(p), "/tmp/\\xFF\\xFEA\\u{1b}.json");
        assert_eq!(path_text(Path::new("/tmp/é.json")), "/tmp/é.json");
    }
}
