//! The user's number format, which decides what one ulp is.

use rug::Float;
use serde::{Deserialize, Serialize};

/// The IEEE format the user's results are stored in: errors are counted in
/// ulps of that format (an f32 result is judged in f32 ulps).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UserFormat {
    /// binary32: 24-bit significand, subnormals down to 2^−149.
    F32,
    /// binary64: 53-bit significand, subnormals down to 2^−1074.
    F64,
}

impl UserFormat {
    /// Significand bits (24 or 53).
    pub fn bits(self) -> u32 {
        match self {
            UserFormat::F32 => 24,
            UserFormat::F64 => 53,
        }
    }

    /// Exponent of the smallest subnormal (−149 or −1074).
    fn min_exp(self) -> i32 {
        match self {
            UserFormat::F32 => -149,
            UserFormat::F64 => -1074,
        }
    }

    /// Decimal digits carried, `bits · log10 2` (7.22 or 15.95).
    pub fn digits(self) -> f64 {
        self.bits() as f64 * std::f64::consts::LOG10_2
    }

    /// `log2` of one ulp of this format at `r`: `e − (bits − 1)` for
    /// `|r| ∈ [2^e, 2^(e+1))`, never below the subnormal spacing. Taken from
    /// the exact exponent of `r`, so it is right for values outside the f64
    /// range and at powers of two.
    pub fn ulp_exp(self, r: &Float) -> i32 {
        let e = match r.get_exp() {
            Some(exp) => exp - 1,
            None => self.min_exp(),
        };
        (e - (self.bits() as i32 - 1)).max(self.min_exp())
    }

    /// `|x − r|` in ulps of this format at `r` (infinite for a non-finite `x`).
    pub fn ulps(self, x: f64, r: &Float) -> f64 {
        if !x.is_finite() || !r.is_finite() {
            return f64::INFINITY;
        }
        let diff = Float::with_val(r.prec().max(64), x - r).abs();
        (diff >> self.ulp_exp(r)).to_f64()
    }

    /// The name used in JSON and tables.
    pub fn name(self) -> &'static str {
        match self {
            UserFormat::F32 => "f32",
            UserFormat::F64 => "f64",
        }
    }
}

impl std::str::FromStr for UserFormat {
    type Err = String;

    /// `"f64"` or `"f32"` (the CLI's `--format`, Python's `format=`).
    fn from_str(s: &str) -> Result<Self, String> {
        [UserFormat::F64, UserFormat::F32]
            .into_iter()
            .find(|f| f.name() == s)
            .ok_or_else(|| format!("unknown format '{s}' (f64, f32)"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_ulp_in_each_format() {
        let r = Float::with_val(200, 1.5);
        assert_eq!(UserFormat::F64.ulps(1.5 + f64::EPSILON, &r), 1.0);
        let x32 = 1.5f32 + f32::EPSILON;
        assert_eq!(UserFormat::F32.ulps(x32 as f64, &r), 1.0);
        // At a power of two the ulp is the one above it.
        let two = Float::with_val(200, 2.0);
        assert_eq!(UserFormat::F64.ulps(2.0 + 2.0 * f64::EPSILON, &two), 1.0);
        assert_eq!(UserFormat::F64.ulps(f64::NAN, &two), f64::INFINITY);
        // Zero reference: the subnormal spacing.
        let zero = Float::with_val(200, 0.0);
        assert_eq!(UserFormat::F64.ulps(f64::from_bits(3), &zero), 3.0);
    }

    #[test]
    fn names_parse_back() {
        for f in [UserFormat::F64, UserFormat::F32] {
            assert_eq!(f.name().parse::<UserFormat>(), Ok(f));
        }
        let e = "f16".parse::<UserFormat>().unwrap_err();
        assert_eq!(e, "unknown format 'f16' (f64, f32)");
    }
}
