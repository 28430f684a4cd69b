//! The recursions of one window of the block route
//! ([`BlockPrefilter`](super::block_filter::BlockPrefilter)), vectorised
//! along consecutive samples: no transposes, one read of the samples and one
//! write of the coefficients, in order.
//!
//! **Method.** The causal recursion `y_k = x_k + ξ y_{k−1}` over chunks of
//! `V` consecutive samples (`V = 8` for `f64`, one AVX-512 register; 16 for
//! `f32`; 8 for other scalars) is the `V`-tap filter
//! `f_k = Σ_{j<V} ξ^j x_{k−j}` followed by the recursion of stride `V`,
//! `y_k = f_k + ξ^V y_{k−V}` (substitute the recursion into itself `V − 1`
//! times). `f` is formed by doubling, each level one fused multiply-add per
//! lane on the chunk and the chunk before it:
//! `g_k = x_k + ξ x_{k−1}`, `h_k = g_k + ξ² g_{k−2}`, `f_k = h_k + ξ⁴ h_{k−4}`
//! (and `+ ξ⁸ ·_{k−8}` for 16 lanes), so a chunk costs `log₂ V + 1`
//! multiply-adds and `log₂ V` lane shifts, and the only chain from chunk to
//! chunk is one multiply-add (`ξ^V y_{k−V}`: four cycles per chunk). The
//! anti-causal recursion `Y_k = x_k + ξ Y_{k+1}` is the mirror image, run
//! from the window's end. The powers `ξ^{2^l}` are formed by squaring in
//! the scalar (`ξ^V` to `(V − 1) u` relative).
//!
//! A window is `[samples][T zeros]` (`T` at least the longest pole
//! horizon): every causal pass runs first (the first reads the samples,
//! starting from zeros before the window: exact), one pole per pass over
//! the window in place, then every anti-causal pass from the end of the
//! zeros (start 0: the causal values there are below `2^{−BITS−8}` of the
//! window's, and the anti-causal pass shrinks their effect by `|ξ|^T` again
//! before it reaches the samples), the last one writing the coefficients.
//! Linear shift-invariant filters commute, so this order computes the
//! cascade of [`RecursivePrefilter`](crate::sspline::prefilter::RecursivePrefilter)
//! (causal, anti-causal, per pole in turn) on the zero-extended window. The
//! gain and the anti-causal factors `−ξ` of every pole multiply the result
//! once, `G = gain · Π(−ξ_p)`, as it is stored.
//!
//! **Accuracy.** Other roundings than the sequential recursion, not other
//! mathematics: each `f_k` is within `(log₂V + 1) u Σ_{j<V} |ξ^j x_{k−j}|`
//! of its value, and the recursion of stride `V` adds `u |y_k|` per step
//! with the contraction `|ξ|^V`, so every `y_k` is within a few `u` of
//! `Σ_j |ξ|^j |x_{k−j}|` per pass, as the sequential recursion's. Tested
//! against 128-bit MPFR in f64 and f32 within `bound · max|s| + 64 u A`
//! (`verify/tests/it/engine_lanes.rs`: every mode, degrees 2 to 7 and 25,
//! lengths around the vector, window and task sizes; `engine_properties.rs`),
//! and the AVX-512 kernels against this module's plain loops bit for bit
//! (this module's tests, which fail when a lane shift is off by one): every
//! target computes the same bits, because every multiply-add is fused (a
//! hardware FMA, or `mul_add`, correctly rounded either way) and in the same
//! order.
//!
//! **Cost.** Per chunk and pass: `log₂V + 1` multiply-adds and `log₂V`
//! lane shifts (`f64`: 4 and 3 per 8 samples; `f32`: 5 and 4 per 16), one
//! load, one store, and the magnitude (one `vrangepd`) or the scale (one
//! multiply); one chain of four cycles (the multiply-add `ξ^V y`) per chunk
//! and pass. Measured on the 2-core Zen 5 development machine, one thread
//! (`engine_peer tol1d D 100000 3000`, data in L2, median of 3000 calls):
//! cubic 0.52 µs, quintic 0.85 µs per 1000 samples, the kernels about 85%
//! of it (`perf`). Prefetching the next window's samples and coefficients
//! (one line per chunk) took a stand-alone prototype of 10⁷ cubic samples
//! from 7.5 to 4.6 ms (against 4.2 ms for `out[i] = 2 s[i]`).
//! The AVX-512 doubling levels' lane shifts by `valignq`/`valignd` rather
//! than `vpermt2pd`/`vpermt2ps` (the input viewed as integers, see the
//! kernels' `fir`; the same bits): `spline_filter1d(x, d, tol=1e-12)` of
//! 10⁷ `f64` samples, one thread, CPU time, min of 11 alternated against
//! the build before (`python/bench/prefilter_ab.py`, load 1.5 on the 2-core
//! Zen 5 machine): quintic 8.11 → 7.65 ms (2.2× a 3.5 ms `np.copyto`),
//! cubic 4.47 → 4.23 ms, `f32` cubic (`tol=1e-6`) 2.37 → 2.16 ms.
//!
//! Tried and dropped (same machine, one thread): two windows of a block
//! filtered at once (each pass down both in step, their chains
//! interleaved; the same bits): 10⁷ quintic 7.65 → 9.6 ms, cubic 4.4 →
//! 6.7–7.2 ms (not profiled; presumably the two windows' samples, passes
//! and coefficients, about 50 KB, leave the 48 KiB L1), no gain at 10⁶ (in
//! L1 alone, a microbenchmark, 1.19 → 1.01 ns per chunk and pass); two
//! poles fused in one pass, in registers (one load and store per chunk for both): quintic 102
//! µs at 10⁵ samples, 91 µs unfused; a second chain
//! (`y_k = f_k + ξ^V f_{k−V} + ξ^{2V} y_{k−2V}`, one more multiply-add per
//! pair of chunks): no faster (the passes are bound by throughput, not by
//! the chain); the first two doubling levels from unaligned loads of the
//! samples before (`g_{k−2} = x_{k−2} + ξ x_{k−3}` formed again: the same
//! bits, two shuffles fewer): 10⁷ cubic 4.8 → 6.6 ms; the in-register scan
//! (`v += ξ^s shift_s(v)` within the chunk, then `ξ^{i+1} y_{prev}`
//! broadcast; in the prototype): 3.5 against 3.1 ms for 10⁷ samples in
//! cache.
//!
//! CPUs with AVX2 and FMA but not AVX-512 run the same kernels in pairs of
//! 256-bit registers (the lane shifts across the pair by `vperm2f128` and
//! `vshufpd`/`vpalignr`); others (NEON, the baseline) the plain loops,
//! compiled per target by `multiversion`: the same bits everywhere.
//! Measured here by running the AVX2 kernels in the AVX-512 clone (one
//! thread, 10⁵ samples, median): cubic 0.54 against 0.50 µs per 1000
//! samples, quintic 0.89 against 0.82; the plain loops compiled there took
//! 10⁷ cubic samples in 28 ms against 9.4 ms, on a loaded machine.
//!
//! **Source**: the recursions of Unser, Aldroubi and Eden (1993); the
//! doubling (Hillis–Steele) form of a linear recurrence, as in Blelloch
//! (1990), "Prefix sums and their applications", §1.4.

