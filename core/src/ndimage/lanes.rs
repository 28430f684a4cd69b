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
//! that it compiles once per target — no `unsafe` of ours.
//!
//! The exception is the transposes between "`G` windows side by side" and
//! "one window contiguous" ([`load_strip`], [`store_strip`]): LLVM compiled
//! their element loops into AVX-512 gathers and scalar moves (`perf
//! annotate`), and as fixed `[[T; K]; K]` tiles still into scalar moves, so
//! f64 (4 × 4) and f32 (8 × 8) tiles go through AVX intrinsics
//! (unpack/shuffle/permute), safe inside the AVX2 clones (module `x86`);
//! other scalars keep the generic loops. Measured (`engine_peer tol1d 3
//! 10000000 20`, one thread, A/B alternated, min of 5): 20.8 → 15.8 ms.
//! Tried and dropped: 8 × 8 f64 tiles in AVX-512 registers (13.3 → 13.5
//! ms), software prefetch of the next strip (16.1 → 16.7 ms),
//! non-temporal stores of the transposed tiles (13.2 → 16.9 ms), the
//! finiteness/max scan folded into the tile load of the block route (13.7
//! → 17.9 ms: the windows' strided first read from memory is slower than
//! a sequential scan and a re-read from L2).
//!
//! Streaming stores ([`stream_row`]) are the other exception: whole rows
//! copied from L1 into an array larger than L3 by `vmovntpd`, which takes a
//! raw pointer, so the one `unsafe` call sits in a wrapper that checks the
//! line's bounds and alignment and falls back to ordinary stores
//! elsewhere (the N-D prefilter's first pass, the block route's quintic
//! windows).
//!
//! **Accuracy**: the same operations in the same order as the scalar loop;
//! Rust never contracts `a + z·b` into a fused multiply-add on its own, so
//! every target computes the baseline build's bits (the quick report's
//! accuracy figures are unchanged). Tested in f64 and f32 against 128-bit
//! MPFR and against the one-line scalar recursion in
//! `verify/tests/it/engine_lanes.rs`. **Source**: the recursions of Unser,
//! Aldroubi and Eden (1993), as in [`LineFilter`](super::line_filter::LineFilter).

use crate::scalar::Real;
use multiversion::{multiversion, target::match_target};
use std::any::TypeId;

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

/// Two poles' causal passes in one sweep down `rows` (rows of `G` lines):
/// `y = x + ξ₁ y`, `x = y + ξ₂ prev`, `prev = x` (the N-D prefilter's
/// cascade of two poles, `line_filter::Cascade`); `y` and `prev` carry
/// the first and the second pass's last row in and out.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn causal2_fixed<T: Real, const G: usize>(
    rows: &mut [[T; G]],
    y: &mut [T; G],
    prev: &mut [T; G],
    z1: &T,
    z2: &T,
) {
    for row in rows.iter_mut() {
        for ((x, y), p) in row.iter_mut().zip(y.iter_mut()).zip(prev.iter_mut()) {
            *y = x.clone() + z1.clone() * &*y;
            *x = y.clone() + z2.clone() * &*p;
            *p = x.clone();
        }
    }
}

/// Two poles' anti-causal passes in one sweep up `rows` (bottom row
/// first): `u = ξ₁ (u − x)`, `x = ξ₂ (next − u)`, `next = x`; `u` and
/// `next` carry the first and the second pass's row in and out.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn anticausal2_fixed<T: Real, const G: usize>(
    rows: &mut [[T; G]],
    u: &mut [T; G],
    next: &mut [T; G],
    z1: &T,
    z2: &T,
) {
    for row in rows.iter_mut().rev() {
        for ((x, u), n) in row.iter_mut().zip(u.iter_mut()).zip(next.iter_mut()) {
            *u = z1.clone() * (u.clone() - x.clone());
            *x = z2.clone() * (n.clone() - u.clone());
            *n = x.clone();
        }
    }
}

