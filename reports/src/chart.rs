//! SVG line and scatter charts (plotters, SVG backend, no system fonts).
//!
//! Log axes are drawn by plotting `log10` of the data on a linear axis and
//! labelling ticks `1e k`: one code path for every axis combination. Charts
//! refuse non-finite points (and non-positive ones on a log axis) with an
//! error naming the series, so a NaN can never slip silently into a picture.

use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// A linear f64 axis with the tick positions given (the chart's own
/// integer ticks, or plotters' defaults); labels come from the chart's
/// formatters.
struct TickedAxis {
    inner: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Ranged for TickedAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            vec![]
        } else {
            self.ticks.clone()
        }
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A polyline through the points.
    Line,
    /// Markers only (scatter).
    Points,
    /// A polyline with markers.
    LinePoints,
    /// Shaded vertical bands: each point is an x interval `(start, end)`
    /// drawn across the whole plot height (a zone, not data: it does not
    /// set the y range).
    Band,
}

/// One named series of `(x, y)` points.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label.
    pub name: String,
    /// The data.
    pub points: Vec<(f64, f64)>,
    /// How to draw it.
    pub style: Style,
    /// Its colour (`0xRRGGBB`); `None`: the palette's colour for its place.
    pub color: Option<u32>,
}

/// The colour of a failure or a regression.
pub const RED: u32 = 0xd62728;
/// The colour of a pass.
pub const GREEN: u32 = 0x2ca02c;
/// The colour of a limit drawn for reference.
pub const GREY: u32 = 0x7f7f7f;

impl Series {
    /// The same series in a colour of its own (a verdict's, [`RED`],
    /// [`GREEN`]), whatever its place among the series.
    pub fn with_color(mut self, rgb: u32) -> Self {
        self.color = Some(rgb);
        self
    }
    /// A series drawn as a line.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::Line,
            color: None,
        }
    }
    /// A series drawn as markers.
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::Points,
            color: None,
        }
    }
    /// Shaded x intervals `(start, end)` (see [`Style::Band`]).
    pub fn band(name: impl Into<String>, intervals: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points: intervals,
            style: Style::Band,
            color: None,
        }
    }
    /// A series drawn as a line with markers.
    pub fn line_points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            style: Style::LinePoints,
            color: None,
        }
    }
}

/// A chart: title, axis labels, log flags and its series.
#[derive(Debug, Clone)]
pub struct Chart {
    /// File stem of the SVG (`cond_vs_degree` → `cond_vs_degree.svg`).
    pub id: String,
    /// Title drawn above the plot.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// Logarithmic x axis.
    pub x_log: bool,
    /// Logarithmic y axis.
    pub y_log: bool,
    /// The data.
    pub series: Vec<Series>,
    /// One sentence saying what the reader should see.
    pub caption: String,
}

/// A chart with a linear x axis, the usual shape of a report figure: the
/// one constructor the report sections share.
pub fn line_chart(
    id: &str,
    title: &str,
    x_label: &str,
    y_label: &str,
    y_log: bool,
    series: Vec<Series>,
    caption: &str,
) -> Chart {
    Chart {
        id: id.into(),
        title: title.into(),
        x_label: x_label.into(),
        y_label: y_label.into(),
        x_log: false,
        y_log,
        series,
        caption: caption.into(),
    }
}

impl Chart {
    /// The same chart with a logarithmic x axis.
    pub fn with_log_x(mut self) -> Self {
        self.x_log = true;
        self
    }
}

/// `[x, y]` pairs as chart points.
pub fn xy(points: &[[f64; 2]]) -> Vec<(f64, f64)> {
    points.iter().map(|p| (p[0], p[1])).collect()
}

/// Why a chart could not be drawn.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChartError {
    /// A point is NaN or infinite.
    #[error("series '{0}' has a non-finite point")]
    NonFinite(String),
    /// A point is ≤ 0 on a logarithmic axis.
    #[error("series '{0}' has a non-positive value on a log axis")]
    NonPositive(String),
    /// No series has any point.
    #[error("no data")]
    Empty,
    /// plotters failed.
    #[error("drawing failed: {0}")]
    Draw(String),
}

