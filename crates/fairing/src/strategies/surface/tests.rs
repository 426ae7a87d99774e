//! Each closed form against its defining condition; the runs against their promises.

use curve_repr::{BicubicSplineSurface, Side, Surface, Vec3};
use fairness::surface::thin_plate_cell;
use fairness::GaussLegendre;

use super::closed_form::{fixed_tangent_targets, limit_targets};
use super::network::Network;
use super::thin_plate::{thin_plate_targets, value_basis};
use super::*;
use crate::strategies::strain_energy::hermite_energy;

/// A smooth, non-uniformly spaced grid with a few bumps.
fn bumpy(u_count: usize, v_count: usize) -> Vec<Vec<Vec3>> {
    (0..u_count)
        .map(|i| {
            (0..v_count)
                .map(|j| {
                    let x = i as f64 + 0.15 * (j as f64 * 0.7).sin() + 0.05 * (i * i) as f64;
                    let y = 0.8 * j as f64 + 0.1 * (i as f64).cos();
                    let bump = match (i, j) {
                        (3, 2) => 0.4,
                        (4, 4) => -0.3,
                        (5, 2) => 0.25,
                        _ => 0.0,
                    };
                    Vec3::new(x, y, 0.3 * (0.4 * x).sin() + 0.2 * (0.5 * y).cos() + bump)
                })
                .collect()
        })
        .collect()
}

fn network_of(grid: &[Vec<Vec3>]) -> (BicubicSplineSurface, Network) {
    let surface = BicubicSplineSurface::new(grid).unwrap();
    let network = Network::new(
        surface.points(),
        surface.u_knots(),
        surface.v_knots(),
        (false, false),
    )
    .unwrap();
    (surface, network)
}

/// Eq. 18 / 22 / 24: the energy of the network segments touching the group, the group's points
/// replaced by `positions`, every tangent held.
fn local_energy(
    network: &Network,
    knots: (&[f64], &[f64]),
    group: &[(usize, usize)],
    positions: &[Vec3],
) -> f64 {
    let point = |i: usize, j: usize| match group.iter().position(|&g| g == (i, j)) {
        Some(a) => positions[a],
        None => network.point(i, j),
    };
    let (uk, vk) = knots;
    let mut segments_u: Vec<(usize, usize)> = group.iter().flat_map(|&(i, j)| [(i - 1, j), (i, j)]).collect();
    let mut segments_v: Vec<(usize, usize)> = group.iter().flat_map(|&(i, j)| [(i, j - 1), (i, j)]).collect();
    segments_u.sort_unstable();
    segments_u.dedup();
    segments_v.sort_unstable();
    segments_v.dedup();
    let mut e = 0.0;
    for (l, j) in segments_u {
        e += hermite_energy(
            point(l, j),
            point(l + 1, j),
            network.u_tangent(l, j),
            network.u_tangent(l + 1, j),
            uk[l + 1] - uk[l],
        );
    }
    for (i, k) in segments_v {
        e += hermite_energy(
            point(i, k),
            point(i, k + 1),
            network.v_tangent(i, k),
            network.v_tangent(i, k + 1),
            vk[k + 1] - vk[k],
        );
    }
    e
}

/// Central-difference gradient of `f` in every coordinate of every position.
fn gradient(f: &dyn Fn(&[Vec3]) -> f64, at: &[Vec3], step: f64) -> Vec<Vec3> {
    (0..at.len())
        .map(|a| {
            let mut g = Vec3::zeros();
            for c in 0..3 {
                let (mut plus, mut minus) = (at.to_vec(), at.to_vec());
                plus[a][c] += step;
                minus[a][c] -= step;
                g[c] = (f(&plus) - f(&minus)) / (2.0 * step);
            }
            g
        })
        .collect()
}

fn norm(g: &[Vec3]) -> f64 {
    g.iter().map(|v| v.norm_squared()).sum::<f64>().sqrt()
}

const GROUPS: [&[(usize, usize)]; 4] = [
    &[(3, 2)],
    &[(3, 2), (4, 2)],
    &[(4, 3), (4, 4)],
    &[(3, 2), (4, 2), (3, 3), (4, 3)],
];

