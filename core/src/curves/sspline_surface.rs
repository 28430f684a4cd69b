//! Tensor-product S-spline surfaces (seed 000 eq 24–25) and their local
//! update.
//!
//! `Q(u, v) = Σ_k Σ_l D_{kl} β_u(u − k) β_v(v − l)` with the separable
//! truncated convolution `D_{kl} = Σ_a c^u_{|a|} E_{k−a, l}`,
//! `E_{il} = Σ_b c^v_{|b|} P_{i, l−b}` — the "curves of curves" of eq 25.
//! Each direction has its own family (order or Beta2 tension), half-width and
//! end condition (free or periodic; prescribed tangents are a curve-only
//! feature here, because a tangent field along a surface edge needs corner
//! compatibility conditions the seed does not give).
//!
//! Moving `P_{ab}` changes `E` in `2n_v + 1` places and `D` in
//! `(2n_u + 1)(2n_v + 1)` places (interior point): the paper's "square of
//! the support width".

use super::CurveError;
use super::sspline_curve::{Axis, convolve_at};
use crate::param_curve::{ParamSurface, widen};
use crate::scalar::Real;
use crate::sspline::SplineFamily;
use crate::sspline::end_conditions::EndRule;
use crate::validation::{finite_point_at, finite_points};
use nalgebra::SVector;

/// One direction of a surface: family, half-width, end rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Direction {
    /// Basis family.
    pub family: SplineFamily,
    /// Truncation half-width `n ≥ 1`.
    pub n: usize,
    /// [`EndRule::Free`] or [`EndRule::Periodic`].
    pub rule: EndRule,
}

/// A tensor-product S-spline surface through a `ν_u × ν_v` grid.
#[derive(Debug, Clone, PartialEq)]
pub struct SsplineSurface<T: Real, const D: usize> {
    u: Axis<T>,
    v: Axis<T>,
    data: Vec<SVector<T, D>>,
    /// `E`, `ν_u × count_v`, row-major.
    e: Vec<SVector<T, D>>,
    /// `D`, `count_u × count_v`, row-major.
    control: Vec<SVector<T, D>>,
}

impl<T: Real, const D: usize> SsplineSurface<T, D> {
    /// Builds the surface through `data` (row-major, `P_{ij} = data[i·ν_v + j]`).
    ///
    /// **Cost** `O(ν_u ν_v (2n_u + 2n_v + 2) D)` after the coefficients.
    /// **Error**: as for curves, per direction; the truncation errors of the
    /// two directions add (times `max |P|` and the other direction's
    /// `Σ|c|`). Errors: grid too small, order above the point count,
    /// wrong grid size, non-finite data, a tangent rule.
    /// **Method**: the convolution of [`SsplineCurve::new`](super::sspline_curve::SsplineCurve::new)
    /// in `v` (the intermediate net `E`), then in `u` on `E` (the control net `D`). Tested in
    /// `verify/tests/it/sspline_curve.rs::surface_edit_interpolation_and_curves_of_curves`.
    /// **Source**: seed 000 eqs 24–25.
    pub fn new(
        du: &Direction,
        dv: &Direction,
        nu: usize,
        nv: usize,
        data: &[SVector<T, D>],
    ) -> Result<Self, CurveError> {
        if du.rule == EndRule::Reflect || dv.rule == EndRule::Reflect {
            return Err(CurveError::Unsupported("prescribed tangents"));
        }
        // The grid check first: it bounds ν_u and ν_v by the data's length.
        if nu.checked_mul(nv) != Some(data.len()) {
            return Err(CurveError::GridSize {
                nu,
                nv,
                got: data.len(),
            });
        }
        let u = Axis::new(&du.family, du.n, du.rule, nu)?;
        let v = Axis::new(&dv.family, dv.n, dv.rule, nv)?;
        finite_points("data point", data)?;
        let mut s = SsplineSurface {
            u,
            v,
            data: data.to_vec(),
            e: Vec::new(),
            control: Vec::new(),
        };
        let cv = s.v.count;
        s.e = (0..nu * cv).map(|x| s.e_entry(x / cv, x % cv)).collect();
        s.control = (0..s.u.count * cv)
            .map(|x| s.d_entry(x / cv, x % cv))
            .collect();
        Ok(s)
    }

    fn e_entry(&self, i: usize, slot: usize) -> SVector<T, D> {
        let nv = self.v.len;
        convolve_at(&self.v, slot, |l| {
            self.data[i * nv + self.v.rule.fold(l, nv).0].clone()
        })
    }

    fn d_entry(&self, slot_u: usize, slot_v: usize) -> SVector<T, D> {
        let cv = self.v.count;
        convolve_at(&self.u, slot_u, |k| {
            self.e[self.u.rule.fold(k, self.u.len).0 * cv + slot_v].clone()
        })
    }

    /// The control net `D`, `count_u × count_v` row-major.
    pub fn control_points(&self) -> &[SVector<T, D>] {
        &self.control
    }

    /// Control net shape `(count_u, count_v)`.
    pub fn net_shape(&self) -> (usize, usize) {
        (self.u.count, self.v.count)
    }

    /// The data grid.
    pub fn data(&self) -> &[SVector<T, D>] {
        &self.data
    }

