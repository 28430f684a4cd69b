//! Splines of degree 0 and 1 evaluated where the samples lie
//! ([`map_samples_in_place`]): their coefficients are the samples, so no
//! padded copy is needed; each point reads its `(d + 1)^ndim` samples from
//! the input itself, every index beyond an edge folded by the mode as it
//! is read.
//!
//! Why: the [`Interpolant`](super::Interpolant) of degree 0 or 1 copies the
//! whole input into a padded array (and scans it for non-finite values)
//! before it evaluates one point. For a few points on a small array that
//! copy is the call: 25 points on 32³ spent ~30 µs copying 256 KiB where
//! scipy's whole call takes 3.6 µs (issue 50, `python/bench/small_calls.py`).
//! scipy itself reads the input in place (`ni_interpolation.c`).
//!
//! **Same values as the padded route, bit for bit**: element `j` of the
//! padded array is sample [`Mode::fold`]`(j − pad)` (`cval` where the fold
//! gives none), the point is folded as [`Interpolant`](super::Interpolant)
//! folds it ([`Mode::nearest_index`] for degree 0,
//! [`Mode::fold_coordinate`] for degree 1), the weights are
//! [`cell_weights_into`]'s and the products are added in the padded
//! route's nested order from zero
//! (`in_place.rs::tests::equals_the_padded_route_bit_for_bit`).

use super::batch::{check_points, name_non_finite, store_chunks};
use super::{PointRule, cell_weights_into};
use crate::ndimage::NdimageError;
use crate::ndimage::alloc::try_standard_layout;
use crate::ndimage::mode::Mode;
use crate::ndimage::nan_policy::NanPolicy;
use crate::ndimage::nd_prefilter::check_finite;
use crate::ndimage::samples::{Sample, Stored};
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;
use ndarray::{ArrayView2, ArrayViewD, Axis, s};

/// The spline degrees whose coefficients are the samples themselves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleOrder {
    /// Degree 0: the nearest sample.
    Nearest,
    /// Degree 1: multilinear interpolation.
    Linear,
}

impl SampleOrder {
    /// The order of `degree`, for degrees 0 and 1 (`None` above: those
    /// splines need a prefilter or given coefficients).
    pub fn of_degree(degree: u32) -> Option<Self> {
        match degree {
            0 => Some(SampleOrder::Nearest),
            1 => Some(SampleOrder::Linear),
            _ => None,
        }
    }

    /// Samples read per point and axis (the B-spline order).
    fn taps(self) -> usize {
        match self {
            SampleOrder::Nearest => 1,
            SampleOrder::Linear => 2,
        }
    }
}

/// How [`map_samples_in_place`] reads and folds: the spline's order and
/// boundary, and what takes the place of a sample outside the grid.
#[derive(Debug, Clone, Copy)]
pub struct InPlaceOptions {
    /// Degree 0 or 1.
    pub order: SampleOrder,
    /// How the samples extend beyond each edge.
    pub mode: Mode,
    /// The value beyond the edges under `grid-constant`, and at points the
    /// [`PointRule`] sends to it.
    pub cval: f64,
    /// `Propagate`: samples read as they are; `Raise`: refused when one is
    /// not finite (the whole input scanned, as the padded route scans it);
    /// `Local`: a non-finite sample read as NaN (±∞ would weigh in at full
    /// weight). A non-finite `cval` is taken as it is, where the padded
    /// route makes it NaN within its pad: callers with one under `Local`
    /// take the padded route.
    pub nan_policy: NanPolicy,
}

