//! Boundaries that join (issue 46): the surface `jump-lsq` holds an edge of the faired net
//! g0/g1/g2 to a neighbour net; the report's gaps, angles and curvature jumps before and
//! after; what it refuses.

use curve_repr::{Parametrization, Vec3};
use fairing::strategies::{Continuity, Join, JoinEdge, SurfaceJumpLsq, SurfaceJumpLsqSettings};
use fairing::Error;

/// The smooth surface the patches sample.
fn truth(x: f64, y: f64) -> Vec3 {
    Vec3::new(
        x,
        y,
        0.3 * (x - 0.4).powi(2) + 0.15 * (3.0 * y).sin() * (1.0 + x) + 0.1 * x * y,
    )
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
    let size = 1.0; // the patches span a unit square

    assert!(
        report.before.gap > 1e-3,
        "the halves' noisy edges differ: {:?}",
        report.before
    );
    assert!(report.before.angle_degrees > 0.5, "{:?}", report.before);
    assert!(report.after.gap <= 1e-12 * size, "{:?}", report.after);
    assert!(report.after.angle_degrees <= 1e-9, "{:?}", report.after);
    assert!(
        out.lambda_u > 0.0 && out.lambda_v > 0.0,
        "the fit was kept (λ_u = {}, λ_v = {})",
        out.lambda_u,
        out.lambda_v
    );
}

fn rms(a: &[Vec<Vec3>], b: &[Vec<Vec3>]) -> f64 {
    let (sum, count) = a
        .iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold((0.0, 0), |(s, c), (p, q)| (s + (p - q).norm_squared(), c + 1));
    (sum / count as f64).sqrt()
}

#[test]
fn surface_join_g1_fit_still_nears_the_clean_surface() {
    let (first, second) = two_patches();
    let clean = patch(16, 21, 0.5, 1.0, 0.0, 11);
    let settings = SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::U0, Continuity::G1, &first));
    let out = SurfaceJumpLsq::new(settings).run(&second).unwrap();
    let (before, after) = (rms(&second, &clean), rms(&out.surface.grid(), &clean));
    assert!(
        after < 0.7 * before,
        "rms to the clean surface {before:e} → {after:e}"
    );
}

/// GCV's trace with a join in place (the unconstrained trace less the joins' loss,
/// `Joined::correct_with_trace_loss`) against its defining condition: with λ fixed, uniform knots and the
/// refusal rule off the fit is affine in the data, so tr H is the sum over the free nodes of
/// how far a fitted coordinate moves per unit move of its own datum (measured one node at a
/// time). g1 on u0 and, for a second shape of constraint, g1 on v1.
#[test]
fn surface_join_trace_is_the_hat_matrix_trace() {
    let (first, second) = two_patches();
    let v_neighbour: Vec<Vec<Vec3>> = patch(16, 21, 0.5, 1.0, 0.003, 21)
        .into_iter()
        .map(|row| row.into_iter().map(|p| p + Vec3::new(0.0, 1.0, 0.0)).collect())
        .collect();
    for (edge, neighbour) in [(JoinEdge::U0, &first), (JoinEdge::V1, &v_neighbour)] {
        let settings = SurfaceJumpLsqSettings {
            parametrization: Parametrization::Uniform,
            guard: false,
            ..SurfaceJumpLsqSettings::default()
        }
        .with_lambda(3.0)
        .with_join(join(edge, Continuity::G1, neighbour));
        let method = SurfaceJumpLsq::new(settings);
        let base = method.run(&second).unwrap();
        let fitted = base.surface.grid();
        let (rows, columns) = (second.len(), second[0].len());
        let held = |i: usize, j: usize| match edge {
            JoinEdge::U0 => i == 0,
            JoinEdge::V1 => j == columns - 1,
            _ => unreachable!(),
        };
        let delta = 1e-3;
        let mut trace = 0.0;
        for i in 0..rows {
            for j in 0..columns {
                if held(i, j) {
                    continue;
                }
                let mut moved = second.clone();
                moved[i][j].z += delta;
                let out = method.run(&moved).unwrap().surface.grid();
                trace += (out[i][j].z - fitted[i][j].z) / delta;
            }
        }
        assert!(
            (trace - base.dof).abs() <= 1e-6 * trace,
            "{edge:?}: tr H by moving each datum {trace}, the method's {}",
            base.dof
        );
        assert!(
            trace < (rows * columns) as f64 - 1.0,
            "{edge:?}: the fit smooths ({trace})"
        );
    }
}

