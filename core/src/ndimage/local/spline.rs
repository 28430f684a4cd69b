//! [`LocalInterpolant`]: a reusable spline over one array on the local
//! route, its tiles of coefficients computed when a point first needs them
//! and kept within a byte budget, its samples changed in place of a
//! rebuild ([`LocalInterpolant::update`]).

use super::coef_box::CoefBox;
use super::overlay::{Overlaid, Overlay};
use super::plan::{LocalPlan, LocalStats};
use super::spec::{LocalOptions, LocalSpec};
use super::tile_cache::TileCache;
use crate::ndimage::NdimageError;
use crate::ndimage::interpolant::PointRule;
use crate::ndimage::nan_policy::NanPolicy;
use crate::ndimage::samples::SampleSource;
use crate::scalar::Real;
use crate::validation::NonFiniteValue;
use ndarray::ArrayView2;
use rayon::prelude::*;
use std::sync::Arc;

/// A spline over one array on the local route (module documentation).
///
/// The interpolant holds the spline (its [`LocalSpec`]), the tiles computed
/// so far and the samples changed by [`Self::update`]; the array itself is
/// passed to each call (an `ndarray` view, a memory map, blocks fetched from
/// an array-like: any [`SampleSource`] of the shape given to
/// [`Self::new`]), and is never written.
///
/// **Accuracy**: that of the local route ([`crate::ndimage::local`]); a
/// value is a function of the current samples only: the same bits whatever
/// the tiles held, the budget, or the updates that led there (an update
/// recomputes the coefficients within reach by the same operations as a
/// rebuild, so it agrees with a rebuild bit for bit).
///
/// ```
/// use splinelab::ndimage::local::{LocalInterpolant, LocalOptions};
/// use splinelab::ndimage::interpolant::PointRule;
/// use splinelab::prelude::*;
/// let data = ndarray::Array2::from_shape_fn((64, 64), |(i, j)| (i as f64 * 0.1).sin() + j as f64);
/// let mut f = LocalInterpolant::<f64>::new(data.shape(), LocalOptions::new(3, Mode::Mirror), 1 << 20).unwrap();
/// let at = ndarray::array![[10.5, 20.25]];
/// let mut v = [0.0];
/// f.eval_many(&data, at.view(), PointRule::Fold, None, &mut v).unwrap();
/// f.update(&data, &[10, 20], &[100.0]).unwrap();
/// let mut w = [0.0];
/// f.eval_many(&data, at.view(), PointRule::Fold, None, &mut w).unwrap();
/// let mut changed = data.clone();
/// changed[[10, 20]] = 100.0;
/// let g = LocalInterpolant::<f64>::new(data.shape(), LocalOptions::new(3, Mode::Mirror), 1 << 20).unwrap();
/// let mut r = [0.0];
/// g.eval_many(&changed, at.view(), PointRule::Fold, None, &mut r).unwrap();
/// assert_eq!(w[0], r[0]);
/// assert!((w[0] - v[0]).abs() > 1.0);
/// ```
pub struct LocalInterpolant<T> {
    spec: LocalSpec<T>,
    tile: usize,
    /// Tiles sized by cost per call, none cached (a single call's use).
    adaptive: bool,
    cache: TileCache<T>,
    overlay: Overlay<T>,
}

/// Source boxes `(lo, hi)` to fetch.
pub type Boxes = Vec<(Vec<usize>, Vec<usize>)>;

/// A recomputed tile: its key, its coefficients, how many were recomputed.
type Redone<T> = (Vec<i64>, Arc<CoefBox<T>>, usize);

/// A cached tile an update reaches: its key, its coefficients, the changed
/// samples it reads.
type Hit<'i, T> = (Vec<i64>, Arc<CoefBox<T>>, Vec<&'i [usize]>);

/// What an update recomputed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct UpdateStats {
    /// Cached tiles some of whose coefficients changed.
    pub tiles: usize,
    /// Coefficients recomputed.
    pub coefficients: usize,
    /// Cached tiles within reach dropped instead (more than
    /// [`EAGER_TILES`]): recomputed when a point next needs them.
    pub dropped: usize,
}

/// The most cached tiles an update recomputes at once; beyond, the tiles
/// within reach are dropped and recomputed when next needed (an update of
/// many scattered samples would otherwise recompute most of the cache).
pub const EAGER_TILES: usize = 16;

/// The tile edge of a [`LocalInterpolant`] of `ndim` axes (a box of about
/// `2^10` to `2^12` cells).
fn default_tile(ndim: usize) -> usize {
    match ndim {
        1 => 512,
        2 => 32,
        3 => 16,
        _ => 8,
    }
}

