//! Newton–Raphson for square nonlinear systems `F(x) = 0` with an exact
//! Jacobian, plain or damped by backtracking, recording every iterate.
//!
//! **Method.** `J(x_k) Δ_k = −F(x_k)` by LU with partial pivoting, then
//! `x_{k+1} = x_k + λ_k Δ_k`. Plain Newton takes `λ_k = 1`. The damped
//! variant halves `λ` from 1 until the iterate is admissible (for QI:
//! positive lengths) and satisfies the Armijo condition on
//! `φ = ½‖F‖₂²`: `‖F(x_k + λΔ_k)‖₂² ≤ (1 − 2 c λ) ‖F(x_k)‖₂²`, `c = 10⁻⁴`
//! (Dennis–Schnabel, *Numerical Methods for Unconstrained Optimization and
//! Nonlinear Equations*, §6.3). Near a regular root `λ = 1` is accepted and
//! the convergence is quadratic in both variants.
//!
//! **Cost.** Per iteration: one Jacobian, one LU (`⅔ N³`), one residual per
//! trial step. **Stopping.** `‖F(x_k)‖₂ ≤ tol`; failure after `max_iter`
//! steps, on a singular or non-finite Jacobian/step, or when `λ` would
//! drop below `2⁻³⁰`.

use crate::scalar::Real;
use nalgebra::{DMatrix, DVector};
use std::fmt;

/// A square system with its exact Jacobian.
pub trait NonlinearSystem<T: Real> {
    /// `F(x)`.
    fn residual(&self, x: &DVector<T>) -> DVector<T>;
    /// `F(x)` and `J(x) = ∂F/∂x`.
    fn residual_and_jacobian(&self, x: &DVector<T>) -> (DVector<T>, DMatrix<T>);
    /// Whether `x` lies in the domain where a root is meaningful.
    fn admissible(&self, _x: &DVector<T>) -> bool {
        true
    }
}

/// Solver settings.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonOptions<T> {
    /// Stop when `‖F‖₂ ≤ tol`.
    pub tol: T,
    /// Maximum number of Newton steps.
    pub max_iter: usize,
    /// Backtracking line search (see the module doc).
    pub damped: bool,
}

/// One iterate `x_k`: its residual and the step taken from it.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration<T> {
    /// `‖F(x_k)‖₂`.
    pub residual: T,
    /// `‖λ_k Δ_k‖₂` of the step taken from `x_k` (`None` for the last).
    pub step: Option<T>,
    /// `λ_k` (`None` for the last iterate).
    pub damping: Option<T>,
}

/// Why Newton stopped without meeting the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NewtonFailure {
    /// `max_iter` steps without `‖F‖₂ ≤ tol`.
    IterationLimit,
    /// LU found the Jacobian singular.
    SingularJacobian,
    /// A residual, Jacobian or step was NaN or infinite.
    NonFinite,
    /// The damped step size fell below `2⁻³⁰` without sufficient decrease.
    LineSearch,
    /// The iterate left the admissible domain (QI: a length `≤ 0`).
    Inadmissible,
}

impl fmt::Display for NewtonFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            NewtonFailure::IterationLimit => "iteration limit reached",
            NewtonFailure::SingularJacobian => "singular Jacobian",
            NewtonFailure::NonFinite => "non-finite residual or step",
            NewtonFailure::LineSearch => "line search found no decrease",
            NewtonFailure::Inadmissible => "iterate left the admissible domain",
        })
    }
}

/// The outcome: last iterate, full history, and the failure if any.
#[derive(Debug, Clone, PartialEq)]
pub struct NewtonRun<T> {
    /// Last iterate.
    pub x: DVector<T>,
    /// One record per iterate, starting with `x_0`.
    pub history: Vec<Iteration<T>>,
    /// `None` when `‖F(x)‖₂ ≤ tol`.
    pub failure: Option<NewtonFailure>,
}

fn all_finite<T: Real>(v: impl IntoIterator<Item = T>) -> bool {
    v.into_iter().all(|x| x.is_finite())
}

