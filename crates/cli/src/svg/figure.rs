//! Figures, panels, axes and the SVG they render to.

use super::color::Color;
use super::series::{Bars, ColorMap, Comb, Line, Markers, Series};
use super::{escape, ticks};
use fair_door::error::{Error, Result};
use std::fmt::Write as _;

const MARGIN_LEFT: f64 = 72.0;
const MARGIN_RIGHT: f64 = 16.0;
const MARGIN_TOP: f64 = 28.0;
const MARGIN_BOTTOM: f64 = 48.0;
const FIGURE_TITLE: f64 = 32.0;

/// One plot: axes, titles, a legend and what it draws.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Panel {
    /// Title above the panel.
    pub title: Option<String>,
    /// x-axis title.
    pub x_label: Option<String>,
    /// y-axis title.
    pub y_label: Option<String>,
    /// Same scale on x and y (for curves).
    pub equal_aspect: bool,
    /// Draw a legend of the labelled series.
    pub legend: bool,
    /// What the panel draws, in order (later on top).
    pub series: Vec<Series>,
}

impl Panel {
    /// An empty panel with a title and a legend.
    pub fn new(title: impl Into<String>) -> Panel {
        Panel {
            title: Some(title.into()),
            legend: true,
            ..Panel::default()
        }
    }
    /// Sets the x-axis title.
    pub fn with_x_label(mut self, label: impl Into<String>) -> Panel {
        self.x_label = Some(label.into());
        self
    }
    /// Sets the y-axis title.
    pub fn with_y_label(mut self, label: impl Into<String>) -> Panel {
        self.y_label = Some(label.into());
        self
    }
    /// Keeps x and y at the same scale.
    pub fn with_equal_aspect(mut self, equal: bool) -> Panel {
        self.equal_aspect = equal;
        self
    }
    /// Shows or hides the legend.
    pub fn with_legend(mut self, legend: bool) -> Panel {
        self.legend = legend;
        self
    }
    /// Adds a series.
    pub fn with(mut self, series: impl Into<Series>) -> Panel {
        self.series.push(series.into());
        self
    }
    /// Adds a series in place.
    pub fn push(&mut self, series: impl Into<Series>) {
        self.series.push(series.into());
    }
}

/// A figure: panels laid out in a grid, with an optional title.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// Title above all panels.
    pub title: Option<String>,
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Size of each panel in pixels (width, height).
    pub panel_size: (f64, f64),
}

impl Default for Figure {
    fn default() -> Figure {
        Figure {
            title: None,
            panels: Vec::new(),
            columns: 1,
            panel_size: (720.0, 360.0),
        }
    }
}

/// The mapping from data to pixels of one panel.
struct Frame {
    left: f64,
    top: f64,
    width: f64,
    height: f64,
    x: (f64, f64),
    y: (f64, f64),
}

impl Frame {
    fn px(&self, x: f64) -> f64 {
        self.left + (x - self.x.0) / (self.x.1 - self.x.0) * self.width
    }
    fn py(&self, y: f64) -> f64 {
        self.top + self.height - (y - self.y.0) / (self.y.1 - self.y.0) * self.height
    }
    fn point(&self, p: [f64; 2]) -> Option<(f64, f64)> {
        let (x, y) = (self.px(p[0]), self.py(p[1]));
        // Far-away points are clamped so the numbers stay printable; the clip path hides them.
        (x.is_finite() && y.is_finite()).then(|| (x.clamp(-1e6, 1e6), y.clamp(-1e6, 1e6)))
    }
}

impl Figure {
    /// An empty figure, one panel per row, panels 720 × 360 px.
    pub fn new() -> Figure {
        Figure::default()
    }
    /// Sets the title.
    pub fn with_title(mut self, title: impl Into<String>) -> Figure {
        self.title = Some(title.into());
        self
    }
    /// Sets the panels per row (at least 1).
    pub fn with_columns(mut self, columns: usize) -> Figure {
        self.columns = columns.max(1);
        self
    }
    /// Sets each panel's size in pixels.
    pub fn with_panel_size(mut self, width: f64, height: f64) -> Figure {
        self.panel_size = (width.max(160.0), height.max(120.0));
        self
    }
    /// Adds a panel.
    pub fn with_panel(mut self, panel: Panel) -> Figure {
        self.panels.push(panel);
        self
    }
    /// Adds a panel in place.
    pub fn push(&mut self, panel: Panel) {
        self.panels.push(panel);
    }

