//! Sapidis–Farin on every airfoil of `data/` with its default settings: the shape is kept
//! (M_d below 1 % of the chord), where the paper's unbounded run moved the UA(2)-180 upper
//! surface by 14 % of the chord.

use std::path::Path;

use curve_repr::Vec2;
use fairing::strategies::{CurveDomain, SapidisFarin, SapidisFarinSettings};
use fairing::Pipeline;

/// The x, y columns of a CSV file of `data/` (one header line).
pub(super) fn read(path: &Path) -> Vec<Vec2> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .filter_map(|line| {
            let mut f = line.split(',').map(|v| v.trim().parse::<f64>());
            Some(Vec2::new(f.next()?.ok()?, f.next()?.ok()?))
        })
        .collect()
}

/// M_d of a Sapidis–Farin run on `points` (as a function y(x) when x increases strictly).
fn largest_move(points: &[Vec2], settings: SapidisFarinSettings) -> f64 {
    let function = points.windows(2).all(|w| w[1].x > w[0].x);
    let settings = settings.with_domain(if function {
        CurveDomain::Function
    } else {
        CurveDomain::Parametric
    });
    let steps = settings.max_iterations + 1;
    let result = Pipeline::new(SapidisFarin::<2>::new(settings))
        .with_max_iterations(steps)
        .run(points.to_vec())
        .unwrap();
    points
        .iter()
        .zip(&result.points)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max)
}

fn chord(points: &[Vec2]) -> f64 {
    let (lo, hi) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.x), hi.max(p.x))
        });
    hi - lo
}

#[test]
fn every_airfoil_in_data_keeps_its_shape_by_default() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
    let mut files: Vec<_> = std::fs::read_dir(&data)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.file_name().unwrap().to_string_lossy().starts_with("airfoil_"))
        .flat_map(|dir| std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()))
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .collect();
    files.sort();
    assert!(files.len() >= 20, "{files:?}");
    for file in files {
        let points = read(&file);
        let m_d = largest_move(&points, SapidisFarinSettings::default());
        let chord = chord(&points);
        assert!(
            m_d < 0.01 * chord,
            "{}: M_d = {m_d}, chord {chord}",
            file.display()
        );
    }
}

#[test]
fn the_papers_unbounded_run_doubles_the_ua2_180_thickness() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
    let points = read(&data.join("airfoil_ua2-180/ua2-180_upper.csv"));
    let m_d = largest_move(&points, SapidisFarinSettings::paper());
    assert!(m_d > 0.05, "M_d = {m_d}");
}
