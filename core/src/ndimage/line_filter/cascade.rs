//! The two poles of degrees 4 and 5 as one pass down the lines and one up
//! ([`Cascade`]): its starts and ends (the two causal filters' joint
//! impulse response; the symmetric ends solved once per filter by Cramer's
//! rule), its row steps for the fused passes ([`Causal2`],
//! [`Anticausal2`]), and when a filter runs it
//! ([`LineFilter::cascade_for`]). One object with its own derivation, which
//! the rows and the blocks both run.

use super::LineFilter;
use super::recursion::{causal_order, periodic_end_order};
use super::row_kernels::{DownStep, RowCheck, UpStep, load_down, prefetch_starts};
use crate::ndimage::lanes;
use crate::ndimage::mode::Mode;
use crate::scalar::Real;
use multiversion::multiversion;

impl<T: Real> LineFilter<T> {
    /// The [`Cascade`] of a filter of two poles, for lines of `n ≥ 3`
    /// samples under a mode with closed-form starts (`None` otherwise:
    /// the poles' passes in turn).
    pub(super) fn cascade_for(&self, n: usize, mode: Mode) -> Option<&Cascade<T>> {
        let closed_form = matches!(mode, Mode::Mirror | Mode::Reflect | Mode::GridWrap);
        self.cascade.as_deref().filter(|_| n >= 3 && closed_form)
    }
}

/// The two poles `ξ₁, ξ₂` of a degree-4 or degree-5 spline as one pass
/// down the lines and one pass up, instead of down, up, down, up: the four
/// first-order filters are linear and shift-invariant on the extended
/// (infinite) signal, so they commute, and `A₂A₁C₂C₁ s` is the spline's
/// coefficients (up to the gain) like `A₂C₂A₁C₁ s`. Down,
/// `y_k = x_k + ξ₁ y_{k−1}`, `w_k = y_k + ξ₂ w_{k−1}`; up,
/// `u_k = ξ₁ (u_{k+1} − w_k)`, `c_k = ξ₂ (c_{k+1} − u_k)`. A strided
/// axis then reads and writes its work buffer twice instead of four
/// times, and the two chains of each pass are independent work for the
/// vector units.
///
/// **Starts.** `y_0 = Σ_{k<R} ξ₁^k x_{−k}` and
/// `w_0 = Σ_{k<R} h_k x_{−k}` with `h_k = Σ_{i+j=k} ξ₁^i ξ₂^j` (the two
/// causal filters' joint impulse response, `h_k = ξ₂ h_{k−1} + ξ₁^k`),
/// the samples extended by the mode, the reach `R` the larger horizon and
/// on until `|h_k|` is below the larger pole's `|ξ|^K`: both by Horner's
/// rule, the two recursions run from `x_{−R+1}` (state 0) up to `x_0`, so
/// each rounding is damped on its way to the start (as
/// [`causal_start`](super::recursion::causal_start)). At the end the coefficients
/// `c` are symmetric like the samples; with `P = ξ₁ξ₂`, `Q = ξ₁ + ξ₂`,
/// inverting both anti-causal filters gives
/// `P w_k = P c_{k+2} − Q c_{k+1} + c_k`, and for `k = n−1, n−2, n−3`
/// (mirror: `c_{n−1+j} = c_{n−1−j}`) three equations in `c_{n−1}, c_{n−2},
/// c_{n−3}`; reflect (`c_{n−1+j} = c_{n−j}`) two in `c_{n−1}, c_{n−2}`.
/// Their solution (Cramer's rule, once per filter) gives `c_{n−1}`, and
/// `u_{n−1} = c_n − c_{n−1}/ξ₂` (the second anti-causal filter inverted):
/// each a fixed combination of the last three (two) `w`. The determinants
/// are `(1 − ξ₁²)(1 − ξ₂²)(1 − P)`-like products of factors in `(0, 2)`
/// (mirror: `(1 − P)((1 + P)² − Q²)`, reflect: `(1 − P)(1 − ξ₁)(1 − ξ₂)`),
/// never small. Grid-wrap: the periodic sums `u_{n−1} = −Σ_m ξ₁^{m+1}
/// w_{n−1+m}` and `c_{n−1} = P Σ_m h_m w_{n−1+m}` (indices mod `n`,
/// `m < R`), by Horner's rule as the starts. The
/// one-pole closed forms (Unser, Aldroubi and Eden 1993) are the same
/// derivation with one filter.
///
/// **Cost**: `4` flops per sample and pole as before, plus `O(K)` rows of
/// starts. **Accuracy**: another order of the same operations: a few `u`
/// of `A · max|s|` per axis like the passes in turn (tested against 128-bit
/// MPFR in `nd_prefilter`'s and `engine_lanes`' tests; the rows of
/// [`LineFilter::apply_rows`] and [`LineFilter::apply_lines`] run the
/// same operations, bit for bit).
#[derive(Debug, Clone)]
pub(super) struct Cascade<T> {
    pub(super) z: [T; 2],
    /// The reach `R` of the starts (terms of `h`).
    pub(super) reach: usize,
    /// Mirror: the weights of `w_{n−1}, w_{n−2}, w_{n−3}` in `u_{n−1}`
    /// and in `c_{n−1}`.
    mirror: [[T; 3]; 2],
    /// Reflect: the same for `w_{n−1}, w_{n−2}`.
    reflect: [[T; 2]; 2],
    /// `P = ξ₁ξ₂` (grid-wrap's `c_{n−1}`).
    p: T,
}

