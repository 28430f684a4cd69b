//! The QI-curve study (seed 004): Newton convergence histories in f64 and
//! MPFR, iteration counts against the number of points, success rates on
//! random point sets with and without damping, the paper's Figure 2
//! (curvature of the QI interpolant vs a cubic spline) and a 3D curve.
//!
//! Every converged fit is checked independently of the solver: its angles
//! and lengths are converted exactly to a higher precision `R` and the
//! segments re-integrated there with a rule chosen afresh at `R`'s
//! precision ([`check_fit`]). Failures are recorded with their reason.

use nalgebra::Vector3;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use splinelab::qi::circle_tangent::{end_tangent, start_tangent};
use splinelab::qi::cubic_spline::{ClampedCubicSpline, Parameterization};
use splinelab::qi::{QiError, QiInterpolation, QiOptions, QiSegment, interpolate};
use splinelab::quadrature::{GaussLegendre, choose_order};
use splinelab::scalar::{Mp, Real};
use std::collections::BTreeMap;

/// A named point set (f64 coordinates, exact in every precision).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QiCase {
    /// Family and size, e.g. `"helix-10"`.
    pub name: String,
    /// The points `P_0..P_n`.
    pub points: Vec<[f64; 3]>,
}

/// `n` points on the helix `(cos t, sin t, 0.3 t)`, `t = 0.7 k`.
pub fn helix(n: usize) -> QiCase {
    sampled("helix", n, |t| [(0.7 * t).cos(), (0.7 * t).sin(), 0.21 * t])
}

/// `n` points on the unit circle in the xy-plane, 0.5 rad apart. Its
/// tangent passes through `±v_x`, the poles of the `(α, β)` chart.
pub fn circle(n: usize) -> QiCase {
    sampled("circle", n, |t| [(0.5 * t).cos(), (0.5 * t).sin(), 0.0])
}

/// `n` points on the space curve `(0.6 t, sin 0.6t, 0.5 cos 0.42 t)`.
pub fn wave(n: usize) -> QiCase {
    sampled("wave", n, |t| {
        [0.6 * t, (0.6 * t).sin(), 0.5 * (0.42 * t).cos()]
    })
}

/// The paper's Figure 2 setting: 4 points, 3 segments. The paper prints
/// no coordinates, so these are ours: a gently twisting space curve.
pub fn paper_like() -> QiCase {
    QiCase {
        name: "paper-like-4".into(),
        points: vec![
            [0.0, 0.0, 0.0],
            [1.0, 1.0, 0.5],
            [2.0, 0.5, 1.5],
            [3.0, 1.5, 2.0],
        ],
    }
}

fn sampled(family: &str, n: usize, f: impl Fn(f64) -> [f64; 3]) -> QiCase {
    QiCase {
        name: format!("{family}-{n}"),
        points: (0..n).map(|k| f(k as f64)).collect(),
    }
}

pub use crate::rng::SplitMix64;

/// A random walk: 4–8 points, steps of length in `[0.5, 1.5]`, each turning
/// by an angle uniform in `[0°, 150°]` about a random axis. Returns the
/// case and its largest turning angle (degrees).
pub fn random_walk(seed: u64) -> (QiCase, f64) {
    let mut rng = SplitMix64::new(seed);
    let n = 4 + (rng.next_u64() % 5) as usize;
    let mut d = Vector3::new(1.0, 0.3, -0.2).normalize();
    let mut p = Vector3::zeros();
    let mut pts = vec![[0.0; 3]];
    let mut max_turn: f64 = 0.0;
    for k in 1..n {
        if k > 1 {
            let theta = rng.unit() * 150f64.to_radians();
            let r = Vector3::new(rng.unit() - 0.5, rng.unit() - 0.5, rng.unit() - 0.5);
            let perp = (r - d * d.dot(&r)).normalize();
            d = (d * theta.cos() + perp * theta.sin()).normalize();
            max_turn = max_turn.max(theta.to_degrees());
        }
        p += d * (0.5 + rng.unit());
        pts.push([p.x, p.y, p.z]);
    }
    let case = QiCase {
        name: format!("random-{seed}"),
        points: pts,
    };
    (case, max_turn)
}

