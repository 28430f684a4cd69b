//! # splinelab
//!
//! Spline and Bézier numerics written once over a generic scalar
//! ([`scalar::Real`]) and run in `f64` and in MPFR arbitrary precision
//! ([`scalar::Mp`]), so that every f64 result has a high-precision twin.
//!
//! This crate is pure mathematics: it never prints, plots or reads files.
//! [`equations`] maps every equation of the five source papers to the item
//! that implements it; [`param_curve`] gives every curve and surface type
//! the same small capability traits (domain, point, derivative).
//!
//! # One code, two precisions
//!
//! Every routine is written once over [`scalar::Real`]; the run in
//! [`scalar::Mp`] is the f64 run's reference. The NURBS circle, evaluated by
//! rational de Boor in both:
//!
//! ```
//! use splinelab::bspline::nurbs::NurbsCurve;
//! use splinelab::nalgebra::Vector2;
//! use splinelab::scalar::{Mp, Real};
//! type M = Mp<256>;
//! let c64 = NurbsCurve::circle(&Vector2::new(0.0f64, 0.0), &1.0).unwrap();
//! let cmp = NurbsCurve::circle(&Vector2::new(M::from_int(0), M::from_int(0)), &M::from_int(1)).unwrap();
//! let t = 0.3;
//! let (p, q) = (c64.eval(&t).unwrap(), cmp.eval(&M::from_f64_exact(t)).unwrap());
//! // On the unit circle to within 256-bit rounding …
//! assert!((q.norm_squared() - M::from_int(1)).to_f64().abs() < 1e-70);
//! // … and the f64 point within a few ulps of its MPFR twin.
//! for i in 0..2 {
//!     assert!((p[i] - q[i].to_f64()).abs() < 4.0 * f64::EPSILON);
//! }
//! ```
//!
//! # Guide: the interpolation engine
//!
//! `use splinelab::prelude::*;` brings in everything below. [`ndarray`] and
//! [`nalgebra`] are re-exported, so you need not pin their versions.
//!
//! | scipy.ndimage | splinelab |
//! |---|---|
//! | `order=d` (degree, ≤ 5) | `degree: d` in [`prelude::Options`] (`1..=199`); our B-spline *order* `m = d + 1` ([`sspline::SplineFamily::Order`]) |
//! | `mode="mirror"` | [`prelude::Mode::Mirror`] (the paper's tangent ends with zero tangents) |
//! | `mode="reflect"` / `"grid-mirror"` | [`prelude::Mode::Reflect`] |
//! | `mode="grid-wrap"` | [`prelude::Mode::GridWrap`] (the paper's periodic ends; `wrap` accepted as an alias) |
//! | `mode="nearest"` | [`prelude::Mode::Nearest`] (the paper's free ends) |
//! | `mode="grid-constant"`, `cval` | [`prelude::Mode::GridConstant`], `Options::cval` |
//! | `spline_filter1d(a, order, axis, mode=…)` | [`prelude::spline_filter1d`]`(&mut a, axis, &filter)` |
//! | `spline_filter(a, order, mode=…)` | [`prelude::spline_filter`] |
//! | `map_coordinates(a, coords, order, mode=…, cval=…)` | [`prelude::map_coordinates`], or [`prelude::Interpolant`] built once |
//! | — | truncated prefilter of certified width: [`prelude::Route::Truncated`] |
//! | — | 1-D blocks in parallel: [`prelude::BlockPrefilter`] |
//!
//! **Prefilter one axis** (in place, lines in parallel):
//!
//! ```
//! use splinelab::prelude::*;
//! let f = LineFilter::<f64>::new(&SplineFamily::Order(6), Mode::Reflect, 0.0, Route::Exact).unwrap();
//! let mut a = ndarray::Array2::from_shape_fn((64, 48), |(i, j)| ((i * j) as f64).sin());
//! spline_filter1d(&mut a, 0, &f).unwrap();
//! ```
//!
//! **Truncated to a tolerance** (coefficients within `bound · max|s|` of
//! the exact ones, per axis):
//!
//! ```
//! use splinelab::prelude::*;
//! let f = LineFilter::<f64>::new(&SplineFamily::Order(4), Mode::Mirror, 0.0,
//!                                Route::Truncated { tol: 1e-10 }).unwrap();
//! assert!(f.bound() < 1e-10 && f.half_width() == Some(18));
//! ```
//!
//! **Interpolate at arbitrary points**, with derivatives, f32 data too:
//!
//! ```
//! use splinelab::prelude::*;
//! let data = ndarray::Array3::<f32>::from_shape_fn((8, 9, 24), |(i, j, k)| (i + 2 * j + 3 * k) as f32);
//! let f = Interpolant::new(&data, Options::new(3, Mode::Nearest)).unwrap();
//! assert!((f.eval(&[2.0, 3.0, 4.0]).unwrap() - 20.0).abs() < 1e-4);
//! // Linear data is reproduced away from the ends (the ends' influence decays as 0.27^distance).
//! let slope = f.eval_derivative(&[3.5, 4.5, 11.5], &[0, 0, 1]).unwrap();
//! assert!((slope - 3.0).abs() < 1e-4);
//! ```
//!
//! **Many points into your buffer** (parallel, no allocation per point):
//!
//! ```
//! use splinelab::prelude::*;
//! let data = ndarray::Array2::from_shape_fn((50, 50), |(i, j)| (i as f64 * 0.1).cos() * j as f64);
//! let f = Interpolant::new(&data, Options::new(5, Mode::Mirror)).unwrap();
//! let pts = ndarray::Array2::from_shape_fn((1000, 2), |(k, a)| (k * (a + 3)) as f64 % 49.0);
//! let mut out = vec![0.0; 1000];
//! f.eval_many(pts.view(), &mut out).unwrap();
//! ```
//!
//! **High degree, in MPFR** (f64 refuses what it cannot represent):
//!
//! ```
//! use splinelab::prelude::*;
//! assert!(RecursivePrefilter::<f64>::new_within(&SplineFamily::Order(100), 1e-8).is_err());
//! let s = ndarray::Array1::from_shape_fn(30, |i| Mp::<256>::from_int((i * i % 7) as i64));
//! let f = Interpolant::new(&s, Options::new(99, Mode::Mirror)).unwrap();
//! assert!((f.eval(&[4.0]).unwrap() - Mp::<256>::from_int(2)).to_f64().abs() < 1e-50);
//! ```
//!
//! **One long signal in parallel blocks** (within the certified bound of
//! the sequential filter):
//!
//! ```
//! use splinelab::prelude::*;
//! let s: Vec<f64> = (0..100_000).map(|i| (i as f64 * 0.01).sin()).collect();
//! let f = BlockPrefilter::new(&SplineFamily::Order(4), Mode::Mirror, 0.0, 1e-12).unwrap();
//! let d = f.apply(&s, 1 << 14).unwrap();
//! assert_eq!(d.len(), s.len());
//! ```

pub mod arclength;
pub mod bernstein;
pub mod bspline;
pub mod curves;
pub mod equations;
pub mod gridded;
pub mod matrix_condition;
pub mod named;
pub mod ndimage;
pub mod param_curve;
pub mod prelude;
pub mod qi;
pub mod quadrature;
pub mod roots;
pub mod scalar;
pub mod sspline;
pub mod surface_deformation;
pub mod validation;

pub use nalgebra;
pub use ndarray;
