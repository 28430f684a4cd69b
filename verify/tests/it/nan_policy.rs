//! `NanPolicy::Local` (issue 37): the NaN set of an interpolant is exactly
//! the certified reach of its missing samples, and every other value is
//! within `local_bound · max|finite s|` of the exact spline of the samples
//! with the missing ones filled by any values in the data's range.
//!
//! References, written here independently of the engine: the reach by
//! brute force (a coefficient `i` is NaN iff a missing `j` has
//! `fold(i_a + k_a) = j_a`, `|k_a| ≤ n`, on every axis; an output iff its
//! window of `d + 1` coefficients per axis holds one), and the exact
//! (`Route::Exact`, no missing sample) spline of two random fillings in
//! f64. Degrees 0–9 and 15, every mode, 1-D and 2-D, f64 and f32.

use proptest::prelude::*;
use splinelab::ndarray::{ArrayD, IxDyn};
use splinelab::ndimage::missing::local_bound;
use splinelab::prelude::*;

/// The `d + 1` coefficient indices the window at `x` reads (scipy's):
/// from `⌊x⌋ − (d − 1)/2` for odd degrees, `⌊x + ½⌋ − d/2` for even ones.
fn window(x: f64, d: u32) -> std::ops::Range<i64> {
    let first = if d % 2 == 1 {
        x.floor() as i64 - (d as i64 - 1) / 2
    } else {
        (x + 0.5).floor() as i64 - d as i64 / 2
    };
    first..first + d as i64 + 1
}

/// Whether the coefficient at (extended) index `i` lies within `n` of the
/// missing sample `j`, folded by `mode`, on every axis.
fn reaches(i: &[i64], j: &[usize], n: usize, mode: Mode, shape: &[usize]) -> bool {
    (0..shape.len())
        .all(|a| (-(n as i64)..=n as i64).any(|k| mode.fold(i[a] + k, shape[a]) == Some(j[a])))
}

/// Brute force: whether the value at `x` reads a coefficient a missing sample reaches.
fn reached(
    x: &[f64],
    d: u32,
    n: usize,
    mode: Mode,
    shape: &[usize],
    missing: &[Vec<usize>],
) -> bool {
    let wins: Vec<Vec<i64>> = x.iter().map(|&xa| window(xa, d).collect()).collect();
    let mut idx = vec![0i64; shape.len()];
    let total: usize = wins.iter().map(|w| w.len()).product();
    (0..total).any(|mut t| {
        for a in (0..shape.len()).rev() {
            idx[a] = wins[a][t % wins[a].len()];
            t /= wins[a].len();
        }
        missing.iter().any(|j| reaches(&idx, j, n, mode, shape))
    })
}

