//! Tests of the grid spline against closed forms (which also check the
//! B-spline values, shared with `bspline::de_boor`), a dense Kronecker
//! solve in MPFR (which checks the banded solves axis by axis), and its own
//! f64/MPFR twins.

use super::*;
use crate::bspline::de_boor::basis_functions;
use crate::scalar::{Mp, Real};
use nalgebra::DMatrix;
use ndarray::{Array, ArrayD, IxDyn};
use proptest::prelude::*;

type M = Mp<256>;

/// Strictly ascending nodes with gaps in `[min_gap, 1]`, deterministic.
fn nodes(n: usize, seed: u64, min_gap: f64) -> Vec<f64> {
    let mut s = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    let mut x = vec![-0.3];
    for _ in 1..n {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        let r = (s >> 11) as f64 / (1u64 << 53) as f64;
        x.push(x[x.len() - 1] + min_gap + (1.0 - min_gap) * r);
    }
    x
}

fn values(grid: &[Vec<f64>], m: usize, f: impl Fn(&[f64], usize) -> f64) -> ArrayD<f64> {
    let mut shape: Vec<usize> = grid.iter().map(Vec::len).collect();
    shape.push(m);
    Array::from_shape_fn(IxDyn(&shape), |ix| {
        let x: Vec<f64> = (0..grid.len()).map(|a| grid[a][ix[a]]).collect();
        f(&x, ix[grid.len()])
    })
}

#[test]
fn reproduces_polynomials_of_its_degree_with_derivatives() {
    for k in [1usize, 3, 5] {
        let grid = vec![
            nodes(k + 3, 1, 0.05),
            nodes(k + 5, 2, 0.2),
            nodes(k + 1, 3, 0.5),
        ];
        // Degree k in each variable: its own not-a-knot spline.
        let p = |x: &[f64], b: usize| {
            let kk = k as i32;
            (x[0].powi(kk) - 2.0 * x[0] + b as f64) * (1.0 + x[1].powi(kk)) * (x[2].powi(kk) - 0.5)
        };
        let dp0 = |x: &[f64]| {
            let kk = k as i32;
            (kk as f64 * x[0].powi(kk - 1) - 2.0) * (1.0 + x[1].powi(kk)) * (x[2].powi(kk) - 0.5)
        };
        let s = GridSpline::interpolate(grid.clone(), values(&grid, 2, p).view(), k).unwrap();
        for t in 0..20 {
            let x: Vec<f64> = (0..3)
                .map(|a| {
                    let g = &grid[a];
                    // Inside and a little beyond the ends (extrapolation).
                    g[0] - 0.1 + (g[g.len() - 1] - g[0] + 0.2) * ((t * (a + 3)) % 20) as f64 / 19.0
                })
                .collect();
            let v = s.eval(&x, &[]).unwrap();
            // Beyond the ends the degree-k pieces amplify the coefficients'
            // rounding by |B_j(x)| > 1.
            let inside = (0..3).all(|a| x[a] >= grid[a][0] && x[a] <= grid[a][grid[a].len() - 1]);
            let tol = if inside { 1e-11 } else { 1e-8 };
            for (b, got) in v.iter().enumerate() {
                let want = p(&x, b);
                assert!(
                    (got - want).abs() < tol * (1.0 + want.abs()),
                    "k={k} {x:?}: {got} vs {want}"
                );
            }
            let d = s.eval(&x, &[1, 0, 0]).unwrap();
            // A derivative divides the rounding by the node spacing (≥ 0.05 here).
            let dtol = 100.0 * tol;
            assert!(
                (d[0] - dp0(&x)).abs() < dtol * (1.0 + dp0(&x).abs()),
                "k={k} {x:?}: {} vs {}",
                d[0],
                dp0(&x)
            );
        }
    }
}

