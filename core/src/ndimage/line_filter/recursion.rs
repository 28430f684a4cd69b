//! A pole's first-order recursions and their initial values: the causal
//! pass `c⁺_k = c_k + ξ c⁺_{k−1}` and the anti-causal pass
//! `c⁻_k = ξ (c⁻_{k+1} − c⁺_k)` of one line (two steps at a time), the
//! causal start summed over the mode's extension to the pole's horizon and
//! the anti-causal start in the mode's closed form (the
//! [`line_filter`](super) documentation), for one line and for every column
//! of rows side by side. The one-line forms are what
//! [`LineFilter::apply`](super::LineFilter::apply) runs pole after pole; the
//! column starts begin the strided passes (`rows`, `blocks`). Apart because
//! they are the filter's mathematics, shared by every way of running it.

use crate::ndimage::mode::{Folds, Mode};
use crate::scalar::Real;
use multiversion::multiversion;

/// One Horner step of a start, `acc = row + ξ · acc` for a row of `w`
/// values, or `acc = g · row + ξ · acc` with a gain `g` (the row scaled
/// first, as [`lanes::scale`](crate::ndimage::lanes::scale) does).
/// Inlined into [`horner_start`]'s vector clones.
#[inline(always)]
fn horner_row<T: Real>(acc: &mut [T], z: &T, row: &[T], gain: Option<&T>) {
    match gain {
        Some(g) => {
            for (a, x) in acc.iter_mut().zip(row) {
                *a = g.clone() * x + z.clone() * &*a;
            }
        }
        None => {
            for (a, x) in acc.iter_mut().zip(row) {
                *a = x.clone() + z.clone() * &*a;
            }
        }
    }
}

/// `acc = Σ row(i_m) ξ^{m}` over the rows `row(i)` in the order `order`
/// gives them, by Horner's rule (`acc ← row(i) + ξ acc`, from zero), as
/// one call into the vector clone (a short line's causal start folds
/// through ~28 rows). A group's few columns (at most [`IN_REGISTERS`]) go
/// [`CHUNK`] at a time through the whole sum, held in registers rather
/// than stored and reloaded after every row; wider strips, whose rows are
/// runs far apart in a large array, are read row after row as the
/// prefetcher streams them. Either way each column gets the same
/// operations in the same order.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn horner_start<'a, T, I, F>(acc: &mut [T], z: &T, order: I, row: F, gain: Option<&T>)
where
    T: Real + 'a,
    I: Iterator<Item = usize> + Clone,
    F: Fn(usize) -> &'a [T],
{
    // The columns summed in registers, a multiple of `CHUNK`; the rest row
    // after row.
    let held = match acc.len() <= IN_REGISTERS {
        true => acc.len() / CHUNK * CHUNK,
        false => 0,
    };
    let (chunked, rest) = acc.split_at_mut(held);
    for (c, out) in chunked.chunks_exact_mut(CHUNK).enumerate() {
        let at = c * CHUNK;
        let mut a: [T; CHUNK] = std::array::from_fn(|_| T::zero());
        for i in order.clone() {
            horner_row(&mut a, z, &row(i)[at..at + CHUNK], gain);
        }
        out.clone_from_slice(&a);
    }
    rest.fill(T::zero());
    for i in order {
        horner_row(rest, z, &row(i)[held..], gain);
    }
}

/// Columns of [`horner_start`] carried in registers at once: two AVX-512
/// vectors of `f64` (two independent chains hide the multiply-add's latency).
const CHUNK: usize = 16;

/// Columns of [`horner_start`] at most summed [`CHUNK`] at a time: a
/// last-axis group of lines (16 of `f64`, 32 of `f32`).
const IN_REGISTERS: usize = 32;

/// The rows a causal start sums, `fold(−j)` for `j = K − 1, …, 0`
/// ([`causal_start`]'s order), walked by [`Mode::folds`] (no division per row).
pub(super) fn causal_order(horizon: usize, mode: Mode, len: usize) -> CausalOrder {
    let k = horizon.max(1);
    CausalOrder {
        folds: mode.folds(1 - k as i64, len),
        left: k,
    }
}

/// The rows grid-wrap's anti-causal start sums, `(ν − 1 + j) mod ν` for
/// `j = K − 1, …, 0` of `n = ν` rows: the periodic sum of
/// [`anticausal_start`], for one pole and for a [`Cascade`](super::cascade::Cascade)'s pair.
pub(super) fn periodic_end_order(horizon: usize, n: usize) -> impl Iterator<Item = usize> + Clone {
    (0..horizon.max(1)).rev().map(move |j| (n - 1 + j) % n)
}

/// The iterator of [`causal_order`] (its own type so that it inlines into
/// the starts' vector clones).
#[derive(Clone)]
pub(super) struct CausalOrder {
    folds: Folds,
    left: usize,
}

impl Iterator for CausalOrder {
    type Item = usize;

    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        self.left = self.left.checked_sub(1)?;
        self.folds.next().map(|i| i.unwrap_or(0))
    }
}

/// [`causal_start`] of every column of `rows` (times `gain` first, if
/// given), into `acc`.
pub(super) fn causal_start_of<T: Real, R: AsRef<[T]>>(
    rows: &[R],
    gain: Option<&T>,
    z: &T,
    horizon: usize,
    mode: Mode,
    acc: &mut [T],
) {
    horner_start(
        acc,
        z,
        causal_order(horizon, mode, rows.len()),
        |i| rows[i].as_ref(),
        gain,
    );
}

