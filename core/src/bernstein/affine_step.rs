//! The de Casteljau / de Boor step `a ← a·r + b·t` and the convolution
//! step `a ← a + b`, `b ← b·c`, in place with borrowed operands.

use crate::scalar::Real;
use nalgebra::SVector;

/// `a ← a·r + b·t`: the affine combination of one de Casteljau step
/// (seed 002; `r = 1 − t`), in place and with borrowed operands.
///
/// **Rounding**: per coordinate the same operations in the same order as
/// `a.clone() * r.clone() + b.clone() * t.clone()` — two correctly rounded
/// products, then their correctly rounded sum — so results are bitwise the
/// same. **Cost**: for [`Mp`](crate::scalar::Mp) one temporary (`b·t`) per
/// coordinate, where the cloning form allocates the copies of `a`, `b`, `r`,
/// `t` and (for nalgebra vectors, whose `vector * scalar` clones every
/// coordinate and the scalar) more again.
///
/// ```
/// use splinelab::bernstein::affine_step::AffineStep;
/// use splinelab::scalar::Mp;
/// let (r, t) = (Mp::<128>::from(0.75), Mp::<128>::from(0.25));
/// let mut a = Mp::<128>::from(1.0);
/// a.affine_step(&r, &Mp::from(3.0), &t);
/// assert_eq!(a, Mp::from(1.5));
/// ```
///
/// [`scale_in_place`](Self::scale_in_place) and [`accumulate`](Self::accumulate) are the two
/// halves with no temporary at all, for a caller that owns `b` (a
/// convolution `Σ_j c_j P_j`: scale the owned copy of `P_j`, add it).
pub trait AffineStep<T> {
    /// `self ← self·r + b·t`.
    fn affine_step(&mut self, r: &T, b: &Self, t: &T);
    /// `self ← self·r` (each coordinate one correctly rounded product).
    fn scale_in_place(&mut self, r: &T);
    /// `self ← self + b` (each coordinate one correctly rounded sum).
    fn accumulate(&mut self, b: &Self);
}

impl<T: Real> AffineStep<T> for T {
    fn affine_step(&mut self, r: &T, b: &T, t: &T) {
        *self *= r;
        *self += &(b.clone() * t);
    }
    fn scale_in_place(&mut self, r: &T) {
        *self *= r;
    }
    fn accumulate(&mut self, b: &T) {
        *self += b;
    }
}

impl<T: Real, const D: usize> AffineStep<T> for SVector<T, D> {
    fn affine_step(&mut self, r: &T, b: &Self, t: &T) {
        for (a, b) in self.iter_mut().zip(b.iter()) {
            a.affine_step(r, b, t);
        }
    }
    fn scale_in_place(&mut self, r: &T) {
        for a in self.iter_mut() {
            *a *= r;
        }
    }
    fn accumulate(&mut self, b: &Self) {
        for (a, b) in self.iter_mut().zip(b.iter()) {
            *a += b;
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::scalar::Mp;
    use nalgebra::Vector3;

    /// Deterministic values in `[−1, 1]` with full 53-bit significands.
    pub(crate) fn values(n: usize) -> Vec<f64> {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        (0..n)
            .map(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
            })
            .collect()
    }

    /// The in-place step equals the cloning expression it replaces, bit for
    /// bit, for scalars and vectors in f64 and MPFR.
    fn same_as_cloning_form<T: Real>() {
        let v: Vec<T> = values(400).into_iter().map(T::from_f64_exact).collect();
        for w in v.chunks_exact(8) {
            let (r, t) = (&w[0], &w[1]);
            let mut a = w[2].clone();
            a.affine_step(r, &w[3], t);
            assert_eq!(a, w[2].clone() * r + w[3].clone() * t);
            let p = Vector3::new(w[2].clone(), w[4].clone(), w[5].clone());
            let q = Vector3::new(w[3].clone(), w[6].clone(), w[7].clone());
            let mut s = p.clone();
            s.affine_step(r, &q, t);
            assert_eq!(s, p.clone() * r.clone() + q.clone() * t.clone());
            // The convolution step of `convolve_at`: acc + b·c.
            let (mut acc, mut b) = (p.clone(), q.clone());
            b.scale_in_place(t);
            acc.accumulate(&b);
            assert_eq!(acc, p + q * t.clone());
        }
    }

    #[test]
    fn bitwise_same_as_the_cloning_form() {
        same_as_cloning_form::<f64>();
        same_as_cloning_form::<f32>();
        same_as_cloning_form::<Mp<24>>();
        same_as_cloning_form::<Mp<64>>();
    }
}
