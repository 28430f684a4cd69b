//! Input validation shared by every constructor: one error type for "too few
//! points" and "not finite", and the small checks that produce it.
//!
//! Each module's error enum embeds [`InputError`] through `#[from]` (e.g.
//! [`CurveError::Input`](crate::curves::CurveError::Input)), so a check is
//! written once here and its message reads the same everywhere.

use crate::scalar::Real;
use nalgebra::{DMatrix, SVector};

/// Why an input was refused before any computation: one shape for all
/// modules.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum InputError {
    /// Fewer points than the construction needs.
    #[error("{what} needs at least {needed} point{}, got {got}", plural(*needed))]
    TooFewPoints {
        /// The construction (e.g. "a Catmull–Rom spline").
        what: &'static str,
        /// Minimum number of points.
        needed: usize,
        /// Points given.
        got: usize,
    },
    /// A degree below what the construction needs.
    #[error("{what} needs degree ≥ {min}, got {got}")]
    DegreeTooSmall {
        /// The construction (e.g. "a Bézier patch").
        what: &'static str,
        /// The smallest degree it takes.
        min: usize,
        /// The degree given.
        got: usize,
    },
    /// An element of a list (point, knot, sample, …) has a NaN or infinite
    /// coordinate.
    #[error("{what} {index} is not finite")]
    NonFiniteAt {
        /// What the list holds (e.g. "point", "knot").
        what: &'static str,
        /// Position of the offending element.
        index: usize,
    },
    /// An entry of a matrix (a right-hand side, a matrix whose condition is
    /// asked) is NaN or infinite.
    #[error("{what} entry ({row}, {col}) is not finite")]
    NonFiniteEntry {
        /// What the matrix is (e.g. "right-hand side").
        what: &'static str,
        /// Row of the first offending entry (column-major order).
        row: usize,
        /// Its column.
        col: usize,
    },
    /// A single named input (parameter, radius, tangent) is NaN or infinite.
    #[error("{name} is not finite")]
    NonFinite {
        /// Which input.
        name: &'static str,
    },
}

/// Which non-finite value a sample holds, for messages that name it
/// ("sample 34 is not finite (nan)"): comparable (unlike NaN itself).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NonFiniteValue {
    /// Not a number.
    Nan,
    /// `+∞`.
    Inf,
    /// `−∞`.
    NegInf,
}

impl NonFiniteValue {
    /// The kind of `x`, `None` where `x` is finite.
    ///
    /// ```
    /// use splinelab::validation::NonFiniteValue;
    /// assert_eq!(NonFiniteValue::of(&f64::NEG_INFINITY), Some(NonFiniteValue::NegInf));
    /// assert_eq!(NonFiniteValue::of(&1.5f32), None);
    /// assert_eq!(NonFiniteValue::Nan.to_string(), "nan");
    /// ```
    pub fn of<T: Real>(x: &T) -> Option<Self> {
        if x.is_finite() {
            return None;
        }
        let v = x.to_f64();
        Some(if v.is_nan() {
            NonFiniteValue::Nan
        } else if v > 0.0 {
            NonFiniteValue::Inf
        } else {
            NonFiniteValue::NegInf
        })
    }
}

impl std::fmt::Display for NonFiniteValue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            NonFiniteValue::Nan => "nan",
            NonFiniteValue::Inf => "inf",
            NonFiniteValue::NegInf => "-inf",
        })
    }
}

fn plural(n: usize) -> &'static str {
    if n == 1 { "" } else { "s" }
}

/// `Ok` when `got ≥ needed`, else [`InputError::TooFewPoints`].
///
/// ```
/// use splinelab::validation::{InputError, at_least};
/// assert!(at_least("a curve", 2, 2).is_ok());
/// let e = at_least("a curve", 2, 1).unwrap_err();
/// assert_eq!(e, InputError::TooFewPoints { what: "a curve", needed: 2, got: 1 });
/// assert_eq!(e.to_string(), "a curve needs at least 2 points, got 1");
/// ```
pub fn at_least(what: &'static str, needed: usize, got: usize) -> Result<(), InputError> {
    if got >= needed {
        Ok(())
    } else {
        Err(InputError::TooFewPoints { what, needed, got })
    }
}

/// `Ok` when `got ≥ min`, else [`InputError::DegreeTooSmall`].
///
/// ```
/// use splinelab::validation::{InputError, degree_at_least};
/// assert!(degree_at_least("a patch", 1, 1).is_ok());
/// let e = degree_at_least("a patch", 1, 0).unwrap_err();
/// assert_eq!(e, InputError::DegreeTooSmall { what: "a patch", min: 1, got: 0 });
/// assert_eq!(e.to_string(), "a patch needs degree ≥ 1, got 0");
/// ```
pub fn degree_at_least(what: &'static str, min: usize, got: usize) -> Result<(), InputError> {
    if got >= min {
        Ok(())
    } else {
        Err(InputError::DegreeTooSmall { what, min, got })
    }
}

/// `Ok` when `x` is finite, else [`InputError::NonFinite`] naming it.
pub fn finite<T: Real>(name: &'static str, x: &T) -> Result<(), InputError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(InputError::NonFinite { name })
    }
}

/// `Ok` when every scalar is finite, else [`InputError::NonFiniteAt`] at the
/// first that is not. **Cost** one pass.
pub fn finite_scalars<T: Real>(what: &'static str, xs: &[T]) -> Result<(), InputError> {
    first_failing(what, xs.iter().map(|x| x.is_finite()))
}

