//! What happens to a point of a batch evaluation before the interpolant
//! folds it by its mode: scipy's `constant` and `wrap` point rules.

/// What happens to a point before the interpolant folds it by its mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointRule {
    /// Nothing: the interpolant's own mode.
    Fold,
    /// scipy's `constant`: `cval` wherever a coordinate is outside `[0, n − 1]`.
    CvalOutside,
    /// scipy's `wrap`: a coordinate outside `[0, n − 1]` moves by whole
    /// periods `n − 1` into it (`map_coordinate` in scipy's
    /// `ni_interpolation.c`, its operations: a truncating division).
    WrapPeriodNMinus1,
}

impl PointRule {
    /// The rule applied to point `x` of a grid of `shape`: whether it takes
    /// `cval` (moving it by whole periods for the `wrap` rule).
    #[inline]
    pub(crate) fn apply(self, x: &mut [f64], shape: &[usize]) -> bool {
        match self {
            PointRule::Fold => false,
            PointRule::CvalOutside => x
                .iter()
                .zip(shape)
                .any(|(&t, &len)| t < 0.0 || t > (len - 1) as f64),
            PointRule::WrapPeriodNMinus1 => {
                for (t, &len) in x.iter_mut().zip(shape) {
                    *t = wrap_period_n_minus_1(*t, len);
                }
                false
            }
        }
    }
}

/// scipy's `wrap` folding of one coordinate (see [`PointRule`]).
pub(super) fn wrap_period_n_minus_1(x: f64, len: usize) -> f64 {
    if len <= 1 {
        return 0.0;
    }
    let sz = (len - 1) as f64;
    if x < 0.0 {
        x + sz * ((-x / sz).trunc() + 1.0)
    } else if x > sz {
        x - sz * (x / sz).trunc()
    } else {
        x
    }
}