impl<T: Real> Cascade<T> {
    /// The cascade of the poles `z1` (the smaller) and `z2` with their
    /// horizons. `O(K)`.
    pub(super) fn new(z1: &T, z2: &T, horizons: &[usize]) -> Self {
        let kmax = horizons.iter().copied().max().unwrap_or(0);
        let big = z1.to_f64().abs().max(z2.to_f64().abs());
        let tail = big.powi(kmax as i32);
        let mut h = vec![T::one()];
        let mut z1k = T::one();
        while h.len() < kmax.max(1) || (h[h.len() - 1].to_f64().abs() > tail && h.len() < 4 * kmax)
        {
            z1k *= z1.clone();
            let next = z2.clone() * &h[h.len() - 1] + &z1k;
            h.push(next);
        }
        let (one, zero) = (T::one(), T::zero());
        let p = z1.clone() * z2;
        let q = z1.clone() + z2;
        // `u_{n−1} = c_n − c_{n−1}/ξ₂` from the weights of `c_{n−1}` (a)
        // and of `c_n` (b): each times `P`, the equations' right side.
        let weights = |a: &T, b: &T| {
            let (a, b) = (p.clone() * a, p.clone() * b);
            (b - a.clone() / z2, a)
        };
        let m = [
            [one.clone(), -q.clone(), p.clone()],
            [-q.clone(), one.clone() + &p, zero.clone()],
            [p.clone(), -q.clone(), one.clone()],
        ];
        let inv = inverse3(&m);
        let mirror: [(T, T); 3] = std::array::from_fn(|j| weights(&inv[0][j], &inv[1][j]));
        // Reflect: c_n = c_{n−1}.
        let m = [[one.clone() - &q, p.clone()], [p.clone() - &q, one.clone()]];
        let inv = inverse2(&m);
        let reflect: [(T, T); 2] = std::array::from_fn(|j| weights(&inv[0][j], &inv[0][j]));
        Cascade {
            z: [z1.clone(), z2.clone()],
            reach: h.len(),
            mirror: [mirror.clone().map(|(u, _)| u), mirror.map(|(_, c)| c)],
            reflect: [reflect.clone().map(|(u, _)| u), reflect.map(|(_, c)| c)],
            p,
        }
    }

    /// The starts `y_0` and `w_0` of every column of `rows` (times `gain`
    /// first, if given) into `y` and `w0`.
    pub(super) fn starts<R: AsRef<[T]>>(
        &self,
        rows: &[R],
        gain: Option<&T>,
        mode: Mode,
        y: &mut [T],
        w0: &mut [T],
    ) {
        y.fill(T::zero());
        w0.fill(T::zero());
        let order = causal_order(self.reach, mode, rows.len());
        horner2_start(y, w0, &self.z, order, |i| rows[i].as_ref(), gain);
    }

