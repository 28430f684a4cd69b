//! Knot-insertion invariance (seed 003 eq 3–6): after any insertion sequence
//! the curve is unchanged — exactly in rationals (against an independent
//! rational Cox–de Boor evaluation), and in f64 within 4 ulps of the
//! coordinate scale when the f64 result is evaluated exactly (MPFR 256).

use nalgebra::Vector2;
use proptest::prelude::*;
use rug::Rational;
use splinelab::bspline::de_boor::BSpline;
use splinelab::bspline::knot_insertion::{InsertionError, insert_raw};
use splinelab::bspline::knots::KnotVector;
use splinelab::scalar::prelude::*;

/// Reference: `Σ_j N_{j,k}(t) Q_j` by the Cox–de Boor recursion in exact
/// rationals (right-continuous; the right end belongs to the last span).
fn eval_exact(order: usize, t: &[Rational], q: &[Rational], x: &Rational) -> Rational {
    let n = q.len();
    let hi = &t[n];
    // Order-1 basis on spans, the right end in the last non-empty span.
    let last = (0..n)
        .rev()
        .find(|&i| t[i] < t[i + 1] && t[i] <= *x)
        .unwrap();
    let mut b: Vec<Rational> = (0..t.len() - 1)
        .map(|i| {
            let inside = t[i] <= *x && (*x < t[i + 1] || (x == hi && i == last));
            Rational::from(inside as i32)
        })
        .collect();
    for k in 2..=order {
        b = (0..t.len() - k)
            .map(|i| {
                let mut v = Rational::new();
                if t[i + k - 1] > t[i] {
                    v += Rational::from(x - &t[i]) / Rational::from(&t[i + k - 1] - &t[i]) * &b[i];
                }
                if t[i + k] > t[i + 1] {
                    v += Rational::from(&t[i + k] - x) / Rational::from(&t[i + k] - &t[i + 1])
                        * &b[i + 1];
                }
                v
            })
            .collect();
    }
    (0..n).map(|j| Rational::from(&b[j] * &q[j])).sum()
}

/// Random order 2..8, non-decreasing integer knots (repeats allowed), and
/// insertion points: existing knots or quarter points inside the domain.
fn case() -> impl Strategy<Value = (usize, Vec<i32>, Vec<i32>, Vec<u32>)> {
    (2usize..=8, 0usize..6).prop_flat_map(|(k, extra)| {
        let n = k + extra;
        (
            Just(k),
            proptest::collection::vec(0i32..=8, n + k),
            proptest::collection::vec(-100i32..=100, n),
            proptest::collection::vec(0u32..1000, 1..6),
        )
    })
}

