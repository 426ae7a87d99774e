//! Files that OpenCASCADE and ezdxf wrote (data/reference/cad/, see its README) read as the
//! geometry given to those writers, to the digits they print.

use cad::{CadCurve, Format, Units};
use curve_repr::{Curve, NurbsCurve, NurbsSurface, Vec3};
use serde_json::Value;

use crate::common::data;

fn fixtures() -> Value {
    let text = std::fs::read_to_string(data("reference/cad/fixtures.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn point(v: &Value) -> Vec3 {
    Vec3::from_iterator(numbers(v))
}

fn expected_curve(v: &Value) -> NurbsCurve<3> {
    NurbsCurve::new(
        v["degree"].as_u64().unwrap() as usize,
        numbers(&v["knots"]),
        v["control_points"]
            .as_array()
            .unwrap()
            .iter()
            .map(point)
            .collect(),
        numbers(&v["weights"]),
    )
    .unwrap()
}

fn expected_surface(v: &Value) -> NurbsSurface {
    let grid = |w: &Value| -> Vec<Vec<Vec3>> {
        w.as_array()
            .unwrap()
            .iter()
            .map(|row| row.as_array().unwrap().iter().map(point).collect())
            .collect()
    };
    NurbsSurface::new(
        v["degree_u"].as_u64().unwrap() as usize,
        v["degree_v"].as_u64().unwrap() as usize,
        numbers(&v["knots_u"]),
        numbers(&v["knots_v"]),
        grid(&v["control_points"]),
        v["weights"].as_array().unwrap().iter().map(numbers).collect(),
    )
    .unwrap()
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * b.abs().max(1.0)
}

/// Same degree, knots, control points and weights to `relative` precision.
fn assert_same_curve(got: &NurbsCurve<3>, expected: &NurbsCurve<3>, relative: f64, what: &str) {
    assert_eq!(got.degree(), expected.degree(), "{what}");
    assert_eq!(got.knots().len(), expected.knots().len(), "{what}");
    for (a, b) in got.knots().iter().zip(expected.knots()) {
        assert!(close(*a, *b, relative), "{what}: knot {a} vs {b}");
    }
    for (a, b) in got.weights().iter().zip(expected.weights()) {
        assert!(close(*a, *b, relative), "{what}: weight {a} vs {b}");
    }
    for (a, b) in got.control_points().iter().zip(expected.control_points()) {
        assert!(
            (a - b).norm() <= relative * b.norm().max(1.0),
            "{what}: {a:?} vs {b:?}"
        );
    }
}

/// OpenCASCADE prints 9 significant digits in IGES, 12 in STEP.
fn precision(format: Format) -> f64 {
    match format {
        Format::Iges => 1e-8,
        Format::Step => 1e-11,
        Format::Dxf => 0.0,
    }
}

#[test]
fn opencascade_curves_read_as_written() {
    let fixtures = fixtures();
    for name in ["occ_curve3d", "occ_rational_arc"] {
        let expected = expected_curve(&fixtures["curves"][name]);
        for format in [Format::Iges, Format::Step] {
            let path = data(&format!("reference/cad/{name}.{}", format.extension()));
            let model = cad::read_path(&path, None).unwrap();
            assert_eq!(model.curves.len(), 1, "{path}");
            assert!(model.surfaces.is_empty(), "{path}");
            assert_eq!(model.units, Units::Millimetre, "{path}");
            assert_eq!(model.tolerance, 1e-7, "{path}");
            assert_same_curve(&model.curves[0].curve, &expected, precision(format), &path);
        }
    }
}

#[test]
fn opencascade_faces_read_as_their_surfaces_without_their_boundary_curves() {
    let fixtures = fixtures();
    for name in ["occ_surface", "occ_rational_surface"] {
        let expected = expected_surface(&fixtures["surfaces"][name]);
        for format in [Format::Iges, Format::Step] {
            let path = data(&format!("reference/cad/{name}.{}", format.extension()));
            let model = cad::read_path(&path, None).unwrap();
            assert!(
                model.curves.is_empty(),
                "{path}: boundary curves are not shapes of their own"
            );
            assert_eq!(model.surfaces.len(), 1, "{path}");
            let got = &model.surfaces[0].surface;
            let relative = precision(format);
            assert_eq!(got.degrees(), expected.degrees());
            assert_eq!(got.net_size(), expected.net_size());
            let (rows, columns) = expected.net_size();
            for i in 0..rows {
                for j in 0..columns {
                    let (a, b) = (
                        got.control_point(i, j).unwrap(),
                        expected.control_point(i, j).unwrap(),
                    );
                    assert!(
                        (a - b).norm() <= relative * b.norm().max(1.0),
                        "{path}: P[{i}][{j}]"
                    );
                    let (a, b) = (got.weight(i, j).unwrap(), expected.weight(i, j).unwrap());
                    assert!(close(a, b, relative), "{path}: w[{i}][{j}]");
                }
            }
            assert_eq!(got.knot_vectors().0.knots(), expected.knot_vectors().0.knots());
            assert_eq!(got.knot_vectors().1.knots(), expected.knot_vectors().1.knots());
        }
    }
}

#[test]
fn an_opencascade_edge_on_part_of_a_curve_is_cut_to_its_trims() {
    let fixtures = fixtures();
    let basis = expected_curve(&fixtures["curves"]["occ_curve3d"]);
    let model = cad::read_path(data("reference/cad/occ_trimmed.step"), None).unwrap();
    assert_eq!(model.curves.len(), 1);
    let part = &model.curves[0].curve;
    assert_eq!(part.domain(), (0.5, 2.5));
    for k in 0..=100 {
        let t = 0.5 + 2.0 * k as f64 / 100.0;
        assert!((part.point(t) - basis.point(t)).norm() < 1e-11, "t = {t}");
    }
}

#[test]
fn ezdxf_splines_read_exactly() {
    let fixtures = fixtures();
    let model = cad::read_path(data("reference/cad/ezdxf_splines.dxf"), None).unwrap();
    assert_eq!(model.units, Units::Metre);
    let names = fixtures["dxf"]["ezdxf_splines"].as_array().unwrap();
    assert_eq!(model.curves.len(), names.len());
    for (curve, name) in model.curves.iter().zip(names) {
        let expected = expected_curve(&fixtures["curves"][name.as_str().unwrap()]);
        assert_same_curve(&curve.curve, &expected, 0.0, name.as_str().unwrap());
    }
}

/// What OpenCASCADE wrote, written again by us, reads back as the same curve bit for bit.
#[test]
fn opencascade_curves_pass_through_our_writers_unchanged() {
    let model = cad::read_path(data("reference/cad/occ_rational_arc.igs"), None).unwrap();
    let curve: CadCurve = model.curves[0].clone();
    for format in Format::ALL {
        let text = cad::write(&model, format, &cad::WriteOptions::default()).unwrap();
        assert_eq!(cad::read(&text, format).unwrap().curves[0].curve, curve.curve);
    }
}
