//! Error-free transformations of f64 arithmetic.
//!
//! Each returns `(s, e)` with `s` the rounded result and `e` the rounding
//! error, so that `s + e` equals the exact result (no overflow assumed).
//! References: Knuth TAOCP vol. 2 §4.2.2 (TwoSum), Dekker 1971 (FastTwoSum),
//! Ogita–Rump–Oishi, *Accurate sum and dot product*, SIAM J. Sci. Comput. 26
//! (2005) (TwoProd via fused multiply-add).

/// TwoSum (Knuth): `a + b = s + e` exactly, for any finite `a`, `b` whose sum
/// does not overflow. 6 flops, no branch.
///
/// ```
/// use splinelab::scalar::two_sum;
/// let (s, e) = two_sum(1.0, 1e-20);
/// assert_eq!((s, e), (1.0, 1e-20));
/// ```
pub fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// FastTwoSum (Dekker): `a + b = s + e` exactly, provided `|a| ≥ |b|` (or
/// `a == 0`). 3 flops. Callers that cannot guarantee the ordering use
/// [`two_sum`].
///
/// ```
/// use splinelab::scalar::fast_two_sum;
/// // 2 + ε/4 is not representable: it rounds to 2, and the error is ε/4.
/// let (s, e) = fast_two_sum(2.0, f64::EPSILON / 4.0);
/// assert_eq!((s, e), (2.0, f64::EPSILON / 4.0));
/// ```
pub fn fast_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let e = b - (s - a);
    (s, e)
}

/// TwoProd: `a · b = p + e` exactly, using one fused multiply-add
/// (`e = fma(a, b, −p)`). Exact unless `a·b` overflows or `e` underflows
/// (needs `e_a + e_b ≥ −1022 + 53`).
///
/// ```
/// use splinelab::scalar::two_prod;
/// let x = 1.0 + f64::EPSILON;
/// let (p, e) = two_prod(x, x); // (1+ε)² = 1 + 2ε + ε²
/// assert_eq!(p, 1.0 + 2.0 * f64::EPSILON);
/// assert_eq!(e, f64::EPSILON * f64::EPSILON);
/// ```
pub fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let e = a.mul_add(b, -p);
    (p, e)
}
