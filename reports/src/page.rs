//! The page shell every splinelab HTML output shares: the report, a check's
//! page (`check --out`, `splinelab.check(out=...)`), the compare page and the
//! pytest plugin's session page. One stylesheet ([`STYLE`]), inlined so that
//! each page is one self-contained file an artifact viewer opens as it is;
//! verdicts coloured by class ([`verdict`]); the machine-readable files
//! linked in one line ([`machine_readable`]).

use crate::chart::Chart;
use crate::error::CliError;
use crate::html::escape;

/// The stylesheet of every page. Wide tables scroll inside their box
/// (`display:block; overflow-x:auto`) and charts scale down, so no page is
/// wider than the window.
pub const STYLE: &str = "body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;color:#222}\
table{border-collapse:collapse;margin:1em 0;font-size:90%}td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}\
caption{font-weight:bold;margin-bottom:.3em}figure{margin:1.5em 0}figcaption{font-size:90%;color:#444}\
nav li{margin:.2em 0}.meta{color:#666;font-size:90%}\
.scroll,table{overflow-x:auto;max-width:100%}table{display:block}td{white-space:nowrap}\
svg{max-width:100%;height:auto}.summary{background:#f4f7fb;border:1px solid #bcd;padding:.3em 1em;margin:1em 0}\
.summary code{word-break:break-all}.prov th{text-align:left}.prov td{text-align:left;white-space:normal;word-break:break-word}\
td.name{text-align:left;white-space:normal;overflow-wrap:anywhere;min-width:12em}code{word-break:break-word}\
.verdict{font-weight:bold;padding:0 .3em;border-radius:3px}\
.pass,.okay{background:#d7f0d7;color:#125212}.fail,.regressed{background:#f8cfcf;color:#8a1010}\
.improved{background:#d7f0d7}.note{background:#fff6cc}\
p.pass,p.fail,p.okay,p.regressed,p.note{padding:.3em .6em;font-weight:bold}";

/// A whole page: doctype, head (charset, viewport, title, [`STYLE`]) and
/// `body` (already HTML) under an `<h1>` of `title`.
pub fn page(title: &str, body: &str) -> String {
    let t = escape(title);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\"><title>{t}</title>\
         <style>{STYLE}</style></head><body>\n<h1>{t}</h1>\n{body}</body></html>\n"
    )
}

/// The colour class of a verdict word: `pass` for a good one (`pass`,
/// `ok`, `improved`), `fail` for a bad one (`fail`, `regressed`,
/// `missing`), none for anything else (`not gated`, ...).
pub fn verdict_class(word: &str) -> &'static str {
    match word.to_ascii_lowercase().as_str() {
        "pass" | "ok" | "improved" => "pass",
        "fail" | "regressed" | "missing" => "fail",
        _ => "",
    }
}

/// A verdict word in its colour (`<span class="verdict pass">pass</span>`).
pub fn verdict(word: &str) -> String {
    format!(
        "<span class=\"verdict {}\">{}</span>",
        verdict_class(word),
        escape(word)
    )
}

/// One paragraph linking the machine-readable files of a page: each
/// `(file, what it holds)`, relative to the page.
pub fn machine_readable(files: &[(&str, &str)]) -> String {
    let links: Vec<String> = files
        .iter()
        .map(|(file, what)| {
            format!(
                "<a href=\"{f}\"><code>{f}</code></a> ({})",
                escape(what),
                f = escape(file)
            )
        })
        .collect();
    format!(
        "<p class=\"meta\">Machine-readable: {}.</p>\n",
        links.join(", ")
    )
}

/// A chart drawn inline as a `<figure>` with its caption and a link to its
/// own file (`ID.svg`, which the caller writes): `(html, svg)`.
pub fn figure(chart: &Chart) -> Result<(String, String), CliError> {
    let svg = chart
        .render_svg()
        .map_err(|e| CliError::Chart(chart.id.clone(), e.to_string()))?;
    let html = format!(
        "<figure>{svg}<figcaption>{} (<a href=\"{}.svg\">SVG</a>)</figcaption></figure>\n",
        escape(&chart.caption),
        chart.id
    );
    Ok((html, svg))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdict_words_get_their_colour_class() {
        assert_eq!(verdict("pass"), "<span class=\"verdict pass\">pass</span>");
        assert_eq!(verdict_class("REGRESSED"), "fail");
        assert_eq!(verdict_class("not gated"), "");
    }

    #[test]
    fn the_page_carries_the_stylesheet_and_an_escaped_title() {
        let p = page("a <b>", "<p>x</p>");
        assert!(p.contains(STYLE) && p.contains("<h1>a &lt;b&gt;</h1>"));
    }
}
