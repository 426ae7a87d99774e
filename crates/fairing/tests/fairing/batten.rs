//! Okada's batten: each equation against its defining condition (Eq. 12: ∂V/∂X_i = 0; Eq. 13:
//! ∂V/∂P_i = 0, or the projection condition where a range binds; the end tangent: the circle
//! and the equal second derivatives of Step 2), and the strategy's guarantees.

use curve_repr::{Vec2, Vector};
use fairing::strategies::batten::{
    self, chords, circle_tangent, curvature_signs, end_tangent, energy, eq13_positions, eq13_sweep,
    okada_tangents,
};
use fairing::strategies::{Batten, BattenSettings, PositionUpdate};
use fairing::{Constraints, Error, FairingState, FairingStrategy, Pipeline, Refusal, TerminationReason};
use proptest::prelude::*;

/// A noisy spatial (or planar) arc: n points on a circle of radius 10, lifted in z for D = 3.
fn noisy_arc<const D: usize>(noise: &[f64]) -> Vec<Vector<D>> {
    let n = noise.len() / D;
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.2;
            let mut v = Vector::<D>::zeros();
            v[0] = 10.0 * a.cos();
            v[1] = 10.0 * a.sin();
            if D > 2 {
                v[2] = 0.7 * i as f64;
            }
            for c in 0..D {
                v[c] += noise[i * D + c];
            }
            v
        })
        .collect()
}

fn noise(max_points: usize, d: usize) -> impl Strategy<Value = Vec<f64>> {
    (4..max_points).prop_flat_map(move |n| prop::collection::vec(-0.3f64..0.3, n * d))
}

/// Central difference of f along every axis of x.
fn fd_grad<const D: usize>(f: impl Fn(Vector<D>) -> f64, x: Vector<D>, eps: f64) -> Vector<D> {
    let mut g = Vector::<D>::zeros();
    for c in 0..D {
        let (mut a, mut b) = (x, x);
        a[c] += eps;
        b[c] -= eps;
        g[c] = (f(a) - f(b)) / (2.0 * eps);
    }
    g
}

/// Eq. 12: with the tangents Okada's recurrence gives, V (Eq. 5, k held) is stationary in
/// every interior X_i (Y_{i−1} = k_i X_i moves with it).
fn check_eq12<const D: usize>(p: &[Vector<D>]) {
    let t = okada_tangents(p, &[]).unwrap();
    let scale = 1.0 + energy(p, &t);
    for i in 1..p.len() - 1 {
        let g = fd_grad(
            |xi| {
                let mut u = t.clone();
                u.x[i] = xi;
                energy(p, &u)
            },
            t.x[i],
            1e-4,
        );
        // the size of the gradient a unit change of X_i makes, for scale
        let g0 = fd_grad(
            |xi| {
                let mut u = t.clone();
                u.x[i] = xi;
                energy(p, &u)
            },
            t.x[i] * 1.5 + Vector::<D>::repeat(0.1),
            1e-4,
        );
        assert!(
            g.norm() <= 1e-7 * (scale + g0.norm()),
            "Eq. 12 at {i}: grad {g:?} (vs {g0:?} elsewhere)"
        );
    }
}

/// Eq. 13: with the tangents and chords held, V is stationary in every free interior P_i and
/// the fixed points and ends keep their positions bit for bit.
fn check_eq13<const D: usize>(p: &[Vector<D>], fixed: usize) {
    let n = p.len();
    let t = okada_tangents(p, &[]).unwrap();
    let fixed = 1 + fixed % (n - 2);
    let movable: Vec<bool> = (0..n).map(|i| i > 0 && i + 1 < n && i != fixed).collect();
    let q = eq13_positions(p, &t, &movable, p, &vec![f64::INFINITY; n], 100).unwrap();
    assert_eq!(q[0], p[0]);
    assert_eq!(q[n - 1], p[n - 1]);
    assert_eq!(q[fixed], p[fixed]);
    let scale = 1.0 + energy(p, &t);
    for i in (1..n - 1).filter(|&i| movable[i]) {
        let g = fd_grad(
            |pi| {
                let mut r = q.clone();
                r[i] = pi;
                energy(&r, &t)
            },
            q[i],
            1e-4,
        );
        assert!(g.norm() <= 1e-7 * scale, "Eq. 13 at {i}: grad {g:?}");
    }
    assert!(energy(&q, &t) <= energy(p, &t) * (1.0 + 1e-12));
}

