//! Continuity across the joins of a multi-patch surface: the control-point
//! correction of seed 001 §2.3 (eq 5–6) and a measurement of the joins.
//!
//! # The correction
//!
//! Number the control points of an `n_u × n_v` grid of degree-`n` patches
//! globally, `(g_u, g_v) ∈ [0, n_u n] × [0, n_v n]`; patch `(p, q)`'s `P_ij`
//! is `(p n + i, q n + j)`, so points on a shared edge have one copy per
//! patch. The paper's *connected control point group* of a joint (a patch
//! corner `(a n, b n)` shared by two or four patches) is the `3 × 3` block
//! `{an−1, an, an+1} × {bn−1, bn, bn+1}` (clipped at the surface boundary,
//! giving `2 × 3` / `3 × 2` blocks). For bicubic patches these blocks cover
//! every control point on and next to a shared edge; for `n > 3` the
//! remaining edge points `(an, g_v)` get the `3 × 1` block across their edge
//! (and likewise in `v`). Each block is processed independently:
//!
//! 1. each point's value is the mean of its copies (restoring C⁰ if a
//!    deformation broke it; the copies are equal otherwise);
//! 2. the `u`-direction difference vectors `u_k` of neighbouring points in the
//!    block (six for an interior bicubic joint) and the `v`-direction ones
//!    `v_k` are formed;
//! 3. eq 5–6 as printed: `n_u = (1/K) Σ |u_k|`, `ū = Σ u_k / Σ |u_k|`,
//!    `u⁰ = n_u ū`, which simplifies exactly to the mean `u⁰ = (1/K) Σ u_k`
//!    — computed in that form (fewer roundings, no `0/0` when the block has
//!    collapsed); `v⁰` likewise. (Reading `ū` as a unit vector,
//!    `Σu_k/|Σu_k|`, would change only the length of `u⁰`, not the joins.)
//! 4. the centre (the joint or edge point) stays; the block is re-placed on
//!    the regular grid `centre + (g_u − c_u) u⁰ + (g_v − c_v) v⁰`, and every
//!    copy receives the new value.
//!
//! Afterwards, along every shared edge, `P_{n,j} − P_{n−1,j}` of one patch
//! equals `P_{1,j} − P_{0,j}` of its neighbour (up to rounding), so the two
//! cross-boundary derivatives `n Σ_j B_j(v)(·)` agree: C¹, hence G¹, joins.
//! Surface corners belong to one patch and are left alone.

use super::patch::{Patch, PatchGrid, Point3};
use crate::scalar::Real;
use crate::validation::{InputError, degree_at_least};

/// Why the correction cannot be applied.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContinuityError {
    /// The blocks of neighbouring joints overlap unless `n ≥ 3`.
    #[error(transparent)]
    Input(#[from] InputError),
    /// The number of samples along an edge must be at least 2.
    #[error("at least 2 samples per edge are needed, got {0}")]
    TooFewSamples(usize),
}

/// Global indexing of a grid's control points and their copies.
struct Net<'a, T: Real> {
    grid: &'a PatchGrid<T>,
    n: usize,
}

impl<T: Real> Net<'_, T> {
    /// Patches (along one direction) whose index range contains `g`.
    fn owners(&self, g: usize, count: usize) -> Vec<usize> {
        let n = self.n;
        if g.is_multiple_of(n) {
            let k = g / n;
            [k.checked_sub(1), Some(k)]
                .into_iter()
                .flatten()
                .filter(|&p| p < count)
                .collect()
        } else {
            vec![g / n]
        }
    }

    /// Every copy of global point `(gu, gv)` as `(patch index, local index)`.
    fn copies(&self, gu: usize, gv: usize) -> Vec<(usize, usize)> {
        let (nu, nv, n) = (self.grid.nu(), self.grid.nv(), self.n);
        let mut out = Vec::new();
        for p in self.owners(gu, nu) {
            for q in self.owners(gv, nv) {
                out.push((p * nv + q, (gu - p * n) * (n + 1) + (gv - q * n)));
            }
        }
        out
    }

    /// The mean of the copies of `(gu, gv)`.
    fn value(&self, gu: usize, gv: usize) -> Point3<T> {
        let c = self.copies(gu, gv);
        let sum = c.iter().fold(Point3::zeros(), |s, &(p, k)| {
            s + &self.grid.patches()[p].control()[k]
        });
        sum / T::from_int(c.len() as i64)
    }
}

