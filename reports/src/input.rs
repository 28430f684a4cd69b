//! Reading the JSON input files of the commands: one reader, so every
//! command words its failures alike — `cannot read FILE: WHAT at line L
//! column C` for I/O and syntax errors, `cannot read FILE: FIELD …` for
//! content errors.
//!
//! The steps are separate ([`read_text`], then [`parse_json`] or
//! [`parse_object`]) so that tests and fuzzers can feed text directly.

use crate::error::CliError;
use serde::de::DeserializeOwned;
use serde_json::error::Category;
use serde_json::{Map, Value};
use std::path::Path;

/// An input error about `path`.
pub fn input_error(path: &Path, why: impl Into<String>) -> CliError {
    CliError::Input {
        path: path.to_path_buf(),
        why: why.into(),
    }
}

/// Default of the largest input file read: 64 MiB, far above any input
/// the commands' own limits (degree, points, patches) let through.
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 64 << 20;

/// The environment variable that overrides [`DEFAULT_MAX_INPUT_BYTES`].
pub const MAX_INPUT_ENV: &str = "SPLINELAB_MAX_INPUT_BYTES";

/// The input size limit in force: `SPLINELAB_MAX_INPUT_BYTES` if set to a
/// byte count, else [`DEFAULT_MAX_INPUT_BYTES`].
pub fn max_input_bytes() -> Result<u64, CliError> {
    match std::env::var(MAX_INPUT_ENV) {
        Err(_) => Ok(DEFAULT_MAX_INPUT_BYTES),
        Ok(v) => v.trim().parse().map_err(|_| {
            CliError::invalid(
                "SPLINELAB_MAX_INPUT_BYTES",
                "expected a byte count, e.g. 67108864",
            )
        }),
    }
}