/// Eq. 13 with adjustable ranges: the result is the constrained minimiser, i.e. every free
/// point inside its ball has zero gradient and every point on its sphere has a gradient
/// pointing inwards along the radius (KKT for a ball).
fn check_eq13_ranges<const D: usize>(p: &[Vector<D>], radius: f64) {
    let n = p.len();
    let t = okada_tangents(p, &[]).unwrap();
    let movable: Vec<bool> = (0..n).map(|i| i > 0 && i + 1 < n).collect();
    let allowed = vec![radius; n];
    let q = eq13_positions(p, &t, &movable, p, &allowed, 100_000).unwrap();
    let scale = 1.0 + energy(p, &t);
    for i in 1..n - 1 {
        let d = q[i] - p[i];
        assert!(d.norm() <= radius, "point {i} left its range");
        let g = fd_grad(
            |pi| {
                let mut r = q.clone();
                r[i] = pi;
                energy(&r, &t)
            },
            q[i],
            1e-5,
        );
        if d.norm() < radius * (1.0 - 1e-9) {
            assert!(g.norm() <= 1e-6 * scale, "free point {i}: grad {g:?}");
        } else {
            let normal = d / d.norm();
            let tangential = g - normal * g.dot(&normal);
            assert!(
                g.dot(&normal) <= 1e-6 * scale,
                "point {i}: gradient points outwards"
            );
            assert!(
                tangential.norm() <= 1e-6 * scale,
                "point {i}: tangential grad {tangential:?}"
            );
        }
    }
}

/// Step 2: the end tangent is tangent to the circle through the three end points (its
/// centre computed independently), and the two quadratics' second derivatives (chord-length)
/// can be made equal at the middle point: the residual with X's magnitude is parallel to the
/// circle's tangent at the third point.
fn check_end_tangent<const D: usize>(p0: Vector<D>, p1: Vector<D>, p2: Vector<D>) {
    let Some(x) = end_tangent(p0, p1, p2, None) else {
        return;
    };
    let u0 = x / x.norm();
    // circumcentre: c = p0 + s·a + t·b with |c − p0| = |c − p1| = |c − p2|
    let (a, b) = (p1 - p0, p2 - p0);
    let (aa, ab, bb) = (a.dot(&a), a.dot(&b), b.dot(&b));
    let det = 2.0 * (aa * bb - ab * ab);
    if det.abs() < 1e-6 * aa * bb {
        return; // nearly collinear: no circle worth testing
    }
    let s = (bb * (aa - ab)) / det;
    let t = (aa * (bb - ab)) / det;
    let centre = p0 + a * s + b * t;
    let radial = (p0 - centre) / (p0 - centre).norm();
    assert!(u0.dot(&radial).abs() < 1e-9, "not tangent to the circle");
    assert!(u0.dot(&a) > 0.0, "points away from P1");
    let u2 = -circle_tangent(p2, p1, p0).unwrap();
    let radial2 = (p2 - centre) / (p2 - centre).norm();
    assert!(u2.dot(&radial2).abs() < 1e-9);
    let (c0, c1) = (a.norm(), (p2 - p1).norm());
    assert!(x.norm() > 0.0 && x.norm() <= 3.0 * c0 * (1.0 + 1e-15));
    if (x.norm() - c0).abs() <= 1e-12 * c0 {
        return; // the documented fallback (wide arc): nothing more to check
    }
    let w = (p1 - p0 - x) / (c0 * c0) + (p2 - p1) / (c1 * c1); // must equal b·u2/C1²
    let off = w - u2 * w.dot(&u2);
    assert!(
        off.norm() <= 1e-9 * w.norm().max(1.0 / (c0 * c0)),
        "second derivatives differ: {off:?}"
    );
}

/// One Gauss–Seidel sweep of Eq. 13: each free point is the minimiser of V in its own
/// position (within its range) given its left neighbour as already updated and its right
/// neighbour as it was; a Jacobi sweep: given both neighbours as they were. Ranges hold.
fn check_eq13_sweep<const D: usize>(p: &[Vector<D>], radius: f64, gauss_seidel: bool) {
    let n = p.len();
    let t = okada_tangents(p, &[]).unwrap();
    let movable: Vec<bool> = (0..n).map(|i| i > 0 && i + 1 < n).collect();
    let q = eq13_sweep(p, &t, &movable, p, &vec![radius; n], gauss_seidel).unwrap();
    assert_eq!(q[0], p[0]);
    assert_eq!(q[n - 1], p[n - 1]);
    let scale = 1.0 + energy(p, &t);
    for i in 1..n - 1 {
        // the configuration point i saw: updated left part (Gauss–Seidel) or the old one
        let mut seen: Vec<Vector<D>> = p.to_vec();
        if gauss_seidel {
            seen[..i].copy_from_slice(&q[..i]);
        }
        let g = fd_grad(
            |pi| {
                let mut r = seen.clone();
                r[i] = pi;
                energy(&r, &t)
            },
            q[i],
            1e-5,
        );
        let d = q[i] - p[i];
        assert!(d.norm() <= radius);
        if d.norm() < radius * (1.0 - 1e-9) {
            assert!(g.norm() <= 1e-6 * scale, "point {i}: grad {g:?}");
        } else {
            let normal = d / d.norm();
            assert!(g.dot(&normal) <= 1e-6 * scale);
            assert!((g - normal * g.dot(&normal)).norm() <= 1e-6 * scale);
        }
    }
}

