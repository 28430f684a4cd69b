//! The local route's plan for a set of points: where each point is
//! evaluated, which box of coefficients (tile) holds its window, and what
//! the route costs against the global one ([`RouteCost`]).
//!
//! Points are grouped by the tile of `t^D` cells that holds their window's
//! first index (`t` a power of two chosen by cost, or fixed by a cached
//! interpolant); a tile's box is `t + d` coefficients per axis. Without a
//! prefilter each point is its own box: its `(d + 1)^D` support and nothing
//! else (degree 0: the one sample scipy's rule picks).

use super::axis_map::AxisMap;
use super::coef_box::{CoefBox, Work, first_index};
use super::route::{C_POINT, C_READ, RouteCost, global_ns, locate_ns, may_be_local, tile_ns};
use super::spec::LocalSpec;
use crate::ndimage::NdimageError;
use crate::ndimage::interpolant::PointRule;
use crate::ndimage::samples::SampleSource;
use crate::scalar::Real;
use ndarray::ArrayView2;
use rayon::prelude::*;
use std::collections::HashSet;

/// The points of one box.
#[derive(Debug, Clone)]
pub(crate) struct Group {
    pub(crate) lo: Vec<i64>,
    pub(crate) len: Vec<usize>,
    pub(crate) points: Vec<usize>,
}

/// Where a call's points are evaluated (module documentation).
#[derive(Debug, Clone)]
pub struct LocalPlan {
    ndim: usize,
    /// Per point (`ndim` each), the coordinates the cells are found at.
    xs: Vec<f64>,
    /// Per point, the first window index on each axis.
    firsts: Vec<i64>,
    /// Points that take `cval` without evaluation.
    cval_at: Vec<bool>,
    pub(crate) groups: Vec<Group>,
    cost: RouteCost,
}

/// What a call of the local route did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LocalStats {
    /// Boxes of coefficients computed.
    pub tiles: usize,
    /// Samples read from the source (a sample read by two boxes counts twice).
    pub samples_read: usize,
}

/// Tile edges tried: powers of two up to a box of about 2^16 cells.
fn tile_edges(ndim: usize) -> impl Iterator<Item = usize> {
    let top = 16 / ndim.max(1);
    (0..=top as u32).map(|k| 1usize << k)
}

impl LocalPlan {
    /// The plan for the points `points` (`(k, ndim)`, any strides) under
    /// `rule`, tiles of edge `tile` (`None`: the cheapest). Errors: a
    /// point of the wrong dimension, a non-finite coordinate (its flat
    /// index among the coordinates).
    pub fn new<T: Real>(
        spec: &LocalSpec<T>,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
        tile: Option<usize>,
    ) -> Result<Self, NdimageError> {
        let mut plan = Self::located(spec, points, rule)?;
        plan.group(spec, tile);
        Ok(plan)
    }

    /// The plan for `points` where the local route is the cheaper (the
    /// decision of `LocalPlan::new(.., None).cost().prefer_local()`),
    /// `None` where the global route is. Pricing and grouping cost more
    /// per point than either route at many points (measured: 1.9 s for
    /// 10^6 points on a 2048^2 array, whose global route takes 0.1 s), so
    /// a floor of the local cost comes first (`local_floor_ns`); where it
    /// already reaches the global cost, the local route cannot win and
    /// nothing is grouped; where locating the points alone reaches it
    /// (`locate_ns`: reproject's 10⁴ linear points on a 250 × 150 array),
    /// nothing is located.
    pub fn new_if_local<T: Real>(
        spec: &LocalSpec<T>,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
    ) -> Result<Option<Self>, NdimageError> {
        let (samples, filtered) = (spec.shape().iter().product(), spec.filter.is_some());
        let half_width = || Some(spec.half_width());
        if !may_be_local(
            samples,
            spec.ndim(),
            spec.degree(),
            points.nrows(),
            filtered,
            half_width,
        ) {
            // The count alone says the local route cannot win.
            return Ok(None);
        }
        let global = global_ns(samples, spec.ndim(), filtered);
        let mut plan = Self::located(spec, points, rule)?;
        if plan.local_floor_ns(spec) >= global {
            return Ok(None);
        }
        plan.group(spec, None);
        Ok(plan.cost.prefer_local().then_some(plan))
    }

