//! The prefilter's vector kernels (`ndimage::lanes` and
//! `ndimage::window_recursion`, compiled per CPU and chosen at run time)
//! against independent references, in f64 and f32: the certified blocks of
//! one long line against the exact coefficients in 128-bit MPFR (within the
//! tail bound plus the scalar's rounding) — every mode, degrees 1 to 7 and
//! 25, lines and blocks just around the window and vector sizes, lines
//! shorter than a block, and the same bits on any number of threads; the
//! side-by-side lines of a strided and of the contiguous axis against MPFR
//! line by line and against the one-line scalar recursion
//! (`LineFilter::apply`, a different order of operations).

use splinelab::ndarray::{Array1, Array2, Axis};
use splinelab::prelude::*;
use splinelab_verify::rng::SplitMix64;

type W = Mp<128>;

/// A fixed pseudo-random signal in [−1, 1).
fn signal(n: usize, seed: u64) -> Vec<f64> {
    SplitMix64::new(seed).signal(n)
}

/// The exact filter of degree `d` in 128-bit MPFR.
fn mpfr_filter(d: u32, mode: Mode) -> LineFilter<W> {
    LineFilter::<W>::new(&SplineFamily::Order(d + 1), mode, 0.0, Route::Exact).unwrap()
}

/// The exact coefficients of `s` by `f` (MPFR), rounded to f64, and the
/// amplification `1/|V(−1)|`.
fn mpfr_exact(f: &LineFilter<W>, s: &[f64]) -> (Vec<f64>, f64) {
    let mut c: Vec<W> = s.iter().map(|x| W::from_f64_exact(*x)).collect();
    f.apply(&mut c, &mut Vec::new());
    let amp = f.recursive().amplification().to_f64();
    (c.iter().map(|x| x.to_f64()).collect(), amp)
}

fn max_diff<T: Real>(a: &[T], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x.to_f64() - y).abs()))
}

/// The samples as `T` (f32 rounds them; the reference is then taken of the
/// rounded samples).
fn to<T: Real>(s: &[f64]) -> Vec<T> {
    s.iter().map(|x| T::from_f64_exact(*x)).collect()
}

/// One long line in certified blocks (the vector kernels' `[T; 32]` rows)
/// against MPFR: `|D − D_exact| ≤ bound · max|s| + 64 u A` (`u` the unit
/// roundoff of `T`), and against the scalar exact recursion in `T` within
/// the same; every mode, cubic and quintic.
fn blocks_within_bound<T: Real + Send + Sync>(tol: f64) {
    let u = 2f64.powi(-(T::BITS as i32));
    let s64 = signal(50_000, 41);
    let s: Vec<T> = to(&s64);
    let rounded: Vec<f64> = s.iter().map(|x| x.to_f64()).collect();
    for d in [3u32, 5] {
        let family = SplineFamily::Order(d + 1);
        for mode in Mode::ALL {
            let (want, amp) = mpfr_exact(&mpfr_filter(d, mode), &rounded);
            let f = LineFilter::<T>::new(&family, mode, 0.0, Route::Truncated { tol }).unwrap();
            let blocks = BlockPrefilter::from_line_filter(&f).unwrap();
            assert!(blocks.pays_off(s.len()));
            let mut got = vec![T::zero(); s.len()];
            blocks.apply_line_into(&s, &mut got).unwrap();
            let allowed = f.bound() + 64.0 * u * amp;
            let diff = max_diff(&got, &want);
            assert!(
                diff <= allowed,
                "{} d={d} {mode}: {diff:e} > {allowed:e}",
                T::BITS
            );
            let mut scalar = s.clone();
            f.apply(&mut scalar, &mut Vec::new());
            let scalar: Vec<f64> = scalar.iter().map(|x| x.to_f64()).collect();
            let diff = max_diff(&got, &scalar);
            assert!(
                diff <= allowed,
                "{} d={d} {mode} vs scalar: {diff:e}",
                T::BITS
            );
        }
    }
}

#[test]
fn f64_blocks_match_mpfr_within_the_bound() {
    blocks_within_bound::<f64>(1e-12);
}

#[test]
fn f32_blocks_match_mpfr_within_the_bound() {
    blocks_within_bound::<f32>(1e-6);
}

/// Lengths around the sizes the block route cuts at, for `T`: a vector of
/// lanes (8 `f64`, 16 `f32`), a window (8 KiB of samples), a task of four
/// windows; and lines shorter than all of them.
fn awkward_lengths<T>() -> Vec<usize> {
    let window = (8 << 10) / std::mem::size_of::<T>();
    let mut n = vec![1, 2, 7, 8, 9, 15, 16, 17, 33, 100];
    for edge in [window, 2 * window, 4 * window] {
        n.extend([edge - 1, edge, edge + 1]);
    }
    n.push(4 * window + 37);
    n
}

