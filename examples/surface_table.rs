//! The closing-note table of issue 19: every surface method on real and made nets, before and
//! after, and the smoothing baseline at the same displacement.
//!
//! Nets: the Utah teapot's body as surface points (25 × 25, closed in j, a pole row) and as
//! its control net (13 × 13, the same), the PX121 hull offsets (pixel-quantised), and nets
//! made here with a clean twin: a noisy twisted strip (26 × 9), a bumpy door panel (13 × 13),
//! a noisy closed tube (24 × 33, closed in j) and a noisy 200 × 200 height grid.
//!
//! Columns: max z_ij and the network strain energy before → after over the knots of the
//! points (chord-length averaged, periodic across a seam: the methods' own measure, which is
//! the report's for open nets), the report's open measure of a closed net in brackets, S_d
//! (Σ|ΔP|), M_d (max |ΔP|), RMS distance to the clean twin, time of the fairing.
//!
//! Run: `cargo run --release --example surface_table` (a few seconds); arguments choose
//! nets by part of their name (`-- teapot grid`).
//!
//! The last rows of each net are the baseline (`fair surface --method smoothing-spline`):
//! at zhang-cheng's S_d (`--set displacement=…`), and at csaps's own p per direction.

use std::error::Error;
use std::time::Instant;

use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings, GridTopology, Vec3};
use fairing::strategies::{
    Closure, Region, SurfaceFairing, SurfaceFairingSettings, SurfaceSmoothing, SurfaceSmoothingSettings,
    SweepOrder,
};

type Net = Vec<Vec<Vec3>>;

