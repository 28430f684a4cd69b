//! The tensor-product spline interpolant of an N-dimensional array of
//! samples (scipy.ndimage's `map_coordinates` engine, any degree
//! `0..=199`): `f(x) = Σ_i D_i Π_a β(x_a − i_a)` with `D` the prefiltered
//! coefficients, so that `f(j) = s_j` at every grid point `j`.
//!
//! Built once ([`Interpolant::new`], `O(p)` per sample and axis for the
//! exact route), evaluated anywhere: one point ([`Interpolant::eval`]),
//! partial derivatives up to the degree ([`Interpolant::eval_derivative`]),
//! or many points into a caller's buffer in parallel without allocating per
//! point ([`Interpolant::eval_many`]). Coordinates are `f64` sample indices
//! as in scipy; each is split exactly into a cell and a fractional position
//! (never `x + m/2`, see [`centred_cell`]), so the error is relative to the
//! position inside the cell however large `x` is.
//!
//! **Cost** per point: `D` weight windows (`O(m)` each in closed form for
//! degrees 1 to 5, `O(m²)` by de Boor–Cox above) and `m^D`
//! multiply-adds. **Error**: the coefficients' (see [`LineFilter`]) plus the
//! rounding of `m^D` non-negative-weight terms, `≤ m D u Σ|D_i| w_i`.

use super::alloc::try_padded_zeros;
use super::filter_cache;
use super::line_filter::{LineFilter, Route};
use super::mode::Mode;
use super::nan_policy::NanPolicy;
use super::nd_prefilter::{check_finite, padded_coefficients, spline_filter_from};
use super::samples::Sample;
use super::{NdimageError, spline_order};
use crate::scalar::Real;
use crate::sspline::bspline_uniform::{cell_derivatives_into, centred_cell};
use ndarray::{
    ArrayBase, ArrayD, ArrayView2, ArrayViewD, ArrayViewMutD, Data, Dimension, IxDyn, Slice,
};
use std::sync::Arc;

#[cfg(test)]
mod accuracy;
mod affine;
mod batch;
mod in_place;
mod kernel;
mod padding;
mod point_rule;
mod runs;
mod separable;
mod weights;
pub use in_place::{InPlaceOptions, SampleOrder, map_samples_in_place};
use padding::{extend_in_place, extend_padded, relocate_to_padded};
pub use point_rule::PointRule;

/// How to build an [`Interpolant`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    /// Spline degree `0..=199` (scipy's `order`; our B-spline order `m` is
    /// degree + 1, [`spline_order`]).
    pub degree: u32,
    /// Boundary mode.
    pub mode: Mode,
    /// The constant of `grid-constant` (ignored otherwise).
    pub cval: f64,
    /// Exact or truncated coefficients.
    pub route: Route,
    /// What non-finite samples do ([`NanPolicy`]; default
    /// [`NanPolicy::Propagate`], scipy's pattern). [`NanPolicy::Local`]
    /// needs a truncated route for degrees ≥ 2.
    pub nan_policy: NanPolicy,
}

impl Options {
    /// Degree and mode, `cval = 0`, exact route.
    pub fn new(degree: u32, mode: Mode) -> Self {
        Options {
            degree,
            mode,
            cval: 0.0,
            route: Route::Exact,
            nan_policy: NanPolicy::default(),
        }
    }
}

/// A spline interpolant of gridded samples (module documentation).
#[derive(Debug, Clone)]
pub struct Interpolant<T> {
    coeffs: ArrayD<T>,
    shape: Vec<usize>,
    strides: Vec<usize>,
    order: u32,
    pad: usize,
    mode: Mode,
    cval: T,
    bound: f64,
    /// Built by [`Interpolant::from_coefficients`] (scipy's
    /// `prefilter=False`): `nearest` extends the given coefficients.
    given: bool,
}

/// Per-point work space: weights and flat offsets, `m` per axis, on the
/// stack for one point ([`SMALL`]) or in vectors.
struct Scratch<'a, T> {
    w: &'a mut [T],
    off: &'a mut [usize],
    inside: &'a mut [bool],
}