#[test]
fn eq20_23_25_minimise_their_objectives_with_tangents_held() {
    let (surface, network) = network_of(&bumpy(8, 7));
    let knots = (surface.u_knots(), surface.v_knots());
    for group in GROUPS {
        let targets = fixed_tangent_targets(&network, group).unwrap();
        let original: Vec<Vec3> = group.iter().map(|&(i, j)| network.point(i, j)).collect();
        let f = |p: &[Vec3]| local_energy(&network, knots, group, p);
        let g_target = norm(&gradient(&f, &targets, 1e-5));
        let g_original = norm(&gradient(&f, &original, 1e-5));
        assert!(
            g_original > 1e-2,
            "{group:?}: the bump must be visible, |grad| {g_original}"
        );
        assert!(
            g_target < 1e-7 * g_original,
            "{group:?}: |grad| {g_target} vs {g_original}"
        );
        // And a minimum, not a saddle: every nearby point is worse.
        let e = f(&targets);
        for k in 0..24 {
            let perturbed: Vec<Vec3> = targets
                .iter()
                .enumerate()
                .map(|(a, p)| {
                    p + Vec3::new(
                        ((k + a) as f64).sin(),
                        ((3 * k + a) as f64).cos(),
                        (k as f64 * 0.37).sin(),
                    ) * 1e-3
                })
                .collect();
            assert!(f(&perturbed) > e, "{group:?}");
        }
    }
}

#[test]
fn eq20_as_printed_is_the_one_point_case() {
    let (surface, network) = network_of(&bumpy(8, 7));
    let (i, j) = (4, 3);
    let (uk, vk) = (surface.u_knots(), surface.v_knots());
    let (ua, ub) = (1.0 / (uk[i] - uk[i - 1]), 1.0 / (uk[i + 1] - uk[i]));
    let (va, vb) = (1.0 / (vk[j] - vk[j - 1]), 1.0 / (vk[j + 1] - vk[j]));
    let p = |a, b| network.point(a, b);
    let printed = ((p(i - 1, j) * ua.powi(3)
        + p(i + 1, j) * ub.powi(3)
        + p(i, j - 1) * va.powi(3)
        + p(i, j + 1) * vb.powi(3))
        * 2.0
        + closed_form::alpha(&network, i, j)
        + closed_form::beta(&network, i, j))
        / closed_form::tau(&network, i, j);
    let general = fixed_tangent_targets(&network, &[(i, j)]).unwrap()[0];
    assert!((printed - general).norm() < 1e-12 * printed.norm());
}

#[test]
fn limits_zero_the_jump_sum_with_tangents_resolved() {
    let (_, network) = network_of(&bumpy(8, 7));
    for group in GROUPS {
        let targets = limit_targets(&network, group).unwrap();
        let before: f64 = group
            .iter()
            .map(|&(i, j)| (network.u_jump(i, j) + network.v_jump(i, j)).norm())
            .sum();
        let mut moved = network.clone();
        let moves: Vec<_> = group.iter().copied().zip(targets).collect();
        moved.move_points(&moves).unwrap();
        let after: f64 = group
            .iter()
            .map(|&(i, j)| (moved.u_jump(i, j) + moved.v_jump(i, j)).norm())
            .sum();
        assert!(before > 1e-1, "{group:?}");
        assert!(after < 1e-10 * before, "{group:?}: {after} vs {before}");
        // The limit minimises the whole network energy over the group.
        let energy = |p: &[Vec3]| {
            let mut n = network.clone();
            let moves: Vec<_> = group.iter().copied().zip(p.iter().copied()).collect();
            n.move_points(&moves).unwrap();
            n.energy()
        };
        let at: Vec<Vec3> = moves.iter().map(|m| m.1).collect();
        let g = norm(&gradient(&energy, &at, 1e-4));
        let original: Vec<Vec3> = group.iter().map(|&(i, j)| network.point(i, j)).collect();
        assert!(g < 1e-6 * norm(&gradient(&energy, &original, 1e-4)), "{group:?}");
    }
}

#[test]
fn the_one_point_limit_is_the_general_solve_of_one() {
    let (_, network) = network_of(&bumpy(8, 7));
    for i in 1..7 {
        for j in 1..6 {
            let general = limit_targets(&network, &[(i, j)]).unwrap()[0];
            let one = closed_form::limit_target(&network, i, j).unwrap();
            assert!(
                (general - one).norm() <= 1e-12 * (1.0 + general.norm()),
                "({i}, {j})"
            );
        }
    }
    assert!(closed_form::limit_target(&network, 0, 3).is_none());
}

