//! The curves of seed 002 measured against independent references: cubic
//! Hermite ↔ Bézier, rational circular arcs and degree elevation, NURBS
//! circle and cylinder, Catmull–Rom interpolation and C¹ continuity, adaptive
//! vs uniform flattening, de Boor vs Cox–de Boor, B-spline vs Bézier patch.
//!
//! Every error is computed in MPFR at `2·BITS + 64` bits from the exact
//! values of the computed result (so the measurement adds no rounding of
//! its own) and reported **in units of the unit roundoff `u` of the
//! precision under test**, relative to the scale of the data, so that f64
//! and MPFR rows are comparable and can be checked against the documented
//! bounds.
//!
//! Layout: [`cases`] (the inputs), [`measure`] (one construction against
//! its reference; the error arithmetic is [`crate::metrics`]'s),
//! [`properties`] (the verified-properties table), [`gallery`] and
//! [`study`] (the report data).

pub mod cases;
pub mod gallery;
pub mod measure;
pub mod properties;
pub mod study;

pub use cases::{flatten_test_curves, frac, loop_example, study_arcs};
pub use gallery::{Sampled, polyline_self_intersects, sample_catmull_rom};
pub use measure::*;
pub use properties::{PropertyRow, bounds};
pub use study::*;

/// Why a curves measurement failed (a core error, reported as text).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("curves study: {0}")]
pub struct CurvesStudyError(pub String);

fn err(e: impl std::fmt::Display) -> CurvesStudyError {
    CurvesStudyError(e.to_string())
}