    /// The figure as an SVG document.
    pub fn to_svg(&self) -> String {
        let columns = self.columns.max(1);
        let rows = self.panels.len().div_ceil(columns).max(1);
        let (pw, ph) = self.panel_size;
        let title_height = if self.title.is_some() { FIGURE_TITLE } else { 0.0 };
        let width = pw * columns.min(self.panels.len().max(1)) as f64;
        let height = title_height + ph * rows as f64;
        let mut svg = String::new();
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="12">"#
        );
        let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
        if let Some(title) = &self.title {
            let _ = writeln!(
                svg,
                r#"<text x="{:.1}" y="22" text-anchor="middle" font-size="16" font-weight="bold">{}</text>"#,
                width / 2.0,
                escape(title)
            );
        }
        for (index, panel) in self.panels.iter().enumerate() {
            let left = pw * (index % columns) as f64;
            let top = title_height + ph * (index / columns) as f64;
            render_panel(&mut svg, panel, index, left, top, pw, ph);
        }
        svg.push_str("</svg>\n");
        svg
    }

    /// Writes the SVG document to `path`, completely or not at all ([`cad::atomic`]).
    pub fn write(&self, path: &std::path::Path) -> Result<()> {
        cad::atomic::write_text(path, self.to_svg()).map_err(|e| Error::from_write(&e))
    }
}

/// The padded data range of one axis; a degenerate range is widened around its value.
fn padded(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()).max(1e-300) {
        let half = if lo == 0.0 { 0.5 } else { 0.1 * lo.abs() };
        return (lo - half, hi + half);
    }
    let pad = 0.04 * (hi - lo);
    (lo - pad, hi + pad)
}

fn frame_for(panel: &Panel, left: f64, top: f64, width: f64, height: f64) -> Frame {
    let points: Vec<[f64; 2]> = panel.series.iter().flat_map(Series::extent_points).collect();
    let fold = |axis: usize| {
        points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p[axis]), hi.max(p[axis]))
            })
    };
    let (x0, x1) = fold(0);
    let (y0, y1) = fold(1);
    let mut x = padded(x0, x1);
    let mut y = padded(y0, y1);
    let (w, h) = (
        (width - MARGIN_LEFT - MARGIN_RIGHT).max(10.0),
        (height - MARGIN_TOP - MARGIN_BOTTOM).max(10.0),
    );
    if panel.equal_aspect {
        // Pixels per unit must agree: widen the axis that would be drawn at the larger scale.
        let (sx, sy) = (w / (x.1 - x.0), h / (y.1 - y.0));
        if sx > sy {
            let half = w / sy / 2.0;
            let mid = (x.0 + x.1) / 2.0;
            x = (mid - half, mid + half);
        } else {
            let half = h / sx / 2.0;
            let mid = (y.0 + y.1) / 2.0;
            y = (mid - half, mid + half);
        }
    }
    Frame {
        left: left + MARGIN_LEFT,
        top: top + MARGIN_TOP,
        width: w,
        height: h,
        x,
        y,
    }
}

