//! SVG heatmaps of 2-D arrays side by side (plotters, SVG backend, no
//! system fonts), one shared colour scale, NaN and ±inf in a colour of
//! their own: the picture for missing data, where [`crate::chart`] (which
//! refuses non-finite points) cannot go.
//!
//! The values are drawn in [`LEVELS`] colours, each row's runs of one
//! colour as one rectangle, grown down over the rows below that repeat the
//! run: a smooth 96×96 panel is about a thousand elements, not one per
//! cell.

use crate::chart::ChartError;
use crate::html::escape;
use plotters::prelude::*;

/// One array drawn as a panel.
#[derive(Debug, Clone)]
pub struct Panel {
    /// Drawn above the panel.
    pub title: String,
    /// Rows (drawn top to bottom) and columns.
    pub shape: [usize; 2],
    /// The values, C order (row after row).
    pub values: Vec<f64>,
}

/// Panels side by side under a title, with the colour scale below.
#[derive(Debug, Clone)]
pub struct Heatmap {
    /// Title drawn above the panels.
    pub title: String,
    /// The arrays.
    pub panels: Vec<Panel>,
}

/// Colours of the scale (more would not be told apart, and would cut the
/// runs into more rectangles).
pub const LEVELS: usize = 16;
/// Non-finite values: a red no level of the scale comes near.
const MISSING: RGBColor = RGBColor(0xe4, 0x1a, 0x1c);
/// The scale's stops (viridis at 0, ¼, ½, ¾, 1), interpolated linearly.
const STOPS: [u32; 5] = [0x440154, 0x3b528b, 0x21918c, 0x5ec962, 0xfde725];
const WIDTH: u32 = 720;
const TITLE_H: u32 = 34;
const PANEL_TITLE_H: u32 = 22;
const LEGEND_H: u32 = 56;
const GAP: u32 = 12;

/// The colour of level `k` of [`LEVELS`].
fn level_colour(k: usize) -> RGBColor {
    let t = k as f64 / (LEVELS - 1) as f64 * (STOPS.len() - 1) as f64;
    let i = (t.floor() as usize).min(STOPS.len() - 2);
    let f = t - i as f64;
    let [_, r0, g0, b0] = STOPS[i].to_be_bytes();
    let [_, r1, g1, b1] = STOPS[i + 1].to_be_bytes();
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    RGBColor(mix(r0, r1), mix(g0, g1), mix(b0, b1))
}

/// The level of `v` on the scale `[lo, hi]`; `None` for NaN and ±inf.
fn level(v: f64, lo: f64, hi: f64) -> Option<usize> {
    if !v.is_finite() {
        return None;
    }
    let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.5 };
    Some(((t * LEVELS as f64) as usize).min(LEVELS - 1))
}

impl Heatmap {
    /// The finite range over every panel (`[0, 1]` when nothing is finite).
    fn range(&self) -> (f64, f64) {
        let (lo, hi) = self
            .panels
            .iter()
            .flat_map(|p| &p.values)
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if lo <= hi { (lo, hi) } else { (0.0, 1.0) }
    }

    /// Renders the panels as an SVG document, 720 px wide.
    pub fn render_svg(&self) -> Result<String, ChartError> {
        if self.panels.is_empty() {
            return Err(ChartError::Empty);
        }
        if let Some(p) = self
            .panels
            .iter()
            .find(|p| p.values.len() != p.shape[0] * p.shape[1] || p.values.is_empty())
        {
            return Err(ChartError::Draw(format!(
                "panel '{}': {} values for shape {:?}",
                p.title,
                p.values.len(),
                p.shape
            )));
        }
        let n = self.panels.len() as u32;
        let side = (WIDTH - GAP * (n + 1)) / n;
        let height = TITLE_H + PANEL_TITLE_H + side + LEGEND_H;
        let mut svg = String::new();
        self.draw(&mut svg, side, height)
            .map_err(|e| ChartError::Draw(e.to_string()))?;
        Ok(svg)
    }

