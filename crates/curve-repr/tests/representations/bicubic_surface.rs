//! The bicubic spline surface of Zhang–Cheng §4 against its defining conditions: interpolation,
//! network curves that are natural cubic splines (checked against an independent dense solve of
//! the moment equations), continuity across knot lines, twists from splines of M^v, finite
//! differences, exact reproduction where the construction allows it, local rebuild = full
//! rebuild, and errors on bad grids.

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, Error, Parametrization, Side, Surface, Vec3};
use nalgebra::{DMatrix, DVector};
use proptest::prelude::*;

/// A natural cubic spline of scalar data in the moment form (second derivatives σ_i, σ_0 = σ_N
/// = 0, h_{i−1}σ_{i−1} + 2(h_{i−1}+h_i)σ_i + h_iσ_{i+1} = 6(Δ_i − Δ_{i−1})), solved densely by LU:
/// independent of the Hermite tangent form the library uses.
struct DenseNatural {
    x: Vec<f64>,
    y: Vec<f64>,
    sigma: Vec<f64>,
}

impl DenseNatural {
    fn new(x: &[f64], y: &[f64]) -> Self {
        let n = x.len();
        let mut a = DMatrix::<f64>::zeros(n, n);
        let mut b = DVector::<f64>::zeros(n);
        a[(0, 0)] = 1.0;
        a[(n - 1, n - 1)] = 1.0;
        for i in 1..n - 1 {
            let (h0, h1) = (x[i] - x[i - 1], x[i + 1] - x[i]);
            a[(i, i - 1)] = h0;
            a[(i, i)] = 2.0 * (h0 + h1);
            a[(i, i + 1)] = h1;
            b[i] = 6.0 * ((y[i + 1] - y[i]) / h1 - (y[i] - y[i - 1]) / h0);
        }
        let sigma = a.lu().solve(&b).expect("moment system is regular");
        Self {
            x: x.to_vec(),
            y: y.to_vec(),
            sigma: sigma.iter().copied().collect(),
        }
    }

    /// Derivative `order` at t, from the right at a knot (the last interval at the end).
    fn eval(&self, t: f64, order: usize) -> f64 {
        let n = self.x.len();
        let i = self.x.partition_point(|&k| k <= t).saturating_sub(1).min(n - 2);
        let h = self.x[i + 1] - self.x[i];
        let (a, b) = (self.x[i + 1] - t, t - self.x[i]);
        let (s0, s1) = (self.sigma[i], self.sigma[i + 1]);
        let (c0, c1) = (self.y[i] / h - s0 * h / 6.0, self.y[i + 1] / h - s1 * h / 6.0);
        match order {
            0 => s0 * a.powi(3) / (6.0 * h) + s1 * b.powi(3) / (6.0 * h) + c0 * a + c1 * b,
            1 => -s0 * a * a / (2.0 * h) + s1 * b * b / (2.0 * h) - c0 + c1,
            2 => s0 * a / h + s1 * b / h,
            _ => (s1 - s0) / h,
        }
    }
}

/// The natural spline of each coordinate of vector data.
fn dense_natural3(x: &[f64], values: &[Vec3]) -> [DenseNatural; 3] {
    let coordinate = |c: usize| values.iter().map(|p| p[c]).collect::<Vec<_>>();
    [
        DenseNatural::new(x, &coordinate(0)),
        DenseNatural::new(x, &coordinate(1)),
        DenseNatural::new(x, &coordinate(2)),
    ]
}

fn eval3(spline: &[DenseNatural; 3], t: f64, order: usize) -> Vec3 {
    Vec3::new(
        spline[0].eval(t, order),
        spline[1].eval(t, order),
        spline[2].eval(t, order),
    )
}

