//! Writes one faired shape of each kind as IGES, STEP and DXF, and `check.json` with our own
//! evaluation of each at 1 000 parameters and the faired points with their parameters, for
//! `tests/python/check_cad.py` to compare with OpenCASCADE's and ezdxf's readers. The files go
//! to `$FAIR_CAD_CHECK_DIR` if set, else to `cad-check` in cargo's test scratch directory
//! (`target/tmp/cad-check`); `.ci/run` runs the script on them after the test suite:
//!
//! ```sh
//! cargo test -p fair-cad --test cad occ_check
//! python tests/python/check_cad.py target/tmp/cad-check
//! ```
//!
//! (A test rather than an example so that the suite's own build writes the files: an example
//! run with `cargo run -p fair-cad` resolves features for that package alone and recompiled
//! most dependencies in CI.)
//!
//! Shapes: a spline function y(x) (x(t) = t), an open and a closed planar natural spline, a
//! spatial spline, a rational interpolating NURBS (non-unit weights, as the weight method
//! leaves it), Okada's C1 Ferguson chain (double knots), a curve rebuilt with few control
//! points within a tolerance, the bicubic spline surface of a grid, and a rational surface.

use std::path::{Path, PathBuf};

use cad::{CadCurve, CadSettings, CadSurface, Format, Shape};
use curve_repr::{
    BicubicSplineSurface, CubicPieces, Curve, EndCondition, HermiteEnds, HermiteSettings, HermiteSpline,
    Interpolation, InterpolationSettings, NurbsSurface, Parametrization, SplineFunction, Surface, Vec2, Vec3,
};
use serde_json::{json, Value};

type Failure = Box<dyn std::error::Error>;

fn wavy(t: f64) -> f64 {
    (0.8 * t).sin() * 3.0 + 0.15 * (5.3 * t).sin()
}

