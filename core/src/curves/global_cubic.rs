//! Global cubic-spline interpolation on uniform knots — the baseline the
//! S-spline's local update is measured against (seed 000 §1: "cubic spline
//! interpolation has no local support, so a partial change costs work
//! proportional to all the data").
//!
//! The interpolant is the uniform cubic B-spline curve
//! `Q(u) = Σ_{k=−1}^{ν} D_k β_4(u − k)` with `Q(i) = P_i`, i.e.
//! `(D_{i−1} + 4 D_i + D_{i+1})/6 = P_i`, `i = 0..ν−1`, closed by
//!
//! - **natural** ends `Q''(0) = Q''(ν−1) = 0`: `D_{−1} = 2D_0 − D_1`, which
//!   turns row 0 into `D_0 = P_0` (and likewise at the far end);
//! - **clamped** ends `Q'(0) = T_0`, `Q'(ν−1) = T_1`: `D_{−1} = D_1 − 2T_0`,
//!   row 0 becomes `4D_0 + 2D_1 = 6P_0 + 2T_0`.
//!
//! The system is tridiagonal and strictly diagonally dominant, so the Thomas
//! algorithm (no pivoting) is backward stable: `O(ν)` operations and a
//! componentwise relative error of a few `u` times the condition number
//! (`≤ 3` in the ∞-norm for `(1, 4, 1)/6`). The clamped case is checked
//! against the Hermite-form solver of `qi::cubic_spline` (a second algorithm).
//! The result is the same representation as [`super::sspline_curve::SsplineCurve`]
//! (order 4, knots `k − 2 + ℤ`), so both are evaluated by one B-spline code.

use super::CurveError;
use crate::bspline::de_boor::BSpline;
use crate::bspline::knots::KnotVector;
use crate::scalar::Real;
use crate::validation::{InputError, at_least, finite_points, finite_vector};
use nalgebra::SVector;

/// End conditions of the global cubic spline.
#[derive(Debug, Clone, PartialEq)]
pub enum CubicEnds<T: Real, const D: usize> {
    /// `Q'' = 0` at both ends.
    Natural,
    /// `Q'(0) = start`, `Q'(ν − 1) = end`.
    Clamped {
        /// `T_0`.
        start: SVector<T, D>,
        /// `T_1`.
        end: SVector<T, D>,
    },
}

/// The `ν + 2` control points `D_{−1..=ν}` of the cubic interpolant of
/// `data` (module doc). **Cost** `≈ 8ν` flops per coordinate.
/// Errors: fewer than 2 points, non-finite data or tangents.
///
/// **Method**: the tridiagonal system `D_{i−1} + 4 D_i + D_{i+1} = 6 P_i`
/// (end rows from `ends`) by forward elimination and back substitution. **Accuracy**: agrees with the Hermite solver to
/// `1e-13` (`verify/tests/it/sspline_curve.rs::global_cubic_matches_hermite_solver`).
/// **Source**: de Boor, *A Practical Guide to Splines*, ch. IV (cubic spline interpolation).
///
/// ```
/// use nalgebra::Vector1;
/// use splinelab::curves::global_cubic::{CubicEnds, control_points};
/// // Data of the line P_i = i: the interpolant is the line, D_k = k.
/// let p: Vec<Vector1<f64>> = (0..5).map(|i| Vector1::new(i as f64)).collect();
/// let d = control_points(&p, &CubicEnds::Natural).unwrap();
/// assert!(d.iter().enumerate().all(|(k, x)| (x[0] - (k as f64 - 1.0)).abs() < 1e-15));
/// ```
///
/// ```
/// // In MPFR: the same line, D_k = k − 1 to 128-bit rounding.
/// use nalgebra::Vector1;
/// use splinelab::curves::global_cubic::{CubicEnds, control_points};
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<128>;
/// let p: Vec<Vector1<M>> = (0..5).map(|i| Vector1::new(M::from_int(i))).collect();
/// let d = control_points(&p, &CubicEnds::Natural).unwrap();
/// for (k, x) in d.iter().enumerate() {
///     assert!((x[0].clone() - M::from_int(k as i64 - 1)).to_f64().abs() < 1e-36);
/// }
/// ```
pub fn control_points<T: Real, const D: usize>(
    data: &[SVector<T, D>],
    ends: &CubicEnds<T, D>,
) -> Result<Vec<SVector<T, D>>, CurveError> {
    let n = data.len();
    at_least("a global cubic interpolant", 2, n)?;
    finite_points("data point", data)?;
    if let CubicEnds::Clamped { start, end } = ends {
        finite_vector("the start tangent", start)?;
        finite_vector("the end tangent", end)?;
    }
    Ok(solve(data, ends))
}

