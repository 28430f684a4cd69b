//! The not-a-knot tensor-product spline interpolating values on a
//! rectilinear grid — scipy.interpolate's `RegularGridInterpolator(method=
//! "cubic" | "quintic")`, `interpn` and `make_ndbspl`, solved exactly.
//!
//! **Method.** The collocation matrix of the tensor-product B-splines at
//! the grid is the Kronecker product `A_0 ⊗ … ⊗ A_{d−1}` of the 1-D
//! collocation matrices `(A_a)_{ij} = B^{(a)}_j(x^{(a)}_i)` (de Boor,
//! *A Practical Guide to Splines*, XVII, "tensor product"), so the
//! coefficients are `C = (A_0^{−1} ⊗ … ⊗ A_{d−1}^{−1}) V`: one banded solve
//! per grid line along each axis in turn ([`super::BandedLu`], factored once
//! per axis), the same spline scipy's `make_ndbspl` approximates with a
//! sparse iterative solve (`gcrotmk`, `atol = 1e-6`) of the whole
//! `N × N` system. Lines are solved in blocks of [`LANES`] side by side
//! (one contiguous row per node), in parallel.
//!
//! **Cost.** `O(N·m·Σ_a (2kl_a + ku_a))` time, `N = Π n_a` grid points of `m`
//! values each; memory: the coefficients (`N·m` scalars) and one block of
//! `n_a × LANES` scalars per thread — independent of the other axes.
//!
//! **Error.** Per axis the computed solve is exact for a matrix within
//! `γ_{3w}·G_a + γ_{3k}` of `A_a` in the ∞-norm (`G_a` the LU growth, the
//! second term the rounding of the B-spline values; `‖A_a‖∞ = 1` by the
//! partition of unity), which the solve amplifies by
//! `κ_a = ‖A_a^{−1}‖∞`; the later axes' solves amplify by their `κ_b`.
//! So, to first order in the unit roundoff `u`,
//! `max|Ĉ − C| ≤ Σ_a κ_a (γ_{3w_a} G_a + γ_{3k}) M_a Π_{b>a} κ_b`, with
//! `M_a` the largest coefficient after axis `a` (measured). `κ_a` is
//! computed exactly by one solve: a nonsingular totally nonnegative matrix
//! has a checkerboard inverse, so `‖A^{−1}‖∞ = ‖A^{−1}σ‖∞`, `σ_j = (−1)^j`
//! (Gantmacher–Krein; Higham §8.3 for the trick with sign-regular
//! inverses); Hager's estimator (Higham Alg. 15.4) is taken where larger.
//! [`GridSpline::error_bound`] adds the evaluation's rounding
//! ([`super::tensor_eval`]): a bound on `|ŝ(x) − s(x)|` inside the grid,
//! where `s` is the exact spline of the given nodes and values.

use super::banded_lu::BandedLu;
use super::evaluate::{MAX_DIMS, tensor_eval};
use super::layout::Layout;
use super::{GridAxis, GriddedError, MAX_GRID_DEGREE};
use crate::ndimage::alloc::{checked_len, try_with_capacity, try_zeros};
use crate::ndimage::samples::Sample;
use crate::scalar::Real;
use ndarray::{ArrayView3, ArrayViewD, ArrayViewMut2, ArrayViewMut3, Axis, Zip};
use rayon::prelude::*;

/// Grid lines solved side by side: rows of 32 lanes (256 bytes of f64).
pub const LANES: usize = 32;

/// Below this many coefficients the solves run on the calling thread.
const PARALLEL_FROM: usize = 1 << 15;

/// What the solve of one axis' lines amplifies and adds.
#[derive(Debug, Clone)]
pub struct AxisConditioning {
    /// `κ = ‖A^{−1}‖∞` of the axis' collocation matrix (`‖A‖∞ = 1`, so this
    /// is its ∞-norm condition number).
    pub kappa: f64,
    /// The LU growth `G` ([`BandedLu::growth`]).
    pub growth: f64,
    /// The longest inner product of the solve (`w` of `γ_{3w}`).
    pub inner: usize,
    /// Whether the factorization exchanged rows.
    pub pivoted: bool,
    /// The largest |coefficient| after this axis' solves.
    pub max_after: f64,
}

/// The not-a-knot spline of odd degree `k` interpolating `m` values at
/// every point of a rectilinear grid, with the bound of its rounding.
#[derive(Debug, Clone)]
pub struct GridSpline<T: Real> {
    axes: Vec<GridAxis<T>>,
    coefficients: Vec<T>,
    batch: usize,
    conditioning: Vec<AxisConditioning>,
}

