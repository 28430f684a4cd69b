//! The `--prec f64|BITS` option and its dispatch to a concrete scalar type.
//!
//! The MPFR precision of [`Mp`](splinelab::scalar::Mp) is a const generic,
//! so only precisions compiled in can run. A request for `BITS` runs at the
//! smallest compiled precision `W ≥ BITS` ([`Prec::working_bits`]); results
//! are then rounded to `BITS` bits and printed with the digits `BITS` carries,
//! and JSON output states both (`prec`, `working_bits`). The result is thus at
//! least as accurate as a `BITS`-bit computation, never less.

use crate::error::CliError;
use rug::Float;
use splinelab::scalar::{Real, decimal_string};
use std::fmt;
use std::str::FromStr;

/// The one definition of the compiled MPFR precisions, increasing: calls
/// `$crate::$m!{ $args ; 128, 256, … }`. [`LADDER`] and [`with_real!`](crate::with_real)
/// are both generated from it, so they cannot disagree.
///
/// Each step doubles the previous one, so a request above 128 bits runs
/// at most 2× its bits (e.g. 1025 → 2048; 1024 → 1024). Requests of 16 to
/// 128 bits run at 128: one or two limbs cost about the same (a degree-5
/// `prefilter` of 700² samples: 0.35 CPU-s at 64 bits, 0.42 at 128), and
/// an entry at 64 cost the first build 6–7 s on 2 cores (issue 38). Each
/// entry instantiates every command's numerics once more: the reports
/// crate's build grows by about
/// 13 CPU-seconds per entry (measured: 70 s with one entry, 135 s with
/// these six, 194 s with eleven steps of 1.5×), and the first build is what
/// a new user waits for; doubling keeps the cost of a request within 2× of
/// its bits while halving that wait. The ladder stops at [`MAX_BITS`]
/// = 2048: higher requests are refused as out of range rather than run at
/// a precision far above the one asked for, and rather than compiling a
/// further 18 entries (to 2^20) into every build.
#[macro_export]
macro_rules! precision_ladder {
    ($m:ident { $($args:tt)* }) => {
        $crate::$m! { $($args)* ; 128, 256, 512, 1024, 2048 }
    };
}

/// Expands the ladder into a slice (used by [`LADDER`]).
#[doc(hidden)]
#[macro_export]
macro_rules! ladder_slice {
    (; $($w:literal),+) => { &[$($w),+] };
}

/// The compiled MPFR precisions, increasing (from [`precision_ladder!`]).
pub const LADDER: &[u32] = precision_ladder!(ladder_slice {});

/// Smallest accepted `BITS`.
pub const MIN_BITS: u32 = 16;
/// Largest accepted `BITS`: the top of the ladder.
// Justified: evaluated at compile time (an index outside `LADDER` would not compile).
#[allow(clippy::indexing_slicing)]
pub const MAX_BITS: u32 = LADDER[LADDER.len() - 1];

/// A requested precision: IEEE double or an MPFR bit count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Prec {
    /// IEEE 754 binary64.
    F64,
    /// MPFR with this many bits of significand.
    Bits(u32),
}

impl FromStr for Prec {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        if s == "f64" {
            return Ok(Prec::F64);
        }
        let t = s.trim();
        let digits = t.strip_prefix('+').unwrap_or(t);
        if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
            let negative = digits
                .strip_prefix('-')
                .is_some_and(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()));
            return Err(if negative {
                format!("a bit count is positive; accepted: f64 or {MIN_BITS}..={MAX_BITS}")
            } else {
                format!("neither 'f64' nor a bit count {MIN_BITS}..={MAX_BITS}")
            });
        }
        match digits.parse::<u32>() {
            Ok(bits) if (MIN_BITS..=MAX_BITS).contains(&bits) => Ok(Prec::Bits(bits)),
            _ => Err(format!(
                "bit count out of range: accepted {MIN_BITS}..={MAX_BITS} (or f64)"
            )),
        }
    }
}

impl fmt::Display for Prec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Prec::F64 => f.write_str("f64"),
            Prec::Bits(b) => write!(f, "{b}"),
        }
    }
}

