//! `grid-spline`: a user's values of the not-a-knot tensor-product spline
//! on a rectilinear grid — scipy.interpolate's `RegularGridInterpolator` /
//! `interpn` with `method="slinear" | "cubic" | "quintic"`, `make_ndbspl`,
//! or any code that claims that spline — against the exact spline of the
//! user's f64 grid and samples.
//!
//! **Reference.** The spline solved and evaluated in MPFR
//! ([`GridSpline`] over [`Mp`](splinelab::scalar::Mp)), certified by the
//! `p / p + 64` agreement of [`super::agreement`]: the same banded solves
//! at two precisions must agree to 40 bits below an ulp of the user's
//! format. The collocation matrices' B-spline values, the solves and the
//! evaluation all round in MPFR, so the certified reference is the exact
//! spline to far below the user's precision.
//!
//! **Stable bound** (the error a backward-stable computation of the same
//! spline would make, from the problem's conditioning): per point,
//! `E·Σ|W| + γ_{3kd + d + (k+1)^d}·Σ|c||W| + u|f|`, where `W` are the
//! tensor-product B-spline weights at the point, `c` the coefficients, and
//! `E` the coefficient error bound of [`GridSpline::coefficient_error`]:
//! `Σ_a κ_a (γ_{3w_a}G_a + γ_{3k}) M_a Π_{b>a} κ_b`, with `κ_a = ‖A_a^{−1}‖∞`
//! of each axis' collocation matrix (exact by the checkerboard solve), `G_a`
//! the growth of a stable factorization and `M_a` the coefficient sizes. An
//! iterative solve stopped at a tolerance (scipy's `gcrotmk`, `atol=1e-6`)
//! is far above it and fails.

use super::agreement::{Reference, certify};
use super::format::UserFormat;
use super::stable_bound::{gamma, unit_roundoff};
use super::summary::{
    BoundBasis, CheckSummary, Context, ElementError, element_error, from_elements,
};
use super::{CheckError, require_finite, require_len};
use rayon::prelude::*;
use splinelab::gridded::evaluate::next_index;
use splinelab::gridded::{GridAxis, GridSpline, MAX_GRID_DEGREE};
use splinelab::ndarray::{ArrayView, IxDyn};
use splinelab::scalar::Real;

/// Largest `N·d·(3k + 1) + n·(k + 1)^d` accepted (`N` grid samples, `n` points).
pub const MAX_WORK: usize = 20_000_000;

/// What `check grid-spline` is given.
#[derive(Debug, Clone)]
pub struct GridSplineInput {
    /// The nodes of each axis, strictly ascending.
    pub grid: Vec<Vec<f64>>,
    /// The samples on the grid, C order.
    pub samples: Vec<f64>,
    /// Odd degree `k` (scipy: slinear 1, cubic 3, quintic 5).
    pub degree: usize,
    /// The points, point-major (`points[p·d + a]`).
    pub points: Vec<f64>,
    /// The user's values, one per point.
    pub user: Vec<f64>,
    /// The user's format.
    pub format: UserFormat,
    /// `max_ulps`.
    pub max_ulps: Option<f64>,
}

struct SplineReference<'a> {
    input: &'a GridSplineInput,
}

impl Reference for SplineReference<'_> {
    fn compute<T: Real>(&self) -> Result<Vec<T>, CheckError> {
        let i = self.input;
        let grid: Vec<Vec<T>> = i
            .grid
            .iter()
            .map(|g| g.iter().map(|&x| T::from_f64_exact(x)).collect())
            .collect();
        let samples: Vec<T> = i.samples.iter().map(|&x| T::from_f64_exact(x)).collect();
        let s = build(grid, &samples, &i.grid, i.degree)?;
        let points: Vec<T> = i.points.iter().map(|&x| T::from_f64_exact(x)).collect();
        s.eval(&points, &[])
            .map_err(|e| CheckError::Invalid(e.to_string()))
    }
}

