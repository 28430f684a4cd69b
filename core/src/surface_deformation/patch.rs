//! Tensor-product Bézier patches of degree `n` and grids of them.
//!
//! Seed 001 (Maeno–Okada–Toriwaki) eq 1:
//! `R(u, v) = Σ_i Σ_j B_i^n(u) B_j^n(v) P_ij`, `0 ≤ u, v ≤ 1`.
//! A [`PatchGrid`] is the paper's multi-patch surface: `n_u × n_v` patches of
//! one degree, patch `(p, q)` meeting patch `(p+1, q)` along its `u = 1` edge
//! and patch `(p, q+1)` along its `v = 1` edge. Every patch keeps its own
//! control net, so a per-patch deformation may break the joins;
//! [`continuity`](super::continuity) measures and restores them.

use crate::bernstein::basis::bernstein_basis;
use crate::param_curve::{ParamSurface, ParamSurfaceDeriv, unit};
use crate::scalar::Real;
use crate::validation::{InputError, degree_at_least, finite_points};
use nalgebra::Vector3;
use rug::Rational;

/// A point or vector in space.
pub type Point3<T> = Vector3<T>;

/// Why a patch or grid could not be built or evaluated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PatchError {
    /// The control net does not have `(n+1)²` points.
    #[error("a degree-{degree} patch needs {expected} control points, got {got}")]
    WrongPointCount {
        /// The degree.
        degree: usize,
        /// `(n+1)²`.
        expected: usize,
        /// Points given.
        got: usize,
    },
    /// A control point (index `i(n+1) + j` of `P_ij`) has a NaN or infinite
    /// coordinate.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A parameter is NaN or outside `[0, 1]`.
    #[error("parameter {name} = {value} is not in [0, 1]")]
    Parameter {
        /// `u` or `v`.
        name: &'static str,
        /// The value (as f64).
        value: f64,
    },
    /// `R_u × R_v = 0`: the surface has no normal there.
    #[error("the surface is degenerate at (u, v) = ({u}, {v}): R_u × R_v = 0")]
    DegenerateNormal {
        /// `u` (as f64).
        u: f64,
        /// `v` (as f64).
        v: f64,
    },
    /// A grid needs at least one patch in each direction.
    #[error("a patch grid needs at least 1×1 patches, got {nu}×{nv}")]
    EmptyGrid {
        /// Patches in `u`.
        nu: usize,
        /// Patches in `v`.
        nv: usize,
    },
    /// `n_u · n_v` patches cannot be stored.
    #[error("a {nu}×{nv} grid has more patches than can be stored")]
    TooManyPatches {
        /// Patches in `u`.
        nu: usize,
        /// Patches in `v`.
        nv: usize,
    },
    /// The number of patches is not `n_u · n_v`.
    #[error("a {nu}×{nv} grid needs {} patches, got {got}", nu.saturating_mul(*nv))]
    GridSize {
        /// Patches in `u`.
        nu: usize,
        /// Patches in `v`.
        nv: usize,
        /// Patches given.
        got: usize,
    },
    /// The patches of a grid have different degrees.
    #[error("patch {index} has degree {degree}, the grid has degree {expected}")]
    DegreeMismatch {
        /// Patch index.
        index: usize,
        /// Its degree.
        degree: usize,
        /// The first patch's degree.
        expected: usize,
    },
}

/// A degree-`n` tensor Bézier patch: control points `P_ij`, `0 ≤ i, j ≤ n`,
/// stored row-major (`i(n+1) + j`, the ordering of seed 001 eq 2).
#[derive(Debug, Clone, PartialEq)]
pub struct Patch<T: Real> {
    degree: usize,
    control: Vec<Point3<T>>,
}

fn check_param<T: Real>(name: &'static str, x: &T) -> Result<(), PatchError> {
    if x.is_finite() && *x >= T::zero() && *x <= T::one() {
        Ok(())
    } else {
        Err(PatchError::Parameter {
            name,
            value: x.to_f64(),
        })
    }
}

