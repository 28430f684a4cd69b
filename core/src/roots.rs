//! Roots of real polynomials whose roots are all real (hyperbolic
//! polynomials), in any working precision.
//!
//! Method: Laguerre's iteration with Maehly's implicit deflation. For a
//! polynomial of degree `n` with only real roots, Laguerre's step from a point
//! to the right of all roots moves monotonically to the largest root and
//! converges cubically near it (Laguerre; see Parlett, *Laguerre's method
//! applied to the matrix eigenvalue problem*, Math. Comp. 18 (1964), and
//! Wilkinson, *The Algebraic Eigenvalue Problem*, §7.12). Roots found earlier
//! are removed *implicitly* — by subtracting `Σ 1/(x − r_j)` from `p'/p` and
//! `Σ 1/(x − r_j)²` from `−(p'/p)'` — so each root is computed from the
//! original coefficients: no deflated polynomial carries earlier errors
//! forward (Maehly 1954). A final non-deflated Laguerre step polishes each
//! root against `p` itself.
//!
//! Cost: `O(n)` per iteration (Horner for `p, p', p''`) plus `O(k)` for the
//! implicit deflation of `k` known roots; a handful of iterations per root.
//!
//! Accuracy: each root to its attainable accuracy, about
//! `u · Σ|a_j||r|^j / |r·p'(r)|` relative (the root's condition number times
//! the unit roundoff `u` of the scalar), since the iteration stops only when
//! its step is at the rounding-noise level of `p`.

use crate::scalar::Real;
use crate::validation::{InputError, finite_scalars};

/// Why a root computation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RootsError {
    /// More roots were requested than the polynomial's degree.
    #[error("{wanted} roots requested from a polynomial of degree {degree}")]
    TooManyRoots {
        /// Degree of the polynomial.
        degree: usize,
        /// Number of roots requested.
        wanted: usize,
    },
    /// A coefficient is NaN or infinite.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The leading coefficient is zero (or there is none): the list's length
    /// does not give the degree.
    #[error("coefficient {index}, the leading one, is zero or missing")]
    ZeroLeading {
        /// Index of the leading coefficient (power of x).
        index: usize,
    },
    /// The iteration did not settle within its iteration limit.
    #[error("Laguerre iteration for root {index} did not converge in {iterations} steps")]
    NoConvergence {
        /// 0-based index (in descending order) of the root being sought.
        index: usize,
        /// Iterations spent.
        iterations: usize,
    },
    /// The start point is not to the right of the roots, or the polynomial
    /// visibly has non-real roots.
    #[error("the polynomial is not real-rooted to the right of the start point (at x ≈ {at})")]
    NotRealRooted {
        /// Where the violation was seen (rounded to f64).
        at: f64,
    },
}

/// Horner evaluation of `p(x) = Σ a_j x^j` (ascending coefficients) and its
/// first two derivatives, in `3n` multiply-adds.
///
/// ```
/// use splinelab::roots::eval_with_derivatives;
/// // p = 1 + 2x + 3x²  at x = 2: 17, p' = 14, p'' = 6.
/// let (p, d1, d2) = eval_with_derivatives(&[1.0, 2.0, 3.0], &2.0);
/// assert_eq!((p, d1, d2), (17.0, 14.0, 6.0));
/// ```
pub fn eval_with_derivatives<T: Real>(a: &[T], x: &T) -> (T, T, T) {
    let mut p = T::zero();
    let mut d1 = T::zero();
    let mut d2 = T::zero();
    for c in a.iter().rev() {
        d2 = d2 * x.clone() + &d1;
        d1 = d1 * x.clone() + &p;
        p = p * x.clone() + c;
    }
    (p, d1, d2.clone() + d2)
}

