//! The surface `jump-lsq` through the catalogue (issue 46): `g0` keeps the boundary bit for
//! bit, fixed nodes and the tolerance band hold, `g1` is refused, and on a noisy net the
//! automatic λ brings the nodes nearer the clean surface.

use curve_repr::Vec3;
use fairing::catalog::{Catalog, Grid, MethodKind, ParameterMap, SurfaceJob, SurfaceRun};
use fairing::{Constraints, EndClamp, Error};

/// A smooth bowl-and-wave net and its noisy copy (deterministic noise of amplitude `noise`).
fn nets(rows: usize, columns: usize, noise: f64) -> (Grid, Grid) {
    let mut clean = Vec::new();
    let mut noisy = Vec::new();
    for i in 0..rows {
        for j in 0..columns {
            let (x, y) = (i as f64 / (rows - 1) as f64, j as f64 / (columns - 1) as f64);
            let p = Vec3::new(x, y, 0.3 * (x - 0.5).powi(2) + 0.1 * (3.0 * y).sin() * x);
            let h = |s: usize| {
                let t = ((i * 7919 + j * 104_729 + s * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
                2.0 * (t - t.floor()) - 1.0
            };
            clean.push(p);
            noisy.push(p + Vec3::new(h(1), h(2), h(3)) * noise);
        }
    }
    let grid = |points| Grid {
        rows,
        columns,
        points,
    };
    (grid(clean), grid(noisy))
}

fn run(grid: &Grid, constraints: &Constraints) -> Result<SurfaceRun, Error> {
    let catalog = Catalog::builtin();
    let entry = catalog.method(MethodKind::Surface, "jump-lsq").unwrap();
    let settings = entry.settings(&ParameterMap::default()).unwrap();
    let job = SurfaceJob {
        method: "jump-lsq",
        grid,
        constraints,
        bad_points: &[],
        catalog: &catalog,
    };
    entry.fair_surface(&settings, &job)
}

fn rms(a: &[Vec3], b: &[Vec3]) -> f64 {
    (a.iter().zip(b).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt()
}

#[test]
fn g0_keeps_the_boundary_bit_for_bit_and_the_interior_nears_the_truth() {
    let (clean, noisy) = nets(20, 24, 0.004);
    let out = run(&noisy, &Constraints::default().with_end_clamp(EndClamp::G0)).unwrap();
    for k in noisy.boundary() {
        assert_eq!(out.grid.points[k], noisy.points[k], "boundary node {k}");
    }
    assert!(!out.moved.is_empty());
    let interior: Vec<usize> = (0..noisy.points.len())
        .filter(|k| !noisy.boundary().contains(k))
        .collect();
    let pick = |p: &[Vec3]| interior.iter().map(|&k| p[k]).collect::<Vec<_>>();
    let (before, after) = (
        rms(&pick(&noisy.points), &pick(&clean.points)),
        rms(&pick(&out.grid.points), &pick(&clean.points)),
    );
    assert!(after < 0.8 * before, "RMS to the clean net {before} -> {after}");
    assert!(out.extras["lambda_u"].as_f64().unwrap() > 0.0);
    assert!(out.extras["lambda_v"].as_f64().unwrap() > 0.0);
    // G0 holds the boundary lines: the exact path fits the 18 × 22 interior lines.
    assert_eq!(out.extras["basis_u"].as_u64(), Some(18));
    assert_eq!(out.extras["basis_v"].as_u64(), Some(22));
}

#[test]
fn fixed_nodes_and_the_tolerance_band_hold() {
    let (_, noisy) = nets(15, 15, 0.01);
    let fixed = [0, 16, 100, 112, 224];
    let band = 0.004;
    let out = run(
        &noisy,
        &Constraints::default().with_fixed(fixed).with_tolerance(band),
    )
    .unwrap();
    for k in fixed {
        assert_eq!(out.grid.points[k], noisy.points[k], "fixed node {k}");
    }
    let widest = out
        .grid
        .points
        .iter()
        .zip(&noisy.points)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    assert!(widest <= band, "{widest} > {band}");
    assert!(!out.moved.is_empty());
}

#[test]
fn tangent_and_curvature_clamps_and_radii_are_refused() {
    let (_, noisy) = nets(6, 6, 0.01);
    for constraints in [
        Constraints::default().with_end_clamp(EndClamp::G1),
        Constraints::default().with_end_clamp(EndClamp::G2),
        Constraints::default().with_restraining_radii(vec![1.0; 36]),
    ] {
        assert!(
            matches!(run(&noisy, &constraints), Err(Error::Refused { .. })),
            "{constraints:?}"
        );
    }
}