use crate::scalar::Real;
use multiversion::{multiversion, target::match_target};
use std::any::TypeId;
use std::array::from_fn;

/// The recursions of a filter's poles in chunks of consecutive samples.
#[derive(Debug, Clone)]
pub(crate) struct WindowRecursion<T> {
    /// Per pole, `ξ^{2^l}` for `l = 0 ..= log₂ V` (the doubling levels and
    /// `ξ^V`).
    powers: Vec<Vec<T>>,
    /// `gain · Π(−ξ_p)`: the factor applied as the coefficients are stored.
    scale: T,
}

/// Whether `T` is `U` (a constant once compiled).
fn is<T: 'static, U: 'static>() -> bool {
    TypeId::of::<T>() == TypeId::of::<U>()
}

/// Samples per chunk for `T` ([module documentation](self)).
pub(crate) fn lanes<T: 'static>() -> usize {
    if is::<T, f32>() { 16 } else { 8 }
}

impl<T: Real> WindowRecursion<T> {
    /// The recursions of `poles` (each `|ξ| < 1`) and `gain`. `O(p log V)`.
    pub(crate) fn new(poles: &[T], gain: &T) -> Self {
        let levels = lanes::<T>().trailing_zeros() as usize;
        let powers = poles
            .iter()
            .map(|z| {
                let mut p = vec![z.clone()];
                for l in 0..levels {
                    p.push(p[l].clone() * &p[l]);
                }
                p
            })
            .collect();
        let scale = poles.iter().fold(gain.clone(), |g, z| -(g * z));
        WindowRecursion { powers, scale }
    }

    /// The coefficients `out[i] = D_{lo + i}` of the window `src` followed
    /// by `tail` zeros (`src.len()` and `tail` multiples of [`lanes`],
    /// `lo + out.len() ≤ src.len()`, `tail ≥` [`lanes`]), every pole's
    /// causal and anti-causal pass; `buf` is the work space. Returns
    /// `max|src|` (0 for scalars wider than `f64`, which cannot overflow)
    /// and whether the recursions stayed finite: a non-finite sample makes
    /// every causal value after it non-finite (`±∞ · ξ^j` stays infinite,
    /// `∞ − ∞` and `0 · ∞` are NaN), the last one, in the tail, included,
    /// and so does an overflow. `ahead`: where the next window's samples and
    /// coefficients lie, fetched into the cache while this one is filtered
    /// (addresses only: nothing is read through them).
    pub(crate) fn window(
        &self,
        src: &[T],
        tail: usize,
        lo: usize,
        out: &mut [T],
        buf: &mut Vec<T>,
        ahead: Ahead<T>,
    ) -> (f64, bool) {
        // `const`: wider MPFR compiles one width only (`Real::FITS_F64`).
        if const { T::FITS_F64 } && lanes::<T>() == 16 {
            self.window_in::<16>(src, tail, lo, out, buf, ahead)
        } else {
            self.window_in::<8>(src, tail, lo, out, buf, ahead)
        }
    }

    fn window_in<const V: usize>(
        &self,
        src: &[T],
        tail: usize,
        lo: usize,
        out: &mut [T],
        buf: &mut Vec<T>,
        ahead: Ahead<T>,
    ) -> (f64, bool) {
        let (src, rest) = src.as_chunks::<V>();
        debug_assert!(rest.is_empty() && tail.is_multiple_of(V) && lo.is_multiple_of(V));
        buf.resize((src.len() + tail / V) * V, T::zero());
        let (buf, _) = buf.as_chunks_mut::<V>();
        let (Some((first, later)), Some((last, earlier))) =
            (self.powers.split_first(), self.powers.split_last())
        else {
            // No pole (degrees 0 and 1): the coefficients are the samples
            // times the gain.
            let flat = src.as_flattened();
            for (o, x) in out.iter_mut().zip(&flat[lo..]) {
                *o = self.scale.clone() * x;
            }
            let finite = flat.iter().all(|x| x.is_finite());
            return (flat.iter().fold(0.0, magnitude), finite);
        };
        let max = causal(first, Some(src), buf, ahead);
        let finite = buf.last().is_none_or(|c| c.iter().all(|x| x.is_finite()));
        for z in later {
            causal(z, None, buf, None);
        }
        for z in earlier {
            anticausal(z, buf, lo / V, None);
        }
        anticausal(last, buf, lo / V, Some((out, &self.scale)));
        (max, finite)
    }
}