/// The `count` largest roots, in descending order, of `p(x) = Σ a_j x^j`
/// (ascending coefficients), assuming all roots of `p` are real and simple
/// enough to be separated at the working precision, and `start` lies to the
/// right of every root.
///
/// Method, cost and accuracy: see the [module documentation](self).
///
/// **Accuracy**: tested in `roots.rs::tests::wilkinson_like_integers_in_mp`. **Source**:
/// Laguerre's method with implicit deflation (Press et al., *Numerical
/// Recipes*, 3rd ed. (2007), §9.5).
///
/// ```
/// use splinelab::roots::largest_real_roots;
/// // (x + 1)(x + 2)(x + 3) = 6 + 11x + 6x² + x³
/// let r = largest_real_roots(&[6.0, 11.0, 6.0, 1.0], 3, &0.0).unwrap();
/// // Attainable accuracy: u·Σ|a_j||r|^j/|p'(r)| ≈ 1e-14 at r = −2.
/// for (k, root) in r.iter().enumerate() {
///     assert!((root + (k + 1) as f64).abs() < 2e-14);
/// }
/// ```
pub fn largest_real_roots<T: Real>(a: &[T], count: usize, start: &T) -> Result<Vec<T>, RootsError> {
    check_coefficients(a)?;
    let degree = a.len() - 1;
    if count > degree {
        return Err(RootsError::TooManyRoots {
            degree,
            wanted: count,
        });
    }
    let mut roots: Vec<T> = Vec::with_capacity(count);
    for index in 0..count {
        let r = laguerre(a, &roots, start.clone(), index)?;
        roots.push(polish(a, r));
    }
    Ok(roots)
}

/// The `count` roots in (−1, 0) of a *palindromic* polynomial
/// (`a_j = a_{d−j}`) whose roots are all real and negative, hence come in
/// reciprocal pairs `ξ, 1/ξ` — ordered from the one nearest 0 to the one
/// nearest −1.
///
/// Method: Laguerre with implicit deflation, as in [`largest_real_roots`],
/// but every search starts at `x = −1`, the centre of the reciprocal
/// pairs: by symmetry `p'/p(−1) = −d/2 < 0`, so the step goes right, to the
/// inner root nearest −1; that root *and its reciprocal* are then deflated.
/// Starting at 0 instead would put tiny roots (down to `10⁻¹⁸` for
/// Euler–Frobenius polynomials of order 60) next to the start point, and
/// their deflation terms `1/x²` would swamp `p''/p` in `f64`. Cost and
/// accuracy as for [`largest_real_roots`].
///
/// **Accuracy**: the Euler–Frobenius poles to `1e-72` relative in MPFR
/// (`euler_frobenius.rs::tests::published_poles`). **Source**: seed 000 eq 16
/// (reciprocal pole pairs).
///
/// ```
/// use splinelab::roots::palindromic_inner_roots;
/// // z² + 4z + 1: roots −2 ± √3.
/// let r = palindromic_inner_roots(&[1.0f64, 4.0, 1.0], 1).unwrap();
/// assert!((r[0] + 0.2679491924311227).abs() < 1e-16);
/// ```
///
/// ```
/// use splinelab::roots::palindromic_inner_roots;
/// // In MPFR: z² + 4z + 1 has the inner root √3 − 2, to 256-bit rounding.
/// use splinelab::nalgebra::ComplexField;
/// use splinelab::scalar::{Mp, Real};
/// type M = Mp<256>;
/// let a = [1, 4, 1].map(M::from_int);
/// let r = palindromic_inner_roots(&a, 1).unwrap();
/// assert!((r[0].clone() - (M::from_int(3).sqrt() - M::from_int(2))).to_f64().abs() < 1e-74);
/// ```
pub fn palindromic_inner_roots<T: Real>(a: &[T], count: usize) -> Result<Vec<T>, RootsError> {
    check_coefficients(a)?;
    let degree = a.len() - 1;
    if 2 * count > degree {
        return Err(RootsError::TooManyRoots {
            degree,
            wanted: 2 * count,
        });
    }
    let mut known: Vec<T> = Vec::with_capacity(2 * count);
    let mut inner: Vec<T> = Vec::with_capacity(count);
    for index in 0..count {
        let r = polish(a, laguerre(a, &known, -T::one(), index)?);
        let (inside, outside) = if r.clone().abs() < T::one() {
            (r.clone(), r.recip())
        } else {
            (r.clone().recip(), r)
        };
        known.push(inside.clone());
        known.push(outside);
        inner.push(inside);
    }
    inner.reverse();
    Ok(inner)
}

fn check_coefficients<T: Real>(a: &[T]) -> Result<(), RootsError> {
    finite_scalars("coefficient", a)?;
    match a.last() {
        Some(lead) if !lead.is_zero() => Ok(()),
        _ => Err(RootsError::ZeroLeading {
            index: a.len().saturating_sub(1),
        }),
    }
}

