//! The prefilter's row recursions, compiled for the vector units the CPU
//! has and chosen when first called: AVX-512, AVX2 + FMA (x86-64), NEON
//! (aarch64), or the build's baseline (x86-64: SSE2, two f64 lanes).
//!
//! Every kernel here is one generic scalar loop over rows of independent
//! lines (the blocks of one long line in [`BlockPrefilter`](super::block_filter::BlockPrefilter),
//! the side-by-side lines of a strided axis in
//! [`LineFilter::apply_lines`](super::line_filter::LineFilter::apply_lines)): step `i` of the
//! recursion is an element-wise operation over row `i`, which the compiler
//! vectorises as wide as the target allows. Why `multiversion`: it detects
//! the CPU's features at run time on stable Rust (no nightly, no
//! `-C target-cpu=native` for users), caches the choice in one atomic, and
//! leaves the code one generic scalar function (f32, f64 and MPFR alike)
//! that it compiles once per target — no intrinsics, no `unsafe` of ours.
//!
//! **Accuracy**: the same operations in the same order as the scalar loop;
//! Rust never contracts `a + z·b` into a fused multiply-add on its own, so
//! every target computes the baseline build's bits (the quick report's
//! accuracy figures are unchanged). Tested in f64 and f32 against 128-bit
//! MPFR and against the one-line scalar recursion in
//! `verify/tests/engine_lanes.rs`. **Source**: the recursions of Unser,
//! Aldroubi and Eden (1993), as in [`LineFilter`](super::line_filter::LineFilter).

use crate::scalar::Real;
use multiversion::multiversion;

/// Lines per group of the contiguous axis in `f64` (`nd_prefilter`; twice
/// as many in `f32`): rows of this width and twice it get the fixed-width
/// kernels.
pub(crate) const LINES: usize = 16;

/// `row_i += ξ · row_{i−1}` down `rows` (rows of `G` lines), `prev` the row
/// before the first on entry and the last row on return (the causal pass,
/// Unser, Aldroubi and Eden 1993).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn causal_fixed<T: Real, const G: usize>(rows: &mut [[T; G]], prev: &mut [T; G], z: &T) {
    for row in rows.iter_mut() {
        for (x, p) in row.iter_mut().zip(prev.iter_mut()) {
            *x += z.clone() * p.clone();
            *p = x.clone();
        }
    }
}

/// `row_i = ξ (row_{i+1} − row_i)` up `rows` (bottom row first), `next`
/// the row after the last on entry and the first row on return (the
/// anti-causal pass).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn anticausal_fixed<T: Real, const G: usize>(
    rows: &mut [[T; G]],
    next: &mut [T; G],
    z: &T,
) {
    for row in rows.iter_mut().rev() {
        for (x, n) in row.iter_mut().zip(next.iter_mut()) {
            *x = z.clone() * (n.clone() - x.clone());
            *n = x.clone();
        }
    }
}

/// The causal pass down every column of `c` (`L × w`, row `i` at
/// `c[i·w..]`): row `i` += ξ · row `i − 1`.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn causal_strided<T: Real>(c: &mut [T], w: usize, z: &T) {
    // Rows of a known width: the loop over a row unrolls into whole
    // registers (a runtime width of 8 fell to the scalar remainder).
    if w == LINES {
        return causal_rows_of::<T, LINES>(c, z);
    }
    if w == 2 * LINES {
        return causal_rows_of::<T, { 2 * LINES }>(c, z);
    }
    for i in 1..c.len() / w {
        let (head, tail) = c.split_at_mut(i * w);
        for (x, p) in tail[..w].iter_mut().zip(&head[(i - 1) * w..]) {
            *x += z.clone() * p;
        }
    }
}

/// The anti-causal pass up every column of `c` (`L × w`): row `i` =
/// ξ (row `i + 1` − row `i`).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn anticausal_strided<T: Real>(c: &mut [T], w: usize, z: &T) {
    if w == LINES {
        return anticausal_rows_of::<T, LINES>(c, z);
    }
    if w == 2 * LINES {
        return anticausal_rows_of::<T, { 2 * LINES }>(c, z);
    }
    for i in (0..c.len() / w - 1).rev() {
        let (head, tail) = c.split_at_mut((i + 1) * w);
        for (x, nx) in head[i * w..].iter_mut().zip(&tail[..w]) {
            *x = z.clone() * (nx.clone() - x.clone());
        }
    }
}

/// [`causal_strided`] on rows of `G` values.
fn causal_rows_of<T: Real, const G: usize>(c: &mut [T], z: &T) {
    if let Some((first, rest)) = c.as_chunks_mut::<G>().0.split_first_mut() {
        causal_fixed(rest, &mut first.clone(), z);
    }
}

/// [`anticausal_strided`] on rows of `G` values.
fn anticausal_rows_of<T: Real, const G: usize>(c: &mut [T], z: &T) {
    if let Some((last, rest)) = c.as_chunks_mut::<G>().0.split_last_mut() {
        anticausal_fixed(rest, &mut last.clone(), z);
    }
}

/// `c *= f`, element-wise (the gain).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn scale<T: Real>(c: &mut [T], f: &T) {
    for x in c.iter_mut() {
        *x *= f.clone();
    }
}

/// Rows `lo .. lo + rows.len()` of the windows `srcs` times `gain` into
/// `rows` (column `j` = window `j`; each window at least `lo +
/// rows.len()` long): a strip of the group buffer, small enough for L1.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn load_strip<T: Real, const G: usize, S: AsRef<[T]>>(
    rows: &mut [[T; G]],
    lo: usize,
    srcs: &[S],
    gain: &T,
) {
    for (j, src) in srcs.iter().enumerate() {
        for (row, x) in rows.iter_mut().zip(&src.as_ref()[lo..]) {
            row[j] = gain.clone() * x;
        }
    }
}

/// `outs[j][lo ..]` = column `j` of `rows` (a strip of the group buffer;
/// a block shorter than `lo + rows.len()` takes what it has room for).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn store_strip<T: Real, const G: usize>(
    outs: &mut [&mut [T]],
    rows: &[[T; G]],
    lo: usize,
) {
    for (j, o) in outs.iter_mut().enumerate() {
        if let Some(o) = o.get_mut(lo..) {
            for (o, row) in o.iter_mut().zip(rows) {
                *o = row[j].clone();
            }
        }
    }
}