/// [`causal2_fixed`] down every column of `c` (`L × w`) from row 1: row 0
/// holds the second pass's start, `y` (`w` values) the first pass's, and
/// on return its last row.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn causal2_strided<T: Real>(c: &mut [T], w: usize, y: &mut [T], z1: &T, z2: &T) {
    if w == LINES {
        return cascade_rows_of::<T, LINES>(c, y, z1, z2, true);
    }
    if w == 2 * LINES {
        return cascade_rows_of::<T, { 2 * LINES }>(c, y, z1, z2, true);
    }
    for i in 1..c.len() / w {
        let (head, tail) = c.split_at_mut(i * w);
        for ((x, p), y) in tail[..w]
            .iter_mut()
            .zip(&head[(i - 1) * w..])
            .zip(y.iter_mut())
        {
            *y = x.clone() + z1.clone() * &*y;
            *x = y.clone() + z2.clone() * p;
        }
    }
}

/// [`anticausal2_fixed`] up every column of `c` (`L × w`) from row
/// `L − 2`: row `L − 1` holds the second pass's start, `u` the first
/// pass's.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn anticausal2_strided<T: Real>(c: &mut [T], w: usize, u: &mut [T], z1: &T, z2: &T) {
    if w == LINES {
        return cascade_rows_of::<T, LINES>(c, u, z1, z2, false);
    }
    if w == 2 * LINES {
        return cascade_rows_of::<T, { 2 * LINES }>(c, u, z1, z2, false);
    }
    for i in (0..c.len() / w - 1).rev() {
        let (head, tail) = c.split_at_mut((i + 1) * w);
        for ((x, nx), u) in head[i * w..].iter_mut().zip(&tail[..w]).zip(u.iter_mut()) {
            *u = z1.clone() * (u.clone() - x.clone());
            *x = z2.clone() * (nx.clone() - u.clone());
        }
    }
}

/// [`causal2_strided`] (`down`) or [`anticausal2_strided`] on rows of `G`
/// values.
fn cascade_rows_of<T: Real, const G: usize>(
    c: &mut [T],
    carry: &mut [T],
    z1: &T,
    z2: &T,
    down: bool,
) {
    let carry: &mut [T; G] = carry.try_into().expect("G values");
    let rows = c.as_chunks_mut::<G>().0;
    if down {
        if let Some((first, rest)) = rows.split_first_mut() {
            causal2_fixed(rest, carry, &mut first.clone(), z1, z2);
        }
    } else if let Some((last, rest)) = rows.split_last_mut() {
        anticausal2_fixed(rest, carry, &mut last.clone(), z1, z2);
    }
}

/// `c *= f`, element-wise (the gain).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
pub(crate) fn scale<T: Real>(c: &mut [T], f: &T) {
    for x in c.iter_mut() {
        *x *= f.clone();
    }
}

/// Arrays from this size on are written by non-temporal stores where a
/// pass writes values that it does not read again ([`stream_row`]): the
/// L3 of the development machine (32 MiB). Below it the destination may
/// still be in cache when the next pass reads it, and streaming it out to
/// memory would make that pass read it back from there.
pub(crate) const STREAM_BYTES: usize = 32 << 20;

/// `dst = src`, the whole 64-byte lines of `dst` written by non-temporal
/// (streaming) stores where the CPU has them (x86-64 with AVX-512 or AVX,
/// `f64` and `f32`), its ragged ends and everything else by ordinary
/// stores. A streaming store writes a whole cache line to memory without
/// reading it first: an ordinary store into a line that is not in cache
/// reads the line (read for ownership) before overwriting it, so a pass
/// from one array into another moves three times the array's bytes, not
/// two. Copies: the same values whichever store writes them. The stores
/// are weakly ordered: call [`stream_fence`] before the values are read
/// on another thread.
pub(crate) fn stream_row<T: Real>(dst: &mut [T], src: &[T]) {
    #[cfg(target_arch = "x86_64")]
    if const { T::FITS_F64 } && x86::stream(dst, src) {
        return;
    }
    dst.clone_from_slice(src);
}

