//! The faired shapes as exported: exact curves through the faired points, the header's
//! tolerance, the summary a report carries, files named by extension.

use cad::{CadCurve, CadSettings, CadSurface, Format, Shape, Units, WriteOptions};
use curve_repr::{CubicPieces, HermiteSpline, Surface, Vec2};

use crate::common::{function, grid, planar_points};

fn size(curve: &CadCurve) -> f64 {
    cad::model::size(curve.curve.control_points())
}

#[test]
fn a_function_is_written_as_a_curve_with_x_equal_to_t_through_its_points() {
    let spline = function(40);
    let shape = Shape::Curve(CadCurve::from_spline_function(&spline).unwrap());
    for format in Format::ALL {
        let file = cad::export(&shape, format, &CadSettings::default(), &WriteOptions::default()).unwrap();
        let back = &cad::read(&file.text, format).unwrap().curves[0];
        let scale = size(back);
        for (&x, &y) in spline.x().iter().zip(spline.y()) {
            let p = back.curve.point(x);
            assert!((p.x - x).abs() <= 1e-14 * scale && (p.y - y).abs() <= 1e-12 * scale);
            assert_eq!(p.z, 0.0);
        }
        // The faired points come back from the curve alone, at its knots.
        let (points, parameters) = back.sample_points(1);
        assert_eq!(parameters, spline.x().to_vec());
        for (p, &y) in points.iter().zip(spline.y()) {
            assert!((p.y - y).abs() <= 1e-12 * scale);
        }
    }
}

#[test]
fn a_c1_chain_keeps_its_double_knots_and_its_points() {
    let points = planar_points(9);
    let chords: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    let mut breaks = vec![0.0];
    for c in &chords {
        breaks.push(breaks[breaks.len() - 1] + c);
    }
    let tangents: Vec<Vec2> = (0..points.len())
        .map(|i| (points[(i + 1).min(8)] - points[i.saturating_sub(1)]).normalize())
        .collect();
    let pieces = CubicPieces::from_hermite(&breaks, &points, &tangents).unwrap();
    let curve = CadCurve::from_pieces(&pieces, &points, &breaks).unwrap();
    assert_eq!(curve.curve.control_points().len(), 2 * points.len());
    for (p, &t) in curve.points.iter().zip(&breaks) {
        assert!((curve.curve.point(t) - p).norm() <= 1e-12 * size(&curve));
    }
}

#[test]
fn the_header_carries_the_unit_and_a_tolerance_from_the_shape() {
    let spline = HermiteSpline::natural(&planar_points(30)).unwrap();
    let shape = Shape::Curve(CadCurve::from_hermite(&spline).unwrap());
    let automatic = cad::export(
        &shape,
        Format::Iges,
        &CadSettings::default(),
        &WriteOptions::default(),
    )
    .unwrap();
    let scale = automatic.model.size();
    assert_eq!(automatic.model.tolerance, 1e-9 * scale);
    let settings = CadSettings {
        units: Units::Foot,
        tolerance: Some(0.25),
        ..CadSettings::default()
    };
    for format in Format::ALL {
        let file = cad::export(&shape, format, &settings, &WriteOptions::default()).unwrap();
        let back = cad::read(&file.text, format).unwrap();
        assert_eq!(back.units, Units::Foot);
        if format != Format::Dxf {
            assert_eq!(back.tolerance, 0.25);
        }
    }
    let summary = serde_json::to_value(automatic.summary()).unwrap();
    assert_eq!(summary["format"], "iges");
    assert_eq!(summary["units"], "mm");
    assert_eq!(summary["degree"], 3);
    assert_eq!(summary["control_points"], 32);
    assert!(summary["rebuild"].is_null());
}

#[test]
fn a_surface_is_written_exactly_through_its_grid() {
    let net = grid(5, 4);
    let surface = curve_repr::BicubicSplineSurface::new(&net).unwrap();
    let shape = Shape::Surface(CadSurface::from_bicubic(&surface).unwrap());
    for format in [Format::Iges, Format::Step] {
        let file = cad::export(&shape, format, &CadSettings::default(), &WriteOptions::default()).unwrap();
        let back = &cad::read(&file.text, format).unwrap().surfaces[0];
        for (i, row) in net.iter().enumerate() {
            for (j, p) in row.iter().enumerate() {
                let q = back.surface.eval(surface.u_knots()[i], surface.v_knots()[j]);
                assert!((q - p).norm() <= 1e-12 * 10.0);
            }
        }
    }
}

#[test]
fn files_are_named_by_extension_and_read_back_from_disk() {
    let scratch = tempfile::Builder::new()
        .prefix("fair-cad-test-")
        .tempdir()
        .unwrap();
    let directory = scratch.path();
    let spline = HermiteSpline::natural(&planar_points(10)).unwrap();
    let shape = Shape::Curve(CadCurve::from_hermite(&spline).unwrap().with_name("wl"));
    for name in ["a.igs", "b.IGES", "c.stp", "d.step", "e.dxf"] {
        let path = directory.join(name);
        let file = cad::export_to_path(&shape, &path, None, &CadSettings::default()).unwrap();
        assert_eq!(Some(file.format), Format::from_path(&path));
        let back = cad::read_path(&path, None).unwrap();
        assert_eq!(back.curves[0].curve, file.model.curves[0].curve);
        if file.format != Format::Dxf {
            assert!(file.text.contains(name), "{name} is recorded in the file");
        }
    }
    let forced = directory.join("f.txt");
    let file = cad::export_to_path(&shape, &forced, Some(Format::Step), &CadSettings::default()).unwrap();
    assert!(file.text.starts_with("ISO-10303-21;"));
}
