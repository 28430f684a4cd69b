//! The line filter's own tests: the overflow refusal (the degree named,
//! `cval` counted), the cascade against 128-bit MPFR, and the strided
//! routes against each other bit for bit (rows in place, streamed, in
//! blocks).

use super::*;
use crate::ndimage::samples::Sample;

fn exact(order: u32, mode: Mode, cval: f64) -> LineFilter<f64> {
    LineFilter::new(&SplineFamily::Order(order), mode, cval, Route::Exact).unwrap()
}

/// Degree 199's growth bound overflows f64 along two axes whatever the
/// data: the refusal names the degree 199, the axes, and a degree the
/// data fits — one whose check passes while the next one's does not —
/// and the MPFR route; never "scale the data below 0e0".
#[test]
fn a_degree_beyond_the_range_names_one_that_fits() {
    let e = exact(200, Mode::Mirror, 0.0)
        .check_magnitude(0.5, 2)
        .unwrap_err();
    let NdimageError::DegreeRange {
        degree: 199,
        axes: 2,
        bits: 53,
        fits: Some(d),
    } = e
    else {
        panic!("{e}");
    };
    assert!(
        exact(d + 1, Mode::Mirror, 0.0)
            .check_magnitude(0.5, 2)
            .is_ok()
    );
    assert!(
        exact(d + 2, Mode::Mirror, 0.0)
            .check_magnitude(0.5, 2)
            .is_err()
    );
    let message = e.to_string();
    assert!(
        message.contains(&format!("degree {d} and below fit float64"))
            && message.contains("--prec")
    );
    assert!(!message.contains("0e0"), "{message}");
}

/// `cval` counts towards the overflow check only under `grid-constant`,
/// the one mode whose extension holds it (scipy's 'constant' filters
/// with the mirror rule and puts `cval` outside, even infinite).
#[test]
fn cval_counts_only_where_the_mode_extends_by_it() {
    for mode in [Mode::Mirror, Mode::Reflect, Mode::GridWrap, Mode::Nearest] {
        assert!(
            exact(4, mode, f64::INFINITY)
                .check_magnitude(1.0, 1)
                .is_ok(),
            "{mode}"
        );
    }
    let e = exact(4, Mode::GridConstant, 1e308)
        .check_magnitude(1.0, 1)
        .unwrap_err();
    assert!(
        matches!(e, NdimageError::Overflow { max, .. } if max == 1e308),
        "{e}"
    );
}

/// The two poles' passes as one pass down and one up ([`Cascade`]:
/// its starts derived from the symmetry of the result) against 128-bit
/// MPFR running the one-line recursion pole after pole, column by
/// column: degrees 4 and 5, every mode, lines of 3 samples (the
/// fewest the cascade takes) to 41 and 300 (beyond every horizon),
/// in f64 and f32, through [`LineFilter::apply_lines`] and
/// [`LineFilter::apply_rows_from`]. Within `64 u A` of `max|s| = 1`
/// (`A = 1/|V(−1)|`, the per-axis bound of `nd_prefilter`'s tests).
#[test]
fn cascade_of_two_poles_matches_mpfr_at_every_length() {
    cascade_matches_mpfr::<f64>();
    cascade_matches_mpfr::<f32>();
}

fn cascade_matches_mpfr<T: Real>() {
    use crate::scalar::Mp;
    type W = Mp<128>;
    let u = 2f64.powi(-(T::BITS as i32));
    let w = 5;
    for degree in [4u32, 5] {
        let family = SplineFamily::Order(degree + 1);
        for mode in Mode::ALL {
            let f = LineFilter::<T>::new(&family, mode, 0.25, Route::Exact).unwrap();
            assert!(f.cascade.is_some(), "degree {degree} has two poles");
            let wide = LineFilter::<W>::new(&family, mode, 0.25, Route::Exact).unwrap();
            let allowed = 64.0 * u * wide.recursive().amplification().to_f64();
            for n in (3..=41).chain([300]) {
                let data: Vec<T> = (0..n * w)
                    .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 105.5 - 1.0))
                    .collect();
                let mut lines = data.clone();
                f.apply_lines(&mut lines, w, &mut Vec::new());
                let mut rows = vec![T::zero(); n * w];
                let src: Vec<&[T]> = data.chunks(w).collect();
                let mut outs: Vec<&mut [T]> = rows.chunks_mut(w).collect();
                f.apply_rows_from(
                    &src,
                    &mut outs,
                    &mut Vec::new(),
                    &mut Vec::new(),
                    &mut (),
                    n % 2 == 1,
                );
                for j in 0..w {
                    let mut line: Vec<W> = (0..n)
                        .map(|i| W::from_f64_exact(data[i * w + j].to_f64()))
                        .collect();
                    wide.apply(&mut line, &mut Vec::new());
                    for (i, want) in line.iter().enumerate() {
                        let want = want.to_f64();
                        for (route, got) in [("lines", &lines), ("rows", &rows)] {
                            let diff = (got[i * w + j].to_f64() - want).abs();
                            assert!(
                                diff <= allowed,
                                "{} bits degree {degree} {mode:?} n {n} {route} [{i}]: \
                                 {diff:e} > {allowed:e}",
                                T::BITS
                            );
                        }
                    }
                }
            }
        }
    }
}

