//! Full build of the interpolation coefficients of a uniformly sampled
//! signal: `D_k` with `Σ_i D_i β(j − i) = s_j` for every sample `j`, the
//! operation `scipy.ndimage.spline_filter1d` performs. Two routes:
//!
//! - [`RecursivePrefilter`] — the exact inverse filter
//!   `1/V(z) = Λ Π_r 1/((1 − ξ_r z⁻¹)(1 − ξ_r z))` run as a causal and an
//!   anti-causal first-order recursion per pole `ξ_r` (Unser, Aldroubi and
//!   Eden, *B-spline signal processing I–II*, IEEE Trans. SP 41 (1993);
//!   initial values as in Thévenaz, Blu and Unser, *Interpolation
//!   revisited*, IEEE TMI 19 (2000)). `O(p)` operations per sample.
//! - [`ConvolutionPrefilter`] — the truncated S-spline convolution
//!   `D_k = Σ_{|j|≤n} c_{|j|} s_{k−j}` (seed 000 eq 10, 20): every output
//!   independent, `O(n)` operations per sample, error set by the width `n`.
//!
//! Both extend the samples beyond the ends by an [`EndRule`]: `Reflect`
//! (whole-sample mirror `s_{−i} = s_i`, `s_{ν−1+i} = s_{ν−1−i}`: the tangent
//! rule with zero tangents, scipy's `mode="mirror"`) or `Periodic`. The
//! repeated end of `Free` makes the recursive filter's initial values depend
//! on the pole order, so only the convolution accepts it.

use super::coefficients::poles_rounded;
use super::end_conditions::EndRule;
use super::node_values::node_values_exact;
use super::{SplineFamily, SsplineError, TruncatedBasis};
use crate::scalar::{Mp, Real};
use crate::validation::NonFiniteValue;
use rug::Rational;

/// Why a prefilter could not be built or applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PrefilterError {
    /// No samples.
    #[error("the signal is empty")]
    Empty,
    /// A sample is NaN or infinite.
    #[error("sample {index} is not finite ({value})")]
    NonFinite {
        /// Its index.
        index: usize,
        /// What it holds.
        value: NonFiniteValue,
    },
    /// The recursive filter has no exact initial values for this end rule.
    #[error("the recursive prefilter supports the mirror and periodic ends, not {0:?}")]
    UnsupportedEnd(EndRule),
    /// The scalar is too short for this degree: the estimated relative
    /// error of the coefficients exceeds the tolerance asked for.
    #[error(
        "{family} in {scalar} is ill-conditioned: estimated relative error {estimated:.1e} \
         of the coefficients (amplification 1/|V(-1)| = {amplification:.2e}) exceeds {tol:.1e}; \
         use at least {suggested_bits} bits (e.g. --prec {suggested_bits})"
    )]
    IllConditioned {
        /// The family, as text.
        family: String,
        /// The scalar type name.
        scalar: String,
        /// `1/|V(−1)|`, the ∞-norm of the inverse filter.
        amplification: f64,
        /// `u · 1/|V(−1)|`, `u` the unit roundoff of the scalar.
        estimated: f64,
        /// The tolerance that was asked for.
        tol: f64,
        /// The smallest precision whose estimate meets `tol`.
        suggested_bits: u32,
    },
    /// Poles or coefficients could not be computed.
    #[error(transparent)]
    Sspline(#[from] SsplineError),
}

/// A 1-D full build `s ↦ D` (module doc): what [`RecursivePrefilter`] and
/// [`ConvolutionPrefilter`] share, so that code comparing or choosing routes
/// (the verify study `update_cost`, the engine's callers) takes either.
///
/// **Method**, **accuracy** and **source**: those of the implementing route
/// ([`RecursivePrefilter::apply`]: exact inverse filter to a few ulps;
/// [`ConvolutionPrefilter::apply`]: within the width's tail bound).
///
/// ```
/// use splinelab::sspline::{SplineFamily, end_conditions::EndRule};
/// use splinelab::sspline::prefilter::{ConvolutionPrefilter, Prefilter1d, RecursivePrefilter};
/// use splinelab::scalar::prelude::*;
/// // In MPFR: both routes through one trait object, the convolution of
/// // half-width 120 within 1e-50 of the exact filter (cubic tail ≈ 0.268^n).
/// type M = Mp<256>;
/// let f = SplineFamily::Order(4);
/// let routes: Vec<Box<dyn Prefilter1d<M>>> = vec![
///     Box::new(RecursivePrefilter::<M>::new(&f).unwrap()),
///     Box::new(ConvolutionPrefilter::<M>::new(&f, 120).unwrap()),
/// ];
/// let s: Vec<M> = [1, 4, 2, 0, 3, 5, 1].iter().map(|&x| M::from_int(x)).collect();
/// let d: Vec<Vec<M>> = routes.iter().map(|r| r.apply(&s, EndRule::Reflect).unwrap()).collect();
/// for (a, b) in d[0].iter().zip(&d[1]) {
///     assert!((a.clone() - b.clone()).abs().to_f64() < 1e-50);
/// }
/// ```
pub trait Prefilter1d<T: Real> {
    /// The coefficients `D_0..D_{ν−1}` of `samples` extended by `end`.
    /// Errors: empty or non-finite samples; an end the route does not support.
    fn apply(&self, samples: &[T], end: EndRule) -> Result<Vec<T>, PrefilterError>;
}

