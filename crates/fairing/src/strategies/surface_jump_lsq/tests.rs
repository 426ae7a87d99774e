//! Tests of the surface jump least squares against their defining conditions.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, Vec3};
use nalgebra::{DMatrix, DVector};

use super::operator::{gram, jump_matrix};
use super::spectral::Weights;
use super::{SurfaceJumpLsq, SurfaceJumpLsqSettings};
use crate::strategies::surface::Closure;

/// A net of `rows` × `columns` nodes of `surface(x, y)` over x, y ∈ [0, 1], each coordinate
/// moved by a deterministic pseudo-noise (xorshift from `seed`) in [−amplitude/2, amplitude/2).
fn noisy_net(
    rows: usize,
    columns: usize,
    amplitude: f64,
    seed: u64,
    surface: impl Fn(f64, f64) -> Vec3,
) -> Vec<Vec<Vec3>> {
    let mut state = seed;
    let mut noise = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    (0..rows)
        .map(|i| {
            (0..columns)
                .map(|j| {
                    let (x, y) = (i as f64 / (rows - 1) as f64, j as f64 / (columns - 1) as f64);
                    surface(x, y) + Vec3::new(noise(), noise(), noise()) * amplitude
                })
                .collect()
        })
        .collect()
}

/// A smooth open net with a deterministic pseudo-noise on every coordinate.
fn noisy(rows: usize, columns: usize, amplitude: f64) -> Vec<Vec<Vec3>> {
    noisy_net(rows, columns, amplitude, 0x2545_f491_4f6c_dd1d, |x, y| {
        let y = y * 1.3;
        Vec3::new(x, y, 0.3 * (2.0 * x).sin() * (1.5 * y).cos() + 0.1 * x * x)
    })
}

/// A net closed in v (a tube), the last column repeating the first.
fn tube(rows: usize, around: usize, amplitude: f64) -> Vec<Vec<Vec3>> {
    let base = noisy(rows, around, amplitude);
    (0..rows)
        .map(|i| {
            let mut line: Vec<Vec3> = (0..around)
                .map(|j| {
                    let t = std::f64::consts::TAU * j as f64 / around as f64;
                    let r = 1.0 + 0.2 * (i as f64 * 0.3).sin() + base[i][j].z * 0.1;
                    Vec3::new(i as f64 * 0.2, r * t.cos(), r * t.sin())
                })
                .collect();
            line.push(line[0]);
            line
        })
        .collect()
}

#[test]
#[allow(clippy::needless_range_loop)] // (i, j, c) name the node and coordinate compared
fn jump_matrix_gives_the_surface_jumps_scaled() {
    // D applied to a column of the net gives the u-jumps that the bicubic surface itself
    // reports at the column's interior nodes, times h̄³.
    let grid = noisy(9, 7, 0.02);
    let surface = BicubicSplineSurface::new(&grid).unwrap();
    let d = jump_matrix(surface.u_knots(), false).unwrap();
    let h = |i: usize| surface.u_knots()[i] - surface.u_knots()[i - 1];
    for j in 1..6 {
        for c in 0..3 {
            let y = DVector::from_fn(9, |i, _| grid[i][j][c]);
            let jumps = &d * y;
            for i in 1..8 {
                let expected = surface.third_derivative_jump(i, j).unwrap().u[c];
                let scale = (0.5 * (h(i) + h(i + 1))).powi(3);
                assert!(
                    (jumps[i - 1] - scale * expected).abs() <= 1e-9 * (scale * expected.abs()).max(1e-6),
                    "({i}, {j}) coordinate {c}: {} against {}",
                    jumps[i - 1],
                    scale * expected
                );
            }
        }
    }
}

#[test]
fn jump_matrix_is_blind_to_lines_only() {
    // Open: a natural spline has no jump iff it is a line (null space of K of dimension 2).
    let knots = [0.0, 0.3, 0.7, 1.2, 1.5, 2.1, 2.2];
    let d = jump_matrix(&knots, false).unwrap();
    let line = DVector::from_iterator(knots.len(), knots.iter().map(|t| 2.0 - 3.0 * t));
    assert!((&d * line).amax() < 1e-10);
    let quad = DVector::from_iterator(knots.len(), knots.iter().map(|t| t * t));
    assert!((&d * quad).amax() > 1e-3);
    let k = gram(&d);
    let eigen = k.symmetric_eigen();
    let scale = eigen.eigenvalues.amax();
    let null = eigen
        .eigenvalues
        .iter()
        .filter(|&&e| e.abs() <= 1e-10 * scale)
        .count();
    assert_eq!(null, 2);
    // Closed: only the constants (one dimension).
    let d = jump_matrix(&knots, true).unwrap();
    let eigen = gram(&d).symmetric_eigen();
    let scale = eigen.eigenvalues.amax();
    assert_eq!(
        eigen
            .eigenvalues
            .iter()
            .filter(|&&e| e.abs() <= 1e-10 * scale)
            .count(),
        1
    );
}

#[test]
fn lambda_zero_is_the_input_and_tiny_lambda_interpolates() {
    let grid = noisy(8, 10, 0.05);
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let zero = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_guard(false)
            .with_lambda(0.0),
    )
    .run(&grid)
    .unwrap();
    assert_eq!(zero.surface.points(), &flat[..]);
    let tiny = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_guard(false)
            .with_lambda(1e-12),
    )
    .run(&grid)
    .unwrap();
    let worst = tiny
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    assert!(worst < 1e-9, "{worst}");
}

#[test]
fn huge_lambda_gives_the_least_squares_bilinear_surface_without_jumps() {
    let grid = noisy(8, 11, 0.05);
    let (rows, columns) = (8, 11);
    let input = BicubicSplineSurface::new(&grid).unwrap();
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_guard(false)
            .with_lambda(1e12),
    )
    .run(&grid)
    .unwrap();
    // Least-squares fit of a + b u + c v + d u v over the input's knots, independently.
    let (u, v) = (input.u_knots(), input.v_knots());
    let basis = DMatrix::from_fn(rows * columns, 4, |k, c| {
        let (s, t) = (u[k / columns], v[k % columns]);
        [1.0, s, t, s * t][c]
    });
    let size = grid.iter().flatten().map(|p| p.norm()).fold(0.0, f64::max);
    for c in 0..3 {
        let y = DVector::from_iterator(rows * columns, grid.iter().flatten().map(|p| p[c]));
        let coef = (basis.transpose() * &basis)
            .lu()
            .solve(&(basis.transpose() * y))
            .unwrap();
        let fit = &basis * coef;
        for k in 0..rows * columns {
            let got = result.surface.points()[k][c];
            assert!(
                (got - fit[k]).abs() < 1e-7 * size,
                "node {k} coordinate {c}: {got} against {}",
                fit[k]
            );
        }
    }
    // No third-derivative jump across any knot line, over the input's knots.
    let settings = BicubicSurfaceSettings::default()
        .with_u_knots(u.to_vec())
        .with_v_knots(v.to_vec());
    let over_input =
        BicubicSplineSurface::from_flat(result.surface.points().to_vec(), rows, columns, &settings).unwrap();
    assert!(
        over_input.max_z() < 1e-6 * input.max_z(),
        "{} against {}",
        over_input.max_z(),
        input.max_z()
    );
}

/// The gradient of the objective at the free nodes, from the jump matrices directly.
fn gradient(grid: &[Vec<Vec3>], out: &[Vec3], lambda: f64) -> Vec<Vec3> {
    gradient_pair(grid, out, Weights::both(lambda))
}

/// The gradient of Σ|P − P⁰|² + λ_u |D_u P|² + λ_v |P D_vᵀ|² (halved), dense:
/// (P − P⁰) + λ_u K_u P + λ_v P K_v.
fn gradient_pair(grid: &[Vec<Vec3>], out: &[Vec3], w: Weights) -> Vec<Vec3> {
    let input = BicubicSplineSurface::new(grid).unwrap();
    let (rows, columns) = (grid.len(), grid[0].len());
    let ku = gram(&jump_matrix(input.u_knots(), false).unwrap());
    let kv = gram(&jump_matrix(input.v_knots(), false).unwrap());
    let mut g = vec![Vec3::zeros(); rows * columns];
    for c in 0..3 {
        let p = DMatrix::from_fn(rows, columns, |i, j| out[i * columns + j][c]);
        let p0 = DMatrix::from_fn(rows, columns, |i, j| grid[i][j][c]);
        let grad = (&p - &p0) + (&ku * &p) * w.u + (&p * &kv) * w.v;
        for k in 0..rows * columns {
            g[k][c] = grad[(k / columns, k % columns)];
        }
    }
    g
}

#[test]
fn fixed_nodes_held_bit_for_bit_and_the_rest_optimal() {
    let grid = noisy(10, 9, 0.05);
    let fixed = [(0, 0), (3, 4), (5, 5), (9, 2), (4, 0)];
    let lambda = 0.5;
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_lambda(lambda)
            .with_fixed(fixed),
    )
    .run(&grid)
    .unwrap();
    let out = result.surface.points();
    for &(i, j) in &fixed {
        assert_eq!(out[i * 9 + j], grid[i][j]);
    }
    let g = gradient(&grid, out, lambda);
    for (k, gk) in g.iter().enumerate() {
        if !fixed.contains(&(k / 9, k % 9)) {
            assert!(gk.norm() < 1e-9, "node {k}: gradient {}", gk.norm());
        }
    }
    assert!(result.cg_iterations > 0);
}

