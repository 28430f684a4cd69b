//! The tensor-product spline `s(x) = Σ_j c_j Π_a B^{(a)}_{j_a}(x_a)` at
//! points, from coefficients on the grid (the not-a-knot ones of
//! [`super::GridSpline`], or the samples themselves for degree 1: the
//! multilinear interpolant).

use super::GridAxis;
use super::MAX_GRID_DEGREE;
use super::layout::Layout;
use crate::ndimage::samples::Sample;
use crate::scalar::Real;
use rayon::prelude::*;

/// Points evaluated per parallel task; fewer points than this run on the
/// calling thread (a small call pays no thread-pool hand-off).
const POINTS_PER_TASK: usize = 512;

/// `out[p·m + b] = ∂^ν s_b(x_p)` for the points `x` (`n × d`, row-major)
/// and the `m = batch` splines whose coefficients are `coefs` laid out as
/// `layout` says (shape `axes' lengths × m`, any strides: [`Layout`]).
/// `nu[a]` is the derivative order along axis `a` (empty: values).
///
/// **Method**: per point and axis the `k + 1` non-zero B-spline weights
/// ([`GridAxis::weights`]), then the `(k + 1)^d` products against the
/// coefficients, the last axis innermost. Outside the grid the end pieces
/// are continued (extrapolation). **Cost** `O(d·k² + (k+1)^d·m)` a point,
/// points in parallel. **Accuracy** (values, inside the grid): every
/// weight is non-negative and they sum to 1 per axis, so the computed
/// value is within `γ_{3kd + d + (k+1)^d} · max|c|` of the exact sum of
/// the given coefficients. A NaN coordinate gives NaN.
pub fn tensor_eval<T: Real, S: Sample<T>>(
    axes: &[GridAxis<T>],
    coefs: &[S],
    layout: &Layout,
    batch: usize,
    points: &[T],
    nu: &[usize],
    out: &mut [T],
) {
    let d = axes.len();
    if d == 0 || batch == 0 {
        return;
    }
    over_points(points, d, out, batch, POINTS_PER_TASK, |pts, o| {
        let mut w: Vec<[T; MAX_GRID_DEGREE + 1]> =
            (0..d).map(|_| std::array::from_fn(|_| T::zero())).collect();
        let mut acc = vec![T::zero(); batch];
        for (x, y) in pts.chunks_exact(d).zip(o.chunks_exact_mut(batch)) {
            point(axes, coefs, layout, x, nu, &mut w, &mut acc);
            y.clone_from_slice(&acc);
        }
    });
}

/// `work(points, out)` over the points (`d` coordinates each) and their
/// `batch` outputs: on the calling thread up to `per_task` points (a small
/// call pays no thread-pool hand-off), else in parallel tasks of `per_task`.
pub(crate) fn over_points<T: Real, U: Send>(
    points: &[T],
    d: usize,
    out: &mut [U],
    batch: usize,
    per_task: usize,
    work: impl Fn(&[T], &mut [U]) + Sync + Send,
) {
    if points.len() / d <= per_task {
        work(points, out);
    } else {
        points
            .par_chunks(per_task * d)
            .zip(out.par_chunks_mut(per_task * batch))
            .for_each(|(p, o)| work(p, o));
    }
}

/// Steps the multi-index `q` through `0..len(a)` on each axis `a`, the last
/// fastest: `false` once it wraps past the last index (then all zeros).
///
/// ```
/// use splinelab::gridded::evaluate::next_index;
/// let mut q = [0, 1];
/// assert!(next_index(&mut q, |_| 2) && q == [1, 0]);
/// assert!(next_index(&mut q, |_| 2) && q == [1, 1]);
/// assert!(!next_index(&mut q, |_| 2) && q == [0, 0]);
/// ```
pub fn next_index(q: &mut [usize], len: impl Fn(usize) -> usize) -> bool {
    for a in (0..q.len()).rev() {
        q[a] += 1;
        if q[a] < len(a) {
            return true;
        }
        q[a] = 0;
    }
    false
}

/// One point into `acc` (length `m`): weights into `w`, then the sum.
fn point<T: Real, S: Sample<T>>(
    axes: &[GridAxis<T>],
    coefs: &[S],
    layout: &Layout,
    x: &[T],
    nu: &[usize],
    w: &mut [[T; MAX_GRID_DEGREE + 1]],
    acc: &mut [T],
) {
    let d = axes.len();
    let k = axes[0].degree();
    // The first coefficient of the box, in element steps from the origin.
    let strides = &layout.strides;
    let mut base = 0isize;
    for a in 0..d {
        let s = axes[a].weights(&x[a], nu.get(a).copied().unwrap_or(0), &mut w[a]);
        base += (s - k) as isize * strides[a];
    }
    let step_b = strides[d];
    for v in acc.iter_mut() {
        *v = T::zero();
    }
    // Odometer over the first d − 1 axes; the last axis is the inner sum.
    let mut q = [0usize; MAX_DIMS];
    let last = d - 1;
    loop {
        let mut weight = T::one();
        let mut offset = base;
        for a in 0..last {
            weight *= &w[a][q[a]];
            offset += q[a] as isize * strides[a];
        }
        for (j, wl) in w[last][..=k].iter().enumerate() {
            let f = weight.clone() * wl;
            let row = offset + j as isize * strides[last];
            for (b, y) in acc.iter_mut().enumerate() {
                *y += f.clone() * coefs[layout.at(row + b as isize * step_b)].widen();
            }
        }
        if !next_index(&mut q[..last], |_| k + 1) {
            return;
        }
    }
}

/// The most grid dimensions a spline may have (scipy's arrays stop at 64).
pub const MAX_DIMS: usize = 64;
