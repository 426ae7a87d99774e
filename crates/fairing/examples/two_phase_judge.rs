//! The noisy test curves of two-phase fairing, with their clean twins, faired with the
//! default settings and with the paper's: the CSV files the judge compares against the
//! smoothing spline (csaps) and OpenCASCADE at the same displacement.
//!
//! Curves (each open or closed as said; Gaussian noise of σ per coordinate on every point,
//! the ends included; y only for functions):
//!
//! | name | curve | points | σ |
//! |---|---|---|---|
//! | `strophoid` | Han's Fig. 5 strophoid x = 10(t³ − t)/(t² + 1), y = 10(t² − 1)/(t² + 1), t ∈ [−2, 2], open | 129 | 0.05 |
//! | `strophoid-loop` | its loop, t ∈ [−1, 1), closed, a corner where it crosses itself | 96 | 0.03 |
//! | `clothoid` | 5·(C(s), S(s)) (Fresnel integrals), s ∈ [0, 2.5], open | 150 | 0.01 |
//! | `arc` | circle of radius 2 over 270°, open | 100 | 0.01 |
//! | `ellipse` | semi-axes 3 and 2, closed | 120 | 0.01 |
//! | `sine` | function y = sin(x/2), x = 0.1 k | 200 | 0.01 |
//! | `sine-dense` | the same function | 2000 | 0.01 |
//! | `airfoil` | NACA 2412 (4-digit formula, closed trailing edge), cosine spacing, closed | 120 | 3e-4 |
//! | `airfoil-upper` | its upper surface as a function y(x) | 61 | 3e-4 |
//!
//! For each curve and seed it writes `NAME_sSEED_clean.csv`, `_noisy.csv`, `_default.csv` (two-phase with
//! [`TwoPhaseSettings::default`], [`PartitionSettings::default`] and
//! [`SegmentedFairing::DEFAULT_PASSES`]) and `_paper.csv` (the paper's settings,
//! [`TwoPhaseSettings::paper`], [`PartitionSettings::paper`], 3 passes), and one line per file
//! set to `cases.tsv` (name, kind, closed); the real curves of `data/` (airfoil surfaces and
//! hull lines as functions y(x)) are faired the same way, without a clean twin.
//! `examples/two_phase_judge.py` runs the judge over `cases.tsv` and prints the table.
//!
//! It also writes `_prepass.csv`: the default variant's noise pre-pass alone for curves (no
//! phase pass); for functions the pre-pass and one full pass (the pipeline's first step).
//!
//! Run: `cargo run --release -p fairing --example two_phase_judge -- [OUT_DIR] [SEEDS]`
//! (default `out/two_phase_judge`, seeds 1). For measurements, environment variables override
//! the default variant's settings: `HAN_DENOISE` (`off`, `gcv`, `jump-lsq`, `jump-lsq-gcv`),
//! `HAN_MAX_RUN`, `HAN_LIMIT` (turning limit in degrees), `HAN_PASSES` (`max-passes`),
//! `HAN_MOVE_CAP` (`move-cap`: `spacing`, `data`), `HAN_CURVE_GUARD` (`off`, `pass`, `local`;
//! the paper variant always runs `off`). The pre-pass's own settings are constants of the
//! library (`TwoPhaseSettings::function_prepass`, `curve_prepass`): to measure another
//! pre-pass, run it as its own stage.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use curve_repr::Vec2;
use fairing::two_phase::{TwoPhase, TwoPhaseSettings};
use fairing::{CurveGuard, PartitionSettings, Pipeline, SegmentedFairing};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

type Error = Box<dyn std::error::Error>;

/// How a curve is faired and judged.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Function,
    Open,
    Closed,
}

impl Kind {
    fn judge_kind(self) -> &'static str {
        match self {
            Kind::Function => "function",
            _ => "parametric",
        }
    }
}

struct Synthetic {
    name: &'static str,
    kind: Kind,
    sigma: f64,
    clean: Vec<Vec2>,
}

fn strophoid(t: f64) -> Vec2 {
    let d = t * t + 1.0;
    Vec2::new(10.0 * (t * t * t - t) / d, 10.0 * (t * t - 1.0) / d)
}