#[test]
fn iterating_eq20_converges_to_the_eq21_limit() {
    let (_, mut network) = network_of(&bumpy(8, 7));
    let node = (3, 2);
    let limit = limit_targets(&network, &[node]).unwrap()[0];
    let start = network.point(node.0, node.1);
    for _ in 0..200 {
        let next = fixed_tangent_targets(&network, &[node]).unwrap()[0];
        network.move_points(&[(node, next)]).unwrap();
    }
    let reached = network.point(node.0, node.1);
    assert!(
        (reached - limit).norm() < 1e-9 * (limit - start).norm(),
        "{reached:?} vs {limit:?}"
    );
}

#[test]
fn network_matches_the_surface_after_moves() {
    let (mut surface, mut network) = network_of(&bumpy(9, 8));
    let moves = [
        ((2, 3), Vec3::new(1.0, 2.0, 0.5)),
        ((6, 3), Vec3::new(7.0, 2.5, -0.2)),
        ((6, 5), Vec3::new(6.5, 4.0, 0.1)),
    ];
    network.move_points(&moves).unwrap();
    surface.move_points(&moves).unwrap();
    let e = surface.network_strain_energy();
    assert!((network.energy() - e).abs() < 1e-10 * e);
    for i in 1..8 {
        for j in 1..7 {
            let z = surface.z(i, j).unwrap();
            assert!((network.z(i, j) - z).abs() < 1e-9 * (1.0 + z));
        }
    }
}

/// The surface with the group's points displaced by `deltas`, tangents and twists held: the
/// base surface plus Σ B_a Δ_a, B_a the bicubic value basis of node a (independent of
/// thin_plate.rs's quadrature; the energy comes from fairness's thin_plate_cell).
struct Displaced<'a> {
    base: &'a BicubicSplineSurface,
    group: &'a [(usize, usize)],
    deltas: Vec<Vec3>,
}

impl Surface for Displaced<'_> {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        self.base.domain()
    }
    fn partial_from(&self, u: f64, v: f64, du: usize, dv: usize, su: Side, sv: Side) -> Option<Vec3> {
        let mut value = self.base.partial_from(u, v, du, dv, su, sv)?;
        let (uk, vk) = (self.base.u_knots(), self.base.v_knots());
        for (&(i, j), d) in self.group.iter().zip(&self.deltas) {
            let factor = |knots: &[f64], k: usize, t: f64, order: usize| -> f64 {
                if t >= knots[k - 1] && t <= knots[k] {
                    let h = knots[k] - knots[k - 1];
                    value_basis(true, (t - knots[k - 1]) / h)[order] / h.powi(order as i32)
                } else if t > knots[k] && t <= knots[k + 1] {
                    let h = knots[k + 1] - knots[k];
                    value_basis(false, (t - knots[k]) / h)[order] / h.powi(order as i32)
                } else {
                    0.0
                }
            };
            value += d * (factor(uk, i, u, du) * factor(vk, j, v, dv));
        }
        Some(value)
    }
}

#[test]
fn thin_plate_targets_minimise_eq27_29() {
    let surface = BicubicSplineSurface::new(&bumpy(8, 7)).unwrap();
    let rule = GaussLegendre::new(5).unwrap();
    for group in GROUPS {
        let targets = thin_plate_targets(&surface, group).unwrap().unwrap();
        let energy = |p: &[Vec3]| {
            let deltas = group
                .iter()
                .zip(p)
                .map(|(&(i, j), q)| q - surface.point(i, j).unwrap())
                .collect();
            let displaced = Displaced {
                base: &surface,
                group,
                deltas,
            };
            let mut cells: Vec<(usize, usize)> = group
                .iter()
                .flat_map(|&(i, j)| [(i - 1, j - 1), (i - 1, j), (i, j - 1), (i, j)])
                .collect();
            cells.sort_unstable();
            cells.dedup();
            let (uk, vk) = (surface.u_knots(), surface.v_knots());
            cells
                .iter()
                .map(|&(l, k)| {
                    thin_plate_cell(&displaced, (uk[l], uk[l + 1]), (vk[k], vk[k + 1]), &rule).unwrap()
                })
                .sum::<f64>()
        };
        let original: Vec<Vec3> = group.iter().map(|&(i, j)| surface.point(i, j).unwrap()).collect();
        let g0 = norm(&gradient(&energy, &original, 1e-5));
        let g = norm(&gradient(&energy, &targets, 1e-5));
        assert!(g0 > 1e-2 && g < 1e-6 * g0, "{group:?}: {g} vs {g0}");
    }
}