#[test]
fn held_boundary_lines_exact_and_interior_optimal() {
    let grid = noisy(9, 8, 0.05);
    let mut fixed = Vec::new();
    for i in 0..9 {
        for j in 0..8 {
            if i == 0 || j == 0 || i == 8 || j == 7 {
                fixed.push((i, j));
            }
        }
    }
    let lambda = 2.0;
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_lambda(lambda)
            .with_fixed(fixed.clone()),
    )
    .run(&grid)
    .unwrap();
    let out = result.surface.points();
    for &(i, j) in &fixed {
        assert_eq!(out[i * 8 + j], grid[i][j]);
    }
    assert_eq!(result.cg_iterations, 0, "whole held lines need no iteration");
    let g = gradient(&grid, out, lambda);
    for (k, gk) in g.iter().enumerate() {
        if !fixed.contains(&(k / 8, k % 8)) {
            assert!(gk.norm() < 1e-9, "node {k}: gradient {}", gk.norm());
        }
    }
}

#[test]
fn tolerance_band_holds() {
    let grid = noisy(12, 12, 0.08);
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let free = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_guard(false)
            .with_lambda(10.0),
    )
    .run(&grid)
    .unwrap();
    let widest = free
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    let band = 0.5 * widest;
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_lambda(10.0)
            .with_max_distance(band),
    )
    .run(&grid)
    .unwrap();
    assert!(result.band_pins > 0);
    for (p, q) in result.surface.points().iter().zip(&flat) {
        assert!((p - q).norm() <= band, "{} > {band}", (p - q).norm());
    }
}

#[test]
fn seam_stays_closed_and_gcv_moves_toward_the_clean_tube() {
    let clean = tube(14, 16, 0.0);
    let grid = tube(14, 16, 0.2);
    let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_closed(Closure::Auto))
        .run(&grid)
        .unwrap();
    assert!(result.topology.closed_v);
    let out = result.surface.points();
    for i in 0..14 {
        assert_eq!(out[i * 17], out[i * 17 + 16], "row {i}");
    }
    let rms = |a: &[Vec3]| {
        (a.iter()
            .zip(clean.iter().flatten())
            .map(|(p, q)| (p - q).norm_squared())
            .sum::<f64>()
            / a.len() as f64)
            .sqrt()
    };
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    assert!(result.gcv.is_some() && result.lambda_u > 0.0 && result.lambda_v > 0.0);
    assert!(rms(out) < rms(&flat), "{} against {}", rms(out), rms(&flat));
}

#[test]
fn poles_stay_one_point() {
    // Row 0 collapsed to one point (a pole).
    let mut grid = noisy(9, 9, 0.03);
    let apex = Vec3::new(0.0, 0.5, 0.4);
    for p in grid[0].iter_mut() {
        *p = apex;
    }
    let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .run(&grid)
        .unwrap();
    assert!(result.topology.poles.u_start);
    for j in 0..9 {
        assert_eq!(result.surface.points()[j], apex);
    }
}

#[test]
fn end_derivative_is_the_natural_spline_end_tangent() {
    let grid: Vec<Vec<Vec3>> = (0..7)
        .map(|i| {
            (0..5)
                .map(|j| {
                    let (x, y) = (i as f64 * 0.3 + 0.02 * (i * i) as f64, j as f64);
                    Vec3::new(x, y, (x * 1.3).sin() + 0.1 * y * x * x)
                })
                .collect()
        })
        .collect();
    let s = BicubicSplineSurface::new(&grid).unwrap();
    for at_end in [false, true] {
        let a = super::join::end_derivative(s.u_knots(), at_end);
        let i = if at_end { 6 } else { 0 };
        #[allow(clippy::needless_range_loop)] // j indexes the columns of every row
        for j in 0..5 {
            let d: Vec3 = grid.iter().zip(a.iter()).map(|(row, &w)| row[j] * w).sum();
            let t = s.u_tangent(i, j).unwrap();
            assert!(
                (d - t).norm() < 1e-12 * t.norm().max(1.0),
                "end {at_end} j {j}: {d:?} vs {t:?}"
            );
        }
    }
}

#[test]
fn two_weights_solve_their_normal_equations() {
    // (I + λ_u K_u ⊕ λ_v K_v) P = P⁰ at the free nodes, checked densely: on a free net, with
    // the boundary lines held (the coupling to held rows and held columns, split by
    // direction) and with scattered fixed nodes (the conjugate-gradient correction).
    let grid = noisy(9, 8, 0.05);
    let w = Weights { u: 0.3, v: 7.0 };
    let boundary: Vec<(usize, usize)> = (0..9)
        .flat_map(|i| (0..8).map(move |j| (i, j)))
        .filter(|&(i, j)| i == 0 || j == 0 || i == 8 || j == 7)
        .collect();
    for fixed in [Vec::new(), boundary, vec![(2, 3), (6, 1), (0, 7)]] {
        let result = SurfaceJumpLsq::new(
            SurfaceJumpLsqSettings::default()
                .with_guard(false)
                .with_fixed(fixed.clone()),
        )
        .fit(&grid, Some(w))
        .unwrap();
        assert_eq!((result.lambda_u, result.lambda_v), (w.u, w.v));
        let out = result.surface.points();
        for &(i, j) in &fixed {
            assert_eq!(out[i * 8 + j], grid[i][j]);
        }
        let g = gradient_pair(&grid, out, w);
        for (k, gk) in g.iter().enumerate() {
            if !fixed.contains(&(k / 8, k % 8)) {
                assert!(
                    gk.norm() < 1e-9,
                    "fixed {fixed:?}, node {k}: gradient {}",
                    gk.norm()
                );
            }
        }
    }
    // The two weights are not one: swapping them changes the fit.
    let swapped = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
        .fit(&grid, Some(Weights { u: w.v, v: w.u }))
        .unwrap();
    let g = gradient_pair(&grid, swapped.surface.points(), w);
    assert!(g.iter().any(|gk| gk.norm() > 1e-6));
}

/// A net wavy along u (i) and straight along v (j), noisy on every coordinate.
fn ruled(rows: usize, columns: usize, amplitude: f64, seed: u64) -> Vec<Vec<Vec3>> {
    noisy_net(rows, columns, amplitude, seed, |x, y| {
        Vec3::new(x, y, 0.15 * (std::f64::consts::TAU * 1.5 * x).sin())
    })
}

#[test]
fn gcv_smooths_the_straight_direction_harder() {
    // Every v-line (constant i) is straight: its jumps across the v knot lines are noise
    // alone, so GCV's λ_v must be far larger than its λ_u, the u-lines being sine waves.
    // The transposed net must give the transposed pair.
    for seed in [0x2545_f491_4f6c_dd1d_u64, 0x9e37_79b9_7f4a_7c15] {
        let grid = ruled(30, 30, 0.01, seed);
        let run = |g: &[Vec<Vec3>]| {
            SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
                .run(g)
                .unwrap()
        };
        let result = run(&grid);
        assert!(
            result.lambda_v > 100.0 * result.lambda_u,
            "λ_u {} λ_v {}",
            result.lambda_u,
            result.lambda_v
        );
        let transposed: Vec<Vec<Vec3>> = (0..30).map(|j| (0..30).map(|i| grid[i][j]).collect()).collect();
        let t = run(&transposed);
        let close = |a: f64, b: f64| (a.log10() - b.log10()).abs() < 0.05;
        assert!(
            close(t.lambda_u, result.lambda_v) && close(t.lambda_v, result.lambda_u),
            "({}, {}) against ({}, {})",
            t.lambda_u,
            t.lambda_v,
            result.lambda_u,
            result.lambda_v
        );
    }
}

#[test]
fn gcv_rss_and_trace_are_those_of_the_solve() {
    // The score's RSS (from the energies) is |X̂ − Ŷ|² of the spectral solve with a coupling,
    // and its trace is tr (I + λ_u I⊗K_u + λ_v K_v⊗I)⁻¹, built densely.
    use super::spectral::{Coupling, Energies, Planes, Spectral};
    let (m, n) = (5, 4);
    let du = DMatrix::from_fn(3, m, |i, j| ((i * 7 + j * 3) as f64).sin());
    let dv = DMatrix::from_fn(2, n, |i, j| ((i * 5 + j * 2 + 1) as f64).cos());
    let (ku, kv) = (du.transpose() * &du, dv.transpose() * &dv);
    let spectral = Spectral::new(ku.clone(), kv.clone());
    let plane = |k: usize| -> Planes {
        std::array::from_fn(|c| DMatrix::from_fn(m, n, |a, b| ((a * 5 + b * 3 + c * 11 + k) as f64).cos()))
    };
    let y = plane(0);
    let coupling = Coupling {
        u: plane(1),
        v: plane(2),
    };
    for w in [Weights { u: 0.3, v: 7.0 }, Weights { u: 1e3, v: 1e-3 }] {
        let x = spectral.solve_hat(&y, Some(&coupling), w);
        let rss: f64 = (0..3).map(|c| (&x[c] - &y[c]).norm_squared()).sum();
        let (score_rss, trace) = spectral.rss_trace(&Energies::new(&y, Some(&coupling)), w);
        assert!(
            (score_rss - rss).abs() <= 1e-12 * rss,
            "{score_rss} against {rss}"
        );
        let a = DMatrix::identity(m * n, m * n)
            + DMatrix::<f64>::identity(n, n).kronecker(&ku) * w.u
            + kv.kronecker(&DMatrix::<f64>::identity(m, m)) * w.v;
        let dense = a.try_inverse().unwrap().trace();
        assert!((trace - dense).abs() <= 1e-10 * dense, "{trace} against {dense}");
        assert!((spectral.trace(w) - dense).abs() <= 1e-10 * dense);
    }
}