impl<T: Real> Prefilter1d<T> for RecursivePrefilter<T> {
    fn apply(&self, samples: &[T], end: EndRule) -> Result<Vec<T>, PrefilterError> {
        RecursivePrefilter::apply(self, samples, end)
    }
}

impl<T: Real> Prefilter1d<T> for ConvolutionPrefilter<T> {
    fn apply(&self, samples: &[T], end: EndRule) -> Result<Vec<T>, PrefilterError> {
        ConvolutionPrefilter::apply(self, samples, end)
    }
}

fn check_samples<T: Real>(s: &[T]) -> Result<(), PrefilterError> {
    if s.is_empty() {
        return Err(PrefilterError::Empty);
    }
    match s
        .iter()
        .enumerate()
        .find_map(|(i, x)| Some((i, NonFiniteValue::of(x)?)))
    {
        Some((index, value)) => Err(PrefilterError::NonFinite { index, value }),
        None => Ok(()),
    }
}

/// The exact inverse filter of the interpolation condition, by recursion.
#[derive(Debug, Clone, PartialEq)]
pub struct RecursivePrefilter<T> {
    poles: Vec<T>,
    /// `Λ = Π_r (1 − ξ_r)(1 − 1/ξ_r) / V(1)`: each pole pair's recursion
    /// divides a constant by `(1 − ξ)(1 − 1/ξ)`; the filter must divide by `V(1)`.
    /// Correctly rounded (`exact_gain`).
    gain: T,
    /// Terms of the truncated initial sums: `|ξ|^horizon < 2^{−BITS−8}`.
    horizons: Vec<usize>,
    /// `1/|V(−1)|` (see [`RecursivePrefilter::amplification`]).
    amplification: f64,
    /// The family, for error messages.
    family: SplineFamily,
}

impl<T: Real> RecursivePrefilter<T> {
    /// The filter of `family`: its poles computed in MPFR with guard bits
    /// and rounded once to `T` ([`poles_rounded`]), so every order
    /// `2..=200` builds in `f64` (and `f32`). Whether `T` is long enough for
    /// the degree is a separate question: see [`Self::estimated_error`] and
    /// [`Self::new_within`].
    ///
    /// **Accuracy**: each pole correctly rounded to `T` from the MPFR value;
    /// the filter then matches exact rational solutions
    /// (`verify/tests/it/sspline_prefilter.rs::recursive_f64_matches_the_exact_solution`).
    /// **Source**: Unser, Aldroubi & Eden (1993); seed 000 eq 16.
    ///
    /// ```
    /// use splinelab::sspline::{SplineFamily, end_conditions::EndRule, prefilter::RecursivePrefilter};
    /// let f = RecursivePrefilter::<f64>::new(&SplineFamily::Order(4)).unwrap();
    /// let d = f.apply(&[1.0, 4.0, 2.0, 0.0, 3.0], EndRule::Reflect).unwrap();
    /// // Cubic interpolation: (D_{k−1} + 4 D_k + D_{k+1}) / 6 = s_k, mirror ends.
    /// assert!(((d[1] + 4.0 * d[2] + d[3]) / 6.0 - 2.0).abs() < 1e-15);
    /// assert!(((2.0 * d[1] + 4.0 * d[0]) / 6.0 - 1.0).abs() < 1e-15);
    /// ```
    ///
    /// ```
    /// use splinelab::sspline::{SplineFamily, end_conditions::EndRule, prefilter::RecursivePrefilter};
    /// // In MPFR: the quintic filter of constant data is that constant
    /// // (the B-spline translates sum to 1), to 256-bit rounding.
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<256>;
    /// let f = RecursivePrefilter::<M>::new(&SplineFamily::Order(6)).unwrap();
    /// let d = f.apply(&vec![M::from_int(5); 9], EndRule::Reflect).unwrap();
    /// assert!(d.iter().all(|x| (x.clone() - M::from_int(5)).to_f64().abs() < 1e-70));
    /// ```
    pub fn new(family: &SplineFamily) -> Result<Self, PrefilterError> {
        let poles: Vec<T> = poles_rounded(family)?;
        let exact = node_values_exact(family)?;
        let v1: Rational = exact.iter().sum();
        let gain = match exact_gain(&exact, poles.len()) {
            Some(g) => T::from_rational(&g),
            None => pair_product(&poles, T::from_rational(&Rational::from(v1.recip_ref()))),
        };
        let bits = T::BITS as f64 + 8.0;
        let horizons = poles
            .iter()
            .map(|z| (bits / -z.to_f64().abs().log2()).ceil() as usize)
            .collect();
        Ok(RecursivePrefilter {
            poles,
            gain,
            horizons,
            amplification: amplification(&exact),
            family: family.clone(),
        })
    }

