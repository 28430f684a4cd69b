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
    PendingFiles::write(files)?.commit()
}

/// Files written beside their targets and not yet moved into place: a
/// command writes its files ([`PendingFiles::write`]), then does whatever
/// else can fail (printing its summary to stdout, which may be `/dev/full`),
/// and only then [`PendingFiles::commit`]s. Dropped uncommitted (an error
/// returned with `?`), the temporaries are removed and no target is touched.
#[derive(Debug)]
pub struct PendingFiles {
    /// (target, temporary) pairs, in order.
    moves: Vec<(PathBuf, PathBuf)>,
    _registered: Vec<crate::interrupt::Registered>,
}

impl PendingFiles {
    /// Writes every temporary; on a failure removes those written and
    /// returns the error naming the target.
    pub fn write(files: &[(&Path, &[u8])]) -> Result<Self, CliError> {
        // A folder in a target's place is the one thing that makes a rename
        // fail after the writes succeeded: refuse it before writing anything.
        if let Some((path, _)) = files.iter().find(|(path, _)| path.is_dir()) {
            return Err(output_error(
                path,
                std::io::Error::from(std::io::ErrorKind::IsADirectory),
            ));
        }
        let mut pending = PendingFiles {
            moves: Vec::with_capacity(files.len()),
            _registered: Vec::with_capacity(files.len()),
        };
        for (path, contents) in files {
            let tmp = temporary(path);
            pending._registered.push(crate::interrupt::register(&tmp));
            pending.moves.push((path.to_path_buf(), tmp.clone()));
            std::fs::write(&tmp, contents).map_err(|e| output_error(path, e))?;
        }
        Ok(pending)
    }

    /// Renames every temporary over its target.
    pub fn commit(mut self) -> Result<(), CliError> {
        while let Some((path, tmp)) = self.moves.first() {
            std::fs::rename(tmp, path).map_err(|e| output_error(path, e))?;
            self.moves.remove(0);
        }
        Ok(())
    }
}

impl Drop for PendingFiles {
    fn drop(&mut self) {
        for (_, tmp) in &self.moves {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

fn output_error(path: &Path, source: std::io::Error) -> CliError {
    CliError::Output {
        path: path.to_path_buf(),
        source,
    }
}

/// `DIR/.NAME.tmpPID`, beside `path`.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.tmp{}", std::process::id()))
}

/// An output folder built beside its target and moved into place whole:
/// `DIR/.NAME.tmpPID` is created empty, the command writes everything into
/// [`StagedDir::path`], and [`StagedDir::commit`] swaps it for the target.
/// Readers of the target see the old folder or the new one, never a mix; a
/// failure or an interrupt (see [`crate::interrupt`]) before the commit
/// removes the temporary folder and leaves the target untouched.
///
/// The target is replaced as a whole, so it must be absent, empty, or an
/// earlier output of splinelab (an `index.html` and only `.html`, `.svg`
/// and `.json` files): anything else (a subfolder such as a `summary.json`
/// that is a directory, a stray file) is refused before any work is done.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    tmp: PathBuf,
    committed: bool,
    _registered: crate::interrupt::Registered,
}

impl StagedDir {
    /// Checks `target` and creates the temporary folder beside it.
    pub fn new(target: &Path) -> Result<Self, CliError> {
        check_replaceable(target)?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let out_err = |source| CliError::Output {
            path: target.to_path_buf(),
            source,
        };
        std::fs::create_dir_all(&parent).map_err(out_err)?;
        let tmp = temporary(target);
        if tmp.exists() {
            let _ = std::fs::remove_dir_all(&tmp);
        }
        let registered = crate::interrupt::register(&tmp);
        std::fs::create_dir(&tmp).map_err(out_err)?;
        Ok(StagedDir {
            target: target.to_path_buf(),
            tmp,
            committed: false,
            _registered: registered,
        })
    }

    /// The folder to write into.
    pub fn path(&self) -> &Path {
        &self.tmp
    }

    /// Moves the finished folder into place (replacing an earlier output)
    /// and returns the target.
    pub fn commit(mut self) -> Result<PathBuf, CliError> {
        let err = |source| CliError::Output {
            path: self.target.clone(),
            source,
        };
        // The interrupt handler waits on this lock: the swap is not cut short.
        let _hold = crate::interrupt::pending();
        check_replaceable(&self.target)?;
        let mut old = self.tmp.clone().into_os_string();
        old.push(".old");
        let old = PathBuf::from(old);
        let had_old = self.target.exists();
        if had_old {
            std::fs::rename(&self.target, &old).map_err(err)?;
        }
        if let Err(e) = std::fs::rename(&self.tmp, &self.target) {
            if had_old {
                let _ = std::fs::rename(&old, &self.target);
            }
            return Err(err(e));
        }
        self.committed = true;
        if had_old {
            let _ = std::fs::remove_dir_all(&old);
        }
        Ok(self.target.clone())
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.tmp);
        }
    }
}