/// `Ok` when every coordinate of every point is finite, else
/// [`InputError::NonFiniteAt`] at the first point that is not.
///
/// ```
/// use nalgebra::Vector2;
/// use splinelab::validation::{InputError, finite_points};
/// let p = [Vector2::new(0.0, 1.0), Vector2::new(f64::NAN, 0.0)];
/// assert_eq!(finite_points("point", &p), Err(InputError::NonFiniteAt { what: "point", index: 1 }));
/// ```
pub fn finite_points<T: Real, const D: usize>(
    what: &'static str,
    points: &[SVector<T, D>],
) -> Result<(), InputError> {
    first_failing(what, points.iter().map(|p| p.iter().all(|x| x.is_finite())))
}

/// [`finite`] for every coordinate of one vector (a tangent, a centre).
pub fn finite_vector<T: Real, const D: usize>(
    name: &'static str,
    v: &SVector<T, D>,
) -> Result<(), InputError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(InputError::NonFinite { name })
    }
}

/// [`finite`] for one scalar that sits at `index` of a list, when the list
/// is checked element by element together with other conditions.
pub fn finite_at<T: Real>(what: &'static str, index: usize, x: &T) -> Result<(), InputError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(InputError::NonFiniteAt { what, index })
    }
}

/// `Ok` when every entry of `a` is finite, else
/// [`InputError::NonFiniteEntry`] at the first that is not, in column-major
/// order (nalgebra's storage order). **Cost** one pass.
///
/// ```
/// use nalgebra::DMatrix;
/// use splinelab::scalar::{Mp, Real};
/// use splinelab::validation::{InputError, finite_entries};
/// let nan = Mp::<128>::from_f64_exact(f64::NAN);
/// let one = Mp::<128>::from_f64_exact(1.0);
/// let a = DMatrix::from_row_slice(2, 2, &[one.clone(), one.clone(), nan, one]);
/// let e = finite_entries("matrix", &a).unwrap_err();
/// assert_eq!(e, InputError::NonFiniteEntry { what: "matrix", row: 1, col: 0 });
/// assert_eq!(e.to_string(), "matrix entry (1, 0) is not finite");
/// ```
pub fn finite_entries<T: Real>(what: &'static str, a: &DMatrix<T>) -> Result<(), InputError> {
    match a.iter().position(|x| !x.is_finite()) {
        Some(k) => Err(InputError::NonFiniteEntry {
            what,
            row: k % a.nrows(),
            col: k / a.nrows(),
        }),
        None => Ok(()),
    }
}

/// [`finite_points`] for one point that sits at `index` of a list (an
/// edited data point).
pub fn finite_point_at<T: Real, const D: usize>(
    what: &'static str,
    index: usize,
    p: &SVector<T, D>,
) -> Result<(), InputError> {
    finite_points(what, std::slice::from_ref(p))
        .map_err(|_| InputError::NonFiniteAt { what, index })
}

fn first_failing(what: &'static str, mut ok: impl Iterator<Item = bool>) -> Result<(), InputError> {
    match ok.position(|f| !f) {
        Some(index) => Err(InputError::NonFiniteAt { what, index }),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;

    #[test]
    fn too_few_reads_in_the_singular_for_one() {
        let one = at_least("a curve", 1, 0).unwrap_err().to_string();
        assert_eq!(one, "a curve needs at least 1 point, got 0");
        let two = at_least("a curve", 2, 0).unwrap_err().to_string();
        assert_eq!(two, "a curve needs at least 2 points, got 0");
    }

    #[test]
    fn matrix_entries_are_found_in_column_major_order() {
        let mut a = nalgebra::DMatrix::from_element(3, 2, 1.0f64);
        assert!(finite_entries("m", &a).is_ok());
        a[(2, 1)] = f64::INFINITY;
        a[(0, 1)] = f64::NAN;
        let e = finite_entries("m", &a).unwrap_err();
        assert_eq!(
            e,
            InputError::NonFiniteEntry {
                what: "m",
                row: 0,
                col: 1
            }
        );
        a[(2, 0)] = f64::NAN;
        let e = finite_entries("m", &a).unwrap_err();
        assert_eq!(
            e,
            InputError::NonFiniteEntry {
                what: "m",
                row: 2,
                col: 0
            }
        );
    }

    #[test]
    fn checks_refuse_nan_and_infinities_in_f64_and_mpfr() {
        for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(finite("t", &x), Err(InputError::NonFinite { name: "t" }));
            let m = Mp::<64>::from_f64_exact(x);
            assert_eq!(finite("t", &m), Err(InputError::NonFinite { name: "t" }));
            let xs = [1.0, 2.0, x, x];
            let e = finite_scalars("knot", &xs).unwrap_err();
            assert_eq!(
                e,
                InputError::NonFiniteAt {
                    what: "knot",
                    index: 2
                }
            );
            assert_eq!(e.to_string(), "knot 2 is not finite");
        }
        assert!(finite_scalars::<f64>("knot", &[]).is_ok());
        assert_eq!(
            finite_at("node", 3, &f64::NAN),
            Err(InputError::NonFiniteAt {
                what: "node",
                index: 3
            })
        );
        assert!(finite_at("node", 3, &-f64::MAX).is_ok());
        assert!(finite("t", &f64::MAX).is_ok());
    }
}