    /// [`Self::new`], refused with [`PrefilterError::IllConditioned`] when
    /// [`Self::estimated_error`] exceeds `tol` (the error names the estimate
    /// and the precision that would meet `tol`).
    ///
    /// **Method**: [`Self::new`], then the a-priori estimate compared with `tol`.
    /// **Source**: Unser, Aldroubi & Eden (1993).
    ///
    /// ```
    /// use splinelab::sspline::{SplineFamily, prefilter::{RecursivePrefilter, PrefilterError}};
    /// assert!(RecursivePrefilter::<f64>::new_within(&SplineFamily::Order(6), 1e-12).is_ok());
    /// let e = RecursivePrefilter::<f64>::new_within(&SplineFamily::Order(100), 1e-6).unwrap_err();
    /// assert!(matches!(e, PrefilterError::IllConditioned { suggested_bits, .. } if suggested_bits > 53));
    /// ```
    pub fn new_within(family: &SplineFamily, tol: f64) -> Result<Self, PrefilterError> {
        let f = Self::new(family)?;
        let estimated = f.estimated_error();
        if estimated.is_nan() || estimated > tol {
            return Err(PrefilterError::IllConditioned {
                family: family.to_string(),
                scalar: T::type_name(),
                amplification: f.amplification,
                estimated,
                tol,
                suggested_bits: (f.amplification / tol).log2().ceil().max(1.0) as u32 + 1,
            });
        }
        Ok(f)
    }

    /// `1/|V(−1)| = max_ω 1/|V(e^{iω})| = Σ_i |c_i|`: the ∞-norm of the
    /// inverse filter (the symbol `V(e^{iω}) = Σ_j β(j) cos jω` of a B-spline
    /// is smallest at `ω = π`, and `c_i` alternates in sign). It grows like
    /// `(π/2)^m`: `3` for cubics, `≈ 10^{11}` at order 58, `≈ 10^{39}` at 200.
    pub fn amplification(&self) -> f64 {
        self.amplification
    }

    /// First-order estimate of the relative error of the coefficients
    /// against `max |s|`: `u · 1/|V(−1)|`, `u = 2^{−BITS}` — the condition
    /// number of the interpolation problem times one rounding of the data.
    /// Samples known to one ulp of `T` (any data rounded to `T`) determine
    /// the coefficients only to this: an ulp-sized perturbation at the
    /// frequency `ω = π` is amplified by exactly `1/|V(−1)|`. It separates,
    /// in `f64`, degree 31 (`≈ 10^{-10}`) from degree 99 (`≈ 10^{3}`:
    /// meaningless). The arithmetic of the recursion itself adds far less
    /// (measured: a few ulps of `max|s|` on exact random data up to order
    /// 67, test `prefilter_every_order`).
    pub fn estimated_error(&self) -> f64 {
        self.amplification * (-(T::BITS as f64)).exp2()
    }

    /// The spline family this filter inverts.
    pub fn family(&self) -> &SplineFamily {
        &self.family
    }

    /// The poles `ξ_r ∈ (−1, 0)`, nearest 0 first.
    pub fn poles(&self) -> &[T] {
        &self.poles
    }

