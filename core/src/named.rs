//! Enums that the command line, JSON and Python spell out by name.
//!
//! Each such enum derives its names with `strum` (`VariantArray`,
//! `IntoStaticStr`, one `serialize` spelling per variant) and calls
//! [`named_enum!`](crate::named_enum) once for the methods every caller uses:
//! `ALL`-style iteration, `name()`, `Display` and a `FromStr` whose error
//! lists the accepted names. No name table is written by hand.

/// Parses `s` as one of `variants`' names; the error names `what` and every
/// accepted spelling, e.g. `unknown criterion 'x' (expected one of coeff, knot, uniform)`.
/// **Method**: a linear search of `variants` by their `strum` names (string
/// comparison only; not a numerical routine, so there is no accuracy or reference to cite).
///
/// ```
/// use splinelab::sspline::Criterion;
/// assert_eq!("knot".parse::<Criterion>(), Ok(Criterion::Knot));
/// assert_eq!(
///     "x".parse::<Criterion>().unwrap_err(),
///     "unknown criterion 'x' (expected one of coeff, knot, uniform)"
/// );
/// ```
pub fn parse_name<E>(s: &str, what: &str, variants: &[E]) -> Result<E, String>
where
    E: Copy + Into<&'static str>,
{
    variants
        .iter()
        .copied()
        .find(|v| Into::<&'static str>::into(*v) == s)
        .ok_or_else(|| {
            let names: Vec<&'static str> = variants.iter().map(|&v| v.into()).collect();
            format!(
                "unknown {what} '{s}' (expected one of {})",
                names.join(", ")
            )
        })
}

/// Adds `all()`, `name()`, `Display` and `FromStr` to an enum that derives
/// `strum::VariantArray` and `strum::IntoStaticStr`; `$what` names the
/// kind of thing in parse errors (a `String`), or `$err` maps the refused
/// text to the enum's own typed error.
#[macro_export]
macro_rules! named_enum {
    ($t:ty, $what:literal) => {
        $crate::named_enum!(@names $t);
        impl ::std::str::FromStr for $t {
            type Err = String;
            fn from_str(s: &str) -> Result<Self, String> {
                $crate::named::parse_name(s, $what, <$t as ::strum::VariantArray>::VARIANTS)
            }
        }
    };
    ($t:ty, $what:literal, $err:ty, $map:expr) => {
        $crate::named_enum!(@names $t);
        impl ::std::str::FromStr for $t {
            type Err = $err;
            fn from_str(s: &str) -> Result<Self, $err> {
                $crate::named::parse_name(s, $what, <$t as ::strum::VariantArray>::VARIANTS)
                    .map_err(|_| ($map)(s))
            }
        }
    };
    (@names $t:ty) => {
        impl $t {
            /// Every variant, in declaration order.
            pub fn all() -> impl ExactSizeIterator<Item = $t> {
                <$t as ::strum::VariantArray>::VARIANTS.iter().copied()
            }

            /// The command-line / JSON name.
            pub fn name(self) -> &'static str {
                self.into()
            }
        }

        impl ::std::fmt::Display for $t {
            fn fmt(&self, f: &mut ::std::fmt::Formatter<'_>) -> ::std::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}