    /// Parameter domains in `u` and `v`.
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (self.u.domain(), self.v.domain())
    }

    /// `Q(u, v) = Σ_{k,l} D_{kl} β_u(u − k) β_v(v − l)`, evaluated by two
    /// basis windows and `m_u m_v` axpys. **Accuracy**: error
    /// `≤ γ_{3(m_u+m_v)} Σ |D_{kl}| β_u β_v` (Higham, 2nd ed., §3.1); the
    /// surface reproduces its data grid
    /// (`verify/tests/it/sspline_curve.rs::surface_edit_interpolation_and_curves_of_curves`).
    /// **Source**: seed 000 eqs 24–25 (tensor-product S-spline surfaces).
    pub fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, CurveError> {
        self.u.check_param(u)?;
        self.v.check_param(v)?;
        let (wu, wv) = (self.u.window(u), self.v.window(v));
        let cv = self.v.count;
        let mut acc = SVector::zeros();
        for (k, bu) in &wu {
            let row = wv.iter().fold(SVector::<T, D>::zeros(), |r, (l, bv)| {
                r + &self.control[k * cv + l] * bv.clone()
            });
            acc += row * bu.clone();
        }
        Ok(acc)
    }

    /// Moves `P_{ab}` to `p`, recomputing the affected entries of `E` and `D`
    /// (bitwise equal to a full rebuild). **Cost** for an interior point:
    /// `(2n_v + 1)²` for `E` plus `(2n_u + 1)²(2n_v + 1)` for `D`,
    /// independent of the grid size. Returns the number of `D` entries
    /// recomputed. On error nothing changes.
    /// **Method**: recompute only the `D_{kl}` whose windows hold `P_{ab}`
    /// (tested in `verify/tests/it/sspline_curve.rs::surface_edit_interpolation_and_curves_of_curves`).
    /// **Source**: seed 000 §3 (local update) and eqs 24–25.
    pub fn move_point(
        &mut self,
        a: usize,
        b: usize,
        p: SVector<T, D>,
    ) -> Result<usize, CurveError> {
        self.check_edit(a, b, &p)?;
        self.data[a * self.v.len + b] = p;
        let cv = self.v.count;
        let (_, rv) = self.v.affected(b);
        for &(l0, l1) in &rv {
            for l in l0..=l1 {
                self.e[a * cv + l] = self.e_entry(a, l);
            }
        }
        let (_, ru) = self.u.affected(a);
        let mut count = 0;
        for &(k0, k1) in &ru {
            for k in k0..=k1 {
                for &(l0, l1) in &rv {
                    for l in l0..=l1 {
                        self.control[k * cv + l] = self.d_entry(k, l);
                        count += 1;
                    }
                }
            }
        }
        Ok(count)
    }

    /// Moves `P_{ab}` to `p` by `D_{kl} += c^u_{|k−i|} c^v_{|l−j|} (p − P_{ab})`
    /// over the extended indices `(i, j)` owned by `(a, b)` — the paper's
    /// `(2n + 1)²` update (interior point). `E` is updated the same way.
    /// Equal to a rebuild up to rounding.
    pub fn shift_point(
        &mut self,
        a: usize,
        b: usize,
        p: SVector<T, D>,
    ) -> Result<usize, CurveError> {
        self.check_edit(a, b, &p)?;
        let idx = a * self.v.len + b;
        let delta = &p - &self.data[idx];
        self.data[idx] = p;
        let cv = self.v.count as i64;
        let hits = |ax: &Axis<T>, k: usize| -> Vec<(usize, T)> {
            let n = ax.half_width() as i64;
            let (pre, _) = ax.affected(k);
            pre.into_iter()
                .flat_map(|i| {
                    let s0 = i - ax.first;
                    ((s0 - n).max(0)..=(s0 + n).min(ax.count as i64 - 1))
                        .map(move |s| (s as usize, (s - s0).unsigned_abs() as usize))
                })
                .map(|(s, j)| (s, ax.c[j].clone()))
                .collect()
        };
        let (hu, hv) = (hits(&self.u, a), hits(&self.v, b));
        for (l, cl) in &hv {
            self.e[a * cv as usize + l] += &delta * cl.clone();
        }
        for (k, ck) in &hu {
            let dk = &delta * ck.clone();
            for (l, cl) in &hv {
                self.control[k * cv as usize + l] += &dk * cl.clone();
            }
        }
        Ok(hu.len() * hv.len())
    }

    fn check_edit(&self, a: usize, b: usize, p: &SVector<T, D>) -> Result<(), CurveError> {
        let (nu, nv) = (self.u.len, self.v.len);
        if a >= nu || b >= nv {
            return Err(CurveError::IndexOutOfRange {
                index: a.max(b),
                len: if a >= nu { nu } else { nv },
            });
        }
        Ok(finite_point_at("data point", a * nv + b, p)?)
    }
}

impl<T: Real, const D: usize> ParamSurface<T, D> for SsplineSurface<T, D> {
    type Error = CurveError;
    fn domain(&self) -> ((T, T), (T, T)) {
        let (u, v) = SsplineSurface::domain(self);
        (widen(u), widen(v))
    }
    fn eval(&self, u: &T, v: &T) -> Result<SVector<T, D>, CurveError> {
        SsplineSurface::eval(self, u, v)
    }
}
