//! Zhang–Cheng §5's first experiment, rebuilt: a smooth 13 × 13 "door panel" with three local
//! bumps (one point, an adjacent pair, a diagonal pair), faired automatically and
//! interactively by Zhang–Cheng and by Kjellander's one-point method; then a twisted 26 × 9
//! strip with noise, the Utah teapot's body control net (data/surface_utah_teapot), a real
//! Bézier net faired through the bicubic interpolant of its control points (§4.5), and the
//! pixel-digitised PX121 hull offsets (data/hull_px121).
//!
//! Finding on the teapot: its net is stitched from Bézier patches whose seams are G1 only
//! because the control legs across them are collinear. The interpolant of the net knows
//! nothing of that, so fairing moves seam points off those lines and the faired Bézier
//! surface creases at the seams (teapot_highlights.svg shows it). §4.5's rule is sound for a
//! B-spline net with simple knots, not for a composite Bézier net.
//!
//! The paper's panel is not published; ours is a doubly curved sheet 1200 × 900 mm with bumps
//! of 2–3 mm. A Zhang–Cheng step fairs every point (automatic) or every group of bad points
//! (interactive); a Kjellander step moves one point (as the paper compares them).
//! Energies are the network strain energy over chord-length knots (the report's e_s).
//!
//! Run: `cargo run --release --example door_panel [OUT_DIR]` (default `target/door_panel`);
//! it writes highlight-line and z_ij pictures there.

use std::error::Error;
use std::path::{Path, PathBuf};

use curve_repr::{BicubicSplineSurface, NurbsSurface, Vec3};
use fair_cli::input::Grid;
use fair_cli::plots::SurfacePlot;
use fair_cli::svg::{Color, Figure, Line, Panel};
use fairing::strategies::{SurfaceFairing, SurfaceFairingResult, SurfaceFairingSettings, SurfaceMode};
use fairness::highlight::{HighlightSettings, LightSetup};

type Net = Vec<Vec<Vec3>>;

/// The bump-free panel: a sheet bent in both directions, in millimetres.
fn panel() -> Net {
    (0..13)
        .map(|i| {
            (0..13)
                .map(|j| {
                    let (x, y) = (100.0 * i as f64, 75.0 * j as f64);
                    let z =
                        60.0 * (1.0 - ((x - 600.0) / 700.0).powi(2)) + 25.0 * (y / 900.0).powi(2) + 0.02 * x;
                    Vec3::new(x, y, z)
                })
                .collect()
        })
        .collect()
}

/// The three bumps: (node, height in mm along z).
const BUMPS: [((usize, usize), f64); 5] = [
    ((3, 4), 3.0),
    ((8, 3), -2.0),
    ((9, 3), -2.5),
    ((6, 8), 2.0),
    ((7, 9), 2.5),
];

fn bumped(net: &Net) -> Net {
    let mut net = net.clone();
    for ((i, j), h) in BUMPS {
        net[i][j].z += h;
    }
    net
}

fn surface(net: &Net) -> Result<BicubicSplineSurface, Box<dyn Error>> {
    Ok(BicubicSplineSurface::new(net)?)
}

fn flat(net: &Net) -> Vec<Vec3> {
    net.iter().flatten().copied().collect()
}