/// Work space of a single-point evaluation kept on the stack: `ndim × m`
/// up to 24 (3-D to degree 7, 2-D to 11, 1-D to 23); beyond it, vectors.
const SMALL: usize = 24;

impl<T: Real + Send + Sync> Interpolant<T> {
    /// The interpolant of `data` (1 to N dimensions, at least one sample per
    /// axis), degree `0..=199`; non-finite samples by `opts.nan_policy`
    /// ([`super::nan_policy`]: under `Propagate` every coefficient of a
    /// degree ≥ 2 is NaN once one sample is; under `Local` those within the
    /// certified half-width; the evaluation carries a NaN coefficient to every
    /// output whose window holds it). Degrees 0 (the nearest sample,
    /// [`Mode::nearest_index`]) and 1 (multilinear) need no prefilter: their
    /// coefficients are the samples, as in scipy.
    ///
    ///
    /// **Method**: the exact recursive prefilter along every axis ([`LineFilter`]), padded for
    /// `nearest`/`grid-constant`. **Accuracy**: the interpolation condition holds to `O(u)`
    /// relative up to degree 31 in f64 and to 1e-60 in 256-bit MPFR up to degree 99
    /// (`verify/tests/it/engine_properties.rs::high_degrees_satisfy_the_interpolation_condition`);
    /// scipy agreement in `verify/tests/it/engine_scipy.rs::map_coordinates_matches_scipy`.
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let data = ndarray::array![[0.0, 1.0, 4.0], [1.0, 2.0, 5.0], [4.0, 5.0, 8.0]];
    /// let f: Interpolant<f64> = Interpolant::new(&data, Options::new(3, Mode::Mirror)).unwrap();
    /// assert!((f.eval(&[1.0, 2.0]).unwrap() - 5.0).abs() < 1e-14);
    /// let many = ndarray::array![[0.5, 0.5], [2.0, 0.0]];
    /// let mut out = [0.0f64; 2];
    /// f.eval_many(many.view(), &mut out).unwrap();
    /// assert!((out[1] - 4.0).abs() < 1e-14);
    /// ```
    pub fn new<S, D>(data: &ArrayBase<S, D>, opts: Options) -> Result<Self, NdimageError>
    where
        S: Data<Elem = T>,
        D: Dimension,
    {
        Self::from_samples(data, opts)
    }

    /// [`Self::new`] from samples of any element type `E` that reads into
    /// the compute type `T` ([`Sample`]): `f32`, `f64` or integer data
    /// computed in `f64`, as scipy computes them. The samples are widened
    /// exactly as the prefilter's first pass reads them (no widened copy of
    /// the input is made), and the result equals [`Self::new`] on the
    /// widened data bit for bit.
    ///
    /// **Memory**: one coefficient array of `T`, the input's shape grown by
    /// `pad = ⌊(d + 1)/2⌋ + 2` per side (more for `nearest` and
    /// `grid-constant`): the coefficients are computed into the front of
    /// that allocation, moved to their padded places in place and extended
    /// there (`padding.rs`); degrees 0 and 1 and
    /// [`Self::from_coefficients_of`] copy the input into it. Allocated
    /// fallibly ([`NdimageError::OutOfMemory`]).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let data = ndarray::array![[0.0f32, 1.0, 4.0], [1.0, 2.0, 5.0], [4.0, 5.0, 8.5]];
    /// let f = Interpolant::<f64>::from_samples(&data, Options::new(3, Mode::Mirror)).unwrap();
    /// let g = Interpolant::new(&data.mapv(f64::from), Options::new(3, Mode::Mirror)).unwrap();
    /// assert_eq!(f.eval(&[0.7, 1.3]).unwrap(), g.eval(&[0.7, 1.3]).unwrap());
    /// ```
    pub fn from_samples<E, S, D>(
        data: &ArrayBase<S, D>,
        opts: Options,
    ) -> Result<Self, NdimageError>
    where
        E: Sample<T>,
        S: Data<Elem = E>,
        D: Dimension,
    {
        if opts.degree <= 1 {
            return Self::from_coefficients_of(data, opts)
                .map(|f| Interpolant { given: false, ..f });
        }
        let (order, filter) = prefilter_of(&opts, opts.mode, opts.cval)?;
        let mut pad = order as usize / 2 + 2;
        if matches!(opts.mode, Mode::GridConstant | Mode::Nearest) {
            // Beyond this the coefficients equal cval (the end sample) to
            // working precision: the spline is constant there.
            pad += filter.exact_pad() + filter.half_width().unwrap_or(0);
        }
        let coeffs = match opts.mode {
            // The symmetric modes' padded coefficients are the coefficients
            // extended by the mode (what `LineFilter::apply_padded` does):
            // the whole-array prefilter into the padded allocation, then
            // the pads filled in place.
            Mode::Mirror | Mode::Reflect | Mode::GridWrap => {
                prefiltered_padded(&data.view().into_dyn(), &filter, opts.mode, &T::zero(), pad)?
            }
            // In standard layout as made.
            Mode::Nearest | Mode::GridConstant => {
                padded_coefficients(data, &filter, pad)?.into_dyn()
            }
        };
        let cval = T::from_f64_exact(opts.cval);
        let parts = (order, pad, opts.mode, cval, filter.bound());
        Ok(Self::from_parts(data.shape(), coeffs, parts, false))
    }

