//! What a panel draws: lines, markers, bars, curvature combs and colour maps.

use super::color::Color;

/// A polyline through points; non-finite points break it.
#[derive(Debug, Clone, PartialEq)]
pub struct Line {
    /// The vertices.
    pub points: Vec<[f64; 2]>,
    /// Legend entry.
    pub label: Option<String>,
    /// Colour (default: the palette by series index).
    pub color: Option<Color>,
    /// Stroke width in pixels.
    pub width: f64,
    /// Dashed stroke.
    pub dashed: bool,
}

impl Line {
    /// A solid line 1.5 px wide.
    pub fn new(points: impl IntoIterator<Item = [f64; 2]>) -> Line {
        Line {
            points: points.into_iter().collect(),
            label: None,
            color: None,
            width: 1.5,
            dashed: false,
        }
    }
    /// Sets the legend entry.
    pub fn with_label(mut self, label: impl Into<String>) -> Line {
        self.label = Some(label.into());
        self
    }
    /// Sets the colour.
    pub fn with_color(mut self, color: Color) -> Line {
        self.color = Some(color);
        self
    }
    /// Sets the stroke width in pixels.
    pub fn with_width(mut self, width: f64) -> Line {
        self.width = width;
        self
    }
    /// Dashes the stroke.
    pub fn with_dashes(mut self, dashed: bool) -> Line {
        self.dashed = dashed;
        self
    }
}

/// Point markers (circles).
#[derive(Debug, Clone, PartialEq)]
pub struct Markers {
    /// The points.
    pub points: Vec<[f64; 2]>,
    /// Legend entry.
    pub label: Option<String>,
    /// Colour.
    pub color: Option<Color>,
    /// Radius in pixels.
    pub radius: f64,
    /// Hollow circles (stroke only).
    pub hollow: bool,
}

impl Markers {
    /// Filled circles of radius 2.5 px.
    pub fn new(points: impl IntoIterator<Item = [f64; 2]>) -> Markers {
        Markers {
            points: points.into_iter().collect(),
            label: None,
            color: None,
            radius: 2.5,
            hollow: false,
        }
    }
    /// Sets the legend entry.
    pub fn with_label(mut self, label: impl Into<String>) -> Markers {
        self.label = Some(label.into());
        self
    }
    /// Sets the colour.
    pub fn with_color(mut self, color: Color) -> Markers {
        self.color = Some(color);
        self
    }
    /// Sets the radius in pixels.
    pub fn with_radius(mut self, radius: f64) -> Markers {
        self.radius = radius;
        self
    }
    /// Hollow circles.
    pub fn with_hollow(mut self, hollow: bool) -> Markers {
        self.hollow = hollow;
        self
    }
}

/// Vertical bars from 0 (for z_i per data point).
#[derive(Debug, Clone, PartialEq)]
pub struct Bars {
    /// Bar positions.
    pub x: Vec<f64>,
    /// Bar heights (signed).
    pub heights: Vec<f64>,
    /// Legend entry.
    pub label: Option<String>,
    /// Colour.
    pub color: Option<Color>,
    /// Bar width in data units; `None`: 80 % of the smallest spacing.
    pub width: Option<f64>,
}

impl Bars {
    /// Bars at `x` with `heights` (pairs beyond the shorter list are ignored).
    pub fn new(x: Vec<f64>, heights: Vec<f64>) -> Bars {
        Bars {
            x,
            heights,
            label: None,
            color: None,
            width: None,
        }
    }
    /// Bars at 0, 1, 2, … (point indices).
    pub fn indexed(heights: Vec<f64>) -> Bars {
        Bars::new((0..heights.len()).map(|i| i as f64).collect(), heights)
    }
    /// Sets the legend entry.
    pub fn with_label(mut self, label: impl Into<String>) -> Bars {
        self.label = Some(label.into());
        self
    }
    /// Sets the colour.
    pub fn with_color(mut self, color: Color) -> Bars {
        self.color = Some(color);
        self
    }
    /// Sets the bar width in data units.
    pub fn with_width(mut self, width: f64) -> Bars {
        self.width = Some(width);
        self
    }

    /// The bar width: the set one, or 80 % of the smallest positive spacing (1 if none).
    pub fn resolved_width(&self) -> f64 {
        if let Some(w) = self.width.filter(|w| w.is_finite() && *w > 0.0) {
            return w;
        }
        let mut sorted: Vec<f64> = self.x.iter().copied().filter(|v| v.is_finite()).collect();
        sorted.sort_by(f64::total_cmp);
        let spacing = sorted
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|d| *d > 0.0)
            .fold(f64::INFINITY, f64::min);
        if spacing.is_finite() {
            0.8 * spacing
        } else {
            1.0
        }
    }
}

/// A curvature comb: a tooth from each point along its unit normal, `scale · length` long,
/// and the envelope line through the tooth tips.
#[derive(Debug, Clone, PartialEq)]
pub struct Comb {
    /// Points on the curve.
    pub base: Vec<[f64; 2]>,
    /// Unit normals there.
    pub normals: Vec<[f64; 2]>,
    /// Signed tooth lengths (curvature), before scaling.
    pub lengths: Vec<f64>,
    /// Factor applied to every length.
    pub scale: f64,
    /// Legend entry.
    pub label: Option<String>,
    /// Colour.
    pub color: Option<Color>,
}