/// The points of a case in precision `T` (exact conversion).
pub fn points_in<T: Real>(case: &QiCase) -> Vec<Vector3<T>> {
    case.points
        .iter()
        .map(|p| {
            Vector3::new(
                T::from_f64_exact(p[0]),
                T::from_f64_exact(p[1]),
                T::from_f64_exact(p[2]),
            )
        })
        .collect()
}

/// Exact conversion between precisions (`R` at least as wide as `T`).
fn widen<T: Real, R: Real>(x: &T) -> R {
    match x.to_rational() {
        Some(q) => R::from_rational(&q),
        None => R::from_f64_exact(f64::NAN),
    }
}

fn widen_segment<T: Real, R: Real>(s: &QiSegment<T>) -> QiSegment<R> {
    QiSegment {
        alpha: std::array::from_fn(|j| widen(&s.alpha[j])),
        beta: std::array::from_fn(|j| widen(&s.beta[j])),
        length: widen(&s.length),
    }
}

/// Independent measurements of a fit, computed in a higher precision.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitCheck {
    /// `max_i |P_i + l_i ∫₀¹ T_i − P_{i+1}| / D`, `D` the diameter of the
    /// points' bounding box (relative interpolation error, eq 18).
    pub max_end_error: f64,
    /// `max_i |T_i(1) − T_{i+1}(0)|` (G1, eq 19–20).
    pub max_g1_error: f64,
    /// `max_i h |κ⃗_i(1) − κ⃗_{i+1}(0)|`, `κ⃗ = dT/ds`, `h` the mean chord
    /// (G2, eq 21).
    pub max_g2_error: f64,
    /// Bits of the precision the check ran in.
    pub reference_bits: u32,
    /// Order of the reference Gauss rule.
    pub reference_quad_order: usize,
}

/// Re-integrates `fit` in precision `R`: the segment data are converted
/// exactly, a Gauss rule is chosen by doubling to `2⁴ u_R`, and the end
/// points, tangents and curvature vectors are compared at every join.
/// Returns `None` if no rule up to order 4096 reaches that tolerance.
pub fn check_fit<T: Real, R: Real>(fit: &QiInterpolation<T>) -> Option<FitCheck> {
    check_fit_with_rules::<T, R>(fit, &[])
}

/// Gauss rules of orders `16, 32, …, max_order` in `R`, to share between
/// many [`check_fit_with_rules`] calls (building MPFR rules dominates the
/// cost of a check otherwise).
pub fn rule_ladder<R: Real>(max_order: usize) -> Vec<GaussLegendre<R>> {
    std::iter::successors(Some(16), |m| Some(m * 2))
        .take_while(|&m| m <= max_order)
        .filter_map(|m| GaussLegendre::new(m).ok())
        .collect()
}