    /// The interpolant of padded coefficients `coeffs` (standard layout) of
    /// samples of `shape`, from `(order, pad, mode, cval, bound)`.
    fn from_parts(
        shape: &[usize],
        coeffs: ArrayD<T>,
        (order, pad, mode, cval, bound): (u32, usize, Mode, T, f64),
        given: bool,
    ) -> Self {
        Interpolant {
            shape: shape.to_vec(),
            strides: coeffs.strides().iter().map(|&s| s as usize).collect(),
            coeffs,
            order,
            pad,
            mode,
            cval,
            bound,
            given,
        }
    }

    /// The interpolant of the coefficients of `data` under the prefilter of
    /// `filter_mode` (a symmetric mode: `mirror`, `reflect`, `grid-wrap`),
    /// extended beyond the grid by `opts.mode` as given coefficients are
    /// ([`Self::from_coefficients_with`]; `opts.route` and `nan_policy` are
    /// the filter's): scipy's `map_coordinates` for `nearest` and
    /// `grid-constant`, which pads the input by 12 edge samples or `cval`
    /// (the caller pads), filters it with the mode's rule and evaluates the
    /// result with `prefilter=False`. The same coefficients as
    /// [`spline_filter_from`] under `filter_mode` then
    /// [`Self::from_coefficients_of`], in one coefficient array (the
    /// filter's output is the padded array's front, moved up and extended
    /// in place) instead of two. Samples of any [`Sample`] type.
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// use splinelab::ndimage::nd_prefilter::spline_filter_from;
    /// let x = ndarray::array![3.0f32, 3.0, 3.0, 1.0, 4.0, 1.5, 5.0, 5.0, 5.0];
    /// let opts = Options::new(3, Mode::Nearest);
    /// let f = Interpolant::<f64>::from_samples_filtered_as(&x, opts, Mode::Reflect).unwrap();
    /// let filter = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Reflect, 0.0, Route::Exact).unwrap();
    /// let mut c = ndarray::Array1::<f64>::zeros(9);
    /// spline_filter_from(&x, &mut c, &[0], Some(&filter)).unwrap();
    /// let g = Interpolant::from_coefficients_with(&c, opts).unwrap();
    /// assert_eq!(f.eval(&[-3.7]).unwrap(), g.eval(&[-3.7]).unwrap());
    /// ```
    pub fn from_samples_filtered_as<E, S, D>(
        data: &ArrayBase<S, D>,
        opts: Options,
        filter_mode: Mode,
    ) -> Result<Self, NdimageError>
    where
        E: Sample<T>,
        S: Data<Elem = E>,
        D: Dimension,
    {
        if opts.degree <= 1 {
            return Self::from_coefficients_of(data, opts);
        }
        if !matches!(filter_mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap) {
            return Err(NdimageError::FilterMode(filter_mode));
        }
        let (order, filter) = prefilter_of(&opts, filter_mode, 0.0)?;
        let pad = given_pad(opts.mode, order);
        let cval = T::from_f64_exact(opts.cval);
        let coeffs = prefiltered_padded(&data.view().into_dyn(), &filter, opts.mode, &cval, pad)?;
        let parts = (order, pad, opts.mode, cval, filter.bound());
        Ok(Self::from_parts(data.shape(), coeffs, parts, true))
    }

