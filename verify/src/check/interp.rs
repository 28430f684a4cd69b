//! `interp`: a user's interpolated values of N-D samples at query
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
//! [`scipy_filter_rule`](super::interpolation_conditions::scipy_filter_rule)) and evaluates
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
use super::interpolation_conditions::{Mode, family_of_degree, interpolation_coefficients};
use super::prefilter::horizon;
use super::stable_bound::{eval_constant, solve_bound, unit_roundoff};
use super::summary::{
    BoundBasis, CheckSummary, Context, ElementError, Region, element_error, from_elements,
};
use super::{CheckError, require_finite, require_len};
use rayon::prelude::*;
use rug::{Float, Integer, Rational};
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
pub fn scipy_padding(mode: ScipyMode, degree: usize) -> usize {
    match mode {
        ScipyMode::Shared(Mode::Nearest | Mode::GridConstant) if degree > 1 => SCIPY_PAD,
        _ => 0,
    }
}

/// A mode of scipy 1.17's `map_coordinates`: the five of the shared
/// [`Mode`] and the two that fold points differently from how they extend
/// the coefficients — `constant` (the `mirror` spline inside `[0, n − 1]` on
/// every axis, `cval` at any point outside it) and `wrap` (the point wrapped
/// with period `n − 1` into `[0, n − 1]`, then the `mirror` spline).
/// scipy's `_get_spline_boundary_mode` in `ni_interpolation.c` gives both the
/// mirror extension of the coefficients and `spline_filter`'s mirror rule.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScipyMode {
    /// One of the five shared modes.
    Shared(Mode),
    /// scipy's `constant` (its default).
    Constant,
    /// scipy's `wrap` (period `n − 1`).
    Wrap,
}

impl From<Mode> for ScipyMode {
    fn from(m: Mode) -> Self {
        ScipyMode::Shared(m)
    }
}

impl ScipyMode {
    /// scipy's name.
    pub fn name(self) -> &'static str {
        match self {
            ScipyMode::Shared(m) => m.name(),
            ScipyMode::Constant => "constant",
            ScipyMode::Wrap => "wrap",
        }
    }

    /// The mode the coefficients are filtered and extended with.
    pub fn spline_mode(self) -> Mode {
        match self {
            ScipyMode::Shared(m) => m,
            ScipyMode::Constant | ScipyMode::Wrap => Mode::Mirror,
        }
    }
}

impl std::str::FromStr for ScipyMode {
    type Err = String;

    /// Every name scipy's `map_coordinates` takes.
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "constant" => Ok(ScipyMode::Constant),
            "wrap" => Ok(ScipyMode::Wrap),
            _ => s.parse::<Mode>().map(ScipyMode::Shared).map_err(|_| {
                format!(
                    "unknown mode {s:?}: expected constant, nearest, reflect (grid-mirror), mirror, grid-wrap, wrap or grid-constant"
                )
            }),
        }
    }
}