/// The spline of random data in f64 against its 256-bit twin: the
/// coefficients within `coefficient_error`, values within `error_bound`,
/// and both bounds not loose by more than a few orders of magnitude.
#[test]
fn f64_within_its_bound_of_the_mpfr_twin() {
    for (k, gap) in [(3usize, 1e-3), (5, 1e-2), (3, 0.3), (1, 0.1)] {
        let grid = vec![nodes(9, 7, gap), nodes(12, 8, gap), nodes(7, 9, gap)];
        let v = values(&grid, 1, |x, _| {
            (3.0 * x[0]).sin() + x[1] * x[2] - (x[2] * 7.0).cos()
        });
        let s = GridSpline::interpolate(grid.clone(), v.view(), k).unwrap();
        let gm: Vec<Vec<M>> = grid
            .iter()
            .map(|g| g.iter().map(|&x| M::from_f64_exact(x)).collect())
            .collect();
        let sm = GridSpline::<M>::interpolate(gm, v.mapv(M::from_f64_exact).view(), k).unwrap();
        let err = s
            .coefficients()
            .iter()
            .zip(sm.coefficients())
            .map(|(a, b)| (a - b.to_f64()).abs())
            .fold(0.0, f64::max);
        let bound = s.coefficient_error();
        assert!(
            err <= bound,
            "k={k} gap={gap}: error {err:e} above the bound {bound:e}"
        );
        assert!(
            bound < 1e7 * err.max(1e-16),
            "k={k} gap={gap}: bound {bound:e} loose against {err:e}"
        );
        for t in 0..30 {
            let x: Vec<f64> = (0..3)
                .map(|a| {
                    grid[a][0]
                        + (grid[a][grid[a].len() - 1] - grid[a][0]) * ((t * 7 + a * 3) % 30) as f64
                            / 29.0
                })
                .collect();
            let xm: Vec<M> = x.iter().map(|&v| M::from_f64_exact(v)).collect();
            let (a, b) = (
                s.eval(&x, &[]).unwrap()[0],
                sm.eval(&xm, &[]).unwrap()[0].to_f64(),
            );
            assert!(
                (a - b).abs() <= s.error_bound(),
                "{a} vs {b}, bound {:e}",
                s.error_bound()
            );
        }
    }
}

/// The dense collocation matrix `(B_j(x_i))` of an axis (Piegl–Tiller's
/// basis of `bspline::de_boor`).
fn dense_collocation(ax: &GridAxis<M>) -> DMatrix<M> {
    let (n, k) = (ax.len(), ax.degree());
    let mut m = DMatrix::<M>::zeros(n, n);
    for (i, x) in ax.nodes().iter().enumerate() {
        let span = ax.span(x);
        for (q, b) in basis_functions(k + 1, ax.knots(), span, x)
            .into_iter()
            .enumerate()
        {
            m[(i, span - k + q)] = b;
        }
    }
    m
}

/// Against the dense Kronecker collocation system solved by nalgebra's LU
/// in MPFR: the banded solves along each axis in turn are the Kronecker
/// inverse.
#[test]
fn agrees_with_the_dense_solve() {
    let k = 3;
    let grid = vec![nodes(6, 11, 0.05), nodes(5, 12, 0.05)];
    let v = values(&grid, 1, |x, _| {
        (x[0] * 2.0).exp() - x[1] * x[1] * x[1] + x[0] * x[1]
    });
    let s = GridSpline::interpolate(grid.clone(), v.view(), k).unwrap();
    let axes: Vec<GridAxis<M>> = grid
        .iter()
        .enumerate()
        .map(|(a, g)| {
            GridAxis::not_a_knot(g.iter().map(|&x| M::from_f64_exact(x)).collect(), k, a).unwrap()
        })
        .collect();
    let full = dense_collocation(&axes[0]).kronecker(&dense_collocation(&axes[1]));
    let rhs = DMatrix::<M>::from_iterator(v.len(), 1, v.iter().map(|&x| M::from_f64_exact(x)));
    let c = full.lu().solve(&rhs).unwrap();
    for (a, b) in s.coefficients().iter().zip(c.iter()) {
        assert!(
            (a - b.to_f64()).abs() <= s.coefficient_error(),
            "{a} vs {}",
            b.to_f64()
        );
    }
}