#[test]
fn grouping_follows_step_1_3() {
    let groups = group_bad_points(&[(3, 3), (3, 4), (5, 5), (6, 6), (2, 2), (8, 1)]);
    assert_eq!(
        groups,
        vec![
            vec![(3, 3), (3, 4)],
            vec![(5, 5), (6, 5), (5, 6), (6, 6)],
            vec![(2, 2)],
            vec![(8, 1)]
        ]
    );
}

fn spheres_hold(result: &SurfaceFairingResult) {
    let radii = result.radii.as_ref().unwrap();
    let (u_count, v_count) = result.surface.shape();
    for i in 1..u_count - 1 {
        for j in 1..v_count - 1 {
            let k = i * v_count + j;
            let moved = (result.surface.points()[k] - result.original[k]).norm();
            assert!(
                moved <= radii[k] * (1.0 + 1e-12),
                "({i}, {j}) moved {moved} > {}",
                radii[k]
            );
        }
    }
}

#[test]
fn automatic_energy_never_rises_and_points_stay_in_their_spheres() {
    for settings in [
        SurfaceFairingSettings::zhang_cheng().with_tolerance(1e-9),
        SurfaceFairingSettings::zhang_cheng().with_replacement(Replacement::Iterated),
        SurfaceFairingSettings::kjellander().with_max_steps(400),
    ] {
        let result = SurfaceFairing::new(settings.clone()).run(&bumpy(10, 9)).unwrap();
        let mut previous = result.start.energy;
        for step in &result.history {
            assert!(
                step.energy <= previous * (1.0 + 1e-12),
                "{settings:?}: {} > {previous}",
                step.energy
            );
            previous = step.energy;
        }
        assert!(previous < 0.9 * result.start.energy, "{settings:?}");
        spheres_hold(&result);
        // The history's energies are the output's measure: over chord-length knots of the
        // final points, whatever knots the method works on.
        let rebuilt = BicubicSplineSurface::new(&result.surface.grid()).unwrap();
        let e = rebuilt.network_strain_energy();
        assert!((e - previous).abs() < 1e-9 * e);
    }
}

#[test]
fn fixed_points_and_distance_limit_hold() {
    let fixed = [(3, 2), (0, 4), (4, 4)];
    let settings = SurfaceFairingSettings::zhang_cheng()
        .with_fixed(fixed)
        .with_max_distance(0.05);
    let grid = bumpy(10, 9);
    let result = SurfaceFairing::new(settings).run(&grid).unwrap();
    for (i, j) in fixed {
        assert_eq!(result.surface.point(i, j).unwrap(), grid[i][j]);
    }
    for (p, q) in result.surface.points().iter().zip(&result.original) {
        assert!((p - q).norm() <= 0.05 * (1.0 + 1e-12));
    }
    assert!(!result.moved.is_empty());
    // The corners never move (the boundary curves' end points).
    for (i, j) in [(0, 0), (9, 0), (0, 8), (9, 8)] {
        assert_eq!(result.surface.point(i, j).unwrap(), grid[i][j]);
    }
}

#[test]
fn interactive_moves_only_the_named_points() {
    let grid = bumpy(10, 9);
    let bad = vec![(3, 2), (4, 2), (4, 4), (5, 3)];
    for objective in [Objective::Network, Objective::ThinPlate] {
        let settings = SurfaceFairingSettings::zhang_cheng()
            .with_mode(SurfaceMode::Interactive(bad.clone()))
            .with_objective(objective)
            .with_replacement(Replacement::Iterated)
            .with_max_steps(20);
        let result = SurfaceFairing::new(settings).run(&grid).unwrap();
        // The named points, and the 2×2 blocks that diagonal pairs among them span (step 1.3).
        let mut allowed = bad.clone();
        for &(i, j) in &bad {
            for &(a, b) in &bad {
                if a == i + 1 && b.abs_diff(j) == 1 {
                    let j0 = j.min(b);
                    allowed.extend([(i, j0), (i + 1, j0), (i, j0 + 1), (i + 1, j0 + 1)]);
                }
            }
        }
        assert!(
            result.moved.iter().all(|node| allowed.contains(node)),
            "{objective:?}: {:?}",
            result.moved
        );
        assert!(!result.moved.contains(&(3, 3)) && !result.moved.contains(&(6, 2)));
        assert!(!result.moved.is_empty());
        let before = BicubicSplineSurface::new(&grid).unwrap();
        let z_before = bad
            .iter()
            .map(|&(i, j)| before.z(i, j).unwrap())
            .fold(0.0, f64::max);
        let z_after = bad
            .iter()
            .map(|&(i, j)| result.surface.z(i, j).unwrap())
            .fold(0.0, f64::max);
        assert!(z_after < 0.5 * z_before, "{objective:?}: {z_after} vs {z_before}");
    }
}