/// Where the next window's samples and coefficients start (prefetch
/// addresses; `None` for none).
pub(crate) type Ahead<T> = Option<(*const T, *const T)>;

/// The causal pass of the pole of powers `z` down `buf`, reading `src`
/// (then zeros) when given, else `buf` itself; `max|src|` ([`magnitude`];
/// 0 without `src`). Scalars up to f64's precision take the vector clones
/// ([`causal_simd`], whose register kernels serve f64 and f32); wider MPFR
/// the plain loop, whose clones would be the same library calls
/// (`Real::FITS_F64`: none are compiled for it).
#[inline(always)]
fn causal<T: Real, const V: usize>(
    z: &[T],
    src: Option<&[[T; V]]>,
    buf: &mut [[T; V]],
    ahead: Ahead<T>,
) -> f64 {
    if const { T::FITS_F64 } {
        causal_simd(z, src, buf, ahead)
    } else {
        causal_plain(z, src, buf)
    }
}

/// [`causal`] compiled for the CPU's vector units.
#[multiversion(targets(
    "x86_64+avx512f+avx512dq+avx512vl+avx2+fma",
    "x86_64+avx2+fma",
    "aarch64+neon"
))]
fn causal_simd<T: Real, const V: usize>(
    z: &[T],
    src: Option<&[[T; V]]>,
    buf: &mut [[T; V]],
    ahead: Ahead<T>,
) -> f64 {
    match_target! {
        "x86_64+avx512f+avx512dq" => {
            if !avx2_only() && let Some(max) = x86::causal(z, src, buf, ahead) {
                return max;
            }
            if let Some(max) = x86::causal_avx2(z, src, buf, ahead) {
                return max;
            }
        }
        "x86_64+avx2+fma" => {
            if let Some(max) = x86::causal_avx2(z, src, buf, ahead) {
                return max;
            }
        }
        _ => {}
    }
    let _ = ahead;
    causal_plain(z, src, buf)
}

/// The anti-causal pass of the pole of powers `z` up `buf` from its end to
/// chunk `lo`, in place, or when `out` is given into `out[i] = scale ·
/// Y_{lo·V + i}` (its last chunk may be partial). Dispatched as [`causal`].
#[inline(always)]
fn anticausal<T: Real, const V: usize>(
    z: &[T],
    buf: &mut [[T; V]],
    lo: usize,
    out: Option<(&mut [T], &T)>,
) {
    if const { T::FITS_F64 } {
        anticausal_simd(z, buf, lo, out)
    } else {
        anticausal_plain(z, buf, lo, out)
    }
}

/// [`anticausal`] compiled for the CPU's vector units.
#[multiversion(targets(
    "x86_64+avx512f+avx512dq+avx512vl+avx2+fma",
    "x86_64+avx2+fma",
    "aarch64+neon"
))]
fn anticausal_simd<T: Real, const V: usize>(
    z: &[T],
    buf: &mut [[T; V]],
    lo: usize,
    out: Option<(&mut [T], &T)>,
) {
    match_target! {
        "x86_64+avx512f+avx512dq" => {
            let mut out = out;
            if !avx2_only() && x86::anticausal(z, buf, lo, &mut out) {
                return;
            }
            if x86::anticausal_avx2(z, buf, lo, &mut out) {
                return;
            }
            anticausal_plain(z, buf, lo, out)
        }
        "x86_64+avx2+fma" => {
            let mut out = out;
            if x86::anticausal_avx2(z, buf, lo, &mut out) {
                return;
            }
            anticausal_plain(z, buf, lo, out)
        }
        _ => anticausal_plain(z, buf, lo, out),
    }
}

/// Whether the AVX-512 clones run the AVX2 kernels instead (tests only:
/// they check those kernels on a CPU that has AVX-512).
#[cfg(not(test))]
const fn avx2_only() -> bool {
    false
}