/// The values at the rows of `points` (`(count, ndim)`, any strides) of the
/// degree-0 or degree-1 spline of `data` under `opts`, each point first
/// passed through `rule`, into `out` (one per row, [`Stored`]: rounded
/// once from `T`).
///
/// **Formula**: `f(x) = Σ_i s_{fold(i)} Π_a β_m(x_a − i_a)` with `β_1` the
/// box (the nearest sample, ties as [`Mode::nearest_index`] breaks them)
/// and `β_2` the hat (`(1 − u) s_i + u s_{i+1}`), `s` extended beyond the
/// grid by [`Mode::fold`] (`cval` for `grid-constant`); scipy's
/// `map_coordinates(order=0 or 1)`. **Source**: the B-splines of orders 1
/// and 2 (seed 000, eq. 31). **Cost**: `(d + 1)^ndim` reads and
/// multiply-adds per point and nothing proportional to the input's size
/// (a non-contiguous input is copied once into C order first; `Raise`
/// scans the input once). **Error**: the products and sums of the padded
/// route in its order, so the same rounding: within 1 ulp of `max |s|` per
/// multiply-add; exact at degree 0.
///
/// A non-finite coordinate is [`NdimageError::NonFiniteCoordinate`] (the
/// first one's row-major flat index). In parallel over chunks of 2048
/// points on the current rayon pool, as
/// [`Interpolant::eval_many`](super::Interpolant::eval_many).
///
/// ```
/// use splinelab::prelude::*;
/// use splinelab::ndimage::interpolant::{InPlaceOptions, PointRule, SampleOrder, map_samples_in_place};
/// let data = ndarray::array![[0.0, 1.0], [2.0, 4.0]].into_dyn();
/// let at = ndarray::array![[0.5, 0.5], [1.0, 3.0]];
/// let opts = InPlaceOptions { order: SampleOrder::Linear, mode: Mode::Mirror, cval: 0.0, nan_policy: NanPolicy::Propagate };
/// let mut out = [0.0f64; 2];
/// map_samples_in_place::<f64, _, _>(&data.view(), at.view(), &opts, PointRule::Fold, &mut out).unwrap();
/// // (0 + 1 + 2 + 4) / 4, and column 3 mirrored onto column 1.
/// assert_eq!(out, [1.75, 4.0]);
/// ```
pub fn map_samples_in_place<T, E, O>(
    data: &ArrayViewD<'_, E>,
    points: ArrayView2<'_, f64>,
    opts: &InPlaceOptions,
    rule: PointRule,
    out: &mut [O],
) -> Result<(), NdimageError>
where
    T: Real + Send + Sync,
    E: Sample<T>,
    O: Stored<T>,
{
    check_points(points, data.ndim(), out.len())?;
    if data.is_empty() {
        return Err(NdimageError::Empty);
    }
    if opts.nan_policy == NanPolicy::Raise {
        check_finite::<T, _, _, _>(data)?;
    }
    let data = try_standard_layout(data, "a C-ordered copy of the input")?;
    let src = data.as_slice().ok_or(NdimageError::BufferLength {
        expected: data.len(),
        got: 0,
    })?;
    let reader = Reader::new(src, data.shape(), opts);
    let rule = (rule, data.shape());
    store_chunks(out, |start, values| {
        let rows = points.slice(s![start..start + values.len(), ..]);
        reader.eval_rows(rows, rule, values)
    })
    .map_err(|e| name_non_finite(e, points))
}

/// One sample a point reads along one axis: its offset in the C-ordered
/// input along that axis (index × stride), or `None` where the mode gives
/// `cval`.
#[derive(Debug, Clone, Copy, Default)]
struct Tap(Option<usize>);

/// The input as read: its samples in C order, shape, strides and options.
struct Reader<'a, E> {
    src: &'a [E],
    shape: &'a [usize],
    strides: Vec<usize>,
    order: SampleOrder,
    mode: Mode,
    cval: f64,
    /// A non-finite sample read as NaN ([`NanPolicy::Local`]).
    missing_as_nan: bool,
}

impl<'a, E> Reader<'a, E> {
    /// The values at `rows` (points `(count, ndim)`, each first passed
    /// through the rule on the grid of the given shape) into `out`, one
    /// work space for all.
    fn eval_rows<T: Real>(
        &self,
        rows: ArrayView2<'_, f64>,
        (rule, shape): (PointRule, &[usize]),
        out: &mut [T],
    ) -> Result<(), NdimageError>
    where
        E: Sample<T>,
    {
        let ndim = shape.len();
        let mut x = vec![0.0; ndim];
        let mut taps = vec![Tap::default(); ndim * self.order.taps()];
        let mut w = vec![T::zero(); taps.len()];
        // By columns: map_coordinates' points are the transpose of a
        // C-order `(ndim, count)` array, whose columns are contiguous.
        let views: Vec<_> = (0..ndim)
            .map(|a| rows.index_axis_move(Axis(1), a))
            .collect();
        let copies: Vec<Option<Vec<f64>>> = views
            .iter()
            .map(|v| v.to_slice().is_none().then(|| v.to_vec()))
            .collect();
        let columns: Vec<&[f64]> = views
            .iter()
            .zip(&copies)
            .map(|(v, c)| c.as_deref().or(v.to_slice()).unwrap_or_default())
            .collect();
        let mut general = |j: usize| -> Result<T, NdimageError> {
            for (xa, col) in x.iter_mut().zip(&columns) {
                let p = col[j];
                if !p.is_finite() {
                    return Err(NdimageError::NonFiniteCoordinate(0));
                }
                *xa = p;
            }
            Ok(if rule.apply(&mut x, shape) {
                T::from_f64_exact(self.cval)
            } else if self.locate(&x, &mut taps, &mut w) {
                match self.sum_inside(&taps, &w) {
                    Some(v) => v,
                    None => self.sum(&taps, &w, 0, 0, true),
                }
            } else {
                self.sum(&taps, &w, 0, 0, true)
            })
        };
        match ndim {
            1 => self.eval_fixed::<1, T>(&columns, out, general),
            2 => self.eval_fixed::<2, T>(&columns, out, general),
            3 => self.eval_fixed::<3, T>(&columns, out, general),
            _ => out
                .iter_mut()
                .enumerate()
                .try_for_each(|(j, o)| general(j).map(|v| *o = v)),
        }
    }