fn build<T: Real>(
    grid: Vec<Vec<T>>,
    samples: &[T],
    shape_of: &[Vec<f64>],
    degree: usize,
) -> Result<GridSpline<T>, CheckError> {
    let mut shape: Vec<usize> = shape_of.iter().map(Vec::len).collect();
    shape.push(1);
    let view = ArrayView::from_shape(IxDyn(&shape), samples)
        .map_err(|e| CheckError::Invalid(e.to_string()))?;
    GridSpline::interpolate(grid, view, degree).map_err(|e| CheckError::Invalid(e.to_string()))
}

fn validate(i: &GridSplineInput) -> Result<(), CheckError> {
    let d = i.grid.len();
    if d == 0 {
        return Err(CheckError::Empty("grid".into()));
    }
    if i.degree.is_multiple_of(2) || i.degree > MAX_GRID_DEGREE {
        return Err(CheckError::DegreeOutOfRange {
            degree: i.degree,
            min: 1,
            max: MAX_GRID_DEGREE,
        });
    }
    for (a, g) in i.grid.iter().enumerate() {
        require_finite(&format!("grid[{a}]"), g)?;
    }
    require_finite("samples", &i.samples)?;
    require_finite("points", &i.points)?;
    let n: usize = i.grid.iter().map(Vec::len).product();
    require_len("samples (one per grid point)", n, i.samples.len())?;
    if !i.points.len().is_multiple_of(d) {
        return Err(CheckError::Invalid(format!(
            "points: {} numbers are not points of {d} coordinates",
            i.points.len()
        )));
    }
    require_len("values (one per point)", i.points.len() / d, i.user.len())?;
    if i.user.is_empty() {
        return Err(CheckError::Empty("points".into()));
    }
    let per_point = (i.degree + 1).saturating_pow(d as u32);
    let work = n
        .saturating_mul(d * (3 * i.degree + 1))
        .saturating_add(i.user.len().saturating_mul(per_point));
    if work > MAX_WORK {
        return Err(CheckError::TooLarge(format!(
            "N·d·(3k+1) + n·(k+1)^d = {work} exceeds {MAX_WORK}"
        )));
    }
    Ok(())
}

/// `Σ|c||W|` and `Σ|W|` at one point (weights of any sign: extrapolation).
fn abs_sums(axes: &[GridAxis<f64>], coefs: &[f64], x: &[f64]) -> (f64, f64) {
    let d = axes.len();
    let k = axes[0].degree();
    let mut w = vec![[0.0; MAX_GRID_DEGREE + 1]; d];
    let mut base = vec![0usize; d];
    for a in 0..d {
        base[a] = axes[a].weights(&x[a], 0, &mut w[a]) - k;
    }
    let mut strides = vec![1usize; d];
    for a in (0..d.saturating_sub(1)).rev() {
        strides[a] = strides[a + 1] * axes[a + 1].len();
    }
    let (mut cw, mut sw) = (0.0, 0.0);
    let mut q = vec![0usize; d];
    loop {
        let (mut weight, mut at) = (1.0, 0usize);
        for a in 0..d {
            weight *= w[a][q[a]].abs();
            at += (base[a] + q[a]) * strides[a];
        }
        cw += weight * coefs[at].abs();
        sw += weight;
        if !next_index(&mut q, |_| k + 1) {
            return (cw, sw);
        }
    }
}