fn rms(a: &[Vec3], b: &[Vec3]) -> f64 {
    (a.iter().zip(b).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt()
}

fn to_grid(points: &[Vec3], rows: usize, columns: usize) -> Grid {
    Grid {
        rows,
        columns,
        points: points.to_vec(),
    }
}

/// The report energy (chord-length knots) of a run's grid.
fn energy_of(points: &[Vec3], rows: usize, columns: usize) -> Result<f64, Box<dyn Error>> {
    let net: Net = points.chunks(columns).map(<[Vec3]>::to_vec).collect();
    let _ = rows;
    Ok(surface(&net)?.network_strain_energy())
}

fn z_map(s: &BicubicSplineSurface) -> Vec<Vec<f64>> {
    let (rows, columns) = s.shape();
    (0..rows)
        .map(|i| (0..columns).map(|j| s.z(i, j).unwrap_or(0.0)).collect())
        .collect()
}

fn write_plot(
    dir: &Path,
    name: &str,
    title: &str,
    input: &BicubicSplineSurface,
    faired: &BicubicSplineSurface,
) -> Result<PathBuf, Box<dyn Error>> {
    let (rows, columns) = input.shape();
    let plot = SurfacePlot {
        title: title.into(),
        input: Some(to_grid(input.points(), rows, columns)),
        faired: Some(to_grid(faired.points(), rows, columns)),
        z: Some(z_map(faired)),
        z_before: Some(z_map(input)),
        highlights: true,
    };
    let path = dir.join(name);
    plot.figure().write(&path)?;
    Ok(path)
}

/// Steps of a one-point run until its report energy is at most `target`: runs of growing
/// length, each from the start (a Kjellander step is cheap). `None` if not reached.
fn steps_to_reach(
    settings: &SurfaceFairingSettings,
    net: &Net,
    target: f64,
    limit: usize,
) -> Result<Option<usize>, Box<dyn Error>> {
    let (rows, columns) = (net.len(), net[0].len());
    let reaches = |steps: usize| -> Result<bool, Box<dyn Error>> {
        let result =
            SurfaceFairing::new(settings.clone().with_max_steps(steps).with_tolerance(0.0)).run(net)?;
        Ok(energy_of(result.surface.points(), rows, columns)? <= target)
    };
    if !reaches(limit)? {
        return Ok(None);
    }
    // Energy never rises step by step, so bisect on the step count.
    let (mut lo, mut hi) = (0usize, limit);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if reaches(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(Some(hi))
}

fn summary(
    name: &str,
    before: &BicubicSplineSurface,
    result: &SurfaceFairingResult,
    clean: Option<&[Vec3]>,
) -> Result<(), Box<dyn Error>> {
    let (rows, columns) = before.shape();
    let after = &result.surface;
    let e0 = before.network_strain_energy();
    let e1 = energy_of(after.points(), rows, columns)?;
    let (z0, z1) = (before.max_z(), surface(&after.grid())?.max_z());
    println!(
        "{name:<34} steps {:>6} (+{:>4} boundary)  e_s {:>11.4e} -> {:>11.4e} ({:>5.1} %)  max z {:>10.4e} -> {:>10.4e} ({:>+6.1} %)  moved {:>3}  {:?}",
        result.steps,
        result.boundary_steps,
        e0,
        e1,
        100.0 * (e0 - e1) / e0,
        z0,
        z1,
        100.0 * (z1 - z0) / z0,
        result.moved.len(),
        result.termination,
    );
    if let Some(clean) = clean {
        println!(
            "{:<34} RMS distance to the clean (bump-free) net: {:.4} before, {:.4} after",
            "",
            rms(before.points(), clean),
            rms(after.points(), clean)
        );
    }
    Ok(())
}

fn door_panel(dir: &Path) -> Result<(), Box<dyn Error>> {
    println!("== door panel, 13 × 13, bumps at {:?}", BUMPS.map(|b| b.0));
    let clean = panel();
    let net = bumped(&clean);
    let before = surface(&net)?;
    let clean_points = flat(&clean);
    println!(
        "bump-free panel: max z {:.4e}, e_s {:.4e}",
        surface(&clean)?.max_z(),
        surface(&clean)?.network_strain_energy()
    );

    let zc = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng()).run(&net)?;
    summary("Zhang–Cheng automatic", &before, &zc, Some(&clean_points))?;
    let kj = SurfaceFairing::new(SurfaceFairingSettings::kjellander()).run(&net)?;
    summary("Kjellander automatic", &before, &kj, Some(&clean_points))?;

    let bad: Vec<(usize, usize)> = BUMPS.iter().map(|b| b.0).collect();
    let interactive = SurfaceMode::Interactive(bad.clone());
    let zc_i = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_mode(interactive.clone()))
        .run(&net)?;
    summary(
        "Zhang–Cheng interactive (bumps)",
        &before,
        &zc_i,
        Some(&clean_points),
    )?;
    let kj_i_settings = SurfaceFairingSettings::kjellander().with_mode(interactive);
    let kj_i = SurfaceFairing::new(kj_i_settings.clone()).run(&net)?;
    summary(
        "Kjellander interactive (bumps)",
        &before,
        &kj_i,
        Some(&clean_points),
    )?;

    // Steps to the same energy: Zhang–Cheng's final energy as the target. Each count is
    // found by bisection over the step limit (energy never rises from step to step).
    let (rows, columns) = before.shape();
    for (label, zc_settings, kj_settings) in [
        (
            "automatic",
            SurfaceFairingSettings::zhang_cheng(),
            SurfaceFairingSettings::kjellander(),
        ),
        (
            "interactive",
            SurfaceFairingSettings::zhang_cheng().with_mode(SurfaceMode::Interactive(bad.clone())),
            kj_i_settings,
        ),
    ] {
        // The common level: the higher of the two methods' final energies (each run to its
        // own stop), plus 1e-6 relative.
        let zc_final = SurfaceFairing::new(zc_settings.clone()).run(&net)?;
        let kj_final = SurfaceFairing::new(kj_settings.clone()).run(&net)?;
        let (zc_e, kj_e) = (
            energy_of(zc_final.surface.points(), rows, columns)?,
            energy_of(kj_final.surface.points(), rows, columns)?,
        );
        let target = zc_e.max(kj_e) * (1.0 + 1e-6);
        let zc_steps = steps_to_reach(&zc_settings, &net, target, zc_final.steps.max(1))?;
        let kj_steps = steps_to_reach(&kj_settings, &net, target, kj_final.steps.max(1))?;
        println!(
            "{label:<12} final e_s: Zhang–Cheng {zc_e:.6e} ({} steps), Kjellander {kj_e:.6e} ({} steps); steps to e_s ≤ {target:.6e}: Zhang–Cheng {}, Kjellander {}",
            zc_final.steps,
            kj_final.steps,
            zc_steps.map_or("not reached".to_string(), |s| s.to_string()),
            kj_steps.map_or("not reached".to_string(), |s| s.to_string()),
        );
        let energy_after = |settings: &SurfaceFairingSettings, steps: usize| -> Result<f64, Box<dyn Error>> {
            energy_of(
                SurfaceFairing::new(settings.clone().with_max_steps(steps).with_tolerance(0.0))
                    .run(&net)?
                    .surface
                    .points(),
                rows,
                columns,
            )
        };
        println!(
            "{:<12} e_s after 1, 2, 4, 8 steps: Zhang–Cheng {:.4e} {:.4e} {:.4e} {:.4e}; Kjellander {:.4e} {:.4e} {:.4e} {:.4e}",
            "",
            energy_after(&zc_settings, 1)?,
            energy_after(&zc_settings, 2)?,
            energy_after(&zc_settings, 4)?,
            energy_after(&zc_settings, 8)?,
            energy_after(&kj_settings, 1)?,
            energy_after(&kj_settings, 2)?,
            energy_after(&kj_settings, 4)?,
            energy_after(&kj_settings, 8)?,
        );
    }
    println!(
        "wrote {}",
        write_plot(
            dir,
            "door_panel_zhang_cheng.svg",
            "door panel: Zhang–Cheng automatic",
            &before,
            &zc.surface
        )?
        .display()
    );
    println!(
        "wrote {}",
        write_plot(
            dir,
            "door_panel_kjellander.svg",
            "door panel: Kjellander automatic",
            &before,
            &kj.surface
        )?
        .display()
    );
    println!(
        "wrote {}",
        write_plot(
            dir,
            "door_panel_zhang_cheng_interactive.svg",
            "door panel: Zhang–Cheng interactive",
            &before,
            &zc_i.surface
        )?
        .display()
    );
    Ok(())
}