/// `‖A^{−1}‖∞` by the checkerboard solve against the dense inverse (MPFR).
#[test]
fn condition_is_the_dense_inverse_norm() {
    for (k, gap) in [(3usize, 1e-4), (5, 0.01), (3, 0.5)] {
        let g = nodes(14, 21, gap);
        let v = values(std::slice::from_ref(&g), 1, |x, _| x[0]);
        let s = GridSpline::interpolate(vec![g.clone()], v.view(), k).unwrap();
        let ax = GridAxis::not_a_knot(
            g.iter().map(|&x| M::from_f64_exact(x)).collect::<Vec<M>>(),
            k,
            0,
        )
        .unwrap();
        let n = ax.len();
        let a = dense_collocation(&ax);
        let inv = a.try_inverse().unwrap();
        let exact = (0..n)
            .map(|i| (0..n).fold(0.0, |s, j| s + inv[(i, j)].to_f64().abs()))
            .fold(0.0, f64::max);
        let kappa = s.conditioning()[0].kappa;
        assert!(
            (kappa - exact).abs() <= 1e-8 * exact,
            "k={k}: {kappa} vs {exact}"
        );
    }
}

#[test]
fn pchip_reproduces_multilinear_data() {
    let grid = vec![nodes(5, 31, 0.1), nodes(4, 32, 0.1), nodes(6, 33, 0.1)];
    let f =
        |x: &[f64], b: usize| 1.0 + x[0] - 2.0 * x[1] + 0.5 * x[0] * x[2] - x[1] * x[2] + b as f64;
    let v = values(&grid, 2, f);
    let axes: Vec<GridAxis<f64>> = grid
        .iter()
        .enumerate()
        .map(|(a, g)| GridAxis::not_a_knot(g.clone(), 1, a).unwrap())
        .collect();
    let pts = [0.1, 0.7, 1.3, -0.5, 2.0, 0.0, 1.9, 1.1, 3.5];
    let mut out = vec![0.0; 6];
    pchip_eval(
        &axes,
        v.as_slice().unwrap(),
        &Layout::c_order(v.shape()),
        2,
        &pts,
        &mut out,
    );
    // The same values read in place through a flipped view (negative strides).
    let mut flipped = v.view();
    flipped.invert_axis(ndarray::Axis(1));
    let rev: Vec<f64> = grid[1].iter().rev().map(|x| -x).collect();
    let axes_rev = [
        axes[0].clone(),
        GridAxis::not_a_knot(rev, 1, 1).unwrap(),
        axes[2].clone(),
    ];
    let (data, layout) = Layout::of_view(&flipped).unwrap();
    let pts_rev: Vec<f64> = pts.chunks(3).flat_map(|p| [p[0], -p[1], p[2]]).collect();
    let mut out_rev = vec![0.0; 6];
    pchip_eval(&axes_rev, data, &layout, 2, &pts_rev, &mut out_rev);
    for (a, b) in out.iter().zip(&out_rev) {
        assert!((a - b).abs() < 1e-13 * (1.0 + a.abs()), "{a} vs {b}");
    }
    for p in 0..3 {
        for b in 0..2 {
            let want = f(&pts[p * 3..p * 3 + 3], b);
            assert!((out[p * 2 + b] - want).abs() < 1e-13 * (1.0 + want.abs()));
        }
    }
}

