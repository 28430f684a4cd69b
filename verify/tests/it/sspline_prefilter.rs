//! The full build of interpolation coefficients (recursive prefilter and
//! truncated convolution) against the exact rational solution of the
//! interpolation conditions `Σ_i D_{fold(i)} β(j − i) = s_j`, assembled from
//! the exact node values: a reference that uses neither poles nor `c_i`.

use proptest::prelude::*;
use rug::Rational;
use splinelab::scalar::prelude::*;
use splinelab::sspline::SplineFamily;
use splinelab::sspline::end_conditions::EndRule;
use splinelab::sspline::euler_frobenius::PoleExpansion;
use splinelab::sspline::node_values::node_values_exact;
use splinelab::sspline::prefilter::{ConvolutionPrefilter, PrefilterError, RecursivePrefilter};
use splinelab::validation::NonFiniteValue;
use splinelab_verify::exact::solve_rational;
use splinelab_verify::update_cost::inverse_norm;

fn family(sel: u32) -> SplineFamily {
    match sel {
        9 => SplineFamily::beta2(Rational::from((5, 2))).unwrap(),
        m => SplineFamily::Order(m),
    }
}

/// The exact `D` for samples `s` (exact as rationals) under `end`.
fn exact(family: &SplineFamily, s: &[f64], end: EndRule) -> Vec<Rational> {
    let v = node_values_exact(family).unwrap();
    let p = (v.len() / 2) as i64;
    let len = s.len();
    let mut a = vec![vec![Rational::new(); len]; len];
    for (j, row) in a.iter_mut().enumerate() {
        for d in -p..=p {
            let k = end.fold(j as i64 - d, len).0;
            row[k] += &v[(p + d) as usize];
        }
    }
    let b: Vec<Rational> = s.iter().map(|&x| Rational::from_f64(x).unwrap()).collect();
    solve_rational(a, &b).expect("the interpolation matrix is nonsingular")
}

/// `max_k |D_k − exact_k|` over `‖1/V‖₁ max |s|` (the scale of `D`), in
/// units of `2^{-bits}`.
fn worst<T: Real>(d: &[T], exact: &[Rational], s: &[f64], f: &SplineFamily, bits: i32) -> f64 {
    let scale = s
        .iter()
        .fold(0f64, |m, x| m.max(x.abs()))
        .max(f64::MIN_POSITIVE)
        * inverse_norm(f).unwrap();
    d.iter()
        .zip(exact)
        .map(|(x, e)| {
            let err = (x.to_rational().unwrap() - e).abs();
            (err.to_f64() / scale) * 2f64.powi(bits)
        })
        .fold(0.0, f64::max)
}

fn samples<T: Real>(s: &[f64]) -> Vec<T> {
    s.iter().map(|&x| T::from_f64_exact(x)).collect()
}