impl<T: Real> GridSpline<T> {
    /// The spline of degree `degree` (odd, `1..=`[`MAX_GRID_DEGREE`])
    /// through `values` (shape `n_0 × … × n_{d−1} × m`, any strides, any
    /// sample type widened exactly) at the grid `nodes` (strictly
    /// ascending per axis, `n_a ≥ degree + 1`).
    ///
    /// ```
    /// use splinelab::gridded::GridSpline;
    /// use ndarray::Array3;
    /// // A cubic polynomial in x times a quadratic in y is its own not-a-knot
    /// // cubic spline: reproduced between the nodes, on any spacing.
    /// let (x, y) = (vec![0.0, 0.3, 1.0, 1.2, 2.0, 2.1], vec![-1.0, 0.5, 0.7, 3.0]);
    /// let f = |a: f64, b: f64| (a * a * a - a) * (b * b + 1.0);
    /// let v = Array3::from_shape_fn((6, 4, 1), |(i, j, _)| f(x[i], y[j]));
    /// let s = GridSpline::interpolate(vec![x, y], v.view().into_dyn(), 3).unwrap();
    /// let at = s.eval(&[1.7, 2.2], &[]).unwrap();
    /// assert!((at[0] - f(1.7, 2.2)).abs() < 1e-12);
    /// // The rounding bound: values up to 72, κ of the axes 6.8 and 35.
    /// assert!(s.error_bound() < 1e-10);
    /// ```
    pub fn interpolate<S: Sample<T>>(
        nodes: Vec<Vec<T>>,
        values: ArrayViewD<'_, S>,
        degree: usize,
    ) -> Result<Self, GriddedError> {
        let d = nodes.len();
        let grid: Vec<usize> = nodes.iter().map(Vec::len).collect();
        if d == 0 || d > MAX_DIMS || values.ndim() != d + 1 || values.shape()[..d] != grid[..] {
            return Err(GriddedError::Shape {
                grid,
                got: values.shape().to_vec(),
            });
        }
        let axes = nodes
            .into_iter()
            .enumerate()
            .map(|(a, x)| GridAxis::not_a_knot(x, degree, a))
            .collect::<Result<Vec<_>, _>>()?;
        let batch = values.shape()[d];
        let mut coefficients = try_zeros(
            checked_len(values.shape(), "spline coefficients")?,
            "spline coefficients",
        )?;
        let shape_error = || GriddedError::Shape {
            grid: grid.clone(),
            got: values.shape().to_vec(),
        };
        let mut out = ndarray::ArrayViewMutD::from_shape(values.shape(), &mut coefficients[..])
            .map_err(|_| shape_error())?;
        // In the values' logical order, whatever their strides: no copy.
        Zip::from(&mut out)
            .and(&values)
            .par_for_each(|o, s| *o = s.widen());
        let mut spline = Self {
            axes,
            coefficients,
            batch,
            conditioning: Vec::with_capacity(d),
        };
        for a in 0..d {
            let c = spline.solve_axis(a)?;
            spline.conditioning.push(c);
        }
        Ok(spline)
    }