#[test]
fn bad_grids_are_typed_errors() {
    let v = values(&[vec![0.0, 1.0, 2.0, 3.0]], 1, |x, _| x[0]);
    let e = |g: Vec<f64>, k| GridSpline::interpolate(vec![g], v.view(), k).err();
    assert!(matches!(
        e(vec![0.0, 1.0, 1.0, 3.0], 3),
        Some(GriddedError::NotAscending { index: 2, .. })
    ));
    assert!(matches!(
        e(vec![0.0, 1.0, f64::NAN, 3.0], 3),
        Some(GriddedError::NotAscending { .. })
    ));
    assert!(matches!(
        e(vec![0.0, 1.0, 2.0, 3.0], 5),
        Some(GriddedError::TooFewPoints { need: 6, .. })
    ));
    assert!(matches!(
        e(vec![0.0, 1.0, 2.0, 3.0], 2),
        Some(GriddedError::Degree(2))
    ));
    assert!(matches!(
        e(vec![0.0, 1.0, 2.0], 1),
        Some(GriddedError::Shape { .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// Meets the data at every node to its bound, on grids down to
    /// near-coincident nodes, and reversing an axis (x → −x) mirrors it.
    #[test]
    fn interpolates_and_mirrors(n0 in 4usize..9, n1 in 6usize..10, seed in 0u64..1000,
                                gap in prop::sample::select(vec![1e-6, 1e-3, 0.2]),
                                k in prop::sample::select(vec![1usize, 3, 5])) {
        let grid = vec![nodes(n0.max(k + 1), seed, gap), nodes(n1, seed + 1, gap)];
        let f = |x: &[f64], _: usize| ((5.0 * x[0]).sin() + x[1]).tanh() + 0.1 * (seed % 7) as f64;
        let v = values(&grid, 1, f);
        let s = GridSpline::interpolate(grid.clone(), v.view(), k).unwrap();
        let bound = s.error_bound();
        for (i, &x0) in grid[0].iter().enumerate() {
            for (j, &x1) in grid[1].iter().enumerate() {
                let got = s.eval(&[x0, x1], &[]).unwrap()[0];
                prop_assert!((got - v[[i, j, 0]]).abs() <= bound, "{} vs {} bound {:e}", got, v[[i, j, 0]], bound);
            }
        }
        let flipped: Vec<f64> = grid[0].iter().rev().map(|x| -x).collect();
        let vf = values(&[flipped.clone(), grid[1].clone()], 1, |x, _| f(&[-x[0], x[1]], 0));
        let sf = GridSpline::interpolate(vec![flipped, grid[1].clone()], vf.view(), k).unwrap();
        let x = [grid[0][1] * 0.7 + grid[0][2] * 0.3, grid[1][2]];
        let (a, b) = (s.eval(&x, &[]).unwrap()[0], sf.eval(&[-x[0], x[1]], &[]).unwrap()[0]);
        prop_assert!((a - b).abs() <= bound + sf.error_bound(), "{} vs {}", a, b);
    }
}

/// The windowed value against the whole spline: within `tol·max|v|` plus
/// rounding, windows narrower than the axis, and the whole window exact.
#[test]
fn cardinal_windows_certify_the_truncation() {
    let grid = vec![nodes(200, 41, 0.3), nodes(150, 42, 0.3)];
    let v = values(&grid, 1, |x, _| {
        (0.7 * x[0]).sin() * (0.3 * x[1]).cos() + 0.01 * x[0]
    });
    let vmax = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for k in [3usize, 5] {
        let s = GridSpline::interpolate(grid.clone(), v.view(), k).unwrap();
        let axes: Vec<CardinalAxis<f64>> = grid
            .iter()
            .enumerate()
            .map(|(a, g)| CardinalAxis::new(g.clone(), k, a).unwrap())
            .collect();
        for tol in [1e-4, 1e-8, 1e-12] {
            for t in 0..15 {
                let x = [
                    grid[0][0] + 2.37 * t as f64 + 0.11,
                    grid[1][0] + 1.91 * t as f64 + 0.05,
                ];
                let w = point_windows(&axes, &x, tol);
                let got = windowed_value(&w, |j| v[[j[0], j[1], 0]]);
                let want = s.eval(&x, &[]).unwrap()[0];
                let rounding = 1e3 * s.error_bound();
                assert!(
                    (got - want).abs() <= tol * vmax + rounding,
                    "k={k} tol={tol}: {got} vs {want}"
                );
                let width = w[0].weights.len();
                assert!(width < 200, "k={k} tol={tol}: window {width} of 200");
                if tol == 1e-4 {
                    assert!(width < 40, "k={k}: window {width} at 1e-4");
                }
            }
        }
        // tol = 0 keeps every sample: the exact spline, to rounding.
        let x = [grid[0][7] + 0.1, grid[1][9] + 0.2];
        let w = point_windows(&axes, &x, 0.0);
        let got = windowed_value(&w, |j| v[[j[0], j[1], 0]]);
        assert!((got - s.eval(&x, &[]).unwrap()[0]).abs() <= 1e3 * s.error_bound());
    }
}
