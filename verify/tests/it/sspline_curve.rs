//! S-spline curves and surfaces (seed 000 eq 20–25): local edits against
//! full rebuilds, interpolation, the derived end-tangent rule against its
//! closed form `Q'(0) = C_n T_0`, the B-spline view (de Boor) against the
//! basis-window evaluation, surfaces against curves of curves (eq 25), and
//! the global cubic baseline against the Hermite-form solver of `qi`.

use nalgebra::{SVector, Vector2, Vector3};
use proptest::prelude::*;
use splinelab::curves::global_cubic::{CubicEnds, control_points, interpolant};
use splinelab::curves::sspline_surface::{Direction, SsplineSurface};
use splinelab::curves::{CurveError, sspline_curve::SsplineCurve};
use splinelab::qi::cubic_spline::{ClampedCubicSpline, Parameterization};
use splinelab::scalar::prelude::*;
use splinelab::sspline::end_conditions::{EndCondition, EndRule};
use splinelab::sspline::{SplineFamily, TruncatedBasis};
use splinelab::validation::InputError;

fn pts<T: Real>(raw: &[[i32; 2]]) -> Vec<Vector2<T>> {
    raw.iter()
        .map(|p| Vector2::new(T::from_int(p[0] as i64), T::from_int(p[1] as i64)))
        .collect()
}

fn end<T: Real>(which: u8) -> EndCondition<T, 2> {
    match which {
        0 => EndCondition::Free,
        1 => EndCondition::Periodic,
        _ => EndCondition::Tangents {
            start: Vector2::new(T::from_int(3), T::from_int(-1)),
            end: Vector2::new(T::from_int(-2), T::from_int(5)),
        },
    }
}

fn family(sel: u32) -> SplineFamily {
    match sel {
        9 => SplineFamily::beta2(rug::Rational::from((5, 2))).unwrap(),
        m => SplineFamily::Order(m),
    }
}

/// Local edit (recompute) is bitwise a rebuild; the incremental edit agrees
/// to rounding. Written once over the scalar.
fn check_edit<T: Real>(
    fam: &SplineFamily,
    n: usize,
    raw: &[[i32; 2]],
    e: u8,
    k: usize,
    to: [i32; 2],
) {
    let data = pts::<T>(raw);
    let mut c = SsplineCurve::new(fam, n, &data, end::<T>(e)).unwrap();
    let mut s = c.clone();
    let p = Vector2::new(T::from_int(to[0] as i64), T::from_int(to[1] as i64));
    c.move_point(k, p.clone()).unwrap();
    s.shift_point(k, p.clone()).unwrap();
    let mut moved = data.clone();
    moved[k] = p;
    let r = SsplineCurve::new(fam, n, &moved, end::<T>(e)).unwrap();
    assert_eq!(
        c.control_points(),
        r.control_points(),
        "recompute ≠ rebuild"
    );
    // Each D_l is a sum of 2n + 1 terms plus one increment per owned index
    // (≤ 2 + (2n + m)/ν of them); terms ≤ Σ|c| · max|P_ext| (≤ 1000 here).
    let sum_c = c
        .coefficients()
        .iter()
        .fold(T::zero(), |a, x| a + x.clone().abs())
        * T::from_int(2);
    let adds = 2 * n as i64 + 1 + (2 * n as i64 + 1) * (3 + (2 * n as i64 + 9) / raw.len() as i64);
    let scale: T = T::from_int(1000 * adds) * sum_c;
    for (a, b) in s.control_points().iter().zip(r.control_points()) {
        assert!((a - b).amax() <= T::unit_roundoff() * scale.clone());
    }
}

