//! `interp`: a user's interpolated values of 1-D or 2-D samples at query
//! points, in the convention of `scipy.ndimage.map_coordinates` (prefilter
//! on, `order` = degree), against a reference built from the exact inputs.
//!
//! The reference is `f(x) = Σ_i D_{e(i)} Π_a β(x_a + P − i_a)`:
//! - `D` solves the interpolation conditions along every axis in turn with
//!   check's own banded solve ([`interpolation_coefficients`]; the tensor
//!   product of the 1-D solutions is the N-D solution), in MPFR;
//! - `e` extends the coefficient grid with the mode's symmetry (the spline of
//!   a symmetric or periodic extension has that symmetry, so evaluating it at
//!   the unfolded point equals scipy's folding of the point, exactly);
//! - `β(t) = (1/d!) Σ_{k=0}^{d+1} (−1)^k C(d+1, k) (t + (d+1)/2 − k)₊^d`, the
//!   centred B-spline by its truncated-power formula (Schoenberg 1946), in
//!   exact rational arithmetic at the f64 point.
//!
//! `nearest` and `grid-constant` follow what scipy 1.17 does for them
//! (`_prepad_for_spline_filter` in `scipy/ndimage/_interpolation.py` and
//! `NI_GeometricTransform` in `ni_interpolation.c`): when it prefilters
//! (degree ≥ 2) it pads every axis by `P` = [`SCIPY_PAD`] = 12 samples
//! (`np.pad` mode `edge` for `nearest`, the constant `cval` for
//! `grid-constant`), filters the padded array with `spline_filter`'s rule for
//! the mode (reflect's for `nearest`, mirror's for `grid-constant`:
//! [`scipy_filter_rule`](super::prefilter::scipy_filter_rule)) and evaluates
//! at `x + P`, taking the edge coefficient (`nearest`) or `cval`
//! (`grid-constant`) for the taps beyond the padded grid. The reference does
//! exactly that, from the user's exact samples, with `x + P` exact (scipy
//! rounds it in f64, which counts in scipy's error). `P = 0` for the other
//! modes and for degree 1 (no prefilter, hence no padding in scipy).
//!
//! This is *not* the exact spline of the infinitely extended signal, which
//! is what splinelab's engine (`LineFilter`, `Interpolant`) computes for
//! these modes: the reflect/mirror rule at the padded edge makes the
//! extension scipy's filter sees differ from the infinite one `2P` samples
//! beyond the grid, so at the edges the two differ by `ρ^k` of max |s|,
//! `2P ≤ k < 2P + 8` (`ρ` the dominant pole; measured by the unit test:
//! 2⁻⁴⁷ to 2⁻⁵⁶ for the cubic, 2⁻³¹ to 2⁻³⁶ for the quintic), decaying as
//! `ρ^j` into the interior. `check interp` judges scipy's convention.
//!
//! No recursive filter, pole, truncation or core evaluator enters: scipy (and
//! splinelab's engine) use a recursive filter and a Cox–de Boor style weight
//! recursion in floating point, so the reference is a second algorithm. The
//! weights are exact, so the `p / p + 64` agreement certifies the solve and
//! the sum. Cost: `O(N q²)` for the solve (`N` samples after padding) and
//! `O(d² + (d+2)^D)` per point, at two precisions per rung of the ladder.

use super::agreement::{Reference, certify};
use super::format::UserFormat;
use super::prefilter::{Mode, family_of_degree, horizon, interpolation_coefficients};
use super::summary::{CheckSummary, Context, ElementError, Region, element_error, from_elements};
use super::{CheckError, require_finite, require_len};
use rayon::prelude::*;
use rug::{Integer, Rational};
use splinelab::scalar::Real;
use splinelab::sspline::SplineFamily;

/// Largest `samples · q + points · (d + 2)^D` accepted (samples after padding).
pub const MAX_WORK: usize = 50_000_000;

/// Coordinates at or beyond `±2^62` samples are refused (their taps would
/// overflow `i64` indices).
const FAR: f64 = (1u64 << 62) as f64;

/// Samples scipy's `map_coordinates` pads on each side of every axis for
/// `nearest` and `grid-constant` before it prefilters (`npad` in
/// `_prepad_for_spline_filter`, scipy 1.17).
pub const SCIPY_PAD: usize = 12;

/// The padding `P` scipy applies for `mode` at `degree`: [`SCIPY_PAD`] for
/// `nearest` and `grid-constant` when it prefilters (degree ≥ 2), else 0.
pub fn scipy_padding(mode: Mode, degree: usize) -> usize {
    match mode {
        Mode::Nearest | Mode::GridConstant if degree > 1 => SCIPY_PAD,
        _ => 0,
    }
}

