//! The coefficients of one box of window indices, computed from the
//! samples within the certified half-width of it, and the values of the
//! points whose windows lie in the box.
//!
//! **Method.** For the box `lo_a .. lo_a + len_a` (each axis): the
//! coefficient indices it needs ([`AxisMap::coefficient`]), a contiguous
//! range `v_a`; the extended samples `v_a ± n` ([`AxisMap::sample`], `cval`
//! where the mode gives none) read from the source run by run
//! ([`gather`]); then the truncated convolution `D_k = c_0 s_k + Σ_{j=1}^n
//! c_j (s_{k−j} + s_{k+j})` along the last axis, then the one before, …,
//! the first ([`ConvolutionPrefilter::apply_extended`] on rows,
//! [`convolve_rows`] across them: the same operations per value).
//!
//! **Same bits whatever the box.** Each intermediate value — after the
//! passes along axes `D−1 .. a` — is the convolution of the same extended
//! samples in the same order, and depends only on its position: a
//! coefficient is the same number whichever box (tile, block, chunk)
//! computes it, and whichever source (in memory, memory-mapped, blocks
//! fetched from an array-like) gives the samples.
//!
//! **Non-finite samples.** [`NanPolicy::Propagate`]: carried by the
//! arithmetic (a NaN reaches the coefficients within `n` of it on every
//! axis, and the points whose windows read those); [`NanPolicy::Local`]:
//! the same with ±∞ read as NaN; [`NanPolicy::Raise`]: refused, naming the
//! first non-finite sample read. Only samples that some window reads are
//! seen: a missing sample elsewhere changes nothing.

use super::axis_map::AxisMap;
use super::gather::{for_each_index, gather, run_boxes, strides};
use super::spec::LocalSpec;
use crate::ndimage::NdimageError;
use crate::ndimage::interpolant::cell_weights_into;
use crate::ndimage::line_filter::convolve_rows;
use crate::ndimage::nan_policy::NanPolicy;
use crate::ndimage::samples::SampleSource;
use crate::scalar::Real;
use crate::sspline::bspline_uniform::centred_cell;
use crate::validation::NonFiniteValue;

/// The coefficients `D_k`, `k_a ∈ lo_a .. lo_a + len_a`, in C order.
#[derive(Debug, Clone)]
pub(crate) struct CoefBox<T> {
    pub(crate) lo: Vec<i64>,
    pub(crate) len: Vec<usize>,
    strides: Vec<usize>,
    pub(crate) data: Vec<T>,
    /// Samples read from the source (for the reports' counts).
    pub(crate) read: usize,
    /// Per axis the first and one past the last source index read (the
    /// box's reach, for updates).
    pub(crate) reach: Vec<(usize, usize)>,
}

/// Sorted distinct `Some` values and each entry's position among them.
fn positions(map: &[Option<usize>]) -> (Vec<usize>, Vec<Option<usize>>) {
    let mut list: Vec<usize> = map.iter().flatten().copied().collect();
    list.sort_unstable();
    list.dedup();
    let pos = map
        .iter()
        .map(|m| m.map(|i| list.binary_search(&i).expect("listed")))
        .collect();
    (list, pos)
}

/// Flat offsets along one axis: `pos[i] · stride`, `None` kept.
fn offsets(pos: &[Option<usize>], stride: usize) -> Vec<Option<usize>> {
    pos.iter().map(|p| p.map(|p| p * stride)).collect()
}

/// The array of `shape` whose element is `src[Σ off_a]` where every
/// axis' offset is `Some`, `cval` elsewhere.
fn spread_into<T: Real>(src: &[T], offs: &[Vec<Option<usize>>], cval: &T, out: &mut Vec<T>) {
    let shape: Vec<usize> = offs.iter().map(Vec::len).collect();
    out.clear();
    out.reserve(shape.iter().product());
    for_each_index(&shape, |_, idx| {
        let mut at = Some(0usize);
        for (a, &i) in idx.iter().enumerate() {
            at = at.zip(offs[a][i]).map(|(s, o)| s + o);
        }
        out.push(at.map_or_else(|| cval.clone(), |k| src[k].clone()));
    });
}

