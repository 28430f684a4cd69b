//! Bernstein polynomials: the basis, Bernstein–Vandermonde matrices and the
//! algorithms that evaluate polynomials given in Bernstein form.

pub mod basis;
pub mod bernstein_sum;
pub mod bezier;
pub mod compensated;
pub mod condition;
pub mod power_form;
pub mod volk_schumaker;