/// A deterministic pseudo-random number in [−1, 1] for node (i, j) and a stream `s`.
fn noise(i: usize, j: usize, s: usize) -> f64 {
    let x = ((i * 7919 + j * 104_729 + s * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
    2.0 * (x - x.floor()) - 1.0
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

/// PX121 waterlines 3–7 × 11 stations, metres.
fn px121() -> Result<Net, Box<dyn Error>> {
    let full = read_net("hull_px121/offsets_m.csv")?;
    Ok(full[3..=7].iter().map(|row| row[..11].to_vec()).collect())
}

/// A strip twisted by a quarter turn along its length; noise ±0.03 across it on the interior.
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
        let angle = std::f64::consts::FRAC_PI_2 * i as f64 / 25.0;
        let normal = Vec3::new(0.0, -angle.sin(), angle.cos());
        for (j, point) in row.iter_mut().enumerate().take(8).skip(1) {
            *point += normal * (0.03 * noise(i, j, 1));
        }
    }
    (clean, noisy)
}

/// The door panel of `examples/door_panel.rs` (13 × 13, mm) with its five bump heights.
fn panel() -> (Net, Net) {
    let clean: Net = (0..13)
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
        .collect();
    let mut bumped = clean.clone();
    for ((i, j), h) in [
        ((3, 4), 3.0),
        ((8, 3), -2.0),
        ((9, 3), -2.5),
        ((6, 8), 2.0),
        ((7, 9), 2.5),
    ] {
        bumped[i][j].z += h;
    }
    (clean, bumped)
}

/// A tube round the z axis, 24 rings of 32 points (the 33rd repeats the first), radius
/// 1 + 0.1 z, with radial noise ±0.01 (the seam's noise written once, so it stays closed).
fn tube() -> (Net, Net) {
    let ring = 32;
    let make = |amplitude: f64| -> Net {
        (0..24)
            .map(|i| {
                (0..=ring)
                    .map(|j| {
                        let k = j % ring;
                        let angle = std::f64::consts::TAU * k as f64 / ring as f64;
                        let z = 0.15 * i as f64;
                        let r = 1.0 + 0.1 * z + amplitude * noise(i, k, 2);
                        Vec3::new(r * angle.cos(), r * angle.sin(), z)
                    })
                    .collect()
            })
            .collect()
    };
    (make(0.0), make(0.01))
}

/// The benchmark's 200 × 200 height grid: a smooth wave with noise ±0.01 on every point.
fn height_grid(size: usize) -> (Net, Net) {
    let make = |amplitude: f64| -> Net {
        (0..size)
            .map(|i| {
                (0..size)
                    .map(|j| {
                        let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
                        Vec3::new(
                            x,
                            y,
                            (0.3 * x).sin() * (0.2 * y).cos() + amplitude * noise(i, j, 3),
                        )
                    })
                    .collect()
            })
            .collect()
    };
    (make(0.0), make(0.01))
}

/// (max z, energy) over the points' knots: periodic across detected seams (`closed`), or the
/// report's open measure.
fn measure(points: &[Vec3], rows: usize, columns: usize, closed: bool) -> Result<(f64, f64), Box<dyn Error>> {
    let topology = if closed {
        GridTopology::detect(points, rows, columns)
    } else {
        GridTopology::open()
    };
    let settings = BicubicSurfaceSettings::default().with_topology(&topology);
    let s = BicubicSplineSurface::from_flat(points.to_vec(), rows, columns, &settings)?;
    Ok((s.max_z(), s.network_strain_energy()))
}

struct Row {
    z: (f64, f64),
    e: (f64, f64),
    open_z: (f64, f64),
    s_d: f64,
    m_d: f64,
    rms: Option<(f64, f64)>,
    ms: f64,
    note: String,
}

fn row_of(
    before: &[Vec3],
    after: &[Vec3],
    rows: usize,
    columns: usize,
    clean: Option<&[Vec3]>,
    ms: f64,
    note: String,
) -> Result<Row, Box<dyn Error>> {
    let (z0, e0) = measure(before, rows, columns, true)?;
    let (z1, e1) = measure(after, rows, columns, true)?;
    let (oz0, _) = measure(before, rows, columns, false)?;
    let (oz1, _) = measure(after, rows, columns, false)?;
    let d: Vec<f64> = before.iter().zip(after).map(|(p, q)| (p - q).norm()).collect();
    let rms = |a: &[Vec3], b: &[Vec3]| {
        (a.iter().zip(b).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt()
    };
    Ok(Row {
        z: (z0, z1),
        e: (e0, e1),
        open_z: (oz0, oz1),
        s_d: d.iter().sum(),
        m_d: d.iter().copied().fold(0.0, f64::max),
        rms: clean.map(|c| (rms(before, c), rms(after, c))),
        ms,
        note,
    })
}

fn print_row(net: &str, method: &str, r: &Row) {
    let rms = r
        .rms
        .map_or(String::from("—"), |(a, b)| format!("{a:.3e} → {b:.3e}"));
    println!(
        "| {net} | {method} | {:.4e} → {:.4e} ({:.3}×) [open {:.4e} → {:.4e}] | {:.4e} → {:.4e} | {:.3e} | {:.3e} | {rms} | {:.1} | {} |",
        r.z.0, r.z.1, r.z.1 / r.z.0, r.open_z.0, r.open_z.1, r.e.0, r.e.1, r.s_d, r.m_d, r.ms, r.note
    );
}

fn flat(net: &Net) -> Vec<Vec3> {
    net.iter().flatten().copied().collect()
}

fn fair_all(name: &str, net: &Net, clean: Option<&Net>) -> Result<(), Box<dyn Error>> {
    if !wanted(name) {
        return Ok(());
    }
    let (rows, columns) = (net.len(), net[0].len());
    let before = flat(net);
    let clean_flat = clean.map(flat);
    let methods: Vec<(&str, SurfaceFairingSettings)> = vec![
        ("zhang-cheng", SurfaceFairingSettings::zhang_cheng()),
        (
            "zhang-cheng, order=queue",
            SurfaceFairingSettings::zhang_cheng().with_order(SweepOrder::Queue),
        ),
        (
            "zhang-cheng, order=tiles",
            SurfaceFairingSettings::zhang_cheng().with_order(SweepOrder::Tiles),
        ),
        (
            "zhang-cheng as printed",
            SurfaceFairingSettings::zhang_cheng().as_printed(),
        ),
        ("kjellander", SurfaceFairingSettings::kjellander()),
        (
            "kjellander as printed",
            SurfaceFairingSettings::kjellander().as_printed(),
        ),
        (
            "zhang-cheng, paper's spheres",
            SurfaceFairingSettings::zhang_cheng()
                .with_region(Region::Sphere)
                .with_radius_scale(1.0),
        ),
        (
            "zhang-cheng, open",
            SurfaceFairingSettings::zhang_cheng().with_closed(Closure::Open),
        ),
        (
            "zhang-cheng, energy-tolerance 1e-6",
            SurfaceFairingSettings::zhang_cheng().with_tolerance(1e-6),
        ),
    ];
    let mut zhang_cheng_s_d = None;
    for (label, settings) in methods {
        let start = Instant::now();
        let result = SurfaceFairing::new(settings).run(net)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let after = result.surface.points().to_vec();
        if zhang_cheng_s_d.is_none() {
            zhang_cheng_s_d = Some(
                before
                    .iter()
                    .zip(&after)
                    .map(|(p, q)| (p - q).norm())
                    .sum::<f64>(),
            );
        }
        let note = format!(
            "{} steps, {:?}{}{}",
            result.steps,
            result.termination,
            result
                .refusal
                .map_or(String::new(), |r| format!(", refused: {}", r.name())),
            if result.refused_steps > 0 {
                format!(", {} refused tries", result.refused_steps)
            } else {
                String::new()
            }
        );
        let row = row_of(&before, &after, rows, columns, clean_flat.as_deref(), ms, note)?;
        print_row(name, label, &row);
    }
    // The baseline: at zhang-cheng's S_d (when it moved anything), and at csaps's own p.
    let mut baselines = vec![(
        "smoothing-spline, csaps's p".to_owned(),
        SurfaceSmoothingSettings::default(),
    )];
    if let Some(s_d) = zhang_cheng_s_d.filter(|&d| d > 0.0) {
        baselines.insert(
            0,
            (
                "smoothing-spline at zhang-cheng's S_d".to_owned(),
                SurfaceSmoothingSettings::default().with_displacement(s_d),
            ),
        );
    }
    for (label, settings) in baselines {
        let start = Instant::now();
        let result = SurfaceSmoothing::new(settings).run(net)?;
        let ms = start.elapsed().as_secs_f64() * 1e3;
        let after = result.surface.points().to_vec();
        let note = format!("p = ({:.6}, {:.6})", result.p.0, result.p.1);
        let row = row_of(&before, &after, rows, columns, clean_flat.as_deref(), ms, note)?;
        print_row(name, &label, &row);
    }
    Ok(())
}

/// Whether the net `name` was asked for (`cargo run --example surface_table -- teapot grid`;
/// no arguments: every net).
fn wanted(name: &str) -> bool {
    let asked: Vec<String> = std::env::args().skip(1).collect();
    asked.is_empty() || asked.iter().any(|a| name.contains(a.as_str()))
}

fn main() -> Result<(), Box<dyn Error>> {
    println!("| net | method | max z_ij | energy | S_d | M_d | RMS to clean | ms | run |");
    println!("|---|---|---|---|---|---|---|---|---|");
    fair_all(
        "teapot body points 25×25",
        &read_net("surface_utah_teapot/teapot_body_surface_points.csv")?,
        None,
    )?;
    fair_all(
        "teapot body net 13×13",
        &read_net("surface_utah_teapot/teapot_body_control_net.csv")?,
        None,
    )?;
    fair_all("PX121 hull 5×11", &px121()?, None)?;
    let (clean, noisy) = twisted();
    fair_all("twisted strip 26×9", &noisy, Some(&clean))?;
    let (clean, bumped) = panel();
    fair_all("door panel 13×13", &bumped, Some(&clean))?;
    let (clean, noisy) = tube();
    fair_all("tube 24×33 closed", &noisy, Some(&clean))?;
    let (clean, noisy) = height_grid(200);
    fair_all("height grid 200×200", &noisy, Some(&clean))?;
    Ok(())
}