/// What a box of coefficients reads: per axis its coefficient indices
/// (`None`: `cval`), their range, the extended samples' source indices, the
/// sorted distinct ones and each extended sample's position among them.
struct Reads {
    cd: Vec<Vec<Option<i64>>>,
    ranges: Vec<(i64, i64)>,
    maps: Vec<Vec<Option<usize>>>,
    lists: Vec<Vec<usize>>,
    pos: Vec<Vec<Option<usize>>>,
}

impl<T: Real> LocalSpec<T> {
    /// What the box `lo .. lo + len` reads; `Err(cd)` where every
    /// coefficient of the box is the constant beyond the grid.
    fn reads(&self, lo: &[i64], len: &[usize]) -> Result<Reads, Vec<Vec<Option<i64>>>> {
        let n = self.half_width() as i64;
        // Coefficient indices of the box and their range per axis.
        let cd: Vec<Vec<Option<i64>>> = self
            .axes
            .iter()
            .zip(lo.iter().zip(len))
            .map(|(ax, (&l, &k))| (0..k as i64).map(|i| ax.coefficient(l + i)).collect())
            .collect();
        let ranges: Option<Vec<(i64, i64)>> = cd
            .iter()
            .map(|c| {
                let lo = c.iter().flatten().min()?;
                let hi = c.iter().flatten().max()?;
                Some((*lo, *hi + 1))
            })
            .collect();
        let Some(ranges) = ranges else {
            return Err(cd);
        };
        // The extended samples of every needed coefficient, per axis.
        let maps: Vec<Vec<Option<usize>>> = self
            .axes
            .iter()
            .zip(&ranges)
            .map(|(ax, &(a, b))| (a - n..b + n).map(|e| ax.sample(e)).collect())
            .collect();
        let (lists, pos) = maps.iter().map(|m| positions(m)).unzip();
        Ok(Reads {
            cd,
            ranges,
            maps,
            lists,
            pos,
        })
    }

    /// The source boxes `(lo, hi)` that computing the box `lo .. lo + len`
    /// reads (what an array-like must fetch first).
    pub(crate) fn boxes(&self, lo: &[i64], len: &[usize]) -> Vec<(Vec<usize>, Vec<usize>)> {
        match self.reads(lo, len) {
            Ok(r) if r.lists.iter().all(|l| !l.is_empty()) => run_boxes(&r.lists),
            _ => Vec::new(),
        }
    }

    /// The coefficients of the box `lo .. lo + len` (module documentation).
    pub(crate) fn coefficients<S>(
        &self,
        source: &S,
        lo: &[i64],
        len: &[usize],
    ) -> Result<CoefBox<T>, NdimageError>
    where
        S: SampleSource<T> + ?Sized,
    {
        let n = self.half_width() as i64;
        let mut data = Vec::new();
        let Reads {
            cd,
            ranges,
            maps,
            lists,
            pos,
        } = match self.reads(lo, len) {
            Ok(r) => r,
            Err(_) => {
                // Every coefficient of the box is the constant beyond the grid.
                data.resize(len.iter().product(), self.cval.clone());
                return Ok(self.boxed(lo, len, data, 0, vec![(0, 0); len.len()]));
            }
        };
        let reach = lists
            .iter()
            .map(|l| l.first().map_or((0, 0), |&f| (f, l[l.len() - 1] + 1)))
            .collect();
        let mut samples = Vec::new();
        if lists.iter().all(|l| !l.is_empty()) {
            gather(source, &lists, &mut samples)?;
        }
        let read = samples.len();
        self.check_samples(&mut samples, &lists)?;
        // Away from the edges every extended sample is its own source
        // sample, once, in order: the samples read are the extended ones.
        let direct = maps
            .iter()
            .zip(&lists)
            .all(|(m, l)| m.len() == l.len() && m.iter().zip(l).all(|(s, &i)| *s == Some(i)));
        let mut ext = Vec::new();
        if direct {
            ext = samples;
        } else {
            let gstrides = strides(&lists.iter().map(Vec::len).collect::<Vec<_>>());
            let offs: Vec<Vec<Option<usize>>> = pos
                .iter()
                .zip(&gstrides)
                .map(|(p, &s)| offsets(p, s))
                .collect();
            spread_into(&samples, &offs, &self.cval, &mut ext);
        }
        let mut shape: Vec<usize> = maps.iter().map(Vec::len).collect();
        if let Some(conv) = self.filter.as_ref().and_then(|f| f.convolution()) {
            let mut next = Vec::new();
            for axis in (0..shape.len()).rev() {
                convolve_axis(conv, &ext, &shape, axis, &mut next);
                shape[axis] -= 2 * n as usize;
                std::mem::swap(&mut ext, &mut next);
            }
        }
        // `ext` now holds D over the ranges; the box reads it through `cd`.
        let identity = ranges
            .iter()
            .zip(lo.iter().zip(len))
            .all(|(&(a, b), (&l, &k))| a == l && b == l + k as i64);
        if identity && cd.iter().flatten().all(Option::is_some) {
            return Ok(self.boxed(lo, len, ext, read, reach));
        }
        let dstrides = strides(&shape);
        let offs: Vec<Vec<Option<usize>>> = cd
            .iter()
            .zip(ranges.iter().zip(&dstrides))
            .map(|(c, (&(a, _), &s))| c.iter().map(|k| k.map(|k| (k - a) as usize * s)).collect())
            .collect();
        spread_into(&ext, &offs, &self.cval, &mut data);
        Ok(self.boxed(lo, len, data, read, reach))
    }