    /// A lower bound of [`group`](Self::group)'s local cost at every tile
    /// edge: every point located (`locate_ns`), `C_POINT` per evaluated
    /// point and one tile of edge 1 (a tile's cost grows with its edge;
    /// one tile at least where there is a point, [`floor_ns`](super::route::floor_ns)); without a
    /// prefilter, the cost itself.
    fn local_floor_ns<T: Real>(&self, spec: &LocalSpec<T>) -> f64 {
        let live = self.priced_points();
        let (d, m) = (self.ndim, spec.order as usize);
        if spec.filter.is_none() {
            return locate_ns(self.len())
                + live as f64 * (C_POINT + C_READ * (m as f64).powi(d as i32));
        }
        let one_tile = if live > 0 {
            tile_ns(d, spec.degree(), spec.half_width(), 1)
        } else {
            0.0
        };
        locate_ns(self.len()) + one_tile + live as f64 * C_POINT
    }

    /// The points the local route prices as evaluated: those that do not
    /// take `cval`, and one at least where there is a point ([`floor_ns`](super::route::floor_ns)).
    fn priced_points(&self) -> usize {
        let live = self.cval_at.iter().filter(|&&c| !c).count();
        live.max(usize::from(!self.is_empty()))
    }

    /// The points located (cells, `cval` points), not yet grouped.
    fn located<T: Real>(
        spec: &LocalSpec<T>,
        points: ArrayView2<'_, f64>,
        rule: PointRule,
    ) -> Result<Self, NdimageError> {
        let ndim = spec.ndim();
        if points.ncols() != ndim {
            return Err(NdimageError::PointDimension {
                expected: ndim,
                got: points.ncols(),
            });
        }
        let k = points.nrows();
        let mut xs = vec![0.0; k * ndim];
        let mut firsts = vec![0i64; k * ndim];
        let mut cval_at = vec![false; k];
        xs.par_chunks_mut(ndim)
            .zip(firsts.par_chunks_mut(ndim))
            .zip(cval_at.par_iter_mut())
            .enumerate()
            .with_min_len(1024)
            .try_for_each(|(p, ((x, f), c))| {
                locate(spec, points.row(p).iter().copied(), rule, p, x, f, c)
            })?;
        Ok(LocalPlan {
            ndim,
            xs,
            firsts,
            cval_at,
            groups: Vec::new(),
            cost: RouteCost {
                local_ns: 0.0,
                global_ns: 0.0,
                tile: 1,
                tiles: 0,
            },
        })
    }

    /// The estimated cost of each route ([`RouteCost`]).
    pub fn cost(&self) -> RouteCost {
        self.cost
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.cval_at.len()
    }

    /// Whether there are no points.
    pub fn is_empty(&self) -> bool {
        self.cval_at.is_empty()
    }

    /// Groups the points into boxes and prices both routes.
    fn group<T: Real>(&mut self, spec: &LocalSpec<T>, tile: Option<usize>) {
        let (d, m) = (self.ndim, spec.order as usize);
        let live: Vec<usize> = (0..self.len()).filter(|&p| !self.cval_at[p]).collect();
        let samples: usize = spec.shape().iter().product();
        let filtered = spec.filter.is_some();
        if !filtered {
            self.groups = live
                .iter()
                .map(|&p| Group {
                    lo: self.firsts[p * d..(p + 1) * d].to_vec(),
                    len: vec![m; d],
                    points: vec![p],
                })
                .collect();
            let per_point = C_POINT + C_READ * (m as f64).powi(d as i32);
            self.cost = RouteCost {
                local_ns: locate_ns(self.len()) + self.priced_points() as f64 * per_point,
                global_ns: global_ns(samples, d, false),
                tile: 1,
                tiles: live.len(),
            };
            return;
        }
        let n = spec.half_width();
        let degree = spec.degree();
        let priced = |t: usize| {
            let shift = t.trailing_zeros();
            // Tiles counted by a hash of their key (a collision only
            // lowers the estimate by one tile).
            let tiles: HashSet<u64> = live
                .iter()
                .map(|&p| {
                    self.firsts[p * d..(p + 1) * d]
                        .iter()
                        .fold(0xcbf2_9ce4_8422_2325u64, |h, f| {
                            (h ^ (f >> shift) as u64).wrapping_mul(0x0100_0000_01b3)
                        })
                })
                .collect();
            (
                tiles.len() as f64 * tile_ns(d, degree, n, t),
                t,
                tiles.len(),
            )
        };
        let (local, t, tiles) = match tile {
            Some(t) => priced(t.max(1).next_power_of_two()),
            None => tile_edges(d)
                .map(priced)
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap_or((0.0, 1, 0)),
        };
        // One tile at least where there is a point ([`floor_ns`]).
        let (local, priced) = if live.is_empty() && !self.is_empty() {
            (tile_ns(d, degree, n, t), 1)
        } else {
            (local, live.len())
        };
        self.cost = RouteCost {
            local_ns: locate_ns(self.len()) + local + priced as f64 * C_POINT,
            global_ns: global_ns(samples, d, true),
            tile: t,
            tiles,
        };
        let shift = t.trailing_zeros();
        let mut order = live;
        let key = |p: usize| -> Vec<i64> {
            self.firsts[p * d..(p + 1) * d]
                .iter()
                .map(|f| f >> shift)
                .collect()
        };
        order.par_sort_by_cached_key(|&p| key(p));
        let mut groups: Vec<Group> = Vec::new();
        for p in order {
            let k = key(p);
            match groups.last_mut() {
                Some(g) if g.lo.iter().zip(&k).all(|(lo, k)| *lo == k << shift) => g.points.push(p),
                _ => groups.push(Group {
                    lo: k.iter().map(|k| k << shift).collect(),
                    len: vec![t + m - 1; d],
                    points: vec![p],
                }),
            }
        }
        self.groups = groups;
    }