/// A wavy, non-uniformly spaced grid (deterministic).
fn wavy_grid(u_count: usize, v_count: usize) -> Vec<Vec<Vec3>> {
    let xs: Vec<f64> = (0..u_count)
        .map(|i| i as f64 + 0.35 * ((i * i) as f64).sin())
        .collect();
    let ys: Vec<f64> = (0..v_count)
        .map(|j| 1.3 * j as f64 + 0.4 * (j as f64 * 1.7).cos())
        .collect();
    xs.iter()
        .enumerate()
        .map(|(i, &x)| {
            ys.iter()
                .enumerate()
                .map(|(j, &y)| {
                    let noise = 0.05 * ((7 * i + 13 * j) as f64).sin();
                    Vec3::new(
                        x + 0.1 * y,
                        y - 0.05 * x,
                        (0.8 * x).sin() * (0.5 * y).cos() + noise,
                    )
                })
                .collect()
        })
        .collect()
}

fn close(a: Vec3, b: Vec3, tolerance: f64) -> bool {
    (a - b).norm() <= tolerance * (1.0 + a.norm().max(b.norm()))
}

/// Parameters inside each interval (and the knots) of a knot vector.
fn samples(knots: &[f64]) -> Vec<f64> {
    let mut t = Vec::new();
    for w in knots.windows(2) {
        for s in [0.0, 0.21, 0.5, 0.86] {
            t.push(w[0] + s * (w[1] - w[0]));
        }
    }
    t.extend(knots.last());
    t
}

#[test]
fn interpolates_every_point_and_network_curves_are_natural_splines() {
    let grid = wavy_grid(7, 6);
    let surface = BicubicSplineSurface::new(&grid).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    for (i, row) in grid.iter().enumerate() {
        for (j, p) in row.iter().enumerate() {
            assert!(close(surface.eval(uk[i], vk[j]), *p, 1e-13), "P_{i}{j}");
            for side_u in [Side::Left, Side::Right] {
                for side_v in [Side::Left, Side::Right] {
                    let value = surface.partial_from(uk[i], vk[j], 0, 0, side_u, side_v).unwrap();
                    assert!(close(value, *p, 1e-13));
                }
            }
        }
    }
    // u-lines S(u, v_j) against the dense natural spline through row j.
    for (j, &v) in vk.iter().enumerate() {
        let row: Vec<Vec3> = grid.iter().map(|line| line[j]).collect();
        let spline = dense_natural3(&uk, &row);
        for &u in &samples(&uk) {
            for order in 0..=3 {
                let expected = eval3(&spline, u, order);
                let got = surface
                    .partial_from(u, v, order, 0, Side::Right, Side::Right)
                    .unwrap();
                assert!(
                    close(got, expected, 1e-10),
                    "u-line {j} at {u}, order {order}: {got} vs {expected}"
                );
            }
        }
    }
    // v-lines S(u_i, v) against the dense natural spline through column i.
    for (i, &u) in uk.iter().enumerate() {
        let spline = dense_natural3(&vk, &grid[i]);
        for &v in &samples(&vk) {
            for order in 0..=3 {
                let expected = eval3(&spline, v, order);
                let got = surface
                    .partial_from(u, v, 0, order, Side::Right, Side::Right)
                    .unwrap();
                assert!(close(got, expected, 1e-10), "v-line {i} at {v}, order {order}");
            }
        }
    }
}

#[test]
fn twists_are_splines_of_the_v_tangents_in_either_direction() {
    let grid = wavy_grid(6, 8);
    let surface = BicubicSplineSurface::new(&grid).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    let (m1, n1) = surface.shape();
    // M^v from the dense splines along v, then the dense spline of M^v along u.
    let v_tangents: Vec<Vec<Vec3>> = (0..m1)
        .map(|i| {
            let spline = dense_natural3(&vk, &grid[i]);
            vk.iter().map(|&v| eval3(&spline, v, 1)).collect()
        })
        .collect();
    let u_tangents: Vec<Vec<Vec3>> = (0..m1)
        .map(|i| {
            (0..n1)
                .map(|j| {
                    let row: Vec<Vec3> = grid.iter().map(|line| line[j]).collect();
                    eval3(&dense_natural3(&uk, &row), uk[i], 1)
                })
                .collect()
        })
        .collect();
    for j in 0..n1 {
        let column: Vec<Vec3> = (0..m1).map(|i| v_tangents[i][j]).collect();
        let spline = dense_natural3(&uk, &column);
        for (i, &u) in uk.iter().enumerate() {
            let expected = eval3(&spline, u, 1);
            assert!(close(surface.twist(i, j).unwrap(), expected, 1e-10), "T_{i}{j}");
            assert!(close(surface.partial(u, vk[j], 1, 1).unwrap(), expected, 1e-10));
            assert!(close(surface.v_tangent(i, j).unwrap(), v_tangents[i][j], 1e-10));
            assert!(close(surface.u_tangent(i, j).unwrap(), u_tangents[i][j], 1e-10));
        }
    }
    // The other order: splines along v of M^u give the same twists (T = A_u P A_vᵀ).
    for (i, tangents) in u_tangents.iter().enumerate() {
        let spline = dense_natural3(&vk, tangents);
        for (j, &v) in vk.iter().enumerate() {
            assert!(
                close(surface.twist(i, j).unwrap(), eval3(&spline, v, 1), 1e-10),
                "T_{i}{j} via v"
            );
        }
    }
}