    fn boxed(
        &self,
        lo: &[i64],
        len: &[usize],
        data: Vec<T>,
        read: usize,
        reach: Vec<(usize, usize)>,
    ) -> CoefBox<T> {
        CoefBox {
            lo: lo.to_vec(),
            len: len.to_vec(),
            strides: strides(len),
            data,
            read,
            reach,
        }
    }

    /// The NaN policy and the overflow bound on the samples read: refused
    /// under [`NanPolicy::Raise`] (the first non-finite one, by its flat
    /// index in the array), ±∞ as NaN under [`NanPolicy::Local`]; the
    /// largest finite magnitude against the filter's growth.
    fn check_samples(&self, samples: &mut [T], lists: &[Vec<usize>]) -> Result<(), NdimageError> {
        // One branch-free sweep (it vectorises) where every magnitude is
        // a finite f64, the usual case; else the exact rule, sample by
        // sample (finite in `T`, first non-finite one).
        let (mut max, any_bad) = samples.iter().fold((0.0f64, false), |(m, bad), x| {
            let v = x.to_f64().abs();
            let finite = v.is_finite();
            let m = if finite && v > m { v } else { m };
            (m, bad | !finite)
        });
        let mut first_bad = None;
        if any_bad {
            max = 0.0;
            for (k, x) in samples.iter().enumerate() {
                if x.is_finite() {
                    max = max.max(x.to_f64().abs());
                } else if first_bad.is_none() {
                    first_bad = Some(k);
                }
            }
        }
        if let Some(k) = first_bad {
            match self.nan_policy {
                NanPolicy::Raise => {
                    let shape: Vec<usize> = lists.iter().map(Vec::len).collect();
                    let gs = strides(&shape);
                    let src = strides(&self.shape);
                    let index = (0..shape.len())
                        .map(|a| lists[a][k / gs[a] % shape[a]] * src[a])
                        .sum();
                    let value = NonFiniteValue::of(&samples[k]).expect("not finite");
                    return Err(NdimageError::NonFinite { index, value });
                }
                NanPolicy::Local => {
                    let nan = T::from_f64_exact(f64::NAN);
                    for x in samples.iter_mut().filter(|x| !x.is_finite()) {
                        *x = nan.clone();
                    }
                }
                NanPolicy::Propagate => {}
            }
        }
        match &self.filter {
            Some(f) => f.check_magnitude(max, self.ndim()),
            None => Ok(()),
        }
    }
}

