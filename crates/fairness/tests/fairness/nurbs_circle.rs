//! Energies of an exact NURBS circle arc (rational quadratic, The NURBS Book A7.1), whose
//! curvature is 1/r everywhere: Ek = ∫κ² ds = κ²·L = Δθ/r and Ek′ = ∫(dκ/ds)² ds = 0.

use curve_repr::{NurbsCurve, Vec2};
use fairness::energy::{arc_length, curvature_energy, curvature_slope_energy};
use fairness::Adaptive;

#[test]
fn ek_of_a_nurbs_circle_arc_is_kappa_squared_times_length_and_ek_prime_vanishes() {
    let tolerance = 1e-10;
    for (radius, start, end) in [
        (2.5, 0.3, 2.9),
        (0.4, -1.0, 4.5),
        (10.0, 0.0, 2.0 * std::f64::consts::PI),
    ] {
        let arc = NurbsCurve::circular_arc(Vec2::new(1.0, -2.0), radius, start, end).unwrap();
        let settings = Adaptive::default().with_relative_tolerance(tolerance);
        let length = arc_length(&arc, &settings).unwrap();
        let sweep = end - start;
        assert!((length - radius * sweep).abs() < tolerance * radius * sweep * 10.0);
        let ek = curvature_energy(&arc, &settings).unwrap();
        let expected = sweep / radius; // κ² L = (1/r²)(r Δθ)
        assert!(
            (ek - expected).abs() <= 10.0 * tolerance * expected,
            "Ek {ek} against {expected}"
        );
        // dκ/ds is zero up to round-off: integrate to an absolute tolerance far below any
        // curvature variation a fairing method would care about.
        let absolute = Adaptive::default().with_absolute_tolerance(1e-20);
        let ek_prime = curvature_slope_energy(&arc, &absolute).unwrap();
        assert!(ek_prime.abs() < 1e-16, "Ek' {ek_prime}");
    }
}