#[test]
fn a_weight_at_the_limit_makes_the_lines_straight() {
    // Where GCV takes λ_v → ∞ (the v-lines straight in the data), the output's v-lines are
    // straight to round-off (`straighten`), not a faint planar wiggle left by the computed
    // null vectors; λ_u stays finite.
    // (On this seed GCV takes the limit; on others its minimum is at a finite λ_v ~10⁸.)
    let grid = ruled(30, 60, 0.01, 0x9e37_79b9_7f4a_7c15);
    let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
        .run(&grid)
        .unwrap();
    assert!(result.lambda_v >= super::LIMIT_WEIGHT, "λ_v {}", result.lambda_v);
    assert!(result.lambda_u < 1e12, "λ_u {}", result.lambda_u);
    for i in 0..30 {
        let line: Vec<Vec3> = (0..60).map(|j| result.surface.point(i, j).unwrap()).collect();
        let chord = line[59] - line[0];
        for p in &line {
            let off = (*p - line[0]).cross(&chord).norm() / chord.norm_squared();
            assert!(off < 1e-13, "line {i}: relative offset {off}");
        }
    }
}

#[test]
fn the_limit_is_taken_within_the_parsimony_margin_only() {
    // with_limits against its defining condition: a direction's limit is taken when its score
    // is at most the minimum's × (1 + LIMIT_SE_FACTOR · √(6 Δtr) / (3 (N − tr))), and not
    // above; of two such limits the lower-scoring one.
    use super::{with_limits, LIMIT_SE_FACTOR, LOG_LAMBDA_LIMIT};
    let (n, tr_best, dropped): (f64, f64, f64) = (1200.0, 30.0, 4.0);
    let se = (6.0 * dropped).sqrt() / (3.0 * (n - tr_best));
    let best = ((7.0, 1.0), 2.0);
    let trace = |u: f64, v: f64| {
        if u >= LOG_LAMBDA_LIMIT || v >= LOG_LAMBDA_LIMIT {
            tr_best - dropped
        } else {
            tr_best
        }
    };
    for (factor_u, factor_v, expect) in [
        (0.99, 5.0, (LOG_LAMBDA_LIMIT, 1.0)),
        (1.01, 5.0, (7.0, 1.0)),
        (5.0, 0.99, (7.0, LOG_LAMBDA_LIMIT)),
        (0.5, 0.2, (7.0, LOG_LAMBDA_LIMIT)),
        (-1.0, 0.2, (LOG_LAMBDA_LIMIT, 1.0)),
    ] {
        let score = |u: f64, v: f64| {
            let factor = if u >= LOG_LAMBDA_LIMIT {
                factor_u
            } else if v >= LOG_LAMBDA_LIMIT {
                factor_v
            } else {
                0.0
            };
            best.1 * (1.0 + factor * LIMIT_SE_FACTOR * se)
        };
        let (taken, _) = with_limits(score, trace, n, best);
        assert_eq!(taken, expect, "factors ({factor_u}, {factor_v})");
    }
    // No degrees of freedom dropped (a minimum at the range's top): only a score no worse.
    let flat = |_: f64, _: f64| tr_best;
    let worse = |u: f64, _: f64| {
        if u >= LOG_LAMBDA_LIMIT {
            2.0 * (1.0 + 1e-12)
        } else {
            3.0
        }
    };
    assert_eq!(with_limits(worse, flat, n, best).0, (7.0, 1.0));
    let same = |u: f64, _: f64| if u >= LOG_LAMBDA_LIMIT { 2.0 } else { 3.0 };
    assert_eq!(with_limits(same, flat, n, best).0, (LOG_LAMBDA_LIMIT, 1.0));
}

#[test]
fn lines_straight_in_the_data_come_out_straight_within_the_margin() {
    // A net straight along v plus noise, on eight seeds: the v-lines come out straight to
    // round-off, the wavy u-lines smoothed at a finite λ_u. (On other seeds GCV's minimum is
    // at a finite λ_v ~10⁸ more than the margin below the limit's score, and is kept.)
    for k in 1..=8u64 {
        let seed = 0x9e37_79b9_7f4a_7c15u64.wrapping_mul(k) | 1;
        let grid = ruled(30, 60, 0.01, seed);
        let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
            .run(&grid)
            .unwrap();
        assert!(
            result.lambda_v >= super::LIMIT_WEIGHT,
            "seed {seed:x}: λ_v {}",
            result.lambda_v
        );
        assert!(result.lambda_u < 1e12, "seed {seed:x}: λ_u {}", result.lambda_u);
        for i in 0..30 {
            let line: Vec<Vec3> = (0..60).map(|j| result.surface.point(i, j).unwrap()).collect();
            let chord = line[59] - line[0];
            for p in &line {
                let off = (*p - line[0]).cross(&chord).norm() / chord.norm_squared();
                assert!(off < 1e-13, "seed {seed:x}, line {i}: relative offset {off}");
            }
        }
    }
}

#[test]
fn gently_curved_directions_are_not_straightened() {
    // Curved in both directions (the smooth test net), and a hull-like net whose lines along u
    // are shallow parabolas under noise of a tenth of their rise: neither direction is taken
    // to the limit.
    let hull = |seed| {
        noisy_net(41, 16, 0.004, seed, |x, y| {
            Vec3::new(
                x,
                0.05 * (1.0 - (2.0 * x - 1.0).powi(2)) * (1.0 - y * y),
                0.07 * y,
            )
        })
    };
    let nets = [
        noisy(30, 30, 0.01),
        hull(0x2545_f491_4f6c_dd1d),
        hull(0x9e37_79b9_7f4a_7c15),
    ];
    for (k, grid) in nets.iter().enumerate() {
        let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
            .run(grid)
            .unwrap();
        assert!(
            result.lambda_u < 1e12 && result.lambda_v < 1e12,
            "net {k}: λ_u {} λ_v {}",
            result.lambda_u,
            result.lambda_v
        );
    }
}

/// The largest distance between two nets' nodes over the largest move of `a` from `input`.
fn relative_gap(a: &[Vec3], b: &[Vec3], input: &[Vec3]) -> f64 {
    let gap = a.iter().zip(b).map(|(p, q)| (p - q).norm()).fold(0.0, f64::max);
    let moved = a
        .iter()
        .zip(input)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    gap / moved
}

/// The exact path's and the reduced path's fits of `grid` with knots at every site (both
/// directions reduced), at the weights `w` (`None`: by GCV).
/// The exact fit and the reduced path's with knots at every site, for the directions of more
/// than `above` sites.
fn exact_and_all_knots(
    grid: &[Vec<Vec3>],
    settings: SurfaceJumpLsqSettings,
    w: Option<Weights>,
    above: usize,
) -> (super::SurfaceJumpLsqResult, super::SurfaceJumpLsqResult) {
    let settings = settings.with_guard(false);
    let exact = SurfaceJumpLsq::new(settings.clone()).fit(grid, w).unwrap();
    let reduced = SurfaceJumpLsq::new(settings)
        .with_reduction(above, usize::MAX)
        .fit(grid, w)
        .unwrap();
    (exact, reduced)
}

#[test]
fn reduced_basis_on_every_site_is_the_exact_method() {
    // With its knots at all the sites the reduced space is the exact one (N = I), so the
    // reduced path's fit, GCV score and weights are the exact path's to round-off: on an
    // open net, a tube (closed in v), and at given weights as well as by GCV.
    let cases = [
        noisy(23, 11, 0.03),
        tube(17, 13, 0.03),
        noisy_net(19, 9, 0.02, 7, |x, y| Vec3::new(x, y, (3.0 * x).sin() * y)),
    ];
    for grid in &cases {
        let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
        for w in [
            Some(Weights { u: 0.3, v: 20.0 }),
            Some(Weights { u: 1e4, v: 1e-3 }),
            None,
        ] {
            let (exact, reduced) = exact_and_all_knots(grid, SurfaceJumpLsqSettings::default(), w, 0);
            let gap = relative_gap(exact.surface.points(), reduced.surface.points(), &flat);
            assert!(gap < 1e-9, "{w:?}: gap {gap}");
            assert!(
                (exact.dof - reduced.dof).abs() < 1e-8 * exact.dof,
                "{} {}",
                exact.dof,
                reduced.dof
            );
            if w.is_none() {
                let (a, b) = (exact.gcv.unwrap(), reduced.gcv.unwrap());
                assert!((a - b).abs() < 1e-8 * a, "gcv {a} against {b}");
                assert!((exact.lambda_u.log10() - reduced.lambda_u.log10()).abs() < 1e-4);
                assert!((exact.lambda_v.log10() - reduced.lambda_v.log10()).abs() < 1e-4);
            }
        }
    }
}

/// The nodes of the grid's boundary (its first and last rows and columns): `g0`.
fn boundary(rows: usize, columns: usize) -> Vec<(usize, usize)> {
    (0..rows)
        .flat_map(|i| (0..columns).map(move |j| (i, j)))
        .filter(|&(i, j)| i == 0 || j == 0 || i + 1 == rows || j + 1 == columns)
        .collect()
}

