//! `check cond`: the certified references against closed forms, injected
//! errors found where they were put, bad input refused with a typed error.

use splinelab_verify::check::cond::{CondInput, Norm, check_cond};
use splinelab_verify::check::{CheckError, UserFormat};
use splinelab_verify::conditioning::Basis;

fn input(sets: Vec<Vec<f64>>, basis: Basis, norm: Norm, user: Vec<f64>) -> CondInput {
    CondInput {
        node_sets: sets,
        basis,
        norm,
        user,
        format: UserFormat::F64,
        max_ulps: Some(1.0),
    }
}

#[test]
fn closed_forms_pass_and_an_injected_error_is_found() {
    // Monomial on {0, 1}: A = [[1, 0], [1, 1]], A⁻¹ = [[1, 0], [−1, 1]]:
    // cond_∞ = 2 · 2 = 4; σ² = (3 ± √5)/2, so cond₂ = (3 + √5)/2 = φ².
    // Bernstein degree 2 on {0, ½, 1}: B = [[1,0,0],[¼,½,¼],[0,0,1]],
    // B⁻¹ = [[1,0,0],[−½,2,−½],[0,0,1]]: cond_∞ = 1 · 3 = 3.
    let phi2 = (3.0 + 5f64.sqrt()) / 2.0; // within ½ ulp: √5 and the sum/halving round once each
    let cases = [
        (vec![0.0, 1.0], Basis::Monomial, Norm::Inf, 4.0, 0.0),
        (vec![0.0, 1.0], Basis::Monomial, Norm::Two, phi2, 1.0),
        (vec![0.0, 0.5, 1.0], Basis::Bernstein, Norm::Inf, 3.0, 0.0),
        (vec![0.0, 1.0], Basis::Bernstein, Norm::Two, 1.0, 0.0),
    ];
    for (nodes, basis, norm, value, tol) in cases {
        let s = check_cond(&input(vec![nodes.clone()], basis, norm, vec![value])).unwrap();
        let w = s.worst.clone().unwrap();
        assert!(w.ulps <= tol, "{basis:?} {norm:?}: {} ulps", w.ulps);
        assert_eq!(s.verdict, "pass");
        let off = f64::from_bits(value.to_bits() + 3);
        let s = check_cond(&input(vec![nodes], basis, norm, vec![off])).unwrap();
        let w = s.worst.unwrap();
        assert!(
            (w.ulps - 3.0).abs() <= tol,
            "{basis:?} {norm:?}: {}",
            w.ulps
        );
        assert_eq!((s.failed, s.verdict.as_str()), (1, "fail"));
    }
}

#[test]
fn several_node_sets_are_checked_element_by_element() {
    let sets = vec![vec![0.0, 1.0], vec![0.0, 0.5, 1.0]];
    let s = check_cond(&input(
        sets,
        Basis::Bernstein,
        Norm::Inf,
        vec![1.0, f64::NAN],
    ))
    .unwrap();
    assert_eq!((s.n, s.non_finite, s.verdict.as_str()), (2, 1, "fail"));
    assert_eq!(s.worst.unwrap().index, 1);
}

#[test]
fn bad_input_is_a_typed_error() {
    let one = input(vec![vec![0.5]], Basis::Monomial, Norm::Two, vec![1.0]);
    assert!(matches!(check_cond(&one), Err(CheckError::Invalid(_))));
    let twice = input(vec![vec![0.5, 0.5]], Basis::Monomial, Norm::Inf, vec![1.0]);
    assert!(matches!(check_cond(&twice), Err(CheckError::Invalid(_))));
    let short = input(vec![vec![0.0, 1.0]], Basis::Monomial, Norm::Two, vec![]);
    assert!(matches!(
        check_cond(&short),
        Err(CheckError::LengthMismatch { .. })
    ));
    let nan = input(
        vec![vec![0.0, f64::NAN]],
        Basis::Monomial,
        Norm::Two,
        vec![1.0],
    );
    assert!(matches!(
        check_cond(&nan),
        Err(CheckError::NonFiniteInput { .. })
    ));
}