/// What `check interp` is given.
#[derive(Debug, Clone)]
pub struct InterpInput {
    /// The samples, C order.
    pub samples: Vec<f64>,
    /// Their shape: one or two axes, each at least one sample.
    pub shape: Vec<usize>,
    /// The query points, point-major: `points[k · D + a]` is coordinate `a`
    /// of point `k` (scipy's `coordinates` transposed), in sample indices.
    pub points: Vec<f64>,
    /// The user's values, one per point.
    pub user: Vec<f64>,
    /// The user's format.
    pub format: UserFormat,
    /// Spline degree `d` (scipy's `order`), in [`DEGREES`](super::prefilter::DEGREES).
    pub degree: usize,
    /// The end mode (any of scipy's five; see the module documentation for
    /// `nearest` and `grid-constant`).
    pub mode: Mode,
    /// `--max-ulps`.
    pub max_ulps: Option<f64>,
}

/// The exact centred B-spline of degree `d` at `t`, by the truncated-power
/// formula (module documentation). `O(d²)` rational operations.
pub fn centred_bspline(d: usize, t: &Rational) -> Rational {
    let half = Rational::from((d as i64 + 1, 2));
    let mut sum = Rational::new();
    let mut binom = Integer::from(1);
    for k in 0..=d + 1 {
        let u = Rational::from(t + &half) - k as i64;
        if u > 0 {
            let p: Rational = rug::ops::Pow::pow(u, d as i32);
            let term = p * &binom;
            if k % 2 == 0 {
                sum += term;
            } else {
                sum -= term;
            }
        }
        binom = binom * (d as u64 + 1 - k as u64) / (k as u64 + 1);
    }
    let fact = Integer::from(Integer::factorial(d as u32));
    sum / fact
}

/// The non-zero weights `(i, β(x − i))` of one exact coordinate.
fn weights(d: usize, x: &Rational) -> Vec<(i64, Rational)> {
    let c = x
        .clone()
        .floor()
        .numer()
        .to_i64()
        .expect("validated: |x| < 2^62");
    let r = d as i64 / 2 + 2;
    (c - r..=c + r)
        .filter_map(|i| {
            let w = centred_bspline(d, &Rational::from(x - i));
            (w != 0).then_some((i, w))
        })
        .collect()
}

/// The samples padded by `pad` on each side of every axis, as scipy's
/// `np.pad` does: `mode.fold` of the index (`edge` for `nearest`), `cval`
/// where it has none (`grid-constant`). Returns the values and the shape.
fn padded(
    samples: &[f64],
    shape: &[usize],
    pad: usize,
    mode: Mode,
    cval: f64,
) -> (Vec<f64>, Vec<usize>) {
    let big: Vec<usize> = shape.iter().map(|n| n + 2 * pad).collect();
    let values = (0..big.iter().product())
        .map(|flat: usize| {
            let mut rest = flat;
            let mut index = vec![0; big.len()];
            for a in (0..big.len()).rev() {
                index[a] = rest % big[a];
                rest /= big[a];
            }
            let source = index.iter().zip(shape).try_fold(0, |acc, (&i, &n)| {
                Some(acc * n + mode.fold(i as i64 - pad as i64, n)?)
            });
            source.map_or(cval, |k| samples[k])
        })
        .collect();
    (values, big)
}

/// A tap of the sum: the coefficient's index per axis (`None`: beyond a
/// `grid-constant` grid, worth `cval`) and its exact weight.
type Taps = Vec<(Option<usize>, Rational)>;

struct InterpReference {
    /// The (padded) samples and their shape.
    grid: Vec<f64>,
    shape: Vec<usize>,
    family: SplineFamily,
    mode: Mode,
    cval: f64,
    /// Per point, per axis: the taps.
    taps: Vec<Vec<Taps>>,
}

impl InterpReference {
    fn new(input: &InterpInput, family: SplineFamily, cval: f64, pad: usize) -> Self {
        let (grid, shape) = padded(&input.samples, &input.shape, pad, input.mode, cval);
        let dims = shape.len();
        let taps = input
            .points
            .par_chunks(dims)
            .map(|p| {
                p.iter()
                    .zip(&shape)
                    .map(|(x, n)| {
                        let x = Rational::from_f64(*x).expect("finite coordinate") + pad as u32;
                        weights(input.degree, &x)
                            .into_iter()
                            .map(|(i, w)| (input.mode.fold(i, *n), w))
                            .collect()
                    })
                    .collect()
            })
            .collect();
        InterpReference {
            grid,
            shape,
            family,
            mode: input.mode,
            cval,
            taps,
        }
    }

