//! The Bernstein–Vandermonde solvers against exact rationals, MPFR and each
//! other (seed 001 eq 3; Marco–Martínez 2007).

use nalgebra::DMatrix;
use proptest::prelude::*;
use rug::Rational;
use rug::ops::Pow;
use splinelab::bernstein::basis::binomial;
use splinelab::matrix_condition::cond_inf;
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::bv_solve::{
    BvError, Method1d, TensorSolver, solve_1d, solve_tensor,
};
use splinelab::surface_deformation::inverse_mapping::{SampleGrid, control_points, sample};
use splinelab::surface_deformation::patch::{Patch, Point3};
use splinelab::surface_deformation::vandermonde::{NodeFamily, bernstein_vandermonde};
use splinelab::validation::InputError;
use splinelab_verify::bv_solvers::{RhsKind, measure, right_hand_sides};
use splinelab_verify::exact::solve_rational;
use splinelab_verify::metrics::ulps_f64;

/// Solves `A x = b` exactly, `A_{ji} = B_i^n(t_j)` at exact rational nodes.
fn exact_solve(t: &[Rational], b: &[Rational]) -> Vec<Rational> {
    let n = t.len() - 1;
    let a: Vec<Vec<Rational>> = t
        .iter()
        .map(|tj| {
            let om = Rational::from(1) - tj.clone();
            (0..=n)
                .map(|i| {
                    Rational::from(binomial(n as u32, i as u32))
                        * tj.clone().pow(i as u32)
                        * om.clone().pow((n - i) as u32)
                })
                .collect()
        })
        .collect();
    solve_rational(a, b).expect("nonsingular")
}

#[test]
fn marco_martinez_matches_exact_rational_solutions_to_a_few_ulps() {
    // The system actually solved: the f64 nodes j/n and the f64 right-hand
    // side, both taken as exact rationals.
    let mut worst = 0f64;
    for n in [1usize, 2, 3, 4, 6, 9, 12, 16, 20] {
        let t: Vec<f64> = NodeFamily::Equispaced.nodes(n).unwrap();
        let tq: Vec<Rational> = t.iter().map(|&x| Rational::from_f64(x).unwrap()).collect();
        let r = right_hand_sides(RhsKind::SignAlternating, n + 1, n + 1, 42 + n as u64);
        let x = solve_1d(&t, &r, Method1d::MarcoMartinez).unwrap();
        for c in 0..2 {
            let b: Vec<Rational> = r
                .column(c)
                .iter()
                .map(|&v| Rational::from_f64(v).unwrap())
                .collect();
            let exact = exact_solve(&tq, &b);
            for (i, e) in exact.iter().enumerate() {
                let ulps = ulps_f64(x[(i, c)], &rug::Float::with_val(256, e));
                worst = worst.max(ulps);
                // Bound from the error analysis: O(n) roundings per multiplier,
                // 2n no-cancellation passes: relative error ≤ c·n²·u; measured
                // errors are far smaller (a few ulps), the bound uses 2n + 8.
                assert!(
                    ulps <= 2.0 * n as f64 + 8.0,
                    "n={n} i={i}: {} vs {} ({ulps} ulps)",
                    x[(i, c)],
                    e.to_f64()
                );
            }
        }
    }
    assert!(worst > 0.0, "a test that measured nothing");
}

#[test]
fn marco_martinez_stays_near_u_where_gepp_follows_cond_u() {
    for n in [20usize, 30] {
        let row = measure(n, NodeFamily::Equispaced, RhsKind::SignAlternating).unwrap();
        let cond_u = row.cond2_1d * f64::EPSILON / 2.0;
        // Componentwise, independent of cond: the a-priori bound is O(n²u).
        assert!(
            row.mm_1d.componentwise < (n * n) as f64 * f64::EPSILON,
            "{row:?}"
        );
        assert!(
            row.kronecker_mm.componentwise < 2.0 * (n * n) as f64 * f64::EPSILON,
            "{row:?}"
        );
        assert!(row.mm_1d.componentwise < 1e-3 * cond_u, "{row:?}");
        // GEPP is backward stable: its normwise error stays within (n+1)·cond·u.
        assert!(row.gepp_1d.normwise < (n + 1) as f64 * cond_u, "{row:?}");
    }
}