/// Orders the streaming stores of [`stream_row`] before every later store
/// (a full fence): what a pass that streamed calls when it ends, before its
/// rows are handed to other threads (`rayon` synchronises ordinary
/// stores only).
pub(crate) fn stream_fence() {
    // A sequentially consistent fence is `mfence` on x86-64, which also
    // orders the weakly ordered streaming stores (as `sfence` would, but
    // without an `unsafe` call to a `target_feature` function).
    std::sync::atomic::fence(std::sync::atomic::Ordering::SeqCst);
}

/// Rows `lo .. lo + rows.len()` of the windows `srcs` times `gain` into
/// `rows` (column `j` = window `j`; each window at least `lo +
/// rows.len()` long): a strip of the group buffer, small enough for L1.
///
/// f32 and f64 move in square tiles ([`tile_side`]): each tile reads `K`
/// contiguous runs of `K` samples (one per window), transposes them in
/// vector registers (`x86::transpose_avx`) and writes `K` contiguous row pieces;
/// the rows and windows left over, and wider scalars (MPFR), take the
/// plain loop ([`load_plain`]). The same products either way (the gain
/// multiplies each sample once; a transpose does no arithmetic), tested
/// bit for bit against the plain loop in this module's tests.
pub(crate) fn load_strip<T: Real, const G: usize, S: AsRef<[T]>>(
    rows: &mut [[T; G]],
    lo: usize,
    srcs: &[S],
    gain: &T,
) {
    if const { !T::FITS_F64 } {
        // Wider than f64 (MPFR): no tile clones compiled (`Real::FITS_F64`).
        return load_plain(rows, lo, srcs, gain);
    }
    match tile_side::<T>() {
        8 if G.is_multiple_of(8) => load_tiles::<T, G, S, 8>(rows, lo, srcs, gain),
        4 if G.is_multiple_of(4) => load_tiles::<T, G, S, 4>(rows, lo, srcs, gain),
        _ => load_plain(rows, lo, srcs, gain),
    }
}

/// The side of [`load_strip`]'s and [`store_strip`]'s tiles for `T`: 8
/// for f32 and 4 for f64 (one 256-bit register per tile row), 0 (no tiles)
/// for other scalars, whose clones are not register moves.
fn tile_side<T: Real>() -> usize {
    if is::<T, f32>() {
        8
    } else if is::<T, f64>() {
        4
    } else {
        0
    }
}

/// Whether `T` is `U` (a constant once compiled).
fn is<T: 'static, U: 'static>() -> bool {
    TypeId::of::<T>() == TypeId::of::<U>()
}

/// [`load_strip`] element by element: the reference of the tiles, and
/// what MPFR runs.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn load_plain<T: Real, const G: usize, S: AsRef<[T]>>(
    rows: &mut [[T; G]],
    lo: usize,
    srcs: &[S],
    gain: &T,
) {
    for (j, src) in srcs.iter().enumerate() {
        load_column(rows, j, &src.as_ref()[lo..], gain);
    }
}

/// Column `j` of `rows` = `gain ·` the first `rows.len()` of `src`.
#[inline(always)]
fn load_column<T: Real, const G: usize>(rows: &mut [[T; G]], j: usize, src: &[T], gain: &T) {
    for (row, x) in rows.iter_mut().zip(src) {
        row[j] = gain.clone() * x;
    }
}

/// [`load_strip`] in `K × K` tiles (`G` a multiple of `K`).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn load_tiles<T: Real, const G: usize, S: AsRef<[T]>, const K: usize>(
    rows: &mut [[T; G]],
    lo: usize,
    srcs: &[S],
    gain: &T,
) {
    let whole = rows.len() / K * K;
    let (tiled, rest) = rows.split_at_mut(whole);
    let mut windows = srcs.chunks_exact(K);
    for (t, group) in (&mut windows).enumerate() {
        for (r, tile_rows) in tiled.chunks_exact_mut(K).enumerate() {
            let at = lo + r * K;
            // K contiguous runs in, one per window ...
            let runs: [&[T; K]; K] = std::array::from_fn(|j| {
                group[j].as_ref()[at..at + K].try_into().expect("K samples")
            });
            // ... K contiguous row pieces out.
            let mut pieces = tile_rows.iter_mut().map(|row| {
                <&mut [T; K]>::try_from(&mut row[t * K..(t + 1) * K]).expect("K columns")
            });
            let pieces: [&mut [T; K]; K] = std::array::from_fn(|_| pieces.next().expect("K rows"));
            match_target! {
                "x86_64+avx2" => {
                    let mut pieces = pieces;
                    if !x86::transpose_avx(&runs, &mut pieces, Some(gain)) {
                        transpose_plain(runs, pieces, Some(gain))
                    }
                }
                _ => transpose_plain(runs, pieces, Some(gain)),
            }
        }
    }
    // Windows beyond the last whole group of K, then the rows below the
    // last whole tile: element by element.
    let done = srcs.len() - windows.remainder().len();
    for (j, src) in srcs.iter().enumerate().skip(done) {
        load_column(tiled, j, &src.as_ref()[lo..], gain);
    }
    load_plain(rest, lo + whole, srcs, gain);
}