/// [`causal_start`] of every column of `c` (`L × w`), into `acc`.
pub(super) fn causal_start_rows<T: Real>(
    c: &[T],
    w: usize,
    z: &T,
    horizon: usize,
    mode: Mode,
    acc: &mut [T],
) {
    let row = |i: usize| &c[i * w..(i + 1) * w];
    horner_start(acc, z, causal_order(horizon, mode, c.len() / w), row, None);
}

/// [`anticausal_start`] of every column, into `acc`.
pub(super) fn anticausal_start_rows<T: Real>(
    c: &[T],
    w: usize,
    z: &T,
    horizon: usize,
    mode: Mode,
    acc: &mut [T],
) {
    let n = c.len() / w;
    let last = &c[(n - 1) * w..];
    match mode {
        Mode::Reflect => {
            let f = z.clone() / (z.clone() - T::one());
            for (a, x) in acc.iter_mut().zip(last) {
                *a = f.clone() * x;
            }
        }
        Mode::GridWrap => {
            let order = periodic_end_order(horizon, n);
            horner_start(acc, z, order, |i| &c[i * w..(i + 1) * w], None);
            let mz = -z.clone();
            for a in acc.iter_mut() {
                *a = mz.clone() * a.clone();
            }
        }
        _ => {
            let f = z.clone() / (z.clone() * z - T::one());
            let before = &c[(n - 2) * w..(n - 1) * w];
            for ((a, x), y) in acc.iter_mut().zip(last).zip(before) {
                *a = f.clone() * (x.clone() + z.clone() * y.clone());
            }
        }
    }
}

/// `c⁺_k = c_k + ξ c⁺_{k−1}`, `k ≥ 1`, run two steps at a time:
/// `c⁺_k = (c_k + ξ c_{k−1}) + ξ² c⁺_{k−2}`. One step is a dependent
/// multiply-add (the loop is bound by its latency, not by arithmetic);
/// with the look-ahead, two interleaved chains advance at once, the
/// `ξ c_{k−1}` terms being independent work. Rounding: one more operation
/// per sample and the rounded `ξ²`, each a relative `u` on terms the
/// recursion damps by `1/(1 − ξ²)`: the same few ulps.
#[inline]
pub(super) fn causal<T: Real>(c: &mut [T], z: T) {
    if c.len() < 2 {
        return;
    }
    let z2 = z.clone() * &z;
    let mut older = c[0].clone();
    let mut s_prev = c[1].clone();
    c[1] += z.clone() * &older;
    let mut prev = c[1].clone();
    for x in c[2..].iter_mut() {
        let s = x.clone();
        *x = (s.clone() + z.clone() * s_prev) + z2.clone() * older;
        older = prev;
        prev = x.clone();
        s_prev = s;
    }
}

/// `c⁻_k = ξ (c⁻_{k+1} − c⁺_k)`, `k < ν − 1`, two steps at a time as in
/// [`causal`]: `c⁻_k = ξ² c⁻_{k+2} − (ξ² c⁺_{k+1} + ξ c⁺_k)`.
#[inline]
pub(super) fn anticausal<T: Real>(c: &mut [T], z: T) {
    let n = c.len();
    if n < 2 {
        return;
    }
    let z2 = z.clone() * &z;
    let mut later = c[n - 1].clone();
    let mut s_next = c[n - 2].clone();
    c[n - 2] = z.clone() * (later.clone() - &s_next);
    let mut next = c[n - 2].clone();
    for x in c[..n - 2].iter_mut().rev() {
        let s = x.clone();
        *x = z2.clone() * later - (z2.clone() * s_next + z.clone() * &s);
        later = next;
        next = x.clone();
        s_next = s;
    }
}

/// `c⁺_0 = Σ_{j<K} ξ^j s_{−j}`, the samples extended by `mode` (symmetric
/// or periodic), truncated at the horizon `K` and evaluated by Horner's
/// rule from the far end, `a ← s_{−j} + ξ a` for `j = K − 1, …, 0`: each
/// rounding is damped by `ξ^j` on its way to `c⁺_0`, so the sum carries
/// about `u |c⁺_0| / (1 − |ξ|)`, as one step of the recursion does. (Summed
/// from `j = 0` with running powers, every one of the `≈ K` additions rounds
/// at the full size of the sum: for a line shorter than the horizon,
/// folded back and forth, that was the largest error of the filter after
/// the gain's; `verify/tests/it/prefilter_rounding.rs` pins it.)
pub(super) fn causal_start<T: Real>(c: &[T], z: &T, horizon: usize, mode: Mode) -> T {
    causal_order(horizon, mode, c.len()).fold(T::zero(), |sum, i| c[i].clone() + z.clone() * sum)
}

/// `c⁻_{ν−1}` of the mode (module documentation); grid-wrap's periodic sum
/// `−ξ Σ_{j<K} ξ^j c⁺_{(ν−1+j) mod ν}` by Horner's rule as [`causal_start`].
pub(super) fn anticausal_start<T: Real>(c: &[T], z: &T, horizon: usize, mode: Mode) -> T {
    let n = c.len();
    let z = z.clone();
    match mode {
        Mode::Reflect => z.clone() / (z - T::one()) * c[n - 1].clone(),
        Mode::GridWrap => {
            let sum = periodic_end_order(horizon, n)
                .fold(T::zero(), |sum, i| c[i].clone() + z.clone() * sum);
            -z * sum
        }
        _ => z.clone() / (z.clone() * &z - T::one()) * (c[n - 1].clone() + z * c[n - 2].clone()),
    }
}