/// [`check_fit`] with prebuilt rules (ascending, each twice the previous):
/// the first rule whose doubling estimate meets the tolerance is used; past
/// the ladder, rules are built as needed up to order 4096.
pub fn check_fit_with_rules<T: Real, R: Real>(
    fit: &QiInterpolation<T>,
    ladder: &[GaussLegendre<R>],
) -> Option<FitCheck> {
    let segs: Vec<QiSegment<R>> = fit.segments.iter().map(widen_segment).collect();
    let pts: Vec<Vector3<R>> = fit.points.iter().map(|p| p.map(|c| widen(&c))).collect();
    let h: R = widen(&fit.scale);
    let tol = R::unit_roundoff().scale_by_pow2(4);
    // Walk the ladder once, keeping each rule's end displacements, so no
    // MPFR integral is computed twice.
    let ends = |r: &GaussLegendre<R>| {
        segs.iter()
            .map(|s| s.end_displacement(r))
            .collect::<Vec<_>>()
    };
    let mut found = None;
    let mut prev: Option<(usize, Vec<Vector3<R>>)> = None;
    for (k, r) in ladder.iter().enumerate() {
        let cur = ends(r);
        if let Some((j, p)) = &prev
            && max_gap(p, &cur, &h) <= tol
        {
            found = Some((ladder[*j].clone(), p.clone()));
            break;
        }
        prev = Some((k, cur));
    }
    let (rule, disp) = match found {
        Some(f) => f,
        None => {
            let start = ladder.last().map_or(16, |r| r.order());
            let rule = choose_order(start, 4096, &tol, |a, b| gap(&segs, a, b, &h))
                .ok()?
                .0;
            let d = ends(&rule);
            (rule, d)
        }
    };
    let diam = bounding_diameter(&pts);
    let one = R::one();
    let zero = R::zero();
    let mut check = FitCheck {
        max_end_error: 0.0,
        max_g1_error: 0.0,
        max_g2_error: 0.0,
        reference_bits: R::BITS,
        reference_quad_order: rule.order(),
    };
    for (i, s) in segs.iter().enumerate() {
        let miss = (&pts[i] + &disp[i] - &pts[i + 1]).norm() / diam.clone();
        check.max_end_error = check.max_end_error.max(miss.to_f64());
        if let Some(next) = segs.get(i + 1) {
            let g1 = (s.tangent_at(&one) - next.tangent_at(&zero)).norm();
            let g2 =
                (s.curvature_vector_at(&one) - next.curvature_vector_at(&zero)).norm() * h.clone();
            check.max_g1_error = check.max_g1_error.max(g1.to_f64());
            check.max_g2_error = check.max_g2_error.max(g2.to_f64());
        }
    }
    Some(check)
}

fn max_gap<R: Real>(a: &[Vector3<R>], b: &[Vector3<R>], h: &R) -> R {
    a.iter().zip(b).fold(R::zero(), |acc, (x, y)| {
        let d = (x - y).norm() / h.clone();
        if d > acc || !d.is_finite() { d } else { acc }
    })
}

fn gap<R: Real>(segs: &[QiSegment<R>], a: &GaussLegendre<R>, b: &GaussLegendre<R>, h: &R) -> R {
    segs.iter().fold(R::zero(), |acc, s| {
        let d = (s.end_displacement(a) - s.end_displacement(b)).norm() / h.clone();
        if d > acc || !d.is_finite() { d } else { acc }
    })
}

fn bounding_diameter<R: Real>(pts: &[Vector3<R>]) -> R {
    let mut lo = pts[0].clone();
    let mut hi = pts[0].clone();
    for p in pts {
        for c in 0..3 {
            if p[c] < lo[c] {
                lo[c] = p[c].clone();
            }
            if p[c] > hi[c] {
                hi[c] = p[c].clone();
            }
        }
    }
    (hi - lo).norm()
}

/// One Newton run with its full history.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConvergenceRun {
    /// Point-set name.
    pub case: String,
    /// Scalar type (`"f64"`, `"mp256"`, …).
    pub precision: String,
    /// Its bits.
    pub bits: u32,
    /// Number of points.
    pub points: usize,
    /// Damped Newton.
    pub damped: bool,
    /// Whether Newton met its tolerance.
    pub converged: bool,
    /// The error message when it did not.
    pub failure: Option<String>,
    /// Newton steps taken.
    pub iterations: usize,
    /// `‖F(x_k)‖₂`, 6 significant digits, one per iterate from `x_0`.
    pub residuals: Vec<String>,
    /// `log10 ‖F(x_k)‖₂` (computed in the working precision, so values
    /// below f64's range are kept); `None` for an exact zero.
    pub log10_residuals: Vec<Option<f64>>,
    /// `log10 ‖Δx_k‖₂` of each step.
    pub log10_steps: Vec<Option<f64>>,
    /// Observed order `p_k = log(r_{k+1}/r_k) / log(r_k/r_{k−1})` for
    /// `k = 1..` while the residual decreases; `None` elsewhere.
    pub observed_orders: Vec<Option<f64>>,
    /// Gauss–Legendre order of the final system.
    pub quad_order: Option<usize>,
    /// Independent check of the result (`None` if not converged).
    pub check: Option<FitCheck>,
    /// Tolerance Newton was given.
    pub tol: f64,
}

