//! Checking a `.npy` file's header against its size before anything is
//! allocated from it.
//!
//! `ndarray-npy` trusts the header: it allocates `HEADER_LEN` bytes (up to
//! 4 GiB in format 2.0) to read the header, then `product(shape) × itemsize`
//! bytes for the data, before it finds the file too short. A 200-byte file
//! claiming shape `(10**12,)` would ask for 8 TB and abort the process. So
//! the file is read whole first (it is bounded by the input limit,
//! [`crate::input::max_input_bytes`]), and [`validate`] checks here, on those
//! bytes, that the header is one of ours and that it describes exactly the
//! bytes that follow it; only then does `ndarray-npy` decode them.
//!
//! Format: <https://numpy.org/doc/stable/reference/generated/numpy.lib.format.html>.

use ndarray_npy::npy::header::Header;
use py_literal::Value as PyValue;

/// numpy's own cap on the header dictionary (`max_header_size`, numpy ≥
/// 1.24, 10 000 bytes): a larger header is refused before it is parsed.
pub const MAX_HEADER_BYTES: usize = 10_000;

/// The deepest bracket nesting accepted in a header. A real header nests 2
/// deep (`{'shape': (2, 3)}`); the cap keeps the recursive-descent parser
/// of the dictionary far from the end of the stack whatever the file says.
const MAX_HEADER_NESTING: usize = 8;

/// The element types read: f64 and f32, either byte order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NpyFloat {
    /// `<f8` or `>f8`.
    F64,
    /// `<f4` or `>f4`.
    F32,
}

impl NpyFloat {
    /// Bytes per element.
    pub fn size(self) -> usize {
        match self {
            NpyFloat::F64 => 8,
            NpyFloat::F32 => 4,
        }
    }

    fn name(self) -> &'static str {
        match self {
            NpyFloat::F64 => "float64",
            NpyFloat::F32 => "float32",
        }
    }

    fn from_descr(descr: &str) -> Option<Self> {
        match descr {
            "<f8" | ">f8" => Some(NpyFloat::F64),
            "<f4" | ">f4" => Some(NpyFloat::F32),
            _ => None,
        }
    }
}

/// What a validated header says: the element type and the shape, whose
/// element count times the element size is exactly the data's length.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NpyLayout {
    /// The element type.
    pub dtype: NpyFloat,
    /// The shape.
    pub shape: Vec<usize>,
}

/// Checks `bytes`, a whole `.npy` file, without allocating more than the
/// header's length: the magic string, a known version, a header that fits
/// in the file and in [`MAX_HEADER_BYTES`], a float dtype, and a shape
/// whose size is exactly the bytes after the header. The error says which
/// (one line, printable: the header's own text is shown escaped).
pub fn validate(bytes: &[u8]) -> Result<NpyLayout, String> {
    let (prefix, header_len) = header_span(bytes)?;
    // `header_span` checked that the header lies inside `bytes`.
    let truncated = || format!("truncated .npy header: {header_len} bytes claimed");
    let head = bytes.get(..prefix + header_len).ok_or_else(truncated)?;
    let dict = head.get(prefix..).ok_or_else(truncated)?;
    if nesting(dict) > MAX_HEADER_NESTING {
        return Err(format!(
            "malformed .npy header: brackets nested deeper than {MAX_HEADER_NESTING}"
        ));
    }
    let header = Header::from_reader(&mut &head[..]).map_err(|e| {
        let why = e.to_string();
        let why = why
            .lines()
            .next()
            .unwrap_or("")
            .trim_end_matches([':', ' ']);
        format!(
            "malformed .npy header ({}): {}",
            escaped(why),
            escaped(&String::from_utf8_lossy(dict))
        )
    })?;
    let dtype = match &header.type_descriptor {
        PyValue::String(s) => NpyFloat::from_descr(s),
        _ => None,
    }
    .ok_or_else(|| {
        format!(
            "dtype {} is not supported: expected float64 ('<f8', '>f8') or float32 ('<f4', '>f4')",
            escaped(&header.type_descriptor.to_string())
        )
    })?;
    let body = bytes.len() - prefix - header_len;
    let claimed = header
        .shape
        .iter()
        .try_fold(dtype.size(), |n, &d| n.checked_mul(d));
    if claimed != Some(body) {
        let claim = claimed.map_or("more than 2^64".to_string(), |n| n.to_string());
        return Err(format!(
            "the header claims shape {:?} of {} ({claim} bytes) but {body} bytes follow it \
             (truncated or not the file the header describes)",
            header.shape,
            dtype.name()
        ));
    }
    Ok(NpyLayout {
        dtype,
        shape: header.shape,
    })
}