#[test]
fn continuity_across_knot_lines_is_c2_everywhere_and_third_derivatives_jump() {
    let surface = BicubicSplineSurface::new(&wavy_grid(6, 7)).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    let mut largest_jump: f64 = 0.0;
    for &u in &uk[1..uk.len() - 1] {
        for &v in &samples(&vk) {
            for b in 0..=3 {
                for a in 0..=3 {
                    let left = surface.partial_from(u, v, a, b, Side::Left, Side::Right).unwrap();
                    let right = surface
                        .partial_from(u, v, a, b, Side::Right, Side::Right)
                        .unwrap();
                    if a <= 2 {
                        assert!(close(left, right, 1e-10), "∂^({a},{b}) across u = {u} at v = {v}");
                    } else {
                        largest_jump = largest_jump.max((left - right).norm());
                    }
                }
            }
        }
    }
    assert!(largest_jump > 1e-3, "third derivative in u should jump somewhere");
    largest_jump = 0.0;
    for &v in &vk[1..vk.len() - 1] {
        for &u in &samples(&uk) {
            for a in 0..=3 {
                for b in 0..=3 {
                    let below = surface.partial_from(u, v, a, b, Side::Right, Side::Left).unwrap();
                    let above = surface
                        .partial_from(u, v, a, b, Side::Right, Side::Right)
                        .unwrap();
                    if b <= 2 {
                        assert!(
                            close(below, above, 1e-10),
                            "∂^({a},{b}) across v = {v} at u = {u}"
                        );
                    } else {
                        largest_jump = largest_jump.max((below - above).norm());
                    }
                }
            }
        }
    }
    assert!(largest_jump > 1e-3, "third derivative in v should jump somewhere");
}

#[test]
fn partials_agree_with_finite_differences() {
    let surface = BicubicSplineSurface::new(&wavy_grid(5, 6)).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    let step = 1e-5;
    for iu in 0..uk.len() - 1 {
        for jv in 0..vk.len() - 1 {
            for (su, sv) in [(0.3, 0.6), (0.71, 0.18)] {
                let u = uk[iu] + su * (uk[iu + 1] - uk[iu]);
                let v = vk[jv] + sv * (vk[jv + 1] - vk[jv]);
                for a in 0..=3 {
                    for b in 0..=3 {
                        let value = |u: f64, v: f64| surface.partial(u, v, a, b).unwrap();
                        if a < 3 {
                            let difference = (value(u + step, v) - value(u - step, v)) / (2.0 * step);
                            let exact = surface.partial(u, v, a + 1, b).unwrap();
                            assert!(
                                close(difference, exact, 1e-6),
                                "d/du of ({a},{b}): {difference} vs {exact}"
                            );
                        }
                        if b < 3 {
                            let difference = (value(u, v + step) - value(u, v - step)) / (2.0 * step);
                            let exact = surface.partial(u, v, a, b + 1).unwrap();
                            assert!(close(difference, exact, 1e-6), "d/dv of ({a},{b})");
                        }
                    }
                }
            }
        }
    }
    assert_eq!(surface.partial(0.5, 0.5, 4, 0), None);
    assert_eq!(surface.partial(0.5, 0.5, 0, 4), None);
    assert_eq!(surface.partial(f64::NAN, 0.5, 0, 0), None);
}