/// Checks the user's values of the grid spline (parallel over the points).
pub fn check_grid_spline(input: &GridSplineInput) -> Result<CheckSummary, CheckError> {
    validate(input)?;
    let spline = build(
        input.grid.clone(),
        &input.samples,
        &input.grid,
        input.degree,
    )?;
    let certified = certify(&SplineReference { input }, input.format, 128)?;
    let (k, d) = (input.degree, input.grid.len());
    // The stable bound in the user's format: the f64 spline's bound terms
    // rescaled from f64's unit roundoff to the format's.
    let scale = unit_roundoff(input.format) / f64::EPSILON * 2.0;
    let coef_error = spline.coefficient_error() * scale;
    let terms = 3 * k * d + d + (k + 1).saturating_pow(d as u32);
    let u = unit_roundoff(input.format);
    let g_eval = gamma(terms, input.format);
    let elements: Vec<ElementError> = input
        .points
        .par_chunks(d)
        .zip(input.user.par_iter())
        .zip(certified.values.par_iter())
        .enumerate()
        .map(|(i, ((x, v), r))| {
            let (cw, sw) = abs_sums(spline.axes(), spline.coefficients(), x);
            let bound = coef_error * sw + g_eval * cw + u * r.to_f64().abs();
            element_error(i, *v, r, input.format, None).with_bound(bound)
        })
        .collect();
    let kappas: Vec<String> = spline
        .conditioning()
        .iter()
        .map(|c| format!("{:.3e}", c.kappa))
        .collect();
    let ctx = Context {
        kind: "grid-spline",
        format: input.format,
        reference_bits: Some(certified.bits),
        reference: format!(
            "the not-a-knot tensor-product spline of degree {k} solved and evaluated in MPFR ({}/{} bits agree)",
            certified.low_bits, certified.bits
        ),
        horizon: None,
        max_ulps: input.max_ulps,
        bound: BoundBasis::PerElement(format!(
            "E·Σ|W| + γ_{terms}·Σ|c||W| + u|f|, E = {coef_error:.3e} the coefficient error of a stable banded solve per axis (κ_a = ‖A_a⁻¹‖∞ = [{}]; Higham, Accuracy and Stability, 2nd ed., Thm 9.4; de Boor & Pinkus 1977 for the totally nonnegative collocation matrices)",
            kappas.join(", ")
        )),
    };
    Ok(from_elements(&ctx, elements))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(user: impl Fn(&[f64]) -> f64) -> GridSplineInput {
        let grid = vec![
            vec![0.0, 0.4, 1.0, 1.3, 2.0, 2.2],
            vec![-1.0, 0.0, 0.5, 2.0, 2.5],
        ];
        let f = |x: f64, y: f64| (x * 2.0).sin() * y + y * y * y;
        let samples = grid[0]
            .iter()
            .flat_map(|&x| grid[1].iter().map(move |&y| f(x, y)))
            .collect();
        let points: Vec<f64> = (0..40)
            .flat_map(|i| [0.05 * i as f64, -1.0 + 0.08 * i as f64])
            .collect();
        let user = points.chunks(2).map(&user).collect();
        GridSplineInput {
            grid,
            samples,
            degree: 3,
            points,
            user,
            format: UserFormat::F64,
            max_ulps: None,
        }
    }

    #[test]
    fn splinelab_passes_and_a_perturbed_answer_fails() {
        // The user's numbers from the f64 spline (a different code path:
        // the f64 instance, against the certified MPFR reference).
        let probe = input(|_| 0.0);
        let s = build(probe.grid.clone(), &probe.samples, &probe.grid, 3).unwrap();
        let good = input(|x| s.eval(x, &[]).unwrap()[0]);
        let r = check_grid_spline(&good).unwrap();
        assert_eq!(r.verdict, "pass", "{:?}", r.worst_excess);
        // An answer off by 1e-9 (an iterative solve's residue) fails.
        let bad = input(|x| s.eval(x, &[]).unwrap()[0] + 1e-9);
        assert_eq!(check_grid_spline(&bad).unwrap().verdict, "fail");
    }

    #[test]
    fn bad_inputs_are_errors() {
        let mut i = input(|_| 0.0);
        i.degree = 2;
        assert!(matches!(
            check_grid_spline(&i),
            Err(CheckError::DegreeOutOfRange { .. })
        ));
        let mut i = input(|_| 0.0);
        i.samples.pop();
        assert!(matches!(
            check_grid_spline(&i),
            Err(CheckError::LengthMismatch { .. })
        ));
        let mut i = input(|_| 0.0);
        i.grid[0][2] = 0.3;
        assert!(matches!(check_grid_spline(&i), Err(CheckError::Invalid(_))));
    }
}