    /// The tensor-product coefficients in `T`, C order.
    fn coefficients<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let mut c: Vec<T> = self.grid.iter().map(|x| T::from_f64_exact(*x)).collect();
        let shape = &self.shape;
        let stride = |a: usize| shape[a + 1..].iter().product::<usize>();
        for (a, &n) in shape.iter().enumerate() {
            let s = stride(a);
            let lines: Vec<usize> = (0..c.len()).filter(|k| (k / s) % n == 0).collect();
            for start in lines {
                let line: Vec<T> = (0..n).map(|j| c[start + j * s].clone()).collect();
                let solved = interpolation_coefficients(&line, &self.family, self.mode)?;
                for (j, v) in solved.into_iter().enumerate() {
                    c[start + j * s] = v;
                }
            }
        }
        Ok(c)
    }
}

impl Reference for InterpReference {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let c = self.coefficients::<T>()?;
        let cval = T::from_f64_exact(self.cval);
        let at = |index: Option<usize>| index.map_or_else(|| cval.clone(), |k| c[k].clone());
        let cols = self.shape.get(1).copied().unwrap_or(1);
        let value = |w: &[Taps]| -> T {
            let mut sum = T::zero();
            match w {
                [x] => {
                    for (i, wi) in x {
                        sum += T::from_rational(wi) * at(*i);
                    }
                }
                [x, y] => {
                    for (i, wi) in x {
                        let mut row = T::zero();
                        for (j, wj) in y {
                            let k = i.zip(*j).map(|(i, j)| i * cols + j);
                            row += T::from_rational(wj) * at(k);
                        }
                        sum += T::from_rational(wi) * row;
                    }
                }
                _ => unreachable!("validated: 1-D or 2-D"),
            }
            sum
        };
        Ok(self.taps.iter().map(|w| value(w)).collect())
    }
}

/// Whether a point is within `h` samples of an edge of any axis (or outside).
fn region(point: &[f64], shape: &[usize], h: usize) -> Region {
    let near = point
        .iter()
        .zip(shape)
        .any(|(x, n)| *x < h as f64 || *x > (*n as f64 - 1.0) - h as f64);
    if near {
        Region::Boundary
    } else {
        Region::Interior
    }
}

fn validate(inp: &InterpInput, cval: f64) -> Result<(usize, SplineFamily), CheckError> {
    let family = family_of_degree(inp.degree)?;
    let dims = inp.shape.len();
    if !(1..=2).contains(&dims) {
        return Err(CheckError::Invalid(format!(
            "samples must be 1-D or 2-D, got {dims} axes"
        )));
    }
    if inp.shape.contains(&0) {
        return Err(CheckError::Empty("samples".into()));
    }
    require_len(
        "samples (product of shape)",
        inp.shape.iter().product(),
        inp.samples.len(),
    )?;
    require_finite("samples", &inp.samples)?;
    require_finite("cval", &[cval])?;
    require_finite("coordinates", &inp.points)?;
    if let Some(k) = inp.points.iter().position(|x| x.abs() >= FAR) {
        return Err(CheckError::Invalid(format!(
            "coordinate {} (index {k}) is beyond ±2^62 samples",
            inp.points[k]
        )));
    }
    if !inp.points.len().is_multiple_of(dims) {
        return Err(CheckError::Invalid(format!(
            "{} coordinates are not a whole number of {dims}-D points",
            inp.points.len()
        )));
    }
    let count = inp.points.len() / dims;
    if count == 0 {
        return Err(CheckError::Empty("coordinates".into()));
    }
    require_len("values (one per point)", count, inp.user.len())?;
    let d = inp.degree;
    let pad = scipy_padding(inp.mode, d);
    let padded_len = inp.shape.iter().fold(1usize, |acc, n| {
        acc.saturating_mul(n.saturating_add(2 * pad))
    });
    let work = padded_len
        .saturating_mul(family.pole_count().max(1))
        .saturating_add(count.saturating_mul((d + 2).pow(dims as u32)));
    if work > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "samples·q + points·(d+2)^D = {work} exceeds {MAX_WORK}"
        )));
    }
    Ok((count, family))
}

/// Checks the user's interpolated values with scipy's default `cval = 0`
/// (see [`check_interp_with_cval`]).
pub fn check_interp(input: &InterpInput) -> Result<CheckSummary, CheckError> {
    check_interp_with_cval(input, 0.0)
}