    fn draw(
        &self,
        svg: &mut String,
        side: u32,
        height: u32,
    ) -> Result<(), Box<dyn std::error::Error + '_>> {
        let root = SVGBackend::with_string(svg, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let font = |size| ("sans-serif", size).into_font().color(&BLACK);
        root.draw(&Text::new(self.title.clone(), (GAP as i32, 8), font(18)))?;
        let (lo, hi) = self.range();
        for (k, p) in self.panels.iter().enumerate() {
            let x0 = (GAP + k as u32 * (side + GAP)) as i32;
            let y0 = (TITLE_H + PANEL_TITLE_H) as i32;
            root.draw(&Text::new(p.title.clone(), (x0, y0 - 18), font(13)))?;
            draw_cells(&root, p, (x0, y0), side, (lo, hi))?;
        }
        let y = (TITLE_H + PANEL_TITLE_H + side + 14) as i32;
        draw_scale(&root, (GAP as i32, y), (lo, hi))?;
        root.present()?;
        Ok(())
    }
}

/// A run of one colour: columns `start..end` of rows `top..`, its level.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Run {
    start: usize,
    end: usize,
    level: Option<usize>,
    top: usize,
}

/// The runs of one colour in `row` (starting at row `top`).
fn runs(row: &[f64], top: usize, (lo, hi): (f64, f64)) -> Vec<Run> {
    let mut out = vec![];
    let mut start = 0;
    while start < row.len() {
        let l = level(row[start], lo, hi);
        let end = (start..row.len())
            .find(|&c| level(row[c], lo, hi) != l)
            .unwrap_or(row.len());
        out.push(Run {
            start,
            end,
            level: l,
            top,
        });
        start = end;
    }
    out
}

/// The rectangles of a panel, `(run, bottom row)`: each row's runs, a run
/// repeated (same columns and colour) in the rows below it grown over them.
fn rectangles(p: &Panel, range: (f64, f64)) -> Vec<(Run, usize)> {
    let [rows, cols] = p.shape;
    let (mut open, mut done): (Vec<Run>, Vec<(Run, usize)>) = (vec![], vec![]);
    for r in 0..rows {
        let next = runs(&p.values[r * cols..(r + 1) * cols], r, range);
        let same = |a: &Run, b: &Run| (a.start, a.end, a.level) == (b.start, b.end, b.level);
        let (kept, closed): (Vec<Run>, Vec<Run>) = open
            .into_iter()
            .partition(|o| next.iter().any(|n| same(o, n)));
        done.extend(closed.into_iter().map(|o| (o, r)));
        open = next
            .into_iter()
            .map(|n| kept.iter().find(|o| same(o, &n)).copied().unwrap_or(n))
            .collect();
    }
    done.extend(open.into_iter().map(|o| (o, rows)));
    done
}

/// One panel's cells in a `side`-pixel square at `at` (the longer axis
/// fills it), as [`rectangles`].
fn draw_cells<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    p: &Panel,
    at: (i32, i32),
    side: u32,
    range: (f64, f64),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let [rows, cols] = p.shape;
    let cell = f64::from(side) / rows.max(cols) as f64;
    let edge = |origin: i32, k: usize| origin + (k as f64 * cell).round() as i32;
    for (run, bottom) in rectangles(p, range) {
        let corners = [
            (edge(at.0, run.start), edge(at.1, run.top)),
            (edge(at.0, run.end), edge(at.1, bottom)),
        ];
        let colour = run.level.map_or(MISSING, level_colour);
        area.draw(&Rectangle::new(corners, colour.filled()))?;
    }
    let frame = [(at.0, at.1), (edge(at.0, cols), edge(at.1, rows))];
    area.draw(&Rectangle::new(frame, BLACK.stroke_width(1)))
}

