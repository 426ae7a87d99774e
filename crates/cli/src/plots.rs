//! The pictures `fair` draws: a curve before and after with its curvature comb and z_i bars;
//! a surface grid with its z_ij map. Built from plain data so the numerical crates supply
//! what they have and the rest is left out.

use crate::input::{CurvePoints, Grid};
use crate::svg::{Bars, Color, ColorMap, Comb, Figure, Line, Markers, Panel};
use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings};
use fairness::highlight::{HighlightSettings, LightSetup};

pub use fair_door::measure::{CombData, CurvaturePlot};

/// What a curve plot shows; every field but the input is optional.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CurvePlot {
    /// Title of the figure.
    pub title: String,
    /// The data points as read.
    pub input: Vec<[f64; 2]>,
    /// The faired data points.
    pub faired: Option<Vec<[f64; 2]>>,
    /// The input's spline, sampled.
    pub input_curve: Option<Vec<[f64; 2]>>,
    /// The faired spline, sampled.
    pub faired_curve: Option<Vec<[f64; 2]>>,
    /// Curvature comb of the faired (or, for inspect, the input) curve.
    pub comb: Option<CombData>,
    /// z_i per data point before fairing.
    pub z_before: Option<Vec<f64>>,
    /// z_i per data point after fairing.
    pub z_after: Option<Vec<f64>>,
    /// Whether the points are a function y(x) (axes x, y) or a parametric curve (equal aspect).
    pub function: bool,
    /// The curvature plot of the input.
    pub curvature_before: Option<CurvaturePlot>,
    /// The curvature plot of the result.
    pub curvature_after: Option<CurvaturePlot>,
    /// The names of the coordinates drawn in the curve panel, horizontal then vertical
    /// ([`axis_names`]); `None` draws `x`, `y`.
    pub axes: Option<[String; 2]>,
    /// The other projections of a 3D curve ([`other_projections`]), one panel each.
    pub projections: Vec<Projection>,
}

/// One projection of a 3D curve onto a coordinate plane: the data points before and after,
/// with the names of the two coordinates drawn.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Projection {
    /// The horizontal and the vertical coordinate's names.
    pub axes: [String; 2],
    /// The data points as read, projected.
    pub input: Vec<[f64; 2]>,
    /// The faired points, projected.
    pub faired: Option<Vec<[f64; 2]>>,
}

/// The names of the coordinates [`planar_view`] draws, from the input's coordinate names
/// (abscissa first): the first two of a planar curve, the first and the third of a 3D one.
pub fn axis_names(names: &[String]) -> [String; 2] {
    let name = |k: usize, fallback: &str| names.get(k).cloned().unwrap_or_else(|| fallback.to_string());
    if names.len() == 3 {
        [name(0, "x"), name(2, "z")]
    } else {
        [name(0, "x"), name(1, "y")]
    }
}

/// The projections of a 3D curve that [`planar_view`] leaves out — onto the planes of the
/// first two and of the last two coordinates —, each named by its coordinates; none for a
/// planar curve. O(n).
pub fn other_projections(
    names: &[String],
    input: &CurvePoints,
    faired: Option<&CurvePoints>,
) -> Vec<Projection> {
    let (CurvePoints::Spatial(before), true) = (input, names.len() == 3) else {
        return Vec::new();
    };
    let after = match faired {
        Some(CurvePoints::Spatial(p)) => Some(p),
        _ => None,
    };
    [(0usize, 1usize), (1, 2)]
        .into_iter()
        .map(|(a, b)| {
            let project = |p: &Vec<curve_repr::Vec3>| p.iter().map(|v| [v[a], v[b]]).collect::<Vec<_>>();
            Projection {
                axes: [names[a].clone(), names[b].clone()],
                input: project(before),
                faired: after.map(project),
            }
        })
        .collect()
}

/// The plane a spatial curve is drawn in: (x, y) for planar points, (x, z) for spatial ones
/// (a ship's sheer in profile). Documented choice; O(n).
pub fn planar_view(points: &CurvePoints) -> Vec<[f64; 2]> {
    match points {
        CurvePoints::Planar(p) => p.iter().map(|v| [v.x, v.y]).collect(),
        CurvePoints::Spatial(p) => p.iter().map(|v| [v.x, v.z]).collect(),
    }
}