#[test]
fn bilinear_data_are_reproduced_exactly() {
    let uk = vec![0.0, 0.4, 1.5, 1.7, 3.0];
    let vk = vec![-1.0, 0.2, 0.5, 2.5];
    let (a, b, c, d) = (
        Vec3::new(1.0, -2.0, 0.5),
        Vec3::new(0.3, 1.1, -0.7),
        Vec3::new(-0.4, 0.2, 0.9),
        Vec3::new(0.25, -0.6, 1.3),
    );
    let f = |u: f64, v: f64| a + b * u + c * v + d * (u * v);
    let grid: Vec<Vec<Vec3>> = uk
        .iter()
        .map(|&u| vk.iter().map(|&v| f(u, v)).collect())
        .collect();
    let settings = BicubicSurfaceSettings::default()
        .with_u_knots(uk.clone())
        .with_v_knots(vk.clone());
    let surface = BicubicSplineSurface::with_settings(&grid, &settings).unwrap();
    for &u in &samples(&uk) {
        for &v in &samples(&vk) {
            assert!(close(surface.eval(u, v), f(u, v), 1e-13));
            assert!(close(surface.partial(u, v, 1, 0).unwrap(), b + d * v, 1e-12));
            assert!(close(surface.partial(u, v, 0, 1).unwrap(), c + d * u, 1e-12));
            assert!(close(surface.partial(u, v, 1, 1).unwrap(), d, 1e-12));
            for (du, dv) in [(2, 0), (0, 2), (3, 0), (0, 3), (2, 1), (3, 3)] {
                // Exactly zero in exact arithmetic; in floating point a derivative of order
                // (du, dv) amplifies the data's round-off by 1/(h_u^du h_v^dv) with the
                // smallest spacings (0.2 and 0.3 here), so the bound scales with it.
                let amplification = 0.2f64.powi(du as i32) * 0.3f64.powi(dv as i32);
                assert!(
                    surface.partial(u, v, du, dv).unwrap().norm() < 1e-13 / amplification,
                    "({du},{dv}) {}",
                    surface.partial(u, v, du, dv).unwrap().norm()
                );
            }
        }
    }
    assert!(surface.max_z() < 1e-10);
    // The smallest grid: one bilinear patch.
    let small =
        BicubicSplineSurface::new(&[vec![f(0.0, 0.0), f(0.0, 1.0)], vec![f(1.0, 0.0), f(1.0, 1.0)]]).unwrap();
    let scale = |t: f64, knots: &[f64]| t / knots[1];
    let (su, sv) = (small.u_knots().to_vec(), small.v_knots().to_vec());
    for &(s, t) in &[(0.2, 0.9), (0.5, 0.5), (1.0, 0.3)] {
        let bilinear = f(0.0, 0.0) * ((1.0 - s) * (1.0 - t))
            + f(1.0, 0.0) * (s * (1.0 - t))
            + f(0.0, 1.0) * ((1.0 - s) * t)
            + f(1.0, 1.0) * (s * t);
        let point = small.eval(s * su[1], t * sv[1]);
        assert!(
            close(point, bilinear, 1e-13),
            "{} {}",
            scale(s, &su),
            scale(t, &sv)
        );
    }
}

