//! The Bézier evaluation stability study (seed 002: "power form: simple and
//! fast but may be unstable; de Casteljau: more steps, stable").
//!
//! Every f64 result is compared with the **exact** value of the polynomial
//! with the same (f64) coefficients at the same (f64) `t`: all data are
//! dyadic rationals, so de Casteljau's recurrence can be run exactly in big
//! integers ([`ExactPoly`]) and the errors and bounds compared exactly in
//! `rug::Rational` — no tolerance anywhere.
//!
//! Measured: relative error vs `t` near a multiple root, max error vs degree,
//! error vs `cond_B(p, t)`, how often each running / a-priori bound holds and
//! how tight it is, and the closing figure (max relative error of every
//! method on `(t − ½)^20` over a grid of `[0, 1]`).
//!
//! Layout: [`exact`] (the reference arithmetic), [`method`] (what is
//! measured), [`cases`] (the test polynomials), [`measure`] (one case and
//! the bound tallies), [`study`] (the report data).

pub mod cases;
pub mod exact;
pub mod measure;
pub mod method;
pub mod study;

pub use crate::rng::SplitMix64;
pub use cases::{Family, jiang_example, product_of_roots};
pub use exact::{ExactPoly, gamma, unit_roundoff};
pub use measure::{BoundStats, Measured, Tally, check_bounds, measure};
pub use method::{EvalError, Method, Prepared};
pub use study::*;