/// Fresnel integrals (C(s), S(s)) with the π/2 convention, by Simpson's rule on 2000 panels.
fn fresnel(s: f64) -> Vec2 {
    let m = 2000;
    let h = s / m as f64;
    let f = |u: f64| Vec2::new((PI * u * u / 2.0).cos(), (PI * u * u / 2.0).sin());
    let mut sum = f(0.0) + f(s);
    for k in 1..m {
        sum += f(k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
    }
    sum * (h / 3.0)
}

/// NACA 4-digit section (m = 0.02, p = 0.4, t = 0.12, closed trailing edge) at x on the
/// upper (`upper`) or lower surface.
fn naca2412(x: f64, upper: bool) -> Vec2 {
    let (m, p, t) = (0.02, 0.4, 0.12);
    let yt =
        5.0 * t * (0.2969 * x.sqrt() - 0.1260 * x - 0.3516 * x * x + 0.2843 * x.powi(3) - 0.1036 * x.powi(4));
    let (yc, slope) = if x < p {
        (m / (p * p) * (2.0 * p * x - x * x), 2.0 * m / (p * p) * (p - x))
    } else {
        (
            m / ((1.0 - p) * (1.0 - p)) * (1.0 - 2.0 * p + 2.0 * p * x - x * x),
            2.0 * m / ((1.0 - p) * (1.0 - p)) * (p - x),
        )
    };
    let theta = slope.atan();
    let sign = if upper { 1.0 } else { -1.0 };
    Vec2::new(x - sign * yt * theta.sin(), yc + sign * yt * theta.cos())
}

fn synthetic() -> Vec<Synthetic> {
    let range = |n: usize, a: f64, b: f64| (0..n).map(move |k| a + (b - a) * k as f64 / (n - 1) as f64);
    let cosine = |n: usize| (0..n).map(move |k| (1.0 - (PI * k as f64 / (n - 1) as f64).cos()) / 2.0);
    let mut airfoil: Vec<Vec2> = cosine(61).rev().map(|x| naca2412(x, true)).collect();
    airfoil.extend(cosine(61).skip(1).take(59).map(|x| naca2412(x, false)));
    vec![
        Synthetic {
            name: "strophoid",
            kind: Kind::Open,
            sigma: 0.05,
            clean: range(129, -2.0, 2.0).map(strophoid).collect(),
        },
        Synthetic {
            name: "strophoid-loop",
            kind: Kind::Closed,
            sigma: 0.03,
            clean: (0..96).map(|k| strophoid(-1.0 + 2.0 * k as f64 / 96.0)).collect(),
        },
        Synthetic {
            name: "clothoid",
            kind: Kind::Open,
            sigma: 0.01,
            clean: range(150, 0.0, 2.5).map(|s| fresnel(s) * 5.0).collect(),
        },
        Synthetic {
            name: "arc",
            kind: Kind::Open,
            sigma: 0.01,
            clean: range(100, 0.0, 1.5 * PI)
                .map(|a| Vec2::new(2.0 * a.cos(), 2.0 * a.sin()))
                .collect(),
        },
        Synthetic {
            name: "ellipse",
            kind: Kind::Closed,
            sigma: 0.01,
            clean: (0..120)
                .map(|k| {
                    let a = 2.0 * PI * k as f64 / 120.0;
                    Vec2::new(3.0 * a.cos(), 2.0 * a.sin())
                })
                .collect(),
        },
        Synthetic {
            name: "sine",
            kind: Kind::Function,
            sigma: 0.01,
            clean: (0..200)
                .map(|k| 0.1 * k as f64)
                .map(|x| Vec2::new(x, (x / 2.0).sin()))
                .collect(),
        },
        Synthetic {
            name: "sine-dense",
            kind: Kind::Function,
            sigma: 0.01,
            clean: (0..2000)
                .map(|k| 0.1 * k as f64)
                .map(|x| Vec2::new(x, (x / 2.0).sin()))
                .collect(),
        },
        Synthetic {
            name: "airfoil",
            kind: Kind::Closed,
            sigma: 3e-4,
            clean: airfoil,
        },
        Synthetic {
            name: "airfoil-upper",
            kind: Kind::Function,
            sigma: 3e-4,
            clean: cosine(61).map(|x| naca2412(x, true)).collect(),
        },
    ]
}

/// The real curves of `data/` judged as functions y(x).
const REAL: &[(&str, &str)] = &[
    ("ua2-180-upper", "airfoil_ua2-180/ua2-180_upper.csv"),
    ("ua2-180-lower", "airfoil_ua2-180/ua2-180_lower.csv"),
    ("r140-upper", "airfoil_r140/r140_upper.csv"),
    ("fx63137-upper", "airfoil_fx63137/fx63137_upper.csv"),
    ("fx63137-lower", "airfoil_fx63137/fx63137_lower.csv"),
    ("sc20714-upper", "airfoil_sc20714/sc20714_upper.csv"),
    ("naca2412-upper", "airfoil_naca2412/naca2412_upper.csv"),
    ("gunnerus-wl03", "hull_gunnerus/waterlines/wl_03.csv"),
    (
        "block-island-wl36",
        "hull_block_island_boat/waterlines/wl_36in.csv",
    ),
];

fn read(path: &Path) -> Result<Vec<Vec2>, Error> {
    let text = std::fs::read_to_string(path)?;
    Ok(text
        .lines()
        .skip(1)
        .filter_map(|line| {
            let mut f = line.split(',').map(|v| v.trim().parse::<f64>());
            Some(Vec2::new(f.next()?.ok()?, f.next()?.ok()?))
        })
        .collect())
}

fn write(path: &Path, points: &[Vec2]) -> Result<(), Error> {
    let mut text = String::from("x,y\n");
    for p in points {
        writeln!(text, "{:?},{:?}", p.x, p.y)?;
    }
    std::fs::write(path, text)?;
    Ok(())
}

/// Two-phase fairing of `points` with the given settings, as `fair curve` runs it.
fn fair(
    points: &[Vec2],
    kind: Kind,
    settings: &TwoPhaseSettings,
    partition: PartitionSettings,
    passes: usize,
    guard: CurveGuard,
) -> Result<Vec<Vec2>, Error> {
    let result = match kind {
        Kind::Function => Pipeline::new(TwoPhase::new(settings.clone()))
            .with_max_iterations(settings.max_passes.max(1))
            .run(points.to_vec())?,
        Kind::Open | Kind::Closed => Pipeline::new(
            SegmentedFairing::new(TwoPhase::new(settings.clone()))
                .with_partition(partition)
                .with_passes(passes)
                .with_curve_guard(guard),
        )
        .with_closed(kind == Kind::Closed)
        .with_max_iterations(passes)
        .run(points.to_vec())?,
    };
    Ok(result.points)
}

fn main() -> Result<(), Error> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "out/two_phase_judge".into()));
    let seeds: u64 = args.next().map(|s| s.parse()).transpose()?.unwrap_or(1);
    std::fs::create_dir_all(&out)?;
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data");
    let mut tuned = TwoPhaseSettings::default();
    let mut tuned_partition = PartitionSettings::default();
    let mut tuned_guard = SegmentedFairing::<TwoPhase>::DEFAULT_CURVE_GUARD;
    for (key, value) in std::env::vars() {
        match key.as_str() {
            "HAN_MAX_RUN" => tuned.max_run = value.parse()?,
            "HAN_LIMIT" => tuned_partition.limit = value.parse::<f64>()?.to_radians(),
            "HAN_DENOISE" => {
                tuned.denoise = serde_json::from_value(serde_json::Value::String(value))?;
            }
            "HAN_PASSES" => tuned.max_passes = value.parse()?,
            "HAN_MOVE_CAP" => {
                tuned.move_cap = serde_json::from_value(serde_json::Value::String(value))?;
            }
            "HAN_CURVE_GUARD" => {
                tuned_guard = serde_json::from_value(serde_json::Value::String(value))?;
            }
            _ => {}
        }
    }
    let variants = [
        (
            "default",
            tuned.clone(),
            tuned_partition,
            SegmentedFairing::<TwoPhase>::DEFAULT_PASSES,
            tuned_guard,
        ),
        (
            "paper",
            TwoPhaseSettings::paper(),
            PartitionSettings::paper(),
            3,
            CurveGuard::Off,
        ),
        (
            "prepass",
            tuned.clone().with_max_passes(0),
            PartitionSettings::default(),
            1,
            CurveGuard::Off,
        ),
    ];
    let mut manifest = String::new();
    let mut run = |name: &str, kind: Kind, noisy: &[Vec2], clean: Option<&[Vec2]>| -> Result<(), Error> {
        write(&out.join(format!("{name}_noisy.csv")), noisy)?;
        if let Some(clean) = clean {
            write(&out.join(format!("{name}_clean.csv")), clean)?;
        }
        for (variant, settings, partition, passes, guard) in &variants {
            let start = std::time::Instant::now();
            let faired = fair(noisy, kind, settings, *partition, *passes, *guard)?;
            println!(
                "{name:28} {variant:8} {:8.1} ms",
                start.elapsed().as_secs_f64() * 1e3
            );
            write(&out.join(format!("{name}_{variant}.csv")), &faired)?;
        }
        writeln!(
            manifest,
            "{name}\t{}\t{}\t{}",
            kind.judge_kind(),
            kind == Kind::Closed,
            clean.is_some()
        )?;
        Ok(())
    };
    for seed in 1..=seeds {
        for case in synthetic() {
            let mut rng = rand::rngs::StdRng::seed_from_u64(seed * 1000 + case.clean.len() as u64);
            let normal = Normal::new(0.0, case.sigma)?;
            let noisy: Vec<Vec2> = case
                .clean
                .iter()
                .map(|p| match case.kind {
                    Kind::Function => Vec2::new(p.x, p.y + normal.sample(&mut rng)),
                    _ => p + Vec2::new(normal.sample(&mut rng), normal.sample(&mut rng)),
                })
                .collect();
            run(
                &format!("{}_s{seed}", case.name),
                case.kind,
                &noisy,
                Some(&case.clean),
            )?;
        }
    }
    for (name, file) in REAL {
        let points = read(&data.join(file))?;
        run(name, Kind::Function, &points, None)?;
    }
    std::fs::write(out.join("cases.tsv"), manifest)?;
    println!("wrote {}", out.display());
    Ok(())
}