    /// Whether point `j` lies where [`Self::eval_fixed`] evaluates it: on
    /// every axis inside `[0, n − 1]` (degree 0) or `[0, n − 1)` (degree 1),
    /// where no point rule or mode moves it and every tap has its sample
    /// (a NaN coordinate is not: the general loop refuses it).
    #[inline(always)]
    fn is_inside_point(&self, columns: &[&[f64]], j: usize) -> bool {
        columns.iter().zip(self.shape).all(|(col, &n)| {
            let (x, top) = (col[j], (n - 1) as f64);
            x >= 0.0 && (x < top || (x == top && self.order == SampleOrder::Nearest))
        })
    }

    /// The points of `D` axes: those that lie inside
    /// ([`Self::is_inside_point`]) with the axes known at compile time (the
    /// loops of [`Self::locate`] and [`Self::sum_inside`] unrolled: the same
    /// cells, weights and sums from zero in the same order, so the same
    /// bits), the others by `general`.
    fn eval_fixed<const D: usize, T: Real>(
        &self,
        columns: &[&[f64]],
        out: &mut [T],
        mut general: impl FnMut(usize) -> Result<T, NdimageError>,
    ) -> Result<(), NdimageError>
    where
        E: Sample<T>,
    {
        let mut stride = [0usize; D];
        stride.copy_from_slice(&self.strides[..D]);
        for (j, o) in out.iter_mut().enumerate() {
            if !self.is_inside_point(columns, j) {
                *o = general(j)?;
                continue;
            }
            let mut x = [0.0; D];
            for (xa, col) in x.iter_mut().zip(columns) {
                *xa = col[j];
            }
            *o = match self.order {
                SampleOrder::Nearest => {
                    // `Mode::nearest_index` of a point it does not move;
                    // the sums from zero of `sum_inside` (−0 becomes +0).
                    let at = (0..D).fold(0, |at, a| {
                        let t = x[a] as usize;
                        at + (t + usize::from(x[a] - t as f64 >= 0.5)) * stride[a]
                    });
                    T::zero() + self.read(at)
                }
                SampleOrder::Linear => self.linear_inside::<D, T>(&x, &stride),
            };
        }
        Ok(())
    }

    /// Degree 1 at a point inside `[0, n − 1)` on every axis: the cell
    /// `⌊x⌋` and its weights per axis, the products summed from zero from
    /// the first axis in ([`Self::sum_inside`]'s order).
    #[inline(always)]
    fn linear_inside<const D: usize, T: Real>(&self, x: &[f64; D], stride: &[usize; D]) -> T
    where
        E: Sample<T>,
    {
        let mut base = [0usize; D];
        let mut w: [[T; 2]; D] = std::array::from_fn(|_| [T::zero(), T::zero()]);
        for a in 0..D {
            let t = x[a] as usize;
            cell_weights_into(2, 0, x[a] - t as f64, &mut w[a]);
            base[a] = t * stride[a];
        }
        let dot = |at: usize| {
            let mut sum = T::zero();
            for (l, wl) in w[D - 1].iter().enumerate() {
                sum += wl.clone() * self.read(at + base[D - 1] + l * stride[D - 1]);
            }
            sum
        };
        match D {
            1 => dot(0),
            2 => {
                let mut sum = T::zero();
                for (l, w0) in w[0].iter().enumerate() {
                    sum += w0.clone() * dot(base[0] + l * stride[0]);
                }
                sum
            }
            _ => {
                let mut sum = T::zero();
                for (l0, w0) in w[0].iter().enumerate() {
                    let mut plane = T::zero();
                    for (l1, w1) in w[1].iter().enumerate() {
                        plane +=
                            w1.clone() * dot(base[0] + l0 * stride[0] + base[1] + l1 * stride[1]);
                    }
                    sum += w0.clone() * plane;
                }
                sum
            }
        }
    }

