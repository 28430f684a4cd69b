//! Regression compare of two `summary.json` files.
//!
//! The figures both files have are judged by the baseline's kind and
//! tolerance ([`Figure`]): an accuracy figure regresses when it is worse by
//! more than its absolute slack, a cost figure when it is worse by more than
//! its ratio band. Figures only one file has (a different profile, a study
//! that gained or lost a figure) and figures whose kind, unit or direction
//! changed are listed, not judged. Wall-clock figures (a cost in `s` or `ns`)
//! are shown but gate the exit code only with `--timings`: on a shared
//! machine only ratios measured in the same run (unit `ratio`) and
//! deterministic costs (iterations) are reliable gates.

use super::figure::{Better, Figure, Kind};
use crate::chart::{Chart, Series};
use crate::error::CliError;
use crate::html::{escape, num};
use crate::input::read_json;
use crate::page::verdict;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;

/// The verdict on one figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Within tolerance (or better).
    Ok,
    /// Better than the baseline beyond the tolerance (worth refreshing it).
    Improved,
    /// Worse than the baseline beyond the tolerance.
    Regressed,
}

/// One compared figure.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The baseline figure (its kind, unit and tolerance are the contract).
    pub baseline: Figure,
    /// The current value.
    pub current: f64,
    /// The verdict.
    pub verdict: Verdict,
    /// Whether a regression of this figure fails the compare (wall-clock
    /// figures only with `--timings`; never a figure measured over other
    /// cases than the baseline's, see [`comparable`]).
    pub gated: bool,
    /// Whether both files measured it over the same cases.
    pub comparable: bool,
}

/// Everything one compare found.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The figures both files have, in baseline order.
    pub rows: Vec<Comparison>,
    /// Names only the baseline has.
    pub only_baseline: Vec<String>,
    /// Names only the current file has.
    pub only_current: Vec<String>,
    /// Names whose kind, unit or direction differ (not judged).
    pub changed: Vec<String>,
    /// Names both files have, measured over different cases (a different
    /// profile): shown, not gated.
    pub incomparable: Vec<String>,
    /// Gated figures of the baseline that the current run (same profile)
    /// no longer has: each is a regression, unless `--allow-missing`.
    pub missing: Vec<String>,
    /// The report profiles (`quick`, `full`) of baseline and current, when recorded.
    pub profiles: (Option<String>, Option<String>),
}

impl Outcome {
    /// The gated figures that regressed.
    pub fn regressed(&self) -> Vec<&Comparison> {
        self.rows
            .iter()
            .filter(|r| r.gated && r.verdict == Verdict::Regressed)
            .collect()
    }

    /// Whether the compare fails: a gated figure regressed or went missing.
    pub fn failed(&self) -> bool {
        !self.regressed().is_empty() || !self.missing.is_empty()
    }

    /// A plain sentence on the profiles, when they differ (or only one file
    /// records one); none for two files without a profile, such as two
    /// `check --out` or pytest-plugin summaries.
    pub fn profile_note(&self) -> Option<String> {
        let show = |p: &Option<String>| p.clone().unwrap_or_else(|| "not recorded".into());
        match &self.profiles {
            (a, b) if a == b => None,
            (a, b) => Some(format!(
                "The profiles differ (baseline: {}, current: {}): of the {} figures both runs \
                 have, the {} measured over the same cases gate and the {} measured over \
                 different cases are shown, not gated; {} are only in the baseline and {} only \
                 in the current run.",
                show(a),
                show(b),
                self.rows.len(),
                self.rows.len() - self.incomparable.len(),
                self.incomparable.len(),
                self.only_baseline.len(),
                self.only_current.len()
            )),
        }
    }
}

/// Whether a figure is a wall-clock time (a cost in seconds or nanoseconds),
/// which gates only with `--timings`.
pub fn is_wall_clock(f: &Figure) -> bool {
    f.kind == Kind::Cost && matches!(f.unit.as_str(), "s" | "ms" | "µs" | "us" | "ns")
}

/// The report profile recorded in a summary (`profile`, or `report.profile`
/// in older files), if any.
pub fn read_profile(path: &Path) -> Result<Option<String>, CliError> {
    let json: Value = read_json(path)?;
    Ok(json
        .get("profile")
        .or_else(|| json.get("report").and_then(|r| r.get("profile")))
        .and_then(Value::as_str)
        .map(str::to_string))
}