/// `outs[j][lo ..]` = column `j` of `rows` (a strip of the group buffer;
/// a block shorter than `lo + rows.len()` takes what it has room for).
///
/// f32 and f64 move in square tiles as [`load_strip`] (`K` row pieces in,
/// `K` contiguous runs out) wherever all `K` blocks of a tile have room
/// for its rows; the rest, and other scalars, element by element
/// ([`store_plain`]). Copies only: the same bits either way.
pub(crate) fn store_strip<T: Real, const G: usize>(
    outs: &mut [&mut [T]],
    rows: &[[T; G]],
    lo: usize,
) {
    if const { !T::FITS_F64 } {
        return store_plain(outs, rows, lo);
    }
    match tile_side::<T>() {
        8 if G.is_multiple_of(8) => store_tiles::<T, G, 8>(outs, rows, lo),
        4 if G.is_multiple_of(4) => store_tiles::<T, G, 4>(outs, rows, lo),
        _ => store_plain(outs, rows, lo),
    }
}

/// [`store_strip`] element by element.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn store_plain<T: Real, const G: usize>(outs: &mut [&mut [T]], rows: &[[T; G]], lo: usize) {
    for (j, o) in outs.iter_mut().enumerate() {
        store_column(o, rows, j, lo, 0);
    }
}

/// `o[lo + from ..]` = column `j` of `rows[from ..]`, as far as `o` has
/// room.
#[inline(always)]
fn store_column<T: Real, const G: usize>(
    o: &mut [T],
    rows: &[[T; G]],
    j: usize,
    lo: usize,
    from: usize,
) {
    if let (Some(o), Some(rows)) = (o.get_mut(lo + from..), rows.get(from..)) {
        for (o, row) in o.iter_mut().zip(rows) {
            *o = row[j].clone();
        }
    }
}

/// [`store_strip`] in `K × K` tiles (`G` a multiple of `K`).
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn store_tiles<T: Real, const G: usize, const K: usize>(
    outs: &mut [&mut [T]],
    rows: &[[T; G]],
    lo: usize,
) {
    let groups = outs.len() / K;
    let (grouped, left) = outs.split_at_mut(groups * K);
    for (t, group) in grouped.chunks_exact_mut(K).enumerate() {
        // Rows every block of the group has room for (a short last block
        // ends its group's tiles early).
        let room = group.iter().map(|o| o.len()).min().unwrap_or(0);
        let whole = room.saturating_sub(lo).min(rows.len()) / K * K;
        for (r, tile_rows) in rows[..whole].chunks_exact(K).enumerate() {
            let at = lo + r * K;
            // K contiguous row pieces in ...
            let pieces: [&[T; K]; K] = std::array::from_fn(|i| {
                tile_rows[i][t * K..(t + 1) * K]
                    .try_into()
                    .expect("K columns")
            });
            // ... K contiguous runs out, one per block.
            let mut runs = group
                .iter_mut()
                .map(|o| <&mut [T; K]>::try_from(&mut o[at..at + K]).expect("K samples"));
            let runs: [&mut [T; K]; K] = std::array::from_fn(|_| runs.next().expect("K blocks"));
            match_target! {
                "x86_64+avx2" => {
                    let mut runs = runs;
                    if !x86::transpose_avx(&pieces, &mut runs, None) {
                        transpose_plain(pieces, runs, None)
                    }
                }
                _ => transpose_plain(pieces, runs, None),
            }
        }
        for (j, o) in group.iter_mut().enumerate() {
            store_column(o, rows, t * K + j, lo, whole);
        }
    }
    for (j, o) in left.iter_mut().enumerate() {
        store_column(o, rows, groups * K + j, lo, 0);
    }
}