    /// Solves every line along axis `a` in place.
    fn solve_axis(&mut self, a: usize) -> Result<AxisConditioning, GriddedError> {
        let axis = &self.axes[a];
        let n = axis.len();
        let lu = collocation_lu(axis, a)?;
        let kappa = inverse_norm(&lu);
        let outer: usize = self.axes[..a].iter().map(GridAxis::len).product();
        let inner = self.axes[a + 1..]
            .iter()
            .map(GridAxis::len)
            .product::<usize>()
            * self.batch;
        let total = self.coefficients.len();
        let mut view = ArrayViewMut3::from_shape((outer, n, inner), &mut self.coefficients[..])
            .map_err(|_| GriddedError::Shape {
                grid: vec![outer, n, inner],
                got: vec![total],
            })?;
        // Blocks of LANES lanes: columns of each (n × inner) slab, or whole
        // lines, LANES / inner of them side by side.
        let mut slabs: Vec<ArrayViewMut2<'_, T>> = Vec::new();
        let blocks: Vec<ArrayViewMut3<'_, T>> = if inner >= LANES {
            slabs.extend(view.axis_iter_mut(Axis(0)));
            slabs
                .iter_mut()
                .flat_map(|slab| slab.axis_chunks_iter_mut(Axis(1), LANES))
                .map(|b| b.insert_axis(Axis(0)))
                .collect()
        } else {
            view.axis_chunks_iter_mut(Axis(0), (LANES / inner.max(1)).max(1))
                .collect()
        };
        let max_after = if total >= PARALLEL_FROM {
            blocks
                .into_par_iter()
                .map_init(Vec::new, |buf, b| solve_block(&lu, b, buf))
                .try_reduce(T::zero, |x, y| Ok(x.max(y)))?
        } else {
            let mut buf = Vec::new();
            blocks
                .into_iter()
                .map(|b| solve_block(&lu, b, &mut buf))
                .try_fold(T::zero(), |m, r| Ok::<_, GriddedError>(m.max(r?)))?
        };
        Ok(AxisConditioning {
            kappa: kappa.to_f64(),
            growth: lu.growth().to_f64(),
            inner: lu.inner_length(),
            pivoted: lu.pivoted(),
            max_after: max_after.to_f64(),
        })
    }

    /// The axes (nodes and knots).
    pub fn axes(&self) -> &[GridAxis<T>] {
        &self.axes
    }

    /// The B-spline coefficients, C order, shape grid × `m`.
    pub fn coefficients(&self) -> &[T] {
        &self.coefficients
    }

    /// `m`, the values per grid point.
    pub fn batch(&self) -> usize {
        self.batch
    }

    /// The degree.
    pub fn degree(&self) -> usize {
        self.axes[0].degree()
    }

    /// What each axis' solve amplified ([`AxisConditioning`]).
    pub fn conditioning(&self) -> &[AxisConditioning] {
        &self.conditioning
    }

    /// A bound on `max_j |ĉ_j − c_j|`, the computed coefficients against
    /// those of the exact spline (first order in `u`; module doc).
    pub fn coefficient_error(&self) -> f64 {
        let u = T::unit_roundoff().to_f64();
        let k = self.degree();
        let mut total = 0.0;
        for (a, c) in self.conditioning.iter().enumerate() {
            let local =
                c.kappa * (gamma(3 * c.inner, u) * c.growth + gamma(3 * k, u)) * c.max_after;
            let later: f64 = self.conditioning[a + 1..].iter().map(|b| b.kappa).product();
            total += local * later;
        }
        total
    }

    /// A bound on `|ŝ(x) − s(x)|` for `x` inside the grid: the coefficient
    /// error plus the evaluation's rounding `γ_{3kd + d + (k+1)^d} max|ĉ|`.
    pub fn error_bound(&self) -> f64 {
        let (k, d) = (self.degree(), self.axes.len());
        let terms = (k + 1).saturating_pow(d as u32);
        let max_c = self.conditioning.last().map_or(0.0, |c| c.max_after);
        let u = T::unit_roundoff().to_f64();
        self.coefficient_error() + gamma(3 * k * d + d + terms, u) * max_c
    }

    /// The spline (or its partial derivative `∂^{ν_0…ν_{d−1}}`; `nu` empty:
    /// values) at the points `x` (`n × d`, row-major) into `out` (`n × m`).
    pub fn eval_into(&self, x: &[T], nu: &[usize], out: &mut [T]) -> Result<(), GriddedError> {
        let d = self.axes.len();
        if !x.len().is_multiple_of(d) || (!nu.is_empty() && nu.len() != d) {
            return Err(GriddedError::Dimension {
                expected: d,
                got: if nu.is_empty() { x.len() % d } else { nu.len() },
            });
        }
        if out.len() != x.len() / d * self.batch {
            return Err(GriddedError::Dimension {
                expected: x.len() / d * self.batch,
                got: out.len(),
            });
        }
        let mut shape: Vec<usize> = self.axes.iter().map(GridAxis::len).collect();
        shape.push(self.batch);
        let layout = Layout::c_order(&shape);
        tensor_eval(
            &self.axes,
            &self.coefficients,
            &layout,
            self.batch,
            x,
            nu,
            out,
        );
        Ok(())
    }

    /// [`GridSpline::eval_into`] into a new vector.
    pub fn eval(&self, x: &[T], nu: &[usize]) -> Result<Vec<T>, GriddedError> {
        let mut out = vec![T::zero(); x.len() / self.axes.len() * self.batch];
        self.eval_into(x, nu, &mut out)?;
        Ok(out)
    }
}

/// `γ_n = n u / (1 − n u)` (Higham §3.1).
fn gamma(n: usize, u: f64) -> f64 {
    let nu = n as f64 * u;
    nu / (1.0 - nu)
}

