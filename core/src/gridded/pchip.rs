//! scipy's `RegularGridInterpolator(method="pchip")`: PCHIP along the last
//! axis, then along each axis before it on the results (the recursive
//! route of scipy's `_evaluate_spline`), computed locally.
//!
//! **Method.** The 1-D PCHIP (Fritsch & Carlson 1980; Fritsch & Butland
//! 1984's weighted harmonic mean of the neighbouring slopes, Moler's
//! one-sided three-point end slopes, *Numerical Computing with MATLAB* 3.6)
//! on cell `[x_i, x_{i+1}]` depends on the samples `i − 1 ..= i + 2` only
//! (`0 ..= 2` and `n − 3 ..= n − 1` at the ends), so the recursive
//! interpolation at a point needs a window of at most four samples per
//! axis: `4^d` samples a point, where scipy's route builds PCHIPs over the
//! whole grid for every point. The same formulas in the same order as
//! scipy's `PchipInterpolator` (the cell's Hermite cubic in power form
//! about `x_i`, summed from the constant term), so the values agree to a
//! few ulps. Outside the grid the end cells' cubics are continued.
//!
//! **Cost** `O(4^d·m)` a point. PCHIP is not linear in the data: no
//! coefficient array is built.

use super::GridAxis;
use super::evaluate::{next_index, over_points};
use super::layout::Layout;
use crate::ndimage::samples::Sample;
use crate::scalar::Real;

const POINTS_PER_TASK: usize = 256;

/// `out[p·m + b]`: the recursive PCHIP of the `m = batch` value arrays
/// `values` (grid × `m`, laid out as `layout` says) at the points `x` (`n × d`).
/// `axes` carry the nodes (any degree: only nodes and cells are used).
///
/// ```
/// use splinelab::gridded::{GridAxis, Layout, pchip_eval};
/// // Monotone data stays monotone, and PCHIP meets the data at the nodes.
/// let x = vec![0.0, 1.0, 1.5, 4.0, 5.0];
/// let y = [0.0, 0.1, 3.0, 3.1, 9.0];
/// let axes = [GridAxis::not_a_knot(x, 1, 0).unwrap()];
/// let at: Vec<f64> = (0..=50).map(|i| 0.1 * i as f64).collect();
/// let mut out = vec![0.0; at.len()];
/// pchip_eval(&axes, &y, &Layout::c_order(&[5, 1]), 1, &at, &mut out);
/// assert!(out.windows(2).all(|p| p[1] >= p[0]));
/// assert!((out[15] - 3.0).abs() < 1e-15 && (out[40] - 3.1).abs() < 1e-15);
/// ```
pub fn pchip_eval<T: Real, S: Sample<T>>(
    axes: &[GridAxis<T>],
    values: &[S],
    layout: &Layout,
    batch: usize,
    points: &[T],
    out: &mut [T],
) {
    let d = axes.len();
    if d == 0 || batch == 0 {
        return;
    }
    over_points(points, d, out, batch, POINTS_PER_TASK, |pts, o| {
        let mut buf = Vec::new();
        let mut next = Vec::new();
        for (x, y) in pts.chunks_exact(d).zip(o.chunks_exact_mut(batch)) {
            point(axes, values, layout, batch, x, &mut buf, &mut next);
            y.clone_from_slice(&buf[..batch]);
        }
    });
}

/// The samples an axis' PCHIP on the cell of `x` reads: `(lo, hi, cell)`.
fn window<T: Real>(axis: &GridAxis<T>, x: &T) -> (usize, usize, usize) {
    let n = axis.len();
    let i = axis.cell(x);
    if n < 3 {
        return (0, n - 1, i);
    }
    let lo = i.saturating_sub(1).min(n - 3);
    let hi = (i + 2).max(2).min(n - 1);
    (lo, hi, i)
}