    /// The interpolant whose coefficients `D_i` the caller already has
    /// (scipy's `map_coordinates(coeffs, …, prefilter=False)`): `f(x) =
    /// Σ_i D_i Π_a β(x_a − i_a)` with `D` extended beyond the grid by
    /// `mode` (`cval` for `grid-constant`), the point folded as in
    /// [`Interpolant::new`] except for `nearest`, where scipy extends the
    /// coefficients and leaves the point where it is. Degree `0..=199`.
    /// Cost: one copy of `coeffs` with `⌊(d + 1)/2⌋ + 2` values of padding
    /// per side (`d + 3` for `nearest`).
    ///
    ///
    /// **Accuracy**: no rounding beyond the evaluation's (the coefficients are copied); scipy's
    /// `prefilter=False` output reproduced within 16 ulps of max|value|
    /// (`reports/tests/it/cli_engine.rs`, the `--coeffs` fixtures).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let c = ndarray::array![0.0, 6.0, 0.0, 0.0];
    /// let f: Interpolant<f64> = Interpolant::from_coefficients(&c, 3, Mode::Mirror, 0.0).unwrap();
    /// // The cubic B-spline centred at 1: 6 · 2/3 at its centre, 6 · 1/6 one away.
    /// assert_eq!(f.eval(&[1.0]).unwrap(), 4.0);
    /// assert_eq!(f.eval(&[2.0]).unwrap(), 1.0);
    /// ```
    pub fn from_coefficients<S, D>(
        coeffs: &ArrayBase<S, D>,
        degree: u32,
        mode: Mode,
        cval: f64,
    ) -> Result<Self, NdimageError>
    where
        S: Data<Elem = T>,
        D: Dimension,
    {
        let opts = Options {
            cval,
            ..Options::new(degree, mode)
        };
        Self::from_coefficients_with(coeffs, opts)
    }

    /// [`Self::from_coefficients`] with `opts.degree`, `mode`, `cval` and
    /// `nan_policy` (`route` unused): non-finite coefficients are refused
    /// under [`NanPolicy::Raise`] (naming the first), and otherwise carried
    /// to every output whose window holds one (scipy's `0 · NaN`), the
    /// pattern of both `Propagate` and `Local` (given coefficients have no
    /// prefilter to reach through; `Local` makes them NaN, `Propagate`
    /// leaves ±∞ as it is).
    ///
    /// ```
    /// use splinelab::prelude::*;
    /// let c = ndarray::array![0.0, 6.0, f64::NAN, 0.0, 0.0, 0.0, 1.0];
    /// let f: Interpolant<f64> = Interpolant::from_coefficients_with(&c, Options::new(3, Mode::Mirror)).unwrap();
    /// // The cubic window at x reads ⌊x⌋ − 1 ..= ⌊x⌋ + 2: at 3 the NaN has weight 0, and counts.
    /// assert!(f.eval(&[3.0]).unwrap().is_nan() && f.eval(&[0.0]).unwrap().is_nan());
    /// assert!((f.eval(&[5.0]).unwrap() - 1.0 / 6.0).abs() < 1e-15);
    /// ```
    pub fn from_coefficients_with<S, D>(
        coeffs: &ArrayBase<S, D>,
        opts: Options,
    ) -> Result<Self, NdimageError>
    where
        S: Data<Elem = T>,
        D: Dimension,
    {
        Self::from_coefficients_of(coeffs, opts)
    }