/// `apply_rows` (rows read and written in place, passes fused) against
/// `apply_lines` (rows copied, one pass per operation): every mode and
/// route, one to three poles, lines of 1 to 40 samples (shorter and
/// longer than the horizons), rows of 1, 3 and 8 lines.
#[test]
fn rows_in_place_equal_apply_lines_bit_for_bit() {
    let modes = Mode::ALL;
    for degree in [1u32, 2, 3, 5, 7] {
        let family = SplineFamily::Order(degree + 1);
        for mode in modes {
            for route in [
                Route::Exact,
                Route::Truncated { tol: 1e-9 },
                Route::Convolution { tol: 1e-9 },
            ] {
                let f = LineFilter::<f64>::new(&family, mode, 0.5, route).unwrap();
                for (n, w) in [(1, 3), (2, 1), (3, 8), (7, 3), (40, 8)] {
                    let data: Vec<f64> = (0..n * w)
                        .map(|i| ((i * 7919) % 211) as f64 / 97.0 - 1.0)
                        .collect();
                    let mut want = data.clone();
                    f.apply_lines(&mut want, w, &mut Vec::new());
                    let mut got = data.clone();
                    let mut rows: Vec<&mut [f64]> = got.chunks_mut(w).collect();
                    f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
                    assert!(
                        got.iter()
                            .zip(&want)
                            .all(|(a, b)| a.to_bits() == b.to_bits()),
                        "degree {degree} {mode:?} {route:?} n {n} w {w}"
                    );
                }
            }
        }
    }
}

/// Rows filtered in blocks ([`LineFilter::filter_in_blocks`])
/// equal the whole-strip buffer ([`LineFilter::apply_rows`],
/// `apply_rows_from`) bit for bit: degrees 2–5 (one pole; two: the
/// cascade), mirror and reflect, f64 and f32, lines of 256 to 1001 rows
/// (blocks of unequal length, a last block of ≥ 3 rows), rows of 1 to
/// 17 values, in place and from a copy (scanned rows: the same maxima);
/// f32 samples and rows of an f64 filter equal the rows widened,
/// filtered in f64 and rounded once.
#[test]
fn rows_in_blocks_equal_the_whole_buffer_bit_for_bit() {
    rows_in_blocks::<f64>();
    rows_in_blocks::<f32>();
    for degree in [2u32, 3, 5] {
        let f = LineFilter::<f64>::new(
            &SplineFamily::Order(degree + 1),
            Mode::Mirror,
            0.0,
            Route::Exact,
        )
        .unwrap();
        let (n, w) = (700, 9);
        let data: Vec<f32> = (0..n * w)
            .map(|i| ((i * 7919) % 211) as f32 / 97.0 - 1.0)
            .collect();
        let mut wide: Vec<f64> = data.iter().map(|&x| x as f64).collect();
        let mut rows: Vec<&mut [f64]> = wide.chunks_mut(w).collect();
        f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
        let want: Vec<f32> = wide.iter().map(|&x| x as f32).collect();
        // From f32 samples into f32 rows, and in place in f32 rows.
        let mut got = vec![0f32; n * w];
        let src: Vec<&[f32]> = data.chunks(w).collect();
        let mut rows: Vec<&mut [f32]> = got.chunks_mut(w).collect();
        assert!(blocks(
            &f,
            Some(&src),
            &mut rows,
            &mut RowBlocks::default(),
            &mut (),
            false
        ));
        assert_eq!(got, want, "degree {degree} from f32");
        let mut got = data.clone();
        let mut rows: Vec<&mut [f32]> = got.chunks_mut(w).collect();
        assert!(blocks::<_, f32, f32, ()>(
            &f,
            None,
            &mut rows,
            &mut RowBlocks::default(),
            &mut (),
            false
        ));
        assert_eq!(got, want, "degree {degree} in place f32");
    }
}