/// `dst[j][i] = gain · src[i][j]` (no gain: a copy): a `K × K` tile
/// transposed element by element (where [`x86::transpose_avx`] does not
/// apply).
#[inline(always)]
fn transpose_plain<T: Real, const K: usize>(
    src: [&[T; K]; K],
    dst: [&mut [T; K]; K],
    gain: Option<&T>,
) {
    for (j, d) in dst.into_iter().enumerate() {
        for (d, s) in d.iter_mut().zip(&src) {
            *d = match gain {
                Some(g) => g.clone() * &s[j],
                None => s[j].clone(),
            };
        }
    }
}

/// Asks the cache for every line of `row`, ahead of its use: a hint (no
/// effect on values), for loops whose rows lie far apart in memory (a
/// strided axis: each row a short run on its own page, which the
/// hardware prefetchers do not follow). Callable from the x86-64 clones
/// of `multiversion` functions (`match_target!`).
#[cfg(target_arch = "x86_64")]
pub(crate) use x86::prefetch;

/// The tile transposes in AVX registers. Safe code: the intrinsics are
/// safe inside a `#[target_feature]` function (Rust 1.87), and the tiles
/// reach the registers as arrays through `bytemuck` casts (`__m256d` is
/// `Pod`), no pointers; the callers reach these functions only from the
/// clones `multiversion` compiled for AVX2 and chose at run time.
#[cfg(target_arch = "x86_64")]
mod x86 {
    use super::is;
    use crate::scalar::Real;
    use std::any::Any;
    use std::arch::x86_64::*;

    /// [`super::transpose_plain`] in registers, for 4 × 4 tiles of `f64`
    /// and 8 × 8 of `f32`; `false` (nothing done) for other tiles.
    #[target_feature(enable = "avx")]
    #[inline]
    pub(super) fn transpose_avx<T: Real, const K: usize>(
        src: &[&[T; K]; K],
        dst: &mut [&mut [T; K]; K],
        gain: Option<&T>,
    ) -> bool {
        if K == 4 && is::<T, f64>() {
            let rows: [[f64; 4]; 4] = std::array::from_fn(|i| *cast::<_, [f64; 4]>(src[i]));
            let mut out = transpose_f64(rows);
            if let Some(g) = gain {
                let g = _mm256_set1_pd(*cast::<_, f64>(g));
                out = out.map(|r| _mm256_mul_pd(g, r));
            }
            for (d, r) in dst.iter_mut().zip(out) {
                *cast_mut::<_, [f64; 4]>(*d) = bytemuck::cast(r);
            }
            return true;
        }
        if K == 8 && is::<T, f32>() {
            let rows: [[f32; 8]; 8] = std::array::from_fn(|i| *cast::<_, [f32; 8]>(src[i]));
            let mut out = transpose_f32(rows);
            if let Some(g) = gain {
                let g = _mm256_set1_ps(*cast::<_, f32>(g));
                out = out.map(|r| _mm256_mul_ps(g, r));
            }
            for (d, r) in dst.iter_mut().zip(out) {
                *cast_mut::<_, [f32; 8]>(*d) = bytemuck::cast(r);
            }
            return true;
        }
        false
    }