    fn new(src: &'a [E], shape: &'a [usize], opts: &InPlaceOptions) -> Self {
        let mut strides = vec![1; shape.len()];
        for a in (0..shape.len().saturating_sub(1)).rev() {
            strides[a] = strides[a + 1] * shape[a + 1];
        }
        Reader {
            src,
            shape,
            strides,
            order: opts.order,
            mode: opts.mode,
            cval: opts.cval,
            missing_as_nan: opts.nan_policy == NanPolicy::Local,
        }
    }

    /// The samples of point `x` (folded as the padded route folds it) and
    /// their weights, `taps()` per axis; whether every tap has a sample.
    /// Inside `[0, n − 1]` every mode leaves the point where it is, so
    /// there the cell is `x`'s integer part (no libm `floor`, not inlined
    /// on the x86-64 baseline) and no index is folded.
    #[inline(always)]
    fn locate<T: Real>(&self, x: &[f64], taps: &mut [Tap], w: &mut [T]) -> bool {
        let m = self.order.taps();
        let mut all = true;
        for (a, (&xa, &n)) in x.iter().zip(self.shape).enumerate() {
            let stride = self.strides[a];
            let top = (n - 1) as f64;
            if m == 1 {
                let k = if (0.0..=top).contains(&xa) {
                    // `Mode::nearest_index` of a point it does not move.
                    let t = xa as usize;
                    Some(t + usize::from(xa - t as f64 >= 0.5))
                } else {
                    self.mode.nearest_index(xa, n)
                };
                all &= k.is_some();
                taps[a] = Tap(k.map(|k| k * stride));
                w[a] = T::one();
                continue;
            }
            let (taps, w) = (&mut taps[a * 2..a * 2 + 2], &mut w[a * 2..a * 2 + 2]);
            if xa >= 0.0 && xa < top {
                // `centred_cell(2, x)`: the cell `⌊x⌋`, `u = x − ⌊x⌋`.
                let t = xa as usize;
                cell_weights_into(2, 0, xa - t as f64, w);
                taps[0] = Tap(Some(t * stride));
                taps[1] = Tap(Some((t + 1) * stride));
                continue;
            }
            let (first, u) = centred_cell(2, self.mode.fold_coordinate(xa, n));
            cell_weights_into(2, 0, u, w);
            for (l, t) in taps.iter_mut().enumerate() {
                *t = Tap(self.mode.fold(first + l as i64, n).map(|k| k * stride));
                all &= t.0.is_some();
            }
        }
        all
    }

    /// [`Self::sum`] where every tap has a sample, for 1 to 3 axes: plain
    /// nested loops, the same products added in the same order from zero.
    #[inline(always)]
    fn sum_inside<T: Real>(&self, taps: &[Tap], w: &[T]) -> Option<T>
    where
        E: Sample<T>,
    {
        let m = self.order.taps();
        // Axis a's taps (offsets) and weights.
        let axis = |a: usize| {
            let r = a * m..(a + 1) * m;
            taps[r.clone()].iter().map(|t| t.0.unwrap_or(0)).zip(&w[r])
        };
        let dot = |base: usize, a: usize| {
            let mut sum = T::zero();
            for (at, wl) in axis(a) {
                sum += wl.clone() * self.read(base + at);
            }
            sum
        };
        Some(match self.shape.len() {
            1 => dot(0, 0),
            2 => {
                let mut sum = T::zero();
                for (at0, w0) in axis(0) {
                    sum += w0.clone() * dot(at0, 1);
                }
                sum
            }
            3 => {
                let mut sum = T::zero();
                for (at0, w0) in axis(0) {
                    let mut plane = T::zero();
                    for (at1, w1) in axis(1) {
                        plane += w1.clone() * dot(at0 + at1, 2);
                    }
                    sum += w0.clone() * plane;
                }
                sum
            }
            _ => return None,
        })
    }

    /// Sample `at` (C-order offset) under the NaN policy.
    fn read<T: Real>(&self, at: usize) -> T
    where
        E: Sample<T>,
    {
        let v = self.src[at].widen();
        if self.missing_as_nan && !v.is_finite() {
            T::from_f64_exact(f64::NAN)
        } else {
            v
        }
    }