/// `Σ_i Σ_j a_i b_j P_ij` over a row-major net with `cols` columns.
fn tensor_sum<T: Real>(a: &[T], b: &[T], net: impl Fn(usize, usize) -> Point3<T>) -> Point3<T> {
    let mut sum = Point3::zeros();
    for (i, ai) in a.iter().enumerate() {
        let mut row = Point3::zeros();
        for (j, bj) in b.iter().enumerate() {
            row += net(i, j) * bj.clone();
        }
        sum += row * ai.clone();
    }
    sum
}

impl<T: Real> Patch<T> {
    /// A patch from `(n+1)²` control points (row-major `P_ij`), all finite.
    /// **Method**: validation only; exact. **Source**: seed 001 eq 1 (tensor Bézier patch).
    pub fn new(degree: usize, control: Vec<Point3<T>>) -> Result<Self, PatchError> {
        degree_at_least("a Bézier patch", 1, degree)?;
        // Saturates for absurd degrees: no vector holds usize::MAX points.
        let expected = degree
            .saturating_add(1)
            .saturating_mul(degree.saturating_add(1));
        if control.len() != expected {
            return Err(PatchError::WrongPointCount {
                degree,
                expected,
                got: control.len(),
            });
        }
        finite_points("control point", &control)?;
        Ok(Patch { degree, control })
    }

    /// The flat patch `P_ij = origin + (i/n) e_u + (j/n) e_v`. By the linear
    /// precision of the Bernstein basis (`Σ_i (i/n) B_i^n(u) = u`) it is the
    /// parallelogram `origin + u e_u + v e_v` exactly.
    /// **Source**: seed 001 eq 1 (and §3, the flat initial surface).
    pub fn bilinear(
        degree: usize,
        origin: &Point3<T>,
        e_u: &Point3<T>,
        e_v: &Point3<T>,
    ) -> Result<Self, PatchError> {
        degree_at_least("a Bézier patch", 1, degree)?;
        let frac = |k: usize| T::from_rational(&Rational::from((k as i64, degree as i64)));
        let control = (0..=degree)
            .flat_map(|i| (0..=degree).map(move |j| (i, j)))
            .map(|(i, j)| origin + e_u * frac(i) + e_v * frac(j))
            .collect();
        Patch::new(degree, control)
    }

    /// The degree `n`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// All control points, row-major.
    pub fn control(&self) -> &[Point3<T>] {
        &self.control
    }

    /// `P_ij`.
    pub fn point(&self, i: usize, j: usize) -> &Point3<T> {
        &self.control[i * (self.degree + 1) + j]
    }

    /// `R(u, v)` of seed 001 eq 1, for `u, v ∈ [0, 1]`.
    ///
    /// **Method**: both basis rows by [`bernstein_basis`], then the double sum.
    /// **Cost** `O(n²)`. **Accuracy**: all weights are non-negative and sum
    /// to 1, so the error is at most `γ_{4n+2} · max |P_ij|` per coordinate.
    ///
    /// ```
    /// use nalgebra::Vector3;
    /// use splinelab::surface_deformation::patch::Patch;
    /// let z = Vector3::zeros();
    /// let p = Patch::bilinear(3, &z, &Vector3::new(2.0, 0.0, 0.0), &Vector3::new(0.0, 4.0, 0.0)).unwrap();
    /// assert_eq!(p.eval(&0.25, &0.5).unwrap(), Vector3::new(0.5, 2.0, 0.0));
    /// ```
    ///
    /// ```
    /// // In MPFR: the flat patch is the parallelogram origin + u e_u + v e_v.
    /// use nalgebra::Vector3;
    /// use splinelab::surface_deformation::patch::Patch;
    /// use splinelab::scalar::{Mp, Real};
    /// type M = Mp<128>;
    /// let v = |x, y, z| Vector3::new(M::from_int(x), M::from_int(y), M::from_int(z));
    /// let p = Patch::bilinear(3, &v(1, 1, 1), &v(2, 0, 0), &v(0, 4, 0)).unwrap();
    /// let (u, w) = (M::from_int(1) / M::from_int(3), M::from_int(2) / M::from_int(7));
    /// let r = p.eval(&u, &w).unwrap();
    /// let want = [M::from_int(1) + M::from_int(2) * u.clone(), M::from_int(1) + M::from_int(4) * w.clone(), M::from_int(1)];
    /// for i in 0..3 {
    ///     assert!((r[i].clone() - want[i].clone()).to_f64().abs() < 1e-36);
    /// }
    /// ```
    pub fn eval(&self, u: &T, v: &T) -> Result<Point3<T>, PatchError> {
        check_param("u", u)?;
        check_param("v", v)?;
        let (bu, bv) = (
            bernstein_basis(self.degree, u),
            bernstein_basis(self.degree, v),
        );
        Ok(tensor_sum(&bu, &bv, |i, j| self.point(i, j).clone()))
    }

