//! Cost models: what a request will take, estimated from its arguments
//! before it starts, so that the command line (`--budget`) and the Python
//! package (`budget=`) refuse a request of hours up front instead of hanging.
//!
//! The models are calibrated on measurements on the team's 2-core machine
//! (see [`unit_seconds`]); they are meant to be right within a factor of a
//! few, enough to tell a second from an hour.

use splinelab::sspline::SplineFamily;

/// A cost estimate for one request.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Estimated run time, seconds.
    pub seconds: f64,
    /// Estimated peak memory of the large arrays, bytes.
    pub bytes: f64,
    /// What dominates, for the message (e.g. "degree-2000 de Casteljau at 10 parameters").
    pub what: String,
}

/// Why a request was refused before it started: its estimate passes the
/// time budget or the memory limit. Carries the figure that would admit
/// it (twice the time, 1.5× the memory, rounded up), so that each front end
/// names its own knob (`--budget` on the command line, `budget=` in Python).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OverBudget {
    /// The estimated run time passes the budget.
    #[error("this request ({what}) is estimated at {seconds:.2e} s, over the budget of {budget} s")]
    Time {
        /// What dominates the cost.
        what: String,
        /// The estimate, seconds.
        seconds: f64,
        /// The budget, seconds.
        budget: f64,
        /// A budget that admits the request, seconds.
        admit: f64,
    },
    /// The estimated memory passes the limit.
    #[error(
        "this request ({what}) is estimated to need {mib:.0} MiB, over the limit of {limit} MiB"
    )]
    Memory {
        /// What dominates the cost.
        what: String,
        /// The estimate, MiB.
        mib: f64,
        /// The limit, MiB.
        limit: f64,
        /// A limit that admits the request, MiB.
        admit: f64,
    },
}

impl OverBudget {
    /// The budget (seconds) or limit (MiB) that admits the request.
    pub fn admit(&self) -> f64 {
        match self {
            OverBudget::Time { admit, .. } | OverBudget::Memory { admit, .. } => *admit,
        }
    }
}

impl Estimate {
    /// Refuses the request when its time passes `budget` seconds or its
    /// memory passes `max_mib` MiB (`None`: no memory limit). The caller
    /// has checked that both are positive numbers.
    pub fn within(&self, budget: f64, max_mib: Option<f64>) -> Result<(), OverBudget> {
        if self.seconds > budget {
            return Err(OverBudget::Time {
                what: self.what.clone(),
                seconds: self.seconds,
                budget,
                admit: (self.seconds * 2.0).ceil(),
            });
        }
        let mib = self.bytes / (1024.0 * 1024.0);
        match max_mib {
            Some(limit) if mib > limit => Err(OverBudget::Memory {
                what: self.what.clone(),
                mib,
                limit,
                admit: (mib * 1.5).ceil(),
            }),
            _ => Ok(()),
        }
    }
}

/// Seconds of one work unit (about one MPFR multiply-add with its
/// temporaries) at `bits` of precision (53 = f64). Fitted to
/// `cond --degree 80` and `bezier-eval --method decasteljau` (degree 2000,
/// 10 parameters) at f64, 64, 256 and 2048 bits: 2e-8 s in f64,
/// `1e-6·(1 + (bits/64)^0.6)` s in MPFR (2 µs at 64 bits, 9 µs at 2048).
pub fn unit_seconds(bits: u32) -> f64 {
    if bits <= 53 {
        2e-8
    } else {
        1e-6 * (1.0 + (bits as f64 / 64.0).powf(0.6))
    }
}

/// Bytes of one stored number at `bits` (an MPFR value with its limbs).
pub fn number_bytes(bits: u32) -> f64 {
    if bits <= 53 {
        8.0
    } else {
        48.0 + (bits as f64 / 8.0).ceil()
    }
}

/// The cost of [`splinelab::sspline::truncation_width`]: the tail analysis
/// up to the width limit `n_max` (`O(n_max·K·p)` products at 320 bits,
/// `K ≈ n_max + 64/log2(1/ρ)`, see `WidthChooser::choose`), with
/// `log2(1/ρ) ≈ 54/n_sat` from the f64 saturation width `n_sat`, and
/// `n_max ≈ n_sat·log2(1/tol)/54`.
pub fn width_search(family: &SplineFamily, n_sat: usize, tol: f64) -> Estimate {
    let per_bit = n_sat.max(1) as f64 / 54.0;
    let n_max = per_bit * (-tol.log2()).max(1.0) + 2.0;
    let k = n_max + 64.0 * per_bit;
    let m = family.spline_order() as f64;
    let p = (m / 2.0).max(1.0);
    Estimate {
        seconds: (n_max * k * p + 114.0 * k * m) * unit_seconds(320),
        bytes: 2.0 * k * p * number_bytes(320),
        what: format!("width search to n ≈ {n_max:.0} for {family}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The model grows with the degree and with log(1/tol): the Python
    /// budget's refusal of degree 199 at 1e-10 (measured > 60 s) rests on it.
    #[test]
    fn width_search_grows_with_degree_and_accuracy() {
        let cubic = SplineFamily::order(4).unwrap();
        let high = SplineFamily::order(200).unwrap();
        let n_cubic = splinelab::sspline::f64_saturation_width(&cubic).unwrap();
        let n_high = splinelab::sspline::f64_saturation_width(&high).unwrap();
        let a = width_search(&cubic, n_cubic, 1e-10).seconds;
        let b = width_search(&cubic, n_cubic, 1e-14).seconds;
        let c = width_search(&high, n_high, 1e-10).seconds;
        assert!(
            a < 1.0,
            "cubic at 1e-10 is estimated {a} s (it takes milliseconds)"
        );
        assert!(b > a && c > 60.0, "estimates {a} {b} {c}");
    }

    fn estimate(seconds: f64, mib: f64) -> Estimate {
        Estimate {
            seconds,
            bytes: mib * 1024.0 * 1024.0,
            what: "a test".into(),
        }
    }

    #[test]
    fn refusals_name_the_figure_that_admits_the_request() {
        assert_eq!(estimate(5.0, 3.0).within(5.0, None), Ok(()));
        let time = estimate(10.2, 1.0).within(5.0, Some(4.0)).unwrap_err();
        assert!(matches!(time, OverBudget::Time { .. }) && time.admit() == 21.0);
        assert!(
            time.to_string()
                .contains("1.02e1 s, over the budget of 5 s")
        );
        let memory = estimate(1.0, 3.0).within(5.0, Some(2.0)).unwrap_err();
        assert!(matches!(memory, OverBudget::Memory { .. }) && memory.admit() == 5.0);
        assert!(
            memory
                .to_string()
                .contains("need 3 MiB, over the limit of 2 MiB")
        );
    }
}
