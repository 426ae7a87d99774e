//! Adding a fairing strategy: implement `FairingStrategy` (a name and one `step`), and the
//! `Pipeline` gives it the loop, the termination rules, the constraints, the trace and the
//! observers; it composes with the built-in strategies.
//!
//! The strategy here is the simplest local fairing there is: move the point of the largest
//! third-derivative jump z_i (Zhang–Cheng Eq. 17) a fraction of the way towards the midpoint
//! of its neighbours, and stop when the largest jump is small. It is a teaching example, not a
//! method to use; `fairing::strategies::StrainEnergy` does this properly (Eq. 8–15).
//!
//! Run: `cargo run --example custom_strategy`

use curve_repr::{HermiteSpline, Vec2};
use fairing::{Constraints, FairingState, FairingStrategy, Pipeline, Result, StepOutcome};

/// Moves the worst point towards the midpoint of its neighbours.
struct TowardsMidpoint {
    /// How far towards the midpoint, in (0, 1].
    fraction: f64,
    /// Stop when the largest jump is below this.
    target: f64,
}

impl FairingStrategy<2> for TowardsMidpoint {
    fn name(&self) -> &str {
        "towards-midpoint"
    }

    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        let points = state.points().to_vec();
        let spline = HermiteSpline::natural(&points)
            .map_err(|e| fairing::strategy_error(self.name(), e.to_string()))?;
        let jumps: Vec<f64> = spline.third_derivative_jumps().iter().map(|j| j.norm()).collect();
        // The movable interior point with the largest jump (jumps[k] is at point k + 1).
        let worst = jumps
            .iter()
            .enumerate()
            .map(|(k, z)| (k + 1, *z))
            .filter(|(i, _)| state.is_movable(*i))
            .max_by(|a, b| a.1.total_cmp(&b.1));
        let Some((i, largest)) = worst else {
            return Ok(StepOutcome::done(None));
        };
        if largest < self.target {
            return Ok(StepOutcome::done(Some(largest)));
        }
        let midpoint = (points[i - 1] + points[i + 1]) / 2.0;
        // Every move goes through the state, which applies the constraints.
        state.move_point(i, points[i] + self.fraction * (midpoint - points[i]))?;
        Ok(StepOutcome::running(Some(largest)))
    }
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    // A quarter circle sampled at 15 points, with one point pushed out by 2 %.
    let mut points: Vec<Vec2> = (0..15)
        .map(|i| {
            let t = std::f64::consts::FRAC_PI_2 * i as f64 / 14.0;
            Vec2::new(t.cos(), t.sin())
        })
        .collect();
    points[7] *= 1.02;
    let largest_jump = |points: &[Vec2]| -> std::result::Result<f64, curve_repr::Error> {
        let jumps = HermiteSpline::natural(points)?.third_derivative_jumps();
        Ok(jumps.iter().map(|j| j.norm()).fold(0.0, f64::max))
    };
    let largest_before = largest_jump(&points)?;

    let result = Pipeline::new(TowardsMidpoint {
        fraction: 0.5,
        target: 0.4 * largest_before,
    })
    .with_constraints(Constraints::default().with_fixed([0, 14]).with_tolerance(0.05))
    .with_max_iterations(500)
    .run(points.clone())?;

    let largest_after = largest_jump(&result.points)?;
    let moved_most = result
        .points
        .iter()
        .zip(&points)
        .map(|(a, b)| (a - b).norm())
        .fold(0.0, f64::max);
    println!(
        "{} steps ({:?}); largest jump {largest_before:.4} -> {largest_after:.4}; largest move {moved_most:.4} (tolerance 0.05); moved {:?}",
        result.iterations, result.termination, result.moved
    );
    assert!(largest_after < largest_before);
    assert!(moved_most <= 0.05 + 1e-12);
    assert_eq!(result.points[0], points[0]);
    assert_eq!(result.points[14], points[14]);
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