fn log10_of<T: Real>(x: &T) -> Option<f64> {
    (!x.is_zero()).then(|| x.clone().log10().to_f64())
}

/// `p_k` from consecutive log-residuals (see [`ConvergenceRun`]).
pub fn observed_orders(logs: &[Option<f64>]) -> Vec<Option<f64>> {
    (1..logs.len().saturating_sub(1))
        .map(|k| match (logs[k - 1], logs[k], logs[k + 1]) {
            (Some(a), Some(b), Some(c)) if b < a - 1e-3 && c < b => Some((c - b) / (b - a)),
            _ => None,
        })
        .collect()
}

/// Fits `case` in precision `T` and checks it in `R` (wider than `T`).
pub fn convergence_run<T: Real, R: Real>(case: &QiCase, damped: bool) -> ConvergenceRun {
    convergence_run_with_rules::<T, R>(case, damped, &[])
}

/// [`convergence_run`] checking with prebuilt rules ([`rule_ladder`]).
pub fn convergence_run_with_rules<T: Real, R: Real>(
    case: &QiCase,
    damped: bool,
    ladder: &[GaussLegendre<R>],
) -> ConvergenceRun {
    let opts = QiOptions::<T> {
        damped,
        ..Default::default()
    };
    let mut run = ConvergenceRun {
        case: case.name.clone(),
        precision: T::type_name(),
        bits: T::BITS,
        points: case.points.len(),
        damped,
        converged: false,
        failure: None,
        iterations: 0,
        residuals: vec![],
        log10_residuals: vec![],
        log10_steps: vec![],
        observed_orders: vec![],
        quad_order: None,
        check: None,
        tol: opts.tol.to_f64(),
    };
    match interpolate(&points_in::<T>(case), &opts) {
        Ok(fit) => {
            run.converged = true;
            run.iterations = fit.iterations();
            run.residuals = fit
                .history
                .iter()
                .map(|h| h.residual.to_decimal(6))
                .collect();
            run.log10_residuals = fit.history.iter().map(|h| log10_of(&h.residual)).collect();
            run.log10_steps = fit
                .history
                .iter()
                .filter_map(|h| h.step.as_ref())
                .map(log10_of)
                .collect();
            run.quad_order = Some(fit.rule.order());
            run.check = check_fit_with_rules::<T, R>(&fit, ladder);
        }
        Err(e) => {
            if let QiError::NotConverged {
                residuals, steps, ..
            } = &e
            {
                run.iterations = residuals.len().saturating_sub(1);
                run.residuals = residuals.iter().map(|r| format!("{r:.5e}")).collect();
                run.log10_residuals = residuals.iter().map(log10_of).collect();
                run.log10_steps = steps.iter().map(log10_of).collect();
            }
            run.failure = Some(e.to_string());
        }
    }
    run.observed_orders = observed_orders(&run.log10_residuals);
    run
}

/// Iteration count for one family member.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IterationRow {
    /// `"helix"`, `"circle"` or `"wave"`.
    pub family: String,
    /// Number of points.
    pub points: usize,
    /// Damped Newton.
    pub damped: bool,
    /// Whether it converged.
    pub converged: bool,
    /// Newton steps.
    pub iterations: usize,
    /// Last residual (f64).
    pub final_residual: f64,
    /// Interpolation error from [`check_fit`] in `Mp<128>`.
    pub max_end_error: Option<f64>,
    /// Error message on failure.
    pub failure: Option<String>,
}