    /// The anti-causal starts `u_{n−1}` and `c_{n−1}` of every column of
    /// the causal values `c` (`n × w`) into `u` and `last`.
    pub(super) fn ends(&self, c: &[T], w: usize, mode: Mode, u: &mut [T], last: &mut [T]) {
        let n = c.len() / w;
        let row = |i: usize| &c[i * w..(i + 1) * w];
        u.fill(T::zero());
        last.fill(T::zero());
        // Mirror and reflect: fixed weights of the last three (two) rows.
        let weights: Option<(&[T], &[T])> = match mode {
            Mode::Mirror => Some((&self.mirror[0], &self.mirror[1])),
            Mode::Reflect => Some((&self.reflect[0], &self.reflect[1])),
            _ => None,
        };
        match weights {
            Some((for_u, for_last)) => {
                for (j, (fu, fc)) in for_u.iter().zip(for_last).enumerate() {
                    add_scaled(u, fu, row(n - 1 - j));
                    add_scaled(last, fc, row(n - 1 - j));
                }
            }
            None => {
                let order = periodic_end_order(self.reach, n);
                horner2_start(u, last, &self.z, order, row, None);
                let (mz, p) = (-self.z[0].clone(), &self.p);
                for (u, c) in u.iter_mut().zip(last.iter_mut()) {
                    *u = mz.clone() * &*u;
                    *c = p.clone() * &*c;
                }
            }
        }
    }

    /// Both poles down and up every column of `c` (`n × w`, `n ≥ 3`,
    /// already scaled by the gain), in place.
    #[inline(never)]
    pub(super) fn rows(&self, c: &mut [T], w: usize, mode: Mode) {
        let n = c.len() / w;
        let (mut y, mut acc) = (vec![T::zero(); w], vec![T::zero(); w]);
        let rows: Vec<&[T]> = c.chunks(w).collect();
        self.starts(&rows, None, mode, &mut y, &mut acc);
        c[..w].clone_from_slice(&acc);
        lanes::causal2_strided(c, w, &mut y, &self.z[0], &self.z[1]);
        self.ends(c, w, mode, &mut y, &mut acc);
        c[(n - 1) * w..].clone_from_slice(&acc);
        lanes::anticausal2_strided(c, w, &mut y, &self.z[0], &self.z[1]);
    }

    /// The causal half of [`Self::rows`] reading the samples `src` (times
    /// `gain`) into `buf`, `seen` taking in each row; returns `u_{n−1}`,
    /// and `buf`'s last row holds `c_{n−1}` ([`Anticausal2`] does
    /// the rest). The same operations as [`Self::rows`] on the scaled rows.
    #[inline(never)]
    pub(super) fn load<R: AsRef<[T]>, F: RowCheck>(
        &self,
        src: &[R],
        buf: &mut [T],
        gain: &T,
        mode: Mode,
        seen: &mut F,
    ) -> Vec<T> {
        let n = src.len();
        let w = buf.len() / n;
        let (mut y, mut acc) = (vec![T::zero(); w], vec![T::zero(); w]);
        prefetch_starts(src, mode, self.reach);
        seen.row(src[0].as_ref());
        self.starts(src, Some(gain), mode, &mut y, &mut acc);
        buf[..w].clone_from_slice(&acc);
        let mut step = Causal2 {
            gain,
            z: [&self.z[0], &self.z[1]],
            y: &mut y,
        };
        load_down(src, buf, &mut step, seen);
        self.ends(buf, w, mode, &mut y, &mut acc);
        buf[(n - 1) * w..].clone_from_slice(&acc);
        y
    }
}