impl<T: Real + Send + Sync> LocalInterpolant<T> {
    /// The spline `opts` over an array of `shape`, keeping at most
    /// `cache_bytes` bytes of coefficient tiles; refused
    /// ([`NdimageError::CacheTooSmall`]) below one tile's bytes.
    pub fn new(
        shape: &[usize],
        opts: LocalOptions,
        cache_bytes: usize,
    ) -> Result<Self, NdimageError> {
        let spec = LocalSpec::new(shape, opts)?;
        let tile = default_tile(shape.len());
        let smallest = Self::tile_bytes(&spec, tile);
        if cache_bytes < smallest {
            return Err(NdimageError::CacheTooSmall {
                budget: cache_bytes,
                smallest,
            });
        }
        Ok(LocalInterpolant {
            overlay: Overlay::new(shape),
            spec,
            tile,
            adaptive: false,
            cache: TileCache::new(cache_bytes),
        })
    }

    /// The interpolant for one call: tiles sized by cost for its points
    /// (as [`map_coordinates_local`](super::map_coordinates_local)), none
    /// kept. What an array-like's `map_coordinates` uses.
    pub fn for_one_call(mut self) -> Self {
        self.adaptive = true;
        self
    }

    /// The tile edge of a plan (`None`: by cost).
    fn tile_edge(&self) -> Option<usize> {
        (!self.adaptive).then_some(self.tile)
    }

    /// The bytes of one tile's coefficients.
    fn tile_bytes(spec: &LocalSpec<T>, tile: usize) -> usize {
        let side = tile + spec.degree() as usize;
        side.pow(spec.ndim() as u32) * std::mem::size_of::<T>()
    }

    /// The spline's specification (half-width, bound, shape).
    pub fn spec(&self) -> &LocalSpec<T> {
        &self.spec
    }

    /// The cache's budget and the bytes it holds now.
    pub fn cache_bytes(&self) -> (usize, usize) {
        (self.cache.budget(), self.cache.bytes())
    }

    /// Tiles held now.
    pub fn cached_tiles(&self) -> usize {
        self.cache.len()
    }

    /// Bytes held by the changed samples.
    pub fn changed_bytes(&self) -> usize {
        self.overlay.bytes()
    }

    fn check_source<S: SampleSource<T> + ?Sized>(&self, source: &S) -> Result<(), NdimageError> {
        if source.shape() != self.spec.shape() {
            return Err(NdimageError::SourceShape {
                expected: self.spec.shape().to_vec(),
                got: source.shape().to_vec(),
            });
        }
        Ok(())
    }

    /// `∂^deriv f` (values for `None`) at the rows of `points` (`(k, ndim)`)
    /// under `rule`, into `out`; the tiles the points need computed from
    /// `source` (with the changed samples) where the cache does not hold them.
    pub fn eval_many<S: SampleSource<T> + ?Sized>(
        &self,
        source: &S,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
        deriv: Option<&[u32]>,
        out: &mut [T],
    ) -> Result<LocalStats, NdimageError> {
        self.check_source(source)?;
        let plan = LocalPlan::new(&self.spec, points, rule, self.tile_edge())?;
        let src = Overlaid {
            base: source,
            overlay: &self.overlay,
        };
        let cached = self.spec.filter.is_some() && !self.adaptive;
        plan.evaluate_with(&self.spec, deriv, out, |g| {
            if cached && let Some(t) = self.cache.get(&g.lo) {
                return Ok(t);
            }
            let t = Arc::new(self.spec.coefficients(&src, &g.lo, &g.len)?);
            if cached {
                self.cache.put(g.lo.clone(), t.clone());
            }
            Ok(t)
        })
    }