fn point<T: Real, S: Sample<T>>(
    axes: &[GridAxis<T>],
    values: &[S],
    layout: &Layout,
    batch: usize,
    x: &[T],
    buf: &mut Vec<T>,
    next: &mut Vec<T>,
) {
    let d = axes.len();
    let windows: Vec<(usize, usize, usize)> =
        axes.iter().zip(x).map(|(a, v)| window(a, v)).collect();
    let lens: Vec<usize> = windows.iter().map(|w| w.1 - w.0 + 1).collect();
    // Gather the window box into `buf`, C order, batch innermost.
    let strides = &layout.strides;
    buf.clear();
    let mut q = vec![0usize; d];
    loop {
        let offset: isize = (0..d)
            .map(|a| (windows[a].0 + q[a]) as isize * strides[a])
            .sum();
        buf.extend((0..batch).map(|b| values[layout.at(offset + b as isize * strides[d])].widen()));
        if !next_index(&mut q, |a| lens[a]) {
            break;
        }
    }
    // Fold the last axis, then the one before, …
    let mut line = Vec::with_capacity(4);
    for a in (0..d).rev() {
        let (lo, _, cell) = windows[a];
        let len = lens[a];
        let rows = buf.len() / (len * batch);
        next.clear();
        for r in 0..rows {
            for b in 0..batch {
                line.clear();
                line.extend((0..len).map(|j| buf[(r * len + j) * batch + b].clone()));
                next.push(pchip_at(axes[a].nodes(), lo, &line, cell, &x[a]));
            }
        }
        std::mem::swap(buf, next);
    }
}

/// PCHIP of `y` (the samples `lo ..` of an axis with `nodes`) on `cell` at `x`.
fn pchip_at<T: Real>(nodes: &[T], lo: usize, y: &[T], cell: usize, x: &T) -> T {
    let n = nodes.len();
    let yv = |j: usize| &y[j - lo];
    let h = |j: usize| nodes[j + 1].clone() - &nodes[j];
    let m = |j: usize| (yv(j + 1).clone() - yv(j)) / h(j);
    let slope_at = |j: usize| -> T {
        if n == 2 {
            m(0)
        } else if j == 0 {
            edge(h(0), h(1), m(0), m(1))
        } else if j == n - 1 {
            edge(h(n - 2), h(n - 3), m(n - 2), m(n - 3))
        } else {
            interior(h(j - 1), h(j), m(j - 1), m(j))
        }
    };
    let (d0, d1) = (slope_at(cell), slope_at(cell + 1));
    let dx = h(cell);
    let slope = m(cell);
    let t = (d0.clone() + &d1 - slope.clone() - &slope) / &dx;
    let c0 = t.clone() / &dx;
    let c1 = (slope - &d0) / &dx - t;
    let s = x.clone() - &nodes[cell];
    // scipy's evaluate_poly1: c3 + c2·s + c1·s² + c0·s³, powers accumulated.
    let mut z = T::one();
    let mut res = yv(cell).clone() * &z;
    for c in [d0, c1, c0] {
        z *= &s;
        res += c * &z;
    }
    res
}

/// numpy's `sign`: −1, 0, 1, NaN for NaN.
fn sign<T: Real>(v: &T) -> T {
    if is_nan(v) {
        v.clone()
    } else if v.is_zero() {
        T::zero()
    } else if *v > T::zero() {
        T::one()
    } else {
        -T::one()
    }
}

/// NaN: the one value unordered against itself.
fn is_nan<T: PartialOrd>(v: &T) -> bool {
    v.partial_cmp(v).is_none()
}

/// Unequal as numpy compares (`NaN != NaN` is true).
fn differ<T: Real>(a: &T, b: &T) -> bool {
    is_nan(a) || is_nan(b) || a != b
}

/// The interior slope: zero at a sign change or a flat side, else the
/// weighted harmonic mean (Fritsch–Butland).
fn interior<T: Real>(h0: T, h1: T, m0: T, m1: T) -> T {
    if differ(&sign(&m1), &sign(&m0)) || m1.is_zero() || m0.is_zero() {
        return T::zero();
    }
    let w1 = h1.clone() + &h1 + &h0;
    let w2 = h1 + &h0 + &h0;
    let whmean = (w1.clone() / &m0 + w2.clone() / &m1) / (w1 + w2);
    T::one() / whmean
}

/// The one-sided three-point end slope, limited to keep the shape.
fn edge<T: Real>(h0: T, h1: T, m0: T, m1: T) -> T {
    let d = ((h0.clone() + &h0 + &h1) * &m0 - h0.clone() * &m1) / (h0 + h1);
    if differ(&sign(&d), &sign(&m0)) {
        T::zero()
    } else if differ(&sign(&m0), &sign(&m1)) && d.clone().abs() > T::from_int(3) * m0.clone().abs()
    {
        T::from_int(3) * m0
    } else {
        d
    }
}