#[test]
fn planes_are_reproduced_with_averaged_chord_length_knots() {
    // A plane over a non-uniform rectangular x-y grid: the averaged chord steps are then
    // proportional to the x and y steps, so x is affine in u, y in v, and z in both.
    let xs = [0.0, 0.3, 1.2, 1.5, 2.9, 3.1];
    let ys = [-1.0, -0.2, 0.1, 1.4, 2.0];
    let plane = |x: f64, y: f64| 0.7 * x - 1.3 * y + 0.2;
    let grid: Vec<Vec<Vec3>> = xs
        .iter()
        .map(|&x| ys.iter().map(|&y| Vec3::new(x, y, plane(x, y))).collect())
        .collect();
    let surface = BicubicSplineSurface::new(&grid).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    let x_of_u = |u: f64| xs[0] + (u - uk[0]) * (xs[5] - xs[0]) / (uk[5] - uk[0]);
    let y_of_v = |v: f64| ys[0] + (v - vk[0]) * (ys[4] - ys[0]) / (vk[4] - vk[0]);
    for &u in &samples(&uk) {
        for &v in &samples(&vk) {
            let (x, y) = (x_of_u(u), y_of_v(v));
            assert!(close(surface.eval(u, v), Vec3::new(x, y, plane(x, y)), 1e-12));
            assert!(surface.partial(u, v, 2, 0).unwrap().norm() < 1e-10);
            assert!(surface.partial(u, v, 0, 2).unwrap().norm() < 1e-10);
        }
    }
    // Any grid of coplanar points stays in its plane (the construction is affine invariant).
    let normal = Vec3::new(0.3, -0.5, 1.0);
    let distorted: Vec<Vec<Vec3>> = wavy_grid(5, 6)
        .iter()
        .map(|row| {
            row.iter()
                .map(|p| Vec3::new(p.x, p.y, (2.0 - normal.x * p.x - normal.y * p.y) / normal.z))
                .collect()
        })
        .collect();
    let surface = BicubicSplineSurface::new(&distorted).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    for &u in &samples(&uk) {
        for &v in &samples(&vk) {
            assert!((surface.eval(u, v).dot(&normal) - 2.0).abs() < 1e-12);
            assert!(surface.partial(u, v, 2, 1).unwrap().dot(&normal).abs() < 1e-10);
        }
    }
}

#[test]
fn tensor_products_of_natural_splines_are_reproduced_and_quadrics_are_not() {
    let uk = vec![0.0, 0.5, 0.8, 1.9, 2.4, 3.6];
    let vk = vec![0.0, 1.0, 1.3, 2.9, 3.2];
    // f and g: natural cubic splines over the knots (not polynomials).
    let f = DenseNatural::new(&uk, &[0.3, -1.0, 0.4, 2.0, -0.5, 1.0]);
    let g = DenseNatural::new(&vk, &[1.0, 0.2, -0.7, 0.9, 0.1]);
    let settings = BicubicSurfaceSettings::default()
        .with_u_knots(uk.clone())
        .with_v_knots(vk.clone());
    let target = |u: f64, v: f64, a: usize, b: usize| {
        let (u_order, v_order) = (a, b);
        let linear_u = [u, 1.0, 0.0, 0.0][u_order];
        let linear_v = [v, 1.0, 0.0, 0.0][v_order];
        let constant = |order: usize, value: f64| if order == 0 { value } else { 0.0 };
        Vec3::new(
            f.eval(u, u_order) * g.eval(v, v_order),
            linear_u * constant(v_order, 1.0),
            constant(u_order, 1.0) * linear_v,
        )
    };
    let grid: Vec<Vec<Vec3>> = uk
        .iter()
        .map(|&u| vk.iter().map(|&v| target(u, v, 0, 0)).collect())
        .collect();
    let surface = BicubicSplineSurface::with_settings(&grid, &settings).unwrap();
    for &u in &samples(&uk) {
        for &v in &samples(&vk) {
            for a in 0..=3 {
                for b in 0..=3 {
                    let got = surface.partial(u, v, a, b).unwrap();
                    assert!(close(got, target(u, v, a, b), 1e-10), "({a},{b}) at ({u},{v})");
                }
            }
        }
    }

    // z = x² + y² with knots u = x, v = y: a sum s_f(u) + s_g(v) of the natural splines of x²
    // and y², not the quadric: the natural ends force ∂²z/∂u² = 0 at u_0 instead of 2.
    let grid: Vec<Vec<Vec3>> = uk
        .iter()
        .map(|&x| vk.iter().map(|&y| Vec3::new(x, y, x * x + y * y)).collect())
        .collect();
    let surface = BicubicSplineSurface::with_settings(&grid, &settings).unwrap();
    let sf = DenseNatural::new(&uk, &uk.iter().map(|x| x * x).collect::<Vec<_>>());
    let sg = DenseNatural::new(&vk, &vk.iter().map(|y| y * y).collect::<Vec<_>>());
    for &u in &samples(&uk) {
        for &v in &samples(&vk) {
            let z = surface.eval(u, v).z;
            assert!((z - (sf.eval(u, 0) + sg.eval(v, 0))).abs() < 1e-12 * (1.0 + z.abs()));
            assert!(surface.partial(u, v, 1, 1).unwrap().norm() < 1e-12);
        }
    }
    assert!(surface.twists().iter().all(|t| t.norm() < 1e-12));
    assert!(surface.partial(uk[0], 1.0, 2, 0).unwrap().z.abs() < 1e-12);
    let middle = surface.partial(1.9, 1.3, 2, 0).unwrap().z;
    assert!(
        (middle - 2.0).abs() > 1e-3,
        "the quadric is not reproduced: S_uu = {middle}"
    );
}