#[test]
fn bad_settings_are_errors() {
    let grid = bumpy(5, 5);
    let run = |s: SurfaceFairingSettings| SurfaceFairing::new(s).run(&grid);
    assert!(matches!(
        run(SurfaceFairingSettings::default().with_tolerance(f64::NAN)),
        Err(Error::BadParameter { .. })
    ));
    assert!(matches!(
        run(SurfaceFairingSettings::default().with_fixed([(5, 0)])),
        Err(Error::BadConstraint { .. })
    ));
    assert!(matches!(
        run(SurfaceFairingSettings::default().with_mode(SurfaceMode::Interactive(vec![(0, 2)]))),
        Err(Error::BadConstraint { .. })
    ));
    assert!(matches!(
        run(SurfaceFairingSettings::default().with_objective(Objective::ThinPlate)),
        Err(Error::BadParameter { .. })
    ));
    let small = vec![
        vec![Vec3::zeros(), Vec3::x()],
        vec![Vec3::y(), Vec3::new(1.0, 1.0, 0.0)],
    ];
    assert!(SurfaceFairing::default().run(&small).is_err());
}

#[test]
fn boundary_curves_are_faired_by_the_curve_method_first() {
    use crate::strategies::{StrainEnergy, StrainEnergySettings};
    use crate::{Constraints, Pipeline};
    let mut grid = bumpy(9, 8);
    // Put noise on the boundary so that step 2.1 has something to do.
    for (j, p) in grid[0].iter_mut().enumerate() {
        p.z += 0.05 * ((j * 7) as f64).sin();
    }
    for (i, row) in grid.iter_mut().enumerate() {
        row[7].z += 0.04 * ((i * 5) as f64).cos();
    }
    // Step 2.1 alone: no step follows to judge it with, so no refusal rule.
    let settings = SurfaceFairingSettings::zhang_cheng()
        .with_max_steps(0)
        .with_guard(false);
    let result = SurfaceFairing::new(settings).run(&grid).unwrap();
    assert!(result.boundary_steps > 0);
    let faired = result.surface.grid();
    for curve in boundary::boundary_curves(9, 8, (false, false)) {
        let line: Vec<Vec3> = curve.iter().map(|&(i, j)| grid[i][j]).collect();
        let curve_settings =
            StrainEnergySettings::default().with_tolerance(SurfaceFairingSettings::default().tolerance);
        let expected = Pipeline::new(StrainEnergy::<3>::new(curve_settings))
            .with_constraints(Constraints::default())
            .run(line)
            .unwrap()
            .points;
        for (&(i, j), p) in curve.iter().zip(&expected) {
            assert_eq!(faired[i][j], *p, "({i}, {j})");
        }
    }
    // Nothing inside moved (no step was allowed).
    for i in 1..8 {
        for j in 1..7 {
            assert_eq!(faired[i][j], grid[i][j]);
        }
    }
}

mod properties {
    use super::super::queue::SweepQueue;
    use super::*;
    use proptest::prelude::*;

    /// A grid of random heights over slightly uneven spacing, and its network over
    /// chord-length knots (periodic along the closed directions: the last line is not
    /// repeated in the network's distinct nodes).
    fn random_network(rows: usize, columns: usize, heights: &[f64], closed: (bool, bool)) -> Network {
        let points: Vec<Vec3> = (0..rows)
            .flat_map(|i| (0..columns).map(move |j| (i, j)))
            .map(|(i, j)| {
                let h = heights[(i * 13 + j) % heights.len()];
                Vec3::new(i as f64 * (1.0 + 0.05 * j as f64), j as f64 + 0.1 * h, h)
            })
            .collect();
        let knots = |count: usize, closed: bool, step: &dyn Fn(usize) -> f64| -> Vec<f64> {
            let mut t = vec![0.0];
            for k in 0..count - usize::from(!closed) {
                t.push(t[k] + step(k));
            }
            t
        };
        let u = knots(rows, closed.0, &|k| 1.0 + 0.3 * (k as f64 * 1.3).sin().abs());
        let v = knots(columns, closed.1, &|k| 0.7 + 0.2 * (k as f64 * 0.9).cos().abs());
        Network::new(&points, &u, &v, closed).unwrap()
    }