/// Reads the `figures` array of a summary file, with errors that name the
/// file and the field.
pub fn read_figures(path: &Path) -> Result<Vec<Figure>, CliError> {
    let bad = |why: String| CliError::Input {
        path: path.to_path_buf(),
        why,
    };
    let json: Value = read_json(path)?;
    let figures = json
        .get("figures")
        .ok_or_else(|| bad("missing field 'figures'".into()))?;
    let list = figures
        .as_array()
        .ok_or_else(|| bad("field 'figures' is not an array".into()))?;
    if list.is_empty() {
        // Comparing nothing would pass vacuously.
        return Err(bad("field 'figures' is empty".into()));
    }
    list.iter()
        .enumerate()
        .map(|(i, f)| {
            let fig: Figure = serde_json::from_value(f.clone())
                .map_err(|e| bad(format!("field 'figures[{i}]': {e}")))?;
            if !fig.value.is_finite() || !fig.tolerance.is_finite() || fig.tolerance < 0.0 {
                return Err(bad(format!(
                    "field 'figures[{i}]' ({}): non-finite value or tolerance",
                    fig.name
                )));
            }
            Ok(fig)
        })
        .collect()
}

/// Judges `current` against `baseline` by the baseline's contract.
pub fn judge(baseline: &Figure, current: f64) -> Verdict {
    let b = baseline.value;
    // Positive `worse` means current is worse than baseline.
    let (worse, limit) = match (baseline.kind, baseline.better) {
        (Kind::Accuracy, Better::Lower) => (current - b, baseline.tolerance),
        (Kind::Accuracy, Better::Higher) => (b - current, baseline.tolerance),
        (Kind::Cost, better) => {
            // Ratio of worse to better, on the figure's noise floor (and on a
            // tiny one so that 0-cost figures cannot divide by zero).
            let floor = baseline.floor.max(1e-12);
            let r = (current.max(floor) / b.max(floor)).ln();
            let r = if better == Better::Lower { r } else { -r };
            (r, baseline.tolerance.max(1.0).ln())
        }
    };
    if worse > limit {
        Verdict::Regressed
    } else if -worse > limit {
        Verdict::Improved
    } else {
        Verdict::Ok
    }
}

/// Whether `b` and `c` were measured over the same cases: by their
/// [`Figure::over`] when both files record it, else only within one profile
/// (an older file, or a `check` summary, which has no profile).
pub fn comparable(b: &Figure, c: &Figure, same_profile: bool) -> bool {
    match (&b.over, &c.over) {
        (Some(x), Some(y)) => x == y,
        _ => same_profile,
    }
}

/// How [`compare`] treats the figures.
#[derive(Debug, Clone, Copy, Default)]
pub struct Gates {
    /// Wall-clock figures gate too (`--timings`).
    pub timings: bool,
    /// A gated baseline figure absent from a current run of the same
    /// profile is listed, not a regression (`--allow-missing`).
    pub allow_missing: bool,
}

/// Compares the figures both files have (see the module doc). Within one
/// profile a gated baseline figure the current run lacks is a regression
/// (a refactor that drops a measurement must say so), unless
/// `gates.allow_missing`. An error only when the two files share no figure
/// at all (comparing nothing would pass vacuously).
pub fn compare(
    baseline: &[Figure],
    current: &[Figure],
    current_path: &Path,
    gates: Gates,
    profiles: (Option<String>, Option<String>),
) -> Result<Outcome, CliError> {
    let by_name: BTreeMap<&str, &Figure> = current.iter().map(|f| (f.name.as_str(), f)).collect();
    let base_names: std::collections::BTreeSet<&str> =
        baseline.iter().map(|f| f.name.as_str()).collect();
    let same_profile = profiles.0 == profiles.1;
    let gates_kind = |f: &Figure| gates.timings || !is_wall_clock(f);
    let mut out = Outcome {
        rows: Vec::new(),
        only_baseline: Vec::new(),
        only_current: current
            .iter()
            .filter(|f| !base_names.contains(f.name.as_str()))
            .map(|f| f.name.clone())
            .collect(),
        changed: Vec::new(),
        incomparable: Vec::new(),
        missing: Vec::new(),
        profiles,
    };
    for b in baseline {
        match by_name.get(b.name.as_str()) {
            None if same_profile && !gates.allow_missing && gates_kind(b) => {
                out.missing.push(b.name.clone())
            }
            None => out.only_baseline.push(b.name.clone()),
            Some(c) if (c.kind, c.better, &c.unit) != (b.kind, b.better, &b.unit) => {
                out.changed.push(b.name.clone())
            }
            Some(c) => {
                let comparable = comparable(b, c, same_profile);
                if !comparable {
                    out.incomparable.push(b.name.clone());
                }
                out.rows.push(Comparison {
                    baseline: b.clone(),
                    current: c.value,
                    verdict: judge(b, c.value),
                    gated: comparable && gates_kind(b),
                    comparable,
                })
            }
        }
    }
    if out.rows.is_empty() {
        return Err(CliError::Input {
            path: current_path.to_path_buf(),
            why: format!(
                "no figure in common with the baseline ({} baseline figures, {} current)",
                baseline.len(),
                current.len()
            ),
        });
    }
    Ok(out)
}