#[test]
fn reduced_basis_with_held_ends_is_the_exact_method_on_every_site() {
    // Held boundary lines (g0) in a reduced direction are its clamped end coefficients: with
    // knots at every site the fit is the exact path's, and the held nodes are the input's bit
    // for bit. One direction reduced at a time (u on 21 × 10, v on 10 × 21; both reduced:
    // `both_directions_reduced_with_every_edge_held_solve_their_normal_equations`).
    for (rows, columns) in [(21, 10), (10, 21)] {
        let grid = noisy(rows, columns, 0.03);
        let settings = SurfaceJumpLsqSettings::default().with_fixed(boundary(rows, columns));
        let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
        for w in [Some(Weights { u: 2.0, v: 0.05 }), None] {
            let (exact, reduced) = exact_and_all_knots(&grid, settings.clone(), w, 15);
            let gap = relative_gap(exact.surface.points(), reduced.surface.points(), &flat);
            assert!(gap < 1e-9, "{rows} x {columns}, {w:?}: gap {gap}");
            for (i, j) in boundary(rows, columns) {
                assert_eq!(reduced.surface.points()[i * columns + j], grid[i][j]);
            }
        }
    }
}

#[test]
fn a_reduced_fit_is_a_spline_on_its_knots_and_its_score_is_its_residual() {
    // On 40 knots of 160 sites: each u-line of the fit is the natural cubic spline through its
    // values at the knots (it lies in the reduced space), and the GCV score reported is
    // (RSS/3N)/(1 − tr/N)² with the RSS of the output itself, the data outside the reduced
    // space included.
    let (rows, columns) = (160, 6);
    let grid = noisy_net(rows, columns, 0.02, 11, |x, y| {
        Vec3::new(4.0 * x, y, 0.2 * (9.0 * x).sin() * (1.0 + y))
    });
    let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
        .with_reduction(100, 40)
        .run(&grid)
        .unwrap();
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let out = result.surface.points();
    let n = (rows * columns) as f64;
    let rss: f64 = out.iter().zip(&flat).map(|(p, q)| (p - q).norm_squared()).sum();
    let expected = (rss / (3.0 * n)) / (1.0 - result.dof / n).powi(2);
    let gcv = result.gcv.unwrap();
    assert!(
        (gcv - expected).abs() < 1e-6 * expected,
        "{gcv} against {expected}"
    );
    // The input's chord-length knots (the fit's own differ).
    assert_on_knot_splines(&grid, out, 40, 0..columns);
}

/// The natural cubic spline through (τ_k, c_k), by its moments (dense solve).
fn natural_spline(tau: &[f64], c: &[f64]) -> impl Fn(f64) -> f64 {
    let n = tau.len();
    let h: Vec<f64> = tau.windows(2).map(|w| w[1] - w[0]).collect();
    let mut a = DMatrix::<f64>::identity(n, n);
    let mut r = DVector::<f64>::zeros(n);
    for k in 1..n - 1 {
        a[(k, k - 1)] = h[k - 1];
        a[(k, k)] = 2.0 * (h[k - 1] + h[k]);
        a[(k, k + 1)] = h[k];
        r[k] = 6.0 * ((c[k + 1] - c[k]) / h[k] - (c[k] - c[k - 1]) / h[k - 1]);
    }
    let m = a.lu().solve(&r).unwrap();
    let (tau, c) = (tau.to_vec(), c.to_vec());
    move |t: f64| {
        let k = tau.windows(2).position(|w| t <= w[1]).unwrap_or(n - 2);
        let hk = tau[k + 1] - tau[k];
        let a = (tau[k + 1] - t) / hk;
        let b = (t - tau[k]) / hk;
        a * c[k] + b * c[k + 1] + ((a * a * a - a) * m[k] + (b * b * b - b) * m[k + 1]) * hk * hk / 6.0
    }
}

/// The dense solution `x` of coordinate `k` against the fit's nodes `out` (a net of `columns`
/// columns) over the block whose first node is `corner`, to 10⁻⁹.
fn assert_block_is(
    x: &DMatrix<f64>,
    out: &[Vec3],
    corner: (usize, usize),
    columns: usize,
    k: usize,
    w: Weights,
) {
    for i in 0..x.nrows() {
        for j in 0..x.ncols() {
            let gap = (x[(i, j)] - out[(i + corner.0) * columns + j + corner.1][k]).abs();
            assert!(gap < 1e-9, "{w:?} ({i}, {j}) coordinate {k}: {gap}");
        }
    }
}

/// With u reduced to `count` knots and v exact, the basis N of u's reduced lines at the sites
/// and the matrix of the fit's normal equations in vec C:
/// (I ⊗ NᵀN) + λ_u (I ⊗ K') + λ_v (K_v ⊗ NᵀN).
fn reduced_u_normal_matrix(grid: &[Vec<Vec3>], count: usize, w: Weights) -> (DMatrix<f64>, DMatrix<f64>) {
    let input = BicubicSplineSurface::new(grid).unwrap();
    let n = spline_basis(input.u_knots(), count);
    let ntn = n.transpose() * &n;
    let kp = gram(&jump_matrix(&tau_of(input.u_knots(), count), false).unwrap());
    let kv = gram(&jump_matrix(input.v_knots(), false).unwrap());
    let id = DMatrix::<f64>::identity(kv.nrows(), kv.nrows());
    let a = id.kronecker(&ntn) + id.kronecker(&kp) * w.u + kv.kronecker(&ntn) * w.v;
    (n, a)
}

/// With u reduced to `count` knots and v exact, the reduced problem's minimiser under X_p = q_p
/// at each pin ((i, j), q): the KKT system [A Φᵀ; Φ 0] [vec C; m] = [(I ⊗ Nᵀ) vec Y; q], A
/// the matrix of [`reduced_u_normal_matrix`] and Φ's rows the pins' rows of I ⊗ N, solved
/// densely. The fit at the sites, one matrix a coordinate.
fn reduced_u_constrained_fit(
    grid: &[Vec<Vec3>],
    count: usize,
    w: Weights,
    pins: &[((usize, usize), Vec3)],
) -> Vec<DMatrix<f64>> {
    let (rows, columns) = (grid.len(), grid[0].len());
    let (n, a) = reduced_u_normal_matrix(grid, count, w);
    let size = count * columns;
    let mut kkt = DMatrix::zeros(size + pins.len(), size + pins.len());
    kkt.view_mut((0, 0), (size, size)).copy_from(&a);
    for (r, &((i, j), _)) in pins.iter().enumerate() {
        for q in 0..count {
            kkt[(size + r, j * count + q)] = n[(i, q)];
            kkt[(j * count + q, size + r)] = n[(i, q)];
        }
    }
    let lu = kkt.lu();
    (0..3)
        .map(|c| {
            let y = DMatrix::from_fn(rows, columns, |i, j| grid[i][j][c]);
            let mut rhs = DVector::zeros(size + pins.len());
            rhs.rows_mut(0, size)
                .copy_from(&DVector::from_column_slice((n.transpose() * &y).as_slice()));
            for (r, &(_, q)) in pins.iter().enumerate() {
                rhs[size + r] = q[c];
            }
            let solution = lu.solve(&rhs).unwrap();
            &n * DMatrix::from_column_slice(count, columns, &solution.as_slice()[..size])
        })
        .collect()
}

#[test]
#[allow(clippy::needless_range_loop)] // the loop variable names the coordinate compared
fn a_reduced_fit_solves_its_normal_equations() {
    // u reduced to M knots, v exact: the fit's knot values C minimise
    // |N C − Y|² + λ_u tr(Cᵀ K' C) + λ_v tr(N C K_v Cᵀ Nᵀ), solved here densely:
    // [(I ⊗ NᵀN) + λ_u (I ⊗ K') + λ_v (K_v ⊗ NᵀN)] vec C = (I ⊗ Nᵀ) vec Y.
    let (rows, columns, count) = (90, 6, 25);
    let grid = noisy(rows, columns, 0.03);
    for w in [Weights { u: 0.5, v: 3.0 }, Weights { u: 1e3, v: 1e-2 }] {
        let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
            .with_reduction(50, count)
            .fit(&grid, Some(w))
            .unwrap();
        let out = result.surface.points();
        let (n, a) = reduced_u_normal_matrix(&grid, count, w);
        let lu = a.lu();
        for c in 0..3 {
            let y = DMatrix::from_fn(rows, columns, |i, j| grid[i][j][c]);
            let rhs = n.transpose() * &y;
            let vec_c = lu.solve(&DVector::from_column_slice(rhs.as_slice())).unwrap();
            let x = &n * DMatrix::from_column_slice(count, columns, vec_c.as_slice());
            assert_block_is(&x, out, (0, 0), columns, c, w);
        }
    }
}