// Twelve distinguishable colours (matplotlib's tab10, then black and brown),
// so that the sweeps with ten or more series (orders 2..24) do not reuse one.
const PALETTE: [u32; 12] = [
    0x1f77b4, 0xff7f0e, 0x2ca02c, 0xd62728, 0x9467bd, 0x8c564b, 0xe377c2, 0x7f7f7f, 0xbcbd22,
    0x17becf, 0x000000, 0x783c00,
];

/// `0xRRGGBB` as a plotters colour.
fn rgb(c: u32) -> RGBColor {
    let [_, r, g, b] = c.to_be_bytes();
    RGBColor(r, g, b)
}

/// The `k`-th palette colour (cycling).
fn palette(k: usize) -> RGBColor {
    rgb(PALETTE[k % PALETTE.len()])
}

fn transform(v: f64, log: bool, name: &str) -> Result<f64, ChartError> {
    if !v.is_finite() {
        return Err(ChartError::NonFinite(name.to_string()));
    }
    if log {
        if v <= 0.0 {
            return Err(ChartError::NonPositive(name.to_string()));
        }
        Ok(v.log10())
    } else {
        Ok(v)
    }
}

fn padded(lo: f64, hi: f64) -> (f64, f64) {
    let pad = if hi > lo {
        (hi - lo) * 0.05
    } else {
        lo.abs().max(1.0) * 0.05
    };
    (lo - pad, hi + pad)
}

fn tick_label(v: f64, log: bool) -> String {
    if log {
        // Short log ranges get ticks between the decades: label them by value.
        let k = v.round();
        if (v - k).abs() < 1e-9 {
            format!("1e{}", k as i64)
        } else {
            // Three significant digits: neighbouring ticks of a short
            // range (1.05, 1.10) stay distinct.
            format!("{:.2e}", 10f64.powf(v))
        }
    } else if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.1e}")
    } else {
        format!("{v:.3}")
            .trim_end_matches('0')
            .trim_end_matches('.')
            .to_string()
    }
}

