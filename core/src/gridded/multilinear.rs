//! The multilinear interpolant on a rectilinear grid, in scipy's floating-point
//! operations: `RegularGridInterpolator(method="linear")` and its
//! `"nearest"`, bit for bit.
//!
//! The multilinear interpolant is exact arithmetic's one object, but its
//! rounded values depend on how the weights are formed and summed. scipy
//! (1.17, `_rgi_cython.find_indices`, `_evaluate_linear`,
//! `evaluate_linear_2d`) forms, per axis, the cell `i` (`x_i ≤ x < x_{i+1}`,
//! the last cell closed on the right, the end cells continued outside) and
//! the normalised distance `y = (x − x_i) / (x_{i+1} − x_i)`; the corner
//! weights are `1 − y` and `y`, multiplied over the axes left to right, and
//! the `2^d` corners are summed from zero, axis 0 slowest and the lower
//! node first. At a node `y` is exactly 0, so the interpolant returns the
//! sample itself: the B-spline form `(x_{i+1} − x)/h`, `(x − x_i)/h` does
//! not (`(3.4 − 1.5)/1.9 ≠ 1` in floating point).

use super::GridAxis;
use super::evaluate::over_points;
use super::layout::Layout;
use crate::ndimage::samples::Sample;
use crate::scalar::Real;

/// Points a parallel task evaluates (fewer run on the calling thread).
const POINTS_PER_TASK: usize = 1024;

/// How each corner's term is formed: scipy's general route multiplies the
/// weights first (`v · (w_0 · w_1 ⋯)`), its 2-D kernel for float64 and
/// complex128 values multiplies the value by each weight in turn
/// (`(v · w_0) · w_1`). The sums agree in exact arithmetic only.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CornerProduct {
    /// `v · (w_0 · w_1 ⋯ w_{d−1})`: scipy's `_evaluate_linear`.
    WeightsFirst,
    /// `((v · w_0) · w_1) ⋯`: scipy's `evaluate_linear_2d`.
    ValueFirst,
}

/// scipy's cell and normalised distance of `x` on `axis` (at least two
/// nodes): `(i, (x − x_i) / (x_{i+1} − x_i))`, with `i` the cell of
/// [`GridAxis::cell`] (the last cell closed on the right, points beyond the
/// ends in the end cells, so `y < 0` or `y > 1` there). A NaN `x` gives a
/// NaN distance.
///
/// ```
/// use splinelab::gridded::{GridAxis, multilinear::cell_distance};
/// let axis = GridAxis::not_a_knot(vec![1.5, 3.4, 6.7, 7.0, 32.0], 1, 0).unwrap();
/// assert_eq!(cell_distance(&axis, &3.4), (1, 0.0)); // a node: exactly 0
/// assert_eq!(cell_distance(&axis, &32.0), (3, 1.0)); // the last node: the last cell
/// ```
pub fn cell_distance<T: Real>(axis: &GridAxis<T>, x: &T) -> (usize, T) {
    let i = axis.cell(x);
    let g = axis.nodes();
    (i, (x.clone() - &g[i]) / (g[i + 1].clone() - &g[i]))
}

/// The node scipy's `"nearest"` picks on `axis`: the cell's lower node
/// where `y ≤ 1/2`, else the upper (ties to the lower). A NaN coordinate
/// gives node 0 (scipy's cell −1 and `numpy.where(nan <= .5, i, i + 1)`);
/// an axis of one node gives 0.
pub fn nearest_node<T: Real>(axis: &GridAxis<T>, x: &T) -> usize {
    if axis.len() < 2 || x.partial_cmp(x).is_none() {
        return 0;
    }
    let (i, y) = cell_distance(axis, x);
    if y <= T::from_f64_exact(0.5) {
        i
    } else {
        i + 1
    }
}