#[test]
fn kronecker_solve_equals_the_full_solve() {
    type M = Mp<256>;
    for (family, n) in [
        (NodeFamily::Equispaced, 4usize),
        (NodeFamily::ChebyshevGauss, 5),
        (NodeFamily::ChebyshevLobatto, 3),
    ] {
        let t: Vec<M> = family.nodes(n).unwrap();
        let k = (n + 1) * (n + 1);
        let r = right_hand_sides(RhsKind::Random, k, n + 1, 3).map(M::from_f64_exact);
        let full = solve_tensor(&t, &t, &r, TensorSolver::FullLu).unwrap();
        for s in [
            TensorSolver::KroneckerLu,
            TensorSolver::KroneckerMarcoMartinez,
        ] {
            let x = solve_tensor(&t, &t, &r, s).unwrap();
            let err = (&x - &full).amax() / full.amax();
            assert!(
                err < M::from_f64_exact(1e-60),
                "{family} n={n} {s:?}: {}",
                err.to_f64()
            );
        }
    }
    // And in f64 they agree to the conditioning of the problem.
    let t: Vec<f64> = NodeFamily::Equispaced.nodes(6).unwrap();
    let r = right_hand_sides(RhsKind::Random, 49, 7, 5);
    let full = solve_tensor(&t, &t, &r, TensorSolver::FullLu).unwrap();
    let kron = solve_tensor(&t, &t, &r, TensorSolver::KroneckerLu).unwrap();
    let c = cond_inf(&bernstein_vandermonde(&t)).unwrap().powi(2);
    assert!((&kron - &full).amax() <= 64.0 * c * f64::EPSILON * full.amax());
}

#[test]
fn bad_input_is_a_typed_error_and_nothing_is_solved() {
    let r = DMatrix::from_element(9, 1, 1.0);
    let ok = [0.0, 0.5, 1.0];
    for s in TensorSolver::all() {
        assert_eq!(
            solve_tensor(&[0.0, 0.5, 0.5], &ok, &r, s),
            Err(BvError::RepeatedNode { index: 1 })
        );
        assert!(matches!(
            solve_tensor(&ok, &[-0.1, 0.5, 1.0], &r, s),
            Err(BvError::NodeOutOfRange { index: 0, .. })
        ));
        assert_eq!(
            solve_tensor(&ok, &ok, &r.rows(0, 8).into_owned(), s),
            Err(BvError::SizeMismatch {
                expected: 9,
                got: 8
            })
        );
        let mut bad = r.clone();
        bad[(4, 0)] = f64::NAN;
        assert_eq!(
            solve_tensor(&ok, &ok, &bad, s),
            Err(BvError::Input(InputError::NonFiniteEntry {
                what: "right-hand side",
                row: 4,
                col: 0
            }))
        );
    }
}

/// The eq 3 round trip P → samples → P, generic over the scalar: each
/// solver must return the control net within the backward-error bound
/// `c (n+1)² cond_∞(B̃) u ‖P‖` (for Bernstein rows `‖B̃‖_∞ = 1`).
fn round_trip<T: Real>(degree: usize, family: NodeFamily, coords: &[f64]) {
    let k = (degree + 1) * (degree + 1);
    let control: Vec<Point3<T>> = (0..k)
        .map(|i| {
            Point3::new(
                T::from_f64_exact(coords[3 * i]),
                T::from_f64_exact(coords[3 * i + 1]),
                T::from_f64_exact(coords[3 * i + 2]),
            )
        })
        .collect();
    let patch = Patch::new(degree, control).unwrap();
    let grid = SampleGrid::<T>::from_family(family, degree).unwrap();
    let samples = sample(&patch, &grid).unwrap();
    let c = cond_inf(&bernstein_vandermonde(grid.u())).unwrap();
    let scale = patch
        .control()
        .iter()
        .map(|p| p.amax())
        .fold(T::zero(), |a, b| a.max(b));
    let tol = T::from_int((4 * k) as i64) * c.clone() * c * T::unit_roundoff() * scale;
    for s in TensorSolver::all() {
        let back = control_points(&grid, &samples, s).unwrap();
        for (p, q) in back.control().iter().zip(patch.control()) {
            assert!(
                (p - q).amax() <= tol,
                "{s:?} n={degree} {family}: {:?} vs {:?}",
                p,
                q
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn eq3_round_trip_recovers_the_control_points_f64(
        degree in 1usize..=7,
        family in 0usize..3,
        coords in proptest::collection::vec(-10.0f64..10.0, 3 * 64),
    ) {
        round_trip::<f64>(degree, NodeFamily::all().nth(family).unwrap(), &coords);
    }

    #[test]
    fn eq3_round_trip_recovers_the_control_points_mp(
        degree in 1usize..=5,
        family in 0usize..3,
        coords in proptest::collection::vec(-10.0f64..10.0, 3 * 36),
    ) {
        round_trip::<Mp<128>>(degree, NodeFamily::all().nth(family).unwrap(), &coords);
    }
}