    /// The partial derivatives `(R_u, R_v)` at `(u, v)`:
    /// `R_u = n Σ_{i<n} Σ_j B_i^{n−1}(u) B_j^n(v) (P_{i+1,j} − P_ij)` and the
    /// same in `v`. **Cost** `O(n²)`. **Accuracy**: the differences of
    /// control points are exact-input subtractions; the error is at most
    /// `n γ_{4n} · max |ΔP|`.
    pub fn derivatives(&self, u: &T, v: &T) -> Result<(Point3<T>, Point3<T>), PatchError> {
        check_param("u", u)?;
        check_param("v", v)?;
        let n = self.degree;
        let nt = T::from_int(n as i64);
        let (bu, bv) = (bernstein_basis(n, u), bernstein_basis(n, v));
        let (du, dv) = (bernstein_basis(n - 1, u), bernstein_basis(n - 1, v));
        let ru = tensor_sum(&du, &bv, |i, j| self.point(i + 1, j) - self.point(i, j)) * nt.clone();
        let rv = tensor_sum(&bu, &dv, |i, j| self.point(i, j + 1) - self.point(i, j)) * nt;
        Ok((ru, rv))
    }

    /// The unit normal `R_u × R_v / |R_u × R_v|`; a typed error where the
    /// cross product vanishes (a degenerate point, e.g. a collapsed edge).
    /// **Method**: the partials of [`Self::derivatives`] (error `≤ n γ_{4n} max |ΔP|`),
    /// then the cross product divided by its norm. **Source**: seed 001 eq 1.
    pub fn normal(&self, u: &T, v: &T) -> Result<Point3<T>, PatchError> {
        let (ru, rv) = self.derivatives(u, v)?;
        let c = ru.cross(&rv);
        let len = c.norm();
        if len.is_zero() || !len.is_finite() {
            return Err(PatchError::DegenerateNormal {
                u: u.to_f64(),
                v: v.to_f64(),
            });
        }
        Ok(c / len)
    }
}

/// A multi-patch surface: `n_u × n_v` patches of one degree; patch `(p, q)`
/// is stored at `p · n_v + q`, its `u = 1` edge meets patch `(p+1, q)` and its
/// `v = 1` edge meets patch `(p, q+1)`.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchGrid<T: Real> {
    nu: usize,
    nv: usize,
    patches: Vec<Patch<T>>,
}

impl<T: Real> PatchGrid<T> {
    /// A grid from its patches (row-major over `(p, q)`), all of one degree.
    /// **Method**: validation only; exact. **Source**: seed 001 §3 (the patch grid).
    pub fn new(nu: usize, nv: usize, patches: Vec<Patch<T>>) -> Result<Self, PatchError> {
        if nu == 0 || nv == 0 {
            return Err(PatchError::EmptyGrid { nu, nv });
        }
        if nu.checked_mul(nv) != Some(patches.len()) {
            return Err(PatchError::GridSize {
                nu,
                nv,
                got: patches.len(),
            });
        }
        let expected = patches[0].degree();
        if let Some(index) = patches.iter().position(|p| p.degree() != expected) {
            return Err(PatchError::DegreeMismatch {
                index,
                degree: patches[index].degree(),
                expected,
            });
        }
        Ok(PatchGrid { nu, nv, patches })
    }