#[test]
fn third_derivative_jumps_and_z_match_one_sided_limits() {
    let surface = BicubicSplineSurface::new(&wavy_grid(6, 5)).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    let jumps = surface.third_derivative_jumps();
    assert_eq!(jumps.len(), 4 * 3);
    let mut max_z: f64 = 0.0;
    for jump in &jumps {
        let (u, v) = (uk[jump.i], vk[jump.j]);
        let u_jump = surface
            .partial_from(u, v, 3, 0, Side::Right, Side::Right)
            .unwrap()
            - surface.partial_from(u, v, 3, 0, Side::Left, Side::Right).unwrap();
        let v_jump = surface
            .partial_from(u, v, 0, 3, Side::Right, Side::Right)
            .unwrap()
            - surface.partial_from(u, v, 0, 3, Side::Right, Side::Left).unwrap();
        assert!(close(jump.u, u_jump, 1e-10) && close(jump.v, v_jump, 1e-10));
        let z = surface.z(jump.i, jump.j).unwrap();
        assert!((z - (u_jump.norm() + v_jump.norm())).abs() < 1e-9 * (1.0 + z));
        max_z = max_z.max(z);
    }
    assert_eq!(surface.max_z(), max_z);
    assert!(max_z > 0.0);
    for (i, j) in [(0, 2), (5, 2), (2, 0), (2, 4), (9, 9)] {
        assert_eq!(surface.z(i, j), None);
    }
}

#[test]
fn network_strain_energy_equals_the_integral_of_the_network_curvature() {
    let surface = BicubicSplineSurface::new(&wavy_grid(5, 7)).unwrap();
    let (uk, vk) = (surface.u_knots().to_vec(), surface.v_knots().to_vec());
    // 3-point Gauss–Legendre is exact for the quadratic |S''|² on each segment.
    let nodes = [
        (-(0.6f64).sqrt(), 5.0 / 9.0),
        (0.0, 8.0 / 9.0),
        ((0.6f64).sqrt(), 5.0 / 9.0),
    ];
    let integrate = |knots: &[f64], f: &dyn Fn(f64) -> f64| {
        knots
            .windows(2)
            .map(|w| {
                let (mid, half) = ((w[0] + w[1]) / 2.0, (w[1] - w[0]) / 2.0);
                nodes
                    .iter()
                    .map(|&(x, weight)| weight * half * f(mid + half * x))
                    .sum::<f64>()
            })
            .sum::<f64>()
    };
    let mut expected = 0.0;
    for &v in &vk {
        expected += integrate(&uk, &|u| surface.partial(u, v, 2, 0).unwrap().norm_squared());
    }
    for &u in &uk {
        expected += integrate(&vk, &|v| surface.partial(u, v, 0, 2).unwrap().norm_squared());
    }
    let energy = surface.network_strain_energy();
    assert!(
        (energy - expected).abs() < 1e-10 * expected,
        "{energy} vs {expected}"
    );
    assert!(energy > 0.0);
}