#[test]
fn surface_join_g0_puts_the_edge_on_the_neighbours_bit_for_bit() {
    let (first, second) = two_patches();
    let settings = SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::U0, Continuity::G0, &first));
    let out = SurfaceJumpLsq::new(settings).run(&second).unwrap();
    let grid = out.surface.grid();
    assert_eq!(grid[0], first[15], "the edge row is the neighbour's last row");
    let report = &out.joins[0];
    assert!(
        report.before.gap > 1e-3 && report.after.gap <= 1e-12,
        "{report:?}"
    );
}

#[test]
fn surface_join_g2_on_a_v_edge_to_a_reversed_neighbour() {
    // Split across y this time; the neighbour's rows and columns both run the other way, so
    // its edge meeting our v0 is its v0, reversed.
    let transpose = |g: &[Vec<Vec3>]| -> Vec<Vec<Vec3>> {
        (0..g[0].len())
            .map(|j| g.iter().map(|r| r[j]).collect())
            .collect()
    };
    let swap = |g: Vec<Vec<Vec3>>| -> Vec<Vec<Vec3>> {
        g.into_iter()
            .map(|r| r.into_iter().map(|p| Vec3::new(p.y, p.x, p.z)).collect())
            .collect()
    };
    // Patches over y ∈ [0, 0.5] and [0.5, 1] as nets with rows along x.
    let first = swap(transpose(&patch(18, 12, 0.0, 0.5, 0.003, 3)));
    let first = SurfaceJumpLsq::default().run(&first).unwrap().surface.grid();
    let neighbour: Vec<Vec<Vec3>> = first
        .iter()
        .rev()
        .map(|r| r.iter().rev().copied().collect())
        .collect();
    let second = swap(transpose(&patch(18, 12, 0.5, 1.0, 0.003, 21)));
    let settings =
        SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::V0, Continuity::G2, &neighbour));
    let out = SurfaceJumpLsq::new(settings).run(&second).unwrap();
    let report = &out.joins[0];
    assert_eq!(
        (report.neighbour_edge, report.reversed),
        (JoinEdge::V0, true),
        "{report:?}"
    );
    assert!(
        report.before.angle_degrees > 0.5 && report.before.curvature_jump > 0.1,
        "{report:?}"
    );
    assert!(report.after.gap <= 1e-12, "{report:?}");
    assert!(report.after.angle_degrees <= 1e-9, "{report:?}");
    assert!(report.after.curvature_jump <= 1e-9, "{report:?}");
}

#[test]
fn surface_join_a_middle_patch_held_g1_on_both_sides() {
    // Three patches with uniform knots: the middle one's v knots are both neighbours', so
    // both joins are exact.
    let uniform = || SurfaceJumpLsqSettings::default().with_parametrization(Parametrization::Uniform);
    let faired = |g: Vec<Vec<Vec3>>| SurfaceJumpLsq::new(uniform()).run(&g).unwrap().surface.grid();
    let left = faired(patch(12, 15, 0.0, 0.3, 0.003, 5));
    let right = faired(patch(12, 15, 0.7, 1.0, 0.003, 7));
    let middle = patch(16, 15, 0.3, 0.7, 0.003, 9);
    let both = |settings: SurfaceJumpLsqSettings| {
        settings
            .with_join(join(JoinEdge::U0, Continuity::G1, &left))
            .with_join(join(JoinEdge::U1, Continuity::G1, &right))
    };
    let out = SurfaceJumpLsq::new(both(uniform())).run(&middle).unwrap();
    for report in &out.joins {
        assert!(report.before.angle_degrees > 0.5, "{report:?}");
        assert!(report.after.gap <= 1e-12, "{report:?}");
        assert!(report.after.angle_degrees <= 1e-9, "{report:?}");
    }
    // Chord-length knots: the middle takes the first join's knots along the edge; the right
    // neighbour's differ a little, so across that edge the nodes meet exactly and the edge
    // curves and tangent planes nearly between them.
    let out = SurfaceJumpLsq::new(both(SurfaceJumpLsqSettings::default()))
        .run(&middle)
        .unwrap();
    assert!(out.joins[0].after.angle_degrees <= 1e-9, "{:?}", out.joins[0]);
    let second = &out.joins[1];
    assert!(second.after.gap <= 0.2 * second.before.gap, "{second:?}");
    assert!(
        second.after.angle_degrees <= 0.02 * second.before.angle_degrees,
        "{second:?}"
    );
}

