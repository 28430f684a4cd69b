//! `splinelab width --emit c|rust|json|npy`: the truncated coefficient table
//! `c_0..c_n` (`c_{−i} = c_i`) as source code or data for production use,
//! each value correctly rounded to the dtype from MPFR (the `production`
//! coefficients: partial fractions with ≥ 128 guard bits, rounded once),
//! with the certified bound, family, tolerance and splinelab version in a
//! comment.
//!
//! Decimal literals carry 17 significant digits for `double` (9 for
//! `float`), which any correctly rounding compiler reads back to the very
//! same value.

use crate::array_io::{write_npy_f32, write_npy_f64};
use crate::error::CliError;
use splinelab::sspline::{CoefficientMethod, SplineFamily, WidthChoice, coefficients};
use std::fmt::Write as _;

/// The output forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Emit {
    /// A C header.
    C,
    /// A Rust module fragment.
    Rust,
    /// A JSON object.
    Json,
    /// A 1-D `.npy` of `c_0..c_n` (needs `--output`).
    Npy,
}

/// Parses `--emit`.
pub fn parse_emit(s: &str) -> Result<Emit, String> {
    match s {
        "c" => Ok(Emit::C),
        "rust" => Ok(Emit::Rust),
        "json" => Ok(Emit::Json),
        "npy" => Ok(Emit::Npy),
        _ => Err(format!(
            "unknown form '{s}' (expected c, rust, json or npy)"
        )),
    }
}

/// The element type of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dtype {
    /// IEEE binary64 (`double`, `f64`).
    F64,
    /// IEEE binary32 (`float`, `f32`).
    F32,
}

/// Parses `--dtype`.
pub fn parse_dtype(s: &str) -> Result<Dtype, String> {
    match s {
        "f64" => Ok(Dtype::F64),
        "f32" => Ok(Dtype::F32),
        _ => Err(format!("unknown dtype '{s}' (expected f64 or f32)")),
    }
}

/// Checks `--name`: a C identifier (letters, digits, `_`, not starting with
/// a digit), at most 64 characters.
pub fn parse_name(s: &str) -> Result<String, String> {
    let ok = !s.is_empty()
        && s.len() <= 64
        && s.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && !s.starts_with(|c: char| c.is_ascii_digit());
    if ok {
        Ok(s.to_string())
    } else {
        Err("a C identifier: ASCII letters, digits and _, not starting with a digit, ≤ 64 characters".into())
    }
}

/// The table with what it certifies.
#[derive(Debug, Clone)]
pub struct Table {
    /// The family.
    pub family: SplineFamily,
    /// The width choice (n, criterion, tolerance, achieved error, bound).
    pub choice: WidthChoice,
    /// The element type.
    pub dtype: Dtype,
    /// `c_0..c_n` as decimal literals (17 or 9 significant digits).
    pub literals: Vec<String>,
    /// `c_0..c_n` rounded to the dtype, widened exactly to f64.
    pub values: Vec<f64>,
}

impl Table {
    /// The table `c_0..c_n` for `choice`, each value rounded once from MPFR.
    pub fn new(
        family: &SplineFamily,
        choice: &WidthChoice,
        dtype: Dtype,
    ) -> Result<Self, CliError> {
        let count = choice.n + 1;
        let method = CoefficientMethod::Production;
        let (values, literals): (Vec<f64>, Vec<String>) = match dtype {
            Dtype::F64 => coefficients::<f64>(family, count, method)
                .map_err(CliError::numerical)?
                .into_iter()
                .map(|c| (c, format!("{c:.16e}")))
                .unzip(),
            Dtype::F32 => coefficients::<f32>(family, count, method)
                .map_err(CliError::numerical)?
                .into_iter()
                .map(|c| (f64::from(c), format!("{c:.8e}")))
                .unzip(),
        };
        Ok(Table {
            family: family.clone(),
            choice: choice.clone(),
            dtype,
            literals,
            values,
        })
    }

