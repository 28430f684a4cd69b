//! Knot vectors: finite, non-decreasing sequences `t_0 ≤ t_1 ≤ … ≤ t_m`.

use crate::scalar::Real;
use crate::validation::{InputError, finite_scalars};
use rug::Rational;
use serde::{Deserialize, Serialize};

/// Why a knot vector is invalid.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum KnotError {
    /// Fewer than two knots.
    #[error("a knot vector needs at least 2 knots, got {0}")]
    TooFew(usize),
    /// A knot is NaN or infinite.
    #[error(transparent)]
    Input(#[from] InputError),
    /// `t_index < t_{index−1}`.
    #[error("knot {index} is smaller than knot {}", index - 1)]
    Decreasing {
        /// Position of the first knot that decreases.
        index: usize,
    },
    /// More knots than can be addressed or allocated.
    #[error("{points} control points of order {order} need more knots than can be stored")]
    TooMany {
        /// The order asked for.
        order: usize,
        /// The control points asked for.
        points: usize,
    },
}

/// A validated knot vector (finite, non-decreasing, at least 2 knots).
/// Serialises as the plain list of knots; deserialising validates.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(
    try_from = "Vec<T>",
    into = "Vec<T>",
    bound(
        serialize = "T: Real + Serialize",
        deserialize = "T: Real + Deserialize<'de>"
    )
)]
pub struct KnotVector<T: Real> {
    knots: Vec<T>,
}

impl<T: Real> TryFrom<Vec<T>> for KnotVector<T> {
    type Error = KnotError;
    fn try_from(knots: Vec<T>) -> Result<Self, KnotError> {
        KnotVector::new(knots)
    }
}

impl<T: Real> From<KnotVector<T>> for Vec<T> {
    fn from(k: KnotVector<T>) -> Vec<T> {
        k.knots
    }
}