    /// The flat index of the largest z among `live` (ties: smaller index), by a full rescan.
    fn rescan(network: &Network, live: &[bool]) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for (k, _) in live.iter().enumerate().filter(|(_, &l)| l) {
            let z = network.z_at(k);
            if best.is_none_or(|(b, _)| z > b) {
                best = Some((z, k));
            }
        }
        best.map(|b| b.1)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(32))]

        /// The local update of the network (O(window) per move) equals a full rebuild over the
        /// same knots to 1e-12 after random moves: tangents, jumps, every z and the energy.
        #[test]
        fn local_moves_equal_a_full_rebuild(
            rows in 4usize..40,
            columns in 4usize..40,
            heights in proptest::collection::vec(-1.0f64..1.0, 64),
            moves in proptest::collection::vec((0usize..1000, 0usize..1000, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 1..24),
            closed_u in any::<bool>(),
            closed_v in any::<bool>(),
        ) {
            let closed = (closed_u, closed_v);
            let mut network = random_network(rows, columns, &heights, closed);
            let nv = columns;
            let u_count = network.points().len() / nv;
            let interior: Vec<(usize, usize)> = (0..u_count)
                .flat_map(|i| (0..nv).map(move |j| (i, j)))
                .filter(|&(i, j)| network.is_interior(i, j))
                .collect();
            for &(a, b, x, y, z) in &moves {
                let (i, j) = interior[(a * 1000 + b) % interior.len()];
                let to = network.point(i, j) + Vec3::new(x, y, z);
                network.move_points(&[((i, j), to)]).unwrap();
            }
            let u_knots: Vec<f64> = {
                let s = network.u_stiffness();
                let mut t = vec![0.0];
                for k in 0..u_count - usize::from(!closed_u) { t.push(t[k] + s.step(k)); }
                t
            };
            let v_knots: Vec<f64> = {
                let s = network.v_stiffness();
                let mut t = vec![0.0];
                for k in 0..nv - usize::from(!closed_v) { t.push(t[k] + s.step(k)); }
                t
            };
            let rebuilt = Network::new(network.points(), &u_knots, &v_knots, closed).unwrap();
            let scale = |f: &dyn Fn(&Network, usize, usize) -> Vec3| {
                interior.iter().fold(1e-300f64, |m, &(i, j)| m.max(f(&rebuilt, i, j).norm()))
            };
            let (ju, jv) = (scale(&|n, i, j| n.u_jump(i, j)), scale(&|n, i, j| n.v_jump(i, j)));
            let (tu, tv) = (scale(&|n, i, j| n.u_tangent(i, j)), scale(&|n, i, j| n.v_tangent(i, j)));
            for i in 0..u_count {
                for j in 0..nv {
                    prop_assert!((network.u_jump(i, j) - rebuilt.u_jump(i, j)).norm() <= 1e-12 * ju);
                    prop_assert!((network.v_jump(i, j) - rebuilt.v_jump(i, j)).norm() <= 1e-12 * jv);
                    prop_assert!((network.u_tangent(i, j) - rebuilt.u_tangent(i, j)).norm() <= 1e-12 * tu);
                    prop_assert!((network.v_tangent(i, j) - rebuilt.v_tangent(i, j)).norm() <= 1e-12 * tv);
                    let k = i * nv + j;
                    prop_assert!(network.z_bound(k) >= rebuilt.z_at(k) * (1.0 - 1e-12));
                }
            }
            let (e, f) = (network.energy(), rebuilt.energy());
            prop_assert!((e - f).abs() <= 1e-12 * f, "{} vs {}", e, f);
        }

        /// The automatic mode's queue pops, after every move, the node a full rescan of the
        /// current z of the nodes still to come chooses.
        #[test]
        fn the_queue_pops_what_a_full_rescan_chooses(
            rows in 4usize..30,
            columns in 4usize..30,
            heights in proptest::collection::vec(-1.0f64..1.0, 64),
            steps in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0), 64),
            closed_u in any::<bool>(),
            to_limit in any::<bool>(),
        ) {
            let mut network = random_network(rows, columns, &heights, (closed_u, false));
            let count = network.points().len();
            let u_count = count / columns;
            let mut live: Vec<bool> = (0..count).map(|k| network.is_interior(k / columns, k % columns)).collect();
            let mut queue = SweepQueue::new(&network, (0..count).filter(|&k| live[k]));
            let mut made = 0;
            while let Some(k) = queue.pop(&network) {
                prop_assert_eq!(Some(k), rescan(&network, &live));
                live[k] = false;
                let (i, j) = (k / columns, k % columns);
                // The limit point (Eq. 21) or a random shove, as the sweep's moves are.
                let to = if to_limit {
                    limit_targets(&network, &[(i, j)]).unwrap()[0]
                } else {
                    let (x, y, z) = steps[made % steps.len()];
                    network.point(i, j) + Vec3::new(x, y, z)
                };
                network.move_points(&[((i, j), to)]).unwrap();
                queue.moved(&mut network, i, j);
                made += 1;
            }
            prop_assert_eq!(rescan(&network, &live), None);
            prop_assert_eq!(made, (0..u_count).flat_map(|i| (0..columns).map(move |j| (i, j))).filter(|&(i, j)| network.is_interior(i, j)).count());
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Random 4–7 × 4–7 grids with random heights: the automatic run never raises the
        /// energy, keeps every point in its sphere and every fixed node in place.
        #[test]
        fn automatic_runs_keep_their_promises(
            rows in 4usize..8,
            columns in 4usize..8,
            heights in proptest::collection::vec(-1.0f64..1.0, 49),
            fixed_index in 0usize..49,
            kjellander in any::<bool>(),
            sort in any::<bool>(),
        ) {
            let grid: Vec<Vec<Vec3>> = (0..rows)
                .map(|i| (0..columns).map(|j| Vec3::new(i as f64 * (1.0 + 0.1 * j as f64), j as f64, heights[i * 7 + j])).collect())
                .collect();
            let fixed = (fixed_index % rows, (fixed_index / 7) % columns);
            let order = if sort { SweepOrder::Sort } else { SweepOrder::Queue };
            let base = if kjellander { SurfaceFairingSettings::kjellander().with_max_steps(300) } else { SurfaceFairingSettings::zhang_cheng().with_order(order) };
            let result = SurfaceFairing::new(base.with_fixed([fixed])).run(&grid).unwrap();
            // The refusal rules: neither the energy nor the largest z_ij ever rises.
            let (mut previous, mut previous_z) = (result.start.energy, result.start.max_z);
            for step in &result.history {
                prop_assert!(step.energy <= previous * (1.0 + 1e-12) + 1e-300);
                prop_assert!(step.max_z <= previous_z * (1.0 + 1e-12) + 1e-300);
                previous = step.energy;
                previous_z = step.max_z;
            }
            spheres_hold(&result);
            prop_assert_eq!(result.surface.point(fixed.0, fixed.1).unwrap(), grid[fixed.0][fixed.1]);
        }
    }
}

