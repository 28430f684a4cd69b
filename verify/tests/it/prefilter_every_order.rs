//! `RecursivePrefilter` in `f64` and `f32` at every order 2..=200: poles
//! rounded once from MPFR, results checked against a 256-bit build, and the
//! ill-conditioning estimate checked to bound the measured error.

use rayon::prelude::*;
use splinelab::scalar::{Mp, Real};
use splinelab::sspline::SplineFamily;
use splinelab::sspline::end_conditions::EndRule;
use splinelab::sspline::prefilter::{PrefilterError, RecursivePrefilter};
use splinelab_verify::rng::SplitMix64;

type W = Mp<256>;

/// A fixed pseudo-random signal in [−1, 1).
fn signal(n: usize) -> Vec<f64> {
    SplitMix64::new(0x9e37_79b9_7f4a_7c15).signal(n)
}

/// max_k |a_k − b_k| / max|b|, the reference in 256 bits.
fn rel_err<T: Real>(a: &[T], b: &[W]) -> f64 {
    let scale = b.iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
    a.iter()
        .zip(b)
        .map(|(x, y)| (W::from_f64_exact(x.to_f64()) - y.clone()).to_f64().abs())
        .fold(0.0, f64::max)
        / scale
}

/// Every order up to 120 (the failures were 46, 49, 51, 53, 55 and
/// ≥ 57) and a sample above (each of those builds takes ~1 s of MPFR).
#[test]
fn every_order_builds_in_f64_and_the_estimate_bounds_the_error() {
    let s = signal(300);
    let sw: Vec<W> = s.iter().map(|x| W::from_f64_exact(*x)).collect();
    let orders: Vec<u32> = (2..=120).chain([133, 157, 181, 199, 200]).collect();
    orders.par_iter().for_each(|&m| {
        let f = SplineFamily::Order(m);
        let p64 = RecursivePrefilter::<f64>::new(&f).unwrap_or_else(|e| panic!("m={m}: {e}"));
        assert_eq!(p64.poles().len(), f.pole_count(), "m={m}");
        let est = p64.estimated_error();
        assert!(est.is_finite() && est > 0.0, "m={m}");
        // Only orders the reference can check cheaply and f64 can represent.
        if m % 7 != 4 || est > 1e-2 {
            return;
        }
        let got = p64.apply(&s, EndRule::Reflect).unwrap();
        let want = RecursivePrefilter::<W>::new(&f)
            .unwrap()
            .apply(&sw, EndRule::Reflect)
            .unwrap();
        let err = rel_err(&got, &want);
        assert!(
            err <= 32.0 * est.max(f64::EPSILON),
            "m={m}: error {err:e}, estimate {est:e}"
        );
    });
}

#[test]
fn f32_prefilter_matches_the_reference() {
    let s = signal(200);
    let s32: Vec<f32> = s.iter().map(|x| *x as f32).collect();
    let sw: Vec<W> = s32.iter().map(|x| W::from_f64_exact(*x as f64)).collect();
    for m in [2u32, 4, 6, 8, 12] {
        let f = SplineFamily::Order(m);
        let p = RecursivePrefilter::<f32>::new(&f).unwrap();
        let want = RecursivePrefilter::<W>::new(&f)
            .unwrap()
            .apply(&sw, EndRule::Reflect)
            .unwrap();
        let err = rel_err(&p.apply(&s32, EndRule::Reflect).unwrap(), &want);
        assert!(err <= 32.0 * p.estimated_error(), "m={m}: {err:e}");
    }
}

#[test]
fn ill_conditioned_degrees_are_refused_with_a_suggestion() {
    let f = SplineFamily::Order(100);
    match RecursivePrefilter::<f64>::new_within(&f, 1e-8) {
        Err(PrefilterError::IllConditioned {
            estimated,
            suggested_bits,
            amplification,
            ..
        }) => {
            assert!(estimated > 1e-8);
            // At the suggested precision the estimate meets the tolerance.
            assert!(amplification * (-(suggested_bits as f64)).exp2() <= 1e-8);
            assert!(suggested_bits > 53 && suggested_bits < 200);
        }
        other => panic!("expected IllConditioned, got {other:?}"),
    }
    // The same degree is fine in 256 bits.
    assert!(RecursivePrefilter::<W>::new_within(&f, 1e-30).is_ok());
    // Cubic: amplification 1/|V(−1)| = 1/(2/3 − 1/3) = 3 exactly.
    let c = RecursivePrefilter::<f64>::new(&SplineFamily::Order(4)).unwrap();
    assert!((c.amplification() - 3.0).abs() < 1e-15);
}
