//! Han et al. Fig. 5: the strophoid x = 10(t³ − t)/(t² + 1), y = 10(t² − 1)/(t² + 1),
//! t ∈ [−2, 2], sampled at 65 equally spaced t; 40 interior points (chosen by a seeded
//! shuffle) perturbed by Gaussian noise N(0, σ²) in x and y (σ = 0.08, the paper gives none);
//! faired by the arbitrary-curve pipeline (§4.2: partition by turning angle, overlap 5,
//! bisector frames, two-phase fairing per segment, blending; 3 passes).
//!
//! Prints the vibration and inflection counts (parametric kind of docs/CONTRACT.md: natural
//! chord-length spline, zeros dropped) and the RMS distance of the data points to the clean
//! strophoid, before and after: with the paper's settings (turning limit π, the paper's
//! rules: [`TwoPhaseSettings::paper`], [`PartitionSettings::paper`]), the paper's rules with the
//! 2π/3 limit (papers/README.md), both without the curve guard, and the defaults (noise
//! pre-pass, long runs, 2π/3, the curve guard `local`); writes
//! before/after SVGs to out/examples/.
//!
//! Run: `cargo run --release --example strophoid_fig5`

use std::f64::consts::PI;

use curve_repr::Vec2;
use fair_cli::svg::{Color, Figure, Line, Markers, Panel};
use fairing::two_phase::{TwoPhase, TwoPhaseSettings};
use fairing::{CurveGuard, PartitionSettings, Pipeline, SegmentedFairing};
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

fn strophoid(t: f64) -> Vec2 {
    let d = t * t + 1.0;
    Vec2::new(10.0 * (t * t * t - t) / d, 10.0 * (t * t - 1.0) / d)
}

/// RMS over the points of the distance to the clean strophoid (closest of 40 001 samples,
/// refined by golden-section search on the bracketing interval).
fn rms_distance(points: &[Vec2]) -> f64 {
    let samples: Vec<(f64, Vec2)> = (0..=40_000)
        .map(|k| {
            let t = -2.0 + 4.0 * k as f64 / 40_000.0;
            (t, strophoid(t))
        })
        .collect();
    let sum: f64 = points
        .iter()
        .map(|p| {
            let (t0, _) = samples
                .iter()
                .min_by(|a, b| (a.1 - p).norm().total_cmp(&(b.1 - p).norm()))
                .copied()
                .unwrap_or((0.0, *p));
            let (mut a, mut b) = ((t0 - 1e-4).max(-2.0), (t0 + 1e-4).min(2.0));
            let g = (5f64.sqrt() - 1.0) / 2.0;
            for _ in 0..60 {
                let (c, d) = (b - g * (b - a), a + g * (b - a));
                if (strophoid(c) - p).norm() < (strophoid(d) - p).norm() {
                    b = d;
                } else {
                    a = c;
                }
            }
            (strophoid((a + b) / 2.0) - p).norm_squared()
        })
        .sum();
    (sum / points.len() as f64).sqrt()
}

fn counts(points: &[Vec2]) -> Result<(usize, usize), Box<dyn std::error::Error>> {
    let s = fairness::summary::parametric(points)?;
    Ok((s.vibrations.unwrap_or(0), s.inflections.unwrap_or(0)))
}

fn plot(
    title: &str,
    points: &[Vec2],
    color: Color,
    path: &std::path::Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let clean: Vec<[f64; 2]> = (0..=800)
        .map(|k| {
            let p = strophoid(-2.0 + 4.0 * k as f64 / 800.0);
            [p.x, p.y]
        })
        .collect();
    let pts: Vec<[f64; 2]> = points.iter().map(|p| [p.x, p.y]).collect();
    let panel = Panel::new(title)
        .with_equal_aspect(true)
        .with_x_label("x")
        .with_y_label("y")
        .with(
            Line::new(clean)
                .with_label("clean strophoid")
                .with_color(Color::palette(7))
                .with_dashes(true),
        )
        .with(
            Line::new(pts.clone())
                .with_label("polygon of the points")
                .with_color(color),
        )
        .with(
            Markers::new(pts)
                .with_label("data points")
                .with_color(color)
                .with_radius(2.5),
        );
    Figure::new().with_panel(panel).write(path)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n = 65;
    let clean: Vec<Vec2> = (0..n)
        .map(|k| strophoid(-2.0 + 4.0 * k as f64 / (n - 1) as f64))
        .collect();
    let mut rng = rand::rngs::StdRng::seed_from_u64(5);
    let mut interior: Vec<usize> = (1..n - 1).collect();
    interior.shuffle(&mut rng);
    let normal = Normal::new(0.0, 0.08)?;
    let mut noisy = clean.clone();
    for &k in interior.iter().take(40) {
        noisy[k] += Vec2::new(normal.sample(&mut rng), normal.sample(&mut rng));
    }
    let (vib, infl) = counts(&noisy)?;
    let (cv, ci) = counts(&clean)?;
    println!("Strophoid, 65 points, 40 interior points with N(0, 0.08²) noise in x and y");
    println!(
        "{:<34} {:>10} {:>11} {:>12}",
        "", "vibrations", "inflections", "RMS to clean"
    );
    println!("{:<34} {cv:>10} {ci:>11} {:>12.4}", "clean samples", 0.0);
    println!(
        "{:<34} {vib:>10} {infl:>11} {:>12.4}",
        "noisy (before)",
        rms_distance(&noisy)
    );
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("out/examples");
    std::fs::create_dir_all(&dir)?;
    plot(
        "Strophoid, noisy (before)",
        &noisy,
        Color::palette(1),
        &dir.join("strophoid_fig5_before.svg"),
    )?;
    for (name, settings, partition, guard, file) in [
        (
            "faired, the paper's settings (π)",
            TwoPhaseSettings::paper(),
            PartitionSettings::paper(),
            CurveGuard::Off,
            "strophoid_fig5_after.svg",
        ),
        (
            "the paper's rules, limit 2π/3",
            TwoPhaseSettings::paper(),
            PartitionSettings::paper().with_limit(2.0 * PI / 3.0),
            CurveGuard::Off,
            "strophoid_fig5_after_limit_2pi3.svg",
        ),
        (
            "faired, default settings",
            TwoPhaseSettings::default(),
            PartitionSettings::default(),
            SegmentedFairing::<TwoPhase>::DEFAULT_CURVE_GUARD,
            "strophoid_fig5_after_default.svg",
        ),
    ] {
        let result = Pipeline::new(
            SegmentedFairing::new(TwoPhase::new(settings))
                .with_partition(partition)
                .with_passes(SegmentedFairing::<TwoPhase>::DEFAULT_PASSES)
                .with_curve_guard(guard),
        )
        .run(noisy.clone())?;
        let (v, i) = counts(&result.points)?;
        println!(
            "{name:<34} {v:>10} {i:>11} {:>12.4}",
            rms_distance(&result.points)
        );
        plot(
            &format!("Strophoid, {name}"),
            &result.points,
            Color::palette(0),
            &dir.join(file),
        )?;
    }
    println!("SVGs in {}", dir.display());
    Ok(())
}