    /// `Λ = Π_r (1 − ξ_r)(1 − 1/ξ_r) / V(1)`, the gain applied before the
    /// passes, correctly rounded to `T` from its exact rational value
    /// `1/b_q` (`z^q V(z) = b_q Π_r (z − ξ_r)(z − 1/ξ_r)` at `z = 1`; e.g. 6 for cubics, 120 for quintics).
    /// Formed in `T` from the rounded poles it was off by up to about one
    /// ulp (quintic `f64`: `120 (1 − 1.07 u)`), a bias every output of
    /// every filtered axis shares.
    pub fn gain(&self) -> &T {
        &self.gain
    }

    /// Per pole, the number of terms `K` of an initial sum after which the
    /// neglected tail is below `2^{−BITS−8}` relatively.
    pub fn horizons(&self) -> &[usize] {
        &self.horizons
    }

    /// `1/V(1)`: the coefficients of a constant signal `s ≡ 1`.
    pub fn constant_response(&self) -> T {
        self.gain.clone() / pair_product(&self.poles, T::one())
    }

    /// The coefficients `D_0..D_{ν−1}` interpolating `samples` under `end`.
    ///
    /// **Method**: multiply by `Λ`, then per pole `ξ`: causal
    /// `c⁺_k = s_k + ξ c⁺_{k−1}`, anti-causal `c⁻_k = ξ (c⁻_{k+1} − c⁺_k)`.
    /// The initial values sum the extended signal to the horizon
    /// `K = ⌈(BITS + 8)/log₂(1/|ξ|)⌉` (so the neglected tail is below
    /// `2^{−BITS−8}` relatively) or, for `ν ≤ K`, exactly over the period.
    ///
    /// **Cost** `4p + 1` flops per sample (`p` poles) plus `O(pK)`.
    /// **Error**: each pass is a stable recursion that amplifies rounding by
    /// at most `1/(1 − |ξ|)`; measured in the verify study `update_cost`
    /// against a 256-bit build (a few ulps of `max |s|` for cubic and
    /// quintic). Errors: empty or non-finite samples, the `Free` end.
    /// Tests: `verify/tests/it/sspline_prefilter.rs::recursive_f64_matches_the_exact_solution`,
    /// `recursive_mp256_matches_the_exact_solution`. **Source**: Unser, Aldroubi &
    /// Eden (1993); Thévenaz, Blu & Unser (2000), initial values.
    pub fn apply(&self, samples: &[T], end: EndRule) -> Result<Vec<T>, PrefilterError> {
        check_samples(samples)?;
        if end == EndRule::Free {
            return Err(PrefilterError::UnsupportedEnd(end));
        }
        let mut c: Vec<T> = samples.iter().map(|s| s.clone() * &self.gain).collect();
        if c.len() == 1 {
            // Both extensions of one sample are constant: D = s / V(1).
            return Ok(c
                .into_iter()
                .map(|x| x / pair_product(&self.poles, T::one()))
                .collect());
        }
        for (z, &k) in self.poles.iter().zip(&self.horizons) {
            c[0] = match end {
                EndRule::Periodic => periodic_causal_start(&c, z, k),
                _ => mirror_causal_start(&c, z, k),
            };
            for i in 1..c.len() {
                let prev = c[i - 1].clone();
                c[i] += z.clone() * prev;
            }
            let last = c.len() - 1;
            c[last] = match end {
                EndRule::Periodic => periodic_anticausal_start(&c, z, k),
                _ => mirror_anticausal_start(&c, z),
            };
            for i in (0..last).rev() {
                c[i] = z.clone() * (c[i + 1].clone() - &c[i]);
            }
        }
        Ok(c)
    }
}

/// `1/|V(−1)|` from the exact node values: the alternating sum cancels
/// about 0.65 bits per order, so it runs in 512-bit MPFR (≥ 380 bits left).
fn amplification(v: &[Rational]) -> f64 {
    let alternating = v
        .iter()
        .enumerate()
        .fold(Mp::<512>::from_int(0), |a, (j, x)| {
            let x = Mp::<512>::from_rational(x);
            if j % 2 == 0 { a + x } else { a - x }
        });
    1.0 / alternating.to_f64().abs()
}