/// Eq. 12 makes the Ferguson chain C2 in the chord-length parameter s = C_i t: at every
/// interior point, d²P/ds² = P̈/C² is the same from both segments (and the first derivative
/// X/C too, by Y_{i−1} = k_i X_i).
fn check_eq12_c2<const D: usize>(p: &[Vector<D>]) {
    let t = okada_tangents(p, &[]).unwrap();
    for i in 1..p.len() - 1 {
        let [_, _, r2l, r3l] = batten::ferguson(p[i - 1], p[i], t.x[i - 1], t.y(i - 1).unwrap());
        let [_, _, r2r, _] = batten::ferguson(p[i], p[i + 1], t.x[i], t.y(i).unwrap());
        let (cl, cr) = (t.chords[i - 1], t.chords[i]);
        let left = (r2l * 2.0 + r3l * 6.0) / (cl * cl);
        let right = r2r * 2.0 / (cr * cr);
        assert!(
            (left - right).norm() <= 1e-9 * (1.0 + left.norm()),
            "C2 at {i}: {left:?} vs {right:?}"
        );
        let (dl, dr) = (t.y(i - 1).unwrap() / cl, t.x[i] / cr);
        assert!((dl - dr).norm() <= 1e-12 * (1.0 + dl.norm()));
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn eq13_sweeps_2d(n in noise(20, 2), r in 0.001f64..1.0, gs in any::<bool>()) {
        check_eq13_sweep(&noisy_arc::<2>(&n), r, gs);
    }
    #[test]
    fn eq13_sweeps_3d(n in noise(20, 3), r in 0.001f64..1.0, gs in any::<bool>()) {
        check_eq13_sweep(&noisy_arc::<3>(&n), r, gs);
    }
    #[test]
    fn eq12_2d(n in noise(30, 2)) { check_eq12(&noisy_arc::<2>(&n)); }
    #[test]
    fn eq12_is_c2_2d(n in noise(30, 2)) { check_eq12_c2(&noisy_arc::<2>(&n)); }
    #[test]
    fn eq12_is_c2_3d(n in noise(30, 3)) { check_eq12_c2(&noisy_arc::<3>(&n)); }
    #[test]
    fn eq12_3d(n in noise(30, 3)) { check_eq12(&noisy_arc::<3>(&n)); }
    #[test]
    fn eq13_2d(n in noise(30, 2), f in 0usize..100) { check_eq13(&noisy_arc::<2>(&n), f); }
    #[test]
    fn eq13_3d(n in noise(30, 3), f in 0usize..100) { check_eq13(&noisy_arc::<3>(&n), f); }
    #[test]
    fn eq13_ranges_2d(n in noise(20, 2), r in 0.001f64..0.2) { check_eq13_ranges(&noisy_arc::<2>(&n), r); }
    #[test]
    fn eq13_ranges_3d(n in noise(20, 3), r in 0.001f64..0.2) { check_eq13_ranges(&noisy_arc::<3>(&n), r); }
    #[test]
    fn end_tangent_3d(v in prop::collection::vec(-10.0f64..10.0, 9)) {
        let p = |k: usize| Vector::<3>::new(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
        check_end_tangent(p(0), p(1), p(2));
    }
}

/// On a circle with equal chords the end tangent's magnitude is R tan θ (the reading of
/// Step 2 (2) documented on `end_tangent`), which tends to the chord for small θ.
#[test]
fn end_tangent_on_a_circle() {
    for (r, theta) in [(1.0, 0.3), (5.0, 0.05), (2.0, 1.0)] {
        let p = |k: f64| Vec2::new(r * (k * theta).cos(), r * (k * theta).sin());
        let x = end_tangent(p(0.0), p(1.0), p(2.0), None).unwrap();
        assert!(
            (x.norm() - r * f64::tan(theta)).abs() < 1e-12 * r,
            "{} vs {}",
            x.norm(),
            r * theta.tan()
        );
        assert!(x.x.abs() < 1e-12 && x.y > 0.0);
    }
    // collinear points: the chord
    let x = end_tangent(
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(3.0, 0.0),
        None,
    )
    .unwrap();
    assert!((x - Vec2::new(1.0, 0.0)).norm() < 1e-12);
}

/// Step 4: curvature signs of a counter-clockwise circle are all +1, clockwise all −1; a
/// planar S curve changes sign once.
#[test]
fn curvature_signs_follow_the_turning() {
    let ccw: Vec<Vec2> = (0..12)
        .map(|i| Vec2::new((i as f64 * 0.3).cos(), (i as f64 * 0.3).sin()))
        .collect();
    let t = okada_tangents(&ccw, &[]).unwrap();
    assert!(curvature_signs(&ccw, &t).iter().all(|&s| s == 1));
    let cw: Vec<Vec2> = ccw.iter().map(|p| Vec2::new(p.x, -p.y)).collect();
    let t = okada_tangents(&cw, &[]).unwrap();
    assert!(curvature_signs(&cw, &t).iter().all(|&s| s == -1));
    let s_curve: Vec<Vec2> = (0..21)
        .map(|i| {
            let x = i as f64 * 0.3 - 3.0;
            Vec2::new(x, x.powi(3) * 0.1)
        })
        .collect();
    let t = okada_tangents(&s_curve, &[]).unwrap();
    let signs: Vec<i8> = curvature_signs(&s_curve, &t)
        .into_iter()
        .filter(|&s| s != 0)
        .collect();
    assert_eq!(signs.windows(2).filter(|w| w[0] != w[1]).count(), 1, "{signs:?}");
}

/// A prescribed tangent direction is kept (the tangent there is parallel to it, pointing the
/// same way), and Eq. 12 still holds at every other interior point.
#[test]
fn prescribed_tangent_direction() {
    let noise: Vec<f64> = (0..3 * 14).map(|i| 0.2 * ((i as f64) * 7.31).sin()).collect();
    let p = noisy_arc::<3>(&noise);
    let (j, dir) = (6, Vector::<3>::new(-1.0, 1.0, 0.3));
    let t = okada_tangents(&p, &[(j, dir)]).unwrap();
    let u = t.x[j] / t.x[j].norm();
    assert!((u - dir / dir.norm()).norm() < 1e-12);
    let y = t.y(j - 1).unwrap();
    assert!(
        (y / y.norm() - u).norm() < 1e-12,
        "Y_{{j-1}} not along the direction"
    );
    for i in (1..p.len() - 1).filter(|&i| i != j) {
        let g = fd_grad(
            |xi| {
                let mut v = t.clone();
                v.x[i] = xi;
                energy(&p, &v)
            },
            t.x[i],
            1e-4,
        );
        // at i = j − 1 the neighbour X_j is held; Eq. 12 at i involves only X_{i±1} as given.
        assert!(g.norm() < 1e-6 * (1.0 + energy(&p, &t)), "Eq. 12 at {i}: {g:?}");
    }
}

fn run_batten<const D: usize>(
    p: &[Vector<D>],
    constraints: Constraints,
    update: PositionUpdate,
) -> (Vec<Vector<D>>, usize, TerminationReason) {
    let result = Pipeline::new(Batten::<D>::new(
        BattenSettings::default().with_position_update(update),
    ))
    .with_constraints(constraints)
    .with_max_iterations(500)
    .run(p.to_vec())
    .unwrap();
    (result.points, result.iterations, result.termination)
}

/// The strategy: ends and fixed points bit for bit, every point within its range, the
/// position update never raises V at the tangents it was computed with, and the run stops
/// by the curvature-sign rule (never before two iterations).
fn check_strategy<const D: usize>(p: &[Vector<D>], fixed: usize, radius: f64, solve: bool) {
    let update = if solve {
        PositionUpdate::Solve
    } else {
        PositionUpdate::GaussSeidel
    };
    let n = p.len();
    let fixed = fixed % n;
    let constraints = Constraints::default()
        .with_fixed([fixed])
        .with_restraining_radii(vec![radius; n]);
    let mut state = FairingState::new(p.to_vec(), constraints.clone(), false).unwrap();
    let mut s = Batten::new(BattenSettings::default().with_position_update(update));
    s.init(&mut state).unwrap();
    for m in 0..500 {
        let before = state.points().to_vec();
        let t = okada_tangents(&before, &[]).unwrap();
        let out = s.step(&mut state).unwrap();
        assert!(out.criterion.unwrap() <= energy(&before, &t) * (1.0 + 1e-12) + 1e-12);
        if out.done {
            assert!(m >= 1, "stopped after one iteration");
            break;
        }
    }
    let q = state.points();
    assert_eq!(q[fixed], p[fixed]);
    assert_eq!(q[0], p[0]);
    assert_eq!(q[n - 1], p[n - 1]);
    for k in 0..n {
        assert!((q[k] - p[k]).norm() <= radius);
    }
    let (r, _, termination) = run_batten(p, constraints, update);
    assert_eq!(termination, TerminationReason::StrategyDone);
    assert_eq!(r.as_slice(), q);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn strategy_2d(n in noise(40, 2), f in 0usize..100, r in 0.01f64..1.0, solve in any::<bool>()) {
        check_strategy(&noisy_arc::<2>(&n), f, r, solve);
    }
    #[test]
    fn strategy_3d(n in noise(40, 3), f in 0usize..100, r in 0.01f64..1.0, solve in any::<bool>()) {
        check_strategy(&noisy_arc::<3>(&n), f, r, solve);
    }
}

/// Unrestricted, the batten smooths a noisy arc: the energy at the final tangents is below
/// that of the data, and the curvature signs (one plane) are all of one sign.
#[test]
fn unrestricted_batten_removes_wiggles() {
    let noise: Vec<f64> = (0..2 * 25)
        .map(|i| 0.25 * ((i as f64) * 12.9898).sin().fract())
        .collect();
    let p = noisy_arc::<2>(&noise);
    for update in [
        PositionUpdate::GaussSeidel,
        PositionUpdate::Solve,
        PositionUpdate::Jacobi,
    ] {
        let (q, iterations, termination) = run_batten(&p, Constraints::default().with_fixed([8, 16]), update);
        assert_eq!(termination, TerminationReason::StrategyDone);
        assert!(iterations >= 2);
        let tp = okada_tangents(&p, &[]).unwrap();
        let tq = okada_tangents(&q, &[]).unwrap();
        assert!(energy(&q, &tq) < energy(&p, &tp), "{update:?}");
        let signs = curvature_signs(&q, &tq);
        assert!(signs.iter().all(|&s| s == 1), "{update:?}: {signs:?}");
    }
}

/// Bad inputs are errors: too few points, coinciding points, a closed curve, a zero or
/// out-of-range prescribed direction, tangents that do not fit the points.
#[test]
fn bad_inputs_are_errors() {
    assert!(okada_tangents(&[Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)], &[]).is_err());
    assert!(chords(&[Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0)]).is_err());
    let p: Vec<Vec2> = (0..6).map(|i| Vec2::new(i as f64, (i as f64).sin())).collect();
    let mut closed = FairingState::new(p.clone(), Constraints::default(), true).unwrap();
    // Typed refusals a caller can match on: the closed curve, the parameter at fault.
    let refusal = Batten::new(BattenSettings::default())
        .init(&mut closed)
        .unwrap_err();
    assert!(
        matches!(
            refusal,
            Error::Refused {
                what: Refusal::Closed,
                ..
            }
        ),
        "{refusal:?}"
    );
    for settings in [
        BattenSettings::default().with_tangent_direction(2, Vec2::zeros()),
        BattenSettings::default().with_tangent_direction(9, Vec2::new(1.0, 0.0)),
    ] {
        let mut state = FairingState::new(p.clone(), Constraints::default(), false).unwrap();
        let refusal = Batten::new(settings).init(&mut state).unwrap_err();
        assert!(
            matches!(&refusal, Error::BadValue { name, .. } if name == "tangent-directions"),
            "{refusal:?}"
        );
    }
    // tangents that do not fit the points: an error, not a panic
    let mut t = okada_tangents(&p, &[]).unwrap();
    t.chords.pop();
    let all = vec![true; p.len()];
    let inf = vec![f64::INFINITY; p.len()];
    assert!(eq13_positions(&p, &t, &all, &p, &inf, 10).is_err());
    assert!(eq13_sweep(&p, &t, &all, &p, &inf, true).is_err());
    assert!(energy(&p, &t).is_finite());
    assert!(t.y(t.x.len() - 2).is_none());
    let _ = curvature_signs(&p, &t);
    let _ = batten::ferguson(p[0], p[1], p[0], p[1]);
}
