//! The HTML report: one self-contained `index.html` assembled from the
//! sections of every study, each chart also written as its own `.svg`, and
//! `summary.json` with every section's headline figures.
//!
//! Adding a study means writing one `section` function (see
//! [`sections::SECTIONS`]) that returns a [`Section`].

pub mod bernstein_inverse;
pub mod bezier_eval;
pub mod check;
pub mod compare;
pub mod conditioning;
pub mod curves;
pub mod engine;
pub mod figure;
pub mod gridded;
pub mod projection;
pub mod provenance;
pub mod qi;
pub mod sections;
pub mod small_calls;
pub mod sspline;
pub mod update_cost;
pub mod update_cost_engine;

pub use figure::Figure;

use crate::chart::Chart;
use crate::error::CliError;
use crate::html::escape;
use crate::output::{StagedDir, write_atomic};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use serde_json::{Map, Value, json};
use std::path::Path;
use std::time::Instant;

/// How much work the report does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Profile {
    /// A short sweep for CI (the whole report in under 30 s).
    pub quick: bool,
}

impl Profile {
    /// `quick` or `full`, as `summary.json` records it.
    pub fn name(&self) -> &'static str {
        if self.quick { "quick" } else { "full" }
    }

    /// `quick` in the quick profile, `full` otherwise: the one place a
    /// section's parameters depend on the profile.
    pub fn pick<'a, T: ?Sized>(&self, quick: &'a T, full: &'a T) -> &'a T {
        if self.quick { quick } else { full }
    }

    /// The parameters `quick()` or `full()` of a study, by profile.
    pub fn params<P>(&self, quick: impl FnOnce() -> P, full: impl FnOnce() -> P) -> P {
        if self.quick { quick() } else { full() }
    }
}

/// What a study contributes to the report.
#[derive(Debug, Clone)]
pub struct Section {
    /// Stable identifier: the HTML anchor and the key in `summary.json`.
    pub id: &'static str,
    /// Heading.
    pub title: String,
    /// Body HTML (built with [`crate::html`]); charts are appended after it.
    pub html: String,
    /// Charts, drawn inline and written as `<id>.svg`.
    pub charts: Vec<Chart>,
    /// The section's data for `summary.json` (stored under its id).
    pub summary: Value,
    /// Headline figures watched by `splinelab compare` (names start with the
    /// section id); stored in `summary.json` under `figures`.
    pub figures: Vec<Figure>,
}

/// A section's error, with the section named.
pub type ReportError = CliError;

/// A function that runs one study and presents it.
pub type SectionFn = fn(&Profile) -> Result<Section, ReportError>;

fn render_section(s: &Section, seconds: f64, dir: &Path) -> Result<String, CliError> {
    let mut html = format!(
        "<section id=\"{}\">\n<h2>{}</h2>\n{}",
        s.id,
        escape(&s.title),
        s.html
    );
    for chart in &s.charts {
        let (figure, svg) = crate::page::figure(chart)?;
        write_atomic(&dir.join(format!("{}.svg", chart.id)), svg.as_bytes())?;
        html.push_str(&figure);
    }
    html.push_str(&format!(
        "<p class=\"meta\">Section computed in {seconds:.2} s.</p>\n</section>\n"
    ));
    Ok(html)
}

/// Noise band for wall-clock figures: CI machines are shared and noisy, so a
/// section must be 4× slower than the baseline before it counts as a regression.
pub const TIME_BAND: f64 = 4.0;

/// Section timings below half a second are noise, not signal.
pub const TIME_FLOOR: f64 = 0.5;

/// A figure must be finite and named after its section.
fn check_figures(section: &str, figures: &[Figure]) -> Result<(), CliError> {
    for f in figures {
        if !f.value.is_finite() || !f.name.starts_with(&format!("{section}.")) {
            return Err(CliError::Numerical(format!(
                "section {section}: figure '{}' is not finite or not named '{section}.…' ({})",
                f.name, f.value
            )));
        }
    }
    Ok(())
}

/// A progress bar over the sections on stderr: drawn only when stderr is a
/// terminal (indicatif hides it otherwise, e.g. in CI) and not `quiet`.
fn progress(len: usize, quiet: bool) -> ProgressBar {
    let target = if quiet {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let bar = ProgressBar::with_draw_target(Some(len as u64), target);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:30} {pos}/{len} sections  {msg} ({elapsed})")
    {
        bar.set_style(style);
    }
    bar
}

/// The committed baseline the summary box compares with, when the report
/// runs from the repository root (as `scripts/report.sh` does).
pub const BASELINE: &str = "reports/baseline/summary.json";

/// The box at the top of the page: how many figures, what the committed
/// baseline comparison says (when it is there), and each section's headline
/// figure (its first), linked to the section.
fn summary_box(
    figures: &[Figure],
    headlines: &[(&str, String, Option<Figure>)],
    profile: &Profile,
) -> String {
    let verdict = baseline_verdict(figures, profile);
    let rows: String = headlines
        .iter()
        .map(|(id, title, f)| {
            let figure = f.as_ref().map_or("—".to_string(), |f| {
                format!(
                    "<code>{}</code> = {} {}",
                    escape(f.name.trim_start_matches(&format!("{id}."))),
                    crate::html::num(f.value),
                    escape(&f.unit)
                )
            });
            format!("<li><a href=\"#{id}\">{}</a>: {figure}</li>", escape(title))
        })
        .collect();
    // A list, not a table: it wraps on a phone where a two-column table
    // would push the figures off screen.
    format!(
        "<div class=\"summary\"><p><b>{} figures</b> in {} sections ({} profile). {}</p>\
         <p>Headline figure of each section:</p><ul>{rows}</ul></div>\n",
        figures.len(),
        headlines.len(),
        profile.name(),
        escape(&verdict)
    )
}

