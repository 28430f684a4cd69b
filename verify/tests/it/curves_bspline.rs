//! B-splines and NURBS: de Boor against the Cox–de Boor basis sum (a second
//! algorithm) on random knot vectors, clamped Bézier knots against
//! de Casteljau and the hodograph, the bicubic Bézier patch (seed 001's
//! `Patch`) against the NURBS surface, and the serde round trip.

use crate::common;
use common::strategies::grid_points;
use nalgebra::{Vector2, Vector3};
use proptest::prelude::*;
use splinelab::bspline::de_boor::{BSpline, BSplineError};
use splinelab::bspline::knots::{KnotError, KnotVector};
use splinelab::scalar::prelude::*;
use splinelab::surface_deformation::patch::Patch;
use splinelab_verify::curves::{bounds, bspline_vs_bezier, de_boor_vs_basis, patch_vs_nurbs};

fn build<T: Real>(order: usize, knots: &[i32], pts: &[[i32; 2]]) -> Option<BSpline<T, 2>> {
    let mut k: Vec<i32> = knots.to_vec();
    k.sort();
    let k = KnotVector::new(k.iter().map(|&x| T::from_int(x as i64)).collect()).unwrap();
    let q = pts
        .iter()
        .map(|p| Vector2::new(T::from_int(p[0] as i64), T::from_int(p[1] as i64)))
        .collect();
    match BSpline::new(order, q, k) {
        Ok(c) => Some(c),
        Err(BSplineError::EmptyDomain) => None,
        Err(e) => panic!("{e}"),
    }
}

fn case() -> impl Strategy<Value = (usize, Vec<i32>, Vec<[i32; 2]>)> {
    (1usize..=6, 0usize..5).prop_flat_map(|(order, extra)| {
        let n = order + extra;
        (
            Just(order),
            proptest::collection::vec(0i32..=12, n + order),
            proptest::collection::vec([-50i32..=50, -50i32..=50], n),
        )
    })
}

fn control() -> impl Strategy<Value = Vec<[i32; 2]>> {
    grid_points::<2>(50, 2..11)
}

fn v<T: Real>(p: &[[i32; 2]]) -> Vec<Vector2<T>> {
    p.iter()
        .map(|q| Vector2::new(T::from_int(q[0] as i64), T::from_int(q[1] as i64)))
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn de_boor_equals_the_basis_sum((order, knots, pts) in case()) {
        if let Some(c) = build::<f64>(order, &knots, &pts) {
            prop_assert!(de_boor_vs_basis(&c, 24).unwrap() <= bounds::BSPLINE);
        }
        if let Some(c) = build::<Mp<128>>(order, &knots, &pts) {
            prop_assert!(de_boor_vs_basis(&c, 8).unwrap() <= bounds::BSPLINE);
        }
    }

    /// Batch evaluation into a buffer gives the same bits as one `eval` per
    /// parameter, in any order (sorted, reversed, shuffled: the span hint is
    /// right, off by one, or wrong), at knots and at both domain ends, in f64
    /// and MPFR; a bad parameter anywhere is the same typed error and leaves
    /// the buffer untouched.
    #[test]
    fn batch_evaluation_equals_pointwise_eval((order, knots, pts) in case(), picks in proptest::collection::vec(0u32..=96, 0..40)) {
        fn check<T: Real>(c: &BSpline<T, 2>, picks: &[u32]) -> Result<(), TestCaseError> {
            let (lo, hi) = c.domain();
            let at = |p: u32| lo.clone() + (hi.clone() - lo.clone()) * T::from_int(p as i64) / T::from_int(96);
            let mut ts: Vec<T> = picks.iter().map(|&p| at(p)).collect();
            ts.extend(c.knots().as_slice().iter().filter(|t| **t >= lo && **t <= hi).cloned());
            let mut sorted = ts.clone();
            sorted.sort_by(|a, b| a.partial_cmp(b).unwrap());
            let mut reversed = sorted.clone();
            reversed.reverse();
            for set in [ts, sorted, reversed] {
                let mut out = vec![Vector2::zeros(); set.len()];
                c.eval_into(&set, &mut out).unwrap();
                for (t, p) in set.iter().zip(&out) {
                    prop_assert_eq!(p, &c.eval(t).unwrap());
                }
            }
            let bad = vec![at(48), hi.clone() + T::one(), at(0)];
            let mut out = vec![Vector2::new(T::from_int(7), T::from_int(7)); 3];
            prop_assert_eq!(c.eval_into(&bad, &mut out), Err(c.eval(&bad[1]).unwrap_err()));
            prop_assert!(out.iter().all(|p| p[0] == T::from_int(7)));
            prop_assert_eq!(
                c.eval_into(&bad, &mut out[..2]),
                Err(BSplineError::OutputLength { params: 3, got: 2 })
            );
            Ok(())
        }
        if let Some(c) = build::<f64>(order, &knots, &pts) {
            check(&c, &picks)?;
        }
        if let Some(c) = build::<Mp<128>>(order, &knots, &pts) {
            check(&c, &picks)?;
        }
    }

    #[test]
    fn bezier_knots_give_the_bezier_curve_and_its_hodograph(p in control()) {
        let (a, b) = bspline_vs_bezier(&v::<f64>(&p)).unwrap();
        prop_assert!(a <= bounds::BSPLINE && b <= bounds::BSPLINE, "{a} {b}");
        let (a, b) = bspline_vs_bezier(&v::<Mp<128>>(&p)).unwrap();
        prop_assert!(a <= bounds::BSPLINE && b <= bounds::BSPLINE, "{a} {b}");
    }

    #[test]
    fn bicubic_patch_equals_the_nurbs_surface(net in proptest::collection::vec([-8i32..=8, -8i32..=8, -8i32..=8], 16)) {
        let p = |n: &[[i32; 3]]| -> Vec<Vector3<f64>> { n.iter().map(|q| Vector3::new(q[0] as f64, q[1] as f64, q[2] as f64)).collect() };
        prop_assert!(patch_vs_nurbs(&Patch::new(3, p(&net)).unwrap()).unwrap() <= bounds::BSPLINE);
        let pm: Vec<Vector3<Mp<128>>> = net.iter().map(|q| Vector3::new(Mp::from_int(q[0] as i64), Mp::from_int(q[1] as i64), Mp::from_int(q[2] as i64))).collect();
        prop_assert!(patch_vs_nurbs(&Patch::new(3, pm).unwrap()).unwrap() <= bounds::BSPLINE);
    }
}

