//! Bernstein polynomials: the basis and the algorithms that evaluate
//! polynomials given in Bernstein form (de Casteljau, power form, direct sum,
//! Volk–Schumaker, compensated), with their condition numbers.
//!
//! Seed 001's surface pipeline built on this basis (Bernstein–Vandermonde
//! matrices, their solvers, tensor patches, the inverse mapping) lives in
//! [`crate::surface_deformation`].

pub mod affine_step;
pub mod basis;
pub mod bernstein_sum;
pub mod bezier;
pub mod compensated;
pub mod poly_condition;
pub mod power_form;
pub mod volk_schumaker;