#[test]
#[allow(clippy::needless_range_loop)] // the loop variable names the coordinate compared
fn a_reduced_fit_with_held_boundary_solves_its_normal_equations() {
    // g0 on a net whose u-direction is reduced (v exact): the held nodes stay bit for bit, the
    // u-lines' end coefficients are the held ends, and the free knot values C minimise
    // Σ_{R×C} |X − Y|² + λ_u Σ_j |D' c_j|² + λ_v Σ_i |D_v X[i, :]|² (whole rows, the held
    // columns included), X = N_RF C + N_RE P⁰_E: solved here densely.
    let (rows, columns, count) = (80, 7, 21);
    let grid = noisy(rows, columns, 0.03);
    let input = BicubicSplineSurface::new(&grid).unwrap();
    let tau = tau_of(input.u_knots(), count);
    let n_full = spline_basis(input.u_knots(), count);
    let (r, c) = (rows - 2, columns - 2);
    let f = count - 2;
    let n_rf = n_full.view((1, 1), (r, f)).into_owned();
    let n_re = DMatrix::from_fn(r, 2, |i, e| n_full[(i + 1, if e == 0 { 0 } else { count - 1 })]);
    let kp = gram(&jump_matrix(&tau, false).unwrap());
    let kp_ff = kp.view((1, 1), (f, f)).into_owned();
    let kp_fe = DMatrix::from_fn(f, 2, |i, e| kp[(i + 1, if e == 0 { 0 } else { count - 1 })]);
    let kv = gram(&jump_matrix(input.v_knots(), false).unwrap());
    let kv_cc = kv.view((1, 1), (c, c)).into_owned();
    let kv_hc = DMatrix::from_fn(2, c, |h, j| kv[(if h == 0 { 0 } else { columns - 1 }, j + 1)]);
    let a = n_rf.transpose() * &n_rf;
    let id = DMatrix::<f64>::identity(c, c);
    for w in [Weights { u: 0.5, v: 3.0 }, Weights { u: 1e3, v: 1e-2 }] {
        let result = SurfaceJumpLsq::new(
            SurfaceJumpLsqSettings::default()
                .with_guard(false)
                .with_fixed(boundary(rows, columns)),
        )
        .with_reduction(50, count)
        .fit(&grid, Some(w))
        .unwrap();
        let out = result.surface.points();
        for (i, j) in boundary(rows, columns) {
            assert_eq!(out[i * columns + j], grid[i][j]);
        }
        let system = id.kronecker(&a) + id.kronecker(&kp_ff) * w.u + kv_cc.kronecker(&a) * w.v;
        let lu = system.lu();
        for k in 0..3 {
            let y = DMatrix::from_fn(r, c, |i, j| grid[i + 1][j + 1][k]);
            let ends = DMatrix::from_fn(2, c, |e, j| grid[if e == 0 { 0 } else { rows - 1 }][j + 1][k]);
            let sides = DMatrix::from_fn(r, 2, |i, h| grid[i + 1][if h == 0 { 0 } else { columns - 1 }][k]);
            let shift = &n_re * &ends;
            let rhs = n_rf.transpose() * (&y - &shift)
                - &kp_fe * &ends * w.u
                - n_rf.transpose() * (&shift * &kv_cc + &sides * &kv_hc) * w.v;
            let vec_c = lu.solve(&DVector::from_column_slice(rhs.as_slice())).unwrap();
            let x = &n_rf * DMatrix::from_column_slice(f, c, vec_c.as_slice()) + &shift;
            assert_block_is(&x, out, (1, 1), columns, k, w);
        }
    }
}

#[test]
fn a_reduced_direction_beside_held_lines_of_the_other_is_the_exact_method() {
    // A long u direction reduced, its own lines free, while the v direction (exact) holds its
    // edge lines: the coupling of the held v lines lies at the sites, the u direction has none.
    // With knots at every site the fit is the exact path's; the held nodes stay bit for bit.
    let (rows, columns) = (21, 10);
    let grid = noisy(rows, columns, 0.03);
    let held: Vec<(usize, usize)> = (0..rows).flat_map(|i| [(i, 0), (i, columns - 1)]).collect();
    let settings = SurfaceJumpLsqSettings::default().with_fixed(held.clone());
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    for w in [Some(Weights { u: 2.0, v: 0.05 }), None] {
        let (exact, reduced) = exact_and_all_knots(&grid, settings.clone(), w, 15);
        let gap = relative_gap(exact.surface.points(), reduced.surface.points(), &flat);
        assert!(gap < 1e-9, "{w:?}: gap {gap}");
        for &(i, j) in &held {
            assert_eq!(reduced.surface.points()[i * columns + j], grid[i][j]);
        }
    }
}

#[test]
fn a_reduced_direction_on_fewer_knots_beside_held_lines_of_the_other_is_on_its_knots() {
    // 40 u sites on 12 knots, the v edges held: the run succeeds (the u direction's empty
    // coupling was once taken as coefficients, 12 rows against 40), the held nodes stay bit for
    // bit, and each free u-line of the fit is the natural cubic spline through its values at
    // the knots.
    let (rows, columns, count) = (40, 10, 12);
    let grid = noisy(rows, columns, 0.03);
    let held: Vec<(usize, usize)> = (0..rows).flat_map(|i| [(i, 0), (i, columns - 1)]).collect();
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_fixed(held.clone())
            .with_guard(false),
    )
    .with_reduction(15, count)
    .fit(&grid, None)
    .unwrap();
    let out = result.surface.points();
    for &(i, j) in &held {
        assert_eq!(out[i * columns + j], grid[i][j]);
    }
    assert_on_knot_splines(&grid, out, count, 1..columns - 1);
}

/// Columns `lines` of the fit `out` of `grid`, reduced along u to `count` knots, are natural
/// cubic splines on those knots (the input's chord-length sites; the fit's own differ):
/// their values at every site are the spline through their values at the knot sites.
#[allow(clippy::needless_range_loop)] // (j, c) name the line and coordinate compared
fn assert_on_knot_splines(grid: &[Vec<Vec3>], out: &[Vec3], count: usize, lines: std::ops::Range<usize>) {
    let (rows, columns) = (grid.len(), grid[0].len());
    let input = BicubicSplineSurface::new(grid).unwrap();
    let sites = input.u_knots();
    let knot_sites = super::reduced::knot_sites(rows, count, false);
    let tau: Vec<f64> = knot_sites.iter().map(|&i| sites[i]).collect();
    for j in lines {
        for c in 0..3 {
            let values: Vec<f64> = knot_sites.iter().map(|&i| out[i * columns + j][c]).collect();
            let spline = natural_spline(&tau, &values);
            for (i, &t) in sites.iter().enumerate() {
                let off = (spline(t) - out[i * columns + j][c]).abs();
                assert!(off < 1e-9, "site {i}, line {j}: {off}");
            }
        }
    }
}

#[test]
fn the_spectrums_bottom_is_the_jump_matrixs_squared_singular_values() {
    // K = DᵀD squares D's condition number: on 300 uneven sites K's own eigendecomposition
    // returns more modes than the null space below 10⁻¹¹ of its largest eigenvalue
    // (round-off). Refined, the bottom of the spectrum is D's squared singular values
    // (nalgebra's SVD of D, an independent computation) to 10⁻⁶ relative, only the null space
    // (lines; constants when closed) is ~0, and the vectors stay orthonormal eigenvectors.
    let sites: Vec<f64> = (0..300)
        .map(|i| {
            let t = i as f64 / 299.0;
            t + 0.02 * (17.0 * t).sin()
        })
        .collect();
    for (closed, null) in [(false, 2), (true, 1)] {
        let knots: Vec<f64> = if closed {
            sites.iter().copied().chain([1.0 + 1.0 / 299.0]).collect()
        } else {
            sites.clone()
        };
        let d = jump_matrix(&knots, closed).unwrap();
        let k = gram(&d);
        let (mut values, mut vectors) = super::spectral::symmetric_eigen(&k);
        let top = values.iter().fold(0.0f64, |m, &x| m.max(x));
        let tiny = values.iter().filter(|&&x| x <= 1e-11 * top).count();
        assert!(
            tiny > null,
            "closed {closed}: K's own bottom is already resolved ({tiny})"
        );
        super::spectral::refine_bottom(&mut values, &mut vectors, |v| &d * v);
        let mut expected: Vec<f64> = d
            .clone()
            .svd(false, false)
            .singular_values
            .iter()
            .map(|s| s * s)
            .collect();
        expected.resize(values.len(), 0.0);
        expected.sort_by(f64::total_cmp);
        let mut got = values.clone();
        got.sort_by(f64::total_cmp);
        assert!(
            got[..null].iter().all(|&x| x <= 1e-25 * top),
            "closed {closed}: null {:?}",
            &got[..null]
        );
        for k in null..null + 40 {
            let rel = (got[k] - expected[k]).abs() / expected[k];
            assert!(
                rel < 1e-6,
                "closed {closed}: mode {k}: {} against {} ({rel:e})",
                got[k],
                expected[k]
            );
        }
        for (j, &value) in values.iter().enumerate() {
            let v = vectors.column(j);
            assert!((v.norm() - 1.0).abs() < 1e-10);
            assert!((&k * v - v * value).amax() < 1e-9 * top);
        }
    }
}

#[test]
fn a_coarse_basis_is_kept_only_where_it_resolves_the_fit() {
    // 260 sites along u (more than COARSE_KNOTS), λ by GCV. A smooth surface: the default fit
    // is the 200-knot basis's, bit for bit, and within a twentieth of the noise of the exact
    // fit. A surface with a wave of 4 sites along u: the coarse basis cannot resolve it, and
    // the default fit is the exact one, bit for bit.
    let (rows, columns) = (260, 6);
    let exact_fit = |grid: &[Vec<Vec3>]| {
        SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
            .with_reduction(usize::MAX, usize::MAX)
            .fit(grid, None)
            .unwrap()
    };
    let smooth = noisy_net(rows, columns, 0.02, 5, |x, y| {
        Vec3::new(4.0 * x, y, 0.3 * (5.0 * x).sin() * (1.0 + 0.5 * y))
    });
    let default = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .fit(&smooth, None)
        .unwrap();
    let coarse = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .with_reduction(super::COARSE_KNOTS, super::COARSE_KNOTS)
        .fit(&smooth, None)
        .unwrap();
    assert_eq!(default.surface.points(), coarse.surface.points());
    assert_eq!(default.basis, (super::COARSE_KNOTS, columns));
    let exact = exact_fit(&smooth);
    assert_ne!(default.surface.points(), exact.surface.points());
    let gap = default
        .surface
        .points()
        .iter()
        .zip(exact.surface.points())
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    // The noise is uniform on [−0.01, 0.01) per coordinate: σ ≈ 0.0058.
    assert!(gap < 0.05 * 0.0058, "coarse against exact: {gap}");
    let wavy = noisy_net(rows, columns, 0.02, 6, |x, y| {
        Vec3::new(
            4.0 * x,
            y,
            0.3 * (2.0 * std::f64::consts::PI * 259.0 * x / 4.0).sin() + 0.1 * y,
        )
    });
    let default = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .fit(&wavy, None)
        .unwrap();
    assert_eq!(default.surface.points(), exact_fit(&wavy).surface.points());
    assert_eq!(default.basis, (rows, columns));
}