fn shapes() -> Result<Vec<(Shape, CadSettings)>, Failure> {
    let exact = CadSettings::default();
    let mut out = Vec::new();

    let x: Vec<f64> = (0..60)
        .map(|i| -2.0 + i as f64 * 0.17 + 0.03 * (i as f64).sin())
        .collect();
    let y: Vec<f64> = x.iter().map(|&v| wavy(v)).collect();
    let function = SplineFunction::new(&x, &y, EndCondition::ParabolicRunout)?;
    out.push((
        Shape::Curve(CadCurve::from_spline_function(&function)?.with_name("function")),
        exact.clone(),
    ));

    let open: Vec<Vec2> = (0..40)
        .map(|i| {
            let a = i as f64 * 0.12;
            Vec2::new(30.0 * a.cos() + 0.2 * (7.0 * a).sin(), 12.0 * a.sin())
        })
        .collect();
    let spline = HermiteSpline::natural(&open)?;
    out.push((
        Shape::Curve(CadCurve::from_hermite(&spline)?.with_name("planar")),
        exact.clone(),
    ));

    let ring: Vec<Vec2> = (0..24)
        .map(|i| {
            let a = i as f64 / 24.0 * std::f64::consts::TAU;
            Vec2::new(
                100.0 + 8.0 * a.cos(),
                -50.0 + 5.0 * a.sin() + 0.3 * (3.0 * a).cos(),
            )
        })
        .collect();
    let closed = HermiteSpline::new(&ring, &HermiteSettings::default().with_ends(HermiteEnds::Closed))?;
    out.push((
        Shape::Curve(CadCurve::from_hermite(&closed)?.with_name("closed")),
        exact.clone(),
    ));

    let helix: Vec<Vec3> = (0..50)
        .map(|i| {
            let a = i as f64 * 0.2;
            Vec3::new(2.0 * a.cos(), 2.0 * a.sin(), 0.4 * a + 0.01 * (11.0 * a).sin())
        })
        .collect();
    let spatial = HermiteSpline::natural(&helix)?;
    out.push((
        Shape::Curve(CadCurve::from_hermite(&spatial)?.with_name("spatial")),
        exact.clone(),
    ));

    let section: Vec<Vec2> = (0..15)
        .map(|i| {
            let a = i as f64 / 14.0 * std::f64::consts::PI;
            Vec2::new(5.0 * a.cos(), 2.0 * a.sin())
        })
        .collect();
    let interpolation = Interpolation::with_parametrization(
        &section,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )?;
    let weights: Vec<f64> = (0..interpolation.control_count())
        .map(|i| 1.0 + 0.4 * (i as f64 * 0.9).sin().abs())
        .collect();
    let rational = interpolation.solve(&weights)?;
    out.push((
        Shape::Curve(
            CadCurve::from_nurbs(&rational, &section, interpolation.params())?.with_name("rational"),
        ),
        exact.clone(),
    ));

    // Okada's chain: unit-parameter Ferguson segments with chord-scaled tangents, C1 only.
    let chain: Vec<Vec2> = (0..12)
        .map(|i| Vec2::new(i as f64 * 2.0, wavy(i as f64 * 0.7) * 2.0))
        .collect();
    let chords: Vec<f64> = chain.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let mut breaks = vec![0.0];
    for c in &chords {
        breaks.push(breaks[breaks.len() - 1] + c);
    }
    let direction = |i: usize| {
        let (a, b) = (chain[i.saturating_sub(1)], chain[(i + 1).min(chain.len() - 1)]);
        (b - a).normalize()
    };
    let segments: Vec<[Vec2; 4]> = (0..chords.len())
        .map(|i| {
            let (p0, p1) = (chain[i], chain[i + 1]);
            let (tx, ty) = (direction(i) * chords[i], direction(i + 1) * chords[i]);
            [p0, tx, (p1 - p0) * 3.0 - tx * 2.0 - ty, (p0 - p1) * 2.0 + tx + ty]
        })
        .collect();
    let pieces = CubicPieces::from_unit_power(&breaks, &segments)?;
    out.push((
        Shape::Curve(CadCurve::from_pieces(&pieces, &chain, &breaks)?.with_name("ferguson")),
        exact.clone(),
    ));

    let dense: Vec<Vec2> = (0..600)
        .map(|i| {
            let t = i as f64 / 599.0 * 12.0;
            Vec2::new(t * 10.0, wavy(t) * 4.0)
        })
        .collect();
    let dense_spline = HermiteSpline::natural(&dense)?;
    out.push((
        Shape::Curve(CadCurve::from_hermite(&dense_spline)?.with_name("rebuilt")),
        CadSettings {
            fit_tolerance: Some(0.01),
            units: cad::Units::Metre,
            ..CadSettings::default()
        },
    ));

    let grid: Vec<Vec<Vec3>> = (0..9)
        .map(|i| {
            (0..7)
                .map(|j| {
                    let (u, v) = (i as f64 * 1.3, j as f64 * 0.9 + 0.1 * i as f64);
                    Vec3::new(u, v, (0.4 * u).sin() * (0.6 * v).cos() * 2.0)
                })
                .collect()
        })
        .collect();
    let bicubic = BicubicSplineSurface::new(&grid)?;
    out.push((
        Shape::Surface(CadSurface::from_bicubic(&bicubic)?.with_name("surface")),
        exact.clone(),
    ));

    let net: Vec<Vec<Vec3>> = (0..5)
        .map(|i| {
            (0..4)
                .map(|j| Vec3::new(i as f64 * 1.5, j as f64 * 1.25, 0.3 * ((i + 2 * j) as f64).sin()))
                .collect()
        })
        .collect();
    let mut w = vec![vec![1.0; 4]; 5];
    w[2][1] = 1.5;
    w[3][2] = 0.7;
    let knots_u = vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0];
    let knots_v = vec![0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0];
    let weighted = NurbsSurface::new(3, 3, knots_u, knots_v, net, w)?;
    out.push((
        Shape::Surface(CadSurface::new(weighted).with_name("rational surface")),
        exact,
    ));
    Ok(out)
}

fn triple(p: &Vec3) -> Value {
    json!([p.x, p.y, p.z])
}