/// The compare charts' ratios are drawn within `[1/RATIO_EDGE, RATIO_EDGE]`.
const RATIO_EDGE: f64 = 1e6;

fn study(name: &str) -> &str {
    name.split('.').next().unwrap_or(name)
}

/// Per study, current ÷ baseline for each figure (log scale) against its
/// global number `#` in the table, with each regressed figure drawn as its
/// own highlighted series named after it (so it is named in the legend,
/// which sits below the plot and never covers a point).
fn charts(rows: &[Comparison]) -> Vec<Chart> {
    let mut by_study: BTreeMap<&str, Vec<(usize, &Comparison)>> = BTreeMap::new();
    for (i, r) in rows.iter().enumerate() {
        by_study
            .entry(study(&r.baseline.name))
            .or_default()
            .push((i + 1, r));
    }
    by_study
        .into_iter()
        .filter_map(|(study, rs)| {
            // A zero on one side (a count of failures going from 0 to 1)
            // is drawn at the edge of the range, not at 1e300.
            let ratio = |r: &Comparison| {
                let (b, c) = (
                    r.baseline.value.abs().max(1e-300),
                    r.current.abs().max(1e-300),
                );
                (c / b).clamp(1.0 / RATIO_EDGE, RATIO_EDGE)
            };
            let pts = |want: Verdict, gated: bool| -> Vec<(f64, f64)> {
                rs.iter()
                    .filter(|(_, r)| r.verdict == want && (want != Verdict::Regressed || r.gated == gated))
                    .map(|(i, r)| (*i as f64, ratio(r)))
                    .collect()
            };
            let mut series: Vec<Series> = [
                ("within tolerance", pts(Verdict::Ok, true)),
                ("improved", pts(Verdict::Improved, true)),
                ("slower, timing not gated", pts(Verdict::Regressed, false)),
            ]
            .into_iter()
            .map(|(label, p)| Series::points(label, p))
            .collect();
            series.extend(
                rs.iter()
                    .filter(|(_, r)| r.gated && r.verdict == Verdict::Regressed)
                    .map(|(i, r)| {
                        Series::points(
                            format!("REGRESSED #{i} {}", r.baseline.name),
                            vec![(*i as f64, ratio(r))],
                        )
                        .with_color(crate::chart::RED)
                    }),
            );
            series.retain(|s| !s.points.is_empty());
            (!series.is_empty()).then(|| Chart {
                id: format!("compare_{}", crate::output::safe_stem(study)),
                title: format!("{study}: current ÷ baseline per figure"),
                x_label: "figure # (see table)".into(),
                y_label: "current / baseline".into(),
                x_log: false,
                y_log: true,
                series,
                caption: format!(
                    "Study {study}: each figure's current value over its baseline value, by its # in the table \
                     (a ratio beyond {RATIO_EDGE:e} either way, such as a zero on one side, drawn at that edge)."
                ),
            })
        })
        .collect()
}

/// The verdict word of a row, as the table and `compare.json` say it.
fn verdict_word(r: &Comparison) -> &'static str {
    match (r.verdict, r.gated) {
        (Verdict::Ok, _) => "ok",
        (Verdict::Improved, _) => "improved",
        (Verdict::Regressed, true) => "regressed",
        (_, false) if !r.comparable => "not gated: measured over other cases",
        (Verdict::Regressed, false) => "slower (timing, not gated; --timings gates it)",
    }
}

/// A table of `(#, row)`: each figure's baseline, current value, change,
/// tolerance and verdict (in colour).
fn table(rows: &[(usize, &Comparison)]) -> String {
    let mut s = String::from(
        "<div class=\"scroll\"><table><tr><th>#</th><th>figure</th><th>kind</th><th>unit</th><th>baseline</th>\
         <th>current</th><th>delta</th><th>tolerance</th><th>verdict</th></tr>\n",
    );
    for (i, r) in rows {
        let b = &r.baseline;
        let word = verdict_word(r);
        let class = match (r.verdict, r.gated) {
            (Verdict::Improved, _) => "improved",
            (Verdict::Regressed, true) => "regressed",
            _ => "",
        };
        let tol = match b.kind {
            Kind::Accuracy => format!("± {}", num(b.tolerance)),
            Kind::Cost => format!("× {}", num(b.tolerance)),
        };
        s.push_str(&format!(
            "<tr class=\"{class}\"><td>{i}</td><td class=\"name\">{}</td><td>{:?}</td><td>{}</td>\
             <td>{}</td><td>{}</td><td>{}</td><td>{tol}</td><td>{}</td></tr>\n",
            escape(&b.name),
            b.kind,
            escape(&b.unit),
            num(b.value),
            num(r.current),
            num(r.current - b.value),
            verdict(word),
        ));
    }
    s.push_str("</table></div>\n");
    s
}

