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

/// TwoProd: `a · b = p + e` exactly. Exact unless `a·b` overflows or `e`
/// underflows (needs `e_a + e_b ≥ −1022 + 53`).
///
/// With hardware FMA (`target_feature = "fma"`) it is one fused multiply-add,
/// `e = fma(a, b, −p)`, 2 flops. Without it, `f64::mul_add` falls back to a
/// slow correctly rounded software routine, so Dekker's product (Veltkamp
/// splitting into 26-bit halves, 17 flops) is used instead; it is exact under
/// the same conditions provided `|a|, |b| < 2^995` so that the split cannot
/// overflow.
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
    (p, product_error(a, b, p))
}

#[cfg(target_feature = "fma")]
fn product_error(a: f64, b: f64, p: f64) -> f64 {
    a.mul_add(b, -p)
}

#[cfg(not(target_feature = "fma"))]
fn product_error(a: f64, b: f64, p: f64) -> f64 {
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    al * bl - (((p - ah * bh) - al * bh) - ah * bl)
}

/// Veltkamp's split `a = hi + lo` with `hi`, `lo` of at most 26 significant
/// bits each (factor `2^27 + 1`), so their pairwise products are exact.
#[cfg(not(target_feature = "fma"))]
fn split(a: f64) -> (f64, f64) {
    const FACTOR: f64 = 134_217_729.0; // 2^27 + 1
    let c = FACTOR * a;
    let hi = c - (c - a);
    (hi, a - hi)
}