/// Reads `path` as UTF-8 text (no `-` for stdin: every command takes a file),
/// within the limits of [`read_bytes`].
pub fn read_text(path: &Path) -> Result<String, CliError> {
    String::from_utf8(read_bytes(path)?).map_err(|e| {
        input_error(
            path,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// Reads the bytes of `path`.
///
/// Only a regular file is read (a FIFO with no writer would block for ever,
/// `/dev/zero` would never end), and at most [`max_input_bytes`]: a larger
/// file is refused with the limit and how to raise it. Nothing larger than
/// the limit is allocated, whatever the file says about itself.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, CliError> {
    use std::io::Read;
    let io = |e: std::io::Error| input_error(path, e.to_string());
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a pipe, device or socket)"
        };
        return Err(input_error(path, format!("{what}: give a regular file")));
    }
    let limit = max_input_bytes()?;
    let too_big = |size: u64| {
        input_error(
            path,
            format!(
                "{size} bytes or more, above the input limit of {limit} bytes \
                 (raise it with {MAX_INPUT_ENV}=BYTES)"
            ),
        )
    };
    if meta.len() > limit {
        return Err(too_big(meta.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(limit.saturating_add(1)).read_to_end(&mut bytes))
        .map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_big(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Parses `text`, the contents of `path`, as a `T` (serde's message names the
/// field, the expected type and the line and column).
pub fn parse_json<T: DeserializeOwned>(path: &Path, text: &str) -> Result<T, CliError> {
    if text.trim().is_empty() {
        return Err(input_error(path, "the file is empty, expected JSON"));
    }
    serde_json::from_str(text).map_err(|e| input_error(path, describe(&e)))
}

/// [`read_text`] then [`parse_json`].
pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T, CliError> {
    parse_json(path, &read_text(path)?)
}

/// Parses `text` as a JSON object whose keys are all in `allowed` (a
/// misspelt optional key is an error, not silently ignored).
pub fn parse_object(
    path: &Path,
    text: &str,
    allowed: &[&str],
) -> Result<Map<String, Value>, CliError> {
    let Value::Object(map) = parse_json::<Value>(path, text)? else {
        return Err(input_error(path, "expected a JSON object {…}"));
    };
    if let Some(key) = map.keys().find(|k| !allowed.contains(&k.as_str())) {
        return Err(input_error(
            path,
            format!("unknown field \"{key}\", expected one of {allowed:?}"),
        ));
    }
    Ok(map)
}

/// The array under `key` of an object from [`parse_object`].
pub fn array_field<'a>(
    path: &Path,
    map: &'a Map<String, Value>,
    key: &str,
) -> Result<&'a [Value], CliError> {
    match map.get(key) {
        Some(Value::Array(a)) => Ok(a),
        Some(other) => Err(input_error(
            path,
            format!("field \"{key}\" must be an array, got {}", kind(other)),
        )),
        None => Err(input_error(
            path,
            format!("missing field \"{key}\" (an array)"),
        )),
    }
}

/// The JSON type of `v`, for messages.
pub fn kind(v: &Value) -> &'static str {
    match v {
        Value::Null => "null",
        Value::Bool(_) => "a boolean",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "an array",
        Value::Object(_) => "an object",
    }
}

/// Most characters of the user's input a message quotes.
pub const QUOTE_CAP: usize = 80;

/// `text` as quoted in a message: at most [`QUOTE_CAP`] characters (the
/// head, an ellipsis with the count left out, the tail), control characters
/// escaped, so a mistyped 4 kB value does not flood the terminal.
pub fn excerpt(text: &str) -> String {
    let shown: Vec<char> = text
        .chars()
        .flat_map(|c| {
            if c.is_control() {
                c.escape_default().collect::<Vec<_>>()
            } else {
                vec![c]
            }
        })
        .collect();
    if shown.len() <= QUOTE_CAP {
        return shown.into_iter().collect();
    }
    let head: String = shown.iter().take(QUOTE_CAP - 20).collect();
    let tail: String = shown.iter().skip(shown.len() - 12).collect();
    format!("{head}…[{} characters]…{tail}", shown.len() - QUOTE_CAP + 8)
}

/// serde's message prefixed by what kind of failure it is, each quoted
/// piece of the input in it (`string "…"`) cut to an [`excerpt`].
fn describe(e: &serde_json::Error) -> String {
    let what = match e.classify() {
        Category::Eof => "truncated JSON",
        Category::Syntax => "malformed JSON",
        Category::Data => "unexpected JSON content",
        Category::Io => "I/O error",
    };
    let message = e.to_string();
    let capped: Vec<String> = message
        .split('"')
        .enumerate()
        .map(|(i, piece)| {
            if i % 2 == 1 {
                excerpt(piece)
            } else {
                piece.to_string()
            }
        })
        .collect();
    format!("{what}: {}", capped.join("\""))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn why(r: Result<impl std::fmt::Debug, CliError>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn each_failure_names_the_file_and_what_is_wrong() {
        let p = Path::new("in.json");
        assert_eq!(
            why(parse_json::<Value>(p, " \n")),
            "cannot read in.json: the file is empty, expected JSON"
        );
        assert_eq!(
            why(parse_json::<Value>(p, "{\"a\": [1,")),
            "cannot read in.json: truncated JSON: EOF while parsing a value at line 1 column 9"
        );
        assert_eq!(
            why(parse_json::<Value>(p, "[1e999]")),
            "cannot read in.json: malformed JSON: number out of range at line 1 column 6"
        );
        assert_eq!(
            why(parse_json::<Vec<f64>>(p, "[1, \"2\"]")),
            "cannot read in.json: unexpected JSON content: invalid type: string \"2\", \
             expected f64 at line 1 column 7"
        );
        assert_eq!(
            why(parse_object(p, "[]", &["a"])),
            "cannot read in.json: expected a JSON object {…}"
        );
        assert_eq!(
            why(parse_object(p, "{\"b\": 1}", &["a"])),
            "cannot read in.json: unknown field \"b\", expected one of [\"a\"]"
        );
        let map = parse_object(p, "{\"a\": 1}", &["a", "c"]).unwrap();
        assert_eq!(
            why(array_field(p, &map, "a")),
            "cannot read in.json: field \"a\" must be an array, got a number"
        );
        assert_eq!(
            why(array_field(p, &map, "c")),
            "cannot read in.json: missing field \"c\" (an array)"
        );
        let long = format!("[\"{}\"]", "word ".repeat(800));
        let message = why(parse_json::<Vec<f64>>(p, &long));
        assert!(message.chars().count() < 200, "{message}");
        assert!(
            message.contains("word word") && message.contains("characters]"),
            "{message}"
        );
        assert!(
            why(read_text(Path::new("/nonexistent/in.json")))
                .starts_with("cannot read /nonexistent/in.json: No such file")
        );
    }
}