#[cfg(test)]
thread_local! {
    static AVX2_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
fn avx2_only() -> bool {
    AVX2_ONLY.with(|c| c.get())
}

/// The chunks a pole's pass carries from chunk to chunk: the previous
/// (causal) or next (anti-causal) chunk at each doubling level (at most 4:
/// 16 lanes).
type Carry<T, const V: usize> = [[T; V]; 4];

/// `ξ^{2^l}·shifted + cur` lane by lane, one rounding each (`mul_add`).
#[inline(always)]
fn level<T: Real, const V: usize>(z: &T, shifted: impl Fn(usize) -> T, cur: &[T; V]) -> [T; V] {
    from_fn(|i| z.clone().mul_add(shifted(i), cur[i].clone()))
}

/// Doubling levels of a pole of powers `z` (`z` ends with `ξ^V`).
fn levels<T>(z: &[T]) -> usize {
    z.len() - 1
}

/// The `V`-tap filter `f` of one chunk by doubling ([module
/// documentation](self)): causal (`carry` holds the previous chunk's
/// levels) or anti-causal (`ANTI`: the mirror image, `carry` the next
/// chunk's).
#[inline(always)]
fn fir<T: Real, const V: usize, const ANTI: bool>(
    z: &[T],
    carry: &mut Carry<T, V>,
    x: [T; V],
) -> [T; V] {
    let mut cur = x;
    for (l, zl) in z[..levels(z)].iter().enumerate() {
        let s = 1 << l;
        let other = std::mem::replace(&mut carry[l], cur);
        let now = &carry[l];
        let shifted = |i: usize| match (ANTI, i >= s, i + s < V) {
            (false, true, _) => now[i - s].clone(),
            (false, false, _) => other[V - s + i].clone(),
            (true, _, true) => now[i + s].clone(),
            (true, _, false) => other[i + s - V].clone(),
        };
        cur = level(zl, shifted, now);
    }
    cur
}

/// The recursion of stride `V`: `ξ^V y + f` (`y` the chunk before in pass
/// order), replacing `y`.
#[inline(always)]
fn stride<T: Real, const V: usize>(z: &[T], y: &mut [T; V], f: [T; V]) -> [T; V] {
    *y = level(&z[levels(z)], |i| y[i].clone(), &f);
    y.clone()
}

/// Zeros carried into the first chunk of a pass.
#[inline(always)]
fn carry<T: Real, const V: usize>() -> Carry<T, V> {
    from_fn(|_| from_fn(|_| T::zero()))
}

/// `max(m, |x|)` for `f64` and narrower scalars (a NaN `x` leaves `m`: the
/// window reports non-finite samples otherwise); wider scalars cannot
/// overflow and report 0.
#[inline(always)]
fn magnitude<T: Real>(m: f64, x: &T) -> f64 {
    if T::BITS > 53 {
        return 0.0;
    }
    let a = x.to_f64().abs();
    if a > m { a } else { m }
}

/// [`causal`] lane by lane: the reference the vector kernels equal bit for
/// bit, and what other targets and scalars run (inlined into each clone of
/// [`causal`], so `mul_add` is the target's FMA where it has one).
#[inline(always)]
fn causal_plain<T: Real, const V: usize>(
    z: &[T],
    src: Option<&[[T; V]]>,
    buf: &mut [[T; V]],
) -> f64 {
    let mut carry = carry::<T, V>();
    let mut max = 0.0;
    let mut input = |i: usize, buf: &[[T; V]]| match src {
        Some(src) => match src.get(i) {
            Some(s) => {
                max = s.iter().fold(max, magnitude);
                s.clone()
            }
            None => from_fn(|_| T::zero()),
        },
        None => buf[i].clone(),
    };
    let mut y: [T; V] = from_fn(|_| T::zero());
    for i in 0..buf.len() {
        let f = fir::<T, V, false>(z, &mut carry, input(i, buf));
        buf[i] = stride(z, &mut y, f);
    }
    max
}

/// [`anticausal`] lane by lane (the reference of the vector kernels).
#[inline(always)]
fn anticausal_plain<T: Real, const V: usize>(
    z: &[T],
    buf: &mut [[T; V]],
    lo: usize,
    mut out: Option<(&mut [T], &T)>,
) {
    let mut carry = carry::<T, V>();
    let mut emit = |i: usize, y: [T; V], buf: &mut [[T; V]]| match &mut out {
        Some((out, scale)) => {
            if let Some(o) = out.get_mut((i - lo) * V..) {
                for (o, y) in o.iter_mut().zip(y) {
                    *o = scale.clone() * y;
                }
            }
        }
        None => buf[i] = y,
    };
    let mut y: [T; V] = from_fn(|_| T::zero());
    for i in (lo..buf.len()).rev() {
        let f = fir::<T, V, true>(z, &mut carry, buf[i].clone());
        let y = stride(z, &mut y, f);
        emit(i, y, buf);
    }
}

/// The kernels of `f64` (8 lanes) and `f32` (16 lanes) for AVX-512 (one
/// register a chunk) and AVX2 + FMA (two, the lane shifts across the pair
/// by `vperm2f128` and `vshufpd`/`vpalignr`): the plain loops' operations
/// in the same order, in registers. Safe code: the intrinsics are safe
/// inside `#[target_feature]` functions, and chunks reach the registers as
/// arrays through `bytemuck` casts; the callers are the clones
/// `multiversion` compiled for those features and chose at run time.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::{Ahead, is};
    use crate::scalar::Real;
    use std::any::Any;
    use std::arch::x86_64::*;

    /// `x` as a `U` (`T` is `U`: checked by the caller).
    #[inline(always)]
    fn cast<T: 'static, U: 'static>(x: &T) -> &U {
        (x as &dyn Any).downcast_ref().expect("same type")
    }

    /// `x` as a `U` (`T` is `U`: checked by the caller).
    #[inline(always)]
    fn cast_mut<T: 'static, U: 'static>(x: &mut T) -> &mut U {
        (x as &mut dyn Any).downcast_mut().expect("same type")
    }

    /// The dispatchers of one instruction set: the causal and anti-causal
    /// passes in registers for `f64` × 8 and `f32` × 16 (`None` / `false`,
    /// nothing done, for other scalars and widths), through the kernel
    /// modules `$f64` and `$f32`.
    macro_rules! dispatch {
        ($feat:literal, $causal:ident, $anticausal:ident, $f64:ident, $f32:ident) => {
            #[target_feature(enable = $feat)]
            pub(super) fn $causal<T: Real, const V: usize>(
                z: &[T],
                src: Option<&[[T; V]]>,
                buf: &mut [[T; V]],
                ahead: Ahead<T>,
            ) -> Option<f64> {
                let ahead = ahead.map(|(s, o)| (s as *const i8, o as *const i8));
                if V == 8 && is::<T, f64>() {
                    return Some($f64::causal(powers(z)?, src, buf, ahead));
                }
                if V == 16 && is::<T, f32>() {
                    return Some($f32::causal(powers(z)?, src, buf, ahead));
                }
                None
            }

            #[target_feature(enable = $feat)]
            pub(super) fn $anticausal<T: Real, const V: usize>(
                z: &[T],
                buf: &mut [[T; V]],
                lo: usize,
                out: &mut Option<(&mut [T], &T)>,
            ) -> bool {
                if V == 8 && is::<T, f64>() {
                    let Some(z) = powers(z) else {
                        return false;
                    };
                    let out = out.as_mut().map(|(o, s)| (&mut **o, *cast::<T, f64>(s)));
                    $f64::anticausal(z, buf, lo, out);
                    return true;
                }
                if V == 16 && is::<T, f32>() {
                    let Some(z) = powers(z) else {
                        return false;
                    };
                    let out = out.as_mut().map(|(o, s)| (&mut **o, *cast::<T, f32>(s)));
                    $f32::anticausal(z, buf, lo, out);
                    return true;
                }
                false
            }
        };
    }

    dispatch!(
        "avx512f,avx512dq,fma",
        causal,
        anticausal,
        avx512_f64,
        avx512_f32
    );
    dispatch!("avx2,fma", causal_avx2, anticausal_avx2, avx2_f64, avx2_f32);

    /// The powers `z` as `[U; L]` (`T` is `U`), `None` unless there are `L`.
    #[inline(always)]
    fn powers<T: Real, U: Real + Copy, const L: usize>(z: &[T]) -> Option<[U; L]> {
        let mut p = [U::zero(); L];
        if z.len() != L {
            return None;
        }
        for (x, y) in p.iter_mut().zip(z) {
            *x = *cast::<T, U>(y);
        }
        Some(p)
    }

    /// The kernels of one vector type: `$v` lanes of `$t` in `$m` (with the
    /// target features `$feat`), lane shifts by `$after` (`valign` of two
    /// chunks), one `($l, $prev, $next)` per doubling level: the shift
    /// `2^$l` as the `valign` counts that bring in the previous chunk
    /// (causal) and the next one (anti-causal).
    macro_rules! kernels {
        ($name:ident, $feat:literal, $t:ty, $v:literal, $m:ty, $set1:ident, $zero:ident,
         $fmadd:ident, $mul:ident, $range:ident, $after:ident, $view:ident,
         $(($l:literal, $prev:literal, $next:literal, $int:literal)),+) => {
            #[allow(non_snake_case)]
            pub(super) mod $name {
                use super::*;

                /// Powers: the doubling levels', then `ξ^V`.
                const L: usize = [$($l),+].len() + 1;

                #[inline(always)]
                fn load<T: 'static, const V: usize>(x: &[T; V]) -> $m {
                    bytemuck::cast::<[$t; $v], $m>(*cast::<[T; V], [$t; $v]>(x))
                }

                #[inline(always)]
                fn store<T: 'static, const V: usize>(x: &mut [T; V], v: $m) {
                    *cast_mut::<[T; V], [$t; $v]>(x) = bytemuck::cast(v);
                }

                /// Lanes `N .. N + V` of `[lo, hi]` (`valign`).
                #[target_feature(enable = $feat)]
                #[inline]
                fn after<const N: i32>(hi: $m, lo: $m) -> $m {
                    $after::<N>(hi, lo)
                }

                /// A pole's registers: its powers, the chunks its doubling
                /// levels carry, the last `y` of the stride recursion, and a
                /// zero the compiler does not know (see [`fir`]).
                struct Pole {
                    z: [$m; L],
                    carry: [$m; L - 1],
                    y: $m,
                    opaque: $m,
                }

                #[target_feature(enable = $feat)]
                #[inline]
                fn pole(z: [$t; L]) -> Pole {
                    let zero = $zero();
                    let mut p = Pole {
                        z: [zero; L],
                        carry: [zero; L - 1],
                        y: zero,
                        opaque: $set1(std::hint::black_box(0.0)),
                    };
                    for (r, x) in p.z.iter_mut().zip(z) {
                        *r = $set1(x);
                    }
                    p
                }

                /// [`super::super::fir`] in registers. A level marked
                /// `$int` views its input as integers plus the opaque zero
                /// (the same bits): LLVM then shifts it by `valignq`/`valignd`
                /// (an immediate) instead of `vpermt2pd`/`vpermt2ps` (an
                /// index register, which it picks for lanes it last saw as
                /// floating point); the faster, measured in the [module
                /// documentation](super::super).
                #[target_feature(enable = $feat)]
                #[inline]
                fn fir<const ANTI: bool>(p: &mut Pole, x: $m) -> $m {
                    let mut cur = x;
                    $(
                        if $int {
                            cur = $view(cur, p.opaque);
                        }
                        let other = std::mem::replace(&mut p.carry[$l], cur);
                        let shifted = if ANTI {
                            after::<$next>(other, cur)
                        } else {
                            after::<$prev>(cur, other)
                        };
                        cur = $fmadd(p.z[$l], shifted, cur);
                    )+
                    cur
                }

                /// [`super::super::stride`] in registers.
                #[target_feature(enable = $feat)]
                #[inline]
                fn stride(p: &mut Pole, f: $m) -> $m {
                    p.y = $fmadd(p.z[L - 1], p.y, f);
                    p.y
                }

                /// [`super::super::causal_plain`] in registers; the
                /// magnitude by `vrangepd`/`vrangeps` (max of absolute
                /// values; what a NaN sample leaves there is not used).
                #[target_feature(enable = $feat)]
                pub(in super::super) fn causal<T: 'static, const V: usize>(
                    z: [$t; L],
                    src: Option<&[[T; V]]>,
                    buf: &mut [[T; V]],
                    ahead: Option<(*const i8, *const i8)>,
                ) -> f64 {
                    let mut p = pole(z);
                    let mut max = $zero();
                    let line = std::mem::size_of::<[$t; $v]>();
                    let mut input = |i: usize, buf: &[[T; V]]| match src {
                        Some(src) => match src.get(i) {
                            Some(s) => {
                                if let Some((s, o)) = ahead {
                                    _mm_prefetch::<_MM_HINT_T0>(s.wrapping_add(i * line));
                                    _mm_prefetch::<_MM_HINT_T0>(o.wrapping_add(i * line));
                                }
                                let x = load(s);
                                max = $range::<0b1011>(max, x);
                                x
                            }
                            None => $zero(),
                        },
                        None => load(&buf[i]),
                    };
                    for i in 0..buf.len() {
                        let f = fir::<false>(&mut p, input(i, buf));
                        store(&mut buf[i], stride(&mut p, f));
                    }
                    let max: [$t; $v] = bytemuck::cast(max);
                    max.iter().fold(0.0f64, |m, &x| super::super::magnitude(m, &x))
                }

                /// [`super::super::anticausal_plain`] in registers.
                #[target_feature(enable = $feat)]
                pub(in super::super) fn anticausal<T: Real, const V: usize>(
                    z: [$t; L],
                    buf: &mut [[T; V]],
                    lo: usize,
                    mut out: Option<(&mut [T], $t)>,
                ) {
                    let mut p = pole(z);
                    let scale = $set1(out.as_ref().map_or(1.0, |o| o.1));
                    let mut emit = |i: usize, y: $m, buf: &mut [[T; V]]| match &mut out {
                        Some((out, _)) => {
                            let at = (i - lo) * V;
                            let y = $mul(scale, y);
                            match out.get_mut(at..at + V) {
                                Some(o) => store(<&mut [T; V]>::try_from(o).expect("V lanes"), y),
                                None => {
                                    let y: [$t; $v] = bytemuck::cast(y);
                                    for (o, y) in out.iter_mut().skip(at).zip(y) {
                                        *cast_mut::<T, $t>(o) = y;
                                    }
                                }
                            }
                        }
                        None => store(&mut buf[i], y),
                    };
                    for i in (lo..buf.len()).rev() {
                        let f = fir::<true>(&mut p, load(&buf[i]));
                        let y = stride(&mut p, f);
                        emit(i, y, buf);
                    }
                }
            }
        };
    }

    /// A lane operation of AVX-512 done on the registers viewed as integers:
    /// `$from($op($to(a), $to(b)))`, the same bits in and out (the casts are
    /// free).
    macro_rules! on_integers {
        ($(#[$doc:meta])* $name:ident $(<$n:ident>)?, $m:ty, $to:ident, $from:ident, $op:ident) => {
            $(#[$doc])*
            #[target_feature(enable = "avx512f")]
            #[inline]
            fn $name$(<const $n: i32>)?(a: $m, b: $m) -> $m {
                $from($op$(::<$n>)?($to(a), $to(b)))
            }
        };
    }

    on_integers!(
        /// `valignq` on `f64` lanes: lanes `N .. N + 8` of `[b, a]`.
        after_pd8<N>, __m512d, _mm512_castpd_si512, _mm512_castsi512_pd, _mm512_alignr_epi64
    );
    on_integers!(
        /// `valignd` on `f32` lanes: lanes `N .. N + 16` of `[b, a]`.
        after_ps16<N>, __m512, _mm512_castps_si512, _mm512_castsi512_ps, _mm512_alignr_epi32
    );
    on_integers!(
        /// `a + b` as 64-bit integers: `a` when `b` is 0, in the integer
        /// domain ([`avx512_f64`]'s `fir`).
        int_pd8, __m512d, _mm512_castpd_si512, _mm512_castsi512_pd, _mm512_add_epi64
    );
    on_integers!(
        /// `a + b` as 32-bit integers ([`int_pd8`] for `f32`).
        int_ps16, __m512, _mm512_castps_si512, _mm512_castsi512_ps, _mm512_add_epi32
    );

    /// The operations of the kernels on a chunk in two AVX2 registers
    /// `$pair` of `$reg` (each half with its instruction): `$set1`, `$zero`,
    /// `$fmadd`, `$mul`, and `$absmax`, `max(m, |x|)` lane by lane (AVX2
    /// has no `vrange`; a NaN sample's lane is not used: the window reports
    /// it otherwise).
    macro_rules! pairs {
        ($pair:ident, $t:ty, $reg:ty, $set1:ident, $zero:ident, $fmadd:ident, $mul:ident,
         $absmax:ident, $same:ident, $i_set1:ident, $i_zero:ident, $i_fmadd:ident, $i_mul:ident,
         $i_max:ident, $i_andnot:ident) => {
            #[allow(non_camel_case_types)]
            type $pair = [$reg; 2];

            #[target_feature(enable = "avx2,fma")]
            #[inline]
            fn $set1(x: $t) -> $pair {
                [$i_set1(x); 2]
            }

            #[target_feature(enable = "avx2,fma")]
            #[inline]
            fn $zero() -> $pair {
                [$i_zero(); 2]
            }

            #[target_feature(enable = "avx2,fma")]
            #[inline]
            fn $fmadd(a: $pair, b: $pair, c: $pair) -> $pair {
                [$i_fmadd(a[0], b[0], c[0]), $i_fmadd(a[1], b[1], c[1])]
            }

            #[target_feature(enable = "avx2,fma")]
            #[inline]
            fn $mul(a: $pair, b: $pair) -> $pair {
                [$i_mul(a[0], b[0]), $i_mul(a[1], b[1])]
            }

            #[target_feature(enable = "avx2,fma")]
            #[inline]
            fn $absmax<const IMM: i32>(m: $pair, x: $pair) -> $pair {
                let sign = $i_set1(-0.0);
                [
                    $i_max(m[0], $i_andnot(sign, x[0])),
                    $i_max(m[1], $i_andnot(sign, x[1])),
                ]
            }

            /// `x` (the AVX2 kernels shift in the floating-point domain).
            #[inline(always)]
            fn $same(x: $pair, _zero: $pair) -> $pair {
                x
            }
        };
    }

    pairs!(
        f64x4x2,
        f64,
        __m256d,
        set1_pd2,
        zero_pd2,
        fmadd_pd2,
        mul_pd2,
        absmax_pd2,
        same_pd2,
        _mm256_set1_pd,
        _mm256_setzero_pd,
        _mm256_fmadd_pd,
        _mm256_mul_pd,
        _mm256_max_pd,
        _mm256_andnot_pd
    );
    pairs!(
        f32x8x2,
        f32,
        __m256,
        set1_ps2,
        zero_ps2,
        fmadd_ps2,
        mul_ps2,
        absmax_ps2,
        same_ps2,
        _mm256_set1_ps,
        _mm256_setzero_ps,
        _mm256_fmadd_ps,
        _mm256_mul_ps,
        _mm256_max_ps,
        _mm256_andnot_ps
    );

    /// Lanes `k .. k + 4` of `q` (16 lanes in four registers), `k < 12`.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn lanes4_pd(q: &[__m256d; 4], k: usize) -> __m256d {
        let (j, m) = (k / 4, k % 4);
        if m == 0 {
            return q[j];
        }
        let t = _mm256_permute2f128_pd::<0x21>(q[j], q[j + 1]);
        match m {
            1 => _mm256_shuffle_pd::<0b0101>(q[j], t),
            2 => t,
            _ => _mm256_shuffle_pd::<0b0101>(t, q[j + 1]),
        }
    }

    /// `valignq` of the pair: lanes `N .. N + 8` of `[lo, hi]`.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn after_pd2<const N: i32>(hi: f64x4x2, lo: f64x4x2) -> f64x4x2 {
        let q = [lo[0], lo[1], hi[0], hi[1]];
        let n = N as usize;
        [lanes4_pd(&q, n), lanes4_pd(&q, n + 4)]
    }

    /// Lanes `k .. k + 8` of `q` (32 lanes in four registers), `k < 24`:
    /// whole 128-bit halves by `vperm2f128`, the rest by `vpalignr` within
    /// the halves.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn lanes8_ps(q: &[__m256; 4], k: usize) -> __m256 {
        let (j, m) = (k / 8, k % 8);
        if m == 0 {
            return q[j];
        }
        let t = _mm256_permute2f128_ps::<0x21>(q[j], q[j + 1]);
        let (a, b) = if m < 4 { (t, q[j]) } else { (q[j + 1], t) };
        let (a, b) = (_mm256_castps_si256(a), _mm256_castps_si256(b));
        _mm256_castsi256_ps(match m % 4 {
            0 => return t,
            1 => _mm256_alignr_epi8::<4>(a, b),
            2 => _mm256_alignr_epi8::<8>(a, b),
            _ => _mm256_alignr_epi8::<12>(a, b),
        })
    }

    /// `valignd` of the pair: lanes `N .. N + 16` of `[lo, hi]`.
    #[target_feature(enable = "avx2,fma")]
    #[inline]
    fn after_ps2<const N: i32>(hi: f32x8x2, lo: f32x8x2) -> f32x8x2 {
        let q = [lo[0], lo[1], hi[0], hi[1]];
        let n = N as usize;
        [lanes8_ps(&q, n), lanes8_ps(&q, n + 8)]
    }

    // One line per kernel module: name, features, scalar, lanes, register,
    // the operations, then the doubling levels (shift 2^l: the valign counts
    // bringing in the previous and the next chunk).
    #[rustfmt::skip]
    kernels!(avx512_f64, "avx512f,avx512dq,fma", f64, 8, __m512d, _mm512_set1_pd, _mm512_setzero_pd,
        _mm512_fmadd_pd, _mm512_mul_pd, _mm512_range_pd, after_pd8, int_pd8,
        (0, 7, 1, true), (1, 6, 2, true), (2, 4, 4, false));
    #[rustfmt::skip]
    kernels!(avx512_f32, "avx512f,avx512dq,fma", f32, 16, __m512, _mm512_set1_ps, _mm512_setzero_ps,
        _mm512_fmadd_ps, _mm512_mul_ps, _mm512_range_ps, after_ps16, int_ps16,
        (0, 15, 1, true), (1, 14, 2, true), (2, 12, 4, true), (3, 8, 8, false));
    #[rustfmt::skip]
    kernels!(avx2_f64, "avx2,fma", f64, 8, f64x4x2, set1_pd2, zero_pd2, fmadd_pd2, mul_pd2,
        absmax_pd2, after_pd2, same_pd2, (0, 7, 1, false), (1, 6, 2, false), (2, 4, 4, false));
    #[rustfmt::skip]
    kernels!(avx2_f32, "avx2,fma", f32, 16, f32x8x2, set1_ps2, zero_ps2, fmadd_ps2, mul_ps2,
        absmax_ps2, after_ps2, same_ps2, (0, 15, 1, false), (1, 14, 2, false), (2, 12, 4, false),
        (3, 8, 8, false));
}

