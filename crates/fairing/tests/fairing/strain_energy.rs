//! Zhang–Cheng strain-energy fairing: each closed form against its defining condition,
//! Theorems 1–3, the automatic mode's guarantees and the §5 two-point claim.

use curve_repr::{Curve, HermiteSettings, HermiteSpline, Parametrization, Side, Vector};
use fairing::strategies::strain_energy::{eq13, eq8, hermite_energy, jump, stiffness_diagonal};
use fairing::strategies::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
use fairing::{Constraints, Error, FairingState, FairingStrategy, Pipeline, Refusal};
use proptest::prelude::*;

fn params<const D: usize>(p: &[Vector<D>], par: Parametrization) -> Vec<f64> {
    par.parameters(p).unwrap()
}

fn spline_at<const D: usize>(p: &[Vector<D>], t: &[f64]) -> HermiteSpline<D> {
    HermiteSpline::new(p, &HermiteSettings::new().with_parameters(t.to_vec())).unwrap()
}

fn energy<const D: usize>(p: &[Vector<D>], t: &[f64]) -> f64 {
    spline_at(p, t).strain_energy()
}

/// A noisy arc: n points on a circle of radius 10 (lifted in z for D = 3) plus noise.
fn noisy_arc<const D: usize>(noise: &[f64]) -> Vec<Vector<D>> {
    let n = noise.len() / D;
    (0..n)
        .map(|i| {
            let a = i as f64 * 0.15;
            let mut v = Vector::<D>::zeros();
            v[0] = 10.0 * a.cos();
            v[1] = 10.0 * a.sin();
            if D > 2 {
                v[2] = 0.5 * i as f64;
            }
            for c in 0..D {
                v[c] += noise[i * D + c];
            }
            v
        })
        .collect()
}

fn noise(max_points: usize, d: usize) -> impl Strategy<Value = Vec<f64>> {
    (6..max_points).prop_flat_map(move |n| prop::collection::vec(-0.3f64..0.3, n * d))
}

fn par_strategy() -> impl Strategy<Value = Parametrization> {
    prop_oneof![Just(Parametrization::Uniform), Just(Parametrization::ChordLength)]
}

/// Central-difference gradient of f at x along every axis (f quadratic: exact up to rounding).
fn fd_grad<const D: usize>(f: impl Fn(Vector<D>) -> f64, x: Vector<D>, eps: f64) -> Vector<D> {
    let mut g = Vector::<D>::zeros();
    for c in 0..D {
        let mut a = x;
        let mut b = x;
        a[c] += eps;
        b[c] -= eps;
        g[c] = (f(a) - f(b)) / (2.0 * eps);
    }
    g
}

fn run_one<const D: usize>(
    p: &[Vector<D>],
    settings: StrainEnergySettings,
) -> (Vec<Vector<D>>, StrainEnergy<D>) {
    let mut state = FairingState::new(p.to_vec(), Constraints::default(), false).unwrap();
    let mut s = StrainEnergy::new(settings);
    s.init(&mut state).unwrap();
    s.step(&mut state).unwrap();
    (state.points().to_vec(), s)
}

fn check_eq8<const D: usize>(p: &[Vector<D>], par: Parametrization) {
    let t = params(p, par);
    let sp = spline_at(p, &t);
    let m = sp.tangents().to_vec();
    for k in 1..p.len() - 1 {
        let e = |x: Vector<D>| {
            hermite_energy(p[k - 1], x, m[k - 1], m[k], t[k] - t[k - 1])
                + hermite_energy(x, p[k + 1], m[k], m[k + 1], t[k + 1] - t[k])
        };
        let best = eq8(&sp, k);
        let g0 = fd_grad(e, p[k], 1e-3);
        let g = fd_grad(e, best, 1e-3);
        assert!(
            g.norm() <= 1e-6 * (1.0 + g0.norm()),
            "Eq. 8 at {k}: grad {g:?} vs {g0:?}"
        );
    }
}

fn check_eq13<const D: usize>(p: &[Vector<D>], par: Parametrization) {
    let t = params(p, par);
    let sp = spline_at(p, &t);
    let m = sp.tangents().to_vec();
    for k in 1..p.len() - 2 {
        let e = |x: Vector<D>, y: Vector<D>| {
            hermite_energy(p[k - 1], x, m[k - 1], m[k], t[k] - t[k - 1])
                + hermite_energy(x, y, m[k], m[k + 1], t[k + 1] - t[k])
                + hermite_energy(y, p[k + 2], m[k + 1], m[k + 2], t[k + 2] - t[k + 1])
        };
        let (a, b) = eq13(&sp, k);
        let ga = fd_grad(|x| e(x, b), a, 1e-3);
        let gb = fd_grad(|y| e(a, y), b, 1e-3);
        let g0 = fd_grad(|x| e(x, p[k + 1]), p[k], 1e-3);
        assert!(
            ga.norm() + gb.norm() <= 1e-6 * (1.0 + g0.norm()),
            "Eq. 13 at {k}: {ga:?} {gb:?}"
        );
    }
}