#[test]
fn a_smooth_net_of_hundreds_of_sites_is_faired_near_its_clean_surface_on_the_exact_path() {
    // 400 × 20 sites of a smooth surface with noise, on the exact path (no reduction). With
    // the penalty's smoothest modes along u taken as round-off null (the 3rd to ~14th on 400
    // sites) this net was "faired" at λ_u → ∞ to 8.4 times the input's distance from the clean
    // surface. It must end nearer than a fifth of the input's (RMS).
    let (rows, columns) = (400, 20);
    let clean = |x: f64, y: f64| {
        let pi = std::f64::consts::PI;
        Vec3::new(x, y, 0.2 * (2.4 * pi * x).sin() * (0.6 * pi * y).cos())
    };
    let grid = noisy_net(rows, columns, 0.02, 1, clean);
    let result = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .with_reduction(usize::MAX, usize::MAX)
        .fit(&grid, None)
        .unwrap();
    let truth: Vec<Vec3> = (0..rows)
        .flat_map(|i| {
            (0..columns).map(move |j| clean(i as f64 / (rows - 1) as f64, j as f64 / (columns - 1) as f64))
        })
        .collect();
    let rms = |a: &[Vec3]| {
        (a.iter()
            .zip(&truth)
            .map(|(p, q)| (p - q).norm_squared())
            .sum::<f64>()
            / a.len() as f64)
            .sqrt()
    };
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let (input, faired) = (rms(&flat), rms(result.surface.points()));
    assert!(
        faired < 0.2 * input,
        "RMS to the clean surface {faired}, the input's {input}"
    );
}

/// The natural cubic splines on `count` knots of the input's `sites` (knot sites spread by
/// count, module `reduced`) evaluated at the sites: N (sites × knots).
fn spline_basis(sites: &[f64], count: usize) -> DMatrix<f64> {
    let tau = tau_of(sites, count);
    DMatrix::from_fn(sites.len(), count, |i, k| {
        let e: Vec<f64> = (0..count).map(|q| f64::from(u8::from(q == k))).collect();
        natural_spline(&tau, &e)(sites[i])
    })
}

#[test]
#[allow(clippy::needless_range_loop)] // the loop variable names the coordinate compared
fn both_directions_reduced_with_held_ends_of_one_solve_their_normal_equations() {
    // Both directions reduced (u to Mu knots, v to Mv), the first and last rows held: the
    // model is X = N_uF C N_vᵀ + N_uE E N_vᵀ, E the held rows' projection onto the v basis
    // (Eᵀ = (N_vᵀN_v)⁻¹N_vᵀHᵀ, H the held rows), and C minimises
    // |X − Y|² + λ_u Σ_j |D'_u [E; C] n_j|² + λ_v Σ_i |D'_v (N_u [E; C])_i|², solved here
    // densely; the output at the free nodes is X (the held rows themselves at the edge).
    let (rows, columns, count) = (60, 48, 14);
    let grid = noisy(rows, columns, 0.03);
    let input = BicubicSplineSurface::new(&grid).unwrap();
    let n_u = spline_basis(input.u_knots(), count);
    let n_v = spline_basis(input.v_knots(), count);
    let (r, f) = (rows - 2, count - 2);
    let n_uf = n_u.view((1, 1), (r, f)).into_owned();
    let n_ue = DMatrix::from_fn(r, 2, |i, e| n_u[(i + 1, if e == 0 { 0 } else { count - 1 })]);
    let n_u_rows = n_u.rows(1, r).into_owned(); // N_u at the free rows, every coefficient
    let ku = gram(&jump_matrix(&tau_of(input.u_knots(), count), false).unwrap());
    let kv = gram(&jump_matrix(&tau_of(input.v_knots(), count), false).unwrap());
    let ku_ff = ku.view((1, 1), (f, f)).into_owned();
    let ku_fe = DMatrix::from_fn(f, 2, |i, e| ku[(i + 1, if e == 0 { 0 } else { count - 1 })]);
    let vtv = n_v.transpose() * &n_v;
    let vtv_inverse = vtv.clone().try_inverse().unwrap();
    let held: Vec<(usize, usize)> = (0..columns).flat_map(|j| [(0, j), (rows - 1, j)]).collect();
    for w in [Weights { u: 0.5, v: 3.0 }, Weights { u: 1e3, v: 1e-2 }] {
        let result = SurfaceJumpLsq::new(
            SurfaceJumpLsqSettings::default()
                .with_guard(false)
                .with_fixed(held.clone()),
        )
        .with_reduction(40, count)
        .fit(&grid, Some(w))
        .unwrap();
        assert_eq!(result.basis, (f, count), "both directions reduced");
        let out = result.surface.points();
        for &(i, j) in &held {
            assert_eq!(out[i * columns + j], grid[i][j]);
        }
        let a = n_uf.transpose() * &n_uf;
        let system = vtv.kronecker(&a) + vtv.kronecker(&ku_ff) * w.u + kv.kronecker(&a) * w.v;
        let lu = system.lu();
        for k in 0..3 {
            let y = DMatrix::from_fn(r, columns, |i, j| grid[i + 1][j][k]);
            let h = DMatrix::from_fn(2, columns, |e, j| grid[if e == 0 { 0 } else { rows - 1 }][j][k]);
            let e = (&vtv_inverse * n_v.transpose() * h.transpose()).transpose(); // 2 × Mv
            let mut ec = DMatrix::zeros(count, count); // [E; C] with C zero
            ec.row_mut(0).copy_from(&e.row(0));
            ec.row_mut(count - 1).copy_from(&e.row(1));
            let rhs = n_uf.transpose() * (&y - &n_ue * &h) * &n_v
                - &ku_fe * &e * &vtv * w.u
                - n_uf.transpose() * (&n_u_rows * &ec) * &kv * w.v;
            let vec_c = lu.solve(&DVector::from_column_slice(rhs.as_slice())).unwrap();
            let x = (&n_uf * DMatrix::from_column_slice(f, count, vec_c.as_slice()) + &n_ue * &e)
                * n_v.transpose();
            assert_block_is(&x, out, (1, 0), columns, k, w);
        }
    }
}

/// The knots of a direction reduced to `count` of its `sites`.
fn tau_of(sites: &[f64], count: usize) -> Vec<f64> {
    super::reduced::knot_sites(sites.len(), count, false)
        .iter()
        .map(|&i| sites[i])
        .collect()
}

#[test]
fn a_g1_join_on_reduced_bases_is_the_exact_join_on_every_site_and_holds_on_fewer_knots() {
    // A noisy net joined g1 on u0 to a clean neighbour of the same surface. With knots at
    // every site (both directions reduced) the fit is the exact path's; on 12 knots a
    // direction the edge is the neighbour's bit for bit and the tangent planes agree along it
    // to round-off (the spectral correction meets the constraints in the reduced space only;
    // the rest is met at the sites), and the fit nears the clean surface.
    use super::join::{Continuity, Join, JoinEdge};
    let surface = |x: f64, y: f64| Vec3::new(x, y, 0.3 * (2.0 * x).sin() * (1.5 * y).cos() + 0.1 * x * x);
    let (rows, columns) = (36, 30);
    let grid = noisy_net(rows, columns, 0.01, 3, |x, y| surface(0.5 + 0.5 * x, y));
    let clean = noisy_net(rows, columns, 0.0, 3, |x, y| surface(0.5 + 0.5 * x, y));
    let neighbour = noisy_net(rows, columns, 0.0, 3, |x, y| surface(0.5 * x, y));
    let settings = SurfaceJumpLsqSettings::default().with_join(Join {
        edge: JoinEdge::U0,
        continuity: Continuity::G1,
        neighbour: neighbour.clone(),
        source: "neighbour".into(),
    });
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    for w in [Some(Weights { u: 2.0, v: 0.05 }), None] {
        let (exact, reduced) = exact_and_all_knots(&grid, settings.clone(), w, 20);
        assert_eq!(reduced.basis, (rows - 1, columns));
        let gap = relative_gap(exact.surface.points(), reduced.surface.points(), &flat);
        assert!(gap < 1e-9, "{w:?}: gap {gap}");
    }
    let reduced = SurfaceJumpLsq::new(settings)
        .with_reduction(20, 12)
        .run(&grid)
        .unwrap();
    assert_eq!(reduced.basis, (11, 12));
    let out = reduced.surface.points();
    for j in 0..columns {
        assert_eq!(out[j], neighbour[rows - 1][j], "edge node {j}");
    }
    let report = &reduced.joins[0];
    assert!(report.before.angle_degrees > 0.5, "{:?}", report.before);
    assert!(report.after.angle_degrees < 1e-9, "{:?}", report.after);
    let rms = |net: &[Vec3]| {
        let sum: f64 = net
            .iter()
            .zip(clean.iter().flatten())
            .map(|(p, q)| (p - q).norm_squared())
            .sum();
        (sum / net.len() as f64).sqrt()
    };
    assert!(
        rms(out) < 0.5 * rms(&flat),
        "{} against the input's {}",
        rms(out),
        rms(&flat)
    );
}