/// Outcome of one random set in one Newton variant.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Converged and passed the independent check (end error ≤ 1e-12).
    pub success: bool,
    /// Newton met its tolerance.
    pub converged: bool,
    /// Newton steps.
    pub iterations: usize,
    /// Short failure reason (`None` on success).
    pub reason: Option<String>,
    /// Full error message (`None` on success).
    pub message: Option<String>,
    /// Interpolation error from [`check_fit`] in `Mp<128>`.
    pub max_end_error: Option<f64>,
}

/// One random point set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RandomRow {
    /// Generator seed ([`random_walk`]).
    pub seed: u64,
    /// Number of points.
    pub points: usize,
    /// Largest turning angle between consecutive chords (degrees).
    pub max_turn_deg: f64,
    /// Smallest angle between a chord and the chart's poles `±v_x`
    /// (degrees): near a pole α is ill-determined.
    pub pole_angle_deg: f64,
    /// Plain Newton.
    pub plain: Outcome,
    /// Damped Newton.
    pub damped: Outcome,
}

/// The f64 interpolation error threshold a converged fit must meet.
pub const F64_END_TOL: f64 = 1e-12;

fn short_reason(e: &QiError) -> String {
    match e {
        QiError::NotConverged { reason, .. } => reason.to_string(),
        QiError::Quadrature(_) => "quadrature tolerance not met".into(),
        QiError::InvalidTangent { .. } => "invalid tangent".into(),
        QiError::CoincidentPoints { .. } => "coincident points".into(),
        other => other.to_string(),
    }
}

fn f64_outcome(
    case: &QiCase,
    damped: bool,
    ladder: &[GaussLegendre<Mp<128>>],
) -> (Outcome, Option<QiInterpolation<f64>>) {
    let opts = QiOptions::<f64> {
        damped,
        ..Default::default()
    };
    match interpolate(&points_in::<f64>(case), &opts) {
        Ok(fit) => {
            let err = check_fit_with_rules::<f64, Mp<128>>(&fit, ladder).map(|c| c.max_end_error);
            let ok = err.is_some_and(|e| e <= F64_END_TOL);
            let o = Outcome {
                success: ok,
                converged: true,
                iterations: fit.iterations(),
                reason: (!ok).then(|| "independent check failed".to_string()),
                message: (!ok)
                    .then(|| format!("re-integrated end error {err:?} above {F64_END_TOL:e}")),
                max_end_error: err,
            };
            (o, Some(fit))
        }
        Err(e) => {
            let iterations = match &e {
                QiError::NotConverged { residuals, .. } => residuals.len().saturating_sub(1),
                _ => 0,
            };
            let o = Outcome {
                success: false,
                converged: false,
                iterations,
                reason: Some(short_reason(&e)),
                message: Some(e.to_string()),
                max_end_error: None,
            };
            (o, None)
        }
    }
}

/// Success statistics of the random sets.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RandomStudy {
    /// Number of sets.
    pub sets: usize,
    /// Successes of plain Newton.
    pub plain_successes: usize,
    /// Successes of damped Newton.
    pub damped_successes: usize,
    /// Failure counts by reason, plain Newton.
    pub plain_failures: BTreeMap<String, usize>,
    /// Failure counts by reason, damped Newton.
    pub damped_failures: BTreeMap<String, usize>,
    /// Success rate (plain, damped) per 30° bin of the largest turning angle:
    /// `(bin start in degrees, sets, plain rate, damped rate)`.
    pub by_turn: Vec<(f64, usize, f64, f64)>,
    /// The same per 15° bin of the chords' smallest angle to the poles `±v_x`.
    pub by_pole_angle: Vec<(f64, usize, f64, f64)>,
    /// Every set.
    pub rows: Vec<RandomRow>,
}