#[test]
fn serde_round_trip_keeps_knots_and_points_and_validates() {
    let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0]).unwrap();
    let c = BSpline::new(3, v::<f64>(&[[0, 0], [1, 2], [3, 1], [4, 0]]), k).unwrap();
    let json = serde_json::to_string(&c).unwrap();
    assert!(
        json.contains("\"order\":3") && json.contains("\"knots\":[0.0,0.0,0.0,0.5,1.0,1.0,1.0]"),
        "{json}"
    );
    let back: BSpline<f64, 2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, c);
    let bad = json.replace("0.5", "1.5");
    assert!(serde_json::from_str::<BSpline<f64, 2>>(&bad).is_err());
    let wrong_dim = r#"{"order":2,"knots":[0,0,1,1],"points":[[0,0],[1,1,1]]}"#;
    assert!(serde_json::from_str::<BSpline<f64, 2>>(wrong_dim).is_err());
    assert_eq!(
        KnotVector::new(vec![1.0, 0.0]),
        Err(KnotError::Decreasing { index: 1 })
    );
}

#[test]
fn derivative_matches_a_central_difference_in_mpfr() {
    // Non-uniform cubic: P'(t) against (P(t + h) − P(t − h)) / 2h in MPFR 256
    // with h = 2^−60 (truncation O(h²) ≈ 2^−120, rounding ≈ 2^−256 / h).
    type M = Mp<256>;
    let k = KnotVector::new(
        [0, 0, 0, 0, 1, 3, 4, 4, 4, 4]
            .iter()
            .map(|&x| M::from_int(x))
            .collect(),
    )
    .unwrap();
    let c = BSpline::new(
        4,
        v::<M>(&[[0, 0], [1, 3], [4, -2], [6, 5], [8, 1], [9, 0]]),
        k,
    )
    .unwrap();
    let h = M::from(1.0).scale_by_pow2(-60);
    for t in [0.5, 1.5, 2.75, 3.5] {
        let t = M::from(t);
        let fd = (c.eval(&(t.clone() + h.clone())).unwrap()
            - c.eval(&(t.clone() - h.clone())).unwrap())
            / (h.clone() * M::from(2.0));
        let d = c.eval_derivative(&t, 1).unwrap();
        assert!((d - fd).norm() < 1e-30, "t = {t}");
    }
}
