//! Where a report comes from: the provenance block (version, commit, date,
//! toolchain, machine, profile, the regenerating command) and the full
//! references of the five source papers.

use crate::html::escape;
use serde_json::{Value, json};
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// The first line a command prints, or `unknown` when it cannot run.
fn first_line(program: &str, args: &[&str]) -> String {
    Command::new(program)
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.lines().next().map(str::to_string))
        .unwrap_or_else(|| "unknown".into())
}

/// The CPU model from `/proc/cpuinfo` (Linux), or `unknown`.
fn cpu_model() -> String {
    std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into())
}

/// The current UTC time as `YYYY-MM-DD hh:mm UTC` (days to civil date by
/// Howard Hinnant's algorithm; no date library needed for one line).
fn utc_now() -> String {
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_secs() as i64)
        .unwrap_or(0);
    let (days, rem) = (secs.div_euclid(86_400), secs.rem_euclid(86_400));
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02} UTC",
        rem / 3600,
        rem % 3600 / 60
    )
}

/// Where any splinelab page comes from: the version, the commit of the
/// working directory's repository, the date, the machine and the command
/// line of this process (a check's page, the compare page, the pytest
/// plugin's session page; the report adds its own fields, [`provenance`]).
pub fn run_provenance() -> Value {
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    // args_os: a path that is not UTF-8 (`--out out\xFF`) is shown, not a panic.
    let command = std::env::args_os()
        .map(|a| a.to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join(" ");
    json!({
        "version": env!("CARGO_PKG_VERSION"),
        "git_commit": first_line("git", &["rev-parse", "--short=12", "HEAD"]),
        "date": utc_now(),
        "cpu": cpu_model(),
        "threads": threads,
        "command": command,
    })
}

/// The provenance of this report, as `summary.json` records it:
/// [`run_provenance`] with the toolchain, the profile and the command that
/// regenerates it.
pub fn provenance(quick: bool) -> Value {
    let mut p = run_provenance();
    p["rustc"] = json!(first_line("rustc", &["--version"]));
    p["profile"] = json!(if quick { "quick" } else { "full" });
    p["regenerate"] = json!(if quick {
        "scripts/report.sh --quick"
    } else {
        "scripts/report.sh"
    });
    p
}

/// The provenance block of a page: a row for each field `p` has.
pub fn provenance_html(p: &Value) -> String {
    let text = |k: &str| p[k].as_str().map(escape);
    let rows: String = [
        ("splinelab", text("version")),
        ("git commit", text("git_commit")),
        ("date", text("date")),
        ("rustc (on PATH)", text("rustc")),
        (
            "CPU",
            text("cpu").map(|c| format!("{c} ({} threads)", p["threads"])),
        ),
        ("profile", text("profile")),
        (
            "this run",
            text("command").map(|c| format!("<code>{c}</code>")),
        ),
        (
            "regenerate",
            text("regenerate").map(|c| format!("<code>{c}</code>")),
        ),
    ]
    .into_iter()
    .filter_map(|(k, v)| Some(format!("<tr><th>{}</th><td>{}</td></tr>", escape(k), v?)))
    .collect();
    format!(
        "<details class=\"meta\" open><summary>Provenance</summary><div class=\"scroll\">\
         <table class=\"prov\">{rows}</table></div></details>\n"
    )
}

/// The five source papers (seed numbers as in the sections), as fully as the
/// sources themselves state them.
pub const REFERENCES: [(&str, &str); 5] = [
    (
        "000",
        "Shigeru Kuriyama, Toshiyuki Kawai, Koichi Omura (Osaka University, Faculty of \
         Engineering, Dept. of Electronic Engineering): “Free Form Surface Modeling with Cardinal \
         Spline” (カーディナルスプラインを用いた自由曲面のモデリング手法).",
    ),
    (
        "001",
        "Akira Maeno, Minoru Okada, Jun-ichiro Toriwaki (Nagoya University; Chubu University): \
         “An intuitive deformation method for bicubic Bézier surfaces using the Bernstein inverse \
         mapping” (Bernstein 逆写像を用いた双三次ベジエ曲面の直観的変形手法), conference paper 5T-06.",
    ),
    (
        "002",
        "Kenshi Takayama: “Computer Graphics — Modeling (1)” (コンピュータグラフィクス論 \
         －モデリング (1)－), lecture notes, 16 April 2015.",
    ),
    (
        "003",
        "Tomomi Honda, Kenzo Mitamura, Yoshiro Iwai: “Local Modification Method for B-Spline \
         Curve by Insertion of Knots in the General CAD System” (はん用 CAD における節点挿入による \
         B スプライン曲線の局所修正法), received 29 February 2000.",
    ),
    (
        "004",
        "Kenjiro T. Miura, Naoki Sakiyama (Shizuoka University, Dept. of Mechanical \
         Engineering): “Interpolation of 3D point sequences by quaternion integral curves” \
         (四元数積分曲線による3D点列の内挿), conference paper 1AD-6.",
    ),
];

/// The references section of the page.
pub fn references_html() -> String {
    let items: String = REFERENCES
        .iter()
        .map(|(seed, text)| {
            format!(
                "<li value=\"{}\">[seed {seed}] {}</li>",
                seed.parse::<u32>().unwrap_or(0),
                escape(text)
            )
        })
        .collect();
    format!(
        "<section id=\"references\"><h2>References</h2><p>The five source papers the studies \
         implement, cited as each states itself (author names romanised; titles in English \
         with the original).</p><ol start=\"0\">{items}</ol></section>\n"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_date_has_the_calendar_shape() {
        let d = utc_now();
        assert_eq!(d.len(), "2026-11-23 13:16 UTC".len(), "{d}");
        assert!(d.starts_with("20") && d.ends_with(" UTC"));
    }
}