/// The gain `Λ = Π_r (1 − ξ_r)(1 − 1/ξ_r) / V(1)` as an exact rational:
/// `1/b_q`, `b_q` the outermost node value. `z^q V(z) = Σ_{k=−q}^{q} b_k
/// z^{k+q}` is a polynomial of degree `2q` with leading coefficient `b_q`
/// whose roots are the poles `ξ_r` and their reciprocals (the node values
/// are palindromic), so `z^q V(z) = b_q Π_r (z − ξ_r)(z − 1/ξ_r)` and at
/// `z = 1`, `V(1) = b_q Π_r (1 − ξ_r)(1 − 1/ξ_r)`. `None` unless there are
/// `q` poles and `b_q ≠ 0` (then the product is formed in `T`). The
/// product formed from the rounded poles in `T` instead carries their
/// rounding and its own (`f64` quintic: `1.07 u` low, cubic and quartic
/// `0.67 u` high), and the whole filter output with it.
fn exact_gain(node_values: &[Rational], poles: usize) -> Option<Rational> {
    let b = node_values.first()?;
    (node_values.len() == 2 * poles + 1 && *b != 0).then(|| Rational::from(b.recip_ref()))
}

/// `init · Π_r (1 − ξ_r)(1 − 1/ξ_r)`; with `init = 1`, what the recursions
/// divide a constant by.
fn pair_product<T: Real>(poles: &[T], init: T) -> T {
    poles.iter().fold(init, |g, z| {
        g * (T::one() - z.clone()) * (T::one() - T::one() / z.clone())
    })
}

/// `Σ_{j≥0} ξ^j s_{−j}` for the mirror extension of period `2ν − 2`.
fn mirror_causal_start<T: Real>(c: &[T], z: &T, horizon: usize) -> T {
    let n = c.len();
    if horizon < n {
        let mut zk = T::one();
        let mut sum = T::zero();
        for x in &c[..horizon] {
            sum += zk.clone() * x;
            zk *= z.clone();
        }
        return sum;
    }
    // Exact: one period folded, divided by 1 − ξ^{2ν−2}.
    let mut zk = z.clone();
    let mut z2k = z.clone().powi(2 * n as i32 - 3);
    let iz = T::one() / z.clone();
    let mut sum = c[0].clone() + z.clone().powi(n as i32 - 1) * c[n - 1].clone();
    for x in &c[1..n - 1] {
        sum += (zk.clone() + &z2k) * x.clone();
        zk *= z.clone();
        z2k *= iz.clone();
    }
    sum / (T::one() - zk.clone() * zk)
}

/// `c⁻_{ν−1}` of the mirror extension: `ξ/(ξ² − 1) (c⁺_{ν−1} + ξ c⁺_{ν−2})`.
fn mirror_anticausal_start<T: Real>(c: &[T], z: &T) -> T {
    let n = c.len();
    z.clone() / (z.clone() * z - T::one()) * (c[n - 1].clone() + z.clone() * c[n - 2].clone())
}

/// `Σ_{j≥0} ξ^j x_{index(j)}` for a `ν`-periodic index: exact (one period
/// over `1 − ξ^ν`) when `ν ≤ horizon`, truncated at the horizon otherwise.
fn periodic_sum<T: Real>(c: &[T], z: &T, horizon: usize, index: impl Fn(usize) -> usize) -> T {
    let mut zk = T::one();
    let mut sum = T::zero();
    for j in 0..horizon.min(c.len()) {
        sum += zk.clone() * c[index(j)].clone();
        zk *= z.clone();
    }
    if horizon < c.len() {
        sum
    } else {
        sum / (T::one() - zk)
    }
}

/// `c⁺_0 = Σ_{j≥0} ξ^j s_{(−j) mod ν}`.
fn periodic_causal_start<T: Real>(c: &[T], z: &T, horizon: usize) -> T {
    let n = c.len();
    periodic_sum(c, z, horizon, |j| (n - j) % n)
}

/// `c⁻_{ν−1} = −ξ Σ_{j≥0} ξ^j c⁺_{(ν−1+j) mod ν}`.
fn periodic_anticausal_start<T: Real>(c: &[T], z: &T, horizon: usize) -> T {
    let n = c.len();
    -z.clone() * periodic_sum(c, z, horizon, |j| (n - 1 + j) % n)
}

/// The truncated S-spline convolution of half-width `n`.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvolutionPrefilter<T> {
    c: Vec<T>,
}

impl<T: Real> ConvolutionPrefilter<T> {
    /// The filter `c_0..c_n` of `family` ([`TruncatedBasis::new`], ≤ 1 ulp each).
    pub fn new(family: &SplineFamily, n: usize) -> Result<Self, PrefilterError> {
        let c = TruncatedBasis::<T>::new(family, n)?.coefficients().to_vec();
        Ok(ConvolutionPrefilter { c })
    }

    /// The half-width `n`.
    pub fn half_width(&self) -> usize {
        self.c.len() - 1
    }