/// The collocation matrix `(B_j(x_i))` of an axis, factored.
pub(crate) fn collocation_lu<T: Real>(
    axis: &GridAxis<T>,
    a: usize,
) -> Result<BandedLu<T>, GriddedError> {
    let (n, k) = (axis.len(), axis.degree());
    let mut rows: Vec<(usize, [T; MAX_GRID_DEGREE + 1])> = Vec::with_capacity(n);
    let (mut kl, mut ku) = (0usize, 0usize);
    for x in axis.nodes() {
        let mut w: [T; MAX_GRID_DEGREE + 1] = std::array::from_fn(|_| T::zero());
        let s = axis.weights(x, 0, &mut w);
        let i = rows.len();
        kl = kl.max(i.saturating_sub(s - k));
        ku = ku.max(s.saturating_sub(i));
        rows.push((s, w));
    }
    BandedLu::factor(n, kl, ku, |i, j| {
        let (s, w) = &rows[i];
        if j + k >= *s && j <= *s {
            w[j + k - s].clone()
        } else {
            T::zero()
        }
    })
    .map_err(|index| GriddedError::Singular { axis: a, index })
}

/// `‖A^{−1}‖∞`: `‖A^{−1}σ‖∞` (exact for the checkerboard inverse of a
/// totally nonnegative matrix), or Hager's estimate where that is larger.
fn inverse_norm<T: Real>(lu: &BandedLu<T>) -> T {
    let n = lu.len();
    let mut y: Vec<T> = (0..n)
        .map(|j| if j % 2 == 0 { T::one() } else { -T::one() })
        .collect();
    lu.solve_lanes(&mut y, 1);
    let checker = y.iter().fold(T::zero(), |m, v| m.max(v.clone().abs()));
    checker.max(hager(lu))
}

/// Hager's estimate of `‖A^{−1}‖∞ = ‖A^{−T}‖₁` (Higham Alg. 15.4, five steps at most).
fn hager<T: Real>(lu: &BandedLu<T>) -> T {
    let n = lu.len();
    let mut x = vec![T::one() / T::from_int(n as i64); n];
    let mut est = T::zero();
    for step in 0..5 {
        let mut y = x.clone();
        lu.solve_transpose(&mut y); // A^{−T} x
        let norm = y.iter().fold(T::zero(), |s, v| s + v.clone().abs());
        if step > 0 && norm <= est {
            break;
        }
        est = norm;
        let mut z: Vec<T> = y
            .iter()
            .map(|v| if *v >= T::zero() { T::one() } else { -T::one() })
            .collect();
        lu.solve_lanes(&mut z, 1); // (A^{−T})ᵀ ξ
        let (j, zj) = z
            .iter()
            .enumerate()
            .fold((0, T::zero()), |(bj, bv), (i, v)| {
                if v.clone().abs() > bv {
                    (i, v.clone().abs())
                } else {
                    (bj, bv)
                }
            });
        let ztx = z
            .iter()
            .zip(&x)
            .fold(T::zero(), |s, (a, b)| s + a.clone() * b);
        if zj <= ztx {
            break;
        }
        x = vec![T::zero(); n];
        x[j] = T::one();
    }
    est
}

/// Gathers a block of lines (`g × n × w` view: `g·w` lanes, `n` nodes),
/// solves it, scatters it back; returns the largest |coefficient|.
fn solve_block<T: Real>(
    lu: &BandedLu<T>,
    mut block: ArrayViewMut3<'_, T>,
    buf: &mut Vec<T>,
) -> Result<T, GriddedError> {
    let (g, n, w) = block.dim();
    let lanes = g * w;
    if buf.len() < n * lanes {
        buf.clear();
        let mut fresh = try_with_capacity(n * lanes, "spline line block")?;
        fresh.resize(n * lanes, T::zero());
        *buf = fresh;
    }
    let buf = &mut buf[..n * lanes];
    for_each_lane(block.view(), lanes, |at, v| buf[at] = v.clone());
    lu.solve_lanes(buf, lanes);
    let mut max = T::zero();
    for (gi, mut plane) in block.outer_iter_mut().enumerate() {
        let (mut i, mut c) = (0, 0);
        for v in plane.iter_mut() {
            let x = &buf[i * lanes + gi * w + c];
            max = max.max(x.clone().abs());
            *v = x.clone();
            c += 1;
            if c == w {
                c = 0;
                i += 1;
            }
        }
    }
    Ok(max)
}

/// Calls `f(i·lanes + g·w + c, &block[g, i, c])` in the block's memory order.
fn for_each_lane<T>(block: ArrayView3<'_, T>, lanes: usize, mut f: impl FnMut(usize, &T)) {
    let w = block.dim().2;
    for (gi, plane) in block.outer_iter().enumerate() {
        let (mut i, mut c) = (0, 0);
        for v in plane.iter() {
            f(i * lanes + gi * w + c, v);
            c += 1;
            if c == w {
                c = 0;
                i += 1;
            }
        }
    }
}
