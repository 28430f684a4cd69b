//! Headline figures: the numbers a CI pipeline watches for regressions.
//!
//! Every figure carries its kind, unit, direction and tolerance, so that
//! `splinelab compare` can judge a change without knowing the study.

use serde::{Deserialize, Serialize};

/// What a figure measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Kind {
    /// An error, a bound, digits or bits: deterministic, compared with an
    /// absolute slack in its unit.
    Accuracy,
    /// A time or an iteration count: compared as a ratio, with a noise band.
    Cost,
}

/// Which direction is better.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Better {
    /// Smaller values are better (errors, times).
    Lower,
    /// Larger values are better (correct digits, success rates).
    Higher,
}

/// One headline figure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Figure {
    /// Unique dotted name, starting with the section id
    /// (`conditioning.cond2_f64_digits.equispaced.n30`).
    pub name: String,
    /// The value (always finite: a figure that could not be measured is not
    /// reported as a number).
    pub value: f64,
    /// Accuracy or cost.
    pub kind: Kind,
    /// Unit, e.g. `digits`, `relative error`, `ulps`, `s`, `iterations`.
    pub unit: String,
    /// Which direction is better.
    pub better: Better,
    /// Accuracy: the absolute slack in `unit` a change may use before it
    /// counts as a regression. Cost: the ratio (≥ 1) of noise band, e.g. 3
    /// means "regressed when more than 3× worse".
    pub tolerance: f64,
    /// Cost figures only: values below this floor count as the floor, so
    /// that timer resolution and scheduling noise on tiny timings cannot
    /// look like a 10× slowdown. 0 when absent.
    #[serde(default)]
    pub floor: f64,
    /// What the figure was measured over: `"fixed cases"` when its case set
    /// is the same in every report profile, `"quick profile's cases"` /
    /// `"full profile's cases"` when the profile chooses it (set by
    /// [`crate::report::write_report`] from the section's registry entry).
    /// `splinelab compare` gates a figure across profiles only when both
    /// files say it was measured over the same thing. Absent in older files.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub over: Option<String>,
}

impl Figure {
    /// An accuracy figure where lower is better (an error), with an absolute slack.
    pub fn error(name: impl Into<String>, value: f64, unit: &str, slack: f64) -> Self {
        Figure::new(name, value, Kind::Accuracy, unit, Better::Lower, slack)
    }

    /// An accuracy figure where higher is better (digits, bits), with an absolute slack.
    pub fn digits(name: impl Into<String>, value: f64, unit: &str, slack: f64) -> Self {
        Figure::new(name, value, Kind::Accuracy, unit, Better::Higher, slack)
    }

    /// A cost figure (lower is better) with a ratio noise band.
    pub fn cost(name: impl Into<String>, value: f64, unit: &str, band: f64) -> Self {
        Figure::new(name, value, Kind::Cost, unit, Better::Lower, band)
    }

    /// A figure with every field given.
    pub fn new(
        name: impl Into<String>,
        value: f64,
        kind: Kind,
        unit: &str,
        better: Better,
        tolerance: f64,
    ) -> Self {
        Figure {
            name: name.into(),
            value,
            kind,
            unit: unit.into(),
            better,
            tolerance,
            floor: 0.0,
            over: None,
        }
    }

    /// The same figure with what it was measured over, unless the section
    /// already said (see [`Figure::over`]).
    pub fn measured_over(mut self, over: &str) -> Self {
        self.over.get_or_insert_with(|| over.to_string());
        self
    }

    /// The same figure with a noise floor (cost figures).
    pub fn with_floor(mut self, floor: f64) -> Self {
        self.floor = floor;
        self
    }
}

/// A figure-name fragment from free text: ASCII alphanumerics lower-cased,
/// every other run of characters one `_` (`é` read as `e`).
pub fn slug(s: &str) -> String {
    let mut out = String::new();
    for c in s.replace('é', "e").chars() {
        if c.is_ascii_alphanumeric() {
            out.push(c.to_ascii_lowercase());
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    out.trim_matches('_').to_string()
}