#[cfg(test)]
mod tests {
    //! The dispatched kernels (AVX-512 where the CPU has it, and the AVX2
    //! ones in their place) against the plain loops, bit for bit: f64 and
    //! f32, one to five poles, poles near 0 and near 1, windows of one
    //! chunk and of many, tails, the first coefficient at chunk 0 and
    //! later, and a last chunk the output only partly takes. (On a CPU
    //! without them both sides run the plain loops; the MPFR tests in
    //! `verify` hold there as well.)
    use super::*;

    /// Deterministic samples in [−1, 1), every fifth scaled by 10³.
    fn samples<T: Real>(n: usize, seed: u64) -> Vec<T> {
        (0..n as u64)
            .map(|i| {
                let k = (i + seed).wrapping_mul(7919) % 2003;
                let x = k as f64 / 1001.5 - 1.0;
                T::from_f64_exact(if i % 5 == 0 { x * 1e3 } else { x })
            })
            .collect()
    }

    /// Both ways through a window, dispatched and plain.
    fn check<T: Real, const V: usize>(poles: &[f64], chunks: usize, tail: usize, lo: usize) {
        let z: Vec<T> = poles.iter().map(|&z| T::from_f64_exact(z)).collect();
        let r = WindowRecursion::new(&z, &T::from_f64_exact(6.0));
        let src = samples::<T>(chunks * V, (chunks * 31 + tail) as u64);
        let (src, _) = src.as_chunks::<V>();
        let zero: [T; V] = from_fn(|_| T::zero());
        let len = (chunks + tail) * V;
        for take in [len - lo * V, (len - lo * V).saturating_sub(3), 1] {
            let mut got = vec![zero.clone(); chunks + tail];
            let mut want = got.clone();
            let (first, rest) = r.powers.split_first().unwrap();
            let m1 = causal(first, Some(src), &mut got, None);
            let m2 = causal_plain(first, Some(src), &mut want);
            assert_eq!(m1, m2, "max, poles {poles:?}");
            assert!(m1 > 0.0);
            for z in rest {
                causal(z, None, &mut got, None);
                causal_plain(z, None, &mut want);
            }
            assert!(got == want, "causal, poles {poles:?} chunks {chunks}");
            let (mut o1, mut o2) = (vec![T::zero(); take], vec![T::zero(); take]);
            for (k, z) in r.powers.iter().enumerate() {
                let last = k + 1 == r.powers.len();
                anticausal(z, &mut got, lo, last.then_some((&mut o1[..], &r.scale)));
                anticausal_plain(z, &mut want, lo, last.then_some((&mut o2[..], &r.scale)));
            }
            assert!(got == want, "anti-causal, poles {poles:?} chunks {chunks}");
            assert!(o1 == o2, "out, poles {poles:?} chunks {chunks} take {take}");
        }
    }

