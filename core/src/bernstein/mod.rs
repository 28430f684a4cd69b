//! Bernstein polynomials: the basis, Bernstein–Vandermonde matrices and the
//! algorithms that evaluate polynomials given in Bernstein form.

pub mod basis;
pub mod vandermonde;
