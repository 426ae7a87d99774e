//! Rebuild with few control points: the deviation it reports, the tolerance it meets, the
//! curvature counts it compares (against the report's own definitions), the warning when
//! wiggles come back.

use cad::{rebuild, CadCurve, CadSettings, CurveKind, Error, Format, RebuildTarget, Shape, WriteOptions};
use curve_repr::{Curve, EndCondition, HermiteEnds, HermiteSettings, HermiteSpline, SplineFunction, Vec2};

use crate::common::{function, planar_points};

/// Three radians of a rippled ellipse, n points.
fn gentle(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let a = i as f64 / (n - 1) as f64 * 3.0;
            Vec2::new(20.0 * a.cos() + 0.1 * (9.0 * a).sin(), 7.0 * a.sin())
        })
        .collect()
}

fn vertical_deviation(curve: &CadCurve, rebuilt: &CadCurve) -> f64 {
    curve
        .points
        .iter()
        .zip(&curve.parameters)
        .map(|(q, &t)| (q.y - rebuilt.curve.point(t).y).abs())
        .fold(0.0, f64::max)
}

/// On the exact faired curve the counts are the `fair` report's own (fairness::summary).
#[test]
fn the_faired_counts_are_the_reports_counts() {
    let spline = function(120);
    let curve = CadCurve::from_spline_function(&spline).unwrap();
    let (_, report) = rebuild(&curve, RebuildTarget::ControlPoints(20), 3).unwrap();
    let summary = fairness::summary::function(spline.x(), spline.y()).unwrap();
    assert_eq!(report.faired.inflections, summary.inflections);
    assert_eq!(Some(report.faired.vibrations), summary.vibrations);

    let points = planar_points(80);
    let natural = HermiteSpline::natural(&points).unwrap();
    let curve = CadCurve::from_hermite(&natural).unwrap();
    let (_, report) = rebuild(&curve, RebuildTarget::ControlPoints(12), 3).unwrap();
    let summary = fairness::summary::parametric(&points).unwrap();
    assert_eq!(report.faired.inflections, summary.inflections);
    assert_eq!(Some(report.faired.vibrations), summary.vibrations);
}

#[test]
fn a_function_is_rebuilt_as_a_function_with_its_vertical_deviation() {
    let spline = function(200);
    let curve = CadCurve::from_spline_function(&spline).unwrap();
    let (rebuilt, report) = rebuild(&curve, RebuildTarget::ControlPoints(14), 3).unwrap();
    assert_eq!(rebuilt.curve.control_points().len(), 14);
    assert_eq!(rebuilt.kind, CurveKind::Function);
    assert_eq!(report.max_deviation, vertical_deviation(&curve, &rebuilt));
    let (a, b) = rebuilt.curve.domain();
    for k in 0..=300 {
        let t = a + (b - a) * k as f64 / 300.0;
        assert!((rebuilt.curve.point(t).x - t).abs() <= 1e-12 * b.abs().max(1.0));
    }
}

#[test]
fn a_tolerance_rebuild_meets_it_with_the_fewest_control_points_the_search_finds() {
    let points = gentle(400);
    let natural = HermiteSpline::natural(&points).unwrap();
    let curve = CadCurve::from_hermite(&natural).unwrap();
    let (rebuilt, report) = rebuild(&curve, RebuildTarget::Tolerance(1e-3), 3).unwrap();
    assert!(!report.exact_fallback);
    assert!(report.max_deviation <= 1e-3);
    let n = rebuilt.curve.control_points().len();
    assert_eq!(report.control_points, n);
    assert!(n < 100, "{n}");
    let deviation = |c: &CadCurve| {
        points
            .iter()
            .zip(natural.parameters())
            .map(|(q, &t)| {
                (Vec2::new(q.x, q.y) - {
                    let p = c.curve.point(t);
                    Vec2::new(p.x, p.y)
                })
                .norm()
            })
            .fold(0.0, f64::max)
    };
    assert_eq!(report.max_deviation, deviation(&rebuilt));
    let (fewer, _) = rebuild(&curve, RebuildTarget::ControlPoints(n - 1), 3).unwrap();
    assert!(deviation(&fewer) > 1e-3);
}

