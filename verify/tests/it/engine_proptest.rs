//! Property tests of the engine's invariants (issue 14), with
//! near-degenerate inputs: lines of 1, 2, 3 samples, values within a few
//! ulps of each other, huge and tiny magnitudes.
//!
//! References: closed forms (a constant's coefficients are the constant; a
//! B-spline reproduces linear functions, so away from the ends a linear
//! signal's coefficients are the signal), exact symmetries (grid-wrap
//! commutes with shifts; scaling by 2^e is exact in binary floating point),
//! the interpolation condition, and central differences in 256-bit MPFR.

use proptest::prelude::*;
use splinelab::ndarray::{Array1, Array2};
use splinelab::prelude::*;

const EPS: f64 = f64::EPSILON;

fn filter(degree: u32, mode: Mode, cval: f64) -> LineFilter<f64> {
    LineFilter::new(&SplineFamily::Order(degree + 1), mode, cval, Route::Exact).unwrap()
}

fn coeffs(f: &LineFilter<f64>, s: &[f64]) -> Vec<f64> {
    let mut c = s.to_vec();
    f.apply(&mut c, &mut Vec::new());
    c
}

fn mode() -> impl Strategy<Value = Mode> {
    prop::sample::select(Mode::ALL.to_vec())
}

/// A magnitude from 2^−900 to 2^900 (huge and tiny).
fn magnitude() -> impl Strategy<Value = f64> {
    (-900i32..=900).prop_map(|e| 2f64.powi(e))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// A constant signal (plus a few ulps of noise: values within a few
    /// ulps of each other) has coefficients equal to the constant, up to
    /// the noise times the amplification 1/|V(−1)| and rounding, in every
    /// mode (grid-constant with cval = the constant), at any length ≥ 1.
    #[test]
    fn constants_are_reproduced(
        degree in 1u32..=9,
        mode in mode(),
        len in 1usize..=40,
        k in -1.0f64..1.0,
        scale in magnitude(),
        noise in prop::collection::vec(-4i32..=4, 40),
    ) {
        let k = k * scale;
        let f = filter(degree, mode, k);
        let amp = f.recursive().amplification();
        let ulp = k.abs() * EPS;
        let s: Vec<f64> = (0..len).map(|j| k + noise[j] as f64 * ulp).collect();
        let c = coeffs(&f, &s);
        let allowed = amp * 4.0 * ulp + 64.0 * amp * EPS * (k.abs() + 4.0 * ulp);
        for (j, cj) in c.iter().enumerate() {
            prop_assert!((cj - k).abs() <= allowed, "d={degree} {mode} len={len} j={j}: {cj:e} vs {k:e}");
        }
    }

    /// Away from the ends (where the pole's influence `ρ^K < 2^{−60}`), the
    /// coefficients of a linear signal `a + b j` are the signal, in mirror
    /// and reflect, and the interpolant there is the line.
    #[test]
    fn linear_functions_are_reproduced_in_the_interior(
        degree in 1u32..=7,
        reflect in any::<bool>(),
        a in -10.0f64..10.0,
        b in -1.0f64..1.0,
        extra in 0usize..40,
        frac in 0.0f64..1.0,
    ) {
        let mode = if reflect { Mode::Reflect } else { Mode::Mirror };
        let f = filter(degree, mode, 0.0);
        let rho = f.recursive().poles().iter().map(|z| z.abs()).fold(0.0, f64::max);
        let k = if rho == 0.0 { 1 } else { (-60.0 / rho.log2()).ceil() as usize + 1 };
        let n = 2 * k + 1 + extra;
        let s: Vec<f64> = (0..n).map(|j| a + b * j as f64).collect();
        let c = coeffs(&f, &s);
        let amp = f.recursive().amplification();
        let scale = a.abs() + b.abs() * n as f64;
        let allowed = 64.0 * amp * EPS * scale;
        for j in k..n - k {
            prop_assert!((c[j] - s[j]).abs() <= allowed, "d={degree} {mode} j={j}: {} vs {}", c[j], s[j]);
        }
        let g: Interpolant<f64> = Interpolant::new(&Array1::from(s), Options::new(degree, mode)).unwrap();
        let x = k as f64 + frac * (n - 2 * k - 1) as f64;
        let v = g.eval(&[x]).unwrap();
        prop_assert!((v - (a + b * x)).abs() <= allowed * degree as f64, "x={x}: {v} vs {}", a + b * x);
    }

    /// grid-wrap is periodic: filtering a rotated signal rotates the
    /// coefficients (to rounding).
    #[test]
    fn grid_wrap_commutes_with_shifts(
        degree in 1u32..=9,
        s in prop::collection::vec(-1.0f64..1.0, 1..60),
        shift in 0usize..60,
    ) {
        let f = filter(degree, Mode::GridWrap, 0.0);
        let n = s.len();
        let r: Vec<f64> = (0..n).map(|j| s[(j + shift) % n]).collect();
        let (cs, cr) = (coeffs(&f, &s), coeffs(&f, &r));
        let allowed = 64.0 * f.recursive().amplification() * EPS;
        for j in 0..n {
            let d = (cr[j] - cs[(j + shift) % n]).abs();
            prop_assert!(d <= allowed, "d={degree} n={n} j={j}: {d:e}");
        }
    }

    /// Scaling the samples by 2^e scales the coefficients by exactly 2^e
    /// (every rounding scales with it), from 2^−900 to 2^900.
    #[test]
    fn power_of_two_scaling_is_exact(
        degree in 1u32..=9,
        mode in mode(),
        s in prop::collection::vec(-1.0f64..1.0, 1..40),
        scale in magnitude(),
    ) {
        let f = filter(degree, mode, 0.0);
        let c = coeffs(&f, &s);
        let scaled: Vec<f64> = s.iter().map(|x| x * scale).collect();
        let cs = coeffs(&f, &scaled);
        for (j, (x, y)) in c.iter().zip(&cs).enumerate() {
            if x.abs() > 1e-200 {
                prop_assert_eq!(x * scale, *y, "j={}", j);
            }
        }
    }

    /// The interpolant returns the samples at the grid points (1-D and 2-D,
    /// every mode, lines of 1 to 12 samples), to the rounding of
    /// coefficients of size ≤ amplification^ndim · max|s|.
    #[test]
    fn interpolation_at_the_nodes_returns_the_samples(
        degree in 1u32..=9,
        mode in mode(),
        rows in 1usize..=12,
        cols in 1usize..=12,
        seed in any::<u64>(),
    ) {
        let s = splinelab_verify::rng::SplitMix64::new(seed).signal(rows * cols);
        let amp = filter(degree, mode, 0.3).recursive().amplification();
        let opts = Options { cval: 0.3, ..Options::new(degree, mode) };
        let m = (degree + 1) as f64;
        let line = Array1::from(s[..cols].to_vec());
        let f1: Interpolant<f64> = Interpolant::new(&line, opts).unwrap();
        for (j, &sj) in s[..cols].iter().enumerate() {
            let v = f1.eval(&[j as f64]).unwrap();
            prop_assert!((v - sj).abs() <= 32.0 * m * amp * EPS, "1-D d={degree} {mode} j={j}: {v} vs {sj}");
        }
        let grid = Array2::from_shape_vec((rows, cols), s.clone()).unwrap();
        let f2: Interpolant<f64> = Interpolant::new(&grid, opts).unwrap();
        for i in 0..rows {
            for j in 0..cols {
                let v = f2.eval(&[i as f64, j as f64]).unwrap();
                let want = s[i * cols + j];
                prop_assert!((v - want).abs() <= 64.0 * m * amp * amp * EPS, "2-D d={degree} {mode} ({i},{j}): {v} vs {want}");
            }
        }
    }

    /// The first derivative of the 256-bit interpolant against a central
    /// difference of step h = 2^−40 in 256 bits, away from the knots (so
    /// the spline is one polynomial around x and the difference's error is
    /// h²/6 |f'''|).
    #[test]
    fn derivative_matches_mpfr_central_difference(
        degree in 2u32..=9,
        mode in mode(),
        n in 2usize..=24,
        cell in 0usize..24,
        k in 0u32..16,
        seed in any::<u64>(),
    ) {
        type M = Mp<256>;
        let s: Vec<M> = splinelab_verify::rng::SplitMix64::new(seed)
            .signal(n)
            .into_iter()
            .map(M::from_f64_exact)
            .collect();
        let opts = Options { cval: 0.3, ..Options::new(degree, mode) };
        let f: Interpolant<M> = Interpolant::new(&Array1::from(s), opts).unwrap();
        // Odd degrees have knots at integers, even ones at half-integers:
        // (2k + 1)/64 off either keeps x ± h inside one polynomial piece.
        let x = (cell % (n - 1)) as f64 + (2 * k + 1) as f64 / 64.0;
        let h = 2f64.powi(-40);
        let d = f.eval_derivative(&[x], &[1]).unwrap();
        let diff = (f.eval(&[x + h]).unwrap() - f.eval(&[x - h]).unwrap()) / M::from_f64_exact(2.0 * h);
        let err = (d.clone() - diff).to_f64().abs();
        let amp = filter(degree, mode, 0.3).recursive().amplification();
        // |f'''| ≤ 8^3 · A · max|s|-ish for a spline of degree ≤ 9: h²·that ≪ 1e-18.
        prop_assert!(err <= 1e-18 * amp, "d={degree} {mode} x={x}: f'={:e} diff err {err:e}", d.to_f64());
    }
}
