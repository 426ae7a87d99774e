//! Write → read returns the same knots, weights and control points to the last bit, in all
//! three formats, with the unit and the tolerance of the header.

use cad::{CadCurve, CadModel, CadSurface, Format, Units, WriteOptions};
use curve_repr::{HermiteSpline, NurbsCurve, Vec3};
use proptest::prelude::*;

use crate::common::{curves, planar_points, surfaces};

fn model(curves: Vec<CadCurve>, surfaces: Vec<CadSurface>, units: Units, tolerance: f64) -> CadModel {
    CadModel {
        curves,
        surfaces,
        units,
        tolerance,
    }
}

/// What a format keeps of a name: IGES an 8-character label, DXF a layer name.
fn kept_name(format: Format, name: &str) -> String {
    match format {
        Format::Iges => name
            .chars()
            .filter(char::is_ascii_alphanumeric)
            .take(8)
            .collect::<String>()
            .to_ascii_uppercase(),
        _ => name.to_string(),
    }
}

fn assert_round_trip(written: &CadModel, format: Format) {
    let text = cad::write(written, format, &WriteOptions::default()).unwrap();
    let back = cad::read(&text, format).unwrap();
    assert_eq!(back.curves.len(), written.curves.len(), "{format}");
    assert_eq!(back.surfaces.len(), written.surfaces.len(), "{format}");
    for (a, b) in written.curves.iter().zip(&back.curves) {
        // NurbsCurve's equality compares every knot, control point and weight exactly.
        assert_eq!(a.curve, b.curve, "{format}: {}", a.name);
        assert_eq!(kept_name(format, &a.name), b.name, "{format}");
        assert_eq!(a.dimension, b.dimension, "{format}: {}", a.name);
    }
    for (a, b) in written.surfaces.iter().zip(&back.surfaces) {
        assert_eq!(a.surface, b.surface, "{format}: {}", a.name);
        assert_eq!(kept_name(format, &a.name), b.name, "{format}");
    }
    assert_eq!(back.units, written.units, "{format}");
    if format != Format::Dxf {
        assert_eq!(back.tolerance.to_bits(), written.tolerance.to_bits(), "{format}");
    }
}

#[test]
fn every_curve_and_surface_reads_back_to_the_last_bit() {
    for format in Format::ALL {
        for curve in curves() {
            assert_round_trip(&model(vec![curve], vec![], Units::Millimetre, 1.234e-7), format);
        }
        if format != Format::Dxf {
            for surface in surfaces() {
                assert_round_trip(&model(vec![], vec![surface], Units::Inch, 3e-9), format);
            }
            // Several shapes in one file, in order.
            assert_round_trip(&model(curves(), surfaces(), Units::Metre, 1e-6), format);
        } else {
            assert_round_trip(&model(curves(), vec![], Units::Metre, 1e-6), format);
        }
    }
}

#[test]
fn every_unit_reads_back_from_every_format() {
    for format in Format::ALL {
        for units in Units::ALL {
            assert_round_trip(&model(curves()[..1].to_vec(), vec![], units, 0.5), format);
        }
    }
}

#[test]
fn a_dense_curve_reads_back_exactly() {
    let spline = HermiteSpline::natural(&planar_points(20_000)).unwrap();
    let curve = CadCurve::from_hermite(&spline).unwrap();
    for format in Format::ALL {
        assert_round_trip(
            &model(vec![curve.clone()], vec![], Units::Millimetre, 1e-9),
            format,
        );
    }
}

/// Any finite f64 the writers print: subnormal, huge, negative zero.
fn coordinate() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        any::<f64>().prop_filter("finite", |v| v.is_finite()),
        Just(-0.0),
        Just(5e-324),
    ]
}

fn nurbs() -> impl Strategy<Value = NurbsCurve<3>> {
    (1usize..6, 0usize..8)
        .prop_flat_map(|(degree, interior)| {
            let count = degree + 1 + interior;
            (
                Just(degree),
                prop::collection::vec(0.0..1.0f64, interior),
                prop::collection::vec((coordinate(), coordinate(), coordinate()), count),
                prop::collection::vec(1e-3..1e3f64, count),
                -1e6..1e6f64,
                1e-6..1e6f64,
            )
        })
        .prop_filter_map(
            "valid knots",
            |(degree, mut interior, points, weights, start, length)| {
                interior.sort_by(f64::total_cmp);
                let mut knots = vec![start; degree + 1];
                knots.extend(interior.iter().map(|k| start + k * length));
                knots.extend(vec![start + length; degree + 1]);
                let points = points.into_iter().map(|(x, y, z)| Vec3::new(x, y, z)).collect();
                NurbsCurve::new(degree, knots, points, weights).ok()
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_nurbs_curves_read_back_to_the_last_bit(curve in nurbs()) {
        for format in Format::ALL {
            let written = model(vec![CadCurve::new(curve.clone())], vec![], Units::Millimetre, 1e-7);
            let text = cad::write(&written, format, &WriteOptions::default()).unwrap();
            let back = cad::read(&text, format).unwrap();
            prop_assert_eq!(&back.curves[0].curve, &curve, "{}", format);
        }
    }
}