/// Files an output folder may hold to be replaced whole.
const REPLACEABLE: [&str; 3] = ["html", "svg", "json"];

/// Refuses a target that is not absent, empty or an earlier output.
pub fn check_replaceable(target: &Path) -> Result<(), CliError> {
    let refuse = |why: String| CliError::Output {
        path: target.to_path_buf(),
        source: std::io::Error::other(why),
    };
    let meta = match std::fs::symlink_metadata(target) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(refuse(e.to_string())),
        Ok(m) => m,
    };
    if !meta.is_dir() {
        return Err(refuse("exists and is not a folder".into()));
    }
    let entries = std::fs::read_dir(target)
        .and_then(|d| d.collect::<Result<Vec<_>, _>>())
        .map_err(|e| refuse(e.to_string()))?;
    if entries.is_empty() {
        return Ok(());
    }
    if !entries.iter().any(|e| e.file_name() == "index.html") {
        return Err(refuse(
            "is a non-empty folder that is not an earlier splinelab output (no index.html); \
             it would be replaced whole: choose a new or empty folder"
                .into(),
        ));
    }
    for e in &entries {
        let name = e.file_name();
        let is_file = e.file_type().map(|t| t.is_file()).unwrap_or(false);
        let ext_ok = Path::new(&name)
            .extension()
            .and_then(|x| x.to_str())
            .is_some_and(|x| REPLACEABLE.contains(&x));
        if !is_file || !ext_ok {
            return Err(refuse(format!(
                "holds {}, which is not a file splinelab writes ({}); the folder would be \
                 replaced whole: remove it or choose another folder",
                name.to_string_lossy(),
                if is_file {
                    "unexpected extension"
                } else {
                    "not a regular file"
                }
            )));
        }
    }
    Ok(())
}

/// A file name stem made from `name` (a figure or study name): ASCII
/// letters, digits, `-` and `_` kept, everything else (`/`, NUL, dots,
/// non-ASCII) replaced by `_`, at most 64 characters.
pub fn safe_stem(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .take(64)
        .collect();
    if s.is_empty() { "_".into() } else { s }
}

/// Appends one formatted line to a `String` of command output (which is then
/// written by [`emit`]): `outln!(buf, "x = {x}")`. Writing to a `String`
/// cannot fail, so commands build their whole output first.
#[macro_export]
macro_rules! outln {
    ($buf:expr) => { $buf.push('\n') };
    ($buf:expr, $($arg:tt)*) => {{
        $buf.push_str(&format!($($arg)*));
        $buf.push('\n');
    }};
}

/// Writes `text` to stdout and flushes it. Every command's output goes
/// through here, never through `println!` (which panics on a failed write):
/// a closed pipe (`| head -1`) is [`CliError::ClosedPipe`], which ends the
/// program quietly as Unix tools do; any other failure (`> /dev/full`) is
/// [`CliError::Stdout`], an error message and a non-zero exit.
pub fn emit(text: &str) -> Result<(), CliError> {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(stdout_error)
}

/// Classifies a failed write to stdout.
pub fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::ClosedPipe
    } else {
        CliError::Stdout(e)
    }
}

/// Writes a line to stderr; a failure there has nowhere to be reported, so
/// it is ignored (`eprintln!` would panic).
pub fn note(line: &str) {
    use std::io::Write;
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// Longest run of non-blank characters an error message echoes in full.
pub const ECHO_CAP: usize = 80;

/// Shortens every run of more than [`ECHO_CAP`] non-blank characters in a
/// message (a 1 MB key, a 100,000-digit number echoed back) to its head and
/// tail with the count of what was left out.
pub fn cap_echo(message: &str) -> String {
    let mut out = String::with_capacity(message.len().min(4096));
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let n = word.chars().count();
        if n > ECHO_CAP {
            let head: String = word.chars().take(40).collect();
            let tail: String = word.chars().skip(n.saturating_sub(16)).collect();
            out.push_str(&format!(
                "{head}…[{} characters omitted]…{tail}",
                n.saturating_sub(56)
            ));
        } else {
            out.push_str(word);
        }
        word.clear();
    };
    for c in message.chars() {
        if c.is_whitespace() {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// Writes a JSON value to stdout, pretty-printed, through [`emit`].
pub fn print_json(value: &serde_json::Value) -> Result<(), CliError> {
    let text = serde_json::to_string_pretty(value).map_err(CliError::numerical)?;
    emit(&format!("{text}\n"))
}