impl Prec {
    /// The precision the computation runs at: 53 for f64, else the smallest
    /// compiled MPFR precision `≥ BITS`.
    pub fn working_bits(self) -> u32 {
        match self {
            Prec::F64 => 53,
            // `b ≤ MAX_BITS`, the last entry, by construction of `Prec`.
            Prec::Bits(b) => LADDER.iter().copied().find(|&w| w >= b).unwrap_or(MAX_BITS),
        }
    }

    /// Significant decimal digits justified by the requested precision.
    pub fn digits(self) -> usize {
        let bits = match self {
            Prec::F64 => 53,
            Prec::Bits(b) => b,
        };
        (bits as f64 * std::f64::consts::LOG10_2).ceil() as usize + 1
    }

    /// Formats a result computed at the working precision: rounded to the
    /// requested bits, then printed with [`Prec::digits`] digits (17 for f64,
    /// which round-trips).
    pub fn format<T: Real>(self, x: &T) -> String {
        match self {
            Prec::F64 => decimal_string(&x.to_float(), 17),
            Prec::Bits(b) => decimal_string(&Float::with_val(b, x.to_float()), self.digits()),
        }
    }
}

/// Parses `--prec` for clap, with the range in the message.
pub fn parse_prec(s: &str) -> Result<Prec, String> {
    s.parse()
}

/// Turns a `Prec` check into a [`CliError`] (for callers outside clap).
pub fn invalid_prec(why: String) -> CliError {
    CliError::invalid("--prec", why)
}

/// Runs `$body` with `$T` bound to the scalar type for `$prec`:
/// `f64`, or `Mp<W>` with `W = $prec.working_bits()` (arms generated from
/// [`precision_ladder!`]). Used in functions returning `Result<_,
/// CliError>`: a precision off the ladder returns an error from them.
///
/// ```ignore
/// let s = with_real!(prec, T => compute::<T>(&args)?);
/// ```
#[macro_export]
macro_rules! with_real {
    ($prec:expr, $T:ident => $body:expr) => {
        $crate::precision_ladder!(dispatch_real { $prec, $T, $body })
    };
}

/// The `match` behind [`with_real!`].
#[doc(hidden)]
#[macro_export]
macro_rules! dispatch_real {
    ($prec:expr, $T:ident, $body:expr ; $($w:literal),+) => {{
        use splinelab::scalar::Mp;
        match $prec.working_bits() {
            53 => {
                type $T = f64;
                $body
            }
            $(
                $w => {
                    type $T = Mp<$w>;
                    $body
                }
            )+
            // On the ladder by construction (`Prec` is validated); an error,
            // not a panic, should that ever change.
            w => {
                return Err($crate::error::CliError::numerical(format!(
                    "working precision {w} bits is not on the ladder"
                )))
            }
        }
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn precision_range_and_ladder() {
        assert_eq!("f64".parse::<Prec>(), Ok(Prec::F64));
        assert!("15".parse::<Prec>().is_err());
        assert!("1000001".parse::<Prec>().is_err());
        assert!("2049".parse::<Prec>().is_err());
        assert!(
            "4294967296"
                .parse::<Prec>()
                .unwrap_err()
                .contains("out of range")
        );
        assert!("abc".parse::<Prec>().is_err());
        assert_eq!(Prec::Bits(100).working_bits(), 128);
        assert_eq!(Prec::Bits(256).working_bits(), 256);
        assert_eq!(Prec::Bits(1025).working_bits(), 2048);
        assert_eq!(Prec::Bits(2048).working_bits(), 2048);
        assert!(Prec::Bits(128).digits() >= 30);
    }

    /// Every accepted request runs at most 2× its bits (128 for the
    /// smallest), on an entry that `with_real!` dispatches.
    #[test]
    fn working_precision_is_at_most_twice_the_request() -> Result<(), CliError> {
        assert!(LADDER.windows(2).all(|w| w[0] < w[1]));
        for b in MIN_BITS..=MAX_BITS {
            let w = Prec::Bits(b).working_bits();
            assert!(w >= b && (w <= 128 || w < 2 * b), "{b} -> {w}");
            let dispatched = crate::with_real!(Prec::Bits(b), T => <T as Real>::BITS);
            assert_eq!(dispatched, w);
        }
        Ok(())
    }
}
