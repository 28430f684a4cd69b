//! Truncation error measures and the width chooser (seed 000 eq 10, 28):
//! ordering knot ≤ uniform ≤ bound, the sup against dense sampling, the knot
//! error against direct evaluation in higher precision, and the chooser
//! against the cubic closed form.

use nalgebra::ComplexField;
use rug::Rational;
use splinelab::scalar::{Mp, Real};
use splinelab::sspline::{
    Criterion, SplineFamily, SsplineError, TruncatedBasis, TruncationAnalysis, truncation_width,
};

type M = Mp<128>;

fn families() -> Vec<SplineFamily> {
    vec![
        SplineFamily::Order(3),
        SplineFamily::Order(4),
        SplineFamily::Order(7),
        SplineFamily::Beta2(Rational::from(5)),
        SplineFamily::Beta2(Rational::from((1, 3))),
    ]
}

#[test]
fn knot_le_uniform_le_bound() {
    for f in families() {
        let a = TruncationAnalysis::<M>::new(&f, 12).unwrap();
        for n in 1..=12 {
            let e = a.errors(n);
            assert!(
                e.knot <= e.uniform && e.uniform <= e.bound,
                "{f} n={n}: {e:?}"
            );
        }
    }
}

/// Two-sided: the analysis' sup is not below the best of 1001 dense samples
/// refined by 80 golden-section steps (its own search uses 17 samples and
/// f64), nor above it by more than its documented `10⁻⁹`. The pointwise
/// error itself is checked against closed forms in
/// `sspline_width_closed_forms.rs`.
#[test]
fn uniform_error_is_the_sup_of_dense_samples() {
    for f in families() {
        let a = TruncationAnalysis::<M>::new(&f, 4).unwrap();
        for n in [1, 3] {
            let sup = a.uniform_error(n);
            let refined = refined_sup(|x| a.curve_error(n, x), 1000);
            let rel = ((refined.clone() - sup.clone()) / refined.clone())
                .abs()
                .to_f64();
            assert!(rel < 1e-9, "{f} n={n}: refined {refined:?} vs sup {sup:?}");
        }
    }
}

/// `max` of `g` on `[0, ½]`: `grid + 1` samples, then golden section in the
/// bracket of the best one, in `M`.
fn refined_sup(g: impl Fn(&M) -> M, grid: i64) -> M {
    let at = |j: i64| M::from_int(j) / M::from_int(2 * grid);
    let (j, mut top) = (0..=grid)
        .map(|j| (j, g(&at(j))))
        .fold((0, M::from_int(-1)), |b, v| if v.1 > b.1 { v } else { b });
    let (mut lo, mut hi) = (at((j - 1).max(0)), at((j + 1).min(grid)));
    let ratio = (M::from_int(5).sqrt() - M::from_int(1)) / M::from_int(2);
    for _ in 0..80 {
        let x1 = hi.clone() - ratio.clone() * (hi.clone() - lo.clone());
        let x2 = lo.clone() + ratio.clone() * (hi.clone() - lo.clone());
        let (f1, f2) = (g(&x1), g(&x2));
        if f1 < f2 {
            lo = x1;
        } else {
            hi = x2;
        }
        top = [f1, f2]
            .into_iter()
            .fold(top, |t, f| if f > t { f } else { t });
    }
    top
}

/// The knot error from the tail equals `max_j |S_n(j) − δ_{0j}|` evaluated
/// directly from the truncated basis in 256-bit MPFR (a different route:
/// the full truncated sum, cancelling against δ).
#[test]
fn knot_error_matches_direct_evaluation() {
    for f in families() {
        let a = TruncationAnalysis::<M>::new(&f, 8).unwrap();
        for n in [1, 2, 5, 8] {
            let s = TruncatedBasis::<Mp<256>>::new(&f, n).unwrap();
            let direct = (0..=n as i64 + 4)
                .map(|j| {
                    let d = if j == 0 { 1 } else { 0 };
                    (s.eval(&Mp::from_int(j)) - Mp::from_int(d)).abs()
                })
                .fold(Mp::<256>::from_int(0), |x, y| if y > x { y } else { x });
            let tail = a.knot_error(n);
            let rel = ((direct.to_f64() - tail.to_f64()) / tail.to_f64()).abs();
            assert!(rel < 1e-14, "{f} n={n}: {direct:?} vs {tail:?}");
        }
    }
}

/// Cubic: |c_n| = √3 (2 − √3)^n exactly (eq 18), so the coeff width is the
/// smallest n ≥ 1 with that below ε — computed here in 256-bit MPFR.
#[test]
fn coeff_width_of_the_cubic_matches_eq18() {
    let s3 = Mp::<256>::from_int(3).sqrt();
    let rho = Mp::<256>::from_int(2) - s3.clone();
    for tol in [0.5, 1e-3, 1e-6, 3e-9, 1e-12, 1e-15, 1e-30] {
        let want = (1..)
            .find(|n| s3.clone() * rho.clone().powi(*n) < Mp::from_f64_exact(tol))
            .unwrap() as usize;
        let w = truncation_width(&SplineFamily::Order(4), tol, Criterion::Coeff).unwrap();
        assert_eq!(w.n, want, "tol {tol}");
        assert!(w.achieved < tol);
    }
}

#[test]
fn widths_meet_the_tolerance_minimally_and_grow_as_it_shrinks() {
    for f in families() {
        for c in Criterion::all() {
            let mut last = 0;
            for tol in [1e-2, 1e-4, 1e-8, 1e-12] {
                let w = truncation_width(&f, tol, c).unwrap();
                let a = TruncationAnalysis::<M>::new(&f, w.n).unwrap();
                let measure = |n| match c {
                    Criterion::Coeff => a.coeff_error(n),
                    Criterion::Knot => a.knot_error(n),
                    Criterion::Uniform => a.uniform_error(n),
                };
                let eps = M::from_f64_exact(tol);
                assert!(measure(w.n) < eps, "{f} {c} {tol}");
                assert!(
                    (1..w.n).all(|n| measure(n) >= eps),
                    "{f} {c} {tol}: not minimal"
                );
                assert!(w.bound >= a.uniform_error(w.n).to_f64());
                assert!(w.n >= last);
                last = w.n;
            }
        }
    }
}

#[test]
fn bad_tolerances_are_typed_errors() {
    let f = SplineFamily::Order(4);
    for tol in [0.0, -1e-3, 1.0, 2.0, f64::NAN, f64::INFINITY] {
        assert!(matches!(
            truncation_width(&f, tol, Criterion::Knot),
            Err(SsplineError::InvalidTolerance(_))
        ));
    }
    assert!(matches!(
        TruncatedBasis::<f64>::new(&f, 0),
        Err(SsplineError::ZeroWidth)
    ));
}
