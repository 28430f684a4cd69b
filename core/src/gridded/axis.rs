//! One axis of a rectilinear grid: its nodes, the not-a-knot knot vector of
//! an odd degree on them, the cell a coordinate falls in, and the B-spline
//! weights (and their derivatives) there.

use super::{GriddedError, MAX_GRID_DEGREE};
use crate::bspline::de_boor::basis_into;
use crate::scalar::Real;

/// The nodes `x_0 < … < x_{n−1}` of one grid axis with the knots of the
/// not-a-knot spline of odd degree `k` on them.
///
/// **Knots** (de Boor, *A Practical Guide to Splines*, XIII (12); scipy's
/// `_not_a_knot`): with `m = (k − 1)/2`,
/// `t = (x_0)^{k+1}, x_{m+1}, …, x_{n−m−2}, (x_{n−1})^{k+1}` — `n + k + 1`
/// knots, so `n` B-splines, one per node. The nodes `x_1 … x_m` and
/// `x_{n−m−1} … x_{n−2}` are not knots: the spline's `k`-th derivative is
/// continuous across them ("not a knot"). For `k = 1` every node is a knot
/// and the spline is the piecewise linear interpolant.
#[derive(Debug, Clone)]
pub struct GridAxis<T: Real> {
    nodes: Vec<T>,
    knots: Vec<T>,
    degree: usize,
    /// `(x_0, 1/h)` where the nodes are uniform to rounding: the cell of a
    /// coordinate by arithmetic (then checked against the nodes).
    uniform: Option<(f64, f64)>,
}

impl<T: Real> GridAxis<T> {
    /// The axis `axis` (for messages) with `nodes` and the not-a-knot knots
    /// of odd `degree`. Errors: an even or too high degree, fewer than
    /// `degree + 1` nodes, nodes not finite and strictly ascending.
    pub fn not_a_knot(nodes: Vec<T>, degree: usize, axis: usize) -> Result<Self, GriddedError> {
        if degree.is_multiple_of(2) || degree > MAX_GRID_DEGREE {
            return Err(GriddedError::Degree(degree));
        }
        let n = nodes.len();
        if n < degree + 1 {
            return Err(GriddedError::TooFewPoints {
                axis,
                got: n,
                degree,
                need: degree + 1,
            });
        }
        if let Some(index) =
            (0..n).find(|&i| !nodes[i].clone().is_finite() || (i > 0 && nodes[i] <= nodes[i - 1]))
        {
            return Err(GriddedError::NotAscending { axis, index });
        }
        let m = (degree - 1) / 2;
        let mut knots = Vec::with_capacity(n + degree + 1);
        knots.extend(std::iter::repeat_n(nodes[0].clone(), degree + 1));
        knots.extend(nodes[m + 1..n - m - 1].iter().cloned());
        knots.extend(std::iter::repeat_n(nodes[n - 1].clone(), degree + 1));
        let uniform = uniform_step(&nodes);
        Ok(Self {
            nodes,
            knots,
            degree,
            uniform,
        })
    }

    /// The nodes.
    pub fn nodes(&self) -> &[T] {
        &self.nodes
    }

    /// The knot vector (`n + k + 1` knots).
    pub fn knots(&self) -> &[T] {
        &self.knots
    }

    /// The number of nodes, which is the number of B-splines.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the axis has no nodes (never, once built).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The degree `k`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// Whether the nodes are uniform (to rounding): cells by arithmetic.
    pub fn is_uniform(&self) -> bool {
        self.uniform.is_some()
    }

    /// The cell `i` of `x`: `x_i ≤ x < x_{i+1}`, clamped to `0 ..= n − 2`
    /// (points beyond the ends belong to the end cells; a NaN to cell 0).
    /// By arithmetic on uniform axes (then corrected against the nodes, so
    /// the answer is the bisection's), by bisection on the others.
    pub fn cell(&self, x: &T) -> usize {
        let n = self.nodes.len();
        let last = n.saturating_sub(2);
        match self.uniform {
            Some((x0, inv_h)) => {
                let guess = ((x.to_f64() - x0) * inv_h).floor();
                // `as` saturates (a NaN gives 0).
                let mut i = (guess.max(0.0) as usize).min(last);
                while i > 0 && *x < self.nodes[i] {
                    i -= 1;
                }
                while i < last && *x >= self.nodes[i + 1] {
                    i += 1;
                }
                i
            }
            None => self
                .nodes
                .partition_point(|v| v <= x)
                .saturating_sub(1)
                .min(last),
        }
    }

