//! The interpolation conditions a prefilter's coefficients solve, and their
//! solution in any precision: the reference of `check prefilter`.
//!
//! The reference solves `Σ_k β(j − k) D_{e(k)} = s_j`, `j = 0..N−1`, with `β`
//! the centred basis of the family (exact node values from core's
//! [`node_values_exact`]) and `e` the mode's extension of the sequence, as
//! `scipy.ndimage.spline_filter1d` defines it: `mirror` (whole-sample,
//! `s_{−i} = s_i`), `reflect` (half-sample, `s_{−1−i} = s_i`) and
//! `grid-wrap`/`wrap` (periodic); for `nearest` and `grid-constant` the
//! rule scipy's filter actually applies ([`scipy_filter_rule`]). Folding the extension into the matrix keeps
//! it banded (half-bandwidth `q` = number of poles) for the symmetric modes;
//! the periodic one adds corner entries, handled by Sherman–Morrison–Woodbury
//! ([`banded`](super::banded)). No recursive filter, no pole and no
//! truncation horizon enters the reference, so it is independent of the
//! filters being checked. Cost `O(N q²)` per precision.

use super::CheckError;
use super::banded::{Banded, solve_dense, solve_with_corners};
pub use splinelab::ndimage::mode::Mode;
use splinelab::scalar::Real;
use splinelab::sspline::SplineFamily;
use splinelab::sspline::node_values::node_values_exact;

/// Supported degrees (scipy's `order`).
pub const DEGREES: std::ops::RangeInclusive<usize> = 1..=15;

/// The modes whose interpolation conditions are exact boundary rules of
/// scipy's `spline_filter1d` (the extension of the samples is the one the
/// filter's boundary rule assumes).
pub const EXACT_MODES: [Mode; 3] = [Mode::Mirror, Mode::Reflect, Mode::GridWrap];

/// The boundary rule scipy 1.17's `spline_filter1d` applies for `mode`:
/// the [`EXACT_MODES`] are their own; `nearest` is filtered with the
/// half-sample rule of `reflect` and `grid-constant` with the whole-sample
/// rule of `mirror` (scipy's C filter has no rule of its own for them;
/// checked bit for bit on scipy 1.17.1, degrees 2–5, by the committed
/// fixtures). `map_coordinates` pads 12 samples first for these two modes;
/// `spline_filter1d` does not, so its output is the mirror/reflect solution.
pub fn scipy_filter_rule(mode: Mode) -> Mode {
    match mode {
        Mode::Nearest => Mode::Reflect,
        Mode::GridConstant => Mode::Mirror,
        m => m,
    }
}

/// scipy-name parsing for the shared [`Mode`] (kept for the library's
/// callers that wrote `Mode::parse`; `str::parse` does the same).
pub trait ParseMode: Sized {
    /// Parses scipy's names (`wrap` and `grid-mirror` are aliases).
    fn parse(s: &str) -> Option<Self>;
}

impl ParseMode for Mode {
    fn parse(s: &str) -> Option<Mode> {
        s.parse().ok()
    }
}

/// The index in `0..n` that index `k` of the extended sequence copies, for
/// the [`EXACT_MODES`] (`None` for the others).
pub fn extend(mode: Mode, k: i64, n: usize) -> Option<usize> {
    match mode {
        Mode::Mirror | Mode::Reflect | Mode::GridWrap => mode.fold(k, n),
        Mode::Nearest | Mode::GridConstant => None,
    }
}

/// The family of degree `d` (order `d + 1`), validated against [`DEGREES`].
pub fn family_of_degree(degree: usize) -> Result<SplineFamily, CheckError> {
    if !DEGREES.contains(&degree) {
        return Err(CheckError::DegreeOutOfRange {
            degree,
            min: *DEGREES.start(),
            max: *DEGREES.end(),
        });
    }
    Ok(SplineFamily::order(degree as u32 + 1)?)
}

/// Solves the interpolation conditions of `family` with `mode` for the
/// samples `s`, in `T` (see the module documentation); `nearest` and
/// `grid-constant` as scipy's `spline_filter1d` treats them
/// ([`scipy_filter_rule`]). `O(N q²)` for
/// `N > 4q + 4`, a dense LU below that.
pub fn interpolation_coefficients<T: Real>(
    s: &[T],
    family: &SplineFamily,
    mode: Mode,
) -> Result<Vec<T>, CheckError> {
    let mode = scipy_filter_rule(mode);
    let v: Vec<T> = node_values_exact(family)?
        .iter()
        .map(T::from_rational)
        .collect();
    let q = v.len() / 2;
    let n = s.len();
    let entries = (0..n).flat_map(|j| {
        v.iter().enumerate().filter_map(move |(l, b)| {
            let k = extend(mode, j as i64 + l as i64 - q as i64, n)?;
            Some((j, k, b.clone()))
        })
    });
    if n <= 4 * q + 4 {
        return solve_dense(n, &entries.collect::<Vec<_>>(), s.to_vec());
    }
    let mut band = Banded::zeros(n, q);
    let mut corners: Vec<(usize, Vec<(usize, T)>)> = vec![];
    for (i, j, b) in entries {
        if !band.add(i, j, &b) {
            match corners.last_mut() {
                Some((row, list)) if *row == i => list.push((j, b)),
                _ => corners.push((i, vec![(j, b)])),
            }
        }
    }
    solve_with_corners(&band.factor()?, &corners, s.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extensions_follow_scipy() {
        let n = 4;
        let e = |m: Mode| (-3..7).map(|k| extend(m, k, n)).collect::<Vec<_>>();
        // mirror: d c b | a b c d | c b a
        assert_eq!(e(Mode::Mirror), [3, 2, 1, 0, 1, 2, 3, 2, 1, 0].map(Some));
        // reflect: c b a | a b c d | d c b
        assert_eq!(e(Mode::Reflect), [2, 1, 0, 0, 1, 2, 3, 3, 2, 1].map(Some));
        assert_eq!(e(Mode::GridWrap), [1, 2, 3, 0, 1, 2, 3, 0, 1, 2].map(Some));
        // scipy's `wrap` is not grid-wrap (it filters with the mirror rule).
        assert_eq!(Mode::parse("wrap"), None);
        assert_eq!(Mode::parse("grid-mirror"), Some(Mode::Reflect));
    }
}