/// Tick positions (in axis units: `log10` on a log axis) at whole numbers
/// for an axis whose data are all integers (degrees, orders, indices): a
/// 1-2-5 step on a linear axis, `1 2 3 4 5 6 8 10 15 20 …` thinned to at
/// most twelve on a log one.
fn integer_ticks(lo: f64, hi: f64, log: bool) -> Vec<f64> {
    if log {
        let (a, b) = (10f64.powf(lo), 10f64.powf(hi));
        let mut v: Vec<f64> = (0..12)
            .flat_map(|e| [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0].map(|m| m * 10f64.powi(e)))
            .filter(|x| *x >= a * (1.0 - 1e-9) && *x <= b * (1.0 + 1e-9))
            .collect();
        let keep = v.len().div_ceil(12).max(1);
        if keep > 1 {
            v = v.into_iter().step_by(keep).collect();
        }
        return v.into_iter().map(f64::log10).collect();
    }
    let span = (hi - lo).max(1.0);
    let step = [1.0, 2.0, 5.0]
        .iter()
        .flat_map(|m| (0..20).map(move |e| m * 10f64.powi(e)))
        .filter(|s| span / s <= 10.0)
        .fold(f64::INFINITY, f64::min);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// The label of an integer tick (the value, not its logarithm).
fn integer_label(v: f64, log: bool) -> String {
    let x = if log { 10f64.powf(v) } else { v };
    format!("{}", x.round() as i64)
}

/// A rate tick: `1.2 M/s` (SI prefixes k, M, G, T), the value read through
/// the log axis when there is one.
fn rate_label(v: f64, log: bool) -> String {
    let x = if log { 10f64.powf(v) } else { v };
    let (scale, prefix) = [(1e12, "T"), (1e9, "G"), (1e6, "M"), (1e3, "k")]
        .into_iter()
        .find(|(s, _)| x.abs() >= *s)
        .unwrap_or((1.0, ""));
    let m = x / scale;
    let digits = if m.abs() >= 100.0 {
        0
    } else if m.abs() >= 10.0 {
        1
    } else {
        2
    };
    let text = format!("{m:.digits$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    format!("{text} {prefix}/s")
}

impl Chart {
    /// Renders the chart as an SVG document (720 px wide: a 440 px plot and
    /// one 18 px legend row per series below it).
    pub fn render_svg(&self) -> Result<String, ChartError> {
        let mut data = Vec::with_capacity(self.series.len());
        for s in &self.series {
            let pts = s
                .points
                .iter()
                .map(|&(x, y)| {
                    let y_log = self.y_log && s.style != Style::Band;
                    let y_axis_log = if s.style == Style::Band {
                        self.x_log
                    } else {
                        y_log
                    };
                    Ok((
                        transform(x, self.x_log, &s.name)?,
                        transform(y, y_axis_log, &s.name)?,
                    ))
                })
                .collect::<Result<Vec<_>, ChartError>>()?;
            data.push(pts);
        }
        let all = || {
            data.iter()
                .zip(&self.series)
                .filter(|(_, s)| s.style != Style::Band)
                .flat_map(|(d, _)| d)
        };
        if all().next().is_none() {
            return Err(ChartError::Empty);
        }
        let fold = |f: fn(&(f64, f64)) -> f64| {
            all()
                .map(f)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                })
        };
        let (x0, x1) = padded(fold(|p| p.0).0, fold(|p| p.0).1);
        let integer_x = self
            .series
            .iter()
            .filter(|s| s.style != Style::Band)
            .flat_map(|s| &s.points)
            .all(|p| p.0.fract() == 0.0);
        let (y0, y1) = padded(fold(|p| p.1).0, fold(|p| p.1).1);
        let mut svg = String::new();
        let x_ticks = if integer_x {
            integer_ticks(x0, x1, self.x_log)
        } else {
            RangedCoordf64::from(x0..x1).key_points(10)
        };
        self.draw(&mut svg, &data, (x0..x1, y0..y1), (x_ticks, integer_x))
            .map_err(|e| ChartError::Draw(e.to_string()))?;
        Ok(svg)
    }

    fn draw(
        &self,
        svg: &mut String,
        data: &[Vec<(f64, f64)>],
        (xr, yr): (std::ops::Range<f64>, std::ops::Range<f64>),
        (x_ticks, integer_x): (Vec<f64>, bool),
    ) -> Result<(), Box<dyn std::error::Error + '_>> {
        let legend_h = LEGEND_PAD + LEGEND_ROW * self.series.len() as u32;
        let root = SVGBackend::with_string(svg, (720, PLOT_H + legend_h)).into_drawing_area();
        root.fill(&WHITE)?;
        let (plot, legend) = root.split_vertically(PLOT_H);
        let mut chart = ChartBuilder::on(&plot)
            .caption(&self.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(64)
            .build_cartesian_2d(
                TickedAxis {
                    inner: xr.into(),
                    ticks: x_ticks,
                },
                yr.clone(),
            )?;
        let (xl, yl) = (self.x_log, self.y_log);
        let rate = self.y_label.ends_with("per second");
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&|v| match integer_x {
                true => integer_label(*v, xl),
                false => tick_label(*v, xl),
            })
            .y_label_formatter(&|v| match rate {
                true => rate_label(*v, yl),
                false => tick_label(*v, yl),
            })
            .draw()?;
        for (k, (s, pts)) in self.series.iter().zip(data).enumerate() {
            let color = s.color.map_or_else(|| palette(k), rgb);
            if s.style == Style::Band {
                let shade = color.mix(0.15);
                chart.draw_series(
                    pts.iter().map(|&(a, b)| {
                        Rectangle::new([(a, yr.start), (b, yr.end)], shade.filled())
                    }),
                )?;
                let y = (LEGEND_PAD / 2 + LEGEND_ROW * k as u32 + LEGEND_ROW / 2) as i32;
                legend.draw(&Rectangle::new([(76, y - 6), (98, y + 6)], shade.filled()))?;
                legend.draw(&Text::new(
                    s.name.clone(),
                    (106, y - 7),
                    ("sans-serif", 14).into_font().color(&BLACK),
                ))?;
                continue;
            }
            if s.style != Style::Points {
                chart.draw_series(LineSeries::new(pts.iter().copied(), color.stroke_width(2)))?;
            }
            if s.style != Style::Line {
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            }
            // The legend sits below the plot area, one row per series, so
            // it can never cover a data point.
            let y = (LEGEND_PAD / 2 + LEGEND_ROW * k as u32 + LEGEND_ROW / 2) as i32;
            let x = 76;
            if s.style != Style::Points {
                legend.draw(&PathElement::new(
                    vec![(x, y), (x + 22, y)],
                    color.stroke_width(2),
                ))?;
            }
            if s.style != Style::Line {
                legend.draw(&Circle::new((x + 11, y), 3, color.filled()))?;
            }
            legend.draw(&Text::new(
                s.name.clone(),
                (x + 30, y - 7),
                ("sans-serif", 14).into_font().color(&BLACK),
            ))?;
        }
        root.present()?;
        Ok(())
    }
}

