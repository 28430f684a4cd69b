//! QI interpolation (seed 004): interpolation, G1/G2 and quadratic Newton
//! convergence, each checked by re-integrating the result at a higher
//! precision with an independently chosen Gauss rule.

use splinelab::qi::{NewtonFailure, QiError, QiOptions, interpolate};
use splinelab::scalar::prelude::*;
use splinelab::validation::InputError;
use splinelab_verify::qi::{
    check_fit, circle, convergence_run, helix, paper_like, points_in, wave,
};

/// G1/G2 bounds follow from the Newton tolerance: the G1 residual bounds the
/// angle gap δ and |ΔT| ≤ 2√2 δ (|∂T/∂α| ≤ 1, |∂T/∂β| = 2); the G2 residual
/// bounds h·Δ(α'/l) by 2 (h/l_min)² tol, and the curvature vector adds terms
/// of size κ h δ. For these data sets h/l_min < 2, κ h < 2: 2⁸·tol covers it.
fn assert_fit_ok<T: Real, R: Real>(name: &str, end_bound: f64) {
    let case = match name {
        "helix" => helix(10),
        "circle" => circle(10),
        "wave" => wave(12),
        _ => paper_like(),
    };
    let opts = QiOptions::<T>::default();
    let fit = interpolate(&points_in::<T>(&case), &opts).unwrap();
    let check = check_fit::<T, R>(&fit).unwrap();
    let tol = opts.tol.to_f64();
    assert!(
        check.max_end_error <= end_bound,
        "{name} {}: end error {:e} > {end_bound:e}",
        T::type_name(),
        check.max_end_error
    );
    assert!(
        check.max_g1_error <= 4.0 * tol,
        "{name}: G1 {:e}",
        check.max_g1_error
    );
    assert!(
        check.max_g2_error <= 256.0 * tol,
        "{name}: G2 {:e}",
        check.max_g2_error
    );
}

#[test]
fn f64_fits_hit_every_point_to_1e_12_relative_with_g1_g2_joins() {
    for name in ["helix", "circle", "wave", "paper"] {
        assert_fit_ok::<f64, Mp<128>>(name, 1e-12);
    }
}

#[test]
fn mp256_fits_hit_every_point_to_2_pow_minus_236() {
    for name in ["helix", "paper"] {
        assert_fit_ok::<Mp<256>, Mp<512>>(name, 2f64.powi(-256 + 20));
    }
}

/// Second algorithm/precision: the f64 solution agrees with the Mp<256>
/// solution to what the conditioning of the system allows (~1e-12 here).
#[test]
fn f64_solution_agrees_with_mp256_solution() {
    let case = helix(10);
    let a = interpolate(&points_in::<f64>(&case), &QiOptions::default()).unwrap();
    let b = interpolate(&points_in::<Mp<256>>(&case), &QiOptions::default()).unwrap();
    for (sa, sb) in a.segments.iter().zip(&b.segments) {
        for j in 0..3 {
            assert!((sa.alpha[j] - sb.alpha[j].to_f64()).abs() < 1e-11);
            assert!((sa.beta[j] - sb.beta[j].to_f64()).abs() < 1e-11);
        }
        assert!((sa.length - sb.length.to_f64()).abs() < 1e-11);
    }
}

/// Quadratic convergence over many digits in MPFR: the residuals pass
/// 1e-10 and 1e-20 and 1e-40, each step roughly squares the previous, and
/// the observed order is within 0.15 of 2 on at least three steps.
#[test]
fn mp256_newton_converges_quadratically() {
    let run = convergence_run::<Mp<256>, Mp<512>>(&helix(10), false);
    assert!(run.converged, "{:?}", run.failure);
    let logs: Vec<f64> = run.log10_residuals.iter().map(|l| l.unwrap()).collect();
    for target in [-10.0, -20.0, -40.0] {
        assert!(logs.iter().any(|&l| l < target), "{logs:?}");
    }
    // r_{k+1} ≤ 100 r_k² whenever r_k < 1e-3 and the step is above the floor.
    for w in logs.windows(2) {
        if w[0] < -3.0 && w[1] > -70.0 {
            assert!(w[1] <= 2.0 * w[0] + 2.0, "not quadratic: {logs:?}");
        }
    }
    assert_quadratic_orders(&run.observed_orders);
}

/// Newton converges quadratically: at least three observed orders within
/// 0.15 of 2.
fn assert_quadratic_orders(orders: &[Option<f64>]) {
    let near_two = orders
        .iter()
        .flatten()
        .filter(|p| (*p - 2.0).abs() < 0.15)
        .count();
    assert!(near_two >= 3, "orders {orders:?}");
}

/// One small Mp<1024> case: the paper-like 4 points, checked in Mp<1088>
/// (64 guard bits are ample for a 2^-1004 claim and keep the test cheap;
/// the report checks the Mp<1024> helix in Mp<2048>).
#[test]
fn mp1024_small_case_converges_to_2_pow_minus_1004() {
    let run = convergence_run::<Mp<1024>, Mp<1088>>(&paper_like(), false);
    assert!(run.converged, "{:?}", run.failure);
    let check = run.check.unwrap();
    // 2^(−1024+20) ≈ 5.6e-303 is still a normal f64.
    assert!(
        check.max_end_error <= 2f64.powi(-1004),
        "{:e}",
        check.max_end_error
    );
    assert!(run.log10_residuals.last().unwrap().unwrap() < -290.0);
    assert_quadratic_orders(&run.observed_orders);
}

#[test]
fn bad_inputs_are_typed_errors_not_panics() {
    let o = QiOptions::<Mp<128>>::default();
    let pts = points_in::<Mp<128>>(&helix(6));
    assert_eq!(
        interpolate(&pts[..2], &o).unwrap_err(),
        QiError::Input(InputError::TooFewPoints {
            what: "QI interpolation",
            needed: 3,
            got: 2
        })
    );
    let mut p = pts.clone();
    p[4].x = Mp::new(f64::NAN);
    assert_eq!(
        interpolate(&p, &o).unwrap_err(),
        QiError::Input(InputError::NonFiniteAt {
            what: "point",
            index: 4
        })
    );
    let mut p = pts.clone();
    p[0].z = Mp::new(f64::NEG_INFINITY);
    assert_eq!(
        interpolate(&p, &o).unwrap_err(),
        QiError::Input(InputError::NonFiniteAt {
            what: "point",
            index: 0
        })
    );
    let mut p = pts.clone();
    p[3] = p[2].clone();
    assert_eq!(
        interpolate(&p, &o).unwrap_err(),
        QiError::CoincidentPoints { index: 2 }
    );
    // Non-convergence within the limit: the history comes back.
    let o2 = QiOptions { max_iter: 2, ..o };
    match interpolate(&pts, &o2).unwrap_err() {
        QiError::NotConverged {
            reason,
            residuals,
            steps,
        } => {
            assert_eq!(reason, NewtonFailure::IterationLimit);
            assert_eq!(residuals.len(), 3);
            assert_eq!(steps.len(), 2);
            assert!(residuals[2] < residuals[0]);
        }
        e => panic!("unexpected {e:?}"),
    }
}