#[test]
fn settings_choose_the_knots() {
    let grid = wavy_grid(4, 3);
    let surface = BicubicSplineSurface::new(&grid).unwrap();
    // Averaged chord length, by the definition.
    for i in 0..3 {
        let mean: f64 = (0..3).map(|j| (grid[i + 1][j] - grid[i][j]).norm()).sum::<f64>() / 3.0;
        let step = surface.u_knots()[i + 1] - surface.u_knots()[i];
        assert!((step - mean).abs() < 1e-14 * mean);
    }
    for j in 0..2 {
        let mean: f64 = (0..4).map(|i| (grid[i][j + 1] - grid[i][j]).norm()).sum::<f64>() / 4.0;
        let step = surface.v_knots()[j + 1] - surface.v_knots()[j];
        assert!((step - mean).abs() < 1e-14 * mean);
    }
    assert_eq!(surface.u_knots()[0], 0.0);
    let uniform = BicubicSplineSurface::with_settings(
        &grid,
        &BicubicSurfaceSettings::default().with_parametrization(Parametrization::Uniform),
    )
    .unwrap();
    assert_eq!(uniform.u_knots(), &[0.0, 1.0, 2.0, 3.0]);
    assert_eq!(uniform.v_knots(), &[0.0, 1.0, 2.0]);
    assert_eq!(uniform.grid(), grid);
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    let from_flat = BicubicSplineSurface::from_flat(flat, 4, 3, &BicubicSurfaceSettings::default()).unwrap();
    assert_eq!(from_flat, surface);
}