    /// [`super::stream_row`] for `f64` and `f32` (`false`: nothing done,
    /// other scalars or a CPU without AVX): the head of `dst` up to its
    /// first 64-byte boundary and the tail after its last whole line by
    /// ordinary stores, the lines between by [`stream_f64`] / [`stream_f32`].
    pub(super) fn stream<T: Real>(dst: &mut [T], src: &[T]) -> bool {
        assert_eq!(dst.len(), src.len(), "stream_row: rows of one length");
        let avx512 = std::is_x86_feature_detected!("avx512f");
        if !(avx512 || std::is_x86_feature_detected!("avx")) {
            return false;
        }
        let lanes = 64 / size_of::<T>();
        let head = dst.as_ptr().align_offset(64).min(dst.len());
        if !(is::<T, f64>() || is::<T, f32>()) {
            return false;
        }
        let (d_head, d_rest) = dst.split_at_mut(head);
        let (s_head, s_rest) = src.split_at(head);
        d_head.clone_from_slice(s_head);
        let whole = d_rest.len() / lanes * lanes;
        let (d_mid, d_tail) = d_rest.split_at_mut(whole);
        let (s_mid, s_tail) = s_rest.split_at(whole);
        d_tail.clone_from_slice(s_tail);
        // The lines as `[f64; 8]` (the bytes of 16 `f32` alike).
        if is::<T, f64>() {
            let d = d_mid.as_chunks_mut::<8>().0.iter_mut();
            let s = s_mid.as_chunks::<8>().0.iter();
            stream_lines(d.zip(s).map(|(d, s)| (cast_mut(d), *cast(s))), avx512);
        } else {
            let d = d_mid.as_chunks_mut::<16>().0.iter_mut();
            let s = s_mid.as_chunks::<16>().0.iter();
            let lines = d.zip(s).map(|(d, s)| {
                let (d, s) = (cast_mut::<_, [f32; 16]>(d), cast::<_, [f32; 16]>(s));
                (bytemuck::cast_mut(d), bytemuck::cast(*s))
            });
            stream_lines(lines, avx512);
        }
        true
    }

