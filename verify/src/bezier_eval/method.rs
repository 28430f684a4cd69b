//! The evaluation methods compared, and a polynomial prepared for all of them.

use serde::{Deserialize, Serialize};
use splinelab::bernstein::bernstein_sum::bernstein_sum_bounded;
use splinelab::bernstein::bezier::{BernsteinPoly, BezierError, Evaluation};
use splinelab::bernstein::compensated::compensated_de_casteljau_bounded;
use splinelab::bernstein::power_form::PowerForm;
use splinelab::bernstein::volk_schumaker::volk_schumaker_bounded;
use splinelab::scalar::Real;

/// The evaluation methods compared (command-line names in [`Method::name`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[derive(strum::VariantArray, strum::IntoStaticStr)]
#[strum(serialize_all = "kebab-case")]
pub enum Method {
    /// de Casteljau's algorithm.
    #[serde(rename = "decasteljau")]
    #[strum(serialize = "decasteljau")]
    DeCasteljau,
    /// Bernstein → monomial conversion in the working precision, then Horner.
    Power,
    /// Conversion exact in rationals then rounded, then Horner.
    PowerExact,
    /// Direct Bernstein sum (binomials × powers).
    Bernstein,
    /// The Volk–Schumaker `O(n)` scheme.
    Vs,
    /// Compensated de Casteljau: de Casteljau at twice the working precision,
    /// rounded (error-free transformations of the scalar).
    Compensated,
}

splinelab::named_enum!(Method, "method");

/// Why an evaluation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvalError {
    /// Bad input or overflow in core.
    #[error(transparent)]
    Bezier(#[from] BezierError),
}

/// A Bernstein polynomial prepared for every method (the power forms are
/// converted once).
#[derive(Debug, Clone)]
pub struct Prepared<T: Real> {
    /// The polynomial.
    pub poly: BernsteinPoly<T>,
    power: Result<PowerForm<T>, BezierError>,
    power_exact: Result<PowerForm<T>, BezierError>,
}

impl<T: Real> Prepared<T> {
    /// Validates the coefficients and converts to power form (both routes).
    pub fn new(coeffs: Vec<T>) -> Result<Self, BezierError> {
        let poly = BernsteinPoly::new(coeffs)?;
        Ok(Prepared {
            power: PowerForm::from_bernstein(&poly),
            power_exact: PowerForm::from_bernstein_exact(&poly),
            poly,
        })
    }

    /// `p(t)` with its running error bound by `method`.
    pub fn evaluate(&self, method: Method, t: &T) -> Result<Evaluation<T>, EvalError> {
        Ok(match method {
            Method::DeCasteljau => self.poly.de_casteljau_bounded(t)?,
            Method::Power => self.power.clone()?.horner_bounded(t)?,
            Method::PowerExact => self.power_exact.clone()?.horner_bounded(t)?,
            Method::Bernstein => bernstein_sum_bounded(&self.poly, t)?,
            Method::Vs => volk_schumaker_bounded(&self.poly, t)?,
            Method::Compensated => compensated_de_casteljau_bounded(&self.poly, t)?,
        })
    }
}
