//! The N-D prefilter (`spline_filter`, every axis in turn) against a
//! high-precision reference: accuracy, not agreement with a peer.
//!
//! **Reference.** The same [`LineFilter`] (exact route, same mode and
//! `cval`) run in 256-bit MPFR ([`Wide`]) on each line of each axis alone,
//! axis after axis, from the exact samples — the one-line recursion, not the
//! N-D engine's row kernels, slabs or pole cascade, so an independent order
//! of operations whose own rounding (`2^{−256}` relative, times `A^D`) is far
//! below anything measured in `f64`.
//!
//! **Measure.** [`metrics::eps_of_max`]: `max_k |D_k − D*_k| / (ε · max|D*|)`,
//! `ε = 2^{1−BITS}` of the format under test, formed in MPFR; the normwise
//! unit scipy agreement is judged in, so a figure against MPFR and one
//! against scipy read the same way.
//!
//! **Documented bound** ([`rounding_bound`]): each axis adds at most `64 u A`
//! of rounding per unit of its input's extended magnitude (`A = 1/|V(−1)|`
//! the amplification, `u = 2^{−BITS}`) and amplifies what came before by
//! `A`, so over `D` axes `|D − D*| ≤ 64 u D A^D · max(max|s|, |cval|)` (the
//! bound `core::ndimage::nd_prefilter`'s tests and `engine_lanes` hold the
//! engine to; `|cval|` enters for `grid-constant` only).
//!
//! [`fixture_case`] measures one case of scipy's committed fixtures for the
//! report's engine section and `tests/nd_prefilter_mpfr.rs`: our `f64` and
//! `f32` results and scipy's own `f64` output against the same reference.

use crate::metrics;
use splinelab::ndarray::{ArrayD, Axis};
use splinelab::prelude::*;

/// The reference precision: 256-bit MPFR.
pub type Wide = Mp<256>;

/// The filter of degree `degree` (scipy's `order`) under `mode`, exact route.
fn filter<T: Real>(degree: u32, mode: Mode, cval: f64) -> Result<LineFilter<T>, NdimageError> {
    LineFilter::new(&SplineFamily::Order(degree + 1), mode, cval, Route::Exact)
}

/// The exact-route coefficients of `samples` along every axis, computed in
/// `W` line by line with [`LineFilter::apply`] (module documentation), from
/// the exact values of `samples` and of `cval` as `T` holds it. Cost: `D`
/// passes of the one-line recursion in `W` (for `nearest` and
/// `grid-constant` each line padded by the pole horizon of `W`).
pub fn reference<W: Real, T: Real>(
    samples: &ArrayD<T>,
    degree: u32,
    mode: Mode,
    cval: f64,
) -> Result<ArrayD<W>, NdimageError> {
    let f = filter::<W>(degree, mode, T::from_f64_exact(cval).to_f64())?;
    let mut a = samples.mapv(|x| W::from_f64_exact(x.to_f64()));
    let mut scratch = Vec::new();
    for axis in 0..a.ndim() {
        for mut lane in a.lanes_mut(Axis(axis)) {
            let mut line = lane.to_vec();
            f.apply(&mut line, &mut scratch);
            lane.iter_mut().zip(line).for_each(|(d, s)| *d = s);
        }
    }
    Ok(a)
}

/// The documented bound on `|D − D*|` of the exact route in `T` over `ndim`
/// axes: `64 u D A^D · max(max|s|, |cval|)` (module documentation), where
/// `max_ext = max(max|s|, |cval|)`.
pub fn rounding_bound<T: Real>(filter: &LineFilter<T>, ndim: usize, max_ext: f64) -> f64 {
    let u = (-(T::BITS as f64)).exp2();
    let amp = filter.recursive().amplification();
    64.0 * u * ndim as f64 * amp.powi(ndim as i32) * max_ext
}

/// One array's `spline_filter` in `T` against [`Wide`]: the error and the
/// documented bound, both in units of `ε · max|D*|` of `T`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// [`metrics::eps_of_max`] of the engine's result.
    pub error: f64,
    /// [`rounding_bound`] in the same unit.
    pub bound: f64,
}

/// `samples` (rounded to `T`) through the engine's [`spline_filter`] in
/// `T`, judged against [`reference`] in [`Wide`]; returns the reference
/// too (as computed for `T`'s samples), to judge a peer's output by.
pub fn measure<T: Real + Send + Sync>(
    samples: &ArrayD<f64>,
    degree: u32,
    mode: Mode,
    cval: f64,
) -> Result<(Measured, ArrayD<Wide>), NdimageError> {
    let s = samples.mapv(T::from_f64_exact);
    let f = filter::<T>(degree, mode, cval)?;
    let mut got = s.clone();
    spline_filter(&mut got, &f)?;
    let want = reference::<Wide, T>(&s, degree, mode, cval)?;
    let got: Vec<T> = got.iter().cloned().collect();
    let want_flat: Vec<Wide> = want.iter().cloned().collect();
    let max_ext = s
        .iter()
        .fold(0.0f64, |m, x| m.max(x.to_f64().abs()))
        .max(match mode {
            Mode::GridConstant => T::from_f64_exact(cval).to_f64().abs(),
            _ => 0.0,
        });
    let scale = want_flat
        .iter()
        .fold(0.0f64, |m, r| m.max(r.to_f64().abs()))
        * (1.0 - T::BITS as f64).exp2();
    let measured = Measured {
        error: metrics::eps_of_max(&got, &want_flat),
        bound: rounding_bound(&f, samples.ndim(), max_ext) / scale,
    };
    Ok((measured, want))
}

/// One scipy fixture case: `spline_filter(x, degree, mode)` by the engine
/// in `f64` and `f32` and by scipy (its committed `f64` output), each
/// against 256-bit MPFR.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixtureCase {
    /// The engine in `f64` (`f64` ulps of max|D*|).
    pub f64: Measured,
    /// The engine in `f32` on the samples rounded to `f32` (`f32` ulps).
    pub f32: Measured,
    /// scipy's output against the `f64` samples' reference (`f64` ulps).
    pub scipy: f64,
}

/// Measures one fixture case (`x` the samples, `scipy` scipy's
/// `spline_filter` of them; `cval` the fixtures' `grid-constant` value).
/// Panics if the shapes differ (a fixture bug).
pub fn fixture_case(
    x: &ArrayD<f64>,
    scipy: &ArrayD<f64>,
    degree: u32,
    mode: Mode,
    cval: f64,
) -> Result<FixtureCase, NdimageError> {
    assert_eq!(x.shape(), scipy.shape(), "fixture shapes differ");
    let (f64_case, want) = measure::<f64>(x, degree, mode, cval)?;
    let (f32_case, _) = measure::<f32>(x, degree, mode, cval)?;
    let scipy: Vec<f64> = scipy.iter().copied().collect();
    let want: Vec<Wide> = want.iter().cloned().collect();
    Ok(FixtureCase {
        f64: f64_case,
        f32: f32_case,
        scipy: metrics::eps_of_max(&scipy, &want),
    })
}