/// The figures that moved beyond their tolerance, numbered as in the full
/// table: gated regressions first, then improvements, then the timings
/// that got slower without gating.
fn moved(rows: &[Comparison]) -> Vec<(usize, &Comparison)> {
    let rank = |r: &Comparison| match (r.verdict, r.gated) {
        (Verdict::Regressed, true) => Some(0),
        (Verdict::Improved, _) => Some(1),
        (Verdict::Regressed, false) => Some(2),
        (Verdict::Ok, _) => None,
    };
    let mut m: Vec<(u8, usize, &Comparison)> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| Some((rank(r)?, i + 1, r)))
        .collect();
    m.sort_by_key(|(rank, i, _)| (*rank, *i));
    m.into_iter().map(|(_, i, r)| (i, r)).collect()
}

/// `compare.json`: everything the page shows, for a machine (the action's
/// step summary reads it).
fn compare_json(outcome: &Outcome, inputs: (&Path, &Path)) -> serde_json::Value {
    let rows: Vec<serde_json::Value> = outcome
        .rows
        .iter()
        .map(|r| {
            serde_json::json!({
                "name": r.baseline.name,
                "kind": r.baseline.kind,
                "unit": r.baseline.unit,
                "better": r.baseline.better,
                "tolerance": r.baseline.tolerance,
                "baseline": r.baseline.value,
                "current": r.current,
                "verdict": verdict_word(r),
                "gated": r.gated,
            })
        })
        .collect();
    let names = |v: &[&Comparison]| {
        v.iter()
            .map(|r| r.baseline.name.clone())
            .collect::<Vec<_>>()
    };
    let improved: Vec<&Comparison> = outcome
        .rows
        .iter()
        .filter(|r| r.verdict == Verdict::Improved)
        .collect();
    serde_json::json!({
        "baseline": inputs.0.display().to_string(),
        "current": inputs.1.display().to_string(),
        "failed": outcome.failed(),
        "regressed": names(&outcome.regressed()),
        "missing": outcome.missing,
        "improved": names(&improved),
        "only_baseline": outcome.only_baseline,
        "only_current": outcome.only_current,
        "changed": outcome.changed,
        "incomparable": outcome.incomparable,
        "profiles": [outcome.profiles.0, outcome.profiles.1],
        "rows": rows,
    })
}

/// A titled list of figure names (nothing when empty).
fn name_list(title: &str, names: &[String]) -> String {
    if names.is_empty() {
        return String::new();
    }
    let items: String = names
        .iter()
        .map(|n| format!("<li><code>{}</code></li>", escape(n)))
        .collect();
    format!(
        "<details><summary>{} ({})</summary><ul>{items}</ul></details>\n",
        escape(title),
        names.len()
    )
}