    /// Evaluates the plan: `∂^deriv f` (values where `deriv` is `None`) at
    /// every point into `out`, `cval` (0 for a derivative) at points the
    /// rule sends there, the boxes computed in parallel by `tile` (a
    /// cache's lookup, or [`LocalSpec::coefficients`]).
    pub(crate) fn evaluate_with<T, F>(
        &self,
        spec: &LocalSpec<T>,
        deriv: Option<&[u32]>,
        out: &mut [T],
        tile: F,
    ) -> Result<LocalStats, NdimageError>
    where
        T: Real + Send + Sync,
        F: Fn(&Group) -> Result<std::sync::Arc<CoefBox<T>>, NdimageError> + Sync,
    {
        if out.len() != self.len() {
            return Err(NdimageError::BufferLength {
                expected: self.len(),
                got: out.len(),
            });
        }
        let zero = vec![0u32; self.ndim];
        let deriv = deriv.unwrap_or(&zero);
        if let Some(&d) = deriv.iter().find(|&&d| d > spec.degree()) {
            return Err(NdimageError::DerivativeTooHigh {
                order: d,
                degree: spec.degree(),
            });
        }
        let fill = if deriv.iter().any(|&d| d > 0) {
            T::zero()
        } else {
            spec.cval.clone()
        };
        for (o, &c) in out.iter_mut().zip(&self.cval_at) {
            if c {
                *o = fill.clone();
            }
        }
        let d = self.ndim;
        let results: Vec<(Vec<(usize, T)>, usize)> = self
            .groups
            .par_iter()
            .with_min_len(if spec.filter.is_some() { 1 } else { 256 })
            .map(|g| {
                let b = tile(g)?;
                let mut work = Work::new(d, spec.order);
                let values = g
                    .points
                    .iter()
                    .map(|&p| {
                        let x = &self.xs[p * d..(p + 1) * d];
                        (p, b.eval(spec.order, x, deriv, &mut work))
                    })
                    .collect();
                Ok((values, b.read))
            })
            .collect::<Result<_, NdimageError>>()?;
        let mut stats = LocalStats {
            tiles: results.len(),
            samples_read: 0,
        };
        for (values, read) in results {
            stats.samples_read += read;
            for (p, v) in values {
                out[p] = v;
            }
        }
        Ok(stats)
    }

    /// [`Self::evaluate_with`] computing every box from `source`.
    pub fn evaluate<T, S>(
        &self,
        spec: &LocalSpec<T>,
        source: &S,
        deriv: Option<&[u32]>,
        out: &mut [T],
    ) -> Result<LocalStats, NdimageError>
    where
        T: Real + Send + Sync,
        S: SampleSource<T> + ?Sized,
    {
        self.evaluate_with(spec, deriv, out, |g| {
            spec.coefficients(source, &g.lo, &g.len)
                .map(std::sync::Arc::new)
        })
    }
}

/// One point: checked finite, moved by the rule and the axes' coordinate
/// rules into `x`, its window's first indices into `first`, `cval` flagged.
fn locate<T: Real>(
    spec: &LocalSpec<T>,
    coords: impl Iterator<Item = f64>,
    rule: PointRule,
    p: usize,
    x: &mut [f64],
    first: &mut [i64],
    cval: &mut bool,
) -> Result<(), NdimageError> {
    let d = x.len();
    for (a, (xa, c)) in x.iter_mut().zip(coords).enumerate() {
        if !c.is_finite() {
            return Err(NdimageError::NonFiniteCoordinate(p * d + a));
        }
        *xa = c;
    }
    if rule.apply(x, spec.shape()) {
        *cval = true;
        return Ok(());
    }
    for (a, ax) in spec.axes.iter().enumerate() {
        if spec.order == 1 {
            match ax.nearest(x[a]) {
                Some(i) => first[a] = i as i64,
                None => *cval = true,
            }
            continue;
        }
        x[a] = AxisMap::coordinate(ax, x[a]);
        first[a] = first_index(spec.order, ax, x[a]);
    }
    Ok(())
}