/// Where scipy evaluates coordinate `x` of an axis of `n` samples, exactly:
/// `None` when a `constant` point is outside `[0, n − 1]` (the value is
/// `cval`), the point wrapped with period `n − 1` for `wrap`
/// (`map_coordinate` in `ni_interpolation.c`: `(0, n − 1]` from below,
/// `[0, n − 1)` from above), else `x` itself.
pub fn scipy_point(mode: ScipyMode, x: &Rational, n: usize) -> Option<Rational> {
    let last = Rational::from(n as u64 - 1);
    match mode {
        ScipyMode::Constant if *x < 0 || *x > last => None,
        ScipyMode::Wrap if *x < 0 || *x > last => {
            if n <= 1 {
                return Some(Rational::new());
            }
            let sz = Rational::from(n as u64 - 1);
            Some(if *x < 0 {
                let k = (-x.clone() / &sz).trunc();
                x.clone() + sz * (k + 1u32)
            } else {
                let k = Rational::from(x / &sz).trunc();
                x.clone() - sz * k
            })
        }
        _ => Some(x.clone()),
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
    /// Spline degree `d` (scipy's `order`), in [`DEGREES`](super::interpolation_conditions::DEGREES).
    pub degree: usize,
    /// The end mode: any of scipy's `map_coordinates` modes (see the
    /// module documentation for `nearest`, `grid-constant`, `constant` and
    /// `wrap`).
    pub mode: ScipyMode,
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

/// `|β'(x − i)|` for the taps of [`weights`]: `β'_d(t) = β_{d−1}(t + ½) −
/// β_{d−1}(t − ½)`, exact then rounded to f64 (0 for degree 0).
fn derivative_weight(d: usize, t: &Rational) -> f64 {
    if d == 0 {
        return 0.0;
    }
    let half = Rational::from((1, 2));
    let plus = centred_bspline(d - 1, &Rational::from(t + &half));
    let minus = centred_bspline(d - 1, &Rational::from(t - &half));
    (plus - minus).abs().to_f64()
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

/// One tap of one axis: the coefficient's index on that axis (`None`:
/// beyond a `grid-constant` grid, worth `cval`), its exact weight, and
/// `|β'|` there (for the bound's coordinate term).
#[derive(Debug, Clone)]
struct Tap {
    index: Option<usize>,
    w: Rational,
    dw: f64,
}

/// The taps of one point (one list per axis), or `None` where scipy returns
/// `cval` without interpolating (`constant` outside the grid); and per axis
/// the coordinate rounding `δx_a` a stable evaluation makes first.
#[derive(Debug, Clone)]
struct PointTaps {
    axes: Option<Vec<Vec<Tap>>>,
    shift_error: Vec<f64>,
}

struct InterpReference {
    /// The (padded) samples and their shape.
    grid: Vec<f64>,
    shape: Vec<usize>,
    family: SplineFamily,
    mode: ScipyMode,
    cval: f64,
    /// Per point: the taps.
    taps: Vec<PointTaps>,
}

impl InterpReference {
    fn new(input: &InterpInput, family: SplineFamily, cval: f64, pad: usize) -> Self {
        let spline = input.mode.spline_mode();
        let (grid, shape) = padded(&input.samples, &input.shape, pad, spline, cval);
        let dims = shape.len();
        let u = unit_roundoff(input.format);
        let taps = input
            .points
            .par_chunks(dims)
            .map(|p| {
                let mut shift_error = vec![0.0; dims];
                let axes = p
                    .iter()
                    .zip(&input.shape)
                    .zip(&shape)
                    .enumerate()
                    .map(|(a, ((x, n0), n))| {
                        let given = Rational::from_f64(*x).expect("finite coordinate");
                        let at = scipy_point(input.mode, &given, *n0)? + pad as u32;
                        let inside = *x >= 0.0 && *x <= (*n0 as f64 - 1.0);
                        if pad > 0 || !inside {
                            // x + P, or a fold: one rounding of the result.
                            shift_error[a] = u * (x.abs() + at.to_f64().abs());
                        }
                        Some(
                            weights(input.degree, &at)
                                .into_iter()
                                .map(|(i, w)| Tap {
                                    index: spline.fold(i, *n),
                                    dw: derivative_weight(input.degree, &Rational::from(&at - i)),
                                    w,
                                })
                                .collect(),
                        )
                    })
                    .collect();
                PointTaps { axes, shift_error }
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
                let solved =
                    interpolation_coefficients(&line, &self.family, self.mode.spline_mode())?;
                for (j, v) in solved.into_iter().enumerate() {
                    c[start + j * s] = v;
                }
            }
        }
        Ok(c)
    }

    /// The stable bound of every point (module [`stable_bound`]):
    /// `γ_eval (Σ|c||W| + Σ_a Σ|c||W^(a)|) + Σ|W| E + Σ_a δx_a Σ|c||∂_a W| + u|f|`
    /// (`W^(a)`: the weights with axis `a`'s set to 1), with the
    /// coefficients and their bounds `E` from [`solve_bound`].
    fn bounds(
        &self,
        degree: usize,
        format: UserFormat,
        refs: &[Float],
    ) -> Result<Vec<f64>, CheckError> {
        let (c, e) = if degree > 1 {
            solve_bound(
                &self.grid,
                &self.shape,
                &self.family,
                self.mode.spline_mode(),
                format,
            )?
        } else {
            // No prefilter: the coefficients are the samples, exactly.
            (self.grid.clone(), vec![0.0; self.grid.len()])
        };
        let g = eval_constant(degree, self.shape.len(), format);
        let u = unit_roundoff(format);
        let abs_c = |k: Option<usize>| k.map_or(self.cval.abs(), |k| c[k].abs());
        let err = |k: Option<usize>| k.map_or(0.0, |k| e[k]);
        Ok(self
            .taps
            .par_iter()
            .zip(refs.par_iter())
            .map(|(p, r)| {
                let rounding = u * r.to_f64().abs();
                let Some(axes) = &p.axes else {
                    return rounding;
                };
                let moved: f64 = (0..axes.len())
                    .filter(|&a| p.shift_error[a] > 0.0)
                    .map(|a| {
                        let special = Some((a, Factor::Derivative));
                        p.shift_error[a] * abs_tensor(axes, &self.shape, special, &abs_c)
                    })
                    .sum();
                let absolute_weights: f64 = (0..axes.len())
                    .map(|a| abs_tensor(axes, &self.shape, Some((a, Factor::One)), &abs_c))
                    .sum();
                g * (abs_tensor(axes, &self.shape, None, &abs_c) + absolute_weights)
                    + abs_tensor(axes, &self.shape, None, &err)
                    + moved
                    + rounding
            })
            .collect())
    }
}

/// What axis `a`'s factor is in [`abs_tensor`]: `|β|` on every axis but one,
/// where it is `|β'|` (the coordinate term) or 1 (a weight known only to an
/// absolute `γ`, as scipy's last weight `1 − Σ others`).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Factor {
    Derivative,
    One,
}

/// `Σ_j v(j) Π_a |W_a|` over the taps, axis `special.0` replaced by
/// `special.1`, in f64.
fn abs_tensor(
    axes: &[Vec<Tap>],
    shape: &[usize],
    special: Option<(usize, Factor)>,
    v: &impl Fn(Option<usize>) -> f64,
) -> f64 {
    fn walk(
        axes: &[Vec<Tap>],
        shape: &[usize],
        special: Option<(usize, Factor)>,
        v: &impl Fn(Option<usize>) -> f64,
        a: usize,
        offset: Option<usize>,
    ) -> f64 {
        if a == axes.len() {
            return v(offset);
        }
        axes[a]
            .iter()
            .map(|t| {
                let w = match special {
                    Some((b, Factor::Derivative)) if b == a => t.dw,
                    Some((b, Factor::One)) if b == a => 1.0,
                    _ => t.w.to_f64().abs(),
                };
                let next = offset.zip(t.index).map(|(o, i)| o * shape[a] + i);
                w * walk(axes, shape, special, v, a + 1, next)
            })
            .sum()
    }
    walk(axes, shape, special, v, 0, Some(0))
}

/// `Σ_j c_j Π_a W_a` over the taps in `T` (axis by axis, as 1-D sums nest).
fn tensor_value<T: Real>(
    axes: &[Vec<Tap>],
    shape: &[usize],
    at: &impl Fn(Option<usize>) -> T,
    a: usize,
    offset: Option<usize>,
) -> T {
    if a == axes.len() {
        return at(offset);
    }
    let mut sum = T::zero();
    for t in &axes[a] {
        let next = offset.zip(t.index).map(|(o, i)| o * shape[a] + i);
        sum += T::from_rational(&t.w) * tensor_value(axes, shape, at, a + 1, next);
    }
    sum
}

impl Reference for InterpReference {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let c = self.coefficients::<T>()?;
        let cval = T::from_f64_exact(self.cval);
        let at = |index: Option<usize>| index.map_or_else(|| cval.clone(), |k| c[k].clone());
        Ok(self
            .taps
            .iter()
            .map(|p| match &p.axes {
                Some(axes) => tensor_value(axes, &self.shape, &at, 0, Some(0)),
                None => cval.clone(),
            })
            .collect())
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
    if dims == 0 {
        return Err(CheckError::Invalid(
            "samples must have at least one axis, got a 0-D array".into(),
        ));
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
        .saturating_add(count.saturating_mul((d + 2).saturating_pow(dims.min(64) as u32)));
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
    let bounds = r.bounds(input.degree, input.format, &cert.values)?;
    let elements: Vec<ElementError> = (0..count)
        .into_par_iter()
        .map(|k| {
            let reg = region(&input.points[k * dims..(k + 1) * dims], &input.shape, h);
            element_error(k, input.user[k], &cert.values[k], input.format, Some(reg))
                .with_bound(bounds[k])
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
        bound: BoundBasis::PerElement(interp_bound_text(input.degree, dims, input.format)),
    };
    Ok(from_elements(&ctx, elements))
}

/// The account of the interpolated values' stable bound.
fn interp_bound_text(d: usize, dims: usize, format: UserFormat) -> String {
    format!(
        "γ_{m}·Σ_j |c_j|(|W_j(x)| + Σ_a |W_j^(a)(x)|) + Σ_j |W_j(x)|·E_j + Σ_a δx_a·Σ_j |c_j||∂_a W_j(x)| + u|f(x)| in {}: \
         a stable tensor-product evaluation (each weight within γ of itself, or of 1 where it is \
         formed as 1 − Σ others as scipy does: W^(a) has axis a's weights set to 1; m = D(6d + 2) = {m}; \
         Higham, Accuracy and Stability, 2nd ed., §3.1) of coefficients with the banded solve's \
         componentwise bound E per axis (§7.2, Thm 9.4), δx_a = u(|x_a| + |x'_a|) where the point \
         is shifted (scipy's +12 padding) or folded",
        format.name(),
        m = dims * (6 * d + 2)
    )
}

/// The reference text's account of scipy's padding (empty without one).
fn padding_text(mode: ScipyMode, pad: usize, cval: f64) -> String {
    match (pad, mode) {
        (0, ScipyMode::Constant) => format!(
            "scipy's constant mode: the mirror spline inside [0, n − 1], cval {cval} outside; "
        ),
        (0, ScipyMode::Wrap) => {
            "scipy's wrap mode: the point wrapped with period n − 1, then the mirror spline; "
                .into()
        }
        (0, _) => String::new(),
        (_, ScipyMode::Shared(Mode::GridConstant)) => format!(
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
            mode: mode.into(),
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