/// The mean of the differences between consecutive points along one
/// direction of a block (`None` if the block has one point in it).
fn mean_difference<T: Real>(block: &[Vec<Point3<T>>], along_u: bool) -> Option<Point3<T>> {
    let mut sum = Point3::zeros();
    let mut count = 0i64;
    let (rows, cols) = (block.len(), block[0].len());
    for a in 0..rows {
        for b in 0..cols {
            let next = if along_u {
                (a + 1 < rows).then(|| (a + 1, b))
            } else {
                (b + 1 < cols).then(|| (a, b + 1))
            };
            if let Some((a2, b2)) = next {
                sum += &block[a2][b2] - &block[a][b];
                count += 1;
            }
        }
    }
    (count > 0).then(|| sum / T::from_int(count))
}

/// Re-places one block `us × vs` (global indices) about its centre `(cu, cv)`.
fn correct_block<T: Real>(
    net: &Net<T>,
    us: &[usize],
    vs: &[usize],
    centre: (usize, usize),
    out: &mut [Vec<Point3<T>>],
) {
    let block: Vec<Vec<Point3<T>>> = us
        .iter()
        .map(|&gu| vs.iter().map(|&gv| net.value(gu, gv)).collect())
        .collect();
    let u0 = mean_difference(&block, true).unwrap_or_else(Point3::zeros);
    let v0 = mean_difference(&block, false).unwrap_or_else(Point3::zeros);
    let c = net.value(centre.0, centre.1);
    let offset = |g: usize, c: usize| T::from_int(g as i64 - c as i64);
    for &gu in us {
        for &gv in vs {
            let p = &c + &u0 * offset(gu, centre.0) + &v0 * offset(gv, centre.1);
            for (patch, k) in net.copies(gu, gv) {
                out[patch][k] = p.clone();
            }
        }
    }
}

/// `{c−1, c, c+1} ∩ [0, max]`.
fn around(c: usize, max: usize) -> Vec<usize> {
    [c.checked_sub(1), Some(c), Some(c + 1)]
        .into_iter()
        .flatten()
        .filter(|&g| g <= max)
        .collect()
}

/// The continuity correction of seed 001 §2.3 (see the module docs for the
/// blocks and eq 5–6). Returns a new grid; the input is not modified.
///
/// **Cost** `O(n_u n_v n)`. **Accuracy**: afterwards copies of a shared
/// point are identical (C⁰ exactly) and the difference vectors across every
/// shared edge agree to a few units of roundoff of the coordinates (C¹).
/// Errors for degree `< 3`.
/// **Method**: average the shared control points and the difference vectors
/// across each join.
pub fn correct_continuity<T: Real>(grid: &PatchGrid<T>) -> Result<PatchGrid<T>, ContinuityError> {
    let n = grid.degree();
    // Below degree 3 the blocks of neighbouring joints overlap.
    degree_at_least("the continuity correction", 3, n)?;
    let net = Net { grid, n };
    let (nu, nv) = (grid.nu(), grid.nv());
    let (mu, mv) = (nu * n, nv * n);
    let mut out: Vec<Vec<Point3<T>>> = grid
        .patches()
        .iter()
        .map(|p| p.control().to_vec())
        .collect();
    for a in 0..=nu {
        for b in 0..=nv {
            let (gu, gv) = (a * n, b * n);
            if net.copies(gu, gv).len() > 1 {
                correct_block(&net, &around(gu, mu), &around(gv, mv), (gu, gv), &mut out);
            }
        }
    }
    // Edge points not in any joint block (only for n > 3).
    let interior = |g: usize| !matches!(g % n, 0 | 1) && g % n != n - 1;
    for a in 1..nu {
        for gv in (0..=mv).filter(|&g| interior(g)) {
            correct_block(&net, &around(a * n, mu), &[gv], (a * n, gv), &mut out);
        }
    }
    for b in 1..nv {
        for gu in (0..=mu).filter(|&g| interior(g)) {
            correct_block(&net, &[gu], &around(b * n, mv), (gu, b * n), &mut out);
        }
    }
    let patches = out
        .into_iter()
        .map(|c| {
            Patch::new(n, c).expect("re-placed points are finite combinations of finite points")
        })
        .collect();
    Ok(PatchGrid::new(nu, nv, patches).expect("same shape as the input grid"))
}