fn check_limits<const D: usize>(p: &[Vector<D>], par: Parametrization) {
    let t = params(p, par);
    let n = p.len();
    let k = n / 2;
    // Eq. 11: the spline through the other points, at t_k.
    let (q, s) = run_one(
        p,
        StrainEnergySettings::default()
            .with_parametrization(par)
            .with_mode(Mode::Interactive(vec![k])),
    );
    let (po, to): (Vec<_>, Vec<_>) = (0..n).filter(|&i| i != k).map(|i| (p[i], t[i])).unzip();
    let want = spline_at(&po, &to).jet(t[k], Side::Left)[0];
    assert!(
        (q[k] - want).norm() < 1e-8 * (1.0 + want.norm()),
        "Eq. 11: {:?} vs {want:?}",
        q[k]
    );
    // and then z_k = 0 (§3.3).
    assert!(s.indicator()[k] < 1e-7 * (1.0 + s.indicator().iter().cloned().fold(0.0, f64::max)));
    // Theorem 1 for the one-point replacement.
    assert!(energy(&q, &t) <= energy(p, &t) * (1.0 + 1e-12));
    // Theorem 3 / Eq. 15: two points.
    let (q2, _) = run_one(
        p,
        StrainEnergySettings::default()
            .with_parametrization(par)
            .with_mode(Mode::Interactive(vec![k, k + 1])),
    );
    let (po, to): (Vec<_>, Vec<_>) = (0..n)
        .filter(|&i| i != k && i != k + 1)
        .map(|i| (p[i], t[i]))
        .unzip();
    let sp = spline_at(&po, &to);
    for j in [k, k + 1] {
        let want = sp.jet(t[j], Side::Left)[0];
        assert!(
            (q2[j] - want).norm() < 1e-8 * (1.0 + want.norm()),
            "Eq. 15 at {j}"
        );
    }
    assert!(energy(&q2, &t) <= energy(p, &t) * (1.0 + 1e-12));
    // Theorem 2: iterating Eq. 8 converges to Eq. 11's point.
    let mut state = FairingState::new(p.to_vec(), Constraints::default(), false).unwrap();
    let mut it = StrainEnergy::new(
        StrainEnergySettings::default()
            .with_parametrization(par)
            .with_mode(Mode::Interactive(vec![k]))
            .with_replacement(Replacement::Iterated)
            .with_tolerance(0.0),
    );
    it.init(&mut state).unwrap();
    let mut last = energy(p, &t);
    for _ in 0..3000 {
        let out = it.step(&mut state).unwrap();
        let e = energy(state.points(), &t);
        assert!(e <= last * (1.0 + 1e-12) + 1e-14, "Theorem 1 for Eq. 8");
        last = e;
        if out.done {
            break;
        }
    }
    assert!(
        (state.points()[k] - q[k]).norm() < 1e-6 * (1.0 + q[k].norm()),
        "Theorem 2"
    );
}

fn check_automatic<const D: usize>(p: &[Vector<D>], par: Parametrization, fixed: usize) {
    let t = params(p, par);
    let n = p.len();
    let fixed = fixed % n;
    // radii computed independently: |spline through the others at t_k − P_k| on the original.
    let radii: Vec<f64> = (0..n)
        .map(|k| {
            if k == 0 || k + 1 == n {
                return 0.0;
            }
            let (po, to): (Vec<_>, Vec<_>) = (0..n).filter(|&i| i != k).map(|i| (p[i], t[i])).unzip();
            (spline_at(&po, &to).jet(t[k], Side::Left)[0] - p[k]).norm()
        })
        .collect();
    let mut state = FairingState::new(p.to_vec(), Constraints::default().with_fixed([fixed]), false).unwrap();
    let mut s = StrainEnergy::new(StrainEnergySettings::default().with_parametrization(par));
    s.init(&mut state).unwrap();
    let mut last = energy(p, &t);
    for _ in 0..200 {
        let out = s.step(&mut state).unwrap();
        let e = energy(state.points(), &t);
        assert!(e <= last * (1.0 + 1e-12) + 1e-14, "energy rose {last} -> {e}");
        assert!(
            (s.energy() - e).abs() <= 1e-8 * (1.0 + e),
            "local energy {} vs {e}",
            s.energy()
        );
        last = e;
        if out.done {
            break;
        }
    }
    let q = state.points();
    assert_eq!(q[fixed].as_slice(), p[fixed].as_slice(), "fixed point moved");
    assert_eq!(q[0].as_slice(), p[0].as_slice());
    assert_eq!(q[n - 1].as_slice(), p[n - 1].as_slice());
    for k in 0..n {
        assert!(
            (q[k] - p[k]).norm() <= radii[k] * (1.0 + 1e-9) + 1e-12,
            "point {k} left its region"
        );
    }
    // the indicator kept locally equals a fresh one
    let fresh = spline_at(q, &t).third_derivative_jumps();
    for k in 1..n - 1 {
        assert!((s.indicator()[k] - fresh[k - 1].norm()).abs() <= 1e-7 * (1.0 + fresh[k - 1].norm()));
    }
}