/// The colour scale from `lo` to `hi` and the swatch of non-finite values.
fn draw_scale<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (x, y): (i32, i32),
    (lo, hi): (f64, f64),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let step = 320 / LEVELS as i32;
    for k in 0..LEVELS {
        let left = x + (k as i32) * step;
        area.draw(&Rectangle::new(
            [(left, y), (left + step, y + 14)],
            level_colour(k).filled(),
        ))?;
    }
    let font = ("sans-serif", 12).into_font().color(&BLACK);
    let right = x + LEVELS as i32 * step;
    area.draw(&Text::new(format!("{lo:.3}"), (x, y + 18), font.clone()))?;
    area.draw(&Text::new(
        format!("{hi:.3}"),
        (right - 34, y + 18),
        font.clone(),
    ))?;
    let swatch = right + 40;
    area.draw(&Rectangle::new(
        [(swatch, y), (swatch + 22, y + 14)],
        MISSING.filled(),
    ))?;
    area.draw(&Text::new("NaN (missing)", (swatch + 30, y), font))
}

/// A heatmap as an HTML figure: the SVG inline, then its caption.
pub fn figure_html(svg: &str, caption: &str) -> String {
    format!(
        "<figure>{svg}<figcaption>{}</figcaption></figure>\n",
        escape(caption)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_span_the_scale_and_missing_has_its_own_colour() {
        assert_eq!(level(0.0, 0.0, 1.0), Some(0));
        assert_eq!(level(1.0, 0.0, 1.0), Some(LEVELS - 1));
        assert_eq!(level(f64::NAN, 0.0, 1.0), None);
        assert_eq!(level(f64::NEG_INFINITY, 0.0, 1.0), None);
        assert_eq!(level_colour(0), RGBColor(0x44, 0x01, 0x54));
        assert_eq!(level_colour(LEVELS - 1), RGBColor(0xfd, 0xe7, 0x25));
        assert!((0..LEVELS).all(|k| level_colour(k) != MISSING));
    }

    /// Every cell is covered by exactly one rectangle of its own colour,
    /// and repeated runs are merged down the rows.
    #[test]
    fn rectangles_tile_the_panel_in_its_colours() {
        let (rows, cols) = (7, 9);
        let values: Vec<f64> = (0..rows * cols)
            .map(|k| match (k / cols, k % cols) {
                (r, c) if (2..5).contains(&r) && (3..6).contains(&c) => f64::NAN,
                (_, c) => (c / 3) as f64,
            })
            .collect();
        let p = Panel {
            title: "p".into(),
            shape: [rows, cols],
            values,
        };
        let rects = rectangles(&p, (0.0, 2.0));
        let mut covered = vec![0; rows * cols];
        for (run, bottom) in &rects {
            for r in run.top..*bottom {
                for c in run.start..run.end {
                    covered[r * cols + c] += 1;
                    assert_eq!(run.level, level(p.values[r * cols + c], 0.0, 2.0));
                }
            }
        }
        assert!(covered.iter().all(|&n| n == 1), "{covered:?}");
        // Columns 0-2 and 6-8 whole, 3-5 above, NaN, below.
        assert_eq!(rects.len(), 5, "{rects:?}");
    }

    /// A NaN run is one rectangle, a two-valued row two; a shape that does
    /// not fit its values is refused.
    #[test]
    fn runs_are_merged_and_bad_shapes_refused() {
        let panel = |values: Vec<f64>| Panel {
            title: "p".into(),
            shape: [2, 3],
            values,
        };
        let map = Heatmap {
            title: "t".into(),
            panels: vec![panel(
                vec![f64::NAN; 3]
                    .into_iter()
                    .chain([0.0, 0.0, 1.0])
                    .collect(),
            )],
        };
        let svg = map.render_svg().unwrap();
        // 3 cell runs + frame + 32 scale levels + swatch + background.
        assert_eq!(
            svg.matches("<rect").count(),
            3 + 1 + LEVELS + 1 + 1,
            "{svg}"
        );
        assert!(svg.contains("NaN (missing)"));
        let bad = Heatmap {
            panels: vec![panel(vec![0.0; 5])],
            ..map
        };
        assert!(matches!(bad.render_svg(), Err(ChartError::Draw(_))));
    }
}