/// Smallest angle (degrees) between a chord of `case` and `±v_x`, the
/// poles of the paper's `(α, β)` chart.
pub fn pole_angle_deg(case: &QiCase) -> f64 {
    case.points
        .windows(2)
        .map(|w| {
            let d = Vector3::new(w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]);
            (d.x.abs() / d.norm()).acos().to_degrees()
        })
        .fold(90.0, f64::min)
}

/// Success rates per bin `[lo, lo + width)` of `key`:
/// `(lo, sets, plain rate, damped rate)`, empty bins left out.
fn binned(
    rows: &[RandomRow],
    key: fn(&RandomRow) -> f64,
    width: f64,
    bins: usize,
) -> Vec<(f64, usize, f64, f64)> {
    (0..bins)
        .filter_map(|b| {
            let lo = width * b as f64;
            let in_bin: Vec<&RandomRow> = rows
                .iter()
                .filter(|r| key(r) >= lo && key(r) < lo + width)
                .collect();
            let k = in_bin.len();
            let rate = |f: fn(&RandomRow) -> bool| {
                in_bin.iter().filter(|r| f(r)).count() as f64 / k as f64
            };
            (k > 0).then(|| (lo, k, rate(|r| r.plain.success), rate(|r| r.damped.success)))
        })
        .collect()
}

/// Runs `sets` random walks (seeds `1..=sets`) with plain and damped
/// Newton in f64, in parallel.
pub fn run_random(sets: usize) -> RandomStudy {
    let ladder = rule_ladder::<Mp<128>>(128);
    let rows: Vec<RandomRow> = (1..=sets as u64)
        .into_par_iter()
        .map(|seed| {
            let (case, max_turn_deg) = random_walk(seed);
            RandomRow {
                seed,
                points: case.points.len(),
                max_turn_deg,
                pole_angle_deg: pole_angle_deg(&case),
                plain: f64_outcome(&case, false, &ladder).0,
                damped: f64_outcome(&case, true, &ladder).0,
            }
        })
        .collect();
    let count = |f: &dyn Fn(&RandomRow) -> &Outcome| {
        let mut m = BTreeMap::new();
        for r in &rows {
            if let Some(reason) = &f(r).reason {
                *m.entry(reason.clone()).or_insert(0) += 1;
            }
        }
        m
    };
    let by_turn = binned(&rows, |r| r.max_turn_deg, 30.0, 5);
    let by_pole_angle = binned(&rows, |r| r.pole_angle_deg, 15.0, 6);
    RandomStudy {
        sets,
        plain_successes: rows.iter().filter(|r| r.plain.success).count(),
        damped_successes: rows.iter().filter(|r| r.damped.success).count(),
        plain_failures: count(&|r| &r.plain),
        damped_failures: count(&|r| &r.damped),
        by_turn,
        by_pole_angle,
        rows,
    }
}

/// Iterations against the number of points for the three smooth families,
/// plain and damped, in f64 (in parallel).
pub fn run_iterations_vs_n(ns: &[usize]) -> Vec<IterationRow> {
    let ladder = rule_ladder::<Mp<128>>(128);
    let jobs: Vec<(QiCase, &str, bool)> = ["helix", "circle", "wave"]
        .iter()
        .flat_map(|fam| {
            ns.iter().flat_map(move |&n| {
                let case = match *fam {
                    "helix" => helix(n),
                    "circle" => circle(n),
                    _ => wave(n),
                };
                [(case.clone(), *fam, false), (case, *fam, true)]
            })
        })
        .collect();
    jobs.par_iter()
        .map(|(case, fam, damped)| {
            let run = convergence_run_with_rules::<f64, Mp<128>>(case, *damped, &ladder);
            IterationRow {
                family: fam.to_string(),
                points: case.points.len(),
                damped: *damped,
                converged: run.converged,
                iterations: run.iterations,
                final_residual: run
                    .log10_residuals
                    .last()
                    .copied()
                    .flatten()
                    .map_or(0.0, |l| 10f64.powf(l)),
                max_end_error: run.check.map(|c| c.max_end_error),
                failure: run.failure,
            }
        })
        .collect()
}