/// The `2^d` corners of a grid cell in scipy's order (axis 0 slowest, the
/// lower node first): for corner `c`, bit `d − 1 − a` is its node on axis
/// `a`, and `offsets[c]` its distance in elements from the cell's first
/// sample. The same for every point of a grid, so made once a call.
#[derive(Debug, Clone)]
pub struct Corners {
    strides: Vec<isize>,
    offsets: Vec<isize>,
}

impl Corners {
    /// The corners of a cell of `d` axes with element `strides`.
    pub fn new(strides: &[isize], d: usize) -> Self {
        let offsets = (0..1usize << d)
            .map(|c| {
                (0..d)
                    .map(|a| ((c >> (d - 1 - a)) & 1) as isize * strides[a])
                    .sum()
            })
            .collect();
        Self {
            strides: strides[..d].to_vec(),
            offsets,
        }
    }
}

/// Corner `c`'s node on axis `a` of `d`: 0 lower, 1 upper.
#[inline(always)]
fn node(c: usize, a: usize, d: usize) -> usize {
    (c >> (d - 1 - a)) & 1
}

/// The multilinear interpolant of `m` sample columns at one point `x`
/// (one coordinate per axis), in scipy's operations: `acc[b]` for column
/// `b`, with `sample(offset, b)` the sample at node offset
/// `Σ_a i_a · strides[a]`. `w` is scratch of at least `d` entries.
///
/// **Formula**: `Σ_corners v_c · Π_a w_a(c)`, `w_a = 1 − y_a` at the lower
/// node and `y_a` at the upper (scipy's `_evaluate_linear`), each term's
/// product as `order` says, summed from `0.0` in scipy's corner order.
/// **Cost** `2^d (d + m)` multiplications. **Accuracy**: at a node the
/// sample itself; inside the grid every weight is in `[0, 1]` and the
/// weights sum to 1 to rounding, so the result is within
/// `γ_{2d+2^d} · max|v|` of the exact interpolant of the samples
/// (Higham, *Accuracy and Stability*, (3.4) and §4.2). Outside the grid
/// the weights grow as the distance does (linear extrapolation).
///
/// ```
/// use splinelab::gridded::{GridAxis, multilinear::{corner_sum, Corners, CornerProduct}};
/// let axis = GridAxis::not_a_knot(vec![1.5, 3.4, 6.7, 7.0, 32.0], 1, 0).unwrap();
/// let v = [0.0, 1.0, 2.0, 3.0, 4.0];
/// let (corners, mut w, mut acc) = (Corners::new(&[1], 1), [[0.0; 2]], [0.0]);
/// let order = CornerProduct::WeightsFirst;
/// corner_sum(&[axis], &corners, &[3.4], order, |o, _| v[o as usize], &mut w, &mut acc);
/// assert_eq!(acc[0], 1.0); // the sample, bit for bit
/// ```
#[inline(always)]
pub fn corner_sum<T: Real>(
    axes: &[GridAxis<T>],
    corners: &Corners,
    x: &[T],
    order: CornerProduct,
    sample: impl Fn(isize, usize) -> T,
    w: &mut [[T; 2]],
    acc: &mut [T],
) {
    let d = axes.len();
    let mut base = 0isize;
    for (a, (axis, wa)) in axes.iter().zip(w.iter_mut()).enumerate() {
        let (i, y) = cell_distance(axis, &x[a]);
        base += i as isize * corners.strides[a];
        *wa = [T::one() - &y, y];
    }
    for v in acc.iter_mut() {
        *v = T::zero();
    }
    let w = &w[..d];
    match order {
        CornerProduct::WeightsFirst => {
            for (c, &offset) in corners.offsets.iter().enumerate() {
                let mut weight = w[0][node(c, 0, d)].clone();
                for (a, wa) in w.iter().enumerate().skip(1) {
                    weight *= &wa[node(c, a, d)];
                }
                for (b, y) in acc.iter_mut().enumerate() {
                    *y += sample(base + offset, b) * &weight;
                }
            }
        }
        CornerProduct::ValueFirst => {
            for (c, &offset) in corners.offsets.iter().enumerate() {
                for (b, y) in acc.iter_mut().enumerate() {
                    let mut term = sample(base + offset, b);
                    for (a, wa) in w.iter().enumerate() {
                        term *= &wa[node(c, a, d)];
                    }
                    *y += term;
                }
            }
        }
    }
}