/// [`BlockPrefilter::apply`] of every awkward length (blocks of 1 sample,
/// of a few vectors, of a window ± 1, of the whole line and more) against
/// the exact coefficients in 128-bit MPFR, within `bound · max|s| + 64 u A`
/// (`max|s| ≤ max(1, |cval|) = 1`); every mode, degree 1 (no pole: the
/// samples), degrees 2..7 and 25 (a cascade of twelve poles).
fn blocks_of_every_shape_match_mpfr<T: Real + Send + Sync>(tol: f64) {
    let u = 2f64.powi(-(T::BITS as i32));
    let window = (8 << 10) / std::mem::size_of::<T>();
    for d in [1u32, 2, 3, 4, 5, 6, 7, 25] {
        let family = SplineFamily::Order(d + 1);
        for mode in Mode::ALL {
            let wide = LineFilter::<W>::new(&family, mode, 0.5, Route::Exact).expect("MPFR filter");
            let amp = wide.recursive().amplification().to_f64();
            let f = LineFilter::<T>::new(&family, mode, 0.5, Route::Truncated { tol }).unwrap();
            let blocks = BlockPrefilter::from_line_filter(&f).unwrap();
            let allowed = f.bound() + 64.0 * u * amp;
            for (k, n) in awkward_lengths::<T>().into_iter().enumerate() {
                if d == 25 && k % 3 != 0 {
                    continue;
                }
                let s: Vec<T> = to(&signal(n, 100 + k as u64));
                let mut c: Vec<W> = s.iter().map(|x| W::from_f64_exact(x.to_f64())).collect();
                wide.apply(&mut c, &mut Vec::new());
                let want: Vec<f64> = c.iter().map(|x| x.to_f64()).collect();
                for block in [1, 40, window - 1, window + 1, n, 3 * n + 5] {
                    let got = blocks.apply(&s, block).unwrap();
                    let diff = max_diff(&got, &want);
                    assert!(
                        diff <= allowed,
                        "{} d={d} {mode} n={n} block={block}: {diff:e} > {allowed:e}",
                        T::BITS
                    );
                }
            }
        }
    }
}

#[test]
fn f64_blocks_of_every_shape_match_mpfr() {
    blocks_of_every_shape_match_mpfr::<f64>(1e-12);
}

#[test]
fn f32_blocks_of_every_shape_match_mpfr() {
    blocks_of_every_shape_match_mpfr::<f32>(1e-6);
}

/// One long line gives the same bits on one, two and three threads (the
/// windows depend on the length only), f64 and f32, cubic and degree 7.
fn blocks_are_the_same_bits_on_any_pool<T: Real + Send + Sync>(tol: f64) {
    let s: Vec<T> = to(&signal(300_001, 9));
    for d in [3u32, 7] {
        let family = SplineFamily::Order(d + 1);
        let f =
            LineFilter::<T>::new(&family, Mode::Reflect, 0.0, Route::Truncated { tol }).unwrap();
        let blocks = BlockPrefilter::from_line_filter(&f).unwrap();
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut out = vec![T::zero(); s.len()];
            pool.install(|| blocks.apply_line_into(&s, &mut out))
                .unwrap();
            out
        };
        let one = run(1);
        assert!(one == run(2) && one == run(3), "{} d={d}", T::BITS);
    }
}

#[test]
fn f64_blocks_are_the_same_bits_on_any_pool() {
    blocks_are_the_same_bits_on_any_pool::<f64>(1e-12);
}

#[test]
fn f32_blocks_are_the_same_bits_on_any_pool() {
    blocks_are_the_same_bits_on_any_pool::<f32>(1e-6);
}

/// Every axis of a 2-D array (axis 0: strided lines side by side; axis 1:
/// contiguous lines in groups) against MPFR line by line, and against the
/// one-line scalar recursion in `T`: within `64 u A` of max|s| = 1.
fn lines_match_mpfr<T: Real + Send + Sync>() {
    let u = 2f64.powi(-(T::BITS as i32));
    let (rows, cols) = (37, 211);
    let s64 = signal(rows * cols, 7);
    let a: Array2<T> = Array2::from_shape_vec((rows, cols), to(&s64)).unwrap();
    for d in [3u32, 5] {
        let family = SplineFamily::Order(d + 1);
        for mode in [Mode::Mirror, Mode::Reflect, Mode::GridWrap, Mode::Nearest] {
            let f = LineFilter::<T>::new(&family, mode, 0.0, Route::Exact).unwrap();
            let wide = mpfr_filter(d, mode);
            for axis in 0..2 {
                let mut got = a.clone();
                spline_filter1d(&mut got, axis, &f).unwrap();
                for (lane, line) in got.lanes(Axis(axis)).into_iter().zip(a.lanes(Axis(axis))) {
                    let line: Vec<T> = line.to_vec();
                    let rounded: Vec<f64> = line.iter().map(|x| x.to_f64()).collect();
                    let (want, amp) = mpfr_exact(&wide, &rounded);
                    let got: Vec<T> = lane.to_vec();
                    let allowed = 64.0 * u * amp;
                    let diff = max_diff(&got, &want);
                    assert!(
                        diff <= allowed,
                        "{} d={d} {mode} axis {axis}: {diff:e}",
                        T::BITS
                    );
                    let mut scalar = Array1::from_vec(line);
                    f.apply(scalar.as_slice_mut().unwrap(), &mut Vec::new());
                    let scalar: Vec<f64> = scalar.iter().map(|x| x.to_f64()).collect();
                    let diff = max_diff(&got, &scalar);
                    assert!(
                        diff <= allowed,
                        "{} d={d} {mode} axis {axis} vs scalar",
                        T::BITS
                    );
                }
            }
        }
    }
}

#[test]
fn f64_lines_side_by_side_match_mpfr() {
    lines_match_mpfr::<f64>();
}

#[test]
fn f32_lines_side_by_side_match_mpfr() {
    lines_match_mpfr::<f32>();
}