/// Picks an insertion point from `pick` inside `[lo, hi]` (in quarters):
/// even picks reuse an existing knot in the domain.
fn insertion_point(knots: &[i32], lo: i32, hi: i32, pick: u32) -> Rational {
    let inner: Vec<i32> = knots
        .iter()
        .copied()
        .filter(|t| (lo..=hi).contains(t))
        .collect();
    if pick.is_multiple_of(2) && !inner.is_empty() {
        Rational::from(inner[(pick as usize / 2) % inner.len()])
    } else {
        let span = (4 * (hi - lo)) as u32;
        Rational::from((4 * lo + (pick % (span + 1)) as i32, 4))
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// Exact: the inserted curve equals the original at every sample.
    #[test]
    fn insertion_is_exactly_invariant_in_rationals((k, mut kn, q, picks) in case()) {
        kn.sort();
        let n = q.len();
        let (lo, hi) = (kn[k - 1], kn[n]);
        prop_assume!(lo < hi);
        let mut t: Vec<Rational> = kn.iter().map(|&x| Rational::from(x)).collect();
        let mut p: Vec<Rational> = q.iter().map(|&x| Rational::from(x)).collect();
        let (t0, p0) = (t.clone(), p.clone());
        for &pick in &picks {
            let u = insertion_point(&kn, lo, hi, pick);
            let mult = t.iter().filter(|x| **x == u).count();
            match insert_raw(k, &t, &p, &u) {
                Some((t1, p1)) => { prop_assert!(mult < k); t = t1; p = p1; }
                None => prop_assert!(mult >= k, "refused below full multiplicity"),
            }
        }
        prop_assert_eq!(t.len(), p.len() + k);
        for s in 0..=64 {
            let x = Rational::from(lo) + Rational::from((s * (hi - lo), 64));
            prop_assert_eq!(eval_exact(k, &t0, &p0, &x), eval_exact(k, &t, &p, &x));
        }
    }

    /// f64: the refined control points, evaluated exactly (MPFR 256), deviate
    /// from the original curve (also evaluated exactly) by ≤ 4 ulps of the
    /// coordinate scale max|Q|; each in-place insertion gives the same bits
    /// as the copying kernel `insert_raw`.
    #[test]
    fn insertion_is_invariant_to_4_ulps_in_f64((k, mut kn, q, picks) in case()) {
        kn.sort();
        let n = q.len();
        prop_assume!(kn[k - 1] < kn[n]);
        let knots = KnotVector::new(kn.iter().map(|&x| x as f64 / 3.0).collect()).unwrap();
        let pts: Vec<Vector2<f64>> = q.iter().map(|&y| Vector2::new(y as f64 / 7.0, -y as f64 / 3.0)).collect();
        let c0 = BSpline::new(k, pts, knots).unwrap();
        let (lo, hi) = c0.domain();
        let mut c = c0.clone();
        for &pick in &picks {
            let u = lo + (hi - lo) * (pick as f64 / 999.0);
            let u = if pick % 3 == 0 { *c.knots().as_slice().iter().find(|t| **t >= lo).unwrap() } else { u };
            // The in-place O(k) route against the copying generic kernel
            // (linear span and multiplicity scans): the same bits.
            let raw = insert_raw(k, c.knots().as_slice(), c.points(), &u);
            match c.insert_knot(&u) {
                Ok(r) => {
                    let (t1, p1) = raw.expect("kernel refused what in-place accepted");
                    prop_assert_eq!(r.knots().as_slice(), &t1[..]);
                    prop_assert_eq!(r.points(), &p1[..]);
                    c = r;
                }
                Err(InsertionError::FullMultiplicity { .. }) => prop_assert!(raw.is_none()),
                Err(e) => panic!("{e}"),
            }
        }
        let scale = c0.points().iter().map(|p| p.amax()).fold(0.0, f64::max);
        let exact = |b: &BSpline<f64, 2>| -> BSpline<Mp<256>, 2> {
            let t = KnotVector::new(b.knots().as_slice().iter().map(|x| Mp::from_f64_exact(*x)).collect()).unwrap();
            let q = b.points().iter().map(|p| p.map(Mp::from_f64_exact)).collect();
            BSpline::new(b.order(), q, t).unwrap()
        };
        let (e0, e1) = (exact(&c0), exact(&c));
        for s in 0..=200 {
            let x = Mp::<256>::from_f64_exact((lo + (hi - lo) * s as f64 / 200.0).min(hi));
            let d = (e0.eval(&x).unwrap() - e1.eval(&x).unwrap()).amax().to_f64();
            prop_assert!(d <= 4.0 * f64::EPSILON * scale, "deviation {d:e} > 4 ulps of {scale}");
        }
    }
}

#[test]
fn global_refinement_doubles_spans_and_keeps_the_curve() {
    let k = KnotVector::clamped_uniform(4, 7).unwrap();
    let q: Vec<Vector2<f64>> = (0..7)
        .map(|i| Vector2::new(i as f64, ((i * 5) % 3) as f64))
        .collect();
    let c = BSpline::new(4, q, k).unwrap();
    let r = c.refine_midpoints().unwrap();
    assert_eq!(r.points().len(), 7 + 4);
    for s in 0..=100 {
        let x = s as f64 / 100.0;
        assert!((r.eval(&x).unwrap() - c.eval(&x).unwrap()).amax() < 8.0 * f64::EPSILON * 6.0);
    }
}

#[test]
fn bad_insertions_are_typed_errors_and_leave_the_curve() {
    let k = KnotVector::clamped_uniform(3, 4).unwrap();
    let q = vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(1.0, 1.0),
        Vector2::new(2.0, 0.0),
        Vector2::new(3.0, 1.0),
    ];
    let c = BSpline::new(3, q, k).unwrap();
    let before = c.clone();
    assert!(matches!(
        c.insert_knot(&1.5),
        Err(InsertionError::OutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(&f64::NAN),
        Err(InsertionError::OutOfDomain { .. })
    ));
    assert!(matches!(
        c.insert_knot(&0.0),
        Err(InsertionError::FullMultiplicity { .. })
    ));
    assert!(matches!(
        c.insert_knot_times(&0.5, 3),
        Err(InsertionError::FullMultiplicity { .. })
    ));
    assert_eq!(c, before);
    // Non-monotone knot vectors are refused before any curve exists.
    assert!(KnotVector::new(vec![0.0, 1.0, 0.5]).is_err());
}

#[test]
fn knots_travel_with_the_points_through_json() {
    let k = KnotVector::clamped_uniform(4, 6).unwrap();
    let q: Vec<Vector2<f64>> = (0..6)
        .map(|i| Vector2::new(i as f64 / 3.0, (i * i) as f64 / 7.0))
        .collect();
    let c = BSpline::new(4, q, k)
        .unwrap()
        .insert_knot(&0.3)
        .unwrap()
        .insert_knot(&0.3)
        .unwrap();
    let json = serde_json::to_string(&c).unwrap();
    let back: BSpline<f64, 2> = serde_json::from_str(&json).unwrap();
    assert_eq!(back, c);
    for s in 0..=50 {
        let x = s as f64 / 50.0;
        assert_eq!(back.eval(&x).unwrap(), c.eval(&x).unwrap());
    }
}