fn record(shape: &Shape, export: &cad::Export, files: Value) -> Value {
    match shape {
        Shape::Curve(_) => {
            let written = &export.model.curves[0];
            let (a, b) = written.curve.domain();
            let params: Vec<f64> = (0..1000).map(|k| a + (b - a) * k as f64 / 999.0).collect();
            let params: Vec<f64> = params.into_iter().map(|t| t.min(b)).collect();
            let points: Vec<Value> = params.iter().map(|&t| triple(&written.curve.point(t))).collect();
            let data: Vec<Value> = written.points.iter().map(triple).collect();
            let slack = export.rebuild.as_ref().map_or(0.0, |r| r.max_deviation);
            json!({
                "kind": "curve", "name": written.name, "files": files,
                "domain": [a, b], "params": params, "points": points,
                "data_params": written.parameters, "data_points": data,
                "data_slack": slack,
                "size": cad::model::size(written.curve.control_points()),
                "units": export.model.units.name(), "tolerance": export.model.tolerance,
                "rebuild": export.rebuild,
            })
        }
        Shape::Surface(_) => {
            let written = &export.model.surfaces[0];
            let ((u0, u1), (v0, v1)) = written.surface.domain();
            let mut params = Vec::new();
            let mut points = Vec::new();
            for a in 0..32 {
                for b in 0..32 {
                    let (u, v) = (u0 + (u1 - u0) * a as f64 / 31.0, v0 + (v1 - v0) * b as f64 / 31.0);
                    let (u, v) = (u.min(u1), v.min(v1));
                    params.push(json!([u, v]));
                    points.push(triple(&written.surface.eval(u, v)));
                }
            }
            let mut data_params = Vec::new();
            let columns = written.v_parameters.len();
            for (k, _) in written.points.iter().enumerate() {
                data_params.push(json!([
                    written.u_parameters[k / columns],
                    written.v_parameters[k % columns]
                ]));
            }
            let rows = written.control_rows();
            let all: Vec<Vec3> = rows.into_iter().flatten().collect();
            json!({
                "kind": "surface", "name": written.name, "files": files,
                "domain": [[u0, u1], [v0, v1]], "params": params, "points": points,
                "data_params": data_params,
                "data_points": written.points.iter().map(triple).collect::<Vec<_>>(),
                "data_slack": 0.0, "size": cad::model::size(&all),
                "units": export.model.units.name(), "tolerance": export.model.tolerance,
            })
        }
    }
}

/// The directory the files go to (see the module's documentation).
fn out_dir() -> PathBuf {
    std::env::var_os("FAIR_CAD_CHECK_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_TARGET_TMPDIR")).join("cad-check"))
}

#[test]
fn writes_every_kind_for_opencascade_and_ezdxf() -> Result<(), Failure> {
    let out = out_dir();
    std::fs::create_dir_all(&out)?;
    let mut records = Vec::new();
    for (shape, settings) in shapes()? {
        let name = match &shape {
            Shape::Curve(c) => c.name.clone(),
            Shape::Surface(s) => s.name.replace(' ', "_"),
        };
        let mut files = serde_json::Map::new();
        let mut first = None;
        for format in Format::ALL {
            if format == Format::Dxf && matches!(shape, Shape::Surface(_)) {
                continue;
            }
            let path: PathBuf = out.join(format!("{name}.{}", format.extension()));
            let export = cad::export_to_path(&shape, &path, Some(format), &settings)?;
            // What we wrote reads back bit for bit.
            let back = cad::read_path(&path, None)?;
            check_round_trip(&export.model, &back, &path)?;
            files.insert(format.name().into(), json!(file_name(&path)));
            first.get_or_insert(export);
        }
        let export = first.ok_or("no format written")?;
        records.push(record(&shape, &export, Value::Object(files)));
    }
    // Nine shapes: each kind the module's documentation lists.
    assert_eq!(records.len(), 9, "shapes written");
    std::fs::write(out.join("check.json"), serde_json::to_string(&records)?)?;
    Ok(())
}

fn file_name(path: &Path) -> String {
    path.file_name()
        .and_then(|n| n.to_str())
        .unwrap_or("")
        .to_string()
}

fn check_round_trip(written: &cad::CadModel, back: &cad::CadModel, path: &Path) -> Result<(), Failure> {
    let same_curves = written
        .curves
        .iter()
        .zip(&back.curves)
        .all(|(a, b)| a.curve == b.curve);
    let same_surfaces = written
        .surfaces
        .iter()
        .zip(&back.surfaces)
        .all(|(a, b)| a.surface == b.surface);
    if written.curves.len() != back.curves.len()
        || written.surfaces.len() != back.surfaces.len()
        || !same_curves
        || !same_surfaces
        || written.units != back.units
    {
        return Err(format!("{}: the round trip changed the geometry", path.display()).into());
    }
    Ok(())
}