impl CurvePlot {
    /// The figure: the curve panel, then a z_i panel when z values are given.
    pub fn figure(&self) -> Figure {
        let [x_label, y_label] = self
            .axes
            .clone()
            .unwrap_or_else(|| ["x".to_string(), "y".to_string()]);
        let title = if self.projections.is_empty() {
            "points and curve".to_string()
        } else {
            format!("points and curve, {x_label}–{y_label} projection")
        };
        let mut curve = Panel::new(title)
            .with_x_label(x_label)
            .with_y_label(y_label)
            .with_equal_aspect(!self.function);
        if let Some(comb) = &self.comb {
            curve.push(
                Comb::new(comb.points.clone(), comb.normals.clone(), comb.curvature.clone())
                    .with_auto_scale(0.15)
                    .with_label("curvature comb")
                    .with_color(Color::rgb(150, 150, 150)),
            );
        }
        match &self.input_curve {
            Some(c) => curve.push(
                Line::new(c.clone())
                    .with_label("input curve")
                    .with_color(Color::palette(0)),
            ),
            None => curve.push(
                Line::new(self.input.clone())
                    .with_label("input polygon")
                    .with_color(Color::palette(0))
                    .with_width(0.8),
            ),
        }
        if let Some(c) = &self.faired_curve {
            curve.push(
                Line::new(c.clone())
                    .with_label("faired curve")
                    .with_color(Color::palette(1)),
            );
        }
        curve.push(
            Markers::new(self.input.clone())
                .with_label("input points")
                .with_color(Color::palette(0)),
        );
        if let Some(p) = &self.faired {
            curve.push(
                Markers::new(p.clone())
                    .with_label("faired points")
                    .with_color(Color::palette(1))
                    .with_hollow(true),
            );
        }
        let mut figure = Figure::new().with_title(self.title.clone()).with_panel(curve);
        for view in &self.projections {
            let [x_label, y_label] = view.axes.clone();
            let mut panel = Panel::new(format!("{x_label}–{y_label} projection"))
                .with_x_label(x_label)
                .with_y_label(y_label)
                .with_equal_aspect(true);
            panel.push(
                Line::new(view.input.clone())
                    .with_label("input polygon")
                    .with_color(Color::palette(0))
                    .with_width(0.8),
            );
            panel.push(
                Markers::new(view.input.clone())
                    .with_label("input points")
                    .with_color(Color::palette(0)),
            );
            if let Some(p) = &view.faired {
                panel.push(
                    Line::new(p.clone())
                        .with_label("faired polygon")
                        .with_color(Color::palette(1))
                        .with_width(0.8),
                );
                panel.push(
                    Markers::new(p.clone())
                        .with_label("faired points")
                        .with_color(Color::palette(1))
                        .with_hollow(true),
                );
            }
            figure.push(panel);
        }
        if self.z_before.is_some() || self.z_after.is_some() {
            let mut z = Panel::new("third-derivative jumps z_i")
                .with_x_label("point index i")
                .with_y_label("z_i");
            if let Some(values) = &self.z_before {
                z.push(
                    Bars::indexed(values.clone())
                        .with_label("before")
                        .with_color(Color::palette(0)),
                );
            }
            if let Some(values) = &self.z_after {
                let x = (0..values.len()).map(|i| i as f64 + 0.2).collect();
                z.push(
                    Bars::new(x, values.clone())
                        .with_width(0.4)
                        .with_label("after")
                        .with_color(Color::palette(1)),
                );
            }
            figure.push(z);
        }
        if let Some(panel) = self.curvature_panel() {
            figure.push(panel);
        }
        figure
    }

    /// The curvature plot: the input's, and the result's over it when there is one.
    fn curvature_panel(&self) -> Option<Panel> {
        let first = self.curvature_before.as_ref().or(self.curvature_after.as_ref())?;
        let mut panel = Panel::new(first.title.clone())
            .with_x_label(first.x_label.clone())
            .with_y_label(first.y_label.clone());
        let both = self.curvature_before.is_some() && self.curvature_after.is_some();
        for (plot, name, color, hollow) in [
            (&self.curvature_before, "input", 0, false),
            (&self.curvature_after, "faired", 1, true),
        ] {
            let Some(plot) = plot else { continue };
            let label = if both { name } else { "curvature" };
            panel.push(
                Line::new(plot.line.clone())
                    .with_label(label)
                    .with_color(Color::palette(color)),
            );
            panel.push(
                Markers::new(plot.knots.clone())
                    .with_color(Color::palette(color))
                    .with_hollow(hollow),
            );
        }
        Some(panel)
    }
}