fn render_panel(svg: &mut String, panel: &Panel, index: usize, left: f64, top: f64, width: f64, height: f64) {
    let frame = frame_for(panel, left, top, width, height);
    let _ = writeln!(svg, r#"<g class="panel">"#);
    if let Some(title) = &panel.title {
        let _ = writeln!(
            svg,
            r#"<text x="{:.1}" y="{:.1}" text-anchor="middle" font-size="14">{}</text>"#,
            frame.left + frame.width / 2.0,
            top + 18.0,
            escape(title)
        );
    }
    render_axes(svg, panel, &frame);
    let clip = format!("clip-panel-{index}");
    let _ = writeln!(
        svg,
        r#"<clipPath id="{clip}"><rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}"/></clipPath>"#,
        frame.left, frame.top, frame.width, frame.height
    );
    let _ = writeln!(svg, r#"<g clip-path="url(#{clip})">"#);
    for (k, series) in panel.series.iter().enumerate() {
        let color = series.color().unwrap_or(Color::palette(k)).hex();
        match series {
            Series::Line(s) => render_line(svg, s, &frame, &color),
            Series::Markers(s) => render_markers(svg, s, &frame, &color),
            Series::Bars(s) => render_bars(svg, s, &frame, &color),
            Series::Comb(s) => render_comb(svg, s, &frame, &color),
            Series::ColorMap(s) => render_color_map(svg, s, &frame),
        }
    }
    svg.push_str("</g>\n");
    if panel.legend {
        render_legend(svg, panel, &frame);
    }
    svg.push_str("</g>\n");
}

fn render_axes(svg: &mut String, panel: &Panel, frame: &Frame) {
    let (bottom, right) = (frame.top + frame.height, frame.left + frame.width);
    let _ = writeln!(
        svg,
        r##"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="none" stroke="#333" stroke-width="1"/>"##,
        frame.left, frame.top, frame.width, frame.height
    );
    let x_target = ((frame.width / 90.0) as usize).clamp(2, 10);
    let y_target = ((frame.height / 50.0) as usize).clamp(2, 10);
    let x_ticks = ticks::nice_ticks(frame.x.0, frame.x.1, x_target);
    let y_ticks = ticks::nice_ticks(frame.y.0, frame.y.1, y_target);
    let x_labels = ticks::labels(&x_ticks, ticks::nice_step(frame.x.0, frame.x.1, x_target));
    let y_labels = ticks::labels(&y_ticks, ticks::nice_step(frame.y.0, frame.y.1, y_target));
    for (t, label) in x_ticks.iter().zip(&x_labels) {
        let x = frame.px(*t);
        let _ = writeln!(
            svg,
            r##"<line x1="{x:.2}" y1="{:.2}" x2="{x:.2}" y2="{bottom:.2}" stroke="#e4e4e4"/><line x1="{x:.2}" y1="{bottom:.2}" x2="{x:.2}" y2="{:.2}" stroke="#333"/><text x="{x:.2}" y="{:.2}" text-anchor="middle">{}</text>"##,
            frame.top,
            bottom + 5.0,
            bottom + 18.0,
            escape(label)
        );
    }
    for (t, label) in y_ticks.iter().zip(&y_labels) {
        let y = frame.py(*t);
        let _ = writeln!(
            svg,
            r##"<line x1="{:.2}" y1="{y:.2}" x2="{right:.2}" y2="{y:.2}" stroke="#e4e4e4"/><line x1="{:.2}" y1="{y:.2}" x2="{:.2}" y2="{y:.2}" stroke="#333"/><text x="{:.2}" y="{:.2}" text-anchor="end">{}</text>"##,
            frame.left,
            frame.left - 5.0,
            frame.left,
            frame.left - 8.0,
            y + 4.0,
            escape(label)
        );
    }
    if let Some(label) = &panel.x_label {
        let _ = writeln!(
            svg,
            r#"<text x="{:.2}" y="{:.2}" text-anchor="middle">{}</text>"#,
            frame.left + frame.width / 2.0,
            bottom + 36.0,
            escape(label)
        );
    }
    if let Some(label) = &panel.y_label {
        let (x, y) = (frame.left - 56.0, frame.top + frame.height / 2.0);
        let _ = writeln!(
            svg,
            r#"<text x="{x:.2}" y="{y:.2}" text-anchor="middle" transform="rotate(-90 {x:.2} {y:.2})">{}</text>"#,
            escape(label)
        );
    }
}

/// Runs of consecutive finite points in pixels.
fn runs(points: &[[f64; 2]], frame: &Frame) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for p in points {
        match frame.point(*p) {
            Some(q) => runs.last_mut().into_iter().for_each(|r| r.push(q)),
            None if runs.last().is_some_and(|r| !r.is_empty()) => runs.push(Vec::new()),
            None => {}
        }
    }
    runs.retain(|r| r.len() >= 2);
    runs
}

/// Above this many points per pixel of a panel's width, a series is thinned ([`thin`]).
const THIN_PER_PIXEL: f64 = 4.0;

/// The side, in pixels, of the boxes within which [`thin`] keeps only the extremes.
const THIN_BOX: f64 = 2.0;

/// The indices of `run` (pixel positions, in order) that draw it as the whole does, when it
/// has more than [`THIN_PER_PIXEL`] points per pixel of `width`: min/max decimation per pixel
/// column, on boxes of [`THIN_BOX`] pixels. Consecutive points within such a box form a group
/// (so that points which jitter by a pixel, as a noisy curve's comb does, still group), of
/// which the first, the last, and those of the lowest and highest y and of the least and
/// greatest x are kept, in their order; so every extreme (and the bounding box) is kept
/// exactly, and the polyline through the kept points differs from the whole only inside
/// boxes of two pixels. All indices when the run is short. O(n); at most 6 points are kept
/// per box the run passes through.
pub(super) fn thin(run: &[(f64, f64)], width: f64) -> Vec<usize> {
    if (run.len() as f64) <= THIN_PER_PIXEL * width.max(1.0) {
        return (0..run.len()).collect();
    }
    let mut kept = Vec::new();
    let mut start = 0;
    while start < run.len() {
        let mut end = start + 1;
        let [mut low, mut high, mut left, mut right] = [start; 4];
        while end < run.len() {
            let (x, y) = run[end];
            // The group's box with this point: less than `THIN_BOX` pixels each way.
            let wide = run[right].0.max(x) - run[left].0.min(x);
            let tall = run[high].1.max(y) - run[low].1.min(y);
            if wide >= THIN_BOX || tall >= THIN_BOX {
                break;
            }
            if y < run[low].1 {
                low = end;
            }
            if y > run[high].1 {
                high = end;
            }
            if x < run[left].0 {
                left = end;
            }
            if x > run[right].0 {
                right = end;
            }
            end += 1;
        }
        let mut group = [start, low, high, left, right, end - 1];
        group.sort_unstable();
        for k in group {
            if kept.last() != Some(&k) {
                kept.push(k);
            }
        }
        start = end;
    }
    // Points that jump by more than a box from one to the next (a comb's tips over noisy
    // curvature) group poorly: past 8 per pixel of width the kept points are grouped by
    // count instead, the extremes of each chunk kept, so that no series keeps more than
    // about 12 points per pixel of width whatever its shape.
    let limit = 8.0 * width.max(1.0);
    if kept.len() as f64 > limit {
        let chunk = (kept.len() as f64 / (limit / 4.0)).ceil() as usize;
        let mut fewer = Vec::new();
        for group in kept.chunks(chunk.max(1)) {
            let by = |f: fn(&(f64, f64)) -> f64, less: bool| {
                group
                    .iter()
                    .copied()
                    .reduce(|a, b| {
                        let (fa, fb) = (f(&run[a]), f(&run[b]));
                        if (less && fb < fa) || (!less && fb > fa) {
                            b
                        } else {
                            a
                        }
                    })
                    .unwrap_or(group[0])
            };
            let x = |p: &(f64, f64)| p.0;
            let y = |p: &(f64, f64)| p.1;
            let mut extremes = [
                group[0],
                by(y, true),
                by(y, false),
                by(x, true),
                by(x, false),
                group[group.len() - 1],
            ];
            extremes.sort_unstable();
            for k in extremes {
                if fewer.last() != Some(&k) {
                    fewer.push(k);
                }
            }
        }
        kept = fewer;
    }
    kept
}

/// `run` thinned for a panel `width` pixels wide ([`thin`]).
fn thinned(run: Vec<(f64, f64)>, width: f64) -> Vec<(f64, f64)> {
    if (run.len() as f64) <= THIN_PER_PIXEL * width.max(1.0) {
        return run;
    }
    thin(&run, width).into_iter().map(|k| run[k]).collect()
}

fn polyline(svg: &mut String, run: &[(f64, f64)], attributes: &str) {
    svg.push_str("<polyline points=\"");
    for (k, (x, y)) in run.iter().enumerate() {
        let _ = write!(svg, "{}{x:.2},{y:.2}", if k == 0 { "" } else { " " });
    }
    let _ = writeln!(svg, "\" fill=\"none\" {attributes}/>");
}

fn render_line(svg: &mut String, line: &Line, frame: &Frame, color: &str) {
    let dash = if line.dashed {
        r#" stroke-dasharray="6 4""#
    } else {
        ""
    };
    let attributes = format!(
        r#"stroke="{color}" stroke-width="{:.2}"{dash}"#,
        line.width.max(0.1)
    );
    for run in runs(&line.points, frame) {
        polyline(svg, &thinned(run, frame.width), &attributes);
    }
}

fn render_markers(svg: &mut String, markers: &Markers, frame: &Frame, color: &str) {
    let fill = if markers.hollow {
        "none".to_string()
    } else {
        color.to_string()
    };
    let _ = writeln!(svg, r#"<g fill="{fill}" stroke="{color}">"#);
    // In pixels, thinned as a line through them would be: past a few markers per pixel
    // column they draw a solid band between the column's lowest and highest, which the kept
    // ones and the curve through them still show.
    let placed: Vec<(f64, f64)> = markers.points.iter().filter_map(|p| frame.point(*p)).collect();
    for (x, y) in thinned(placed, frame.width) {
        let _ = writeln!(
            svg,
            r#"<circle cx="{x:.2}" cy="{y:.2}" r="{:.2}"/>"#,
            markers.radius.max(0.5)
        );
    }
    svg.push_str("</g>\n");
}

fn render_bars(svg: &mut String, bars: &Bars, frame: &Frame, color: &str) {
    let half = bars.resolved_width() / 2.0;
    let _ = writeln!(svg, r#"<g fill="{color}" fill-opacity="0.8">"#);
    if (bars.x.len() as f64) > THIN_PER_PIXEL * frame.width.max(1.0) {
        render_bar_columns(svg, bars, frame);
        svg.push_str("</g>\n");
        return;
    }
    for (x, h) in bars.x.iter().zip(&bars.heights) {
        if let (Some((x0, y0)), Some((x1, y1))) = (frame.point([x - half, 0.0]), frame.point([x + half, *h]))
        {
            let _ = writeln!(
                svg,
                r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}"/>"#,
                x0.min(x1),
                y0.min(y1),
                (x1 - x0).abs().max(0.5),
                (y1 - y0).abs()
            );
        }
    }
    svg.push_str("</g>\n");
}

/// Bars too many for their pixels, one pixel column each: the highest and the lowest bar
/// whose x falls in the column, drawn a pixel wide (what the overlapping bars would have
/// covered). O(n + width).
fn render_bar_columns(svg: &mut String, bars: &Bars, frame: &Frame) {
    let mut columns: std::collections::BTreeMap<i64, (f64, f64)> = std::collections::BTreeMap::new();
    for (x, h) in bars.x.iter().zip(&bars.heights) {
        if let Some((px, _)) = frame.point([*x, *h]) {
            let entry = columns.entry(px.floor() as i64).or_insert((0.0, 0.0));
            *entry = (entry.0.min(*h), entry.1.max(*h));
        }
    }
    for (column, (low, high)) in columns {
        for h in [low, high] {
            let (Some((_, y0)), Some((_, y1))) = (frame.point([0.0, 0.0]), frame.point([0.0, h])) else {
                continue;
            };
            if h != 0.0 {
                let _ = writeln!(
                    svg,
                    r#"<rect x="{column}" y="{:.2}" width="1" height="{:.2}"/>"#,
                    y0.min(y1),
                    (y1 - y0).abs()
                );
            }
        }
    }
}

fn render_comb(svg: &mut String, comb: &Comb, frame: &Frame, color: &str) {
    let tips = comb.tips();
    let mut teeth = String::new();
    let placed: Vec<((f64, f64), (f64, f64))> = comb
        .base
        .iter()
        .zip(&tips)
        .filter_map(|(p, tip)| Some((frame.point(*p)?, frame.point(*tip)?)))
        .collect();
    // The teeth whose tips the envelope keeps ([`thin`]): the comb's extremes, a few per
    // pixel column.
    let tip_pixels: Vec<(f64, f64)> = placed.iter().map(|(_, tip)| *tip).collect();
    for k in thin(&tip_pixels, frame.width) {
        let ((x0, y0), (x1, y1)) = placed[k];
        let _ = write!(teeth, "M{x0:.2} {y0:.2}L{x1:.2} {y1:.2}");
    }
    if !teeth.is_empty() {
        let _ = writeln!(
            svg,
            r#"<path d="{teeth}" fill="none" stroke="{color}" stroke-width="0.8" stroke-opacity="0.7"/>"#
        );
    }
    for run in runs(&tips, frame) {
        polyline(
            svg,
            &thinned(run, frame.width),
            &format!(r#"stroke="{color}" stroke-width="1.2""#),
        );
    }
}

fn render_color_map(svg: &mut String, map: &ColorMap, frame: &Frame) {
    let Some((lo, hi)) = map.value_range() else { return };
    let rows = map.values.len().max(1) as f64;
    let dx = (map.x_range.1 - map.x_range.0) / rows;
    svg.push_str("<g stroke=\"none\">\n");
    for (i, row) in map.values.iter().enumerate() {
        let dy = (map.y_range.1 - map.y_range.0) / row.len().max(1) as f64;
        for (j, v) in row.iter().enumerate() {
            let x = map.x_range.0 + dx * i as f64;
            let y = map.y_range.0 + dy * j as f64;
            let t = if hi > lo {
                ((v - lo) / (hi - lo)).clamp(0.0, 1.0)
            } else {
                0.5
            };
            if let (Some((x0, y0)), Some((x1, y1))) = (frame.point([x, y]), frame.point([x + dx, y + dy])) {
                let _ = writeln!(
                    svg,
                    r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}" fill="{}"/>"#,
                    x0.min(x1),
                    y0.min(y1),
                    (x1 - x0).abs(),
                    (y1 - y0).abs(),
                    Color::sequential(t).hex()
                );
            }
        }
    }
    svg.push_str("</g>\n");
}

fn render_legend(svg: &mut String, panel: &Panel, frame: &Frame) {
    let entries: Vec<(usize, &Series, String)> = panel
        .series
        .iter()
        .enumerate()
        .filter_map(|(k, s)| {
            let label = s.label()?;
            let text = match s {
                Series::ColorMap(map) => match map.value_range() {
                    Some((lo, hi)) => format!("{label} ({lo:.3e} to {hi:.3e})"),
                    None => label.to_string(),
                },
                _ => label.to_string(),
            };
            Some((k, s, text))
        })
        .collect();
    if entries.is_empty() {
        return;
    }
    let longest = entries
        .iter()
        .map(|(_, _, t)| t.chars().count())
        .max()
        .unwrap_or(0) as f64;
    let (w, h) = (36.0 + 7.0 * longest, 8.0 + 18.0 * entries.len() as f64);
    let (x, y) = (frame.left + frame.width - w - 8.0, frame.top + 8.0);
    let _ = writeln!(
        svg,
        r##"<g class="legend"><rect x="{x:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}" fill="white" fill-opacity="0.85" stroke="#999"/>"##
    );
    for (row, (k, series, text)) in entries.iter().enumerate() {
        let color = series.color().unwrap_or(Color::palette(*k)).hex();
        let cy = y + 14.0 + 18.0 * row as f64;
        let swatch = match series {
            Series::Markers(_) => format!(
                r#"<circle cx="{:.2}" cy="{:.2}" r="3" fill="{color}"/>"#,
                x + 16.0,
                cy - 4.0
            ),
            Series::Bars(_) => format!(
                r#"<rect x="{:.2}" y="{:.2}" width="12" height="8" fill="{color}"/>"#,
                x + 10.0,
                cy - 8.0
            ),
            Series::ColorMap(_) => format!(
                r#"<rect x="{:.2}" y="{:.2}" width="6" height="8" fill="{}"/><rect x="{:.2}" y="{:.2}" width="6" height="8" fill="{}"/>"#,
                x + 10.0,
                cy - 8.0,
                Color::sequential(0.0).hex(),
                x + 16.0,
                cy - 8.0,
                Color::sequential(1.0).hex()
            ),
            _ => format!(
                r#"<line x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}" stroke="{color}" stroke-width="2"/>"#,
                x + 8.0,
                cy - 4.0,
                x + 24.0,
                cy - 4.0
            ),
        };
        let _ = writeln!(
            svg,
            r#"{swatch}<text x="{:.2}" y="{cy:.2}">{}</text>"#,
            x + 30.0,
            escape(text)
        );
    }
    svg.push_str("</g>\n");
}