/// Curvature against arc length: the QI interpolant and two clamped cubic
/// splines with the same unit end tangents (the paper's Figure 2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvaturePlot {
    /// Point-set name.
    pub case: String,
    /// `(s, κ)` of the QI curve (f64 fit).
    pub qi: Vec<[f64; 2]>,
    /// `(s, κ)` of the chord-length clamped cubic spline.
    pub spline_chord: Vec<[f64; 2]>,
    /// `(s, κ)` of the uniform-knot clamped cubic spline.
    pub spline_uniform: Vec<[f64; 2]>,
    /// Arc length of the QI curve at the data points.
    pub qi_joints: Vec<f64>,
    /// Largest jump of κ at the QI joints (should be ~0: G2).
    pub qi_max_joint_jump: f64,
}

/// Samples per segment in the curvature and 3D plots.
pub const SAMPLES_PER_SEGMENT: usize = 48;

/// Builds the Figure 2 data for `case` (f64; the fit must converge).
pub fn curvature_plot(case: &QiCase) -> Result<CurvaturePlot, QiError> {
    let pts = points_in::<f64>(case);
    let fit = interpolate(&pts, &QiOptions::default())?;
    let mut qi = Vec::new();
    let mut joints = vec![0.0];
    let mut jump: f64 = 0.0;
    let mut s0 = 0.0;
    for (i, seg) in fit.segments.iter().enumerate() {
        for k in 0..=SAMPLES_PER_SEGMENT {
            let t = k as f64 / SAMPLES_PER_SEGMENT as f64;
            qi.push([s0 + seg.length * t, seg.curvature_at(&t)]);
        }
        if let Some(next) = fit.segments.get(i + 1) {
            jump = jump.max((seg.curvature_at(&1.0) - next.curvature_at(&0.0)).abs());
        }
        s0 += seg.length;
        joints.push(s0);
    }
    let n = pts.len() - 1;
    let t0 = start_tangent(&pts[0], &pts[1], &pts[2])?;
    let t1 = end_tangent(&pts[n - 2], &pts[n - 1], &pts[n])?;
    let spline = |param| -> Result<Vec<[f64; 2]>, QiError> {
        let sp = ClampedCubicSpline::new(&pts, param, &t0, &t1)?;
        Ok(spline_curvature(&sp))
    };
    Ok(CurvaturePlot {
        case: case.name.clone(),
        qi,
        spline_chord: spline(Parameterization::ChordLength)?,
        spline_uniform: spline(Parameterization::Uniform)?,
        qi_joints: joints,
        qi_max_joint_jump: jump,
    })
}

/// `(s, κ)` along a spline; `s` by 32-point Gauss–Legendre on `|S'|`.
fn spline_curvature(sp: &ClampedCubicSpline<f64>) -> Vec<[f64; 2]> {
    let rule = GaussLegendre::<f64>::new(32).expect("32 > 0");
    let mut out = Vec::new();
    let mut s0 = 0.0;
    for i in 0..sp.pieces() {
        let du = sp.knots()[i + 1] - sp.knots()[i];
        for k in 0..=SAMPLES_PER_SEGMENT {
            let t = k as f64 / SAMPLES_PER_SEGMENT as f64;
            let s = s0 + rule.integrate_on(&0.0, &t, |x| sp.jet(i, x)[1].norm()) * du;
            out.push([s, sp.curvature(i, &t)]);
        }
        s0 += rule.integrate(|x| sp.jet(i, x)[1].norm()) * du;
    }
    out
}

