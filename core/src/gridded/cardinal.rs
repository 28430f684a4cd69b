//! Certified windows of the not-a-knot grid spline: which samples a value
//! of the spline needs, to a stated tolerance — the spline of a chunked or
//! larger-than-memory array from the samples near each point only.
//!
//! **Method.** Along an axis the spline is `s(x) = b(x)ᵀ A^{−1} v`, with
//! `b(x)` the `k + 1` non-zero B-spline values at `x` and `A` the axis'
//! collocation matrix ([`super::GridSpline`]). So `s(x) = w(x)ᵀ v` with the
//! **cardinal weights** `w(x) = A^{−T} b(x)` — one transposed banded solve —
//! and for a tensor-product grid `s(x) = Σ_j v_j Π_a w_a(x_a)_{j_a}`. The
//! inverse of a banded, well-conditioned matrix decays exponentially away
//! from the diagonal (Demko, Moss & Smith 1984; for B-spline collocation
//! de Boor 1976, the cubic's rate `2 − √3` on uniform nodes), so `w(x)`
//! is negligible beyond a few dozen samples from `x`; rather than bound
//! the rate, the weights are computed and their tails measured: the window
//! `[lo, hi]` of axis `a` is the narrowest whose outside mass
//! `t_a = Σ_{j∉[lo,hi]} |w_a(x)_j|` is at most
//! `tol / (d · Π_{b≠a} ‖w_b(x)‖₁)`.
//!
//! **Error.** Dropping the samples outside the box of windows changes the
//! value by at most `max|v| · (Π_a ‖w_a‖₁ − Π_a (‖w_a‖₁ − t_a)) ≤
//! max|v| · Σ_a t_a Π_{b≠a} ‖w_b‖₁ ≤ tol · max|v|` (`max|v|` over the whole
//! array: the samples never read), plus the rounding of the weights, which
//! is the transposed twin of [`super::GridSpline::error_bound`]'s.
//!
//! **Cost** `O(Σ_a n_a)` a point for the weights (one banded solve per
//! axis) and `O(Π_a |W_a|)` for the sum over its box.

use super::banded_lu::BandedLu;
use super::evaluate::next_index;
use super::grid_spline::collocation_lu;
use super::{GridAxis, GriddedError, MAX_GRID_DEGREE};
use crate::scalar::Real;

/// One axis' nodes and factored collocation matrix, for cardinal weights.
#[derive(Debug, Clone)]
pub struct CardinalAxis<T: Real> {
    axis: GridAxis<T>,
    lu: BandedLu<T>,
}

/// The weights of one point on one axis inside its window.
#[derive(Debug, Clone)]
pub struct CardinalWeights<T> {
    /// The first sample of the window.
    pub lo: usize,
    /// `w_j` for `j = lo ..= lo + len − 1`.
    pub weights: Vec<T>,
    /// `‖w‖₁` over the whole axis.
    pub norm: T,
}

impl<T: Real> CardinalAxis<T> {
    /// The axis `index` (for messages) with `nodes` and odd `degree`.
    pub fn new(nodes: Vec<T>, degree: usize, index: usize) -> Result<Self, GriddedError> {
        let axis = GridAxis::not_a_knot(nodes, degree, index)?;
        let lu = collocation_lu(&axis, index)?;
        Ok(Self { axis, lu })
    }

    /// The axis.
    pub fn axis(&self) -> &GridAxis<T> {
        &self.axis
    }

    /// `w(x) = A^{−T} b(x)` over the whole axis (a NaN `x` gives NaNs).
    pub fn full_weights(&self, x: &T) -> Vec<T> {
        let k = self.axis.degree();
        let mut b: [T; MAX_GRID_DEGREE + 1] = std::array::from_fn(|_| T::zero());
        let s = self.axis.weights(x, 0, &mut b);
        let mut w = vec![T::zero(); self.axis.len()];
        for (q, v) in b[..=k].iter().enumerate() {
            w[s - k + q] = v.clone();
        }
        self.lu.solve_transpose(&mut w);
        w
    }

