//! Condition numbers in f64 and MPFR against independent references.

use nalgebra::DMatrix;
use rug::{Integer, Rational};
use splinelab::matrix_condition::{cond_inf, cond2};
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::vandermonde::{NodeFamily, tensor_bernstein_vandermonde};
use splinelab_verify::conditioning::{Basis, CondCase, condition_numbers, measure};
use splinelab_verify::metrics::relative_error;

type M = Mp<256>;

fn hilbert<T: Real>(n: usize) -> DMatrix<T> {
    DMatrix::from_fn(n, n, |i, j| {
        T::from_rational(&Rational::from((1, (i + j + 1) as i64)))
    })
}

/// The exact inverse of the Hilbert matrix (1-based closed form):
/// (H⁻¹)_ij = (−1)^(i+j) (i+j−1) C(n+i−1, n−j) C(n+j−1, n−i) C(i+j−2, i−1)².
fn hilbert_inverse<T: Real>(n: usize) -> DMatrix<T> {
    let c = |a: usize, b: usize| Integer::from(Integer::binomial_u(a as u32, b as u32));
    DMatrix::from_fn(n, n, |i0, j0| {
        let (i, j) = (i0 + 1, j0 + 1);
        let sign = if (i + j) % 2 == 0 { 1 } else { -1 };
        let cc = c(i + j - 2, i - 1);
        let v = Integer::from(sign * (i + j - 1) as i64)
            * c(n + i - 1, n - j)
            * c(n + j - 1, n - i)
            * cc.clone()
            * cc;
        T::from_rational(&Rational::from(v))
    })
}

/// Largest eigenvalue of a symmetric matrix by the power method with the
/// Rayleigh quotient: an algorithm independent of the SVD under test.
fn lambda_max(a: &DMatrix<Mp<512>>) -> Mp<512> {
    let n = a.nrows();
    let mut x = nalgebra::DVector::from_element(n, Mp::<512>::one());
    let mut rq = Mp::<512>::zero();
    for _ in 0..400 {
        let y = a * &x;
        rq = x.dot(&y) / x.dot(&x);
        let norm = y.norm();
        x = y / norm;
    }
    rq
}

#[test]
fn mpfr_svd_gets_hilbert_condition_numbers_to_20_digits_and_f64_does_not() {
    for n in [6usize, 8, 10] {
        // Reference: λ_max(H) · λ_max(H⁻¹), H⁻¹ exact, power method in 512 bits.
        let reference = lambda_max(&hilbert(n)) * lambda_max(&hilbert_inverse(n));
        let r = reference.to_float();
        let mp = cond2(&hilbert::<M>(n)).unwrap();
        let rel = relative_error(&mp, &r);
        assert!(
            rel < 1e-20,
            "n={n}: Mp<256> cond2 {mp} vs reference {reference}: rel {rel:e}"
        );
        // f64 loses about log10(cond) of its 16 digits, but stays within the
        // backward-error bound c·n·u·cond.
        let f = cond2(&hilbert::<f64>(n)).unwrap();
        let rel_f = relative_error(&f, &r);
        let c = reference.to_f64();
        assert!(
            rel_f > 1e3 * f64::EPSILON,
            "n={n}: f64 unexpectedly kept all digits"
        );
        assert!(
            rel_f < 10.0 * n as f64 * f64::EPSILON * c,
            "n={n}: rel {rel_f:e}"
        );
    }
    // Published: cond₂(H_10) ≈ 1.6025e13 (Higham, Accuracy and Stability of
    // Numerical Algorithms, 2nd ed., §28.1).
    let h10 = cond2(&hilbert::<M>(10)).unwrap().to_f64();
    assert!((h10 / 1.6025e13 - 1.0).abs() < 1e-4, "{h10:e}");
}

#[test]
fn tensor_condition_numbers_are_products_of_the_univariate_ones() {
    for (n, nodes) in [
        (3usize, NodeFamily::Equispaced),
        (4, NodeFamily::ChebyshevGauss),
    ] {
        let t: Vec<M> = nodes.nodes(n).unwrap();
        let full = tensor_bernstein_vandermonde(&t, &t);
        let one = CondCase {
            degree: n,
            nodes,
            basis: Basis::Bernstein,
            tensor: false,
        };
        let uni = condition_numbers::<M>(&one).unwrap();
        let tol = M::from_f64_exact(1e-60);
        for (direct, product) in [
            (cond2(&full).unwrap(), uni.cond2.clone() * uni.cond2.clone()),
            (
                cond_inf(&full).unwrap(),
                uni.cond_inf.clone() * uni.cond_inf.clone(),
            ),
        ] {
            let rel = ((direct.clone() - product.clone()) / product.clone()).abs();
            assert!(rel < tol, "n={n}: {direct} vs {product}");
        }
    }
}

#[test]
fn f64_bernstein_vandermonde_condition_matches_mpfr_to_the_digits_cond_eps_allows() {
    for nodes in NodeFamily::all() {
        for degree in [2usize, 5, 10, 15, 20, 25, 30] {
            let case = CondCase {
                degree,
                nodes,
                basis: Basis::Bernstein,
                tensor: false,
            };
            let row = measure(&case).unwrap();
            let rel = 10f64.powf(-row.cond2_digits);
            let allowed = 10.0 * (degree + 1) as f64 * f64::EPSILON * row.cond2_ref_f64;
            assert!(
                rel <= allowed.max(2.0 * f64::EPSILON),
                "{nodes} n={degree}: f64 {:e} vs mpfr {}: rel {rel:e} > {allowed:e}",
                row.cond2_f64,
                row.cond2_ref
            );
            let rel_inf = 10f64.powf(-row.cond_inf_digits);
            assert!(
                rel_inf <= allowed.max(2.0 * f64::EPSILON),
                "{nodes} n={degree} cond_inf"
            );
        }
    }
}

#[test]
fn bernstein_basis_is_better_conditioned_than_monomial_at_high_degree() {
    // A known result (Farouki–Rajan 1988): at equispaced nodes on [0, 1] the
    // Bernstein basis is far better conditioned than the power basis.
    let case = |basis| CondCase {
        degree: 20,
        nodes: NodeFamily::Equispaced,
        basis,
        tensor: false,
    };
    let b = condition_numbers::<M>(&case(Basis::Bernstein))
        .unwrap()
        .cond2;
    let m = condition_numbers::<M>(&case(Basis::Monomial))
        .unwrap()
        .cond2;
    assert!(
        m > b.clone() * M::from_int(1000),
        "bernstein {b}, monomial {m}"
    );
}