    fn every_shape<T: Real, const V: usize>() {
        let sets: [&[f64]; 6] = [
            &[-0.2679491924311228],
            &[-0.4305753470999738, -0.04309628820326465],
            &[
                -0.5352804307964382,
                -0.12255461519232669,
                -0.009148694809608277,
            ],
            &[-0.999],
            &[-1e-9, 0.5],
            &[-0.9, -0.6, -0.3, -0.1, -0.01],
        ];
        for poles in sets {
            for (chunks, tail, lo) in [(1, 0, 0), (1, 1, 0), (3, 2, 1), (40, 4, 3), (129, 5, 6)] {
                check::<T, V>(poles, chunks, tail, lo);
            }
        }
    }

    /// `f` with the AVX2 kernels standing in for the AVX-512 ones.
    fn on_avx2(f: impl FnOnce()) {
        AVX2_ONLY.with(|c| c.set(true));
        f();
        AVX2_ONLY.with(|c| c.set(false));
    }

    #[test]
    fn f64_vector_kernels_equal_the_plain_loops() {
        assert_eq!(lanes::<f64>(), 8);
        every_shape::<f64, 8>();
    }

    #[test]
    fn f32_vector_kernels_equal_the_plain_loops() {
        assert_eq!(lanes::<f32>(), 16);
        every_shape::<f32, 16>();
    }

