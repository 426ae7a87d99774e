//! Shapes shared by the test modules.

use cad::{CadCurve, CadSurface};
use curve_repr::{
    BicubicSplineSurface, EndCondition, HermiteEnds, HermiteSettings, HermiteSpline, Interpolation,
    InterpolationSettings, NurbsSurface, Parametrization, SplineFunction, Vec2, Vec3,
};

/// A path under the repository's `data/`.
pub(crate) fn data(path: &str) -> String {
    format!("{}/../../data/{path}", env!("CARGO_MANIFEST_DIR"))
}

pub(crate) fn function(n: usize) -> SplineFunction {
    let x: Vec<f64> = (0..n)
        .map(|i| -1.5 + i as f64 * 0.13 + 0.02 * (i as f64).cos())
        .collect();
    let y: Vec<f64> = x
        .iter()
        .map(|&v| (0.9 * v).sin() * 2.0 + 0.05 * (7.0 * v).sin())
        .collect();
    SplineFunction::new(&x, &y, EndCondition::ParabolicRunout).unwrap()
}

pub(crate) fn planar_points(n: usize) -> Vec<Vec2> {
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.1;
            Vec2::new(20.0 * a.cos() + 0.1 * (9.0 * a).sin(), 7.0 * a.sin())
        })
        .collect()
}

pub(crate) fn curves() -> Vec<CadCurve> {
    let closed = HermiteSpline::new(
        &planar_points(30)[..28],
        &HermiteSettings::default().with_ends(HermiteEnds::Closed),
    )
    .unwrap();
    let helix: Vec<Vec3> = (0..40)
        .map(|i| {
            let a = i as f64 * 0.25;
            Vec3::new(3.0 * a.cos(), 3.0 * a.sin(), 1e-3 * a + 1e5)
        })
        .collect();
    let section = planar_points(12);
    let interpolation = Interpolation::with_parametrization(
        &section,
        Parametrization::ChordLength,
        InterpolationSettings::default(),
    )
    .unwrap();
    let weights: Vec<f64> = (0..interpolation.control_count())
        .map(|i| 1.0 / 3.0 + (i as f64).sqrt())
        .collect();
    let rational = interpolation.solve(&weights).unwrap();
    vec![
        CadCurve::from_spline_function(&function(50))
            .unwrap()
            .with_name("function"),
        CadCurve::from_hermite(&HermiteSpline::natural(&planar_points(25)).unwrap())
            .unwrap()
            .with_name("planar"),
        CadCurve::from_hermite(&closed).unwrap().with_name("closed"),
        CadCurve::from_hermite(&HermiteSpline::natural(&helix).unwrap())
            .unwrap()
            .with_name("far helix"),
        CadCurve::from_nurbs(&rational, &section, interpolation.params())
            .unwrap()
            .with_name("rational"),
    ]
}

pub(crate) fn grid(rows: usize, columns: usize) -> Vec<Vec<Vec3>> {
    (0..rows)
        .map(|i| {
            (0..columns)
                .map(|j| {
                    let (u, v) = (i as f64 * 0.7, j as f64 * 1.1 + 0.05 * i as f64);
                    Vec3::new(u, v, (u * 0.8).sin() * (v * 0.5).cos() / 3.0)
                })
                .collect()
        })
        .collect()
}

pub(crate) fn surfaces() -> Vec<CadSurface> {
    let bicubic = BicubicSplineSurface::new(&grid(6, 5)).unwrap();
    let mut weights = vec![vec![1.0; 4]; 4];
    weights[1][2] = 2.0 / 3.0;
    let rational = NurbsSurface::new(
        3,
        3,
        vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
        vec![0.1, 0.1, 0.1, 0.1, 0.7, 0.7, 0.7, 0.7],
        (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| Vec3::new(i as f64, j as f64, ((i * j) as f64).sqrt()))
                    .collect()
            })
            .collect(),
        weights,
    )
    .unwrap();
    vec![
        CadSurface::from_bicubic(&bicubic).unwrap().with_name("panel"),
        CadSurface::new(rational).with_name("rational panel"),
    ]
}