    /// The narrowest window whose outside mass is at most `tail`, its
    /// weights, and `‖w‖₁`: trimmed from both ends, each side taking what
    /// the other leaves.
    pub fn window(&self, x: &T, tail: &T) -> CardinalWeights<T> {
        let w = self.full_weights(x);
        let norm = w.iter().fold(T::zero(), |s, v| s + v.clone().abs());
        let (mut lo, mut hi) = (0, w.len() - 1);
        let mut dropped = T::zero();
        // Drop the smaller end first while the budget allows.
        while lo < hi {
            let (l, r) = (w[lo].clone().abs(), w[hi].clone().abs());
            let (take, left) = if l <= r { (l, true) } else { (r, false) };
            if dropped.clone() + &take > *tail {
                break;
            }
            dropped += &take;
            if left {
                lo += 1;
            } else {
                hi -= 1;
            }
        }
        CardinalWeights {
            lo,
            weights: w[lo..=hi].to_vec(),
            norm,
        }
    }
}

/// The windows of one point on every axis for a total truncation of at
/// most `tol · max|v|` (module doc): the per-axis budgets from the weights'
/// norms, then the trimmed weights.
///
/// ```
/// use splinelab::gridded::{CardinalAxis, GridSpline, point_windows, windowed_value};
/// use ndarray::Array2;
/// // 400 samples of a cubic spline; its value at 123.4 from ~20 of them.
/// let x: Vec<f64> = (0..400).map(|i| i as f64 + 0.3 * ((i * 7) % 5) as f64).collect();
/// let v = Array2::from_shape_fn((400, 1), |(i, _)| (0.1 * x[i]).sin());
/// let axis = CardinalAxis::new(x.clone(), 3, 0).unwrap();
/// let w = point_windows(&[axis], &[123.4], 1e-10);
/// assert!(w[0].weights.len() < 40);
/// let near = windowed_value(&w, |j| v[[j[0], 0]]);
/// let s = GridSpline::interpolate(vec![x], v.view().into_dyn(), 3).unwrap();
/// assert!((near - s.eval(&[123.4], &[]).unwrap()[0]).abs() <= 1e-10 + s.error_bound());
/// ```
pub fn point_windows<T: Real>(
    axes: &[CardinalAxis<T>],
    x: &[T],
    tol: f64,
) -> Vec<CardinalWeights<T>> {
    let d = axes.len();
    let full: Vec<Vec<T>> = axes.iter().zip(x).map(|(a, v)| a.full_weights(v)).collect();
    let norms: Vec<T> = full
        .iter()
        .map(|w| w.iter().fold(T::zero(), |s, v| s + v.clone().abs()))
        .collect();
    axes.iter()
        .zip(x)
        .enumerate()
        .map(|(a, (ax, v))| {
            let others = norms
                .iter()
                .enumerate()
                .filter(|&(b, _)| b != a)
                .fold(T::one(), |p, (_, n)| p * n);
            let tail = T::from_f64_exact(tol) / (T::from_int(d as i64) * others);
            ax.window(v, &tail)
        })
        .collect()
}

/// `Σ_j v_j Π_a w_a(j_a)` over a point's windows, the samples read from
/// `sample(j)` (grid indices): the spline's value from the window alone.
pub fn windowed_value<T: Real>(
    windows: &[CardinalWeights<T>],
    mut sample: impl FnMut(&[usize]) -> T,
) -> T {
    let d = windows.len();
    let mut q = vec![0usize; d];
    let mut index = vec![0usize; d];
    let mut total = T::zero();
    loop {
        let mut weight = T::one();
        for a in 0..d {
            weight *= &windows[a].weights[q[a]];
            index[a] = windows[a].lo + q[a];
        }
        total += weight * sample(&index);
        if !next_index(&mut q, |a| windows[a].weights.len()) {
            return total;
        }
    }
}