    /// [`Self::from_coefficients_with`] from coefficients of any element
    /// type `E` that reads into `T` ([`Sample`]: scipy's
    /// `map_coordinates(float32_coeffs, …, prefilter=False)` computes in
    /// float64), widened as they are copied into the padded array (one
    /// copy, as [`Self::from_coefficients`]; allocated fallibly).
    pub fn from_coefficients_of<E, S, D>(
        coeffs: &ArrayBase<S, D>,
        opts: Options,
    ) -> Result<Self, NdimageError>
    where
        E: Sample<T>,
        S: Data<Elem = E>,
        D: Dimension,
    {
        let Options {
            degree, mode, cval, ..
        } = opts;
        let order = spline_order(degree)?;
        if coeffs.is_empty() {
            return Err(NdimageError::Empty);
        }
        let pad = given_pad(mode, order);
        let (mut padded, finite) = extend_padded(coeffs, mode, &T::from_f64_exact(cval), pad)?;
        match opts.nan_policy {
            // Names the first non-finite coefficient.
            NanPolicy::Raise if !finite => check_finite::<T, _, _, _>(coeffs)?,
            // Missing is NaN under `Local` (±∞ would give ±∞ at full weight).
            NanPolicy::Local if !finite => {
                let nan = T::from_f64_exact(f64::NAN);
                padded.par_mapv_inplace(|x| if x.is_finite() { x } else { nan.clone() });
            }
            _ => {}
        }
        let parts = (order, pad, mode, T::from_f64_exact(cval), 0.0);
        Ok(Self::from_parts(coeffs.shape(), padded, parts, true))
    }

    /// The point at which axis `a` is evaluated ([`Mode::fold_coordinate`]).
    /// Under `nearest` (degree ≥ 2) the point itself: the spline of the
    /// edge-extended signal is not constant next to the ends (scipy pads 12
    /// edge samples to approximate it); it is clamped only where every
    /// coefficient of its window equals the end one — the end sample to
    /// working precision beyond the exact pad, the end coefficient for given
    /// coefficients — so the value is the same.
    fn coordinate(&self, x: f64, a: usize) -> f64 {
        if self.mode == Mode::Nearest && self.order > 2 {
            let half = self.order as usize / 2;
            let r = if self.given {
                half + 1
            } else {
                self.pad - half - 2
            };
            return x.clamp(-(r as f64), self.shape[a] as f64 - 1.0 + r as f64);
        }
        self.mode.fold_coordinate(x, self.shape[a])
    }

    /// Number of dimensions.
    pub fn ndim(&self) -> usize {
        self.shape.len()
    }

    /// The shape of the sample grid.
    pub fn shape(&self) -> &[usize] {
        &self.shape
    }

    /// The spline degree.
    pub fn degree(&self) -> u32 {
        self.order - 1
    }

    /// The boundary mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// The per-axis coefficient error bound of the truncated route (0 when exact).
    pub fn truncation_bound(&self) -> f64 {
        self.bound
    }