/// Checks the user's interpolated values; `cval` is scipy's constant for
/// `grid-constant` (ignored by the other modes). Inputs are validated first;
/// non-finite user values are failed elements. Boundary points are those
/// within the horizon `h` of an edge of the user's grid on any axis.
pub fn check_interp_with_cval(input: &InterpInput, cval: f64) -> Result<CheckSummary, CheckError> {
    let (count, family) = validate(input, cval)?;
    let dims = input.shape.len();
    let h = horizon(&family, input.format)?;
    let pad = scipy_padding(input.mode, input.degree);
    let r = InterpReference::new(input, family, cval, pad);
    let cert = certify(&r, input.format, 0)?;
    let elements: Vec<ElementError> = (0..count)
        .into_par_iter()
        .map(|k| {
            let reg = region(&input.points[k * dims..(k + 1) * dims], &input.shape, h);
            element_error(k, input.user[k], &cert.values[k], input.format, Some(reg))
        })
        .collect();
    let ctx = Context {
        kind: "interp",
        format: input.format,
        reference_bits: Some(cert.bits),
        reference: format!(
            "{}banded solve per axis ({} mode) and exact B-spline weights, MPFR {} bits agreeing with {} bits",
            padding_text(input.mode, pad, cval),
            input.mode.name(),
            cert.bits,
            cert.low_bits
        ),
        horizon: Some(h),
        max_ulps: input.max_ulps,
    };
    Ok(from_elements(&ctx, elements))
}

/// The reference text's account of scipy's padding (empty without one).
fn padding_text(mode: Mode, pad: usize, cval: f64) -> String {
    match (pad, mode) {
        (0, _) => String::new(),
        (_, Mode::GridConstant) => format!(
            "scipy's map_coordinates convention: samples padded by {pad} with cval {cval}, evaluated at x + {pad}; "
        ),
        _ => format!(
            "scipy's map_coordinates convention: samples padded by {pad} (edge), evaluated at x + {pad}; "
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centred_bspline_closed_forms() {
        // Cubic: β(0) = 2/3, β(±1) = 1/6, β(1/2) = 23/48; linear: hat.
        let q = |a: i64, b: i64| Rational::from((a, b));
        assert_eq!(centred_bspline(3, &q(0, 1)), q(2, 3));
        assert_eq!(centred_bspline(3, &q(-1, 1)), q(1, 6));
        assert_eq!(centred_bspline(3, &q(1, 2)), q(23, 48));
        assert_eq!(centred_bspline(3, &q(2, 1)), q(0, 1));
        assert_eq!(centred_bspline(1, &q(1, 4)), q(3, 4));
        // Partition of unity at an arbitrary point, degrees 1..=7.
        for d in 1..=7 {
            let s: Rational = weights(d, &Rational::from((3, 10)))
                .into_iter()
                .map(|(_, w)| w)
                .sum();
            assert_eq!(s, 1, "degree {d}");
        }
    }

    /// The reference at the edge point 0 with padding `pad`, relative to max |s|.
    fn at_edge(mode: Mode, degree: usize, pad: usize) -> rug::Float {
        use splinelab::scalar::Mp;
        let samples: Vec<f64> = (0..40).map(|j| ((j * j) % 7) as f64 - 3.0).collect();
        let input = InterpInput {
            samples,
            shape: vec![40],
            points: vec![0.0, 0.5],
            user: vec![0.0; 2],
            format: UserFormat::F64,
            degree,
            mode,
            max_ulps: None,
        };
        let family = family_of_degree(degree).unwrap();
        let r = InterpReference::new(&input, family, 0.0, pad);
        Real::to_float(&r.compute::<Mp<320>>().unwrap()[1])
    }

    #[test]
    fn scipy_padding_differs_from_the_infinite_extension_by_about_rho_to_the_2p() {
        // P = 12 (scipy) against P = 100, where the padding is effectively
        // infinite (ρ^200 < 2^-240 for the quintic): at the edge the gap,
        // relative to max |s|, is ρ^k with 2P ≤ k < 2P + 8 (the extensions
        // part 2P to 2P + 2 samples out; the filter's gain adds a few).
        for (mode, degree) in [
            (Mode::Nearest, 3),
            (Mode::GridConstant, 3),
            (Mode::Nearest, 5),
            (Mode::GridConstant, 5),
        ] {
            let family = family_of_degree(degree).unwrap();
            let rho = poles_rho(&family);
            let gap = (at_edge(mode, degree, SCIPY_PAD) - at_edge(mode, degree, 100)).abs();
            let log_gap = gap.to_f64().log2() - 3f64.log2();
            // Measured: k = 29.6 (nearest) and 24.7–25.7 (grid-constant).
            let k = log_gap / rho.log2();
            let p2 = 2.0 * SCIPY_PAD as f64;
            assert!((p2..p2 + 8.0).contains(&k), "{mode} d{degree}: ρ^{k}");
        }
    }

    fn poles_rho(family: &SplineFamily) -> f64 {
        splinelab::sspline::euler_frobenius::poles::<f64>(family)
            .unwrap()
            .iter()
            .map(|x| x.abs())
            .fold(0.0, f64::max)
    }
}