/// Writes the compare page into a folder staged for `dir` and returns it
/// uncommitted with the gated figures that regressed: the caller commits it
/// ([`crate::output::StagedDir::commit`]) once its own output has been
/// written, so a failure there (stdout on a full disk) leaves no new folder.
pub fn write_compare(
    dir: &Path,
    outcome: &Outcome,
    inputs: (&Path, &Path),
) -> Result<(crate::output::StagedDir, Vec<String>), CliError> {
    let staged = crate::output::StagedDir::new(dir)?;
    let dir = staged.path();
    let rows = &outcome.rows;
    let regressed: Vec<String> = outcome
        .regressed()
        .iter()
        .map(|r| r.baseline.name.clone())
        .collect();
    let mut body = String::new();
    for chart in charts(rows) {
        let (figure, svg) = crate::page::figure(&chart)?;
        let file = dir.join(format!("{}.svg", chart.id));
        if file.exists() {
            // Two study names that differ only in characters made safe.
            return Err(CliError::Chart(
                chart.title.clone(),
                "its file name collides with another study's after sanitising".into(),
            ));
        }
        crate::output::write_atomic(&file, svg.as_bytes())?;
        body.push_str(&figure);
    }
    let mut headline = if regressed.is_empty() {
        "<p class=\"okay\">No gated figure regressed beyond its tolerance.</p>".to_string()
    } else {
        format!(
            "<p class=\"regressed\">{} figure(s) regressed: {}</p>",
            regressed.len(),
            escape(&regressed.join(", "))
        )
    };
    if !outcome.missing.is_empty() {
        headline.push_str(&format!(
            "<p class=\"regressed\">{} gated figure(s) missing from the current run \
             (same profile; --allow-missing accepts this): {}</p>",
            outcome.missing.len(),
            escape(&outcome.missing.join(", "))
        ));
    }
    if let Some(note) = outcome.profile_note() {
        headline.push_str(&format!("<p class=\"note\">{}</p>", escape(&note)));
    }
    let lists = name_list(
        "Only in the baseline (not compared)",
        &outcome.only_baseline,
    ) + &name_list(
        "Only in the current run (not compared)",
        &outcome.only_current,
    ) + &name_list(
        "Kind, unit or direction changed (not compared)",
        &outcome.changed,
    ) + &name_list(
        "Measured over other cases (shown, not gated)",
        &outcome.incomparable,
    );
    let moved = moved(rows);
    let moved_html = if moved.is_empty() {
        "<h2>Figures that moved</h2><p>None moved beyond its tolerance.</p>\n".to_string()
    } else {
        format!(
            "<h2>Figures that moved ({})</h2>\n{}",
            moved.len(),
            table(&moved)
        )
    };
    let all: Vec<(usize, &Comparison)> = rows.iter().enumerate().map(|(i, r)| (i + 1, r)).collect();
    let json = serde_json::to_string_pretty(&compare_json(outcome, inputs))
        .map_err(CliError::numerical)?;
    crate::output::write_atomic(&dir.join("compare.json"), json.as_bytes())?;
    let page = crate::page::page(
        "splinelab regression compare",
        &format!(
            "<p>Baseline: <code>{}</code><br>Current: <code>{}</code><br>Compared: {} figures \
             (wall-clock timings {}).</p>{headline}{moved_html}{lists}<h2>Each study: current ÷ baseline</h2>\n\
             {body}<h2>Every figure</h2>\n{}{}{}",
            escape(&inputs.0.display().to_string()),
            escape(&inputs.1.display().to_string()),
            rows.len(),
            if rows.iter().all(|r| r.gated) {
                "gated"
            } else {
                "shown, not gated"
            },
            table(&all),
            crate::page::machine_readable(&[(
                "compare.json",
                "every compared figure with its verdict"
            )]),
            super::provenance::provenance_html(&super::provenance::run_provenance()),
        ),
    );
    crate::output::write_atomic(&dir.join("index.html"), page.as_bytes())?;
    Ok((staged, regressed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_follow_kind_direction_and_tolerance() {
        let err = Figure::error("s.e", 1e-15, "relative error", 1e-15);
        assert_eq!(judge(&err, 1.5e-15), Verdict::Ok);
        assert_eq!(judge(&err, 3e-15), Verdict::Regressed);
        let digits = Figure::digits("s.d", 10.0, "digits", 0.5);
        assert_eq!(judge(&digits, 9.6), Verdict::Ok);
        assert_eq!(judge(&digits, 9.4), Verdict::Regressed);
        assert_eq!(judge(&digits, 11.0), Verdict::Improved);
        let time = Figure::cost("s.t", 2.0, "s", 4.0);
        assert_eq!(judge(&time, 7.9), Verdict::Ok);
        assert_eq!(judge(&time, 8.1), Verdict::Regressed);
        assert_eq!(judge(&time, 0.4), Verdict::Improved);
        let tiny = Figure::cost("s.t", 0.01, "s", 4.0).with_floor(0.5);
        assert_eq!(judge(&tiny, 0.3), Verdict::Ok);
        assert_eq!(judge(&tiny, 2.1), Verdict::Regressed);
    }

    #[test]
    fn profiles_are_noted_only_when_they_differ() {
        let figs = [Figure::error("s.e", 1.0, "ulps", 0.5)];
        let note = |a: Option<&str>, b: Option<&str>| {
            let p = (a.map(str::to_string), b.map(str::to_string));
            compare(&figs, &figs, Path::new("c"), Gates::default(), p)
                .unwrap()
                .profile_note()
        };
        assert_eq!(note(None, None), None);
        assert_eq!(note(Some("quick"), Some("quick")), None);
        assert!(note(None, Some("full")).unwrap().contains("not recorded"));
        assert!(note(Some("quick"), Some("full")).unwrap().contains("full"));
    }
}