/// One pass of the truncated convolution along `axis` of `x` (`shape`,
/// `n` extended values beyond each end of that axis) into `out`.
fn convolve_axis<T: Real>(
    conv: &crate::sspline::prefilter::ConvolutionPrefilter<T>,
    x: &[T],
    shape: &[usize],
    axis: usize,
    out: &mut Vec<T>,
) {
    let n = conv.half_width();
    let l = shape[axis];
    let v = l - 2 * n;
    let outer: usize = shape[..axis].iter().product();
    let inner: usize = shape[axis + 1..].iter().product();
    out.clear();
    out.resize(outer * v * inner, T::zero());
    if inner == 1 && v < SHORT_ROWS && outer > 1 {
        convolve_transposed(conv, x, outer, l, v, out);
        return;
    }
    for (src, dst) in x.chunks(l * inner).zip(out.chunks_mut(v * inner)) {
        if inner == 1 {
            conv.apply_extended(src, dst);
        } else {
            convolve_rows(conv.coefficients(), src, dst, inner);
        }
    }
}

/// Outputs per row below which the pass along the last axis runs on the
/// transposed rows: a point's box gives `order + 1` outputs per row, and
/// the tap loop over so few of them does not vectorise.
const SHORT_ROWS: usize = 16;

/// The pass along the last axis of the `outer × l` rows `x` into the
/// `outer × v` rows `out`, on their transpose: the rows side by side, the
/// taps swept over all of them at once by [`convolve_rows`] (the same
/// operations per value as [`ConvolutionPrefilter::apply_extended`],
/// `c_0 s_k` then `+ c_j (s_{k−j} + s_{k+j})` for `j = 1..n`: the same bits).
fn convolve_transposed<T: Real>(
    conv: &crate::sspline::prefilter::ConvolutionPrefilter<T>,
    x: &[T],
    outer: usize,
    l: usize,
    v: usize,
    out: &mut [T],
) {
    let mut xt = vec![T::zero(); outer * l];
    for (r, row) in x.chunks_exact(l).enumerate() {
        for (k, s) in row.iter().enumerate() {
            xt[k * outer + r] = s.clone();
        }
    }
    let mut yt = vec![T::zero(); v * outer];
    convolve_rows(conv.coefficients(), &xt, &mut yt, outer);
    for (r, row) in out.chunks_mut(v).enumerate() {
        for (k, o) in row.iter_mut().enumerate() {
            *o = yt[k * outer + r].clone();
        }
    }
}

/// Per-point work space of [`CoefBox::eval`]: weights and offsets, `m` per axis.
pub(crate) struct Work<T> {
    w: Vec<T>,
    off: Vec<usize>,
}

impl<T: Real> Work<T> {
    pub(crate) fn new(ndim: usize, order: u32) -> Self {
        let k = ndim * order as usize;
        Work {
            w: vec![T::zero(); k],
            off: vec![0; k],
        }
    }
}

impl<T: Real> CoefBox<T> {
    /// `∂^deriv f` at the point whose axes are at `xs` (already moved by
    /// the coordinate rules), its window inside the box: the global
    /// route's sum (the same weights, the same nesting and order).
    pub(crate) fn eval(&self, order: u32, xs: &[f64], deriv: &[u32], work: &mut Work<T>) -> T {
        if order == 1 {
            return self.data[0].clone();
        }
        let m = order as usize;
        for (a, &x) in xs.iter().enumerate() {
            let (first, u) = centred_cell(order, x);
            let w = &mut work.w[a * m..(a + 1) * m];
            cell_weights_into(order, deriv[a], u, w);
            let base = first - self.lo[a];
            debug_assert!(base >= 0 && base as usize + m <= self.len[a]);
            for l in 0..m {
                work.off[a * m + l] = (base as usize + l) * self.strides[a];
            }
        }
        self.accumulate(work, m, 0, 0)
    }

    fn accumulate(&self, work: &Work<T>, m: usize, axis: usize, base: usize) -> T {
        let last = axis + 1 == self.len.len();
        let mut sum = T::zero();
        for k in axis * m..(axis + 1) * m {
            let v = if last {
                self.data[base + work.off[k]].clone()
            } else {
                self.accumulate(work, m, axis + 1, base + work.off[k])
            };
            sum += work.w[k].clone() * v;
        }
        sum
    }
}

/// The first window index of `x` on an axis (`⌊m/2⌋` cells left of its cell).
#[inline]
pub(crate) fn first_index(order: u32, ax: &AxisMap, x: f64) -> i64 {
    if order == 1 {
        return ax.nearest(x).map_or(i64::MIN, |i| i as i64);
    }
    centred_cell(order, x).0
}