/// `out[p·m + b]`: the multilinear interpolant of the `m = batch` sample
/// columns laid out as `layout` says (grid × m, any strides) at the points
/// `x` (`n × d`, row-major), in scipy's operations ([`corner_sum`]). A NaN
/// coordinate gives NaN. **Cost** `2^d (d + m)` multiplications a point,
/// points in parallel.
pub fn multilinear_eval<T: Real, S: Sample<T>>(
    axes: &[GridAxis<T>],
    samples: &[S],
    layout: &Layout,
    batch: usize,
    points: &[T],
    order: CornerProduct,
    out: &mut [T],
) {
    let d = axes.len();
    if d == 0 || batch == 0 {
        return;
    }
    let corners = Corners::new(&layout.strides, d);
    let step_b = layout.strides[d];
    let sample = |offset: isize, b: usize| samples[layout.at(offset + b as isize * step_b)].widen();
    // One to three axes with their count known at compile time (the loops
    // over axes and corners unrolled: the same operations in the same order).
    match d {
        1 => fixed::<T, 1>(&axes[..1], &corners, points, batch, order, sample, out),
        2 => fixed::<T, 2>(&axes[..2], &corners, points, batch, order, sample, out),
        3 => fixed::<T, 3>(&axes[..3], &corners, points, batch, order, sample, out),
        _ => over_points(points, d, out, batch, POINTS_PER_TASK, |pts, o| {
            let mut w = vec![[T::zero(), T::zero()]; d];
            for (x, acc) in pts.chunks_exact(d).zip(o.chunks_exact_mut(batch)) {
                corner_sum(axes, &corners, x, order, sample, &mut w, acc);
            }
        }),
    }
}

/// [`multilinear_eval`]'s loop for `D` axes.
fn fixed<T: Real, const D: usize>(
    axes: &[GridAxis<T>],
    corners: &Corners,
    points: &[T],
    batch: usize,
    order: CornerProduct,
    sample: impl Fn(isize, usize) -> T + Sync + Send + Copy,
    out: &mut [T],
) {
    over_points(points, D, out, batch, POINTS_PER_TASK, |pts, o| {
        let mut w: [[T; 2]; D] = std::array::from_fn(|_| [T::zero(), T::zero()]);
        for (x, acc) in pts.chunks_exact(D).zip(o.chunks_exact_mut(batch)) {
            corner_sum(&axes[..D], corners, x, order, sample, &mut w, acc);
        }
    });
}