    /// The plane `z = 0` tiled by `n_u × n_v` flat degree-`n` patches of size
    /// `size × size`, patch `(p, q)` covering `[p·size, (p+1)·size] × [q·size, (q+1)·size]`
    /// (the initial surface of seed 001 §3 with `n_u = n_v = 10`, `n = 3`).
    /// **Method**: [`Patch::bilinear`] per patch (exact linear precision); the grid tiles the
    /// plane (`patch.rs::tests::planar_grid_tiles_the_plane`).
    pub fn planar(nu: usize, nv: usize, degree: usize, size: &T) -> Result<Self, PatchError> {
        let (eu, ev) = (
            Point3::new(size.clone(), T::zero(), T::zero()),
            Point3::new(T::zero(), size.clone(), T::zero()),
        );
        let count = nu.checked_mul(nv);
        let mut patches = Vec::new();
        if count.is_none_or(|c| patches.try_reserve_exact(c).is_err()) {
            return Err(PatchError::TooManyPatches { nu, nv });
        }
        for p in 0..nu {
            for q in 0..nv {
                let origin = Point3::new(
                    size.clone() * T::from_int(p as i64),
                    size.clone() * T::from_int(q as i64),
                    T::zero(),
                );
                patches.push(Patch::bilinear(degree, &origin, &eu, &ev)?);
            }
        }
        PatchGrid::new(nu, nv, patches)
    }

    /// Patches in the `u` direction.
    pub fn nu(&self) -> usize {
        self.nu
    }

    /// Patches in the `v` direction.
    pub fn nv(&self) -> usize {
        self.nv
    }

    /// The common degree.
    pub fn degree(&self) -> usize {
        self.patches[0].degree()
    }

    /// Patch `(p, q)`.
    pub fn patch(&self, p: usize, q: usize) -> &Patch<T> {
        &self.patches[p * self.nv + q]
    }

    /// All patches, row-major over `(p, q)`.
    pub fn patches(&self) -> &[Patch<T>] {
        &self.patches
    }

    /// Consumes the grid, returning its patches.
    pub fn into_patches(self) -> Vec<Patch<T>> {
        self.patches
    }
}

impl<T: Real> ParamSurface<T, 3> for Patch<T> {
    type Error = PatchError;
    fn domain(&self) -> ((T, T), (T, T)) {
        (unit(), unit())
    }
    fn eval(&self, u: &T, v: &T) -> Result<Vector3<T>, PatchError> {
        Patch::eval(self, u, v)
    }
}

