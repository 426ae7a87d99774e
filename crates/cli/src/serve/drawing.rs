//! What the page draws beside the report, from the same measurements as the command's plots
//! ([`measure`], [`fairness::highlight`]): the page computes nothing but screen positions.
//!
//! A curve's drawing (JSON):
//! - `plane`: `"xy"`, or `"xz"` for spatial points (a ship's sheer seen in profile), and
//!   `function`: whether the points are a function y(x) (axes stretched) or a parametric
//!   curve (equal aspect);
//! - `view`: the data points in that plane;
//! - `samples`: the spline through them, sampled densely;
//! - `comb`: `points`, unit `normals` and signed `curvature` along the samples (a tooth is
//!   `point + s · curvature · normal` for the page's scale s);
//! - `z`: z_i at each data point (0 at the two ends);
//! - `curvature`: the x–c polyline (function) or κ(t) over the chord length (parametric):
//!   `title`, `x_label`, `y_label`, `line`, `knots` (the values at the data points).
//!
//! A surface's drawing: `view` (the grid seen from above, (x, y) row by row), `z` (z_ij, rows
//! i, columns j, 0 on the border), and `highlights`: the Beier–Chen highlight lines (`lines`,
//! polylines in the light's view plane) and the grid points projected into that plane
//! (`points`). A surface before and after fairing is drawn under one light, set up on the
//! surface before, so that the pictures compare.
//!
//! Numbers that are not finite (a comb tooth at a cusp) are written as `null`.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings};
use serde_json::{json, Value};

use crate::input::{CurvePoints, Grid};
use crate::plots::planar_view;
use fair_door::error::Result;
use fair_door::kind::CurveKind;
use fair_door::measure::{self, CurveMeasurement, SurfaceMeasurement};
use fairness::highlight::{HighlightSettings, LightSetup};

/// The drawing of a curve from its measurement. O(samples).
pub(crate) fn curve(points: &CurvePoints, kind: CurveKind, measured: &CurveMeasurement) -> Value {
    let comb = measured.comb.as_ref().map(|c| {
        json!({
            "points": c.points,
            "normals": c.normals,
            "curvature": c.curvature,
        })
    });
    let curvature = measured.curvature.as_ref().map(|c| {
        json!({
            "title": c.title,
            "x_label": c.x_label,
            "y_label": c.y_label,
            "line": c.line,
            "knots": c.knots,
        })
    });
    json!({
        "plane": if points.dimension() == 3 { "xz" } else { "xy" },
        "function": kind == CurveKind::Function,
        "view": planar_view(points),
        "samples": measured.samples,
        "comb": comb,
        "z": measured.z,
        "curvature": curvature,
    })
}

/// Measures a curve and draws it. O(n).
pub(crate) fn measure_curve(points: &CurvePoints, kind: CurveKind) -> Result<Value> {
    let measured = measure::curve(kind, points)?;
    Ok(curve(points, kind, &measured))
}

fn bicubic(grid: &Grid) -> Option<BicubicSplineSurface> {
    BicubicSplineSurface::from_flat(
        grid.points.clone(),
        grid.rows,
        grid.columns,
        &BicubicSurfaceSettings::default(),
    )
    .ok()
}

/// The light every drawing of a surface and its faired twin shares: set up on `grid`.
pub(crate) fn light_for(grid: &Grid) -> Option<LightSetup> {
    LightSetup::for_surface(&bicubic(grid)?, &HighlightSettings::default())
}

/// The drawing of a surface grid from its measurement, its highlight lines under `light`
/// (none without a light). O(m·n + highlight samples).
pub(crate) fn surface(grid: &Grid, measured: &SurfaceMeasurement, light: Option<&LightSetup>) -> Value {
    let view: Vec<[f64; 2]> = grid.points.iter().map(|p| [p.x, p.y]).collect();
    let highlights = light.zip(bicubic(grid)).map(|(light, surface)| {
        let points: Vec<[f64; 2]> = grid.points.iter().map(|p| light.project(p)).collect();
        json!({
            "lines": light.lines(&surface, HighlightSettings::default().samples),
            "points": points,
        })
    });
    json!({
        "rows": grid.rows,
        "columns": grid.columns,
        "view": view,
        "z": measured.z,
        "highlights": highlights,
    })
}

/// Measures a surface grid and draws it under `light`. O(m·n + highlight samples).
pub(crate) fn measure_surface(grid: &Grid, light: Option<&LightSetup>) -> Result<Value> {
    let measured = measure::surface(grid)?;
    Ok(surface(grid, &measured, light))
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    #[test]
    fn a_curve_drawing_has_one_z_per_point_and_a_comb() {
        let points = CurvePoints::Planar(
            (0..15)
                .map(|i| Vec2::new(i as f64, (i as f64 * 0.4).sin()))
                .collect(),
        );
        let drawing = measure_curve(&points, CurveKind::Function).unwrap();
        assert_eq!(drawing["z"].as_array().unwrap().len(), 15);
        assert_eq!(drawing["view"].as_array().unwrap().len(), 15);
        let comb = &drawing["comb"];
        let teeth = comb["points"].as_array().unwrap().len();
        assert!(teeth > 15);
        assert_eq!(comb["curvature"].as_array().unwrap().len(), teeth);
        assert_eq!(drawing["function"], true);
        assert_eq!(drawing["plane"], "xy");
    }

    #[test]
    fn a_surface_drawing_has_highlight_lines_and_the_z_map() {
        let (rows, columns) = (6, 7);
        let points = (0..rows)
            .flat_map(|i| {
                (0..columns).map(move |j| {
                    let (x, y) = (i as f64, j as f64);
                    Vec3::new(x, y, 0.1 * x * x - 0.05 * y * y + 0.02 * x * y)
                })
            })
            .collect();
        let grid = Grid {
            rows,
            columns,
            points,
        };
        let light = light_for(&grid);
        assert!(light.is_some());
        let drawing = measure_surface(&grid, light.as_ref()).unwrap();
        assert_eq!(drawing["z"].as_array().unwrap().len(), rows);
        assert_eq!(drawing["z"][0].as_array().unwrap().len(), columns);
        assert!(!drawing["highlights"]["lines"].as_array().unwrap().is_empty());
        assert_eq!(
            drawing["highlights"]["points"].as_array().unwrap().len(),
            rows * columns
        );
    }
}