#[test]
fn surface_join_g0_keeps_fixed_nodes_and_the_band() {
    let (first, second) = two_patches();
    let band = 0.002;
    let settings = SurfaceJumpLsqSettings::default()
        .with_join(join(JoinEdge::U0, Continuity::G0, &first))
        .with_fixed([(7, 9)])
        .with_max_distance(band);
    let out = SurfaceJumpLsq::new(settings).run(&second).unwrap();
    let grid = out.surface.grid();
    assert_eq!(grid[7][9], second[7][9]);
    assert_eq!(grid[0], first[15]);
    for i in 1..16 {
        for j in 0..21 {
            assert!((grid[i][j] - second[i][j]).norm() <= band, "node ({i}, {j})");
        }
    }
}

fn refused(settings: SurfaceJumpLsqSettings, net: &[Vec<Vec3>]) -> String {
    match SurfaceJumpLsq::new(settings).run(net) {
        Err(Error::Refused { reason, .. }) => reason,
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn surface_join_refusals_say_why() {
    let (first, second) = two_patches();
    let short: Vec<Vec<Vec3>> = first.iter().map(|r| r[..20].to_vec()).collect();
    let reason = refused(
        SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::U0, Continuity::G1, &short)),
        &second,
    );
    assert!(
        reason.contains("21 nodes") && reason.contains("16 × 20"),
        "{reason}"
    );
    let reason = refused(
        SurfaceJumpLsqSettings::default()
            .with_join(join(JoinEdge::U0, Continuity::G1, &first))
            .with_fixed([(3, 3)]),
        &second,
    );
    assert!(reason.contains("fixed nodes"), "{reason}");
    let reason = refused(
        SurfaceJumpLsqSettings::default()
            .with_join(join(JoinEdge::U0, Continuity::G0, &first))
            .with_fixed([(0, 3)]),
        &second,
    );
    assert!(reason.contains("fixed node (0, 3)"), "{reason}");
    let reason = refused(
        SurfaceJumpLsqSettings::default()
            .with_join(join(JoinEdge::U0, Continuity::G1, &first))
            .with_join(join(JoinEdge::U0, Continuity::G0, &first)),
        &second,
    );
    assert!(reason.contains("two joins on edge u0"), "{reason}");
    let side: Vec<Vec<Vec3>> = (0..16).map(|i| (0..16).map(|j| second[i][j]).collect()).collect();
    let reason = refused(
        SurfaceJumpLsqSettings::default()
            .with_join(join(JoinEdge::U0, Continuity::G1, &first))
            .with_join(join(JoinEdge::V0, Continuity::G1, &side)),
        &second,
    );
    assert!(reason.contains("u edge and a v edge"), "{reason}");
    // A tube closed along u has no u0 edge.
    let tube: Vec<Vec<Vec3>> = (0..13)
        .map(|i| {
            let a = std::f64::consts::TAU * (i % 12) as f64 / 12.0;
            (0..21)
                .map(|j| Vec3::new(a.cos(), a.sin(), j as f64 * 0.1))
                .collect()
        })
        .collect();
    let reason = refused(
        SurfaceJumpLsqSettings::default().with_join(join(JoinEdge::V0, Continuity::G1, &first)),
        &tube,
    );
    assert!(reason.contains("closes up"), "{reason}");
}