/// A sampled interpolant for a 3D view.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Curve3d {
    /// Point-set name.
    pub case: String,
    /// The data points.
    pub points: Vec<[f64; 3]>,
    /// Curve samples, [`SAMPLES_PER_SEGMENT`] + 1 per segment.
    pub samples: Vec<[f64; 3]>,
}

/// Samples the f64 interpolant of `case`.
pub fn curve_3d(case: &QiCase) -> Result<Curve3d, QiError> {
    let fit = interpolate(&points_in::<f64>(case), &QiOptions::default())?;
    let mut samples = Vec::new();
    for i in 0..fit.segments.len() {
        for k in 0..=SAMPLES_PER_SEGMENT {
            let p = fit.point(i, &(k as f64 / SAMPLES_PER_SEGMENT as f64));
            samples.push([p.x, p.y, p.z]);
        }
    }
    Ok(Curve3d {
        case: case.name.clone(),
        points: case.points.clone(),
        samples,
    })
}

/// Study size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QiParams {
    /// Number of random point sets.
    pub random_sets: usize,
    /// Point counts for the iterations-vs-n sweep.
    pub ns: Vec<usize>,
    /// Include the (slow) `Mp<1024>` run.
    pub mp1024: bool,
}

impl QiParams {
    /// A short sweep (the quick report profile).
    pub fn quick() -> Self {
        QiParams {
            random_sets: 50,
            ns: vec![3, 5, 10, 20, 35, 50],
            mp1024: false,
        }
    }
    /// The full study: 1,000 random sets, every n in 3..=50, Mp<1024>.
    pub fn full() -> Self {
        QiParams {
            random_sets: 1000,
            ns: (3..=50).collect(),
            mp1024: true,
        }
    }
}

/// The whole QI study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct QiStudy {
    /// The parameters used.
    pub params: QiParams,
    /// Convergence histories (helix-10, paper-like, circle-10; f64, Mp<256>,
    /// Mp<1024> for helix-10 in the full profile).
    pub convergence: Vec<ConvergenceRun>,
    /// Iterations against the number of points.
    pub iterations_vs_n: Vec<IterationRow>,
    /// Random point sets.
    pub random: RandomStudy,
    /// Figure 2.
    pub curvature: Option<CurvaturePlot>,
    /// 3D view of the helix-10 interpolant.
    pub curve: Option<Curve3d>,
    /// Errors building the plots (reported, not hidden).
    pub plot_errors: Vec<String>,
}

/// Runs the study (see [`QiParams`]).
pub fn run_qi(params: &QiParams) -> QiStudy {
    let cases = [helix(10), paper_like(), circle(10)];
    type Job = Box<dyn Fn() -> ConvergenceRun + Send + Sync>;
    let mut jobs: Vec<Job> = Vec::new();
    for case in &cases {
        for damped in [false, true] {
            let c = case.clone();
            jobs.push(Box::new(move || {
                convergence_run::<f64, Mp<128>>(&c, damped)
            }));
        }
        let c = case.clone();
        jobs.push(Box::new(move || {
            convergence_run::<Mp<256>, Mp<512>>(&c, false)
        }));
    }
    if params.mp1024 {
        let c = helix(10);
        jobs.push(Box::new(move || {
            convergence_run::<Mp<1024>, Mp<2048>>(&c, false)
        }));
    }
    let convergence = jobs.par_iter().map(|j| j()).collect();
    let mut plot_errors = Vec::new();
    let curvature = curvature_plot(&paper_like())
        .map_err(|e| plot_errors.push(format!("curvature plot: {e}")))
        .ok();
    let curve = curve_3d(&helix(10))
        .map_err(|e| plot_errors.push(format!("3D curve: {e}")))
        .ok();
    QiStudy {
        params: params.clone(),
        convergence,
        iterations_vs_n: run_iterations_vs_n(&params.ns),
        random: run_random(params.random_sets),
        curvature,
        curve,
        plot_errors,
    }
}