impl Comb {
    /// A comb with scale 1 (entries beyond the shortest list are ignored).
    pub fn new(base: Vec<[f64; 2]>, normals: Vec<[f64; 2]>, lengths: Vec<f64>) -> Comb {
        Comb {
            base,
            normals,
            lengths,
            scale: 1.0,
            label: None,
            color: None,
        }
    }
    /// Sets the scale factor.
    pub fn with_scale(mut self, scale: f64) -> Comb {
        self.scale = scale;
        self
    }
    /// Scales the longest tooth to `fraction` of the extent of the base points.
    pub fn with_auto_scale(mut self, fraction: f64) -> Comb {
        let extent = |axis: usize| {
            let values = self.base.iter().map(|p| p[axis]).filter(|v| v.is_finite());
            let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            });
            if hi > lo {
                hi - lo
            } else {
                0.0
            }
        };
        let size = extent(0).max(extent(1));
        let longest = self
            .lengths
            .iter()
            .filter(|l| l.is_finite())
            .fold(0.0f64, |m, l| m.max(l.abs()));
        if size > 0.0 && longest > 0.0 {
            self.scale = fraction * size / longest;
        }
        self
    }
    /// Sets the legend entry.
    pub fn with_label(mut self, label: impl Into<String>) -> Comb {
        self.label = Some(label.into());
        self
    }
    /// Sets the colour.
    pub fn with_color(mut self, color: Color) -> Comb {
        self.color = Some(color);
        self
    }

    /// The tooth tips `base + scale · length · normal` (non-finite where any input is).
    pub fn tips(&self) -> Vec<[f64; 2]> {
        self.base
            .iter()
            .zip(&self.normals)
            .zip(&self.lengths)
            .map(|((p, n), l)| [p[0] + self.scale * l * n[0], p[1] + self.scale * l * n[1]])
            .collect()
    }
}

/// A colour map of a value grid `values[i][j]`, cell (i, j) drawn over
/// `x_range` split into the i values and `y_range` split into the j values.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorMap {
    /// The values, row i by column j (ragged rows are drawn as given).
    pub values: Vec<Vec<f64>>,
    /// The x extent of the whole map.
    pub x_range: (f64, f64),
    /// The y extent of the whole map.
    pub y_range: (f64, f64),
    /// Legend entry (the value range is appended).
    pub label: Option<String>,
    /// The value range the colours span, when fixed (so that two maps compare); else the
    /// values' own range.
    pub scale: Option<(f64, f64)>,
}

impl ColorMap {
    /// A map over index space: cell (i, j) covers [i − ½, i + ½] × [j − ½, j + ½].
    pub fn indexed(values: Vec<Vec<f64>>) -> ColorMap {
        let rows = values.len() as f64;
        let columns = values.iter().map(Vec::len).max().unwrap_or(0) as f64;
        ColorMap {
            values,
            x_range: (-0.5, rows - 0.5),
            y_range: (-0.5, columns - 0.5),
            label: None,
            scale: None,
        }
    }
    /// Fixes the value range the colours span (values outside are clamped to its ends).
    pub fn with_scale(mut self, low: f64, high: f64) -> ColorMap {
        self.scale = (low.is_finite() && high.is_finite() && low <= high).then_some((low, high));
        self
    }
    /// Sets the legend entry.
    pub fn with_label(mut self, label: impl Into<String>) -> ColorMap {
        self.label = Some(label.into());
        self
    }
    /// The range the colours span: the fixed scale, else the smallest and largest finite
    /// value, if any.
    pub fn value_range(&self) -> Option<(f64, f64)> {
        if self.scale.is_some() {
            return self.scale;
        }
        let finite = self.values.iter().flatten().copied().filter(|v| v.is_finite());
        finite.fold(None, |range, v| match range {
            None => Some((v, v)),
            Some((lo, hi)) => Some((f64::min(lo, v), f64::max(hi, v))),
        })
    }
}

/// Anything a panel draws.
#[derive(Debug, Clone, PartialEq)]
pub enum Series {
    /// A polyline.
    Line(Line),
    /// Point markers.
    Markers(Markers),
    /// Bars.
    Bars(Bars),
    /// A curvature comb.
    Comb(Comb),
    /// A colour map.
    ColorMap(ColorMap),
}

macro_rules! into_series {
    ($($t:ident),*) => {$(
        impl From<$t> for Series {
            fn from(value: $t) -> Series {
                Series::$t(value)
            }
        }
    )*};
}
into_series!(Line, Markers, Bars, Comb, ColorMap);

impl Series {
    /// The legend entry, if any.
    pub fn label(&self) -> Option<&str> {
        match self {
            Series::Line(s) => s.label.as_deref(),
            Series::Markers(s) => s.label.as_deref(),
            Series::Bars(s) => s.label.as_deref(),
            Series::Comb(s) => s.label.as_deref(),
            Series::ColorMap(s) => s.label.as_deref(),
        }
    }

    /// The set colour, if any.
    pub fn color(&self) -> Option<Color> {
        match self {
            Series::Line(s) => s.color,
            Series::Markers(s) => s.color,
            Series::Bars(s) => s.color,
            Series::Comb(s) => s.color,
            Series::ColorMap(_) => None,
        }
    }

    /// Every finite data point the series covers (for the axes' ranges).
    pub fn extent_points(&self) -> Vec<[f64; 2]> {
        let mut points = match self {
            Series::Line(s) => s.points.clone(),
            Series::Markers(s) => s.points.clone(),
            Series::Bars(s) => {
                let half = s.resolved_width() / 2.0;
                s.x.iter()
                    .zip(&s.heights)
                    .flat_map(|(x, h)| [[x - half, 0.0], [x + half, *h]])
                    .collect()
            }
            Series::Comb(s) => s.base.iter().copied().chain(s.tips()).collect(),
            Series::ColorMap(s) => vec![[s.x_range.0, s.y_range.0], [s.x_range.1, s.y_range.1]],
        };
        points.retain(|p| p[0].is_finite() && p[1].is_finite());
        points
    }
}
