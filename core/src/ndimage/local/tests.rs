//! The local route against the global route (an independent computation:
//! the exact recursive prefilter of the whole array, its padded
//! coefficients, its batch evaluation), within the stated bound; and the
//! same bits whatever the source layout or the tile size.

use super::*;
use crate::ndimage::interpolant::{Interpolant, Options};
use crate::ndimage::line_filter::{LineFilter, Route};
use crate::ndimage::mode::Mode;
use crate::ndimage::nd_prefilter::spline_filter;
use crate::ndimage::samples::SampleSource;
use crate::sspline::SplineFamily;
use ndarray::{Array2, ArrayD, Dimension, IxDyn};
use proptest::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A source that counts the samples it is asked for.
struct Counting<'a, T> {
    inner: ndarray::ArrayViewD<'a, T>,
    read: AtomicUsize,
}

impl<T: Real + Copy + 'static> SampleSource<T> for Counting<'_, T> {
    fn shape(&self) -> &[usize] {
        self.inner.shape()
    }
    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [T]) -> Result<(), NdimageError> {
        self.read.fetch_add(out.len(), Ordering::Relaxed);
        self.inner.read_box(lo, hi, out)
    }
}

/// The global route's value of scipy's call: the engine's interpolant, or
/// scipy's padded route (`np.pad` by `pad`, the filter rule, the
/// coefficients evaluated at `x + pad` as given ones).
fn global<T: Real + Copy + Send + Sync>(
    data: &ArrayD<T>,
    opts: LocalOptions,
    points: &Array2<f64>,
    rule: PointRule,
    deriv: &[u32],
) -> Result<Vec<T>, NdimageError> {
    let (prefilter, pad) = (opts.prefilter, opts.scipy_pad);
    let opts = opts.options;
    let padded = prefilter
        && opts.degree >= 2
        && pad > 0
        && matches!(opts.mode, Mode::Nearest | Mode::GridConstant);
    // The global route's exact coefficients (the local route's truncation
    // is what is measured against them).
    let base = Options {
        cval: opts.cval,
        ..Options::new(opts.degree, opts.mode)
    };
    let (f, shift) = if padded {
        let shape: Vec<usize> = data.shape().iter().map(|n| n + 2 * pad).collect();
        let mut p = ArrayD::from_shape_fn(IxDyn(&shape), |i| {
            let idx: Option<Vec<usize>> = i
                .slice()
                .iter()
                .zip(data.shape())
                .map(|(&j, &n)| opts.mode.fold(j as i64 - pad as i64, n))
                .collect();
            idx.map_or_else(
                || T::from_f64_exact(opts.cval),
                |k: Vec<usize>| data[IxDyn(&k)],
            )
        });
        let rule = if opts.mode == Mode::Nearest {
            Mode::Reflect
        } else {
            Mode::Mirror
        };
        let family = SplineFamily::Order(opts.degree + 1);
        let lf = LineFilter::<T>::new(&family, rule, 0.0, Route::Exact).unwrap();
        spline_filter(&mut p, &lf)?;
        (Interpolant::from_coefficients_with(&p, base)?, pad as f64)
    } else if prefilter {
        (Interpolant::new(data, base)?, 0.0)
    } else {
        (Interpolant::from_coefficients_with(data, base)?, 0.0)
    };
    let mut out = Vec::new();
    for row in points.rows() {
        let mut x = row.to_vec();
        if rule.apply(&mut x, data.shape()) {
            let zero = deriv.iter().any(|&d| d > 0);
            out.push(if zero {
                T::zero()
            } else {
                T::from_f64_exact(opts.cval)
            });
            continue;
        }
        let x: Vec<f64> = x.iter().map(|v| v + shift).collect();
        out.push(f.eval_derivative(&x, deriv)?);
    }
    Ok(out)
}

/// The allowed difference: the truncation's `((A + b)^D − A^D) max|s|`
/// plus the rounding of both routes, `32 (n + 8) u A^D max|s|`.
fn allowed<T: Real>(spec: &LocalSpec<T>, max: f64, deriv: &[u32]) -> f64 {
    let (a, b, d) = (spec.amplification(), spec.bound(), spec.ndim() as i32);
    let u = (-(T::BITS as f64)).exp2();
    let n = spec.half_width() as f64;
    // A derivative's weights sum to at most 2^k in magnitude.
    let k: u32 = deriv.iter().sum();
    let scale = 2f64.powi(k as i32) * max.max(spec.cval.to_f64().abs());
    (((a + b).powi(d) - a.powi(d)) + 32.0 * (n + 8.0) * u * a.powi(d)) * scale
}

