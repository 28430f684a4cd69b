//! The result of any KIND and its JSON contract (`splinelab check --json`):
//! one builder shared by the command line and the Python package, so both
//! print the same object.

use super::knot_insertion::InsertionSummary;
use super::summary::CheckSummary;
use serde_json::{Map, Value, json};

/// What a check produced.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// An element-wise check.
    Elements(Box<CheckSummary>),
    /// A knot-insertion check.
    Insertion(InsertionSummary),
}

impl Outcome {
    /// `true` for a pass.
    pub fn passed(&self) -> bool {
        match self {
            Outcome::Elements(s) => s.verdict == "pass",
            Outcome::Insertion(s) => s.verdict == "pass",
        }
    }

    /// The JSON contract, with `extra` fields (mode, degree, …) added.
    pub fn to_json(&self, extra: &Map<String, Value>) -> Value {
        let mut v = match self {
            Outcome::Elements(s) => serde_json::to_value(s),
            Outcome::Insertion(s) => serde_json::to_value(s),
        }
        .unwrap_or(Value::Null);
        if let Value::Object(m) = &mut v {
            m.extend(extra.clone());
        }
        v
    }
}

/// The fields `check prefilter` and `check interp` add to the contract:
/// `mode` (scipy's name) and `degree`.
pub fn prefilter_extra(mode: &str, degree: usize) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("mode".into(), json!(mode));
    m.insert("degree".into(), json!(degree));
    m
}
