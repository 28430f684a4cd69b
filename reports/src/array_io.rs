//! Reading the user's arrays for `splinelab check`: NumPy `.npy` (f64 or
//! f32, read by `ndarray-npy`), JSON (a list of numbers, or a list of equal
//! lists for 2-D), and text columns (whitespace or comma separated, `#`
//! comments). Every failure is a [`CliError::Input`] naming the file.

use crate::error::CliError;
use crate::input::{input_error, max_input_bytes, parse_json, read_bytes, read_text};
use crate::npy_layout::{NpyFloat, validate};
use ndarray::ArrayD;
use ndarray_npy::{ReadNpyError, ReadNpyExt};
use serde_json::Value;
use splinelab_verify::check::UserFormat;
use splinelab_verify::check::interp::{InterpInput, ScipyMode};
use std::path::Path;

/// An array read from a file, widened to f64 (exactly: f32 → f64 is exact).
#[derive(Debug, Clone, PartialEq)]
pub struct UserArray {
    /// The values, C order.
    pub data: Vec<f64>,
    /// The shape (`[n]` for 1-D).
    pub shape: Vec<usize>,
    /// The format the values were stored in (f32 only from an f32 `.npy`).
    pub format: UserFormat,
}

impl UserArray {
    /// The values of a 1-D array (a single row or column counts as 1-D);
    /// refuses anything else, naming the shape.
    pub fn into_1d(self, path: &Path) -> Result<(Vec<f64>, UserFormat), CliError> {
        let long = self.shape.iter().filter(|d| **d != 1).count();
        if long > 1 {
            return Err(input_error(
                path,
                format!("expected a 1-D array, got shape {:?}", self.shape),
            ));
        }
        Ok((self.data, self.format))
    }
}

/// Reads `path` by its extension: `.npy`, `.json`, anything else as text.
pub fn read_array(path: &Path) -> Result<UserArray, CliError> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("npy") => read_npy(path),
        Some("json") => parse_json_array(path, &read_text(path)?),
        _ => parse_text_array(path, &read_text(path)?),
    }
}

/// [`read_array`] then [`UserArray::into_1d`].
pub fn read_1d(path: &Path) -> Result<(Vec<f64>, UserFormat), CliError> {
    read_array(path)?.into_1d(path)
}

/// Reads a `.npy` file whole (within the input limit), checks its header
/// against its length ([`crate::npy_layout::validate`]) and only then lets
/// `ndarray-npy` decode it: either byte order, C or Fortran order.
fn read_npy(path: &Path) -> Result<UserArray, CliError> {
    let bytes = read_bytes(path)?;
    let layout = validate(&bytes).map_err(|why| input_error(path, why))?;
    let why = |e: ReadNpyError| input_error(path, format!("not a valid f64/f32 .npy file: {e}"));
    Ok(match layout.dtype {
        NpyFloat::F64 => from_nd(
            ArrayD::<f64>::read_npy(&bytes[..]).map_err(why)?,
            UserFormat::F64,
        ),
        NpyFloat::F32 => from_nd(
            ArrayD::<f32>::read_npy(&bytes[..])
                .map_err(why)?
                .mapv(f64::from),
            UserFormat::F32,
        ),
    })
}

fn from_nd(a: ArrayD<f64>, format: UserFormat) -> UserArray {
    UserArray {
        shape: a.shape().to_vec(),
        data: a.iter().copied().collect(),
        format,
    }
}

/// Parses a JSON list of numbers, or a list of equal-length lists (2-D).
pub fn parse_json_array(path: &Path, text: &str) -> Result<UserArray, CliError> {
    let v: Value = parse_json(path, text)?;
    let number = |x: &Value, at: String| {
        x.as_f64()
            .ok_or_else(|| input_error(path, format!("element {at} is not a number")))
    };
    let Value::Array(rows) = v else {
        return Err(input_error(path, "expected a JSON array of numbers"));
    };
    if rows.iter().all(Value::is_number) {
        let data = rows
            .iter()
            .enumerate()
            .map(|(i, x)| number(x, i.to_string()))
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(UserArray {
            shape: vec![data.len()],
            data,
            format: UserFormat::F64,
        });
    }
    let mut data = vec![];
    let cols = rows.first().and_then(Value::as_array).map_or(0, Vec::len);
    for (i, row) in rows.iter().enumerate() {
        match row.as_array() {
            Some(r) if r.len() == cols => {
                for (j, x) in r.iter().enumerate() {
                    data.push(number(x, format!("[{i}][{j}]"))?);
                }
            }
            _ => {
                return Err(input_error(
                    path,
                    format!("row {i} is not a list of {cols} numbers (ragged or mixed array)"),
                ));
            }
        }
    }
    Ok(UserArray {
        shape: vec![rows.len(), cols],
        data,
        format: UserFormat::F64,
    })
}

