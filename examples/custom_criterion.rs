//! Adding a fairness criterion: implement one trait, and every piece that takes a
//! `Criterion` (reports, the NURBS weight optimiser) accepts it.
//!
//! Run: `cargo run --example custom_criterion`

use curve_repr::{Curve, HermiteSpline, Side, Vec2};
use fairness::{Criterion, Energies, Result};

/// The largest speed |C'| at the break points.
struct MaxSpeed;

impl<C: Curve<2>> Criterion<C> for MaxSpeed {
    fn name(&self) -> &str {
        "max-speed"
    }
    fn evaluate(&self, curve: &C) -> Result<f64> {
        Ok(curve
            .breaks()
            .iter()
            .map(|&t| curve.jet(t, Side::Right)[1].norm())
            .fold(0.0, f64::max))
    }
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    // NACA 2412 upper surface (data/airfoil_naca2412, UIUC airfoil database).
    let text = include_str!("../data/airfoil_naca2412/naca2412_upper.csv");
    let points: Vec<Vec2> = text
        .lines()
        .skip(1)
        .filter_map(|line| {
            let mut fields = line.split(',').map(|f| f.trim().parse::<f64>());
            Some(Vec2::new(fields.next()?.ok()?, fields.next()?.ok()?))
        })
        .collect();
    let spline = HermiteSpline::natural(&points)?;
    let criteria: Vec<Box<dyn Criterion<HermiteSpline<2>>>> = vec![Box::new(MaxSpeed)];
    for criterion in &criteria {
        let value = criterion.evaluate(&spline)?;
        println!("{} = {:.6}", criterion.name(), value);
        // The same number by another route: the Hermite spline's stored knot tangents.
        let from_tangents = spline.tangents().iter().map(|t| t.norm()).fold(0.0, f64::max);
        assert!(
            (value - from_tangents).abs() <= 1e-12 * from_tangents,
            "{value} {from_tangents}"
        );
    }
    let energies = Energies::of(&spline)?;
    println!("built-in: E2 = {:.6}, Ek = {:.6}", energies.e2, energies.ek);
    Ok(())
}

// `cargo test` runs this example (`test = true` in Cargo.toml), so the code the README shows
// is checked, not only compiled.
#[cfg(test)]
mod tests {
    #[test]
    fn the_example_runs_and_its_assertions_hold() {
        super::main().unwrap();
    }
}