/// Runs Newton from `x0`; see the module doc. Never panics: every failure
/// is reported in [`NewtonRun::failure`] with the history so far.
/// **Method**: Newton–Raphson, one LU solve per step. **Accuracy**: quadratic
/// convergence to a closed-form root (`newton.rs::tests::converges_quadratically_to_closed_form_root`,
/// `verify/tests/it/qi_interpolation.rs::mp256_newton_converges_quadratically`).
/// **Source**: seed 004 (solver); Golub & Van Loan, §3.4 (LU with pivoting).
pub fn newton<T: Real, S: NonlinearSystem<T>>(
    sys: &S,
    x0: DVector<T>,
    opts: &NewtonOptions<T>,
) -> NewtonRun<T> {
    let mut x = x0;
    let mut history = Vec::new();
    let (mut f, mut jac) = sys.residual_and_jacobian(&x);
    loop {
        let r = f.norm();
        let done = |history: Vec<Iteration<T>>, x, failure| NewtonRun {
            x,
            history,
            failure,
        };
        history.push(Iteration {
            residual: r.clone(),
            step: None,
            damping: None,
        });
        if !r.is_finite() || !all_finite(jac.iter().cloned()) {
            return done(history, x, Some(NewtonFailure::NonFinite));
        }
        if r <= opts.tol {
            let failure = (!sys.admissible(&x)).then_some(NewtonFailure::Inadmissible);
            return done(history, x, failure);
        }
        if history.len() > opts.max_iter {
            return done(history, x, Some(NewtonFailure::IterationLimit));
        }
        let Some(delta) = jac.clone().lu().solve(&(-&f)) else {
            return done(history, x, Some(NewtonFailure::SingularJacobian));
        };
        if !all_finite(delta.iter().cloned()) {
            return done(history, x, Some(NewtonFailure::NonFinite));
        }
        let lambda = if opts.damped {
            match line_search(sys, &x, &delta, &r) {
                Some(l) => l,
                None => return done(history, x, Some(NewtonFailure::LineSearch)),
            }
        } else {
            T::one()
        };
        let step = &delta * lambda.clone();
        let last = history.last_mut().expect("pushed above");
        last.step = Some(step.norm());
        last.damping = Some(lambda);
        x += step;
        (f, jac) = sys.residual_and_jacobian(&x);
    }
}

/// Backtracking: the largest `λ = 2^(−j)`, `j = 0..30`, with an admissible
/// iterate and Armijo decrease (module doc).
fn line_search<T: Real, S: NonlinearSystem<T>>(
    sys: &S,
    x: &DVector<T>,
    delta: &DVector<T>,
    r: &T,
) -> Option<T> {
    let c = T::from_int(1) / T::from_int(10_000);
    let r2 = r.clone() * r;
    let mut lambda = T::one();
    for _ in 0..=30 {
        let trial = x + delta * lambda.clone();
        if sys.admissible(&trial) {
            let rt = sys.residual(&trial).norm();
            let bound = (T::one() - T::from_int(2) * c.clone() * &lambda) * r2.clone();
            if rt.is_finite() && rt.clone() * rt <= bound {
                return Some(lambda);
            }
        }
        lambda = lambda.scale_by_pow2(-1);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    #[allow(unused_imports)]
    use crate::scalar::prelude::*;

    /// `F(x, y) = (x² + y² − 4, x y − 1)`: root with x > y > 0 known in
    /// closed form: x² = 2 + √3, y = 1/x.
    struct Circle;
    impl<T: Real> NonlinearSystem<T> for Circle {
        fn residual(&self, v: &DVector<T>) -> DVector<T> {
            self.residual_and_jacobian(v).0
        }
        fn residual_and_jacobian(&self, v: &DVector<T>) -> (DVector<T>, DMatrix<T>) {
            let (x, y) = (v[0].clone(), v[1].clone());
            let f = DVector::from_vec(vec![
                x.clone() * &x + y.clone() * &y - T::from_int(4),
                x.clone() * &y - T::one(),
            ]);
            let two = T::from_int(2);
            let j = DMatrix::from_row_slice(2, 2, &[two.clone() * &x, two * y.clone(), y, x]);
            (f, j)
        }
    }

    #[test]
    fn converges_quadratically_to_closed_form_root() {
        type M = Mp<256>;
        for damped in [false, true] {
            let opts = NewtonOptions {
                tol: M::unit_roundoff().scale_by_pow2(4),
                max_iter: 30,
                damped,
            };
            let x0 = DVector::from_vec(vec![M::from_int(3), M::from_int(1)]);
            let run = newton(&Circle, x0, &opts);
            assert_eq!(run.failure, None);
            let x = (M::from_int(2) + M::from_int(3).sqrt()).sqrt();
            assert!((run.x[0].clone() - &x).abs() < M::unit_roundoff().scale_by_pow2(6));
            assert!((run.x[1].clone() - x.recip()).abs() < M::unit_roundoff().scale_by_pow2(6));
            // Quadratic phase: some r_{k+1} ≤ 10 r_k² with r_k < 1e-10.
            let r: Vec<f64> = run.history.iter().map(|h| h.residual.to_f64()).collect();
            assert!(
                r.windows(2)
                    .any(|w| w[0] < 1e-10 && w[1] <= 10.0 * w[0] * w[0])
            );
        }
    }

    #[test]
    fn singular_and_limit_are_reported() {
        // Start on the singular line x = y: J = [[2x, 2x], [x, x]].
        let opts = NewtonOptions {
            tol: 1e-14,
            max_iter: 30,
            damped: false,
        };
        let run = newton(&Circle, DVector::from_vec(vec![1.0, 1.0]), &opts);
        assert_eq!(run.failure, Some(NewtonFailure::SingularJacobian));
        let opts = NewtonOptions {
            max_iter: 1,
            ..opts
        };
        let run = newton(&Circle, DVector::from_vec(vec![3.0, 1.0]), &opts);
        assert_eq!(run.failure, Some(NewtonFailure::IterationLimit));
        assert_eq!(run.history.len(), 2);
    }
}
