//! How one axis of the local route reaches its samples: the index maps
//! that make a coefficient computed from a few samples the same number the
//! global route computes from all of them (within the truncation bound).
//!
//! Three spaces per axis:
//!
//! - **coefficient indices** `k ∈ ℤ`, the ones a point's window reads
//!   (unfolded: a point folded to `[0, ν − 1]` reads `k` down to
//!   `−⌊m/2⌋ − 1`). On the engine's own modes every `k` has its own
//!   coefficient, the spline of the extended signal at `k` (for the
//!   symmetric and periodic modes it equals the coefficient at the folded
//!   index bit for bit: the convolution's terms are the same samples in
//!   pairs whose order addition ignores). On scipy's padded route
//!   ([`AxisMap::scipy_padded`]) the coefficients live on a grid of
//!   `ν + 2p` and beyond it are extended as `map_coordinates(...,
//!   prefilter=False)` extends given coefficients: `nearest` repeats the
//!   end one ([`Mode::fold`], clamped), `grid-constant` gives `cval`.
//! - **extended sample indices** `e`, the ones a coefficient's convolution
//!   reads (`k − n ..= k + n`);
//! - **source indices** `0..ν`: [`AxisMap::sample`] folds `e` as the global
//!   route's filter extends its samples ([`Mode::fold`]; `None`: `cval`),
//!   on the padded route first over the padded grid by scipy's filter rule
//!   (reflect for `nearest`, mirror for `grid-constant`), then by the pad's
//!   own extension (edge samples, or `cval`).
//!
//! and the coordinate rule ([`AxisMap::coordinate`]): the point moved where
//! the global route evaluates it (folded by the mode, clamped where every
//! coefficient of the window is the end one, shifted by scipy's pad).

use crate::ndimage::mode::Mode;

/// What happens to a coordinate before its cell is found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Coordinate {
    /// [`Mode::fold_coordinate`] over the coefficient grid.
    Fold(Mode),
    /// Clamped to `[−r, len − 1 + r]` (`nearest` beyond the reach where
    /// every coefficient of the window is the end one).
    Clamp(f64),
}

/// The index maps of one axis (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct AxisMap {
    /// Samples along the axis, `ν`.
    len: usize,
    /// `None`: a coefficient at every integer. `Some((ext, lc))`: a grid of
    /// `lc` coefficients, extended beyond it by `ext` (scipy's padded route).
    grid: Option<(Mode, usize)>,
    /// scipy's padded route: the filter's rule over the padded grid.
    outer: Option<Mode>,
    /// The pad `p` (extended index `e` of the padded grid is sample `e − p`).
    shift: i64,
    /// How the samples extend beyond `0..ν`.
    inner: Mode,
    coordinate: Coordinate,
}

impl AxisMap {
    /// The engine's mode on `len` samples (the coefficients of the signal
    /// extended by `mode` at every integer); `clamp`: the reach beyond which
    /// `nearest` clamps the point (`None`: the mode's fold).
    pub(crate) fn engine(mode: Mode, len: usize, clamp: Option<f64>) -> Self {
        AxisMap {
            len,
            grid: None,
            outer: None,
            shift: 0,
            inner: mode,
            coordinate: clamp.map_or(Coordinate::Fold(mode), Coordinate::Clamp),
        }
    }

    /// scipy's `nearest` / `grid-constant` at degrees 2–5
    /// (`_prepad_for_spline_filter`): the samples padded by `pad` edge
    /// samples / `cval`, filtered with scipy's rule (`reflect` for
    /// `nearest`, `mirror` for `grid-constant`), the coefficients extended
    /// as given ones, the point moved by `pad`; `half`: `⌊m/2⌋`.
    pub(crate) fn scipy_padded(mode: Mode, len: usize, pad: usize, half: usize) -> Self {
        let (rule, coordinate) = if mode == Mode::Nearest {
            (Mode::Reflect, Coordinate::Clamp((half + 1) as f64))
        } else {
            (Mode::Mirror, Coordinate::Fold(Mode::GridConstant))
        };
        AxisMap {
            len,
            grid: Some((mode, len + 2 * pad)),
            outer: Some(rule),
            shift: pad as i64,
            inner: mode,
            coordinate,
        }
    }

    /// The coefficient-grid length the coordinate rule works on.
    pub(crate) fn grid_len(&self) -> usize {
        self.grid.map_or(self.len, |(_, lc)| lc)
    }

    /// The point at which the axis is evaluated (module documentation).
    #[inline]
    pub(crate) fn coordinate(&self, x: f64) -> f64 {
        let x = if self.shift == 0 {
            x
        } else {
            x + self.shift as f64
        };
        let lc = self.grid_len();
        match self.coordinate {
            Coordinate::Fold(mode) => mode.fold_coordinate(x, lc),
            Coordinate::Clamp(r) => x.clamp(-r, lc as f64 - 1.0 + r),
        }
    }

    /// The coefficient index computed for window index `k` (`None`: `cval`).
    #[inline]
    pub(crate) fn coefficient(&self, k: i64) -> Option<i64> {
        match self.grid {
            None => Some(k),
            Some((ext, lc)) => ext.fold(k, lc).map(|j| j as i64),
        }
    }

    /// The source sample the extended index `e` reads (`None`: `cval`).
    #[inline]
    pub(crate) fn sample(&self, e: i64) -> Option<usize> {
        let e = match (self.outer, self.grid) {
            (Some(rule), Some((_, lc))) => rule.fold(e, lc)? as i64,
            _ => e,
        };
        self.inner.fold(e - self.shift, self.len)
    }

    /// The sample scipy's `order=0` returns (`None`: `cval`).
    pub(crate) fn nearest(&self, x: f64) -> Option<usize> {
        self.inner.nearest_index(x, self.len)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The padded route's extended samples are `np.pad`'s array extended
    /// by scipy's filter rule, index by index.
    #[test]
    fn padded_samples_are_the_padded_array_folded_by_the_rule() {
        let (len, pad) = (5usize, 3usize);
        for (mode, rule) in [
            (Mode::Nearest, Mode::Reflect),
            (Mode::GridConstant, Mode::Mirror),
        ] {
            let m = AxisMap::scipy_padded(mode, len, pad, 2);
            let padded: Vec<Option<usize>> = (0..len + 2 * pad)
                .map(|i| mode.fold(i as i64 - pad as i64, len))
                .collect();
            for e in -20i64..30 {
                let j = rule.fold(e, len + 2 * pad).unwrap();
                assert_eq!(m.sample(e), padded[j], "{mode} e {e}");
            }
            assert_eq!(
                m.coefficient(-4),
                mode.fold(-4, len + 2 * pad).map(|j| j as i64)
            );
        }
    }
}