    /// The coefficients `D_i` at the grid points (scipy's `spline_filter` output).
    pub fn coefficients(&self) -> ArrayViewD<'_, T> {
        let mut v = self.coeffs.view();
        for (a, &n) in self.shape.iter().enumerate() {
            v.slice_axis_inplace(ndarray::Axis(a), Slice::from(self.pad..self.pad + n));
        }
        v
    }

    /// The heap work space of one evaluation (weights, offsets, flags).
    fn scratch(&self) -> (Vec<T>, Vec<usize>, Vec<bool>) {
        let k = self.ndim() * self.order as usize;
        (vec![T::zero(); k], vec![0; k], vec![true; k])
    }

    fn check(&self, x: &[f64], deriv: &[u32]) -> Result<(), NdimageError> {
        if x.len() != self.ndim() {
            return Err(NdimageError::PointDimension {
                expected: self.ndim(),
                got: x.len(),
            });
        }
        if let Some(i) = x.iter().position(|c| !c.is_finite()) {
            return Err(NdimageError::NonFiniteCoordinate(i));
        }
        match deriv.iter().find(|&&d| d >= self.order) {
            Some(&d) => Err(NdimageError::DerivativeTooHigh {
                order: d,
                degree: self.degree(),
            }),
            None => Ok(()),
        }
    }

    /// `f(x)` at one point of `ndim` coordinates (sample indices). No heap
    /// allocation for `ndim × (degree + 1) ≤ 24` with `f64`/`f32` (MPFR
    /// values allocate their own limbs).
    pub fn eval(&self, x: &[f64]) -> Result<T, NdimageError> {
        const NONE: [u32; SMALL] = [0; SMALL];
        match NONE.get(..x.len()) {
            Some(zero) => self.eval_derivative(x, zero),
            None => self.eval_derivative(x, &vec![0; x.len()]),
        }
    }

    /// `∂^{d_0 + d_1 + …} f / ∂x_0^{d_0} ∂x_1^{d_1} …` at `x`, each
    /// `d_a ≤` degree (`deriv.len() = ndim`). Derivatives of the spline
    /// itself (under `nearest`, of the edge-extended signal's spline: zero
    /// far outside, where it is constant).
    ///
    /// **Method**: the derivative of each axis' B-spline weights in closed form
    /// ([`cell_derivatives_into`]), then the tensor sum. **Accuracy**: within 1e-9 relative of
    /// 256-bit MPFR central differences
    /// (`verify/tests/it/engine_properties.rs::derivatives_match_mpfr_finite_differences`).
    /// **Source**: the B-spline derivative recurrence (de Boor, *A Practical Guide to Splines*,
    /// ch. X); seed 000 eq 31 for the centred basis.
    pub fn eval_derivative(&self, x: &[f64], deriv: &[u32]) -> Result<T, NdimageError> {
        self.check(x, deriv)?;
        if deriv.len() != x.len() {
            return Err(NdimageError::PointDimension {
                expected: self.ndim(),
                got: deriv.len(),
            });
        }
        let k = self.ndim() * self.order as usize;
        if k <= SMALL {
            let mut w: [T; SMALL] = std::array::from_fn(|_| T::zero());
            let (mut off, mut inside) = ([0; SMALL], [true; SMALL]);
            let mut sc = Scratch {
                w: &mut w[..k],
                off: &mut off[..k],
                inside: &mut inside[..k],
            };
            return Ok(self.eval_in(x, deriv, &mut sc));
        }
        let (mut w, mut off, mut inside) = self.scratch();
        let mut sc = Scratch {
            w: &mut w,
            off: &mut off,
            inside: &mut inside,
        };
        Ok(self.eval_in(x, deriv, &mut sc))
    }

    /// The evaluation proper (inputs checked).
    fn eval_in(&self, x: &[f64], deriv: &[u32], sc: &mut Scratch<T>) -> T {
        let m = self.order as usize;
        for a in 0..self.ndim() {
            if m == 1 {
                let k = self.mode.nearest_index(x[a], self.shape[a]);
                sc.w[a] = T::one();
                sc.inside[a] = k.is_some();
                sc.off[a] = k.map_or(0, |k| (k + self.pad) * self.strides[a]);
                continue;
            }
            let xa = self.coordinate(x[a], a);
            let (first, u) = centred_cell(self.order, xa);
            let w = &mut sc.w[a * m..(a + 1) * m];
            cell_weights_into(self.order, deriv[a], u, w);
            let len = (self.shape[a] + 2 * self.pad) as i64;
            for l in 0..m {
                let i = first + l as i64 + self.pad as i64;
                let inside = (0..len).contains(&i);
                sc.inside[a * m + l] = inside;
                sc.off[a * m + l] = if inside {
                    i as usize * self.strides[a]
                } else {
                    0
                };
            }
        }
        let c = self.coeffs.as_slice().expect("standard layout");
        self.accumulate(c, sc, 0, 0, true)
    }

    /// `Σ_l w_a[l] · (axis a+1 sum at offset base + off_a[l])`, nested.
    fn accumulate(&self, c: &[T], sc: &Scratch<T>, axis: usize, base: usize, inside: bool) -> T {
        let m = self.order as usize;
        let range = axis * m..(axis + 1) * m;
        let last = axis + 1 == self.ndim();
        let mut sum = T::zero();
        for k in range {
            let ok = inside && sc.inside[k];
            let v = if last {
                if ok {
                    c[base + sc.off[k]].clone()
                } else {
                    self.cval.clone()
                }
            } else {
                self.accumulate(c, sc, axis + 1, base + sc.off[k], ok)
            };
            sum += sc.w[k].clone() * v;
        }
        sum
    }
}

