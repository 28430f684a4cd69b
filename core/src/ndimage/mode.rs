//! The boundary modes of the N-D engine, with scipy.ndimage's names and
//! semantics: how samples `s_0..s_{ν−1}` are extended to every integer.
//!
//! | ours | scipy | extension | paper (seed 000 eq 21–23) |
//! |---|---|---|---|
//! | [`Mode::Mirror`] | `mirror` | `d c b │ a b c d │ c b a` (whole-sample symmetric, period `2ν − 2`) | end tangents with zero tangents ([`EndRule::Reflect`]) |
//! | [`Mode::Reflect`] | `reflect`, `grid-mirror` | `d c b a │ a b c d │ d c b a` (half-sample symmetric, period `2ν`) | — |
//! | [`Mode::GridWrap`] | `grid-wrap` | `a b c d │ a b c d │ a b c d` (period `ν`) | periodic ([`EndRule::Periodic`]) |
//! | [`Mode::Nearest`] | `nearest` | `a a a a │ a b c d │ d d d d` | free ([`EndRule::Free`]) |
//! | [`Mode::GridConstant`] | `grid-constant` | `k k k k │ a b c d │ k k k k` (`k = cval`) | — |
//!
//! scipy's `wrap` is not a `Mode`: it is not one spline of an extended
//! signal (scipy filters it with the mirror rule, then wraps points with
//! period `ν − 1`, the first and last samples overlapping), so parsing
//! `"wrap"` is refused here with an error naming `grid-wrap`. The Python
//! drop-in (`map_coordinates`, the resampling functions) and `splinelab
//! check interp` compute scipy's `wrap` as scipy does: the [`Mode::Mirror`]
//! spline, evaluated at points folded with period `ν − 1`.
//!
//! For every `Mode` the interpolation condition is imposed on the whole extended
//! signal, so each mode defines one exact spline on all of ℝ. Evaluation
//! outside `[0, ν − 1]` follows scipy's `map_coordinates`: the symmetric and
//! periodic modes fold the point (the spline has the same symmetry), and
//! `nearest` and `grid-constant` evaluate the spline of the edge- or
//! constant-extended signal where it is (scipy approximates both by padding
//! 12 samples before its filter: it differs from the exact spline by about
//! `ρ^{24}` of the data near the ends, 2⁻³¹ for quintics). Degrees 0 and 1
//! need no prefilter and clamp the point under `nearest`, as scipy does.
//!
//! scipy's `spline_filter1d` has no edge or constant extension: it filters
//! `nearest` with the `reflect` rule and `grid-constant` with the `mirror`
//! rule. Our coefficients for those two modes are the exact ones of the
//! extended signal (the ones scipy's `map_coordinates` approximates).

use crate::sspline::end_conditions::EndRule;
use std::fmt;
use std::str::FromStr;

/// A boundary mode (see the module documentation for the table).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Mode {
    /// Whole-sample symmetric (scipy `mirror`, its default for filters).
    Mirror,
    /// Half-sample symmetric (scipy `reflect` / `grid-mirror`).
    Reflect,
    /// Periodic with period `ν` (scipy `grid-wrap`).
    GridWrap,
    /// Repeat the end samples (scipy `nearest`).
    Nearest,
    /// A constant `cval` beyond the ends (scipy `grid-constant`).
    GridConstant,
}

/// An unknown mode name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", describe_unknown(.0))]
pub struct UnknownMode(pub String);

fn describe_unknown(name: &str) -> String {
    if name == "wrap" {
        // A silent alias would give O(1) differences to scipy.
        return "mode \"wrap\" is scipy's other periodic mode (it filters with the mirror rule and \
                wraps points with period ν − 1): use grid-wrap (period ν)"
            .to_string();
    }
    format!(
        "unknown mode {name:?}: expected mirror, reflect (grid-mirror), grid-wrap, nearest or grid-constant"
    )
}

impl Mode {
    /// Every mode, in the order of the table.
    pub const ALL: [Mode; 5] = [
        Mode::Mirror,
        Mode::Reflect,
        Mode::GridWrap,
        Mode::Nearest,
        Mode::GridConstant,
    ];