#[test]
fn bad_grids_are_errors() {
    let grid = wavy_grid(4, 3);
    let settings = BicubicSurfaceSettings::default();
    let mut ragged = grid.clone();
    ragged[2].pop();
    assert_eq!(
        BicubicSplineSurface::new(&ragged),
        Err(Error::RaggedGrid {
            row: 2,
            expected: 3,
            got: 2
        })
    );
    let mut nan = grid.clone();
    nan[1][2].y = f64::NAN;
    assert!(matches!(
        BicubicSplineSurface::new(&nan),
        Err(Error::NonFinite { index: 5, .. })
    ));
    let mut infinite = grid.clone();
    infinite[0][0].x = f64::INFINITY;
    assert!(matches!(
        BicubicSplineSurface::new(&infinite),
        Err(Error::NonFinite { .. })
    ));
    // Repeated grid lines: rows i = 1, 2 equal, or columns j = 0, 1 equal.
    let mut repeated_u = grid.clone();
    repeated_u[2] = repeated_u[1].clone();
    assert_eq!(
        BicubicSplineSurface::new(&repeated_u),
        Err(Error::RepeatedGridLine {
            direction: "u",
            index: 1
        })
    );
    let mut repeated_v = grid.clone();
    for row in &mut repeated_v {
        row[1] = row[0];
    }
    assert_eq!(
        BicubicSplineSurface::new(&repeated_v),
        Err(Error::RepeatedGridLine {
            direction: "v",
            index: 0
        })
    );
    // Too few lines in a direction.
    assert!(matches!(
        BicubicSplineSurface::new(&grid[..1]),
        Err(Error::TooFewPoints { .. })
    ));
    let single_column: Vec<Vec<Vec3>> = grid.iter().map(|row| vec![row[0]]).collect();
    assert!(matches!(
        BicubicSplineSurface::new(&single_column),
        Err(Error::TooFewPoints { .. })
    ));
    assert!(matches!(
        BicubicSplineSurface::new(&[]),
        Err(Error::TooFewPoints { .. })
    ));
    let empty_rows = vec![Vec::new(), Vec::new()];
    assert!(matches!(
        BicubicSplineSurface::new(&empty_rows),
        Err(Error::TooFewPoints { .. })
    ));
    // Given knots: wrong length, not increasing, not finite.
    let bad =
        |knots: Vec<f64>| BicubicSplineSurface::with_settings(&grid, &settings.clone().with_u_knots(knots));
    assert!(matches!(
        bad(vec![0.0, 1.0, 2.0]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        bad(vec![0.0, 1.0, 1.0, 2.0]),
        Err(Error::NotIncreasing { index: 2, .. })
    ));
    assert!(matches!(
        bad(vec![0.0, 1.0, f64::NAN, 2.0]),
        Err(Error::NonFinite { .. })
    ));
    let bad_v =
        BicubicSplineSurface::with_settings(&grid, &settings.clone().with_v_knots(vec![2.0, 1.0, 3.0]));
    assert!(matches!(bad_v, Err(Error::NotIncreasing { .. })));
    // Flat grid of the wrong size.
    let flat: Vec<Vec3> = grid.iter().flatten().copied().collect();
    assert!(matches!(
        BicubicSplineSurface::from_flat(flat.clone(), 3, 3, &settings),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        BicubicSplineSurface::from_flat(flat, 12, 1, &settings),
        Err(Error::TooFewPoints { .. })
    ));
    // Finite points whose chord lengths overflow.
    let huge: Vec<Vec<Vec3>> = vec![
        vec![Vec3::new(-f64::MAX, 0.0, 0.0), Vec3::new(-f64::MAX, 1.0, 0.0)],
        vec![Vec3::new(f64::MAX, 0.0, 0.0), Vec3::new(f64::MAX, 1.0, 0.0)],
    ];
    assert!(matches!(
        BicubicSplineSurface::new(&huge),
        Err(Error::NonFinite { .. })
    ));
    // Knot steps so small that tangents overflow.
    let tiny = BicubicSplineSurface::with_settings(
        &grid,
        &settings.clone().with_u_knots(vec![0.0, 1e-310, 2e-310, 3e-310]),
    );
    assert!(matches!(tiny, Err(Error::NonFinite { .. })));
}

fn full_rebuild(surface: &BicubicSplineSurface) -> BicubicSplineSurface {
    let settings = BicubicSurfaceSettings::default()
        .with_u_knots(surface.u_knots().to_vec())
        .with_v_knots(surface.v_knots().to_vec());
    BicubicSplineSurface::with_settings(&surface.grid(), &settings).unwrap()
}

fn relative_difference(a: &[Vec3], b: &[Vec3]) -> f64 {
    let scale = b
        .iter()
        .map(|p| p.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    a.iter().zip(b).map(|(x, y)| (x - y).norm()).fold(0.0, f64::max) / scale
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn move_points_equals_a_full_rebuild(
        u_count in 2usize..9,
        v_count in 2usize..9,
        seed in proptest::collection::vec(-1.0f64..1.0, 64 * 3),
        moves in proptest::collection::vec((0usize..64, 0usize..64, -2.0f64..2.0, -2.0f64..2.0, -2.0f64..2.0), 1..12),
    ) {
        let grid: Vec<Vec<Vec3>> = (0..u_count)
            .map(|i| {
                (0..v_count)
                    .map(|j| {
                        let k = 3 * (i * 8 + j);
                        Vec3::new(i as f64 + 0.3 * seed[k], j as f64 + 0.3 * seed[k + 1], seed[k + 2])
                    })
                    .collect()
            })
            .collect();
        let mut surface = BicubicSplineSurface::new(&grid).unwrap();
        let moves: Vec<((usize, usize), Vec3)> = moves
            .iter()
            .map(|&(i, j, x, y, z)| ((i % u_count, j % v_count), Vec3::new(x, y, z)))
            .collect();
        // Two steps: the second starts from an updated surface, as a fairing loop does.
        let (first, second) = moves.split_at(moves.len() / 2);
        surface.move_points(first).unwrap();
        surface.move_points(second).unwrap();
        let full = full_rebuild(&surface);
        prop_assert_eq!(surface.points(), full.points());
        prop_assert!(relative_difference(surface.u_tangents(), full.u_tangents()) < 1e-12);
        prop_assert!(relative_difference(surface.v_tangents(), full.v_tangents()) < 1e-12);
        prop_assert!(relative_difference(surface.twists(), full.twists()) < 1e-12);
        let energy = (surface.network_strain_energy() - full.network_strain_energy()).abs();
        prop_assert!(energy <= 1e-12 * full.network_strain_energy().max(1e-300));
    }
}
