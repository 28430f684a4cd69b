//! The `p / p + 64` agreement driver (MPFR's own test method): a reference
//! computed in floating point is trusted only where the same computation at
//! 64 more bits agrees with it to far more digits than the user's format
//! carries; otherwise the precision is raised.

use super::CheckError;
use super::format::UserFormat;
use rayon::join;
use rug::Float;
use splinelab::scalar::{Mp, Real};

/// Bits beyond one ulp of the user's format to which `p` and `p + 64` must
/// agree, element by element: the reference's own error is then below
/// `2^−40` ulps of what is reported.
pub const AGREEMENT_GUARD_BITS: i32 = 40;

/// The precision pairs tried, lowest first. Each pair compiles every
/// reference computation twice more (the precision is the type
/// [`Mp<BITS>`](splinelab::scalar::Mp)), a tenth of this crate's code (`cargo llvm-lines`:
/// 2.23 million lines with a pair at 384, 2.01 without). So there is
/// none at 384: the pair at 512 does its work at less than 1.5× the cost
/// (a degree-5 MPFR prefilter of 500² samples: 0.28 CPU-s at 256 bits,
/// 0.41 at 512; issue 38, the first build).
pub const LADDER: [(u32, u32); 5] = [(128, 192), (192, 256), (256, 320), (512, 576), (1024, 1088)];

/// A computation that can be run in any [`Real`] precision.
pub trait Reference: Sync {
    /// The reference values computed in `T`.
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError>;
}

/// A reference certified by agreement.
#[derive(Debug, Clone)]
pub struct Certified {
    /// The values at the higher precision of the pair that agreed.
    pub values: Vec<Float>,
    /// The lower precision `p` of that pair.
    pub low_bits: u32,
    /// `p + 64`, the precision of [`Certified::values`].
    pub bits: u32,
}

/// Runs `r` at `p` and `p + 64` (in parallel) up the [`LADDER`], from the
/// first pair with `p ≥ min_bits`, until every element agrees to
/// [`AGREEMENT_GUARD_BITS`] below one ulp of `format`. Cost: that of `r` at
/// the two precisions per rung tried; an error of `r` stops the ladder.
pub fn certify<R: Reference>(
    r: &R,
    format: UserFormat,
    min_bits: u32,
) -> Result<Certified, CheckError> {
    let mut last = (0, 0);
    for &(lo, hi) in LADDER.iter().filter(|(lo, _)| *lo >= min_bits) {
        last = (lo, hi);
        let (a, b) = match lo {
            128 => pair::<R, Mp<128>, Mp<192>>(r)?,
            192 => pair::<R, Mp<192>, Mp<256>>(r)?,
            256 => pair::<R, Mp<256>, Mp<320>>(r)?,
            512 => pair::<R, Mp<512>, Mp<576>>(r)?,
            _ => pair::<R, Mp<1024>, Mp<1088>>(r)?,
        };
        if agree(&a, &b, format) {
            return Ok(Certified {
                values: b,
                low_bits: lo,
                bits: hi,
            });
        }
    }
    Err(CheckError::NotCertified {
        low: last.0,
        high: last.1,
    })
}

fn pair<R: Reference, A: Real, B: Real>(r: &R) -> Result<(Vec<Float>, Vec<Float>), CheckError> {
    let (a, b) = join(|| r.compute::<A>(), || r.compute::<B>());
    Ok((floats(&a?), floats(&b?)))
}

fn floats<T: Real>(v: &[T]) -> Vec<Float> {
    v.iter().map(Real::to_float).collect()
}

/// Every `|a_i − b_i| ≤ 2^(ulp_exp(b_i) − guard)`, both finite.
fn agree(a: &[Float], b: &[Float], format: UserFormat) -> bool {
    use rayon::prelude::*;
    a.len() == b.len()
        && a.par_iter().zip(b.par_iter()).all(|(x, y)| {
            if !x.is_finite() || !y.is_finite() {
                return false;
            }
            let d = Float::with_val(y.prec(), x - y).abs();
            d.is_zero() || {
                let lim = format.ulp_exp(y) - AGREEMENT_GUARD_BITS;
                d.get_exp().is_some_and(|e| e - 1 < lim)
            }
        })
}