fn end(sel: u8) -> EndRule {
    if sel == 0 {
        EndRule::Reflect
    } else {
        EndRule::Periodic
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// f64: a few ulps of the scale of `D` (the stable recursions amplify
    /// rounding by `1/(1 − |ξ|)` per pass).
    #[test]
    fn recursive_f64_matches_the_exact_solution(
        sel in prop::sample::select(vec![2u32, 3, 4, 5, 6, 8, 9]),
        e in 0u8..2,
        s in prop::collection::vec(-1000i32..1000, 1..24),
    ) {
        let s: Vec<f64> = s.iter().map(|&x| x as f64 / 64.0).collect();
        let f = family(sel);
        let d = RecursivePrefilter::<f64>::new(&f).unwrap().apply(&s, end(e)).unwrap();
        let w = worst(&d, &exact(&f, &s, end(e)), &s, &f, 53);
        prop_assert!(w <= 8.0, "{f} {:?} ν={}: {w} ulps", end(e), s.len());
    }

    /// The convolution differs from the exact `D` by at most the tail bound
    /// `Σ_{|j|>n} |c_j| · max |s|` plus a dot product's rounding.
    #[test]
    fn convolution_is_within_its_tail_bound(
        sel in prop::sample::select(vec![3u32, 4, 6, 9]),
        e in 0u8..2,
        n in 1usize..30,
        s in prop::collection::vec(-1000i32..1000, 2..24),
    ) {
        let s: Vec<f64> = s.iter().map(|&x| x as f64 / 64.0).collect();
        let f = family(sel);
        let d = ConvolutionPrefilter::<f64>::new(&f, n).unwrap().apply(&s, end(e)).unwrap();
        let tail = PoleExpansion::<Mp<128>>::new(&f).unwrap().tail_bound(n).to_f64();
        let bound = tail * 2f64.powi(53) + 4.0 * (2 * n + 1) as f64;
        let w = worst(&d, &exact(&f, &s, end(e)), &s, &f, 53);
        prop_assert!(w <= bound, "{f} n={n}: {w} ulps > {bound}");
    }
}

/// 256 bits, exact initial sums (ν below the horizon): within 2^{−240}.
#[test]
fn recursive_mp256_matches_the_exact_solution() {
    for sel in [4u32, 6, 9] {
        for e in 0..2 {
            let s: Vec<f64> = (0..17)
                .map(|i| ((i * 37 % 23) as f64 - 11.0) / 8.0)
                .collect();
            let f = family(sel);
            let d = RecursivePrefilter::<Mp<256>>::new(&f)
                .unwrap()
                .apply(&samples(&s), end(e))
                .unwrap();
            let w = worst(&d, &exact(&f, &s, end(e)), &s, &f, 240);
            assert!(w <= 1.0, "{f} {:?}: {w} × 2^-240", end(e));
        }
    }
}

/// 64 bits with ν = 48 above the horizon (38 terms for the cubic pole):
/// the truncated initial sums stay within a few units of 2^{−64}.
#[test]
fn truncated_initial_sums_keep_full_accuracy() {
    let s: Vec<f64> = (0..48)
        .map(|i| ((i * 53 % 31) as f64 - 15.0) / 4.0)
        .collect();
    for sel in [4u32, 6] {
        for e in 0..2 {
            let f = family(sel);
            let d = RecursivePrefilter::<Mp<64>>::new(&f)
                .unwrap()
                .apply(&samples(&s), end(e))
                .unwrap();
            let w = worst(&d, &exact(&f, &s, end(e)), &s, &f, 64);
            assert!(w <= 32.0, "{f} {:?}: {w} × 2^-64", end(e));
        }
    }
}

#[test]
fn bad_signals_are_refused() {
    let f = SplineFamily::Order(4);
    let r = RecursivePrefilter::<f64>::new(&f).unwrap();
    let c = ConvolutionPrefilter::<f64>::new(&f, 8).unwrap();
    assert_eq!(r.apply(&[], EndRule::Reflect), Err(PrefilterError::Empty));
    assert_eq!(c.apply(&[], EndRule::Free), Err(PrefilterError::Empty));
    let bad = [1.0, f64::NAN, 2.0];
    assert_eq!(
        r.apply(&bad, EndRule::Periodic),
        Err(PrefilterError::NonFinite {
            index: 1,
            value: NonFiniteValue::Nan
        })
    );
    assert_eq!(
        c.apply(&[f64::INFINITY], EndRule::Reflect),
        Err(PrefilterError::NonFinite {
            index: 0,
            value: NonFiniteValue::Inf
        })
    );
    assert_eq!(
        r.apply(&[1.0, 2.0], EndRule::Free),
        Err(PrefilterError::UnsupportedEnd(EndRule::Free))
    );
    assert!(matches!(
        ConvolutionPrefilter::<f64>::new(&f, 0),
        Err(PrefilterError::Sspline(_))
    ));
}

/// Long signals (several interior blocks): the convolution at the
/// f64-saturating width against the recursive filter in 128 bits.
#[test]
fn long_convolution_matches_the_mpfr_recursive_build() {
    let s: Vec<f64> = (0..5000)
        .map(|i| ((i * 7919 % 2003) as f64 - 1001.0) / 1024.0)
        .collect();
    for sel in [4u32, 6] {
        let f = family(sel);
        let n = splinelab::sspline::f64_saturation_width(&f).unwrap();
        let d = ConvolutionPrefilter::<f64>::new(&f, n)
            .unwrap()
            .apply(&s, EndRule::Reflect)
            .unwrap();
        let r = RecursivePrefilter::<Mp<128>>::new(&f)
            .unwrap()
            .apply(&samples(&s), EndRule::Reflect)
            .unwrap();
        let scale =
            2f64.powi(-53) * inverse_norm(&f).unwrap() * s.iter().fold(0f64, |m, x| m.max(x.abs()));
        let w = d
            .iter()
            .zip(&r)
            .map(|(x, y)| (Mp::<128>::from_f64_exact(*x) - y.clone()).abs().to_f64() / scale)
            .fold(0f64, f64::max);
        assert!(w <= 16.0, "{f}: {w} u");
    }
}