    /// The comment lines shared by the C and Rust forms.
    fn provenance(&self) -> Vec<String> {
        let w = &self.choice;
        let fam = match self.family.tension() {
            Some(t) => format!("cubic Beta2 S-spline, tension β2 = {t}"),
            None => format!(
                "S-spline of B-spline order m = {} (degree {})",
                self.family.spline_order(),
                self.family.spline_order() - 1
            ),
        };
        vec![
            format!(
                "Truncated S-spline prefilter c_0..c_n (c_-i = c_i), splinelab {}.",
                env!("CARGO_PKG_VERSION")
            ),
            format!("Family: {fam}."),
            format!(
                "Tolerance {:e} ({} criterion): half-width n = {}, support radius n + m/2 = {} samples.",
                w.tol,
                w.criterion,
                w.n,
                w.n as f64 + self.family.half_support()
            ),
            format!("Achieved {} error {:e}.", w.criterion, w.achieved),
            format!(
                "Certified tail bound sum_{{|i|>n}} |c_i| <= {:e} (guaranteed; rounded up).",
                w.bound
            ),
            format!(
                "Values correctly rounded to {} from MPFR (>= 128 guard bits).",
                match self.dtype {
                    Dtype::F64 => "binary64",
                    Dtype::F32 => "binary32",
                }
            ),
            "Apply: D_k = sum_{|j|<=n} c_|j| s_{k-j}.".into(),
        ]
    }

    /// A C header: `#define PREFIX_HALF_WIDTH n` (the macro upper-cased, as
    /// C macros are, beside the include guard) and
    /// `static const double prefix_coeffs[PREFIX_HALF_WIDTH + 1]`.
    pub fn c_header(&self, prefix: &str) -> String {
        let upper = prefix.to_ascii_uppercase();
        let ty = match self.dtype {
            Dtype::F64 => "double",
            Dtype::F32 => "float",
        };
        let suffix = if self.dtype == Dtype::F32 { "f" } else { "" };
        let mut s = String::from("/*\n");
        for line in self.provenance() {
            let _ = writeln!(s, " * {line}");
        }
        s.push_str(" */\n");
        let _ = writeln!(s, "#ifndef {upper}_SSPLINE_COEFFS_H");
        let _ = writeln!(s, "#define {upper}_SSPLINE_COEFFS_H\n");
        let _ = writeln!(s, "#define {upper}_HALF_WIDTH {}\n", self.choice.n);
        let _ = writeln!(
            s,
            "static const {ty} {prefix}_coeffs[{upper}_HALF_WIDTH + 1] = {{"
        );
        for (i, c) in self.literals.iter().enumerate() {
            let _ = writeln!(s, "    {c}{suffix}, /* c_{i} */");
        }
        s.push_str("};\n\n");
        let _ = writeln!(s, "#endif /* {upper}_SSPLINE_COEFFS_H */");
        s
    }

    /// Rust items: `pub const PREFIX_HALF_WIDTH: usize` and
    /// `pub const PREFIX_COEFFS: [f64; PREFIX_HALF_WIDTH + 1]`.
    pub fn rust_items(&self, prefix: &str) -> String {
        let upper = prefix.to_ascii_uppercase();
        let ty = match self.dtype {
            Dtype::F64 => "f64",
            Dtype::F32 => "f32",
        };
        let mut s = String::new();
        for line in self.provenance() {
            let _ = writeln!(s, "// {line}");
        }
        let _ = writeln!(s, "\n/// Truncation half-width n.");
        let _ = writeln!(
            s,
            "pub const {upper}_HALF_WIDTH: usize = {};",
            self.choice.n
        );
        let _ = writeln!(s, "/// c_0..c_n, c_-i = c_i.");
        let _ = writeln!(
            s,
            "#[allow(clippy::excessive_precision)]\npub const {upper}_COEFFS: [{ty}; {upper}_HALF_WIDTH + 1] = ["
        );
        for (i, c) in self.literals.iter().enumerate() {
            let _ = writeln!(s, "    {c}, // c_{i}");
        }
        s.push_str("];\n");
        s
    }

    /// A JSON object with the values (as numbers, exactly the dtype's
    /// values widened to f64) and the provenance.
    pub fn json(&self) -> serde_json::Value {
        let w = &self.choice;
        serde_json::json!({
            "splinelab_version": env!("CARGO_PKG_VERSION"),
            "order": self.family.spline_order(),
            "tension": self.family.tension().map(|t| t.to_string()),
            "family": self.family.to_string(),
            "tol": w.tol,
            "criterion": w.criterion.name(),
            "half_width": w.n,
            "support_radius_samples": w.n as f64 + self.family.half_support(),
            "achieved": w.achieved,
            "bound": w.bound,
            "dtype": match self.dtype { Dtype::F64 => "f64", Dtype::F32 => "f32" },
            "coeffs": self.values,
        })
    }

    /// The `.npy` bytes of `c_0..c_n` in the dtype.
    pub fn npy(&self) -> Result<Vec<u8>, CliError> {
        let n = self.values.len();
        match self.dtype {
            Dtype::F64 => write_npy_f64(&[n], self.values.clone()),
            Dtype::F32 => write_npy_f32(&[n], self.values.iter().map(|&v| v as f32).collect()),
        }
    }
}