    #[test]
    fn f64_avx2_kernels_equal_the_plain_loops() {
        on_avx2(every_shape::<f64, 8>);
    }

    #[test]
    fn f32_avx2_kernels_equal_the_plain_loops() {
        on_avx2(every_shape::<f32, 16>);
    }

    /// A NaN or infinite sample anywhere in a window (every lane of the
    /// first, a middle and the last chunk), with one pole or fused pairs,
    /// in f64 and f32, is reported; finite samples report `max|s|`.
    fn reports_non_finite<T: Real>() {
        let v = lanes::<T>();
        let poles: [&[f64]; 3] = [&[-0.25], &[-0.43, -0.043], &[-0.9, -0.5, -1e-7]];
        for z in poles {
            let z: Vec<T> = z.iter().map(|&z| T::from_f64_exact(z)).collect();
            let r = WindowRecursion::new(&z, &T::one());
            let mut s = samples::<T>(4 * v, 3);
            let mut out = vec![T::zero(); 4 * v];
            let want = s.iter().fold(0.0f64, |m, x| m.max(x.to_f64().abs()));
            let got = r.window(&s, v, 0, &mut out, &mut Vec::new(), None);
            assert_eq!(got, (want, true));
            for at in (0..v).chain(2 * v..2 * v + 1).chain(3 * v..4 * v) {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let keep = std::mem::replace(&mut s[at], T::from_f64_exact(bad));
                    let (_, finite) = r.window(&s, v, 0, &mut out, &mut Vec::new(), None);
                    assert!(!finite, "{bad} at {at}, {} poles", z.len());
                    s[at] = keep;
                }
            }
        }
    }

    #[test]
    fn a_non_finite_sample_is_reported_f64() {
        reports_non_finite::<f64>();
        on_avx2(reports_non_finite::<f64>);
    }

    #[test]
    fn a_non_finite_sample_is_reported_f32() {
        reports_non_finite::<f32>();
        on_avx2(reports_non_finite::<f32>);
    }
}