impl<T: Real> ParamSurfaceDeriv<T, 3> for Patch<T> {
    fn partials(&self, u: &T, v: &T) -> Result<(Vector3<T>, Vector3<T>), PatchError> {
        self.derivatives(u, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::prelude::*;

    fn v3(x: f64, y: f64, z: f64) -> Point3<f64> {
        Point3::new(x, y, z)
    }

    /// The saddle z = x·y over [0, 1]²: bilinear, so its degree-3 net is
    /// P_ij = (i/3, j/3, (i/3)(j/3)) (linear precision in each variable).
    fn saddle() -> Patch<f64> {
        let c = (0..4).flat_map(|i| {
            (0..4).map(move |j| v3(i as f64 / 3.0, j as f64 / 3.0, (i * j) as f64 / 9.0))
        });
        Patch::new(3, c.collect()).unwrap()
    }

    #[test]
    fn saddle_patch_reproduces_z_equals_xy_with_its_closed_form_normal() {
        let p = saddle();
        for &(u, v) in &[(0.0, 0.0), (0.3, 0.7), (1.0, 0.25), (0.5, 1.0)] {
            let r = p.eval(&u, &v).unwrap();
            assert!((r - v3(u, v, u * v)).norm() < 4e-16, "{r:?}");
            let (ru, rv) = p.derivatives(&u, &v).unwrap();
            assert!((ru - v3(1.0, 0.0, v)).norm() < 1e-14 && (rv - v3(0.0, 1.0, u)).norm() < 1e-14);
            // n = (−y, −x, 1)/√(1 + x² + y²) for z = xy.
            let want = v3(-v, -u, 1.0) / (1.0 + u * u + v * v).sqrt();
            assert!((p.normal(&u, &v).unwrap() - want).norm() < 1e-15);
        }
    }

    #[test]
    fn evaluation_in_mp_matches_the_closed_form_to_its_precision() {
        type M = Mp<160>;
        let c = (0..4).flat_map(|i| {
            (0..4).map(move |j| {
                Point3::new(
                    M::from_int(i) / M::from_int(3),
                    M::from_int(j) / M::from_int(3),
                    M::from_int(i * j) / M::from_int(9),
                )
            })
        });
        let p = Patch::new(3, c.collect()).unwrap();
        let (u, v) = (
            M::from_int(2) / M::from_int(7),
            M::from_int(5) / M::from_int(11),
        );
        let r = p.eval(&u, &v).unwrap();
        let err = (r[2].clone() - u.clone() * v.clone()).abs();
        assert!(
            err < M::from_int(64) * M::unit_roundoff(),
            "{}",
            err.to_f64()
        );
    }

    #[test]
    fn bad_patches_and_parameters_are_typed_errors() {
        assert_eq!(
            Patch::<f64>::new(0, vec![]),
            Err(PatchError::Input(InputError::DegreeTooSmall {
                what: "a Bézier patch",
                min: 1,
                got: 0
            }))
        );
        assert!(matches!(
            Patch::new(1, vec![v3(0.0, 0.0, 0.0); 3]),
            Err(PatchError::WrongPointCount {
                expected: 4,
                got: 3,
                ..
            })
        ));
        let mut c = vec![v3(0.0, 0.0, 0.0); 4];
        c[2].y = f64::NAN;
        assert_eq!(
            Patch::new(1, c),
            Err(PatchError::Input(InputError::NonFiniteAt {
                what: "control point",
                index: 2
            }))
        );
        let p = saddle();
        assert!(matches!(
            p.eval(&1.5, &0.0),
            Err(PatchError::Parameter { name: "u", .. })
        ));
        assert!(matches!(
            p.eval(&0.0, &f64::NAN),
            Err(PatchError::Parameter { name: "v", .. })
        ));
        // A collapsed patch (all points equal) has no normal.
        let flat = Patch::new(1, vec![v3(1.0, 1.0, 1.0); 4]).unwrap();
        assert!(matches!(
            flat.normal(&0.5, &0.5),
            Err(PatchError::DegenerateNormal { .. })
        ));
        assert!(matches!(
            PatchGrid::<f64>::new(0, 1, vec![]),
            Err(PatchError::EmptyGrid { .. })
        ));
        assert!(matches!(
            PatchGrid::new(1, 2, vec![p.clone()]),
            Err(PatchError::GridSize { got: 1, .. })
        ));
        let q = Patch::bilinear(
            2,
            &v3(0.0, 0.0, 0.0),
            &v3(1.0, 0.0, 0.0),
            &v3(0.0, 1.0, 0.0),
        )
        .unwrap();
        assert!(matches!(
            PatchGrid::new(1, 2, vec![p, q]),
            Err(PatchError::DegreeMismatch { index: 1, .. })
        ));
    }

    #[test]
    fn planar_grid_tiles_the_plane() {
        let g = PatchGrid::planar(3, 2, 3, &2.0f64).unwrap();
        let r = g.patch(2, 1).eval(&0.5, &0.25).unwrap();
        assert_eq!(r, v3(5.0, 2.5, 0.0));
        assert_eq!(g.patch(1, 0).normal(&0.3, &0.3).unwrap(), v3(0.0, 0.0, 1.0));
    }
}