/// The O(n) diagonal of K (used for the automatic mode's radii) against its defining
/// condition: P_k − J_k/K_kk is the point at t_k of the spline through the other points
/// (Eq. 11, Theorem 3's one-point case), for every interior k.
fn check_stiffness_diagonal<const D: usize>(p: &[Vector<D>], par: Parametrization) {
    let t = params(p, par);
    let n = p.len();
    let sp = spline_at(p, &t);
    let diagonal = stiffness_diagonal(&sp).unwrap();
    for k in 1..n - 1 {
        let got = p[k] - jump(&sp, k) / diagonal[k];
        let (po, to): (Vec<_>, Vec<_>) = (0..n).filter(|&i| i != k).map(|i| (p[i], t[i])).unzip();
        let want = spline_at(&po, &to).jet(t[k], Side::Left)[0];
        assert!(
            (got - want).norm() < 1e-8 * (1.0 + want.norm()),
            "K_kk at {k}: {got:?} vs {want:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    #[test]
    fn stiffness_diagonal_2d(n in noise(40, 2), par in par_strategy()) {
        check_stiffness_diagonal(&noisy_arc::<2>(&n), par);
    }
    #[test]
    fn stiffness_diagonal_3d(n in noise(40, 3), par in par_strategy()) {
        check_stiffness_diagonal(&noisy_arc::<3>(&n), par);
    }
    #[test]
    fn closed_forms_2d(n in noise(30, 2), par in par_strategy()) {
        let p = noisy_arc::<2>(&n);
        check_eq8(&p, par);
        check_eq13(&p, par);
        check_limits(&p, par);
    }
    #[test]
    fn closed_forms_3d(n in noise(30, 3), par in par_strategy()) {
        let p = noisy_arc::<3>(&n);
        check_eq8(&p, par);
        check_eq13(&p, par);
        check_limits(&p, par);
    }
    #[test]
    fn automatic_2d(n in noise(60, 2), par in par_strategy(), fixed in 0usize..100) {
        check_automatic(&noisy_arc::<2>(&n), par, fixed);
    }
    #[test]
    fn automatic_3d(n in noise(60, 3), par in par_strategy(), fixed in 0usize..100) {
        check_automatic(&noisy_arc::<3>(&n), par, fixed);
    }
}

/// §5: with two adjacent bad points, the two-point replacement reaches a lower energy in
/// fewer steps than replacing one point at a time.
#[test]
fn two_adjacent_bad_points_pair_beats_singles() {
    let mut p = noisy_arc::<2>(&[0.0; 2 * 20]);
    let k = 9;
    for j in [k, k + 1] {
        p[j] *= 1.04; // both pushed outwards together: a bump two points wide
    }
    let par = Parametrization::ChordLength;
    let t = params(&p, par);
    let (pair, _) = run_one(
        &p,
        StrainEnergySettings::default().with_mode(Mode::Interactive(vec![k, k + 1])),
    );
    let e_pair = energy(&pair, &t);
    let mut q = p.clone();
    let mut steps = 0;
    let mut e_single = energy(&q, &t);
    while e_single > e_pair * (1.0 + 1e-9) && steps < 1000 {
        let j = if steps % 2 == 0 { k } else { k + 1 };
        let settings = StrainEnergySettings::default()
            .with_mode(Mode::Interactive(vec![j]))
            .with_parameters(t.clone());
        q = run_one(&q, settings).0;
        e_single = energy(&q, &t);
        steps += 1;
        if steps == 1 {
            assert!(
                e_single > e_pair * (1.0 + 1e-6),
                "one single step already as good: {e_single} vs {e_pair}"
            );
        }
    }
    assert!(steps > 1, "singles took {steps} steps");
    let e0 = energy(&p, &t);
    assert!(e_pair < e0);
}

/// The presets, and the pipeline end to end on a noisy arc (numbers for the report).
#[test]
fn presets_on_a_noisy_arc_lower_the_energy() {
    let noise: Vec<f64> = (0..200)
        .map(|i| 0.2 * ((i as f64) * 12.9898).sin().fract())
        .collect();
    let p = noisy_arc::<2>(&noise);
    for (name, settings) in [
        ("kjellander", StrainEnergySettings::kjellander()),
        ("poliakoff", StrainEnergySettings::poliakoff()),
    ] {
        let t = params(&p, settings.parametrization);
        let e0 = energy(&p, &t);
        let mut pipe = Pipeline::new(StrainEnergy::<2>::new(settings)).with_max_iterations(10_000);
        let result = pipe.run(p.clone()).unwrap();
        let e1 = energy(&result.points, &t);
        let clean = energy(&noisy_arc::<2>(&[0.0; 200]), &t);
        let moved = result
            .points
            .iter()
            .zip(&p)
            .map(|(a, b)| (a - b).norm())
            .fold(0.0, f64::max);
        eprintln!(
            "{name}: energy {e0:.6e} -> {e1:.6e} (noise-free arc at these knots {clean:.6e}), {} steps, {:?}, max move {moved:.4}",
            result.iterations, result.termination
        );
        assert!(e1 < e0);
    }
}

/// Eq. (13) as printed, with the cube weights of papers/README.md
/// (λ = h_{i−1}³/Σ, μ = h_{i+1}³/Σ, Σ = h_{i−1}³ + h_i³ + h_{i+1}³; the OCR-truncated tail of
/// P̄_{i+1} read as + μP_{i−1} + (1 − μ)P_{i+2}), equals our 2×2 solve on random knots.
fn check_printed_eq13<const D: usize>(p: &[Vector<D>], par: Parametrization) {
    let t = params(p, par);
    let sp = spline_at(p, &t);
    let m = sp.tangents();
    for i in 1..p.len() - 2 {
        let (h0, h1, h2) = (t[i] - t[i - 1], t[i + 1] - t[i], t[i + 2] - t[i + 1]);
        let sum = h0.powi(3) + h1.powi(3) + h2.powi(3);
        let (l, mu) = (h0.powi(3) / sum, h2.powi(3) / sum);
        let a = (m[i - 1] * ((1.0 - l) * h0) + m[i] * ((1.0 - l) * h0 - l * h1)
            - m[i + 1] * (l * (h1 + h2))
            - m[i + 2] * (l * h2))
            * 0.5
            + p[i - 1] * (1.0 - l)
            + p[i + 2] * l;
        let b = (m[i - 1] * (mu * h0) + m[i] * (mu * (h0 + h1)) + m[i + 1] * (mu * h1 - (1.0 - mu) * h2)
            - m[i + 2] * ((1.0 - mu) * h2))
            * 0.5
            + p[i - 1] * mu
            + p[i + 2] * (1.0 - mu);
        let (ea, eb) = eq13(&sp, i);
        assert!(
            (a - ea).norm() < 1e-9 * (1.0 + a.norm()),
            "printed Eq. 13 P̄_i at {i}: {a:?} vs {ea:?}"
        );
        assert!(
            (b - eb).norm() < 1e-9 * (1.0 + b.norm()),
            "printed Eq. 13 P̄_i+1 at {i}: {b:?} vs {eb:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    #[test]
    fn printed_eq13_with_cube_weights(n in noise(20, 2), par in par_strategy()) {
        check_printed_eq13(&noisy_arc::<2>(&n), par);
    }
}

/// Automatic mode with pairs (beyond the paper's one-point automatic algorithm): the energy
/// still never rises, and no point leaves its region.
fn check_automatic_pairs<const D: usize>(p: &[Vector<D>]) {
    let t = params(p, Parametrization::ChordLength);
    let mut state = FairingState::new(p.to_vec(), Constraints::default(), false).unwrap();
    let mut s = StrainEnergy::new(StrainEnergySettings::default().with_pairs(true));
    s.init(&mut state).unwrap();
    let mut last = energy(p, &t);
    for _ in 0..200 {
        let out = s.step(&mut state).unwrap();
        let e = energy(state.points(), &t);
        assert!(e <= last * (1.0 + 1e-12) + 1e-14, "energy rose {last} -> {e}");
        last = e;
        if out.done {
            break;
        }
    }
    let n = p.len();
    for k in 1..n - 1 {
        let (po, to): (Vec<_>, Vec<_>) = (0..n).filter(|&i| i != k).map(|i| (p[i], t[i])).unzip();
        let r = (spline_at(&po, &to).jet(t[k], Side::Left)[0] - p[k]).norm();
        assert!((state.points()[k] - p[k]).norm() <= r * (1.0 + 1e-9) + 1e-12);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(16))]
    #[test]
    fn automatic_pairs_2d(n in noise(40, 2)) {
        check_automatic_pairs(&noisy_arc::<2>(&n));
    }
}

/// Interactive step 1.3: two listed bad points that are not adjacent are replaced one at a
/// time, the worse first (each by Eq. 11), so the first step moves exactly one point.
#[test]
fn interactive_non_adjacent_points_go_one_at_a_time() {
    let mut p = noisy_arc::<2>(&[0.0; 2 * 16]);
    p[4] *= 1.03;
    p[10] *= 1.06; // the worse one
    let mut state = FairingState::new(p.clone(), Constraints::default(), false).unwrap();
    let mut s = StrainEnergy::new(StrainEnergySettings::default().with_mode(Mode::Interactive(vec![4, 10])));
    s.init(&mut state).unwrap();
    let first = s.step(&mut state).unwrap();
    assert!(!first.done);
    let moved: Vec<usize> = state.take_moves().iter().map(|m| m.index).collect();
    assert_eq!(moved, vec![10]);
    let second = s.step(&mut state).unwrap();
    assert!(second.done);
    let moved: Vec<usize> = state.take_moves().iter().map(|m| m.index).collect();
    assert_eq!(moved, vec![4]);
}

/// Bad settings and inputs are errors, not panics.
#[test]
fn bad_inputs_are_errors() {
    let p = noisy_arc::<2>(&[0.0; 2 * 8]);
    for mode in [
        Mode::Interactive(vec![0]),
        Mode::Interactive(vec![7]),
        Mode::Interactive(vec![99]),
    ] {
        let mut state = FairingState::new(p.clone(), Constraints::default(), false).unwrap();
        let mut s = StrainEnergy::new(StrainEnergySettings::default().with_mode(mode));
        assert!(s.init(&mut state).is_err());
    }
    let mut state = FairingState::new(p.clone(), Constraints::default(), false).unwrap();
    let mut s = StrainEnergy::new(StrainEnergySettings::default().with_tolerance(f64::NAN));
    assert!(s.init(&mut state).is_err());
    let mut s = StrainEnergy::<2>::new(StrainEnergySettings::default());
    assert!(s.step(&mut state).is_err(), "step before init");
    let mut closed = FairingState::new(p, Constraints::default(), true).unwrap();
    let mut s = StrainEnergy::new(StrainEnergySettings::default());
    // A typed refusal a caller can match on, not a free-text failure.
    let refusal = s.init(&mut closed).unwrap_err();
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
}

/// §5 on random data: on a noisy arc with two adjacent points pushed out together, one
/// two-point replacement (Eq. 15) reaches an energy that no number of one-point replacements
/// (Eq. 11) of the same two points goes below, and one single replacement stays strictly
/// above it: the pair needs one step, singles more.
fn check_pair_beats_singles(noise: &[f64], k: usize, singles: usize) {
    let mut p = noisy_arc::<2>(noise);
    let n = p.len();
    let k = 1 + k % (n - 3);
    for j in [k, k + 1] {
        p[j] *= 1.05;
    }
    let t = params(&p, Parametrization::ChordLength);
    let (pair, _) = run_one(
        &p,
        StrainEnergySettings::default().with_mode(Mode::Interactive(vec![k, k + 1])),
    );
    let e_pair = energy(&pair, &t);
    let mut q = p.clone();
    for step in 0..singles {
        let j = if step % 2 == 0 { k } else { k + 1 };
        let settings = StrainEnergySettings::default()
            .with_mode(Mode::Interactive(vec![j]))
            .with_parameters(t.clone());
        q = run_one(&q, settings).0;
        let e = energy(&q, &t);
        assert!(
            e >= e_pair * (1.0 - 1e-10),
            "singles went below the pair: {e} < {e_pair}"
        );
        if step == 0 {
            assert!(
                e > e_pair * (1.0 + 1e-9),
                "one single step as good as the pair: {e} vs {e_pair}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]
    #[test]
    fn pair_beats_singles(n in noise(30, 2), k in 0usize..100, singles in 1usize..30) {
        check_pair_beats_singles(&n, k, singles);
    }
}