/// Thomas algorithm on rows `i = 0..ν−1` (unknowns `D_0..D_{ν−1}`), then
/// the two outer points from the end conditions.
fn solve<T: Real, const D: usize>(
    p: &[SVector<T, D>],
    ends: &CubicEnds<T, D>,
) -> Vec<SVector<T, D>> {
    let n = p.len();
    let (two, four, six) = (T::from_int(2), T::from_int(4), T::from_int(6));
    // Row i: a_i D_{i−1} + b_i D_i + c_i D_{i+1} = r_i.
    let row = |i: usize| -> (T, T, T, SVector<T, D>) {
        let r = &p[i] * six.clone();
        match ends {
            CubicEnds::Natural if i == 0 || i == n - 1 => (T::zero(), six.clone(), T::zero(), r),
            CubicEnds::Clamped { start, .. } if i == 0 => (
                T::zero(),
                four.clone(),
                two.clone(),
                r + start * two.clone(),
            ),
            CubicEnds::Clamped { end, .. } if i == n - 1 => {
                (two.clone(), four.clone(), T::zero(), r - end * two.clone())
            }
            _ => (T::one(), four.clone(), T::one(), r),
        }
    };
    let mut cp: Vec<T> = Vec::with_capacity(n);
    let mut rp: Vec<SVector<T, D>> = Vec::with_capacity(n);
    for i in 0..n {
        let (a, b, c, r) = row(i);
        let (den, r) = if i == 0 {
            (b, r)
        } else {
            (b - a.clone() * &cp[i - 1], r - &rp[i - 1] * a)
        };
        cp.push(c / den.clone());
        rp.push(r / den);
    }
    let mut d = vec![SVector::zeros(); n + 2];
    d[n] = rp[n - 1].clone();
    for i in (0..n - 1).rev() {
        d[i + 1] = &rp[i] - &d[i + 2] * cp[i].clone();
    }
    let (first, last) = match ends {
        CubicEnds::Natural => (&d[1] * two.clone() - &d[2], &d[n] * two.clone() - &d[n - 1]),
        CubicEnds::Clamped { start, end } => {
            (&d[2] - start * two.clone(), &d[n - 1] + end * two.clone())
        }
    };
    d[0] = first;
    d[n + 1] = last;
    d
}

/// The interpolant as an order-4 [`BSpline`] on the knots `−3, −2, …, ν + 2`
/// (domain `[0, ν − 1]`): the same view as
/// [`super::sspline_curve::SsplineCurve::to_bspline`].
/// **Method**: [`control_points`] wrapped with the uniform knots; no further
/// rounding. **Accuracy**: as [`control_points`]
/// (`verify/tests/it/sspline_curve.rs::global_cubic_matches_hermite_solver`).
/// **Source**: de Boor, *A Practical Guide to Splines*.
pub fn interpolant<T: Real, const D: usize>(
    data: &[SVector<T, D>],
    ends: &CubicEnds<T, D>,
) -> Result<BSpline<T, D>, CurveError> {
    let d = control_points(data, ends)?;
    let knots = KnotVector::new(
        (0..d.len() as i64 + 4)
            .map(|j| T::from_int(j - 3))
            .collect(),
    )
    .map_err(crate::bspline::de_boor::BSplineError::from)?;
    Ok(BSpline::new(4, d, knots)?)
}

/// **Method**: tensor-product global interpolation of a `ν_u × ν_v` grid (row-major,
/// `P[i·ν_v + j]`): the 1D solve along every row, then along every column of
/// the result. Returns the `(ν_u + 2) × (ν_v + 2)` control net, row-major.
/// **Cost** `O(ν_u ν_v)`; a single changed point changes the whole net.
/// **Accuracy**: each direction as [`control_points`]. **Source**: tensor-product
/// interpolation, de Boor, *A Practical Guide to Splines*, ch. XVII.
pub fn surface_control_points<T: Real, const D: usize>(
    data: &[SVector<T, D>],
    nu: usize,
    nv: usize,
    ends: &CubicEnds<T, D>,
) -> Result<Vec<SVector<T, D>>, CurveError> {
    if nu < 2 || nv < 2 {
        return Err(InputError::TooFewPoints {
            what: "a global cubic surface (per direction)",
            needed: 2,
            got: nu.min(nv),
        }
        .into());
    }
    if nu.checked_mul(nv) != Some(data.len()) {
        return Err(CurveError::GridSize {
            nu,
            nv,
            got: data.len(),
        });
    }
    let rows: Vec<Vec<SVector<T, D>>> = (0..nu)
        .map(|i| control_points(&data[i * nv..(i + 1) * nv], ends))
        .collect::<Result<_, _>>()?;
    let (mu, mv) = (nu + 2, nv + 2);
    let mut net = vec![SVector::zeros(); mu * mv];
    let mut column = vec![SVector::zeros(); nu];
    for l in 0..mv {
        for (i, r) in rows.iter().enumerate() {
            column[i] = r[l].clone();
        }
        for (k, x) in control_points(&column, ends)?.into_iter().enumerate() {
            net[k * mv + l] = x;
        }
    }
    Ok(net)
}