    /// [`lines_512`] where `avx512`, else [`lines_256`] (AVX).
    #[inline(always)]
    fn stream_lines<'a>(lines: impl Iterator<Item = (&'a mut [f64; 8], [f64; 8])>, avx512: bool) {
        // SAFETY (both calls): the caller detected the target feature.
        #[allow(unsafe_code)]
        match avx512 {
            true => unsafe { lines_512(lines) },
            false => unsafe { lines_256(lines) },
        }
    }

    /// `d = s` by one 512-bit non-temporal store (`vmovntpd`) per
    /// 64-byte line of `d` (each aligned to 64: checked).
    #[target_feature(enable = "avx512f")]
    fn lines_512<'a>(lines: impl Iterator<Item = (&'a mut [f64; 8], [f64; 8])>) {
        for (d, s) in lines {
            assert!(
                d.as_ptr().cast::<u8>().align_offset(64) == 0,
                "a whole line"
            );
            let v: __m512d = bytemuck::cast(s);
            // SAFETY: `d` is 64 writable bytes aligned to 64 (asserted),
            // borrowed mutably: exactly what the store writes.
            #[allow(unsafe_code)]
            unsafe {
                _mm512_stream_pd(d.as_mut_ptr(), v)
            };
        }
    }

    /// [`lines_512`] by two 256-bit non-temporal stores per line (AVX).
    #[target_feature(enable = "avx")]
    fn lines_256<'a>(lines: impl Iterator<Item = (&'a mut [f64; 8], [f64; 8])>) {
        for (d, s) in lines {
            assert!(
                d.as_ptr().cast::<u8>().align_offset(64) == 0,
                "a whole line"
            );
            let [lo, hi]: [__m256d; 2] = bytemuck::cast(s);
            let p = d.as_mut_ptr();
            // SAFETY: `p` and `p + 4` are the two aligned 32-byte halves
            // of `d` (64 writable bytes aligned to 64, asserted, borrowed
            // mutably): exactly what the stores write.
            #[allow(unsafe_code)]
            unsafe {
                _mm256_stream_pd(p, lo);
                _mm256_stream_pd(p.add(4), hi);
            }
        }
    }

    /// [`super::prefetch`]: one `prefetcht0` per 64-byte line of `row`
    /// (addresses formed with wrapping arithmetic, never dereferenced).
    #[target_feature(enable = "sse")]
    #[inline]
    pub(crate) fn prefetch<T>(row: &[T]) {
        let bytes = std::mem::size_of_val(row);
        let p = row.as_ptr().cast::<i8>();
        for k in (0..bytes).step_by(64) {
            _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(k));
        }
        if bytes > 0 {
            _mm_prefetch::<_MM_HINT_T0>(p.wrapping_add(bytes - 1));
        }
    }

    /// `x` as a `U` (`T` is `U`: checked by the caller).
    fn cast<T: 'static, U: 'static>(x: &T) -> &U {
        (x as &dyn Any).downcast_ref().expect("same type")
    }

    /// `x` as a `U` (`T` is `U`: checked by the caller).
    fn cast_mut<T: 'static, U: 'static>(x: &mut T) -> &mut U {
        (x as &mut dyn Any).downcast_mut().expect("same type")
    }

    /// Rows `a b c d` to columns: unpack pairs within 128-bit halves, then
    /// swap halves.
    #[target_feature(enable = "avx")]
    #[inline]
    fn transpose_f64(rows: [[f64; 4]; 4]) -> [__m256d; 4] {
        let [a, b, c, d] = rows.map(bytemuck::cast::<[f64; 4], __m256d>);
        let ab0 = _mm256_unpacklo_pd(a, b); // a0 b0 a2 b2
        let ab1 = _mm256_unpackhi_pd(a, b); // a1 b1 a3 b3
        let cd0 = _mm256_unpacklo_pd(c, d);
        let cd1 = _mm256_unpackhi_pd(c, d);
        [
            _mm256_permute2f128_pd::<0x20>(ab0, cd0),
            _mm256_permute2f128_pd::<0x20>(ab1, cd1),
            _mm256_permute2f128_pd::<0x31>(ab0, cd0),
            _mm256_permute2f128_pd::<0x31>(ab1, cd1),
        ]
    }

    /// The 8 × 8 `f32` transpose: unpack pairs, shuffle quads (within
    /// 128-bit lanes), then swap halves.
    #[target_feature(enable = "avx")]
    #[inline]
    fn transpose_f32(rows: [[f32; 8]; 8]) -> [__m256; 8] {
        let r = rows.map(bytemuck::cast::<[f32; 8], __m256>);
        let t: [__m256; 8] = std::array::from_fn(|k| {
            let (a, b) = (r[k / 2 * 2], r[k / 2 * 2 + 1]);
            if k % 2 == 0 {
                _mm256_unpacklo_ps(a, b)
            } else {
                _mm256_unpackhi_ps(a, b)
            }
        });
        // t[0] = r0 r1 interleaved low, t[1] high, t[2]/t[3] for r2 r3, ...
        let q: [__m256; 8] = std::array::from_fn(|k| {
            let base = k / 4 * 4;
            let (a, b) = (t[base + (k % 4) / 2], t[base + 2 + (k % 4) / 2]);
            if k % 2 == 0 {
                _mm256_shuffle_ps::<0x44>(a, b)
            } else {
                _mm256_shuffle_ps::<0xEE>(a, b)
            }
        });
        std::array::from_fn(|k| {
            let (a, b) = (q[k % 4], q[4 + k % 4]);
            if k < 4 {
                _mm256_permute2f128_ps::<0x20>(a, b)
            } else {
                _mm256_permute2f128_ps::<0x31>(a, b)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    //! The tiled transposes against the plain loops, bit for bit: every
    //! tile size (4 × 4 f64, 8 × 8 f32), groups of 16 and 32 columns and
    //! one that is no multiple of the f32 tile, strips whose length is no
    //! multiple of the tile, fewer windows than columns, and short blocks.
    use super::*;

    /// Deterministic values of every sign and scale, subnormals included
    /// (a transpose must move them untouched).
    fn values<T: Real>(n: usize, seed: u64) -> Vec<T> {
        let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        (0..n)
            .map(|i| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let m = (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
                let v = match i % 7 {
                    0 => m * 1e-310,
                    1 => m * 1e30,
                    _ => m,
                };
                T::from_f64_exact(v)
            })
            .collect()
    }

    /// `load_strip` and `store_strip` against `load_plain` and
    /// `store_plain` for `windows` windows, strips of `len` rows at `lo`,
    /// and blocks of `room[j]` samples in the store.
    fn check<T: Real, const G: usize>(windows: usize, len: usize, lo: usize, short: usize) {
        let span = lo + len + 3;
        let srcs: Vec<Vec<T>> = (0..windows).map(|j| values(span, j as u64)).collect();
        let gain = T::from_f64_exact(1.0 / 0.36);
        let zero: [T; G] = std::array::from_fn(|_| T::zero());
        let (mut got, mut want) = (vec![zero.clone(); len], vec![zero; len]);
        load_strip(&mut got, lo, &srcs, &gain);
        load_plain(&mut want, lo, &srcs, &gain);
        assert!(
            got == want,
            "load G={G} windows={windows} len={len} lo={lo}"
        );
        // The store: block `j` ends `short · j` samples early (a ragged last block).
        let rows: Vec<[T; G]> = (0..len)
            .map(|i| std::array::from_fn(|j| values::<T>(1, (i * G + j) as u64)[0].clone()))
            .collect();
        let mut got: Vec<Vec<T>> = (0..windows)
            .map(|j| vec![T::zero(); (lo + len).saturating_sub(short * j)])
            .collect();
        let mut want = got.clone();
        store_strip(
            &mut got.iter_mut().map(|v| &mut v[..]).collect::<Vec<_>>(),
            &rows,
            lo,
        );
        store_plain(
            &mut want.iter_mut().map(|v| &mut v[..]).collect::<Vec<_>>(),
            &rows,
            lo,
        );
        assert!(
            got == want,
            "store G={G} windows={windows} len={len} lo={lo} short={short}"
        );
    }

    fn every_shape<T: Real>() {
        for len in [0, 1, 3, 4, 7, 8, 9, 17, 64] {
            for lo in [0, 5] {
                for short in [0, 1, 6] {
                    for windows in [1, 3, 4, 8, 13, 16] {
                        check::<T, 16>(windows, len, lo, short);
                        check::<T, 12>(windows.min(12), len, lo, short);
                    }
                    for windows in [5, 24, 31, 32] {
                        check::<T, 32>(windows, len, lo, short);
                    }
                }
            }
        }
    }

    #[test]
    fn f64_tiles_equal_the_plain_loop() {
        assert_eq!(tile_side::<f64>(), 4);
        every_shape::<f64>();
    }

    #[test]
    fn f32_tiles_equal_the_plain_loop() {
        assert_eq!(tile_side::<f32>(), 8);
        every_shape::<f32>();
    }

    #[test]
    fn mpfr_takes_the_plain_loop() {
        assert_eq!(tile_side::<crate::scalar::Mp<128>>(), 0);
        check::<crate::scalar::Mp<128>, 8>(5, 9, 2, 1);
    }

    /// `stream_row` writes exactly `src` into `dst` and nothing around it:
    /// every length from 0 to 80 at every offset within two cache lines
    /// (heads, whole lines and tails of each size), f64 and f32, each
    /// value's bits (subnormals, NaN-free) against the source. Fails when
    /// the head, the lines or the tail are off by one.
    fn streams<T: Real>() {
        let src = values::<T>(80, 3);
        let guard = T::from_f64_exact(-7.25);
        for off in 0..2 * 64 / size_of::<T>() {
            for len in 0..=80 {
                let mut dst = vec![guard.clone(); off + len + 20];
                stream_row(&mut dst[off..off + len], &src[..len]);
                stream_fence();
                let bits = |x: &T| x.to_f64().to_bits();
                assert!(
                    dst[..off].iter().all(|x| bits(x) == bits(&guard)),
                    "before, {off} {len}"
                );
                assert!(
                    dst[off..off + len]
                        .iter()
                        .zip(&src)
                        .all(|(a, b)| bits(a) == bits(b)),
                    "values, {off} {len}"
                );
                assert!(
                    dst[off + len..].iter().all(|x| bits(x) == bits(&guard)),
                    "after, {off} {len}"
                );
            }
        }
    }

    #[test]
    fn streamed_rows_are_the_source_bit_for_bit() {
        streams::<f64>();
        streams::<f32>();
        streams::<crate::scalar::Mp<128>>();
    }
}