/// What a surface plot shows.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SurfacePlot {
    /// Title of the figure.
    pub title: String,
    /// The grid as read.
    pub input: Option<Grid>,
    /// The faired grid.
    pub faired: Option<Grid>,
    /// z_ij (rows i, columns j), when measured (of the faired grid when there is one).
    pub z: Option<Vec<Vec<f64>>>,
    /// z_ij of the input grid, when a faired grid's z is in `z`.
    pub z_before: Option<Vec<Vec<f64>>>,
    /// Draw highlight lines ([`fairness::highlight`]) of the input's and the faired grid's
    /// bicubic spline surfaces, under one light set up on the input.
    pub highlights: bool,
}

fn grid_lines(grid: &Grid, color: Color, label: &str, panel: &mut Panel) {
    for i in 0..grid.rows {
        let row: Vec<[f64; 2]> = (0..grid.columns)
            .filter_map(|j| grid.get(i, j))
            .map(|p| [p.x, p.y])
            .collect();
        let line = Line::new(row).with_color(color).with_width(0.8);
        panel.push(if i == 0 { line.with_label(label) } else { line });
    }
    for j in 0..grid.columns {
        let column: Vec<[f64; 2]> = (0..grid.rows)
            .filter_map(|i| grid.get(i, j))
            .map(|p| [p.x, p.y])
            .collect();
        panel.push(Line::new(column).with_color(color).with_width(0.8));
    }
}

impl SurfacePlot {
    /// The figure: the grid seen from above (x, y), and the z_ij map when given.
    pub fn figure(&self) -> Figure {
        let mut view = Panel::new("grid, top view")
            .with_x_label("x")
            .with_y_label("y")
            .with_equal_aspect(true);
        if let Some(grid) = &self.input {
            grid_lines(grid, Color::palette(0), "input grid", &mut view);
        }
        if let Some(grid) = &self.faired {
            grid_lines(grid, Color::palette(1), "faired grid", &mut view);
        }
        let mut figure = Figure::new().with_title(self.title.clone()).with_panel(view);
        if self.highlights {
            for panel in self.highlight_panels() {
                figure.push(panel);
            }
        }
        // Before and after share one colour scale, so that the maps compare.
        let shared = [&self.z_before, &self.z]
            .into_iter()
            .flatten()
            .flat_map(|z| z.iter().flatten().copied())
            .filter(|v| v.is_finite())
            .fold(None, |range: Option<(f64, f64)>, v| match range {
                None => Some((v, v)),
                Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
            });
        let map = |z: &Vec<Vec<f64>>| {
            let map = ColorMap::indexed(z.clone()).with_label("z_ij");
            match shared {
                Some((lo, hi)) => map.with_scale(lo, hi),
                None => map,
            }
        };
        if let Some(z) = &self.z_before {
            figure.push(
                Panel::new("z_ij, input")
                    .with_x_label("i")
                    .with_y_label("j")
                    .with(map(z)),
            );
        }
        if let Some(z) = &self.z {
            let title = if self.z_before.is_some() {
                "z_ij, faired"
            } else {
                "z_ij"
            };
            figure.push(Panel::new(title).with_x_label("i").with_y_label("j").with(map(z)));
        }
        figure
    }

    /// Highlight-line panels of the input and the faired grid (Beier–Chen, 20 light lines),
    /// both under the light set up on the input's surface; none for a grid the bicubic
    /// surface cannot be built through.
    pub fn highlight_panels(&self) -> Vec<Panel> {
        let surface_of = |grid: &Grid| {
            BicubicSplineSurface::from_flat(
                grid.points.clone(),
                grid.rows,
                grid.columns,
                &BicubicSurfaceSettings::default(),
            )
            .ok()
        };
        let Some(input) = self.input.as_ref().and_then(surface_of) else {
            return Vec::new();
        };
        let settings = HighlightSettings::default();
        let Some(light) = LightSetup::for_surface(&input, &settings) else {
            return Vec::new();
        };
        let mut panels = Vec::new();
        let faired = self.faired.as_ref().and_then(surface_of);
        for (title, surface, color) in [
            ("highlight lines, input", Some(&input), Color::palette(0)),
            ("highlight lines, faired", faired.as_ref(), Color::palette(1)),
        ] {
            let Some(surface) = surface else { continue };
            let mut panel = Panel::new(title)
                .with_x_label("along the light lines")
                .with_y_label("across")
                .with_equal_aspect(true)
                .with_legend(false);
            for line in light.lines(surface, settings.samples) {
                panel.push(Line::new(line).with_color(color).with_width(0.9));
            }
            panels.push(panel);
        }
        panels
    }
}