fn edit_case() -> impl Strategy<Value = (u32, usize, Vec<[i32; 2]>, u8, usize, [i32; 2])> {
    (prop_oneof![2u32..=8, Just(9u32)], 1usize..=7, 0u8..3).prop_flat_map(|(m, n, e)| {
        let lo = 9.min(m as usize).max(4);
        proptest::collection::vec([-100i32..=100, -100i32..=100], lo..24).prop_flat_map(move |d| {
            let len = d.len();
            (
                Just(m),
                Just(n),
                Just(d),
                Just(e),
                0..len,
                [-100i32..=100, -100i32..=100],
            )
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn local_edit_equals_rebuild_f64((m, n, d, e, k, to) in edit_case()) {
        check_edit::<f64>(&family(m), n, &d, e, k, to);
    }

    #[test]
    fn local_edit_equals_rebuild_mp((m, n, d, e, k, to) in edit_case()) {
        check_edit::<Mp<128>>(&family(m), n, &d, e, k, to);
    }
}

/// An interior edit touches exactly 2n + 1 control points.
#[test]
fn interior_edit_touches_2n_plus_1_points() {
    let data = pts::<f64>(&(0..40).map(|i| [i, i * i % 7]).collect::<Vec<_>>());
    let mut c = SsplineCurve::new(&SplineFamily::Order(4), 6, &data, EndCondition::Free).unwrap();
    let before = c.control_points().to_vec();
    assert_eq!(c.move_point(20, Vector2::new(1.0, 2.0)).unwrap(), 13);
    let changed = before
        .iter()
        .zip(c.control_points())
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(changed, 13);
}

/// Interpolation `Q(i) = P_i` to the truncation bound, and the B-spline view
/// (de Boor) equals the basis-window evaluation, in MPFR 128.
#[test]
fn interpolates_and_matches_de_boor() {
    type M = Mp<128>;
    let raw: Vec<[i32; 2]> = (0..12).map(|i| [3 * i - 7, (i * i) % 11 - 5]).collect();
    let data = pts::<M>(&raw);
    for m in [3u32, 4, 5, 6] {
        for e in 0..3u8 {
            let c = SsplineCurve::new(&SplineFamily::Order(m), 60, &data, end::<M>(e)).unwrap();
            let b = c.to_bspline().unwrap();
            for (i, p) in data.iter().enumerate() {
                let q = c.eval(&M::from_int(i as i64)).unwrap();
                // Truncation at n = 60: tail bound ≤ 1e-19 for m ≤ 6 (ρ ≤ 0.43).
                assert!((q - p).amax().to_f64() < 1e-17, "m={m} e={e} i={i}");
            }
            for s in 0..=44 {
                let u = M::from_int(s).scale_by_pow2(-2);
                let d = (c.eval(&u).unwrap() - b.eval(&u).unwrap()).amax();
                assert!(d.to_f64() < 1e-30, "m={m} e={e} u={}", s as f64 / 4.0);
            }
        }
    }
}

/// Derived tangent rule: `Q'(0) = C_n T_0`, `Q'(ν−1) = C_n T_1` with
/// `C_n = Σ_{|i|≤n} c_i` (exact identity for the truncated spline), and
/// `C_n → 1` so that the untruncated spline meets the tangents exactly.
#[test]
fn prescribed_tangents_hold() {
    type M = Mp<128>;
    let raw: Vec<[i32; 2]> = (0..9).map(|i| [i * i - 3, 7 - 2 * i]).collect();
    let data = pts::<M>(&raw);
    let (t0, t1) = match end::<M>(2) {
        EndCondition::Tangents { start, end } => (start, end),
        _ => unreachable!(),
    };
    for m in [3u32, 4, 5, 6, 8] {
        for n in [3usize, 8, 60] {
            let fam = SplineFamily::Order(m);
            let c = SsplineCurve::new(&fam, n, &data, end::<M>(2)).unwrap();
            let cs = TruncatedBasis::<M>::new(&fam, n).unwrap();
            let cn = cs
                .coefficients()
                .iter()
                .skip(1)
                .fold(cs.coefficients()[0].clone(), |a, x| {
                    a + x.clone() * M::from_int(2)
                });
            let b = c.to_bspline().unwrap();
            let d0 = b.eval_derivative(&M::from_int(0), 1).unwrap();
            let d1 = b.eval_derivative(&M::from_int(8), 1).unwrap();
            assert!(
                (d0 - &t0 * cn.clone()).amax().to_f64() < 1e-30,
                "m={m} n={n}"
            );
            assert!(
                (d1 - &t1 * cn.clone()).amax().to_f64() < 1e-30,
                "m={m} n={n}"
            );
            if n == 60 {
                // |C_n − 1| ≤ tail bound: ≤ 2e-15 for m = 8 (ρ ≈ 0.535).
                assert!((cn - M::from_int(1)).abs().to_f64() < 1e-14);
            }
        }
    }
}

/// Periodic curves close with matching derivatives (de Boor view).
#[test]
fn periodic_curves_close_smoothly() {
    let data = pts::<f64>(&[[0, 0], [4, 1], [5, 5], [1, 6], [-2, 3]]);
    let c = SsplineCurve::new(&SplineFamily::Order(4), 20, &data, EndCondition::Periodic).unwrap();
    let b = c.to_bspline().unwrap();
    for r in 0..3 {
        let a = b.eval_derivative(&0.0, r).unwrap();
        let z = b.eval_derivative(&5.0, r).unwrap();
        assert!((a - z).amax() < 1e-12, "derivative {r}");
    }
}

/// Surface: bitwise local edit, interpolation, and eq 25 (a curve in `v` of
/// the `u`-curves' values) as a second algorithm.
#[test]
fn surface_edit_interpolation_and_curves_of_curves() {
    let (nu, nv) = (9usize, 7usize);
    let grid: Vec<Vector3<f64>> = (0..nu * nv)
        .map(|x| Vector3::new((x / nv) as f64, (x % nv) as f64, ((x * 7) % 5) as f64 - 2.0))
        .collect();
    let du = Direction {
        family: SplineFamily::Order(4),
        n: 12,
        rule: EndRule::Free,
    };
    let dv = Direction {
        family: SplineFamily::Order(5),
        n: 14,
        rule: EndRule::Periodic,
    };
    let mut s = SsplineSurface::new(&du, &dv, nu, nv, &grid).unwrap();
    for (x, p) in grid.iter().enumerate() {
        let q = s.eval(&((x / nv) as f64), &((x % nv) as f64)).unwrap();
        assert!((q - p).amax() < 1e-5, "node {x}");
    }
    // eq 25: Q(u, v) = Σ_j PU_j(u) S_j(v): v-curve through the u-curves' values.
    let (u, v) = (3.3, 2.6);
    let cols: Vec<Vector3<f64>> = (0..nv)
        .map(|j| {
            let col: Vec<_> = (0..nu).map(|i| grid[i * nv + j]).collect();
            SsplineCurve::new(&du.family, du.n, &col, EndCondition::Free)
                .unwrap()
                .eval(&u)
                .unwrap()
        })
        .collect();
    let q = SsplineCurve::new(&dv.family, dv.n, &cols, EndCondition::Periodic)
        .unwrap()
        .eval(&v)
        .unwrap();
    assert!((q - s.eval(&u, &v).unwrap()).amax() < 1e-13);
    let mut t = s.clone();
    let p = Vector3::new(4.0, 3.0, 9.0);
    let touched = s.move_point(4, 3, p).unwrap();
    // The grid is narrower than the support: the whole 11 × 12 net moves.
    assert_eq!(touched, 11 * 12);
    t.shift_point(4, 3, p).unwrap();
    let mut g2 = grid.clone();
    g2[4 * nv + 3] = p;
    let r = SsplineSurface::new(&du, &dv, nu, nv, &g2).unwrap();
    assert_eq!(s.control_points(), r.control_points());
    for (a, b) in t.control_points().iter().zip(r.control_points()) {
        assert!((a - b).amax() < 1e-14);
    }
}

/// The clamped global cubic equals the Hermite-form clamped spline of `qi`
/// (second algorithm); the natural one has Q'' = 0 at both ends.
#[test]
fn global_cubic_matches_hermite_solver() {
    let data: Vec<Vector3<f64>> = (0..11)
        .map(|i| Vector3::new(i as f64, ((i * i) % 7) as f64, (3 - i) as f64 * 0.5))
        .collect();
    let (t0, t1) = (Vector3::new(1.0, -2.0, 0.5), Vector3::new(0.0, 3.0, -1.0));
    let h = ClampedCubicSpline::new(&data, Parameterization::Uniform, &t0, &t1).unwrap();
    let b = interpolant(&data, &CubicEnds::Clamped { start: t0, end: t1 }).unwrap();
    for i in 0..10 {
        for q in 0..4 {
            let t = q as f64 / 4.0;
            let [p, d, _] = h.jet(i, &t);
            let u = i as f64 + t;
            assert!((b.eval(&u).unwrap() - p).amax() < 1e-13);
            assert!((b.eval_derivative(&u, 1).unwrap() - d).amax() < 1e-12);
        }
    }
    let nat = interpolant(&data, &CubicEnds::Natural).unwrap();
    assert!(nat.eval_derivative(&0.0, 2).unwrap().amax() < 1e-12);
    assert!(nat.eval_derivative(&10.0, 2).unwrap().amax() < 1e-12);
    for (i, p) in data.iter().enumerate() {
        assert!((nat.eval(&(i as f64)).unwrap() - p).amax() < 1e-13);
    }
}

/// Bad input: typed errors, no panic, caller's data untouched.
#[test]
fn bad_input_is_refused() {
    let f = SplineFamily::Order(4);
    let one = vec![Vector2::new(0.0, 0.0)];
    assert_eq!(
        SsplineCurve::new(&f, 3, &one, EndCondition::Free),
        Err(CurveError::Input(InputError::TooFewPoints {
            what: "an S-spline curve",
            needed: 2,
            got: 1
        }))
    );
    let three = pts::<f64>(&[[0, 0], [1, 1], [2, 0]]);
    assert!(matches!(
        SsplineCurve::new(&f, 3, &three, EndCondition::Free),
        Err(CurveError::OrderTooHigh { .. })
    ));
    let mut bad = pts::<f64>(&[[0, 0], [1, 1], [2, 0], [3, 3], [4, 4]]);
    bad[2].x = f64::NAN;
    assert_eq!(
        SsplineCurve::new(&f, 3, &bad, EndCondition::Free),
        Err(CurveError::Input(InputError::NonFiniteAt {
            what: "data point",
            index: 2
        }))
    );
    assert!(bad[2].x.is_nan());
    let good = pts::<f64>(&[[0, 0], [1, 1], [2, 0], [3, 3], [4, 4]]);
    let mut c = SsplineCurve::new(&f, 3, &good, EndCondition::Free).unwrap();
    let before = c.clone();
    assert!(c.move_point(5, Vector2::new(0.0, 0.0)).is_err());
    assert!(c.move_point(1, Vector2::new(f64::INFINITY, 0.0)).is_err());
    assert!(c.eval(&4.5).is_err() && c.eval(&f64::NAN).is_err());
    assert_eq!(c, before);
    let inf = EndCondition::Tangents {
        start: Vector2::new(f64::NAN, 0.0),
        end: Vector2::zeros(),
    };
    assert!(SsplineCurve::new(&f, 3, &good, inf).is_err());
    assert!(control_points::<f64, 2>(&one, &CubicEnds::Natural).is_err());
    let d = Direction {
        family: f,
        n: 2,
        rule: EndRule::Reflect,
    };
    let g: Vec<SVector<f64, 1>> = vec![SVector::zeros(); 25];
    assert!(SsplineSurface::new(&d, &d, 5, 5, &g).is_err());
}