impl<T: Real> KnotVector<T> {
    /// Validates the knots.
    pub fn new(knots: Vec<T>) -> Result<Self, KnotError> {
        if knots.len() < 2 {
            return Err(KnotError::TooFew(knots.len()));
        }
        finite_scalars("knot", &knots)?;
        if let Some(w) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(KnotError::Decreasing { index: w + 1 });
        }
        Ok(KnotVector { knots })
    }

    /// Uniform knots `t_j = j`, `j = 0..count` (`count ≥ 2`).
    pub fn uniform(count: usize) -> Result<Self, KnotError> {
        Self::new((0..count).map(|j| T::from_int(j as i64)).collect())
    }

    /// Clamped uniform knots for `points` control points of order `k` on
    /// `[0, 1]`: `k` zeros, the interior knots `j/(points − k + 1)`, `k`
    /// ones (each correctly rounded). `points ≥ k ≥ 1`, else `TooFew`;
    /// `TooMany` when the `points + k` knots cannot be allocated.
    /// **Method**: the knots computed as the ratios `j/(points − k + 1)`.
    /// **Accuracy**: each knot correctly rounded (one division). **Source**:
    /// Piegl & Tiller, *The NURBS Book*, §2.2 (clamped knot vectors).
    pub fn clamped_uniform(order: usize, points: usize) -> Result<Self, KnotError> {
        let too_many = KnotError::TooMany { order, points };
        let count = points.checked_add(order).ok_or(too_many.clone())?;
        if order == 0 || points < order {
            return Err(KnotError::TooFew(count));
        }
        let mut knots = Vec::new();
        knots.try_reserve_exact(count).map_err(|_| too_many)?;
        // `count` elements fit in memory, so it fits an i64.
        let spans = (points - order + 1) as i64;
        knots.extend(std::iter::repeat_n(T::zero(), order));
        knots.extend((1..spans).map(|j| T::from_rational(&Rational::from((j, spans)))));
        knots.extend(std::iter::repeat_n(T::one(), order));
        Self::new(knots)
    }

    /// The knots.
    pub fn as_slice(&self) -> &[T] {
        &self.knots
    }

    /// Number of knots.
    pub fn len(&self) -> usize {
        self.knots.len()
    }

    /// Always false (a knot vector has at least 2 knots); for clippy's
    /// `len_without_is_empty`.
    pub fn is_empty(&self) -> bool {
        self.knots.is_empty()
    }

    /// How many knots equal `u`. **Cost** `O(log m)` (two binary searches
    /// of the sorted knots).
    pub fn multiplicity(&self, u: &T) -> usize {
        self.knots.partition_point(|t| t <= u) - self.knots.partition_point(|t| t < u)
    }

    /// Inserts `u` at `index`, the caller guaranteeing
    /// `t_{index−1} ≤ u ≤ t_index` (so the vector stays valid without a
    /// re-check). **Cost**: one move of the knots after `index`.
    pub(crate) fn insert_sorted(&mut self, index: usize, u: T) {
        debug_assert!(index == 0 || self.knots[index - 1] <= u);
        debug_assert!(index == self.knots.len() || u <= self.knots[index]);
        self.knots.insert(index, u);
    }

    /// Reserves room for `additional` more knots (see [`Vec::reserve`]).
    pub(crate) fn reserve(&mut self, additional: usize) {
        self.knots.reserve(additional);
    }

    /// The span index `i` with `t_i ≤ t < t_{i+1}` and `lo ≤ i ≤ hi`, the
    /// right end `t = t_{hi+1}` belonging to the last non-empty span `≤ hi`.
    /// `None` if `t` is outside `[t_lo, t_{hi+1}]`, not finite, or the range
    /// is empty. **Cost**: `O(log m)` (binary search).
    /// **Accuracy**: exact (comparisons only; tested in
    /// `knots.rs::tests::validation_spans_and_serde_round_trip`). **Source**:
    /// Piegl & Tiller, *The NURBS Book*, Algorithm A2.1 (FindSpan).
    pub fn span(&self, lo: usize, hi: usize, t: &T) -> Option<usize> {
        let k = &self.knots;
        if hi + 1 >= k.len()
            || lo > hi
            || !t.is_finite()
            || *t < k[lo]
            || *t > k[hi + 1]
            || k[lo] >= k[hi + 1]
        {
            return None;
        }
        // Last index i ≤ hi with t_i ≤ t and t_i < t_{i+1}.
        let mut i = (k.partition_point(|x| x <= t) - 1).min(hi);
        while k[i] >= k[i + 1] {
            i -= 1;
        }
        Some(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validation_spans_and_serde_round_trip() {
        assert_eq!(KnotVector::<f64>::new(vec![0.0]), Err(KnotError::TooFew(1)));
        assert_eq!(
            KnotVector::new(vec![0.0, f64::NAN]),
            Err(KnotError::Input(InputError::NonFiniteAt {
                what: "knot",
                index: 1
            }))
        );
        assert_eq!(
            KnotVector::new(vec![0.0, 1.0, 0.5]),
            Err(KnotError::Decreasing { index: 2 })
        );
        let k = KnotVector::clamped_uniform(3, 5).unwrap();
        assert_eq!(
            k.as_slice(),
            &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
        );
        // Domain of 5 points of order 3: spans 2..=4.
        assert_eq!(k.span(2, 4, &0.0), Some(2));
        assert_eq!(k.span(2, 4, &0.5), Some(3));
        assert_eq!(k.span(2, 4, &1.0), Some(4));
        assert_eq!(k.span(2, 4, &1.5), None);
        assert_eq!(k.multiplicity(&1.0), 3);
        let json = serde_json_like(&k);
        assert_eq!(json.len(), 8);
        let bad: Result<KnotVector<f64>, _> = KnotVector::try_from(vec![1.0, 0.0]);
        assert!(bad.is_err());
    }

    fn serde_json_like(k: &KnotVector<f64>) -> Vec<f64> {
        Vec::from(k.clone())
    }
}