/// The length of the fixed prefix (magic, version, length field) and of the
/// header dictionary, checked against the file's length.
fn header_span(bytes: &[u8]) -> Result<(usize, usize), String> {
    const MAGIC: &[u8] = b"\x93NUMPY";
    if !bytes.starts_with(MAGIC) {
        return Err("not a .npy file (it does not start with \\x93NUMPY)".into());
    }
    let field = |at: usize, width: usize| -> Result<usize, String> {
        let raw = bytes
            .get(at..at + width)
            .ok_or("truncated .npy header (the file ends inside the fixed prefix)")?;
        Ok(raw
            .iter()
            .rev()
            .fold(0usize, |n, &b| (n << 8) | usize::from(b)))
    };
    let major = field(6, 1)?;
    let width = match major {
        1 => 2,
        2 | 3 => 4,
        v => {
            return Err(format!(
                ".npy format version {v} is not supported (1, 2 or 3)"
            ));
        }
    };
    let header_len = field(8, width)?;
    let prefix = 8 + width;
    if header_len > MAX_HEADER_BYTES {
        return Err(format!(
            "the .npy header claims {header_len} bytes, above numpy's limit of {MAX_HEADER_BYTES}"
        ));
    }
    if prefix + header_len > bytes.len() {
        return Err(format!(
            "truncated .npy header: it claims {header_len} bytes, the file has {} after the prefix",
            bytes.len() - prefix.min(bytes.len())
        ));
    }
    Ok((prefix, header_len))
}

/// The deepest nesting of `(`, `[` and `{` in `text`.
fn nesting(text: &[u8]) -> usize {
    let (mut depth, mut deepest) = (0usize, 0usize);
    for &b in text {
        match b {
            b'(' | b'[' | b'{' => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    deepest
}

/// `text` with control and non-ASCII characters escaped (`\u{e9}`), at
/// most 80 characters of it: a header is the file's content, not ours to
/// print raw.
fn escaped(text: &str) -> String {
    let all: String = text
        .trim_end()
        .chars()
        .map(|c| {
            if c == ' ' || c.is_ascii_graphic() {
                c.to_string()
            } else {
                c.escape_default().to_string()
            }
        })
        .collect();
    if all.chars().count() <= 80 {
        return all;
    }
    let head: String = all.chars().take(77).collect();
    format!("{head}...")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn npy(version: u8, dict: &str, body: &[u8]) -> Vec<u8> {
        let mut out = b"\x93NUMPY".to_vec();
        out.extend([version, 0]);
        let header = format!("{dict}\n");
        if version == 1 {
            out.extend((header.len() as u16).to_le_bytes());
        } else {
            out.extend((header.len() as u32).to_le_bytes());
        }
        out.extend(header.bytes());
        out.extend(body);
        out
    }

    #[test]
    fn a_header_that_fits_its_body_is_accepted() {
        let d = "{'descr': '>f4', 'fortran_order': True, 'shape': (2, 3), }";
        assert_eq!(
            validate(&npy(2, d, &[0; 24])),
            Ok(NpyLayout {
                dtype: NpyFloat::F32,
                shape: vec![2, 3]
            })
        );
    }

    #[test]
    fn a_claim_larger_or_smaller_than_the_body_is_refused_before_allocating() {
        let d = "{'descr': '<f8', 'fortran_order': False, 'shape': (1000000000000,), }";
        let e = validate(&npy(1, d, &[0; 16])).unwrap_err();
        assert!(
            e.contains("8000000000000 bytes") && e.contains("16 bytes"),
            "{e}"
        );
        let d = "{'descr': '<f8', 'fortran_order': False, 'shape': (1,), }";
        assert!(validate(&npy(1, d, &[0; 16])).is_err());
        let d = "{'descr': '<f8', 'fortran_order': False, 'shape': (4294967296, 4294967296, 2), }";
        assert!(validate(&npy(1, d, &[0; 16])).unwrap_err().contains("2^64"));
    }

    #[test]
    fn a_header_length_beyond_the_file_or_numpys_cap_is_refused() {
        let mut f = npy(2, "{}", &[]);
        f[8..12].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(validate(&f).unwrap_err().contains("numpy's limit"));
        let mut f = npy(1, "{}", &[]);
        f[8..10].copy_from_slice(&9000u16.to_le_bytes());
        assert!(validate(&f).unwrap_err().contains("truncated"));
        assert!(
            validate(b"\x93NUMPY\x01")
                .unwrap_err()
                .contains("truncated")
        );
        assert!(validate(b"PK\x03\x04").unwrap_err().contains("not a .npy"));
    }

    #[test]
    fn deep_nesting_and_foreign_dtypes_are_refused_with_the_text_escaped() {
        let deep = format!("{{'descr': {}'<f8'{}}}", "[".repeat(3000), "]".repeat(3000));
        assert!(
            validate(&npy(2, &deep, &[]))
                .unwrap_err()
                .contains("nested")
        );
        let d = "{'descr': '|O', 'fortran_order': False, 'shape': (1,), }";
        assert!(validate(&npy(1, d, &[0; 8])).unwrap_err().contains("'|O'"));
        let d = "{'descr': [('a', '<f8')], 'fortran_order': False, 'shape': (1,), }";
        assert!(
            validate(&npy(1, d, &[0; 8]))
                .unwrap_err()
                .contains("not supported")
        );
        let d = "{'descr': '\u{e9}\u{1b}', 'fortran_order': False, 'shape': (1,), }";
        let e = validate(&npy(3, d, &[0; 8])).unwrap_err();
        assert!(e.is_ascii() && !e.contains('\u{1b}'), "{e}");
    }
}