#[test]
fn a_nurbs_surface_is_faired_through_its_control_net() {
    use curve_repr::NurbsSurface;
    let net = bumpy(7, 6);
    let weights: Vec<Vec<f64>> = (0..7)
        .map(|i| (0..6).map(|j| 1.0 + 0.1 * ((i + j) % 3) as f64).collect())
        .collect();
    let knots_u = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0, 4.0, 4.0];
    let knots_v = vec![0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 3.0, 3.0, 3.0, 3.0];
    let nurbs = NurbsSurface::new(
        3,
        3,
        knots_u.clone(),
        knots_v.clone(),
        net.clone(),
        weights.clone(),
    )
    .unwrap();
    let fairing = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng());
    let (faired, result) = fairing.run_control_net(&nurbs).unwrap();
    let direct = fairing.run(&net).unwrap();
    assert!(!result.moved.is_empty());
    assert_eq!(faired.knot_vectors().0.knots(), &knots_u[..]);
    assert_eq!(faired.knot_vectors().1.knots(), &knots_v[..]);
    for (i, row) in weights.iter().enumerate() {
        for (j, &w) in row.iter().enumerate() {
            assert_eq!(
                faired.control_point(i, j).unwrap(),
                direct.surface.point(i, j).unwrap()
            );
            assert_eq!(faired.weight(i, j).unwrap(), w);
        }
    }
}