/// Parses text columns: one row per line, numbers separated by whitespace
/// or commas, blank lines and `#` comments skipped; every row has the same
/// number of columns. One column is 1-D, several are 2-D `[rows, cols]`.
pub fn parse_text_array(path: &Path, text: &str) -> Result<UserArray, CliError> {
    let mut data = vec![];
    let mut cols = None;
    let mut rows = 0;
    for (l, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        if *cols.get_or_insert(fields.len()) != fields.len() {
            return Err(input_error(
                path,
                format!(
                    "line {}: {} columns, expected {}",
                    l + 1,
                    fields.len(),
                    cols.unwrap_or(0)
                ),
            ));
        }
        for f in fields {
            let x: f64 = f
                .parse()
                .map_err(|_| input_error(path, format!("line {}: '{f}' is not a number", l + 1)))?;
            data.push(x);
        }
        rows += 1;
    }
    if rows == 0 {
        return Err(input_error(path, "no numbers found"));
    }
    let shape = match cols {
        Some(1) | None => vec![rows],
        Some(c) => vec![rows, c],
    };
    Ok(UserArray {
        data,
        shape,
        format: UserFormat::F64,
    })
}

/// The bytes of a `.npy` file of f64 values with `shape` (C order), written
/// by `ndarray-npy`; write them with [`crate::output::write_atomic`].
pub fn write_npy_f64(shape: &[usize], data: Vec<f64>) -> Result<Vec<u8>, CliError> {
    npy_bytes(shape, data)
}

/// [`write_npy_f64`] for f32 values.
pub fn write_npy_f32(shape: &[usize], data: Vec<f32>) -> Result<Vec<u8>, CliError> {
    npy_bytes(shape, data)
}

fn npy_bytes<A: ndarray_npy::WritableElement>(
    shape: &[usize],
    data: Vec<A>,
) -> Result<Vec<u8>, CliError> {
    use ndarray_npy::WriteNpyExt;
    let a = ArrayD::from_shape_vec(shape.to_vec(), data).map_err(CliError::numerical)?;
    // The header (under 128 bytes for any shape the engine writes) and the values.
    let size = a
        .len()
        .saturating_mul(std::mem::size_of::<A>())
        .saturating_add(128);
    let mut bytes = Vec::new();
    bytes.try_reserve_exact(size).map_err(|_| {
        CliError::numerical(format!("cannot allocate {size} bytes for the .npy output"))
    })?;
    a.write_npy(&mut bytes).map_err(CliError::numerical)?;
    Ok(bytes)
}

/// Refuses what is not a regular file within the input size limit
/// (`SPLINELAB_MAX_INPUT_BYTES`), before reading it.
pub fn check_input_file(path: &Path) -> Result<(), CliError> {
    let meta = std::fs::metadata(path).map_err(|e| input_error(path, e.to_string()))?;
    if !meta.is_file() {
        return Err(input_error(path, "not a regular file"));
    }
    let limit = max_input_bytes()?;
    if meta.len() > limit {
        return Err(input_error(
            path,
            format!(
                "{} bytes, above the input limit of {limit} bytes (raise it with {}=BYTES)",
                meta.len(),
                crate::input::MAX_INPUT_ENV
            ),
        ));
    }
    Ok(())
}

/// Reads an array of samples (any shape, at least one sample per axis,
/// within the input size limit, every sample finite), with the dtype it
/// was stored in.
pub fn read_samples(path: &Path) -> Result<(ArrayD<f64>, UserFormat), CliError> {
    read_samples_as(path, true)
}

