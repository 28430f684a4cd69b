//! Seed 001 (Maeno–Okada–Toriwaki): deforming tensor Bézier surfaces by the
//! Bernstein inverse mapping.
//!
//! The pipeline, in the paper's order: a [`patch`] (eq 1) is sampled on a
//! parameter grid, giving the Bernstein–Vandermonde system of [`vandermonde`]
//! (eq 2); [`bv_solve`] solves it (eq 3, Kronecker and Marco–Martínez
//! solvers); [`inverse_mapping`] recovers control points and deforms a patch
//! by flow vectors (eq 4); [`continuity`] restores the joins of a multi-patch
//! surface afterwards (§2.3, eq 5–6). The Bernstein basis itself is
//! [`crate::bernstein::basis`].

pub mod bv_solve;
pub mod continuity;
pub mod inverse_mapping;
pub mod patch;
pub mod vandermonde;
