//! Catmull–Rom splines (seed 002): interpolation, C¹ continuity and the
//! tangent's closed form, for α = 0, ½, 1, open and closed, in f64 and MPFR;
//! the centripetal spline has no loop on the classic counter-example where
//! the uniform one does; zero chords are typed errors.

use crate::common;
use common::strategies::grid_points;
use nalgebra::Vector2;
use proptest::prelude::*;
use splinelab::curves::CurveError;
use splinelab::curves::catmull_rom::{CatmullRom, Spacing};
use splinelab::scalar::prelude::*;
use splinelab_verify::curves::{
    bounds, catmull_rom_errors, loop_example, min_relative_speed, polyline_self_intersects,
    sample_catmull_rom,
};

fn check<T: Real>(pts: &[[i32; 2]], spacing: Spacing, closed: bool) -> Result<(), TestCaseError> {
    let p: Vec<Vector2<T>> = pts
        .iter()
        .map(|q| Vector2::new(T::from_int(q[0] as i64), T::from_int(q[1] as i64)))
        .collect();
    // Consecutive equal points are rejected (tested separately).
    let c = match CatmullRom::new(p, spacing, closed) {
        Ok(c) => c,
        Err(CurveError::CoincidentPoints { .. }) => return Ok(()),
        Err(e) => return Err(TestCaseError::fail(e.to_string())),
    };
    let e = catmull_rom_errors(&c).unwrap();
    let b = bounds::CATMULL_ROM;
    prop_assert!(
        e.interpolation <= b && e.c1_jump <= b && e.tangent <= b,
        "{} {spacing:?} closed={closed}: {e:?}",
        T::type_name()
    );
    Ok(())
}

fn spacing() -> impl Strategy<Value = Spacing> {
    prop_oneof![
        Just(Spacing::Uniform),
        Just(Spacing::Centripetal),
        Just(Spacing::Chordal)
    ]
}

fn points() -> impl Strategy<Value = Vec<[i32; 2]>> {
    grid_points::<2>(20, 4..9)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn interpolates_and_is_c1_f64(p in points(), s in spacing(), closed in any::<bool>()) {
        check::<f64>(&p, s, closed)?;
    }

    #[test]
    fn interpolates_and_is_c1_mp128(p in points(), s in spacing(), closed in any::<bool>()) {
        check::<Mp<128>>(&p, s, closed)?;
    }
}

#[test]
fn centripetal_has_no_loop_where_uniform_loops() {
    let p = loop_example::<f64>();
    let uni = CatmullRom::new(p.clone(), Spacing::Uniform, false).unwrap();
    let cen = CatmullRom::new(p.clone(), Spacing::Centripetal, false).unwrap();
    assert!(polyline_self_intersects(
        &sample_catmull_rom(&uni, 2000).unwrap()
    ));
    assert!(!polyline_self_intersects(
        &sample_catmull_rom(&cen, 2000).unwrap()
    ));
    // No cusp: the speed stays well away from 0 (relative to chord / Δt).
    let speed = min_relative_speed(&cen, 0, 2000).unwrap();
    assert!(speed > 0.1, "{speed}");
    // The same in MPFR.
    let cen = CatmullRom::new(loop_example::<Mp<128>>(), Spacing::Centripetal, false).unwrap();
    assert!(!polyline_self_intersects(
        &sample_catmull_rom(&cen, 500).unwrap()
    ));
}

#[test]
fn coincident_points_are_rejected_for_nonuniform_spacing() {
    let p = vec![
        Vector2::new(0.0f64, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(1.0, 0.0),
        Vector2::new(2.0, 0.0),
    ];
    for s in [Spacing::Centripetal, Spacing::Chordal] {
        assert_eq!(
            CatmullRom::new(p.clone(), s, false),
            Err(CurveError::CoincidentPoints { index: 1, next: 2 })
        );
    }
    let c = CatmullRom::new(p, Spacing::Uniform, false).unwrap();
    assert_eq!(c.eval(&0.0).unwrap().0, Vector2::new(1.0, 0.0));
    assert!(matches!(c.eval(&2.0), Err(CurveError::OutOfDomain(_))));
}
