//! Seed 001 (Maeno–Okada–Toriwaki): deforming tensor Bézier surfaces by the
//! Bernstein inverse mapping.

pub mod bv_solve;
pub mod continuity;
pub mod inverse_mapping;
pub mod patch;
pub mod vandermonde;