/// The inverse of a 3 × 3 matrix (Cramer's rule: the adjugate over the
/// determinant).
fn inverse3<T: Real>(m: &[[T; 3]; 3]) -> [[T; 3]; 3] {
    let cof = |i: usize, j: usize| {
        let (r0, r1) = ((i + 1) % 3, (i + 2) % 3);
        let (c0, c1) = ((j + 1) % 3, (j + 2) % 3);
        m[r0][c0].clone() * &m[r1][c1] - m[r0][c1].clone() * &m[r1][c0]
    };
    let det = (0..3).fold(T::zero(), |d, j| d + m[0][j].clone() * cof(0, j));
    std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / &det))
}

/// The inverse of a 2 × 2 matrix.
fn inverse2<T: Real>(m: &[[T; 2]; 2]) -> [[T; 2]; 2] {
    let det = m[0][0].clone() * &m[1][1] - m[0][1].clone() * &m[1][0];
    [
        [m[1][1].clone() / &det, -m[0][1].clone() / &det],
        [-m[1][0].clone() / &det, m[0][0].clone() / &det],
    ]
}

/// `acc += f · row` for a row of `w` values.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn add_scaled<T: Real>(acc: &mut [T], f: &T, row: &[T]) {
    for (a, x) in acc.iter_mut().zip(row) {
        *a += f.clone() * x;
    }
}

/// Both starts of a [`Cascade`] by Horner's rule over the rows `row(i)`
/// in the order `order` gives them, from zero: `y = row + ξ₁ y`,
/// `w = y + ξ₂ w` (the row times a gain `g` first, if given, as
/// [`lanes::scale`] does). One call into the vector clone for the whole
/// sum, as `recursion`'s single-pole starts.
#[multiversion(targets("x86_64+avx512f+avx512vl+avx2+fma", "x86_64+avx2+fma", "aarch64+neon"))]
fn horner2_start<'a, T, I, F>(
    y: &mut [T],
    w: &mut [T],
    z: &[T; 2],
    order: I,
    row: F,
    gain: Option<&T>,
) where
    T: Real + 'a,
    I: Iterator<Item = usize>,
    F: Fn(usize) -> &'a [T],
{
    let [z1, z2] = z;
    for i in order {
        for ((y, w), x) in y.iter_mut().zip(w.iter_mut()).zip(row(i)) {
            let x = match gain {
                Some(g) => g.clone() * x,
                None => x.clone(),
            };
            *y = x + z1.clone() * &*y;
            *w = y.clone() + z2.clone() * &*w;
        }
    }
}

/// [`Cascade`]'s pass down: `y = g·s + ξ₁ y`, `x = y + ξ₂ prev`, the
/// operations of [`lanes::causal2_strided`] on scaled rows (`y`: the
/// first pole's row, carried).
struct Causal2<'a, T> {
    gain: &'a T,
    z: [&'a T; 2],
    y: &'a mut [T],
}

impl<T: Real> DownStep<T> for Causal2<'_, T> {
    #[inline(always)]
    fn row(&mut self, x: &mut [T], s: &[T], prev: &[T]) {
        let (g, [z1, z2]) = (self.gain, self.z);
        for (((x, s), p), y) in x.iter_mut().zip(s).zip(prev).zip(self.y.iter_mut()) {
            *y = g.clone() * s + z1.clone() * &*y;
            *x = y.clone() + z2.clone() * p;
        }
    }
}

/// [`Cascade`]'s pass up: `u = ξ₁ (u − c)`, `o = ξ₂ (next − u)`, the
/// operations of [`lanes::anticausal2_strided`] (`u`: the first pole's
/// row, carried).
pub(super) struct Anticausal2<'a, T> {
    pub(super) z: [&'a T; 2],
    pub(super) u: &'a mut [T],
}

impl<T: Real> UpStep<T> for Anticausal2<'_, T> {
    #[inline(always)]
    fn row(&mut self, o: &mut [T], next: &[T], c: &[T]) {
        let [z1, z2] = self.z;
        for (((o, nx), c), u) in o.iter_mut().zip(next).zip(c).zip(self.u.iter_mut()) {
            *u = z1.clone() * (u.clone() - c.clone());
            *o = z2.clone() * (nx.clone() - u.clone());
        }
    }
}