    /// The taps `c_0..c_n`.
    pub fn coefficients(&self) -> &[T] {
        &self.c
    }

    /// `out[k] = D_k` from an already extended signal: `ext[j]` is the
    /// sample `s_{j−n}`, `ext.len() = out.len() + 2n`. The cache-blocked
    /// interior loop of [`Self::apply`], with no end handling.
    pub fn apply_extended(&self, ext: &[T], out: &mut [T]) {
        let n = self.half_width();
        debug_assert_eq!(ext.len(), out.len() + 2 * n);
        for (b, chunk) in out.chunks_mut(BLOCK).enumerate() {
            self.interior(ext, n + b * BLOCK, chunk);
        }
    }

    /// `D_k = c_0 s_k + Σ_{j=1}^{n} c_j (s_{k−j} + s_{k+j})`, `k = 0..ν−1`,
    /// the samples extended by `end` ([`EndRule::fold`]; a `Reflect` end is
    /// the mirror, tangents zero).
    ///
    /// **Cost** `n + 1` multiplications and `2n` additions per sample; the
    /// outputs are independent (vectorisable, parallelisable, and one edited
    /// sample changes `2n + 1` of them). **Error**: the truncation error
    /// `≤ 2 Σ_{j>n} |c_j| · max|s|` (the width's tail bound) plus the
    /// rounding of a length-`n + 1` dot product, `≤ γ_{2n+1} Σ_j |c_j| |s|`.
    /// Errors: empty or non-finite samples.
    ///
    /// Test: `verify/tests/it/sspline_prefilter.rs::convolution_is_within_its_tail_bound`.
    /// **Source**: seed 000 eq 10 (truncation at half-width `n`) and its tail bound.
    ///
    /// ```
    /// use splinelab::sspline::{SplineFamily, end_conditions::EndRule, prefilter::*};
    /// let s = [1.0, 4.0, 2.0, 0.0, 3.0, 5.0, 1.0];
    /// let exact = RecursivePrefilter::<f64>::new(&SplineFamily::Order(4)).unwrap();
    /// let conv = ConvolutionPrefilter::<f64>::new(&SplineFamily::Order(4), 29).unwrap();
    /// let (a, b) = (exact.apply(&s, EndRule::Reflect).unwrap(), conv.apply(&s, EndRule::Reflect).unwrap());
    /// assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-14));
    /// ```
    pub fn apply(&self, samples: &[T], end: EndRule) -> Result<Vec<T>, PrefilterError> {
        check_samples(samples)?;
        let (len, n) = (samples.len(), self.half_width());
        let mut out = vec![T::zero(); len];
        // Interior outputs k ∈ [n, ν − n) need no extension.
        let (a, b) = if len > 2 * n {
            (n, len - n)
        } else {
            (len, len)
        };
        for k in (0..a).chain(b..len) {
            out[k] = self.folded(samples, end, k as i64);
        }
        for lo in (a..b).step_by(BLOCK) {
            let hi = (lo + BLOCK).min(b);
            self.interior(samples, lo, &mut out[lo..hi]);
        }
        Ok(out)
    }

    /// `D_k` near an end, the samples extended by `end`.
    fn folded(&self, s: &[T], end: EndRule, k: i64) -> T {
        let at = |i: i64| s[end.fold(i, s.len()).0].clone();
        let mut acc = self.c[0].clone() * at(k);
        for j in 1..=self.half_width() as i64 {
            acc += self.c[j as usize].clone() * (at(k - j) + at(k + j));
        }
        acc
    }

    /// `out[i] = D_{lo+i}` for interior outputs, the loops interchanged
    /// (`j` outer, `k` inner) so that the inner loop is an axpy over
    /// contiguous slices, which the compiler vectorises; the summation order
    /// per output is that of [`Self::folded`], so both agree bitwise.
    fn interior(&self, s: &[T], lo: usize, out: &mut [T]) {
        for (o, x) in out.iter_mut().zip(&s[lo..]) {
            *o = self.c[0].clone() * x;
        }
        for j in 1..=self.half_width() {
            let cj = &self.c[j];
            for (o, (l, r)) in out.iter_mut().zip(s[lo - j..].iter().zip(&s[lo + j..])) {
                *o += cj.clone() * (l.clone() + r);
            }
        }
    }
}

/// Outputs per cache block of the interior convolution: the block of `D`
/// and its `2n` neighbouring samples stay in L1 across the `n` passes.
const BLOCK: usize = 1024;