/// Deterministic values in [−1, 1) from a seed (a Weyl sequence).
fn values(count: usize, seed: u64) -> Vec<f64> {
    (0..count as u64)
        .map(|i| {
            let x = (i + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ seed;
            (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
        .collect()
}

#[derive(Debug)]
struct Case {
    degree: u32,
    shape: Vec<usize>,
    mode: Mode,
    tol: f64,
    seed: u64,
    missing: Vec<Vec<usize>>,
}

fn local_reach_and_bound<T: Real + Send + Sync>(c: &Case) -> Result<(), TestCaseError> {
    let len: usize = c.shape.iter().product();
    let mut data = values(len, c.seed);
    let flat = |j: &[usize]| j.iter().zip(&c.shape).fold(0, |f, (&i, &n)| f * n + i);
    let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    for (k, j) in c.missing.iter().enumerate() {
        data[flat(j)] = bad[k % 3];
    }
    let to_t = |v: &[f64]| {
        ArrayD::from_shape_vec(
            IxDyn(&c.shape),
            v.iter().map(|&x| T::from_f64_exact(x)).collect(),
        )
        .unwrap()
    };
    let opts = Options {
        route: Route::Truncated { tol: c.tol },
        nan_policy: NanPolicy::Local,
        ..Options::new(c.degree, c.mode)
    };
    let f = Interpolant::new(&to_t(&data), opts).unwrap();
    let n = nan_reach(c.degree, c.tol).unwrap() - (c.degree as usize / 2 + 1);
    // The bound per unit of max|finite s|, and the rounding of f64 / f32.
    let finite: Vec<f64> = data.iter().copied().filter(|x| x.is_finite()).collect();
    let big = finite.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let (lo, hi) = finite
        .iter()
        .fold((big, -big), |(l, h), &x| (l.min(x), h.max(x)));
    let family = SplineFamily::Order(c.degree + 1);
    let (bound, amp) = if c.degree >= 2 {
        let lf =
            LineFilter::<f64>::new(&family, c.mode, 0.0, Route::Truncated { tol: c.tol }).unwrap();
        (
            local_bound(&lf, c.shape.len()),
            lf.recursive().amplification(),
        )
    } else {
        (0.0, 1.0)
    };
    let u = 2f64.powi(-(T::BITS as i32));
    let allowed =
        bound * big + 64.0 * u * amp.powi(c.shape.len() as i32) * big.max(f64::MIN_POSITIVE);
    // Two fillings in the data's range, exact route, f64.
    let fillings: Vec<Interpolant<f64>> = (0..2u64)
        .map(|k| {
            let fill = values(c.missing.len(), c.seed ^ (k + 1));
            let mut v = data.clone();
            for (j, r) in c.missing.iter().zip(fill) {
                v[flat(j)] = lo + (hi - lo) * (r + 1.0) / 2.0;
            }
            let a = ArrayD::from_shape_vec(IxDyn(&c.shape), v).unwrap();
            Interpolant::new(&a, Options::new(c.degree, c.mode)).unwrap()
        })
        .collect();
    let pts = values(20 * c.shape.len(), c.seed ^ 99);
    for (p, chunk) in pts.chunks(c.shape.len()).enumerate() {
        // Points in [0, n − 1], the first few on the grid (zero weights count).
        let x: Vec<f64> = chunk
            .iter()
            .zip(&c.shape)
            .map(|(&r, &len)| {
                let t = (r + 1.0) / 2.0 * (len - 1) as f64;
                if p < 4 { t.round() } else { t }
            })
            .collect();
        let got = f.eval(&x).unwrap().to_f64();
        let want_nan = reached(&x, c.degree, n, c.mode, &c.shape, &c.missing);
        prop_assert_eq!(got.is_nan(), want_nan, "{:?} at {:?}: {}", c.shape, x, got);
        if !want_nan {
            for e in &fillings {
                let diff = (got - e.eval(&x).unwrap()).abs();
                prop_assert!(
                    diff <= allowed,
                    "{:?} at {:?}: {:e} > {:e}",
                    c.shape,
                    x,
                    diff,
                    allowed
                );
            }
        }
    }
    // Nothing missing: within the bound of the exact spline.
    if c.missing.is_empty() {
        let exact = &fillings[0];
        for chunk in pts.chunks(c.shape.len()) {
            let x: Vec<f64> = chunk
                .iter()
                .zip(&c.shape)
                .map(|(&r, &len)| (r + 1.0) / 2.0 * (len - 1) as f64)
                .collect();
            let diff = (f.eval(&x).unwrap().to_f64() - exact.eval(&x).unwrap()).abs();
            prop_assert!(
                diff <= allowed,
                "clean {:?}: {:e} > {:e}",
                c.shape,
                diff,
                allowed
            );
        }
    }
    Ok(())
}

fn case() -> impl Strategy<Value = Case> {
    let degree = prop::sample::select((0u32..=9).chain([15]).collect::<Vec<_>>());
    let shape = prop_oneof![
        (1usize..=45).prop_map(|n| vec![n]),
        (1usize..=14, 1usize..=14).prop_map(|(a, b)| vec![a, b]),
    ];
    (
        degree,
        shape,
        prop::sample::select(Mode::ALL.to_vec()),
        prop::sample::select(vec![1e-3, 1e-6, 1e-12]),
        any::<u64>(),
        prop::collection::vec(any::<u64>(), 0..=3),
    )
        .prop_map(|(degree, shape, mode, tol, seed, picks)| {
            let missing = picks
                .iter()
                .map(|&p| {
                    let mut p = p;
                    shape
                        .iter()
                        .map(|&n| {
                            let i = (p % n as u64) as usize;
                            p /= n as u64;
                            i
                        })
                        .collect()
                })
                .collect();
            Case {
                degree,
                shape,
                mode,
                tol,
                seed,
                missing,
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// (a) The NaN set is exactly the certified reach (brute force);
    /// (b) every other value is within the stated bound of the exact spline
    /// of two fillings in the data's range; (c) with nothing missing, of
    /// the exact spline. f64 and f32, every mode, degrees 0–9 and 15.
    #[test]
    fn local_nan_set_is_the_reach_and_values_any_fillings_spline(c in case()) {
        local_reach_and_bound::<f64>(&c)?;
        local_reach_and_bound::<f32>(&c)?;
    }
}

/// `Propagate` is scipy's pattern on one line and in N-D: every line
/// through a missing sample along a filtered axis, so after every axis all
/// coefficients; the other lines are the finite route's, bit for bit.
#[test]
fn propagate_spreads_along_the_filtered_lines_only() {
    let f =
        LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, Route::Exact).unwrap();
    let clean = ArrayD::from_shape_vec(IxDyn(&[6, 9]), values(54, 3)).unwrap();
    let mut a = clean.clone();
    a[[2, 5]] = f64::NAN;
    let mut one = a.clone();
    spline_filter1d(&mut one, 1, &f).unwrap();
    let mut want = clean.clone();
    spline_filter1d(&mut want, 1, &f).unwrap();
    for ((i, j), (&got, &w)) in (0..6)
        .flat_map(|i| (0..9).map(move |j| (i, j)))
        .zip(one.iter().zip(&want))
    {
        if i == 2 {
            assert!(got.is_nan(), "({i}, {j})");
        } else {
            assert_eq!(got.to_bits(), w.to_bits(), "({i}, {j})");
        }
    }
    spline_filter(&mut a, &f).unwrap();
    assert!(a.iter().all(|x| x.is_nan()));
}

/// `Raise` names the first non-finite sample and its value; `Local`
/// without a width is refused with the reason.
#[test]
fn raise_names_the_sample_and_local_needs_a_tolerance() {
    let f =
        LineFilter::<f32>::new(&SplineFamily::Order(6), Mode::Reflect, 0.0, Route::Exact).unwrap();
    let e = f.clone().with_nan_policy(NanPolicy::Local).unwrap_err();
    assert!(e.to_string().contains("no finite reach"), "{e}");
    let f = f.with_nan_policy(NanPolicy::Raise).unwrap();
    let mut a = ArrayD::from_shape_vec(IxDyn(&[3, 4]), vec![0.5f32; 12]).unwrap();
    a[[1, 2]] = f32::NEG_INFINITY;
    a[[2, 0]] = f32::NAN;
    let e = spline_filter(&mut a, &f).unwrap_err();
    assert_eq!(e.to_string(), "sample 6 is not finite (-inf)");
}

/// Degree 1 has no prefilter: its coefficients are the samples (scipy's
/// `spline_filter` copies for `order < 2`), so a missing sample stays where
/// it is under every policy and every other value is the sample, bit for
/// bit, in every mode.
#[test]
fn degree_one_keeps_a_missing_sample_where_it_is() {
    let clean = ArrayD::from_shape_vec(IxDyn(&[6, 9]), values(54, 7)).unwrap();
    let mut a = clean.clone();
    a[[2, 5]] = f64::NAN;
    for mode in Mode::ALL {
        for route in [Route::Exact, Route::Truncated { tol: 1e-12 }] {
            for policy in [NanPolicy::Propagate, NanPolicy::Local] {
                let Ok(f) = LineFilter::<f64>::new(&SplineFamily::Order(2), mode, 0.0, route)
                    .unwrap()
                    .with_nan_policy(policy)
                else {
                    continue; // Local needs the truncated route
                };
                let mut got = a.clone();
                spline_filter(&mut got, &f).unwrap();
                for (i, (&g, &s)) in got.iter().zip(&a).enumerate() {
                    assert!(
                        g.to_bits() == s.to_bits() || (g.is_nan() && s.is_nan()),
                        "{mode:?} {route:?} {policy:?}: element {i} is {g}, the sample {s}"
                    );
                }
            }
        }
    }
}