    /// scipy's name.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Mirror => "mirror",
            Mode::Reflect => "reflect",
            Mode::GridWrap => "grid-wrap",
            Mode::Nearest => "nearest",
            Mode::GridConstant => "grid-constant",
        }
    }

    /// The paper's end rule with the same extension, where there is one.
    pub fn end_rule(self) -> Option<EndRule> {
        match self {
            Mode::Mirror => Some(EndRule::Reflect),
            Mode::GridWrap => Some(EndRule::Periodic),
            Mode::Nearest => Some(EndRule::Free),
            Mode::Reflect | Mode::GridConstant => None,
        }
    }

    /// The sample index that `s_i` repeats for `len = ν ≥ 1` samples, or
    /// `None` where the extension is the constant (`grid-constant` outside).
    /// Cost `O(1)`.
    ///
    ///
    /// **Method**: the index modulo the mode's period (`2ν − 2`, `2ν`, `ν`) reflected into `[0,
    /// ν)`. **Accuracy**: exact (integer arithmetic). **Source**: scipy's boundary extensions
    /// (`ni_support.c`, `NI_ExtendLine`).
    ///
    /// ```
    /// use splinelab::ndimage::mode::Mode;
    /// let idx = |m: Mode| (-3..7).map(|i| m.fold(i, 4)).collect::<Vec<_>>();
    /// assert_eq!(idx(Mode::Mirror), [3, 2, 1, 0, 1, 2, 3, 2, 1, 0].map(Some));
    /// assert_eq!(idx(Mode::Reflect), [2, 1, 0, 0, 1, 2, 3, 3, 2, 1].map(Some));
    /// assert_eq!(idx(Mode::GridWrap), [1, 2, 3, 0, 1, 2, 3, 0, 1, 2].map(Some));
    /// assert_eq!(idx(Mode::Nearest), [0, 0, 0, 0, 1, 2, 3, 3, 3, 3].map(Some));
    /// assert_eq!(Mode::GridConstant.fold(-1, 4), None);
    /// ```
    #[inline]
    pub fn fold(self, i: i64, len: usize) -> Option<usize> {
        let n = len as i64;
        if (0..n).contains(&i) {
            return Some(i as usize);
        }
        Some(match self {
            Mode::Mirror if n == 1 => 0,
            Mode::Mirror => {
                let r = i.rem_euclid(2 * n - 2);
                (if r < n { r } else { 2 * n - 2 - r }) as usize
            }
            Mode::Reflect => {
                let r = i.rem_euclid(2 * n);
                (if r < n { r } else { 2 * n - 1 - r }) as usize
            }
            Mode::GridWrap => i.rem_euclid(n) as usize,
            Mode::Nearest => i.clamp(0, n - 1) as usize,
            Mode::GridConstant => return None,
        })
    }

    /// [`Self::fold`] of `from, from + 1, from + 2, …` in turn, for `len ≥ 1`
    /// samples: one division for the first index, then a step along the
    /// period. The causal starts walk `fold(−j)` for every `j` below a
    /// pole's horizon (28 for a cubic in `f64`), and on short lines that
    /// division was a visible part of a small call (issue 50). Cost `O(1)`
    /// per index.
    ///
    /// ```
    /// use splinelab::ndimage::mode::Mode;
    /// for m in Mode::ALL {
    ///     let walked: Vec<_> = m.folds(-9, 4).take(20).collect();
    ///     let each: Vec<_> = (-9..11).map(|i| m.fold(i, 4)).collect();
    ///     assert_eq!(walked, each);
    /// }
    /// ```
    pub fn folds(self, from: i64, len: usize) -> Folds {
        let n = len as i64;
        let period = match self {
            Mode::Mirror if n >= 2 => 2 * n - 2,
            Mode::Reflect if n >= 1 => 2 * n,
            Mode::GridWrap if n >= 1 => n,
            _ => 0,
        };
        Folds {
            mode: self,
            len,
            i: from,
            r: if period > 0 {
                from.rem_euclid(period)
            } else {
                0
            },
            period,
        }
    }

    /// Maps a coordinate `x` to the one the interpolant is evaluated at
    /// (scipy's `map_coordinates` rule): folded into `[0, ν − 1]`
    /// (`mirror`), `[−½, ν − ½]` (`reflect`, `grid-wrap`) or clamped to
    /// `[0, ν − 1]` (`nearest`; the interpolant clamps degrees ≥ 2 only
    /// far outside, see [`Mode`]); for `grid-constant` unchanged within
    /// `2^40` of the grid and clamped there beyond (every B-spline window that
    /// far reads only the constant outside, so the value is the same, and the
    /// cell index stays far from `i64` overflow). `f64` arithmetic on the
    /// period, exact when `x` is (`|x| < 2^52`).
    ///
    /// **Method**: the coordinate modulo the period, reflected into the fundamental interval.
    #[inline]
    pub fn fold_coordinate(self, x: f64, len: usize) -> f64 {
        /// Far beyond any padding (pads are at most a few thousand samples).
        const FAR_CONSTANT: f64 = (1u64 << 40) as f64;
        let n = len as f64;
        match self {
            Mode::Mirror if len == 1 => 0.0,
            Mode::Mirror => {
                // Reflections about 0 and ν − 1; `−r` and `p − r` are exact
                // (Sterbenz), so points within one period fold exactly.
                let p = 2.0 * (n - 1.0);
                let r = if x.abs() <= p { x } else { x.rem_euclid(p) };
                let r = r.abs();
                if r <= n - 1.0 { r } else { p - r }
            }
            Mode::Reflect => {
                // Reflections about −½ and ν − ½.
                let p = 2.0 * n;
                let r = if x >= -p - 0.5 && x <= p - 0.5 {
                    x
                } else {
                    // `x mod p` is exact; `x + 0.5` is not beyond 2^52
                    // (it would shift the fold by half a sample).
                    let r = x.rem_euclid(p);
                    if r >= p - 0.5 { r - p } else { r }
                };
                let r = if r < -0.5 { -1.0 - r } else { r };
                if r <= n - 0.5 { r } else { p - 1.0 - r }
            }
            Mode::GridWrap if x >= -0.5 && x <= n - 0.5 => x,
            Mode::GridWrap if x < -0.5 && x >= -0.5 - n => x + n,
            Mode::GridWrap if x > n - 0.5 && x <= 2.0 * n - 0.5 => x - n,
            Mode::GridWrap => {
                // Exact, as for `reflect` (no `x + 0.5`).
                let r = x.rem_euclid(n);
                if r >= n - 0.5 { r - n } else { r }
            }
            Mode::Nearest => x.clamp(0.0, n - 1.0),
            Mode::GridConstant => x.clamp(-FAR_CONSTANT, n + FAR_CONSTANT),
        }
    }

    /// The sample scipy's `map_coordinates(order=0)` returns at `x`: the
    /// point mapped by scipy's coordinate rule (`ni_interpolation.c`:
    /// symmetric and periodic modes fold only points outside `[0, ν − 1]`,
    /// and the negative side of `mirror`/`reflect` by negation, so ties at
    /// half-integers go where scipy sends them), rounded to the nearest
    /// integer with ties up, that index extended by the mode (`None`:
    /// `cval`). The rounding is exact (`⌊y⌋` and `y − ⌊y⌋` are), where
    /// scipy forms `⌊y + ½⌋` in `f64`: the two differ only where `y + ½`
    /// rounds up to an integer, e.g. `y = ½ − 2^{−54}` (scipy: 1, here 0).
    ///
    /// ```
    /// use splinelab::ndimage::mode::Mode;
    /// assert_eq!(Mode::Mirror.nearest_index(8.5, 9), Some(7));
    /// assert_eq!(Mode::Mirror.nearest_index(-2.5, 9), Some(3));
    /// assert_eq!(Mode::GridConstant.nearest_index(-0.5, 9), Some(0));
    /// assert_eq!(Mode::GridConstant.nearest_index(-0.51, 9), None);
    /// // Exact rounding where scipy's f64 `⌊y + ½⌋` gives 1.
    /// assert_eq!(Mode::Mirror.nearest_index(0.5 - 2f64.powi(-54), 9), Some(0));
    /// ```
    pub fn nearest_index(self, x: f64, len: usize) -> Option<usize> {
        let n = len as f64;
        let y = match self {
            Mode::Mirror if len == 1 => 0.0,
            Mode::Mirror if x < 0.0 => {
                let (p, r) = (2.0 * n - 2.0, (-x).rem_euclid(2.0 * n - 2.0));
                if r < n - 1.0 { r } else { p - r }
            }
            Mode::Mirror if x > n - 1.0 => {
                let (p, r) = (2.0 * n - 2.0, x.rem_euclid(2.0 * n - 2.0));
                if r < n { r } else { p - r }
            }
            Mode::Reflect if x < 0.0 => {
                let p = 2.0 * n;
                let r = (-x).rem_euclid(p);
                let r = if r == 0.0 { p } else { r };
                if r > n { p - r } else { r - 1.0 }
            }
            Mode::Reflect if x > n - 1.0 => {
                let r = x.rem_euclid(2.0 * n);
                if r >= n { 2.0 * n - r - 1.0 } else { r }
            }
            Mode::GridWrap if x < 0.0 || x > n - 1.0 => x.rem_euclid(n),
            _ => self.fold_coordinate(x, len),
        };
        let fl = y.floor();
        let i = fl as i64 + i64::from(y - fl >= 0.5);
        self.fold(i, len)
    }
}