    /// Sets the samples at `indices` (`ndim` per sample, C order of the
    /// axes) to `values`, in order (a repeated index keeps the last value,
    /// as numpy's assignment), and recomputes the coefficients within reach
    /// in the cached tiles (where more than [`EAGER_TILES`] tiles are
    /// within reach, drops them instead: recomputed when next needed). Refused, changing nothing: an index outside the
    /// array ([`NdimageError::IndexOutside`]), a non-finite value under
    /// [`NanPolicy::Raise`], a length mismatch.
    pub fn update<S: SampleSource<T> + ?Sized>(
        &mut self,
        source: &S,
        indices: &[usize],
        values: &[T],
    ) -> Result<UpdateStats, NdimageError> {
        self.check_source(source)?;
        let d = self.spec.ndim();
        if indices.len() != values.len() * d {
            return Err(NdimageError::BufferLength {
                expected: values.len() * d,
                got: indices.len(),
            });
        }
        let shape = self.spec.shape().to_vec();
        let strides = super::gather::strides(&shape);
        for (k, idx) in indices.chunks(d).enumerate() {
            if let Some(a) = (0..d).find(|&a| idx[a] >= shape[a]) {
                return Err(NdimageError::IndexOutside {
                    index: idx[a],
                    axis: a,
                    len: shape[a],
                });
            }
            if self.spec.nan_policy == NanPolicy::Raise
                && let Some(value) = NonFiniteValue::of(&values[k])
            {
                let index = idx.iter().zip(&strides).map(|(i, s)| i * s).sum();
                return Err(NdimageError::NonFinite { index, value });
            }
        }
        // Changed in place; a failing read (of a block, or of what the
        // recomputed coefficients need) takes the changes back, leaving the
        // overlay as it was.
        let undo = self
            .overlay
            .set_all(source, indices.chunks(d).zip(values))?;
        let hits = self.hit_tiles(indices);
        let mut stats = UpdateStats::default();
        if hits.len() > EAGER_TILES {
            // Many tiles within reach: recomputed when next needed (by the
            // same operations), not now.
            for (key, _, _) in &hits {
                self.cache.remove(key);
            }
            stats.dropped = hits.len();
            return Ok(stats);
        }
        let src = Overlaid {
            base: source,
            overlay: &self.overlay,
        };
        let redone = match self.recompute(&src, &hits) {
            Ok(redone) => redone,
            Err(e) => {
                self.overlay.revert(undo);
                return Err(e);
            }
        };
        for (key, tile, count) in redone {
            stats.tiles += 1;
            stats.coefficients += count;
            self.cache.replace(&key, tile);
        }
        Ok(stats)
    }