#[test]
#[allow(clippy::needless_range_loop)] // the loop variable names the coordinate compared
fn both_directions_reduced_with_every_edge_held_solve_their_normal_equations() {
    // Both directions reduced to M knots and the whole boundary held (g0). The model's
    // coefficients C_full have the free block C, the corners P⁰ at the corner knots, and along
    // each held edge the projection onto the free splines of that edge's data less the
    // corners' end splines (h' = h − P⁰_corners N_vEᵀ, g' = g − N_uE P⁰_corners). C minimises
    // |N_u C_full N_vᵀ − Y|² + λ_u tr(C_full AV C_fullᵀ K'_u) + λ_v tr(C_fullᵀ AU C_full K'_v)
    // over the free sites (AU = N_uᵀN_u, AV = N_vᵀN_v there), solved here densely; the output
    // there is N_u C_full N_vᵀ.
    let (rows, columns, count) = (50, 44, 13);
    let grid = noisy(rows, columns, 0.03);
    let input = BicubicSplineSurface::new(&grid).unwrap();
    let (ru, cv, f) = (rows - 2, columns - 2, count - 2);
    // N at the free sites, every coefficient; F the free knots, E the two end knots.
    let n_u = spline_basis(input.u_knots(), count).rows(1, ru).into_owned();
    let n_v = spline_basis(input.v_knots(), count).rows(1, cv).into_owned();
    let ends = [0, count - 1];
    let free: Vec<usize> = (1..count - 1).collect();
    let (n_uf, n_ue) = (n_u.select_columns(&free), n_u.select_columns(&ends));
    let (n_vf, n_ve) = (n_v.select_columns(&free), n_v.select_columns(&ends));
    let ku = gram(&jump_matrix(&tau_of(input.u_knots(), count), false).unwrap());
    let kv = gram(&jump_matrix(&tau_of(input.v_knots(), count), false).unwrap());
    let (au, av) = (n_u.transpose() * &n_u, n_v.transpose() * &n_v);
    let ff = |m: &DMatrix<f64>| m.select_rows(&free).select_columns(&free);
    let project =
        |n: &DMatrix<f64>, y: &DMatrix<f64>| (n.transpose() * n).try_inverse().unwrap() * n.transpose() * y;
    for w in [Weights { u: 0.5, v: 3.0 }, Weights { u: 1e3, v: 1e-2 }] {
        let result = SurfaceJumpLsq::new(
            SurfaceJumpLsqSettings::default()
                .with_guard(false)
                .with_fixed(boundary(rows, columns)),
        )
        .with_reduction(40, count)
        .fit(&grid, Some(w))
        .unwrap();
        assert_eq!(result.basis, (f, f), "both directions reduced");
        let out = result.surface.points();
        for (i, j) in boundary(rows, columns) {
            assert_eq!(out[i * columns + j], grid[i][j]);
        }
        let system = ff(&av).kronecker(&ff(&au))
            + ff(&av).kronecker(&ff(&ku)) * w.u
            + ff(&kv).kronecker(&ff(&au)) * w.v;
        let lu = system.lu();
        for k in 0..3 {
            let y = DMatrix::from_fn(ru, cv, |i, j| grid[i + 1][j + 1][k]);
            let h = DMatrix::from_fn(2, cv, |e, j| grid[[0, rows - 1][e]][j + 1][k]);
            let g = DMatrix::from_fn(ru, 2, |i, e| grid[i + 1][[0, columns - 1][e]][k]);
            let corners = DMatrix::from_fn(2, 2, |a, b| grid[[0, rows - 1][a]][[0, columns - 1][b]][k]);
            let eh = project(&n_vf, &(&h - &corners * n_ve.transpose()).transpose()).transpose(); // 2 × f
            let eg = project(&n_uf, &(&g - &n_ue * &corners)); // f × 2
            let mut c0 = DMatrix::zeros(count, count);
            for (a, &ka) in ends.iter().enumerate() {
                for (b, &kb) in ends.iter().enumerate() {
                    c0[(ka, kb)] = corners[(a, b)];
                }
                for (q, &kq) in free.iter().enumerate() {
                    c0[(ka, kq)] = eh[(a, q)];
                    c0[(kq, ka)] = eg[(q, a)];
                }
            }
            let rhs = ff(&(n_u.transpose() * &y * &n_v))
                - ff(&(&au * &c0 * &av + &ku * &c0 * &av * w.u + &au * &c0 * &kv * w.v));
            let vec_c = lu.solve(&DVector::from_column_slice(rhs.as_slice())).unwrap();
            let c = DMatrix::from_column_slice(f, f, vec_c.as_slice());
            let mut c_full = c0;
            for (a, &ka) in free.iter().enumerate() {
                for (b, &kb) in free.iter().enumerate() {
                    c_full[(ka, kb)] = c[(a, b)];
                }
            }
            let x = &n_u * c_full * n_v.transpose();
            assert_block_is(&x, out, (1, 1), columns, k, w);
        }
    }
}

#[test]
fn a_reduced_fit_pins_the_nodes_it_would_leave_on_its_own_basis() {
    // u reduced to M knots, v exact (the normal equations of `a_reduced_fit_solves_its_normal_
    // equations`), under a band 0.9 of the free fit's largest move: the nodes beyond it are
    // pinned where the free fit crosses the band, q_p = y_p + (x_p − y_p) band / |x_p − y_p|,
    // and the fit is the reduced problem's minimiser under X_p = q_p: the KKT system
    // [A Φᵀ; Φ 0] [vec C; m] = [(I ⊗ Nᵀ) vec Y; q], Φ's rows the pins' rows of I ⊗ N, solved
    // here densely. Projecting the free fit onto the band instead (what a band narrower than
    // the noise gets) fails it.
    let (rows, columns, count) = (90, 6, 25);
    let grid = noisy(rows, columns, 0.03);
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let w = Weights { u: 0.5, v: 3.0 };
    let fit = |settings: SurfaceJumpLsqSettings| {
        SurfaceJumpLsq::new(settings.with_guard(false))
            .with_reduction(50, count)
            .fit(&grid, Some(w))
            .unwrap()
    };
    let free = fit(SurfaceJumpLsqSettings::default());
    let moves: Vec<f64> = free
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(p, q)| (p - q).norm())
        .collect();
    let band = 0.9 * moves.iter().copied().fold(0.0, f64::max);
    let pins: Vec<usize> = (0..flat.len()).filter(|&k| moves[k] > band).collect();
    assert!(pins.len() >= 2, "{} pins", pins.len());
    let pinned = fit(SurfaceJumpLsqSettings::default().with_max_distance(band));
    assert_eq!((pinned.band_pins, pinned.band_projected), (pins.len(), 0));
    let targets: Vec<((usize, usize), Vec3)> = pins
        .iter()
        .map(|&k| {
            let (x, y) = (free.surface.points()[k], flat[k]);
            ((k / columns, k % columns), y + (x - y) * (band / moves[k]))
        })
        .collect();
    let expected = reduced_u_constrained_fit(&grid, count, w, &targets);
    let out = pinned.surface.points();
    let projected: Vec<Vec3> = free
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(p, q)| q + (p - q) * (band / (p - q).norm()).min(1.0))
        .collect();
    let mut clip_gap: f64 = 0.0;
    for (c, x) in expected.iter().enumerate() {
        for i in 0..rows {
            for j in 0..columns {
                let gap = (x[(i, j)] - out[i * columns + j][c]).abs();
                assert!(
                    gap < 1e-5 * band,
                    "({i}, {j}) coordinate {c}: {gap} (band {band})"
                );
                clip_gap = clip_gap.max((x[(i, j)] - projected[i * columns + j][c]).abs());
            }
        }
    }
    assert!(clip_gap > 1e-3 * band, "{clip_gap}");
}

#[test]
fn fixed_nodes_on_a_reduced_basis_solve_its_constrained_normal_equations() {
    // u reduced to M knots, v exact, nodes fixed inside the net: the fit is the reduced
    // problem's minimiser under X_p = Y_p at each fixed node, the KKT system
    // [A Φᵀ; Φ 0] [vec C; m] = [(I ⊗ Nᵀ) vec Y; Y_p] (the band test's, with the input's values),
    // solved here densely; the fixed nodes come back bit for bit and the basis stays reduced.
    let (rows, columns, count) = (90, 6, 25);
    let grid = noisy(rows, columns, 0.03);
    let w = Weights { u: 0.5, v: 3.0 };
    let fixed = [(10, 1), (37, 4), (38, 2), (71, 0), (89, 5)];
    let result = SurfaceJumpLsq::new(
        SurfaceJumpLsqSettings::default()
            .with_guard(false)
            .with_fixed(fixed),
    )
    .with_reduction(50, count)
    .fit(&grid, Some(w))
    .unwrap();
    assert_eq!(result.basis, (count, columns));
    let out = result.surface.points();
    for &(i, j) in &fixed {
        assert_eq!(out[i * columns + j], grid[i][j], "fixed node ({i}, {j})");
    }
    let targets: Vec<((usize, usize), Vec3)> = fixed.iter().map(|&(i, j)| ((i, j), grid[i][j])).collect();
    let expected = reduced_u_constrained_fit(&grid, count, w, &targets);
    let free = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_guard(false))
        .with_reduction(50, count)
        .fit(&grid, Some(w))
        .unwrap();
    let mut pulled: f64 = 0.0;
    for (c, x) in expected.iter().enumerate() {
        for i in 0..rows {
            for j in 0..columns {
                let k = i * columns + j;
                let gap = (x[(i, j)] - out[k][c]).abs();
                assert!(gap < 1e-7, "({i}, {j}) coordinate {c}: {gap}");
                if !fixed.contains(&(i, j)) {
                    pulled = pulled.max((out[k][c] - free.surface.points()[k][c]).abs());
                }
            }
        }
    }
    // The fixed nodes pull the fit beside them (the test would pass an unconstrained fit with
    // the fixed nodes written back only if they pulled nothing).
    assert!(pulled > 1e-4, "{pulled}");
}