/// The largest defects of the joins of a grid, measured by evaluating the
/// patches (not by comparing control points).
#[derive(Debug, Clone, PartialEq)]
pub struct JoinDefects<T> {
    /// `max |R_left − R_right|` over the samples of every shared edge (C⁰).
    pub position: T,
    /// `max |∂R_left − ∂R_right|` of the cross-boundary derivative (`R_u`
    /// across a `u`-edge, `R_v` across a `v`-edge) — zero for C¹ joins.
    pub tangent: T,
    /// `max |∂R|` over the same samples, to make `tangent` relative.
    pub tangent_scale: T,
}

/// Measures [`JoinDefects`] at `samples` equally spaced parameters
/// `k/(samples−1)` along every shared edge. **Cost** `O(n_u n_v · samples · n²)`.
/// **Method**: evaluate both patches and their cross-boundary derivatives at
/// the samples and take the largest gaps. **Accuracy**: a sampled maximum
/// (used in `verify/tests/it/bv_deform.rs::continuity_correction_gives_c0_and_g1_joins`).
/// **Source**: seed 001 §2.3, eqs 5–6.
pub fn join_defects<T: Real>(
    grid: &PatchGrid<T>,
    samples: usize,
) -> Result<JoinDefects<T>, ContinuityError> {
    if samples < 2 {
        return Err(ContinuityError::TooFewSamples(samples));
    }
    let params: Vec<T> = (0..samples)
        .map(|k| T::from_rational(&rug::Rational::from((k as i64, samples as i64 - 1))))
        .collect();
    let (zero, one) = (T::zero(), T::one());
    let mut d = JoinDefects {
        position: T::zero(),
        tangent: T::zero(),
        tangent_scale: T::zero(),
    };
    let mut record = |a: (Point3<T>, Point3<T>), b: (Point3<T>, Point3<T>)| {
        d.position = d.position.clone().max((&a.0 - &b.0).norm());
        d.tangent = d.tangent.clone().max((&a.1 - &b.1).norm());
        d.tangent_scale = d.tangent_scale.clone().max(a.1.norm()).max(b.1.norm());
    };
    // The parameters are in [0, 1], so evaluation cannot fail.
    let at = |p: &Patch<T>, u: &T, v: &T, across_u: bool| {
        let (ru, rv) = p.derivatives(u, v).expect("parameters in [0, 1]");
        (
            p.eval(u, v).expect("parameters in [0, 1]"),
            if across_u { ru } else { rv },
        )
    };
    for p in 0..grid.nu() {
        for q in 0..grid.nv() {
            let here = grid.patch(p, q);
            for s in &params {
                if p + 1 < grid.nu() {
                    record(
                        at(here, &one, s, true),
                        at(grid.patch(p + 1, q), &zero, s, true),
                    );
                }
                if q + 1 < grid.nv() {
                    record(
                        at(here, s, &one, false),
                        at(grid.patch(p, q + 1), s, &zero, false),
                    );
                }
            }
        }
    }
    Ok(d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degree_below_three_is_refused() {
        let g = PatchGrid::planar(2, 2, 2, &1.0f64).unwrap();
        assert_eq!(
            correct_continuity(&g),
            Err(ContinuityError::Input(InputError::DegreeTooSmall {
                what: "the continuity correction",
                min: 3,
                got: 2
            }))
        );
        assert_eq!(join_defects(&g, 1), Err(ContinuityError::TooFewSamples(1)));
    }

    #[test]
    fn a_regular_planar_grid_is_a_fixed_point() {
        // Every block of a uniform plane is already a regular grid: the
        // correction must reproduce it up to rounding.
        for n in [3, 5] {
            let g = PatchGrid::planar(3, 2, n, &0.5f64).unwrap();
            let c = correct_continuity(&g).unwrap();
            for (a, b) in c.patches().iter().zip(g.patches()) {
                for (x, y) in a.control().iter().zip(b.control()) {
                    assert!((x - y).norm() < 4.0 * f64::EPSILON, "{x:?} vs {y:?}");
                }
            }
        }
    }
}