/// [`read_samples`], NaN and ±inf samples kept where `finite` is false
/// (missing data, for the engine's `nan_policy`).
pub fn read_samples_as(path: &Path, finite: bool) -> Result<(ArrayD<f64>, UserFormat), CliError> {
    check_input_file(path)?;
    let a = read_array(path)?;
    if a.shape.is_empty() {
        return Err(input_error(
            path,
            "a 0-dimensional array: give at least one axis",
        ));
    }
    if a.data.is_empty() {
        return Err(input_error(
            path,
            format!("no samples (shape {:?})", a.shape),
        ));
    }
    if finite && let Some((i, x)) = a.data.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(input_error(
            path,
            format!(
                "sample {:?} is {x} (every sample must be finite)",
                unravel(i, &a.shape),
            ),
        ));
    }
    let arr = ArrayD::from_shape_vec(a.shape.clone(), a.data)
        .map_err(|e| input_error(path, e.to_string()))?;
    Ok((arr, a.format))
}

/// The multi-index of flat C-order position `i` in `shape`.
pub fn unravel(mut i: usize, shape: &[usize]) -> Vec<usize> {
    let mut idx = vec![0; shape.len()];
    for (k, &n) in idx.iter_mut().zip(shape).rev() {
        *k = i % n.max(1);
        i /= n.max(1);
    }
    idx
}

/// The input of `check interp` from files: samples (1-D or 2-D), scipy's
/// `map_coordinates` coordinates of shape `(dims, count)` (or `(count,)`
/// for 1-D samples), made point-major, and the user's values; a coordinate
/// shape that does not fit the samples is refused, naming its file.
pub fn interp_input(
    samples: &Path,
    coords: &Path,
    (user, format): (Vec<f64>, UserFormat),
    degree: usize,
    mode: impl Into<ScipyMode>,
    max_ulps: Option<f64>,
) -> Result<InterpInput, CliError> {
    let samples_arr = read_array(samples)?;
    let c = read_array(coords)?;
    let dims = samples_arr.shape.len();
    let count = match (dims, c.shape.as_slice()) {
        (1, [k]) => *k,
        (_, [rows, k]) if *rows == dims => *k,
        _ => {
            return Err(input_error(
                coords,
                format!(
                    "expected shape ({dims}, count) for {dims}-D samples, got {:?}",
                    c.shape
                ),
            ));
        }
    };
    // `c.data` holds `dims` rows of `count` (its shape says so); made point-major.
    let rows: Vec<&[f64]> = c.data.chunks_exact(count.max(1)).take(dims).collect();
    Ok(InterpInput {
        samples: samples_arr.data,
        shape: samples_arr.shape,
        points: (0..count)
            .flat_map(|k| rows.iter().filter_map(move |row| row.get(k).copied()))
            .collect(),
        user,
        format,
        degree,
        mode: mode.into(),
        max_ulps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_and_json_arrays() {
        let p = Path::new("x.txt");
        let a = parse_text_array(p, "# c\n1, 2\n3 4\n\n5\t6\n").unwrap();
        assert_eq!(
            (a.shape, a.data),
            (vec![3, 2], vec![1., 2., 3., 4., 5., 6.])
        );
        assert!(parse_text_array(p, "1 2\n3\n").is_err());
        assert!(parse_text_array(p, "1 x\n").is_err());
        let a = parse_json_array(Path::new("x.json"), "[[1,2],[3,4]]").unwrap();
        assert!(a.clone().into_1d(p).is_err());
        assert_eq!(a.shape, vec![2, 2]);
        assert!(parse_json_array(p, "[[1,2],[3]]").is_err());
        assert!(parse_json_array(p, "{\"a\": 1}").is_err());
    }

    #[test]
    fn npy_written_reads_back_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("sl_npy_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.npy");
        let v = vec![0.1, -3.0, 1e-300, 5.0, f64::MAX, 2.5];
        std::fs::write(&p, write_npy_f64(&[2, 3], v.clone()).unwrap()).unwrap();
        let a = read_array(&p).unwrap();
        assert_eq!(
            (a.shape, a.data, a.format),
            (vec![2, 3], v, UserFormat::F64)
        );
        let w = vec![0.1f32, 7.0];
        std::fs::write(&p, write_npy_f32(&[2], w.clone()).unwrap()).unwrap();
        let a = read_array(&p).unwrap();
        let back: Vec<f32> = a.data.iter().map(|&x| x as f32).collect();
        assert_eq!((back, a.format), (w, UserFormat::F32));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