    /// The knot span `s` (`k ≤ s ≤ n − 1`, `t_s ≤ x < t_{s+1}` inside the
    /// grid) of the cell of `x`: the B-splines `s − k ..= s` are the ones
    /// not zero there. Node cell `i` lies in span `k + i − m`, clamped.
    pub fn span(&self, x: &T) -> usize {
        let (k, n) = (self.degree, self.nodes.len());
        let m = (k - 1) / 2;
        (k + self.cell(x)).saturating_sub(m).clamp(k, n - 1)
    }

    /// `out[q] = d^ν/dx^ν B_{s−k+q}(x)`, `q = 0 ..= k`, with `s` the span of
    /// `x` ([`GridAxis::span`], returned). Outside the grid these are the
    /// end pieces' polynomials continued (extrapolation).
    ///
    /// **Method**: the Cox–de Boor recurrence in Piegl–Tiller's triangular
    /// form (*The NURBS Book*, A2.2) for degree `k − ν`, then `ν` steps of
    /// the derivative recurrence
    /// `B'_{j,p} = p B_{j,p−1}/(t_{j+p} − t_j) − p B_{j+1,p−1}/(t_{j+p+1} − t_{j+1})`
    /// (de Boor X (12)), a term with a zero knot difference being zero.
    /// **Cost** `O(k²)`. **Accuracy**: inside the grid every value of degree
    /// `k − ν` is a sum of non-negative terms, relative error `≤ γ_{3k}`.
    /// `ν > k` gives zeros.
    pub fn weights(&self, x: &T, nu: usize, out: &mut [T]) -> usize {
        let k = self.degree;
        let s = self.span(x);
        for v in out.iter_mut() {
            *v = T::zero();
        }
        if nu > k {
            return s;
        }
        let p0 = k - nu;
        let t = &self.knots;
        // Cox–de Boor, degree p0: out[0..=p0] = B_{s−p0..=s, p0}(x).
        let mut left: [T; MAX_GRID_DEGREE + 1] = std::array::from_fn(|_| T::zero());
        let mut right: [T; MAX_GRID_DEGREE + 1] = std::array::from_fn(|_| T::zero());
        basis_into(p0 + 1, t, s, x, out, &mut left, &mut right);
        // Up the degrees: out holds B_{s−p+1..=s, p−1} in out[0..p].
        for p in p0 + 1..=k {
            let scale = T::from_int(p as i64);
            let mut prev = T::zero(); // the old out[q − 1]
            for (q, slot) in out.iter_mut().enumerate().take(p + 1) {
                let j = s + q - p;
                let old = if q < p { slot.clone() } else { T::zero() };
                let a = quotient(&prev, &t[j + p], &t[j]);
                let b = quotient(&old, &t[j + p + 1], &t[j + 1]);
                *slot = (a - b) * &scale;
                prev = old;
            }
        }
        s
    }
}

/// `v / (hi − lo)`, zero where the knots coincide (the B-spline is zero).
fn quotient<T: Real>(v: &T, hi: &T, lo: &T) -> T {
    let d = hi.clone() - lo;
    if d.is_zero() {
        T::zero()
    } else {
        v.clone() / d
    }
}

/// `(x_0, 1/h)` where every node is within a few ulps of `x_0 + i·h`.
fn uniform_step<T: Real>(nodes: &[T]) -> Option<(f64, f64)> {
    let n = nodes.len();
    let (x0, x1) = (nodes[0].to_f64(), nodes[n - 1].to_f64());
    let h = (x1 - x0) / (n - 1) as f64;
    let tol = 8.0 * f64::EPSILON * x0.abs().max(x1.abs());
    let uniform = h > 0.0
        && nodes
            .iter()
            .enumerate()
            .all(|(i, v)| (v.to_f64() - (x0 + i as f64 * h)).abs() <= tol);
    uniform.then_some((x0, 1.0 / h))
}