fn rows_in_blocks<T: Real>() {
    for degree in [2u32, 3, 4, 5] {
        let family = SplineFamily::Order(degree + 1);
        for mode in [Mode::Mirror, Mode::Reflect] {
            let f = LineFilter::<T>::new(&family, mode, 0.0, Route::Exact).unwrap();
            for (n, w) in [(256, 1), (257, 17), (300, 8), (1001, 5)] {
                let data: Vec<T> = (0..n * w)
                    .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 97.0 - 1.0))
                    .collect();
                let mut want = data.clone();
                let mut rows: Vec<&mut [T]> = want.chunks_mut(w).collect();
                f.apply_rows(&mut rows, &mut Vec::new(), &mut Vec::new());
                let bits = |v: &[T]| v.iter().map(|x| x.to_f64().to_bits()).collect::<Vec<_>>();
                let mut got = data.clone();
                let mut rows: Vec<&mut [T]> = got.chunks_mut(w).collect();
                let mut work = RowBlocks::default();
                assert!(blocks::<_, T, T, ()>(
                    &f,
                    None,
                    &mut rows,
                    &mut work,
                    &mut (),
                    false
                ));
                assert_eq!(
                    bits(&got),
                    bits(&want),
                    "degree {degree} {mode:?} n {n} w {w} in place"
                );
                for stream in [false, true] {
                    let mut got = vec![T::zero(); n * w];
                    let src: Vec<&[T]> = data.chunks(w).collect();
                    let mut rows: Vec<&mut [T]> = got.chunks_mut(w).collect();
                    let mut seen = MaxSeen::default();
                    assert!(blocks(
                        &f,
                        Some(&src),
                        &mut rows,
                        &mut work,
                        &mut seen,
                        stream
                    ));
                    assert_eq!(
                        bits(&got),
                        bits(&want),
                        "degree {degree} {mode:?} n {n} w {w} from src"
                    );
                    assert_eq!(seen.rows, n, "each sample row seen once");
                }
            }
            // Too few rows for blocks: refused, nothing written.
            let mut short = vec![T::one(); 100];
            let mut rows: Vec<&mut [T]> = short.chunks_mut(1).collect();
            assert!(!blocks::<_, T, T, ()>(
                &f,
                None,
                &mut rows,
                &mut RowBlocks::default(),
                &mut (),
                false
            ));
            assert!(short.iter().all(|x| *x == T::one()));
        }
    }
}

/// [`LineFilter::filter_in_blocks`] on the rows of a strip.
fn blocks<T: Real, E: Sample<T>, O: Sample<T> + Stored<T>, F: RowCheck>(
    f: &LineFilter<T>,
    src: Option<&[&[E]]>,
    rows: &mut [&mut [O]],
    work: &mut RowBlocks<T>,
    seen: &mut F,
    stream: bool,
) -> bool {
    f.filter_in_blocks(
        &mut StripRows {
            src,
            rows,
            seen,
            stream,
        },
        work,
    )
}

/// Counts the rows a pass takes in.
#[derive(Default)]
struct MaxSeen {
    rows: usize,
}

impl RowCheck for MaxSeen {
    fn row<U: Real>(&mut self, _: &[U]) {
        self.rows += 1;
    }
}

/// The rows written by streaming stores (`apply_rows_from` with
/// `stream`) equal [`LineFilter::apply_lines`] bit for bit: f64 and
/// f32, degrees 3 and 5 (one pole; two: the cascade) and 2, every mode,
/// rows of 1 to 70 values (heads, whole 64-byte lines and tails) at
/// offsets that leave them unaligned, 2 to 40 rows.
#[test]
fn streamed_rows_equal_apply_lines_bit_for_bit() {
    streamed_rows::<f64>();
    streamed_rows::<f32>();
}

fn streamed_rows<T: Real>() {
    for degree in [2u32, 3, 5] {
        let family = SplineFamily::Order(degree + 1);
        for mode in Mode::ALL {
            let f = LineFilter::<T>::new(&family, mode, 0.5, Route::Exact).unwrap();
            for (n, w, off) in [(2, 1, 0), (3, 17, 1), (7, 8, 3), (40, 24, 2), (40, 70, 5)] {
                let data: Vec<T> = (0..n * w)
                    .map(|i| T::from_f64_exact(((i * 7919) % 211) as f64 / 97.0 - 1.0))
                    .collect();
                let mut want = data.clone();
                f.apply_lines(&mut want, w, &mut Vec::new());
                let mut out = vec![T::zero(); off + n * w];
                let mut rows: Vec<&mut [T]> = out[off..].chunks_mut(w).collect();
                let src: Vec<&[T]> = data.chunks(w).collect();
                f.apply_rows_from(
                    &src,
                    &mut rows,
                    &mut Vec::new(),
                    &mut Vec::new(),
                    &mut (),
                    true,
                );
                let bits = |x: &T| x.to_f64().to_bits();
                assert!(
                    out[off..]
                        .iter()
                        .zip(&want)
                        .all(|(a, b)| bits(a) == bits(b)),
                    "{} bits degree {degree} {mode:?} n {n} w {w}",
                    T::BITS
                );
            }
        }
    }
}