/// A strip twisted by a quarter turn along its length, with deterministic noise.
fn twisted() -> (Net, Net) {
    let clean: Net = (0..26)
        .map(|i| {
            let angle = std::f64::consts::FRAC_PI_2 * i as f64 / 25.0;
            (0..9)
                .map(|j| {
                    let r = j as f64 - 4.0;
                    Vec3::new(i as f64, r * angle.cos(), r * angle.sin())
                })
                .collect()
        })
        .collect();
    let mut noisy = clean.clone();
    for (i, row) in noisy.iter_mut().enumerate().take(25).skip(1) {
        for (j, p) in row.iter_mut().enumerate().take(8).skip(1) {
            let s = ((i * 31 + j * 17) as f64 * 12.9898).sin() * 43_758.545;
            *p += Vec3::new(0.0, 0.0, 0.03 * (s.fract() - 0.5) * 2.0);
        }
    }
    (clean, noisy)
}

fn twisted_strip(dir: &Path) -> Result<(), Box<dyn Error>> {
    println!("== twisted strip, 26 × 9, noise ±0.03 on the interior");
    let (clean, noisy) = twisted();
    let before = surface(&noisy)?;
    let zc = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng()).run(&noisy)?;
    summary("Zhang–Cheng automatic", &before, &zc, Some(&flat(&clean)))?;
    let kj = SurfaceFairing::new(SurfaceFairingSettings::kjellander()).run(&noisy)?;
    summary("Kjellander automatic", &before, &kj, Some(&flat(&clean)))?;
    println!(
        "wrote {}",
        write_plot(
            dir,
            "twisted_strip.svg",
            "twisted 26 × 9 strip: Zhang–Cheng automatic",
            &before,
            &zc.surface
        )?
        .display()
    );
    Ok(())
}

