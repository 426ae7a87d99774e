//! Boundaries that join (issue 46): the surface `jump-lsq` holds an edge of the faired net
//! g0/g1/g2 to a neighbour net; the report's gaps, angles and curvature jumps before and
//! after; what it refuses.

use curve_repr::Vec3;
use fairing::strategies::{Continuity, Join, JoinEdge, SurfaceJumpLsq, SurfaceJumpLsqSettings};
use fairing::Error;

/// The smooth surface the patches sample.
fn truth(x: f64, y: f64) -> Vec3 {
    Vec3::new(x, y, 0.3 * (x - 0.4).powi(2) + 0.15 * (3.0 * y).sin() * (1.0 + x) + 0.1 * x * y)
}

/// Deterministic noise in [−1, 1].
fn noise(i: usize, j: usize, s: usize) -> f64 {
    let t = ((i * 7919 + j * 104_729 + s * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
    2.0 * (t - t.floor()) - 1.0
}

/// The net over x ∈ [x0, x1] (rows, along u) × y ∈ [0, 1] (columns), noisy (amplitude
/// `amp`, seeded by `seed`) everywhere.
fn patch(rows: usize, columns: usize, x0: f64, x1: f64, amp: f64, seed: usize) -> Vec<Vec<Vec3>> {
    (0..rows)
        .map(|i| {
            (0..columns)
                .map(|j| {
                    let x = x0 + (x1 - x0) * i as f64 / (rows - 1) as f64;
                    let y = j as f64 / (columns - 1) as f64;
                    let n = Vec3::new(noise(i, j, seed), noise(i, j, seed + 1), noise(i, j, seed + 2));
                    truth(x, y) + n * amp
                })
                .collect()
        })
        .collect()
}

fn join(edge: JoinEdge, continuity: Continuity, neighbour: &[Vec<Vec3>]) -> Join {
    Join {
        edge,
        continuity,
        neighbour: neighbour.to_vec(),
        source: "first.csv".into(),
    }
}

/// Two halves of one noisy surface: the first faired alone, the second joined to it.
fn two_patches() -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let first = patch(16, 21, 0.0, 0.5, 0.003, 1);
    let first = SurfaceJumpLsq::default().run(&first).unwrap().surface.grid();
    let second = patch(16, 21, 0.5, 1.0, 0.003, 11);
    (first, second)
}

#[test]
fn surface_join_g1_holds_the_tangent_plane_where_it_was_broken() {
    let (first, second) = two_patches();
    let kept = first.clone();
    let settings = SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::U0, Continuity::G1, &first));
    let out = SurfaceJumpLsq::new(settings).run(&second).unwrap();
    assert_eq!(first, kept, "the neighbour is untouched");
    let report = &out.joins[0];
    assert_eq!(report.neighbour_edge, JoinEdge::U1);
    assert!(!report.reversed);
    eprintln!("{report:?}");
    let size = 1.0;
    assert!(report.before.gap > 1e-3, "the halves' noisy edges differ: {:?}", report.before);
    assert!(report.before.angle_degrees > 0.5, "{:?}", report.before);
    assert!(report.after.gap <= 1e-12 * size, "{:?}", report.after);
    assert!(report.after.angle_degrees <= 1e-9, "{:?}", report.after);
    assert!(out.lambda > 0.0, "the fit was kept (λ = {})", out.lambda);
}