/// Height of the plot area (px); the legend rows are added below it.
const PLOT_H: u32 = 440;
/// Height of one legend row and the padding around the legend (px).
const LEGEND_ROW: u32 = 18;
const LEGEND_PAD: u32 = 8;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_between_decades_are_labelled_by_value() {
        assert_eq!(tick_label(8.0, true), "1e8");
        assert_eq!(tick_label(7.5, true), "3.16e7"); // 10^7.5 = 31 622 776.6
        // Short ranges: neighbouring ticks stay distinct.
        assert_ne!(tick_label(0.02, true), tick_label(0.04, true));
        assert_eq!(tick_label(-2.0, true), "1e-2");
    }

    #[test]
    fn integer_axes_and_rate_ticks() {
        // Degrees 2..24 on a linear axis: whole numbers, ≤ 11 ticks.
        assert_eq!(
            integer_ticks(0.9, 25.1, false),
            [5.0, 10.0, 15.0, 20.0, 25.0]
        );
        assert_eq!(integer_ticks(1.85, 5.15, false), [2.0, 3.0, 4.0, 5.0]);
        // Degrees 3..30 on a log axis: labels 3 4 5 6 8 10 20 30.
        let t = integer_ticks(3f64.log10(), 30f64.log10(), true);
        let labels: Vec<String> = t.iter().map(|v| integer_label(*v, true)).collect();
        assert_eq!(labels, ["3", "4", "5", "6", "8", "10", "20", "30"]);
        assert_eq!(rate_label(1.234e6, false), "1.23 M/s");
        assert_eq!(rate_label(6.0, true), "1 M/s");
        assert_eq!(rate_label(45_000.0, false), "45 k/s");
    }

    #[test]
    fn a_nan_point_is_refused_with_the_series_named() {
        let c = Chart {
            id: "t".into(),
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            x_log: false,
            y_log: true,
            series: vec![Series::line("bad", vec![(1.0, 1.0), (2.0, f64::NAN)])],
            caption: String::new(),
        };
        assert_eq!(c.render_svg(), Err(ChartError::NonFinite("bad".into())));
        let mut c2 = c.clone();
        c2.series = vec![Series::line("neg", vec![(1.0, -1.0)])];
        assert_eq!(c2.render_svg(), Err(ChartError::NonPositive("neg".into())));
        c2.series = vec![Series::points("ok", vec![(1.0, 10.0), (2.0, 1000.0)])];
        let svg = c2.render_svg().unwrap();
        assert!(svg.starts_with("<svg") && svg.contains("1e3"));
    }
}