fn data_of<T: Real>(shape: &[usize], seed: u64) -> ArrayD<T> {
    let mut s = seed | 1;
    ArrayD::from_shape_fn(IxDyn(shape), |_| {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        T::from_f64_exact(((s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) as f32 as f64)
    })
}

fn check_case<T: Real + Copy + Send + Sync>(
    shape: &[usize],
    opts: LocalOptions,
    coords: &[f64],
    rule: PointRule,
    deriv: &[u32],
    seed: u64,
) -> Result<(), TestCaseError> {
    let d = shape.len();
    let data = data_of::<T>(shape, seed);
    let k = coords.len() / d;
    let points = Array2::from_shape_vec((k, d), coords[..k * d].to_vec()).unwrap();
    let spec = LocalSpec::<T>::new(shape, opts).unwrap();
    let plan = LocalPlan::new(&spec, points.view(), rule, None).unwrap();
    let mut local = vec![T::zero(); k];
    let dv = Some(deriv);
    let got = plan.evaluate(&spec, &data, dv, &mut local);
    let want = match global(&data, opts, &points, rule, deriv) {
        // Data the filter could overflow: refused by both routes (the
        // local one where a tile reads such data).
        Err(NdimageError::Overflow { .. }) => {
            let refused = matches!(got, Err(NdimageError::Overflow { .. }) | Ok(_));
            prop_assert!(refused, "{:?}", got);
            return Ok(());
        }
        other => other.unwrap(),
    };
    got.unwrap();
    let max = data.iter().fold(0.0f64, |m, x| m.max(x.to_f64().abs()));
    let tol = allowed(&spec, max, deriv);
    let exact = spec.filter.is_none();
    for (p, (l, g)) in local.iter().zip(&want).enumerate() {
        let (l, g) = (l.to_f64(), g.to_f64());
        if exact {
            prop_assert_eq!(
                l.to_bits(),
                g.to_bits(),
                "point {} {:?}: {} vs {}",
                p,
                points.row(p),
                l,
                g
            );
        } else {
            prop_assert!(
                (l - g).abs() <= tol,
                "point {} {:?}: local {} global {} diff {:e} > {:e} ({:?}, {} bits)",
                p,
                points.row(p),
                l,
                g,
                (l - g).abs(),
                tol,
                opts,
                T::BITS
            );
        }
    }
    // The same bits from a strided view and from other tile sizes.
    let fortran = data.t().as_standard_layout().into_owned();
    let view = fortran.t();
    for tile in [Some(1), Some(8)] {
        let other = LocalPlan::new(&spec, points.view(), rule, tile).unwrap();
        let mut again = vec![T::zero(); k];
        other.evaluate(&spec, &view, dv, &mut again).unwrap();
        for (a, b) in local.iter().zip(&again) {
            prop_assert_eq!(a.to_f64().to_bits(), b.to_f64().to_bits());
        }
    }
    Ok(())
}

fn modes() -> impl Strategy<Value = (Mode, usize, PointRule)> {
    prop_oneof![
        prop::sample::select(Mode::ALL.to_vec()).prop_map(|m| (m, 0, PointRule::Fold)),
        prop::sample::select(vec![Mode::Nearest, Mode::GridConstant]).prop_map(|m| (
            m,
            12,
            PointRule::Fold
        )),
        Just((Mode::Mirror, 0, PointRule::CvalOutside)),
        Just((Mode::Mirror, 0, PointRule::WrapPeriodNMinus1)),
    ]
}

/// Shape, degree, (mode, pad, rule), prefilter, coordinates, derivative orders, seed.
type Case = (
    Vec<usize>,
    u32,
    (Mode, usize, PointRule),
    bool,
    Vec<f64>,
    Vec<u32>,
    u64,
);

fn case() -> impl Strategy<Value = Case> {
    (1usize..=3, prop_oneof![2u32..=9, Just(15u32), 0u32..=1])
        .prop_flat_map(|(d, degree)| {
            // Degree 15's half-width (hundreds of samples) makes 3-D tiles
            // of tiny arrays huge; 1-D and 2-D cover its folding.
            let d = if degree == 15 { d.min(2) } else { d };
            (prop::collection::vec(1usize..=14, d..=d), Just(degree))
        })
        .prop_flat_map(|(shape, degree)| {
            (
                Just(shape),
                Just(degree),
                modes(),
                prop::bool::weighted(0.85),
                prop::collection::vec(-20.0f64..34.0, 24),
                prop::collection::vec(0u32..=2, 3),
                any::<u64>(),
            )
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(160))]

    /// Every mode (scipy's padded nearest / grid-constant, constant and
    /// wrap included), degrees 0–9 and 15, 1–3-D arrays of 1 to 14 samples
    /// per axis, points inside, at and beyond the edges, derivatives:
    /// within the bound of the global route in f64 and f32 (bit for bit
    /// without a prefilter); the same bits from a strided source and from
    /// tiles of 1 and 8 cells.
    #[test]
    fn local_route_agrees_with_the_global_route(
        (shape, degree, (mode, pad, rule), prefilter, coords, deriv, seed) in case(),
        cval in -2.0f64..2.0,
    ) {
        let d = shape.len();
        let deriv: Vec<u32> = deriv[..d].iter().map(|&k| k.min(degree)).collect();
        let deriv = if rule == PointRule::Fold { deriv } else { vec![0; d] };
        let mut opts = LocalOptions { prefilter, scipy_pad: pad, ..LocalOptions::new(degree, mode) };
        opts.options.cval = cval;
        check_case::<f64>(&shape, opts, &coords, rule, &deriv, seed)?;
        check_case::<f32>(&shape, opts, &coords, rule, &deriv, seed)?;
    }

    /// A source that counts what it is asked for is read only in the
    /// windows: at most, per point, the `(t + d + 2n)^D` samples of its
    /// tile's box, and for degrees 0 and 1 its support.
    #[test]
    fn only_the_windows_are_read(
        degree in 0u32..=5,
        mode in prop::sample::select(Mode::ALL.to_vec()),
        coords in prop::collection::vec(0.0f64..399.0, 1..=6),
    ) {
        let data = data_of::<f64>(&[400, 400], 7);
        let src = Counting { inner: data.view(), read: AtomicUsize::new(0) };
        let k = coords.len() / 2;
        prop_assume!(k > 0);
        let points = Array2::from_shape_vec((k, 2), coords[..2 * k].to_vec()).unwrap();
        let spec = LocalSpec::<f64>::new(&[400, 400], LocalOptions::new(degree, mode)).unwrap();
        let plan = LocalPlan::new(&spec, points.view(), PointRule::Fold, Some(1)).unwrap();
        let mut out = vec![0.0; k];
        let stats = plan.evaluate(&spec, &src, None, &mut out).unwrap();
        let read = src.read.load(Ordering::Relaxed);
        let side = degree as usize + 1 + 2 * spec.half_width();
        prop_assert_eq!(read, stats.samples_read);
        prop_assert!(read <= k * side * side, "{} > {}", read, k * side * side);
    }
}

/// A missing sample reaches only the points whose windows read it, under
/// every policy's arithmetic; `raise` names it only when it is read.
#[test]
fn a_missing_sample_reaches_only_the_windows_that_read_it() {
    let mut data = data_of::<f64>(&[300, 300], 3);
    data[[150, 150]] = f64::NAN;
    let spec = LocalSpec::<f64>::new(&[300, 300], LocalOptions::new(3, Mode::Mirror)).unwrap();
    let reach = (spec.half_width() + 2) as f64;
    let points = Array2::from_shape_vec(
        (3, 2),
        vec![150.3, 150.0, 150.0 + reach + 1.0, 150.0, 20.0, 20.0],
    )
    .unwrap();
    let plan = LocalPlan::new(&spec, points.view(), PointRule::Fold, None).unwrap();
    let mut out = vec![0.0; 3];
    plan.evaluate(&spec, &data, None, &mut out).unwrap();
    assert!(
        out[0].is_nan() && out[1].is_finite() && out[2].is_finite(),
        "{out:?}"
    );
    let mut opts = LocalOptions::new(3, Mode::Mirror);
    opts.options.nan_policy = crate::ndimage::nan_policy::NanPolicy::Raise;
    let spec = LocalSpec::<f64>::new(&[300, 300], opts).unwrap();
    let far = Array2::from_shape_vec((1, 2), vec![20.0, 20.0]).unwrap();
    let plan = LocalPlan::new(&spec, far.view(), PointRule::Fold, None).unwrap();
    assert!(plan.evaluate(&spec, &data, None, &mut out[..1]).is_ok());
    let plan = LocalPlan::new(&spec, points.view(), PointRule::Fold, None).unwrap();
    match plan.evaluate(&spec, &data, None, &mut out) {
        Err(NdimageError::NonFinite { index, .. }) => assert_eq!(index, 150 * 300 + 150),
        other => panic!("{other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// After a random sequence of updates (single samples and boxes,
    /// repeated indices, non-finite values), evaluations with the tiles
    /// cached before the updates equal a fresh interpolant of the changed
    /// samples bit for bit; the caller's array is not written; a small
    /// cache (one tile) gives the same bits.
    #[test]
    fn updates_agree_with_a_rebuild(
        degree in prop_oneof![2u32..=5, Just(9u32), 0u32..=1],
        mode in prop::sample::select(Mode::ALL.to_vec()),
        steps in prop::collection::vec((0usize..40, 0usize..36, 1usize..4, -3.0f64..3.0), 1..6),
        seed in any::<u64>(),
        coords in prop::collection::vec(-3.0f64..42.0, 40),
    ) {
        let shape = [40usize, 36];
        let data = data_of::<f64>(&shape, seed);
        let points = Array2::from_shape_vec((20, 2), coords).unwrap();
        let opts = LocalOptions::new(degree, mode);
        let mut f = LocalInterpolant::<f64>::new(&shape, opts, 1 << 24).unwrap();
        let mut out = vec![0.0; 20];
        f.eval_many(&data, points.view(), PointRule::Fold, None, &mut out).unwrap();
        let mut changed = data.clone();
        for (i, j, w, v) in steps {
            let mut idx = Vec::new();
            let mut vals = Vec::new();
            for a in i..(i + w).min(40) {
                for b in j..(j + w).min(36) {
                    idx.extend([a, b]);
                    let value = if v > 2.9 { f64::NAN } else { v * (a + b) as f64 };
                    vals.push(value);
                    changed[[a, b]] = value;
                }
            }
            f.update(&data, &idx, &vals).unwrap();
            let fresh = LocalInterpolant::<f64>::new(&shape, opts, 1 << 24).unwrap();
            let one_tile = (32 + degree as usize).pow(2) * 8;
            let tiny = LocalInterpolant::<f64>::new(&shape, opts, one_tile).unwrap();
            let (mut got, mut want, mut small) = (vec![0.0; 20], vec![0.0; 20], vec![0.0; 20]);
            f.eval_many(&data, points.view(), PointRule::Fold, None, &mut got).unwrap();
            fresh.eval_many(&changed, points.view(), PointRule::Fold, None, &mut want).unwrap();
            tiny.eval_many(&changed, points.view(), PointRule::Fold, None, &mut small).unwrap();
            for ((g, w), s) in got.iter().zip(&want).zip(&small) {
                prop_assert_eq!(g.to_bits(), w.to_bits());
                prop_assert_eq!(s.to_bits(), w.to_bits());
            }
        }
        prop_assert!(data.iter().zip(data_of::<f64>(&shape, seed).iter()).all(|(a, b)| a.to_bits() == b.to_bits()));
    }
}

/// Updates refused change nothing: an index outside, a NaN under `raise`.
#[test]
fn refused_updates_change_nothing() {
    let data = data_of::<f64>(&[30, 30], 9);
    let mut opts = LocalOptions::new(3, Mode::Mirror);
    opts.options.nan_policy = crate::ndimage::nan_policy::NanPolicy::Raise;
    let mut f = LocalInterpolant::<f64>::new(&[30, 30], opts, 1 << 24).unwrap();
    let at = Array2::from_shape_vec((1, 2), vec![5.5, 6.5]).unwrap();
    let mut before = [0.0];
    f.eval_many(&data, at.view(), PointRule::Fold, None, &mut before)
        .unwrap();
    let e = f.update(&data, &[5, 6, 30, 0], &[1.0, 2.0]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "index 30 is out of bounds for axis 0 with size 30"
    );
    let e = f
        .update(&data, &[5, 6, 7, 7], &[1.0, f64::NAN])
        .unwrap_err();
    assert_eq!(e.to_string(), "sample 217 is not finite (nan)");
    let mut after = [0.0];
    f.eval_many(&data, at.view(), PointRule::Fold, None, &mut after)
        .unwrap();
    assert_eq!(before[0].to_bits(), after[0].to_bits());
    assert!(!f.is_changed());
    match LocalInterpolant::<f64>::new(&[30, 30], opts, 100) {
        Err(NdimageError::CacheTooSmall { smallest, .. }) => assert_eq!(smallest, 35 * 35 * 8),
        other => panic!("{:?}", other.map(|_| ())),
    }
}

/// A source whose reads of more than `limit` samples fail (the boxes an
/// update's recomputation reads, not the changed samples' blocks).
struct SmallReadsOnly<'a> {
    inner: ndarray::ArrayViewD<'a, f64>,
    limit: usize,
}

impl SampleSource<f64> for SmallReadsOnly<'_> {
    fn shape(&self) -> &[usize] {
        self.inner.shape()
    }
    fn read_box(&self, lo: &[usize], hi: &[usize], out: &mut [f64]) -> Result<(), NdimageError> {
        if out.len() > self.limit {
            return Err(NdimageError::NotFetched {
                lo: lo.to_vec(),
                hi: hi.to_vec(),
            });
        }
        self.inner.read_box(lo, hi, out)
    }
}

/// An update whose recomputation fails to read takes its changes back
/// (in place, a repeated index included) and keeps the earlier updates:
/// the values equal a rebuild of the samples as they were.
#[test]
fn an_update_that_fails_to_read_changes_nothing() {
    let data = data_of::<f64>(&[40, 40], 5);
    let opts = LocalOptions::new(3, Mode::Mirror);
    let mut f = LocalInterpolant::<f64>::new(&[40, 40], opts, 1 << 24).unwrap();
    let at = Array2::from_shape_vec((2, 2), vec![5.5, 6.5, 30.25, 12.0]).unwrap();
    let mut out = [0.0; 2];
    f.eval_many(&data, at.view(), PointRule::Fold, None, &mut out)
        .unwrap();
    f.update(&data, &[5, 7], &[3.0]).unwrap();
    let failing = SmallReadsOnly {
        inner: data.view(),
        limit: 256,
    };
    let e = f.update(&failing, &[5, 6, 5, 7, 5, 6], &[1.0, 4.0, 2.0]);
    assert!(matches!(e, Err(NdimageError::NotFetched { .. })));
    let mut changed = data.clone();
    changed[[5, 7]] = 3.0;
    let fresh = LocalInterpolant::<f64>::new(&[40, 40], opts, 1 << 24).unwrap();
    let (mut got, mut want) = ([0.0; 2], [0.0; 2]);
    f.eval_many(&data, at.view(), PointRule::Fold, None, &mut got)
        .unwrap();
    fresh
        .eval_many(&changed, at.view(), PointRule::Fold, None, &mut want)
        .unwrap();
    assert_eq!(got.map(f64::to_bits), want.map(f64::to_bits));
    assert_ne!(got[0].to_bits(), out[0].to_bits());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// `new_if_local` takes the route `new(.., None).cost().prefer_local()`
    /// takes, on arrays where either route wins (from a few points on a
    /// large array to many points on a small one), its plan the same.
    #[test]
    fn new_if_local_decides_as_the_priced_plan(
        (shape, degree, (mode, pad, rule), prefilter, _, _, seed) in case(),
        scale in prop::sample::select(vec![1usize, 20, 200]),
        k in prop_oneof![0usize..=4, 100usize..=3000],
    ) {
        let shape: Vec<usize> = shape.iter().map(|&n| n * scale).collect();
        let opts = LocalOptions { prefilter, scipy_pad: pad, ..LocalOptions::new(degree, mode) };
        let spec = LocalSpec::<f64>::new(&shape, opts).unwrap();
        let d = shape.len();
        let mut state = seed | 1;
        let coords: Vec<f64> = (0..k * d)
            .map(|i| {
                state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                let u = (state >> 11) as f64 / (1u64 << 53) as f64;
                u * (shape[i % d] as f64 + 6.0) - 3.0
            })
            .collect();
        let points = Array2::from_shape_vec((k, d), coords).unwrap();
        let priced = LocalPlan::new(&spec, points.view(), rule, None).unwrap();
        let chosen = LocalPlan::new_if_local(&spec, points.view(), rule).unwrap();
        prop_assert_eq!(chosen.is_some(), priced.cost().prefer_local(), "{:?}", priced.cost());
        if let Some(plan) = chosen {
            prop_assert_eq!(plan.cost(), priced.cost());
            prop_assert_eq!(plan.groups.len(), priced.groups.len());
        }
    }
}