fn read_net(relative: &str) -> Result<Net, Box<dyn Error>> {
    let path = format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path)?;
    let mut cells = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let f: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse())
            .collect::<Result<_, _>>()?;
        if f.len() != 5 {
            return Err(format!("{path}: expected i,j,x,y,z").into());
        }
        cells.push((f[0] as usize, f[1] as usize, Vec3::new(f[2], f[3], f[4])));
    }
    let rows = cells.iter().map(|c| c.0).max().ok_or("empty net")? + 1;
    let columns = cells.iter().map(|c| c.1).max().ok_or("empty net")? + 1;
    let mut net = vec![vec![Vec3::zeros(); columns]; rows];
    for (i, j, p) in cells {
        net[i][j] = p;
    }
    Ok(net)
}

/// The composite bicubic Bézier surface of a stitched net (patch seams every 3 rows and
/// columns) as a B-spline with triple interior knots.
fn bezier_surface(net: &Net) -> Result<NurbsSurface, Box<dyn Error>> {
    let knots = |count: usize| {
        let patches = (count - 1) / 3;
        let mut k = vec![0.0; 4];
        for p in 1..patches {
            k.extend([p as f64; 3]);
        }
        k.extend([patches as f64; 4]);
        k
    };
    let weights = vec![vec![1.0; net[0].len()]; net.len()];
    Ok(NurbsSurface::new(
        3,
        3,
        knots(net.len()),
        knots(net[0].len()),
        net.clone(),
        weights,
    )?)
}

fn teapot(dir: &Path) -> Result<(), Box<dyn Error>> {
    println!("== Utah teapot body control net, 13 × 13 (data/surface_utah_teapot)");
    let net = read_net("surface_utah_teapot/teapot_body_control_net.csv")?;
    let before = surface(&net)?;
    // The Bézier surface faired through the bicubic interpolant of its control net (§4.5).
    let original = bezier_surface(&net)?;
    let (faired, zc) =
        SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng()).run_control_net(&original)?;
    summary("Zhang–Cheng automatic", &before, &zc, None)?;
    println!(
        "{:<34} over the run's own knots: max z {:.4e} -> {:.4e}, energy {:.4e} -> {:.4e}",
        "",
        zc.start.max_z,
        zc.history.last().map_or(f64::NAN, |s| s.max_z),
        zc.start.energy,
        zc.history.last().map_or(f64::NAN, |s| s.energy)
    );
    let worst = |s: &BicubicSplineSurface| {
        let z = z_map(s);
        let mut best = (0, 0, 0.0);
        for (i, row) in z.iter().enumerate() {
            for (j, &v) in row.iter().enumerate() {
                if v > best.2 {
                    best = (i, j, v);
                }
            }
        }
        best
    };
    println!(
        "{:<34} worst node before {:?}, after {:?}",
        "",
        worst(&before),
        worst(&surface(&zc.surface.grid())?)
    );
    let after = zc.surface.grid();
    let seam = (0..net.len())
        .map(|i| (after[i][0] - after[i][12]).norm())
        .fold(0.0, f64::max);
    let pole = after[12].iter().map(|p| p.norm()).fold(0.0, f64::max);
    println!(
        "{:<34} seam |P_i,0 − P_i,12| max {seam:.3e}; pole row max |P| {pole:.3e}",
        ""
    );
    // The Bézier surface of the faired net against the original one, on a 25 × 25 sample.
    let mut deviation: f64 = 0.0;
    for a in 0..=24 {
        for b in 0..=24 {
            let (u, v) = (4.0 * a as f64 / 24.0, 4.0 * b as f64 / 24.0);
            use curve_repr::Surface;
            deviation = deviation.max((original.eval(u, v) - faired.eval(u, v)).norm());
        }
    }
    println!(
        "{:<34} Bézier surface moved at most {deviation:.4} (teapot height 3.15)",
        ""
    );
    println!(
        "wrote {}",
        write_plot(
            dir,
            "teapot_body_net.svg",
            "teapot body control net: Zhang–Cheng automatic",
            &before,
            &zc.surface
        )?
        .display()
    );
    // Highlight lines of the rim-to-side quarter of the Bézier surface (one light plane
    // cannot face a closed body of revolution): u ∈ [1, 3] (upper and lower body), v ∈ [0, 1].
    let quarter = |s: &NurbsSurface| Quarter(s.clone());
    let light =
        LightSetup::for_surface(&quarter(&original), &HighlightSettings::default()).ok_or("no light")?;
    let mut figure =
        Figure::new().with_title("teapot body, one quarter: highlight lines of the Bézier surface");
    for (title, s, c) in [
        ("original net", &original, Color::palette(0)),
        ("faired net", &faired, Color::palette(1)),
    ] {
        let mut panel = Panel::new(title).with_equal_aspect(true).with_legend(false);
        for line in light.lines(&quarter(s), 160) {
            panel.push(Line::new(line).with_color(c).with_width(0.9));
        }
        figure.push(panel);
    }
    let path = dir.join("teapot_highlights.svg");
    figure.write(&path)?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The part u ∈ [1, 3], v ∈ [0, 1] of a teapot body surface.