/// The B-spline order and the prefilter of `opts` (its degree `2..=199`,
/// route and NaN policy) under `mode` with constant `cval`.
fn prefilter_of<T: Real + Send + Sync>(
    opts: &Options,
    mode: Mode,
    cval: f64,
) -> Result<(u32, Arc<LineFilter<T>>), NdimageError> {
    let order = spline_order(opts.degree)?;
    let filter = filter_cache::line_filter(opts.degree, mode, cval, opts.route, opts.nan_policy)?;
    Ok((order, filter))
}

/// The pad of given coefficients of B-spline order `order` under `mode`:
/// under `nearest` the point is not folded, and the window of a point
/// clamped to `order/2 + 1` outside reaches `order + 1` beyond.
fn given_pad(mode: Mode, order: u32) -> usize {
    if mode == Mode::Nearest {
        order as usize + 2
    } else {
        order as usize / 2 + 2
    }
}

/// The coefficients of `data` under `filter` (a symmetric mode), padded by
/// `pad` per side and extended by `mode` (`cval` where it gives none), in
/// one allocation:
/// the prefilter writes the compact coefficients into its front
/// ([`spline_filter_from`], samples widened as its first pass reads them),
/// which are then moved to their padded places and extended in place
/// (`padding.rs`). Bit for bit the coefficients of the filter-then-copy
/// route (`interpolant.rs::tests::one_array_coefficients_equal_filter_then_extension`).
fn prefiltered_padded<T, E>(
    data: &ArrayViewD<'_, E>,
    filter: &LineFilter<T>,
    mode: Mode,
    cval: &T,
    pad: usize,
) -> Result<ArrayD<T>, NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
{
    let shape = data.shape();
    let (padded, mut buf) = try_padded_zeros::<T>(shape, pad, "coefficients")?;
    let axes: Vec<usize> = (0..shape.len()).collect();
    let mut c = ArrayViewMutD::from_shape(IxDyn(shape), &mut buf[..data.len()])
        .expect("the data's size fits the padded one");
    spline_filter_from(data, &mut c, &axes, Some(filter))?;
    relocate_to_padded(&mut buf, shape, pad);
    extend_in_place(&mut buf, shape, mode, cval, pad);
    Ok(ArrayD::from_shape_vec(IxDyn(&padded), buf).expect("the padded shape"))
}

/// scipy's `map_coordinates(data, coordinates, order=degree, mode=…)`:
/// `coordinates` has shape `(ndim, count)` (one row per axis, as in scipy);
/// returns the `count` values. Builds an [`Interpolant`] and evaluates it.
///
///
/// **Accuracy**: within 16 ulps of max|value| of scipy 1.17.1 in every mode, degrees 1–5
/// (`verify/tests/it/engine_scipy.rs::map_coordinates_matches_scipy`), exact where scipy pads
/// (see [`Mode`]).
///
/// ```
/// use splinelab::prelude::*;
/// let data = ndarray::array![0.0, 1.0, 8.0, 27.0, 64.0];
/// let at = ndarray::array![[1.0, 2.5]];
/// let v: Vec<f64> = map_coordinates(&data, at.view(), Options::new(3, Mode::Mirror)).unwrap();
/// assert!((v[0] - 1.0).abs() < 1e-14);
/// ```
pub fn map_coordinates<T, S, D>(
    data: &ArrayBase<S, D>,
    coordinates: ArrayView2<'_, f64>,
    opts: Options,
) -> Result<Vec<T>, NdimageError>
where
    T: Real + Send + Sync,
    S: Data<Elem = T>,
    D: Dimension,
{
    let f = Interpolant::new(data, opts)?;
    let mut out = vec![T::zero(); coordinates.ncols()];
    f.eval_many(coordinates.t(), &mut out)?;
    Ok(out)
}