/// The folded indices of [`Mode::folds`] (an endless iterator: `take` the
/// ones wanted).
#[derive(Debug, Clone)]
pub struct Folds {
    mode: Mode,
    len: usize,
    /// The index to fold next.
    i: i64,
    /// `i` modulo `period` (periodic modes).
    r: i64,
    /// The mode's period, 0 where it has none (or `len` is too short).
    period: i64,
}

impl Iterator for Folds {
    type Item = Option<usize>;

    #[inline(always)]
    fn next(&mut self) -> Option<Option<usize>> {
        let (n, r) = (self.len as i64, self.r);
        let folded = match self.mode {
            _ if self.period == 0 => self.mode.fold(self.i, self.len),
            Mode::Mirror => Some((if r < n { r } else { self.period - r }) as usize),
            Mode::Reflect => Some((if r < n { r } else { self.period - 1 - r }) as usize),
            _ => Some(r as usize),
        };
        self.i += 1;
        self.r = if r + 1 == self.period { 0 } else { r + 1 };
        Some(folded)
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = UnknownMode;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Ok(match s {
            "mirror" => Mode::Mirror,
            "reflect" | "grid-mirror" => Mode::Reflect,
            "grid-wrap" => Mode::GridWrap,
            "nearest" => Mode::Nearest,
            "grid-constant" => Mode::GridConstant,
            _ => return Err(UnknownMode(s.to_string())),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        /// The walk gives `fold` of every index, across many periods,
        /// from any start (negative, inside, beyond), for short lines too.
        #[test]
        fn folds_walk_as_fold_does(from in -300i64..300, len in 1usize..40, count in 0usize..400) {
            for m in Mode::ALL {
                let walked: Vec<_> = m.folds(from, len).take(count).collect();
                let each: Vec<_> = (from..from + count as i64).map(|i| m.fold(i, len)).collect();
                proptest::prop_assert_eq!(walked, each, "{} len {}", m, len);
            }
        }
    }

    #[test]
    fn scipy_wrap_is_refused_and_names_grid_wrap() {
        let e = "wrap".parse::<Mode>().unwrap_err().to_string();
        assert!(
            e.contains("use grid-wrap") && e.contains("mirror rule"),
            "{e}"
        );
        let e = "periodic".parse::<Mode>().unwrap_err().to_string();
        assert!(e.starts_with("unknown mode \"periodic\""), "{e}");
        for m in Mode::ALL {
            assert_eq!(m.name().parse::<Mode>(), Ok(m));
        }
        assert_eq!("grid-mirror".parse::<Mode>(), Ok(Mode::Reflect));
    }
}