/// One Laguerre step for `p / Π(x − r_j)`; `None` when `x` is a root of `p`.
fn laguerre_step<T: Real>(a: &[T], known: &[T], x: &T) -> Option<T> {
    let (p, d1, d2) = eval_with_derivatives(a, x);
    if p.is_zero() {
        return None;
    }
    let g_full = d1 / p.clone();
    let mut g = g_full.clone();
    let mut h = g_full.clone() * g_full - d2 / p;
    for r in known {
        let inv = T::one() / (x.clone() - r);
        g -= inv.clone();
        h -= inv.clone() * inv;
    }
    let n = T::from_int((a.len() - 1 - known.len()) as i64);
    let disc = (n.clone() - T::one()) * (n.clone() * h - g.clone() * &g);
    // A real-rooted polynomial has disc ≥ 0; a tiny negative value is rounding.
    let root = if disc > T::zero() {
        disc.sqrt()
    } else {
        T::zero()
    };
    let denom = if g >= T::zero() { g + root } else { g - root };
    if denom.is_zero() {
        return None;
    }
    Some(n / denom)
}

fn laguerre<T: Real>(a: &[T], known: &[T], start: T, index: usize) -> Result<T, RootsError> {
    const MAX_ITER: usize = 500;
    let u = T::unit_roundoff();
    let noise = u.clone().sqrt();
    let mut x = start;
    let mut prev_step: Option<T> = None;
    for _ in 0..MAX_ITER {
        let Some(step) = laguerre_step(a, known, &x) else {
            return Ok(x);
        };
        if !step.is_finite() {
            return Err(RootsError::NotRealRooted { at: x.to_f64() });
        }
        let size = step.clone().abs();
        let scale = x.clone().abs();
        x -= step;
        if size <= u.clone() * T::from_int(4) * scale.clone() {
            return Ok(x);
        }
        // In the rounding-noise regime the step stops shrinking: accept.
        if let Some(prev) = prev_step
            && size >= prev
            && prev <= noise.clone() * scale
        {
            return Ok(x);
        }
        prev_step = Some(size);
    }
    Err(RootsError::NoConvergence {
        index,
        iterations: MAX_ITER,
    })
}

/// Two non-deflated Laguerre steps against `p` itself, kept only while they
/// are small (`< 2^{−16}|x|`) and reduce `|p|`, removing any bias the
/// implicit deflation left.
fn polish<T: Real>(a: &[T], mut x: T) -> T {
    for _ in 0..2 {
        let Some(step) = laguerre_step(a, &[], &x) else {
            return x;
        };
        // A refinement, never a jump to another root through noisy values.
        if step.clone().abs() > x.clone().abs().scale_by_pow2(-16) {
            break;
        }
        let candidate = x.clone() - step;
        let (p_new, _, _) = eval_with_derivatives(a, &candidate);
        let (p_old, _, _) = eval_with_derivatives(a, &x);
        if p_new.abs() <= p_old.abs() {
            x = candidate;
        } else {
            break;
        }
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::Mp;
    use nalgebra::ComplexField;

    #[test]
    fn wilkinson_like_integers_in_mp() {
        // Π_{k=1}^{10} (x + k): roots −1..−10 exactly; coefficients exact.
        let mut a: Vec<Mp<200>> = vec![Mp::new(1)];
        for k in 1..=10 {
            let mut next = vec![Mp::new(0); a.len() + 1];
            for (j, c) in a.iter().enumerate() {
                next[j] += c.clone() * Mp::new(k);
                next[j + 1] += c.clone();
            }
            a = next;
        }
        let r = largest_real_roots(&a, 10, &Mp::new(0)).unwrap();
        for (k, root) in r.iter().enumerate() {
            let err = (root.clone() + Mp::new(k as i64 + 1)).abs();
            assert!(err.to_f64() < 1e-50, "root {k}: {root:?}");
        }
    }

    #[test]
    fn rejects_bad_input() {
        assert_eq!(
            largest_real_roots(&[1.0, 0.0], 1, &0.0),
            Err(RootsError::ZeroLeading { index: 1 })
        );
        assert_eq!(
            largest_real_roots::<f64>(&[], 0, &0.0),
            Err(RootsError::ZeroLeading { index: 0 })
        );
        let e = largest_real_roots(&[1.0, f64::NAN, 1.0], 1, &0.0).unwrap_err();
        let at = InputError::NonFiniteAt {
            what: "coefficient",
            index: 1,
        };
        assert_eq!(e, RootsError::Input(at));
        assert_eq!(e.to_string(), "coefficient 1 is not finite");
        assert!(matches!(
            largest_real_roots(&[1.0, 1.0], 2, &0.0),
            Err(RootsError::TooManyRoots { .. })
        ));
    }
}