/// `w[l] = β_m^{(d)}(x − first − l)` of the cell position `u`
/// ([`centred_cell`]), `l = 0..m−1`: the weights of every evaluation path.
/// Values (`d = 0`) of orders 2 to 6 at `f64`/`f32` precision in closed
/// form (`weights.rs`: Horner in `u`, within `1.8 · 2^−53` of the exact
/// weight); derivatives, higher orders and MPFR by de Boor–Cox
/// ([`cell_derivatives_into`], reversed). `O(m)` resp. `O(m²)`.
pub(crate) fn cell_weights_into<T: Real>(m: u32, d: u32, u: f64, w: &mut [T]) {
    if d == 0 && T::BITS <= 53 {
        let mut f = [0.0; 6];
        if weights::closed_form_into(m, u, &mut f) {
            for (t, v) in w.iter_mut().zip(&f[..m as usize]) {
                *t = T::from_f64_exact(*v);
            }
            return;
        }
    }
    cell_derivatives_into(m, d, &T::from_f64_exact(u), w);
    w.reverse();
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ndimage::nd_prefilter::spline_filter;
    use crate::sspline::SplineFamily;
    use ndarray::{Array, Axis, IxDyn, Zip};

    /// Smooth deterministic samples of `shape` (also the in-place route's
    /// tests').
    pub(super) fn samples(shape: &[usize]) -> ArrayD<f64> {
        ArrayD::from_shape_fn(IxDyn(shape), |i| {
            i.slice()
                .iter()
                .enumerate()
                .map(|(a, &k)| ((k * (a + 2)) as f64 * 0.83 + a as f64).sin())
                .sum::<f64>()
        })
    }

    /// The coefficients padded in one allocation (computed at its front,
    /// moved up and extended in place) are those of the route that held
    /// two arrays: the prefilter into a compact array, then the copying
    /// extension by the mode ([`extend_padded`]), bit for bit; every
    /// symmetric mode, degrees 2 to 7, 1-D to 4-D.
    #[test]
    fn one_array_coefficients_equal_filter_then_extension() {
        for shape in [&[17usize][..], &[1], &[6, 9], &[5, 1, 7], &[3, 4, 2, 5]] {
            let a = samples(shape);
            for mode in [Mode::Mirror, Mode::Reflect, Mode::GridWrap] {
                for degree in 2..=7 {
                    let f = Interpolant::new(&a, Options::new(degree, mode)).unwrap();
                    let filter = LineFilter::new(
                        &SplineFamily::order(degree + 1).unwrap(),
                        mode,
                        0.0,
                        Route::Exact,
                    )
                    .unwrap();
                    let mut c = a.clone();
                    spline_filter(&mut c, &filter).unwrap();
                    let (want, _) = extend_padded(&c, mode, &0.0, f.pad).unwrap();
                    let bits = |x: &ArrayD<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&f.coeffs), bits(&want), "{shape:?} {mode} {degree}");
                }
            }
        }
    }

    /// `nearest` and `grid-constant` (the padded prefilter, now filled in
    /// place in one array) against the two-array route written out: the
    /// samples grown axis by axis into a new array, each lane through
    /// [`LineFilter::apply_padded`].
    #[test]
    fn padded_coefficients_equal_the_growing_arrays() {
        for shape in [&[13usize][..], &[5, 8], &[4, 1, 6]] {
            let a = samples(shape);
            for mode in [Mode::Nearest, Mode::GridConstant] {
                for degree in [2u32, 3, 5] {
                    let opts = Options {
                        cval: -0.5,
                        ..Options::new(degree, mode)
                    };
                    let f = Interpolant::new(&a, opts).unwrap();
                    let family = SplineFamily::order(degree + 1).unwrap();
                    let filter = LineFilter::new(&family, mode, -0.5, Route::Exact).unwrap();
                    let pad = f.pad;
                    let mut cur = a.clone();
                    for axis in 0..a.ndim() {
                        let mut dim = cur.raw_dim();
                        dim[axis] += 2 * pad;
                        let mut next = Array::from_elem(dim, 0.0);
                        Zip::from(cur.lanes(Axis(axis)))
                            .and(next.lanes_mut(Axis(axis)))
                            .for_each(|src, mut dst| {
                                let mut buf = vec![0.0; src.len() + 2 * pad];
                                buf[pad..pad + src.len()].copy_from_slice(&src.to_vec());
                                filter.apply_padded(&mut buf, pad, &mut Vec::new());
                                dst.iter_mut().zip(buf).for_each(|(d, s)| *d = s);
                            });
                        cur = next;
                    }
                    let bits = |x: &ArrayD<f64>| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&f.coeffs), bits(&cur), "{shape:?} {mode} {degree}");
                }
            }
        }
    }
}