struct Quarter(NurbsSurface);

impl curve_repr::Surface for Quarter {
    fn domain(&self) -> ((f64, f64), (f64, f64)) {
        ((1.0, 3.0), (0.0, 1.0))
    }
    fn partial_from(
        &self,
        u: f64,
        v: f64,
        du: usize,
        dv: usize,
        su: curve_repr::Side,
        sv: curve_repr::Side,
    ) -> Option<Vec3> {
        self.0.partial_from(u, v, du, dv, su, sv)
    }
}

/// The Ulstein PX121 half-breadth table (pixel-digitised, data/hull_px121): waterlines 3–7,
/// the rows with all 11 stations, as a 5 × 11 grid in metres.
fn px121(dir: &Path) -> Result<(), Box<dyn Error>> {
    println!(
        "== Ulstein PX121 hull offsets, waterlines 3-7 × 11 stations (data/hull_px121, pixel-quantised)"
    );
    let path = format!("{}/data/hull_px121/offsets_m.csv", env!("CARGO_MANIFEST_DIR"));
    let mut net = vec![vec![Vec3::zeros(); 11]; 5];
    let mut seen = 0;
    for line in std::fs::read_to_string(&path)?.lines().skip(1) {
        let f: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse())
            .collect::<Result<_, _>>()?;
        let (i, j) = (f[0] as usize, f[1] as usize);
        if (3..=7).contains(&i) && j < 11 {
            net[i - 3][j] = Vec3::new(f[2], f[3], f[4]);
            seen += 1;
        }
    }
    if seen != 55 {
        return Err(format!("{path}: expected 55 cells in waterlines 3-7, found {seen}").into());
    }
    let before = surface(&net)?;
    for (label, settings) in [
        ("Zhang–Cheng automatic", SurfaceFairingSettings::zhang_cheng()),
        ("Kjellander automatic", SurfaceFairingSettings::kjellander()),
    ] {
        let result = SurfaceFairing::new(settings).run(&net)?;
        summary(label, &before, &result, None)?;
        let m_d = before
            .points()
            .iter()
            .zip(result.surface.points())
            .map(|(p, q)| (p - q).norm())
            .fold(0.0, f64::max);
        println!(
            "{:<34} largest move {m_d:.4} m (quantisation step 9 m / 1140 = {:.4} m)",
            "",
            9.0 / 1140.0
        );
        if label.starts_with("Zhang") {
            println!(
                "wrote {}",
                write_plot(
                    dir,
                    "px121_hull.svg",
                    "PX121 hull offsets: Zhang–Cheng automatic",
                    &before,
                    &result.surface
                )?
                .display()
            );
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| format!("{}/target/door_panel", env!("CARGO_MANIFEST_DIR"))),
    );
    std::fs::create_dir_all(&dir)?;
    door_panel(&dir)?;
    twisted_strip(&dir)?;
    teapot(&dir)?;
    px121(&dir)?;
    Ok(())
}