/// One sentence on this run against [`BASELINE`]: how many gated figures
/// regressed or went missing, or why it was not compared.
fn baseline_verdict(figures: &[Figure], profile: &Profile) -> String {
    let path = Path::new(BASELINE);
    if !path.is_file() {
        return format!("No baseline at {BASELINE} (run from the repository root to compare).");
    }
    let outcome = compare::read_figures(path).and_then(|base| {
        let profiles = (
            compare::read_profile(path)?,
            Some(profile.name().to_string()),
        );
        compare::compare(&base, figures, path, compare::Gates::default(), profiles)
    });
    match outcome {
        Err(e) => format!("Baseline not compared: {e}."),
        Ok(o) => {
            let gated = o.rows.iter().filter(|r| r.gated).count();
            let regressed: Vec<String> = o
                .regressed()
                .iter()
                .map(|r| r.baseline.name.clone())
                .collect();
            let mut s = format!(
                "Against the committed baseline ({} profile): {} gated figures compared, {} regressed{}",
                o.profiles.0.as_deref().unwrap_or("profile not recorded"),
                gated,
                regressed.len(),
                if regressed.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", regressed.join(", "))
                }
            );
            if !o.missing.is_empty() {
                s.push_str(&format!(
                    ", {} missing ({})",
                    o.missing.len(),
                    o.missing.join(", ")
                ));
            }
            s.push_str(&format!(
                "; {} not comparable across profiles.",
                o.incomparable.len()
            ));
            s
        }
    }
}

/// Runs every section, in page order, with its wall-clock seconds: those
/// that time nothing side by side on the pool (the report's first run is
/// what a new user waits for, and each of them is one thread), then the
/// timed ones alone ([`sections::Entry::timed`]).
fn run_sections(profile: &Profile, bar: &ProgressBar) -> Result<Vec<(Section, f64)>, ReportError> {
    let run = |entry: &sections::Entry| -> Result<(Section, f64), ReportError> {
        let t = Instant::now();
        let section = (entry.run)(profile)?;
        bar.set_message(section.title.clone());
        bar.inc(1);
        Ok((section, t.elapsed().as_secs_f64()))
    };
    let untimed: Vec<_> = sections::SECTIONS
        .par_iter()
        .map(|e| (!e.timed).then(|| run(e)).transpose())
        .collect::<Result<_, _>>()?;
    untimed
        .into_iter()
        .zip(sections::SECTIONS)
        .map(|(done, e)| done.map_or_else(|| run(e), Ok))
        .collect()
}

/// Runs every section and writes `index.html`, `summary.json` and the
/// charts into `dir`, replacing it whole at the end ([`StagedDir`]: an
/// interrupted or failed run leaves the old folder as it was). Returns the
/// path of `index.html`.
pub fn write_report(
    dir: &Path,
    profile: &Profile,
    quiet: bool,
) -> Result<std::path::PathBuf, CliError> {
    let staged = StagedDir::new(dir)?;
    let (target, dir) = (dir, staged.path());
    let start = Instant::now();
    let mut body = String::new();
    let mut toc = String::new();
    let mut summary = Map::new();
    let mut timings = Map::new();
    let mut figures = Vec::new();
    let mut headlines = Vec::new();
    let bar = progress(sections::SECTIONS.len(), quiet);
    let profile_cases = format!("{} profile's cases", profile.name());
    for (entry, run) in sections::SECTIONS.iter().zip(run_sections(profile, &bar)?) {
        let (section, seconds) = run;
        body.push_str(&render_section(&section, seconds, dir)?);
        toc.push_str(&format!(
            "<li><a href=\"#{}\">{}</a></li>",
            section.id,
            escape(&section.title)
        ));
        summary.insert(section.id.to_string(), section.summary);
        check_figures(section.id, &section.figures)?;
        headlines.push((
            section.id,
            section.title.clone(),
            section.figures.first().cloned(),
        ));
        let over = match entry.cases {
            sections::Cases::Fixed => "fixed cases",
            sections::Cases::ByProfile => &profile_cases,
        };
        figures.extend(section.figures.into_iter().map(|f| f.measured_over(over)));
        let time = Figure::cost(
            format!("report.{}.seconds", section.id),
            seconds,
            "s",
            TIME_BAND,
        );
        figures.push(time.with_floor(TIME_FLOOR).measured_over(&profile_cases));
        timings.insert(section.id.to_string(), json!(seconds));
    }
    bar.finish_and_clear();
    let total = start.elapsed().as_secs_f64();
    summary.insert("profile".into(), json!(profile.name()));
    let prov = provenance::provenance(profile.quick);
    summary.insert("provenance".into(), prov.clone());
    summary.insert(
        "report".into(),
        json!({"profile": profile.name(), "seconds": total, "section_seconds": timings}),
    );
    let page = crate::page::page(
        "splinelab report",
        &format!(
            "<p class=\"meta\">Profile: {}; computed in {total:.1} s. Machine-readable figures: \
             <a href=\"summary.json\">summary.json</a>.</p>\n{}{}<nav><ul>{toc}<li><a href=\"#references\">\
             References</a></li></ul></nav>\n{body}{}",
            profile.name(),
            summary_box(&figures, &headlines, profile),
            provenance::provenance_html(&prov),
            provenance::references_html()
        ),
    );
    summary.insert(
        "figures".into(),
        serde_json::to_value(&figures).map_err(CliError::numerical)?,
    );
    let summary =
        serde_json::to_string_pretty(&Value::Object(summary)).map_err(CliError::numerical)?;
    write_atomic(&dir.join("summary.json"), summary.as_bytes())?;
    write_atomic(&dir.join("index.html"), page.as_bytes())?;
    staged.commit()?;
    Ok(target.join("index.html"))
}