/// `out[p·m + b]`: the sample column `b` at scipy's nearest node of each
/// point ([`nearest_node`] per axis), copied as it is (any element type).
/// A NaN coordinate reads node 0 on its axis (scipy then writes NaN).
/// **Cost** `O(d log n + m)` a point.
pub fn nearest_gather<T: Real, S: Copy + Send + Sync>(
    axes: &[GridAxis<T>],
    samples: &[S],
    layout: &Layout,
    batch: usize,
    points: &[T],
    out: &mut [S],
) {
    let d = axes.len();
    if d == 0 || batch == 0 {
        return;
    }
    let step_b = layout.strides[d];
    over_points(points, d, out, batch, POINTS_PER_TASK, |pts, o| {
        for (x, row) in pts.chunks_exact(d).zip(o.chunks_exact_mut(batch)) {
            let offset: isize = (0..d)
                .map(|a| nearest_node(&axes[a], &x[a]) as isize * layout.strides[a])
                .sum();
            for (b, y) in row.iter_mut().enumerate() {
                *y = samples[layout.at(offset + b as isize * step_b)];
            }
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use rug::Rational;

    fn axis(x: &[f64]) -> GridAxis<f64> {
        GridAxis::not_a_knot(x.to_vec(), 1, 0).unwrap()
    }

    /// scipy's `find_interval_ascending` written out from its definition:
    /// the largest `i ≤ n − 2` with `x_i ≤ x`, 0 below the grid.
    fn scipy_interval(x: &[f64], v: f64) -> usize {
        let n = x.len();
        if v >= x[n - 1] {
            return n - 2;
        }
        (0..n - 1).rev().find(|&i| x[i] <= v).unwrap_or(0)
    }

    #[test]
    fn nodes_give_their_samples_on_non_uniform_grids() {
        // astropy's case: 3.4 on [1.5, 3.4, 6.7, 7, 32] is the sample 1.0.
        let x = [1.5, 3.4, 6.7, 7.0, 32.0];
        let a = axis(&x);
        let v: Vec<f64> = (0..5).map(f64::from).collect();
        for (i, xi) in x.iter().enumerate() {
            let (mut w, mut acc) = ([[0.0; 2]], [f64::NAN]);
            corner_sum(
                std::slice::from_ref(&a),
                &Corners::new(&[1], 1),
                &[*xi],
                CornerProduct::WeightsFirst,
                |o, _| v[o as usize],
                &mut w,
                &mut acc,
            );
            assert_eq!(acc[0], v[i]);
        }
    }

    #[test]
    fn cells_are_scipys_intervals() {
        let x = [-3.0, -1.0, 0.25, 0.5, 2.0, 7.5];
        let a = axis(&x);
        for v in [
            -10.0, -3.0, -2.0, -1.0, 0.0, 0.25, 0.3, 0.5, 1.0, 2.0, 7.0, 7.5, 9.0,
        ] {
            assert_eq!(cell_distance(&a, &v).0, scipy_interval(&x, v), "at {v}");
        }
    }

    #[test]
    fn a_2d_value_is_the_exact_bilinear_to_rounding() {
        // Against the exact rational bilinear interpolant of the samples.
        let (x, y) = ([0.0, 0.3, 1.7, 2.0], [-1.0, 0.1, 4.0]);
        let axes = [axis(&x), axis(&y)];
        let v = |i: usize, j: usize| ((i * 7 + j * 3) % 5) as f64 - 1.5;
        let (px, py) = (1.1, 2.5);
        for order in [CornerProduct::WeightsFirst, CornerProduct::ValueFirst] {
            let (mut w, mut acc) = ([[0.0; 2]; 2], [0.0]);
            corner_sum(
                &axes,
                &Corners::new(&[3, 1], 2),
                &[px, py],
                order,
                |o, _| v(o as usize / 3, o as usize % 3),
                &mut w,
                &mut acc,
            );
            let r = |f: f64| Rational::from_f64(f).unwrap();
            let ty = (r(px) - r(0.3)) / (r(1.7) - r(0.3));
            let tz = (r(py) - r(0.1)) / (r(4.0) - r(0.1));
            let one = Rational::from(1);
            let exact = r(v(1, 1)) * (one.clone() - &ty) * (one.clone() - &tz)
                + r(v(1, 2)) * (one.clone() - &ty) * &tz
                + r(v(2, 1)) * &ty * (one.clone() - &tz)
                + r(v(2, 2)) * &ty * &tz;
            assert!((acc[0] - exact.to_f64()).abs() <= 16.0 * f64::EPSILON * 3.5);
        }
    }

    #[test]
    fn nearest_ties_go_to_the_lower_node() {
        let a = axis(&[0.0, 1.0, 3.0]);
        assert_eq!(nearest_node(&a, &0.5), 0);
        assert_eq!(nearest_node(&a, &0.5000000000000001), 1);
        assert_eq!(nearest_node(&a, &2.0), 1);
        assert_eq!(nearest_node(&a, &-5.0), 0);
        assert_eq!(nearest_node(&a, &50.0), 2);
        assert_eq!(nearest_node(&a, &f64::NAN), 0);
    }
}
