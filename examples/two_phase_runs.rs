//! Han's two-phase fairing on a dense noisy function segment: the default settings (the noise
//! pre-pass, then the phases) against the paper's rules and the long-run option (wrong-sign
//! runs of more than two points, `max_run`), counted as docs/CONTRACT.md defines, with the RMS
//! distance to the clean curve. y = sin(x/2) + N(0, σ²) at x = 0.1 k, k < n. Each variant runs
//! as `fair curve` runs it: the [`TwoPhase`] strategy in a [`Pipeline`].
//!
//! Run: `cargo run --release --example two_phase_runs [n] [all|paper] [σ]` (defaults n = 100000,
//! all, σ = 0.01; with `paper`, only the default and the paper's settings: the timing of one
//! full fairing at large n)

use curve_repr::Vec2;
use fairing::two_phase::{CountGuard, MoveCap, TwoPhase, TwoPhaseSettings};
use fairing::Pipeline;
use fairness::xc::XcPolyline;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args()
        .nth(1)
        .map(|a| a.parse())
        .transpose()?
        .unwrap_or(100_000);
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let sigma: f64 = std::env::args()
        .nth(3)
        .map(|a| a.parse())
        .transpose()?
        .unwrap_or(0.01);
    let normal = Normal::new(0.0, sigma)?;
    let x: Vec<f64> = (0..n).map(|k| 0.1 * k as f64).collect();
    let clean: Vec<f64> = x.iter().map(|t| (t / 2.0).sin()).collect();
    let y: Vec<f64> = clean.iter().map(|v| v + normal.sample(&mut rng)).collect();
    let count = |y: &[f64]| XcPolyline::of_points(&x, y).map(|p| (p.inflections(), p.vibrations()));
    // Vibrations with a drop level of 1e-6 · max|e| instead of docs/CONTRACT.md's 1e-12: how many of
    // the counted sign changes stand on e values that the passes merely shrank.
    let coarse_vibrations = |y: &[f64]| {
        XcPolyline::of_points(&x, y).map(|p| {
            let e = &p.e;
            let level = 1e-6 * e.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let kept: Vec<f64> = e.iter().copied().filter(|v| v.abs() > level).collect();
            kept.windows(2).filter(|w| w[0] * w[1] < 0.0).count()
        })
    };
    let rms =
        |y: &[f64]| (y.iter().zip(&clean).map(|(a, b)| (a - b) * (a - b)).sum::<f64>() / n as f64).sqrt();
    println!("n = {n}, noise {sigma}");
    println!(
        "{:<38} {:>11} {:>11} {:>10} {:>9} {:>7} {:>8}",
        "", "inflections", "vibrations", "vib@1e-6", "rms", "passes", "time"
    );
    let (ci, cv) = count(&clean)?;
    let cc = coarse_vibrations(&clean)?;
    println!("{:<38} {ci:>11} {cv:>11} {cc:>10} {:>9.2e}", "clean", 0.0);
    let (ni, nv) = count(&y)?;
    let nc = coarse_vibrations(&y)?;
    println!("{:<38} {ni:>11} {nv:>11} {nc:>10} {:>9.2e}", "noisy", rms(&y));
    let paper = TwoPhaseSettings::paper();
    let variants = [
        ("default (pre-pass, then phases)", TwoPhaseSettings::default()),
        ("paper (max_run 2)", paper.clone()),
        ("paper + max_run 64", paper.clone().with_max_run(64)),
        (
            "paper + max_run 64, move cap data",
            paper.clone().with_max_run(64).with_move_cap(MoveCap::Data),
        ),
        (
            "paper + max_run 64, guard off",
            paper.clone().with_max_run(64).with_count_guard(CountGuard::Off),
        ),
    ];
    let paper_only = std::env::args().nth(2).as_deref() == Some("paper");
    let points: Vec<Vec2> = x.iter().zip(&y).map(|(&x, &y)| Vec2::new(x, y)).collect();
    for (name, settings) in variants.into_iter().take(if paper_only { 2 } else { usize::MAX }) {
        let start = std::time::Instant::now();
        let result = Pipeline::new(TwoPhase::new(settings.clone()))
            .with_max_iterations(settings.max_passes)
            .run(points.clone())?;
        let seconds = start.elapsed().as_secs_f64();
        let faired: Vec<f64> = result.points.iter().map(|p| p.y).collect();
        let (i, v) = count(&faired)?;
        let vc = coarse_vibrations(&faired)?;
        println!(
            "{name:<38} {i:>11} {v:>11} {vc:>10} {:>9.2e} {:>7} {seconds:>7.2}s",
            rms(&faired),
            result.iterations
        );
    }
    Ok(())
}