#[test]
fn a_closed_curve_is_rebuilt_closed() {
    let ring: Vec<Vec2> = (0..60)
        .map(|i| {
            let a = i as f64 / 60.0 * std::f64::consts::TAU;
            Vec2::new(4.0 * a.cos(), 2.0 * a.sin())
        })
        .collect();
    let closed =
        HermiteSpline::new(&ring, &HermiteSettings::default().with_ends(HermiteEnds::Closed)).unwrap();
    let curve = CadCurve::from_hermite(&closed).unwrap();
    let (rebuilt, report) = rebuild(&curve, RebuildTarget::ControlPoints(24), 3).unwrap();
    let (a, b) = rebuilt.curve.domain();
    assert_eq!(rebuilt.curve.point(a).xy(), ring[0]);
    assert!((rebuilt.curve.point(b).xy() - ring[0]).norm() < 1e-12);
    assert!(rebuilt.is_closed());
    assert!(report.max_deviation < 5e-3, "{}", report.max_deviation);
    assert_eq!(report.rebuilt.inflections, Some(0));
}

/// A flat half-ellipse (a sharp convex nose, no inflection) rebuilt with too few control
/// points rings: the curvature changes sign where the faired curve's never does, and the
/// report says so; with five control points it does not.
#[test]
fn a_rebuild_that_brings_wiggles_back_is_flagged() {
    let nose: Vec<Vec2> = (0..200)
        .map(|i| {
            let t = -1.4 + 2.8 * i as f64 / 199.0;
            Vec2::new(10.0 * t.cos(), 0.3 * t.sin())
        })
        .collect();
    let curve = CadCurve::from_hermite(&HermiteSpline::natural(&nose).unwrap()).unwrap();
    let (_, report) = rebuild(&curve, RebuildTarget::ControlPoints(8), 3).unwrap();
    assert_eq!(report.faired.inflections, Some(0));
    assert!(report.rebuilt.inflections > Some(0), "{report:?}");
    assert!(report.wiggles_back);
    let (_, report) = rebuild(&curve, RebuildTarget::ControlPoints(5), 3).unwrap();
    assert_eq!(report.rebuilt.inflections, Some(0));
    assert!(
        report.rebuilt.vibrations <= report.faired.vibrations,
        "{report:?}"
    );
    assert!(!report.wiggles_back);
}

#[test]
fn a_tolerance_out_of_reach_keeps_the_exact_curve() {
    let spline = SplineFunction::new(
        &[0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0],
        &[0.0, 1.0, -1.0, 2.0, 0.0, 1.0, 3.0, 0.0],
        EndCondition::ParabolicRunout,
    )
    .unwrap();
    let curve = CadCurve::from_spline_function(&spline).unwrap();
    let (kept, report) = rebuild(&curve, RebuildTarget::Tolerance(1e-12), 3).unwrap();
    assert!(report.exact_fallback);
    assert_eq!(kept.curve, curve.curve);
    assert!(report.max_deviation <= 1e-12);
    assert!(!report.wiggles_back);
}

#[test]
fn export_rebuilds_when_asked_and_refuses_what_it_cannot() {
    let curve = CadCurve::from_hermite(&HermiteSpline::natural(&planar_points(100)).unwrap()).unwrap();
    let shape = Shape::Curve(curve);
    let settings = CadSettings {
        control_points: Some(10),
        ..CadSettings::default()
    };
    let file = cad::export(&shape, Format::Step, &settings, &WriteOptions::default()).unwrap();
    let report = file.rebuild.clone().unwrap();
    assert_eq!(file.model.curves[0].curve.control_points().len(), 10);
    assert_eq!(file.model.tolerance, report.max_deviation);
    let summary = serde_json::to_value(file.summary()).unwrap();
    assert_eq!(summary["rebuild"]["control_points"], 10);
    assert!(summary["rebuild"]["faired"]["vibrations"].is_u64());
    let too_many = CadSettings {
        control_points: Some(60),
        ..CadSettings::default()
    };
    assert!(matches!(
        cad::export(&shape, Format::Step, &too_many, &WriteOptions::default()),
        Err(Error::BadParameter {
            name: "control-points",
            ..
        })
    ));
}