    /// `Σ_l w_a[l] · (axis a+1's sum at base + tap)`, nested from the first
    /// axis, each sum from zero: the padded route's `accumulate`, whose
    /// `inside` is here a tap with no sample (`cval` below it).
    fn sum<T: Real>(&self, taps: &[Tap], w: &[T], axis: usize, base: usize, inside: bool) -> T
    where
        E: Sample<T>,
    {
        let m = self.order.taps();
        let last = axis + 1 == self.shape.len();
        let mut sum = T::zero();
        for l in axis * m..(axis + 1) * m {
            let Tap(at) = taps[l];
            let ok = inside && at.is_some();
            let at = base + at.unwrap_or(0);
            let v = if !last {
                self.sum(taps, w, axis + 1, at, ok)
            } else if ok {
                self.read(at)
            } else {
                T::from_f64_exact(self.cval)
            };
            sum += w[l].clone() * v;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ndimage::interpolant::Interpolant;
    use crate::ndimage::interpolant::tests::samples;
    use crate::prelude::Options;
    use ndarray::Array2;

    /// Points inside, at the edges, just and far outside, and at half
    /// samples (degree 0's ties), deterministic.
    fn points(shape: &[usize], count: usize) -> Array2<f64> {
        Array2::from_shape_fn((count, shape.len()), |(k, a)| {
            let n = shape[a] as f64;
            let t = ((k * 7919 + a * 104_729) % 1000) as f64 / 1000.0;
            match k % 5 {
                0 => (k % 3) as f64 * (n - 1.0) / 2.0 + 0.5 * (k % 2) as f64,
                1 => -2.5 * n + 6.0 * n * t,
                _ => (n + 1.0) * t - 1.0,
            }
        })
    }

    /// Every mode and point rule, degrees 0 and 1, 1-D to 4-D (with axes
    /// of one sample), against the padded route's [`Interpolant`]: the
    /// same bits.
    #[test]
    fn equals_the_padded_route_bit_for_bit() {
        let modes = [
            Mode::Mirror,
            Mode::Reflect,
            Mode::GridWrap,
            Mode::Nearest,
            Mode::GridConstant,
        ];
        let rules = [
            PointRule::Fold,
            PointRule::CvalOutside,
            PointRule::WrapPeriodNMinus1,
        ];
        for shape in [
            &[9usize][..],
            &[1],
            &[6, 5],
            &[1, 4],
            &[4, 3, 5],
            &[2, 3, 1, 4],
        ] {
            let a = samples(shape);
            let at = points(shape, 400);
            for mode in modes {
                for degree in [0, 1] {
                    for rule in rules {
                        let opts = Options {
                            cval: -0.75,
                            ..Options::new(degree, mode)
                        };
                        let f = Interpolant::<f64>::new(&a, opts).unwrap();
                        let mut want = vec![0.0; at.nrows()];
                        f.eval_many_with(at.view(), rule, &mut want).unwrap();
                        let in_place = InPlaceOptions {
                            order: SampleOrder::of_degree(degree).unwrap(),
                            mode,
                            cval: -0.75,
                            nan_policy: NanPolicy::Propagate,
                        };
                        let mut got = vec![0.0f64; at.nrows()];
                        map_samples_in_place::<f64, _, _>(
                            &a.view(),
                            at.view(),
                            &in_place,
                            rule,
                            &mut got,
                        )
                        .unwrap();
                        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                            assert_eq!(
                                g.to_bits(),
                                w.to_bits(),
                                "{shape:?} {mode} d={degree} {rule:?} point {k}: {g} vs {w}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// NaN and ±∞ among the samples under `propagate`, `local` (finite
    /// `cval`) and `raise`: the padded route's values bit for bit (NaN
    /// where it gives NaN), and its error under `raise`.
    #[test]
    fn missing_samples_as_the_padded_route() {
        let shape = [5usize, 6];
        let mut a = samples(&shape);
        a[[1, 2]] = f64::NAN;
        a[[4, 5]] = f64::INFINITY;
        a[[0, 0]] = f64::NEG_INFINITY;
        let at = points(&shape, 300);
        for policy in [NanPolicy::Propagate, NanPolicy::Local, NanPolicy::Raise] {
            for mode in [Mode::Mirror, Mode::GridConstant, Mode::Nearest] {
                for degree in [0, 1] {
                    let opts = Options {
                        cval: 2.5,
                        nan_policy: policy,
                        ..Options::new(degree, mode)
                    };
                    let want = Interpolant::<f64>::new(&a, opts).and_then(|f| {
                        let mut v = vec![0.0; at.nrows()];
                        f.eval_many(at.view(), &mut v).map(|_| v)
                    });
                    let in_place = InPlaceOptions {
                        order: SampleOrder::of_degree(degree).unwrap(),
                        mode,
                        cval: 2.5,
                        nan_policy: policy,
                    };
                    let mut v = vec![0.0f64; at.nrows()];
                    let got = map_samples_in_place::<f64, _, _>(
                        &a.view(),
                        at.view(),
                        &in_place,
                        PointRule::Fold,
                        &mut v,
                    )
                    .map(|_| v);
                    match (got, want) {
                        (Ok(g), Ok(w)) => {
                            let bits = |v: &[f64]| {
                                v.iter()
                                    .map(|x| if x.is_nan() { u64::MAX } else { x.to_bits() })
                                    .collect::<Vec<_>>()
                            };
                            assert_eq!(bits(&g), bits(&w), "{policy} {mode} d={degree}");
                        }
                        (Err(g), Err(w)) => assert_eq!(g.to_string(), w.to_string()),
                        (g, w) => panic!("{policy} {mode} d={degree}: {g:?} vs {w:?}"),
                    }
                }
            }
        }
    }

    proptest::proptest! {
        /// Points on half-integers, integers and the edges `0` and `n − 1`
        /// and a few ulps beside them (the ties, the interior fast paths'
        /// limits, `−0.0`), inside and far outside, 1 to 4 axes of 1 to 7
        /// samples, every mode and point rule, degrees 0 and 1: the padded
        /// route's bits.
        #[test]
        fn near_ties_and_edges_equal_the_padded_route(
            shape in proptest::collection::vec(1usize..8, 1..=4),
            mode in proptest::sample::select(Mode::ALL.to_vec()),
            rule in proptest::sample::select(vec![
                PointRule::Fold, PointRule::CvalOutside, PointRule::WrapPeriodNMinus1,
            ]),
            degree in 0u32..=1,
            ticks in proptest::collection::vec((-40i32..40, -3i32..=3), 4..200),
        ) {
            let a = samples(&shape);
            let nd = shape.len();
            let count = ticks.len() / nd;
            let at = Array2::from_shape_fn((count, nd), |(k, ax)| {
                let (half, ulps) = ticks[k * nd + ax];
                let n = shape[ax] as f64;
                // Half-integers around the grid, and its two edges.
                let x = match half {
                    -40 => -0.0,
                    39 => n - 1.0,
                    h => f64::from(h) / 2.0,
                };
                let mut x = x;
                for _ in 0..ulps.unsigned_abs() {
                    x = if ulps > 0 { x.next_up() } else { x.next_down() };
                }
                x
            });
            let opts = Options { cval: 0.375, ..Options::new(degree, mode) };
            let f = Interpolant::<f64>::new(&a, opts).unwrap();
            let mut want = vec![0.0; count];
            f.eval_many_with(at.view(), rule, &mut want).unwrap();
            let in_place = InPlaceOptions {
                order: SampleOrder::of_degree(degree).unwrap(),
                mode,
                cval: 0.375,
                nan_policy: NanPolicy::Propagate,
            };
            let mut got = vec![0.0f64; count];
            map_samples_in_place::<f64, _, _>(&a.view(), at.view(), &in_place, rule, &mut got).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            proptest::prop_assert_eq!(bits(&got), bits(&want));
        }
    }

    /// A non-finite coordinate is named by its row-major flat index.
    #[test]
    fn non_finite_coordinate_is_named() {
        let a = samples(&[4, 4]);
        let mut at = points(&[4, 4], 10);
        at[[7, 1]] = f64::NAN;
        let opts = InPlaceOptions {
            order: SampleOrder::Linear,
            mode: Mode::Reflect,
            cval: 0.0,
            nan_policy: NanPolicy::Propagate,
        };
        let mut out = vec![0.0f64; 10];
        let e = map_samples_in_place::<f64, _, _>(
            &a.view(),
            at.view(),
            &opts,
            PointRule::Fold,
            &mut out,
        );
        assert!(
            matches!(e, Err(NdimageError::NonFiniteCoordinate(15))),
            "{e:?}"
        );
    }
}