#[test]
fn fixed_nodes_the_reduced_basis_cannot_meet_are_held_on_the_exact_path() {
    // Nine adjacent nodes fixed along u, on a basis of 12 knots over 90 sites (8 sites an
    // interval): the basis has five degrees of freedom a line there and cannot pass through
    // them, so the net is fitted on the exact path, bit for bit the fit without the reduction.
    let (rows, columns) = (90, 6);
    let grid = noisy(rows, columns, 0.03);
    let w = Weights { u: 0.5, v: 3.0 };
    let fixed: Vec<(usize, usize)> = (40..49).map(|i| (i, 2)).collect();
    let settings = SurfaceJumpLsqSettings::default()
        .with_guard(false)
        .with_fixed(fixed.clone());
    let reduced = SurfaceJumpLsq::new(settings.clone())
        .with_reduction(50, 12)
        .fit(&grid, Some(w))
        .unwrap();
    let exact = SurfaceJumpLsq::new(settings).fit(&grid, Some(w)).unwrap();
    assert_eq!(exact.basis, (rows, columns));
    assert_eq!(reduced.basis, exact.basis);
    assert_eq!(reduced.surface.points(), exact.surface.points());
    for &(i, j) in &fixed {
        assert_eq!(reduced.surface.points()[i * columns + j], grid[i][j]);
    }
}

#[test]
fn the_fixed_nodes_spread_is_their_fits_largest_free_move_over_the_unconstrained_fits() {
    // `fixed_spread` by its definition, from two fits at the same weights: one fixed node
    // spreads at most 2 (its correction is the smoother's column there, largest at the node);
    // a run of adjacent noisy fixed nodes, which the fit passes through only by carrying
    // their curvature out into the net, far more, and the catalogue warns of it.
    let (rows, columns) = (40, 30);
    let grid = noisy(rows, columns, 0.05);
    let w = Weights::both(1e4);
    let fit = |fixed: &[(usize, usize)]| {
        SurfaceJumpLsq::new(
            SurfaceJumpLsqSettings::default()
                .with_guard(false)
                .with_fixed(fixed.to_vec()),
        )
        .fit(&grid, Some(w))
        .unwrap()
    };
    let free = fit(&[]);
    assert_eq!(free.fixed_spread, 1.0);
    let largest_move = |out: &[Vec3], fixed: &[(usize, usize)]| {
        (0..rows * columns)
            .filter(|&k| !fixed.contains(&(k / columns, k % columns)))
            .map(|k| (out[k] - grid[k / columns][k % columns]).norm())
            .fold(0.0, f64::max)
    };
    let single = [(20, 15)];
    let run: Vec<(usize, usize)> = (11..19).map(|j| (20, j)).collect();
    for (fixed, bounded) in [(&single[..], true), (&run[..], false)] {
        let result = fit(fixed);
        let spread = (largest_move(result.surface.points(), fixed)
            / largest_move(free.surface.points(), fixed))
        .max(1.0);
        assert!(
            (result.fixed_spread - spread).abs() <= 1e-9 * spread,
            "{} against {spread}",
            result.fixed_spread
        );
        assert_eq!(
            spread <= super::FIXED_SPREAD_WARNING,
            bounded,
            "{} fixed nodes: spread {spread}",
            fixed.len()
        );
    }
}

#[test]
fn under_a_band_narrower_than_the_noise_the_pins_give_way_to_the_projected_fit() {
    // On 12 knots a direction, a band of a fifth of the free fit's largest move: pinning the
    // nodes beyond it pushes more out than it holds (or cannot meet them), so the free fit is
    // projected onto the band instead, bit for bit, and every node is within it.
    let grid = noisy(36, 30, 0.03);
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let fit = |settings: SurfaceJumpLsqSettings| {
        SurfaceJumpLsq::new(settings.with_guard(false))
            .with_reduction(20, 12)
            .fit(&grid, Some(Weights::both(0.05)))
            .unwrap()
    };
    let free = fit(SurfaceJumpLsqSettings::default());
    let largest = free
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    // A band wider than every move changes nothing.
    let wide = fit(SurfaceJumpLsqSettings::default().with_max_distance(1.01 * largest));
    assert_eq!(
        (wide.basis, wide.band_pins, wide.band_projected),
        ((12, 12), 0, 0)
    );
    assert_eq!(wide.surface.points(), free.surface.points());
    let band = 0.2 * largest;
    let result = fit(SurfaceJumpLsqSettings::default().with_max_distance(band));
    assert_eq!(result.basis, (12, 12));
    assert_eq!(result.band_pins, 0);
    let expected: Vec<Vec3> = free
        .surface
        .points()
        .iter()
        .zip(&flat)
        .map(|(&p, &q)| super::band_point(q, p, Some(band)))
        .collect();
    assert_eq!(
        result.band_projected,
        expected
            .iter()
            .zip(free.surface.points())
            .filter(|(e, p)| e != p)
            .count()
    );
    assert!(result.band_projected > 0);
    assert_eq!(result.surface.points(), &expected[..]);
    for (p, q) in result.surface.points().iter().zip(&flat) {
        assert!((p - q).norm() <= band);
    }
}

#[test]
fn the_exact_solve_of_a_direction_too_long_for_it_is_refused_before_it_allocates() {
    // A 5002 × 3 strip: a line held inside it needs the exact solve along the strip's 5001
    // other lines (a dense 5001² eigenproblem); refused with the reason, as a typed refusal
    // of the fixed nodes.
    // Without it the strip is faired on the reduced basis, under a band its reduced fit leaves
    // too (0.9 of its largest move: pins on the reduced basis).
    let grid = noisy_net(5002, 3, 0.02, 5, |x, y| Vec3::new(40.0 * x, y, (20.0 * x).sin()));
    let plain = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default())
        .run(&grid)
        .unwrap();
    assert!(plain.basis.0 <= 800, "{:?}", plain.basis);
    // A node fixed inside it is a constraint on the reduced fit.
    let fixed = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_fixed([(2500, 1)]))
        .run(&grid)
        .unwrap();
    assert!(fixed.basis.0 <= 800, "{:?}", fixed.basis);
    assert_eq!(fixed.surface.points()[2500 * 3 + 1], grid[2500][1]);
    let line =
        SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_fixed([(2500, 0), (2500, 1), (2500, 2)]))
            .run(&grid);
    match line {
        Err(crate::Error::Refused {
            what: crate::Refusal::Fixed,
            reason,
            ..
        }) => {
            assert!(reason.contains("5001") && reason.contains("5000"), "{reason}")
        }
        other => panic!("expected the held line refused, got {:?}", other.map(|r| r.basis)),
    }
    let largest = plain
        .surface
        .points()
        .iter()
        .zip(grid.iter().flatten())
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    let width = 0.9 * largest;
    let band = SurfaceJumpLsq::new(SurfaceJumpLsqSettings::default().with_max_distance(width))
        .run(&grid)
        .unwrap();
    assert!(
        band.basis.0 <= 800 && band.band_pins > 0,
        "{:?}, {} pins",
        band.basis,
        band.band_pins
    );
    for (p, q) in band.surface.points().iter().zip(grid.iter().flatten()) {
        assert!((p - q).norm() <= width);
    }
}

#[test]
fn a_join_to_a_neighbour_that_does_not_meet_the_edge_is_refused() {
    // The neighbour meets edge u0; joined to u1 instead, its nearest edge is the net's width
    // away, and moving u1 onto it would drag the edge across the net: refused, naming both
    // edges. Joined to u0 it is taken.
    use super::join::{Continuity, Join, JoinEdge};
    let surface = |x: f64, y: f64| Vec3::new(x, y, 0.3 * (2.0 * x).sin() * (1.5 * y).cos());
    let grid = noisy_net(20, 16, 0.01, 3, |x, y| surface(0.5 + 0.5 * x, y));
    let neighbour = noisy_net(20, 16, 0.0, 3, |x, y| surface(0.5 * x, y));
    let join = |edge| {
        SurfaceJumpLsqSettings::default().with_join(Join {
            edge,
            continuity: Continuity::G1,
            neighbour: neighbour.clone(),
            source: "neighbour".into(),
        })
    };
    assert!(SurfaceJumpLsq::new(join(JoinEdge::U0)).run(&grid).is_ok());
    match SurfaceJumpLsq::new(join(JoinEdge::U1)).run(&grid) {
        Err(crate::Error::Refused {
            what: crate::Refusal::Join,
            reason,
            ..
        }) => assert!(
            reason.contains("join u1") && reason.contains("(u1)") && reason.contains("%"),
            "{reason}"
        ),
        other => panic!("expected a refusal, got {:?}", other.map(|r| r.joins)),
    }
}