    /// The cached tiles that read a changed sample, with the coefficients
    /// within reach of the changes recomputed (the bounding box of them in
    /// each tile), and how many.
    fn recompute<S: SampleSource<T> + ?Sized>(
        &self,
        src: &S,
        hits: &[Hit<'_, T>],
    ) -> Result<Vec<Redone<T>>, NdimageError> {
        hits.par_iter()
            .map(|(key, tile, hit)| self.redo_tile(src, key, tile, hit))
            .filter_map(Result::transpose)
            .collect()
    }

    /// One tile's coefficients within reach of the samples `hit`.
    fn redo_tile<S: SampleSource<T> + ?Sized>(
        &self,
        src: &S,
        key: &[i64],
        tile: &CoefBox<T>,
        hit: &[&[usize]],
    ) -> Result<Option<Redone<T>>, NdimageError> {
        let Some((lo, sub_lo, sub_len)) = self.within_reach(tile, hit) else {
            return Ok(None);
        };
        let fresh = self.spec.coefficients(src, &sub_lo, &sub_len)?;
        let mut next = tile.clone();
        let count = fresh.data.len();
        super::gather::for_each_index(&sub_len, |k, idx| {
            let at = idx
                .iter()
                .enumerate()
                .fold(0, |s, (a, &i)| s * tile.len[a] + lo[a] + i);
            next.data[at] = fresh.data[k].clone();
        });
        Ok(Some((key.to_vec(), Arc::new(next), count)))
    }

    /// The sub-box of `tile` whose coefficients read one of the samples
    /// `hit` (their bounding box): its first position in the tile, its
    /// first coefficient index and its size.
    #[allow(clippy::type_complexity)]
    fn within_reach(
        &self,
        tile: &CoefBox<T>,
        hit: &[&[usize]],
    ) -> Option<(Vec<usize>, Vec<i64>, Vec<usize>)> {
        let n = self.spec.half_width() as i64;
        // Per axis, the box's coefficient indices and their range.
        let coefs: Vec<Vec<Option<i64>>> = (0..self.spec.ndim())
            .map(|a| {
                let ax = &self.spec.axes[a];
                (0..tile.len[a] as i64)
                    .map(|p| ax.coefficient(tile.lo[a] + p))
                    .collect()
            })
            .collect();
        // The box positions along axis `a` whose convolution reads source
        // index `s`: those within `n` of an extended index that `s` fills.
        let span = |a: usize, s: usize| -> Option<(usize, usize)> {
            let ax = &self.spec.axes[a];
            let c = &coefs[a];
            let lo = *c.iter().flatten().min()?;
            let hi = *c.iter().flatten().max()?;
            let images: Vec<i64> = (lo - n..=hi + n)
                .filter(|&e| ax.sample(e) == Some(s))
                .collect();
            let reads =
                |k: &Option<i64>| k.is_some_and(|k| images.iter().any(|e| (k - e).abs() <= n));
            let first = c.iter().position(reads)?;
            let last = c.iter().rposition(reads)?;
            Some((first, last))
        };
        let mut lo = vec![usize::MAX; self.spec.ndim()];
        let mut hi = vec![0usize; self.spec.ndim()];
        for idx in hit {
            let spans: Option<Vec<(usize, usize)>> =
                idx.iter().enumerate().map(|(a, &i)| span(a, i)).collect();
            if let Some(spans) = spans {
                for (a, (f, l)) in spans.into_iter().enumerate() {
                    lo[a] = lo[a].min(f);
                    hi[a] = hi[a].max(l + 1);
                }
            }
        }
        if lo.iter().zip(&hi).any(|(l, h)| l >= h) {
            return None;
        }
        let sub_lo: Vec<i64> = lo
            .iter()
            .zip(&tile.lo)
            .map(|(&l, &t)| t + l as i64)
            .collect();
        let sub_len: Vec<usize> = lo.iter().zip(&hi).map(|(l, h)| h - l).collect();
        Some((lo, sub_lo, sub_len))
    }

    /// The tiles an update of the samples `indices` recomputes, with the
    /// samples each hit.
    fn hit_tiles<'i>(&self, indices: &'i [usize]) -> Vec<Hit<'i, T>> {
        if self.spec.filter.is_none() {
            return Vec::new();
        }
        let d = self.spec.ndim();
        // Sorted by the first axis, a tile's candidates are one range of
        // them (found by bisection): the cost is the tiles' count plus the
        // hits, not their product.
        let mut sorted: Vec<&[usize]> = indices.chunks(d).collect();
        sorted.sort_unstable_by_key(|idx| idx[0]);
        self.cache.select(|tile| {
            let (lo, hi) = tile.reach[0];
            let from = sorted.partition_point(|idx| idx[0] < lo);
            let to = sorted.partition_point(|idx| idx[0] < hi);
            let hit: Vec<&[usize]> = sorted[from..to]
                .iter()
                .filter(|idx| {
                    idx.iter()
                        .zip(&tile.reach)
                        .all(|(&i, &(lo, hi))| lo <= i && i < hi)
                })
                .copied()
                .collect();
            (!hit.is_empty()).then_some(hit)
        })
    }

    /// The source boxes that evaluating at `points` under `rule` reads
    /// (the tiles not cached): what an array-like must fetch, as
    /// [`Blocks`](crate::ndimage::samples::Blocks), before
    /// [`Self::eval_many`].
    pub fn boxes_for_eval(
        &self,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
    ) -> Result<Boxes, NdimageError> {
        let plan = LocalPlan::new(&self.spec, points, rule, self.tile_edge())?;
        let cached = self.spec.filter.is_some() && !self.adaptive;
        let mut out: Vec<(Vec<usize>, Vec<usize>)> = plan
            .groups
            .iter()
            .filter(|g| !(cached && self.cache.get(&g.lo).is_some()))
            .flat_map(|g| self.spec.boxes(&g.lo, &g.len))
            .collect();
        out.sort_unstable();
        out.dedup();
        Ok(out)
    }

    /// The source boxes that [`Self::update`] of the samples `indices`
    /// reads: the blocks of changed samples not yet held, and what the
    /// recomputed coefficients read.
    pub fn boxes_for_update(&self, indices: &[usize]) -> Boxes {
        let d = self.spec.ndim();
        let mut out = self.overlay.missing_blocks(indices.chunks(d));
        for (_, tile, hit) in self.hit_tiles(indices) {
            if let Some((_, sub_lo, sub_len)) = self.within_reach(&tile, &hit) {
                out.extend(self.spec.boxes(&sub_lo, &sub_len));
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The changed samples' blocks: first index and samples (to save).
    pub fn changed_blocks(&self) -> Vec<(Vec<usize>, Vec<T>)> {
        self.overlay.blocks()
    }

    /// Restores a block of changed samples saved by [`Self::changed_blocks`]
    /// (the cache is cleared).
    pub fn restore_block(&mut self, first: &[usize], data: Vec<T>) -> Result<(), NdimageError> {
        self.overlay.restore(first, data)?;
        self.cache.clear();
        Ok(())
    }

    /// Whether any sample has been changed.
    pub fn is_changed(&self) -> bool {
        !self.overlay.is_empty()
    }
}
