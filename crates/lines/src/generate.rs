//! Tables of offsets with a known hull behind them, to measure a fairing against the truth:
//! the Wigley hull y = (B/2)(1 − ξ²)(1 − ζ²) (Wigley 1934; ξ = 2x/L − 1, ζ = 1 − z/D), cut by
//! stations, waterlines and buttocks, rounded to the step, optionally with Gaussian noise before
//! the rounding and with planted transcription errors (the planted-error JSON that
//! `lines_check.py --planted` reads).

use std::fmt::Write as _;

/// Length, beam and depth of the generated Wigley hull (inches), and its rounding step.
pub const L: f64 = 400.0;
/// Beam.
pub const B: f64 = 60.0;
/// Depth.
pub const D: f64 = 40.0;
/// Rounding step (1/8 in).
pub const STEP: f64 = 0.125;

/// A generated table: the table (long form with a `kind` column), the exact truth in the same
/// layout, and the planted errors as JSON.
#[derive(Clone, Debug)]
pub struct Generated {
    /// The table as given to the fairing.
    pub table: String,
    /// The exact values in the same layout.
    pub truth: String,
    /// `{"errors": [{"id", "type", "cells": [{"line", "station_index", "field"}]}]}`.
    pub planted: String,
}

/// The Wigley half-breadth at (x, z).
pub fn wigley_y(x: f64, z: f64) -> f64 {
    let xi = 2.0 * x / L - 1.0;
    let zeta = 1.0 - z / D;
    0.5 * B * (1.0 - xi * xi) * (1.0 - zeta * zeta)
}

/// The height where the Wigley station at x reaches half-breadth b (None above the sheer).
pub fn wigley_z(x: f64, b: f64) -> Option<f64> {
    let xi = 2.0 * x / L - 1.0;
    let full = 0.5 * B * (1.0 - xi * xi);
    if full <= 0.0 || b >= full {
        return None;
    }
    let zeta = (1.0 - b / full).sqrt();
    Some(D * (1.0 - zeta))
}

/// A small deterministic generator (xorshift64*), Gaussian by Box–Muller.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    pub(crate) fn normal(&mut self) -> f64 {
        let (a, b) = (self.unit(), self.unit());
        (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
    }
}

/// A Wigley table: 21 stations, waterlines every D/8, buttocks every B/10; each offset
/// plus `noise_steps` × N(0, 1) steps, rounded to [`STEP`]; `planted` transcription errors
/// (an offset off by 6 to 16 steps, as a mis-read eighth or inch) on interior cells. `seed`
/// picks the noise and the errors.
pub fn wigley(noise_steps: f64, planted: usize, seed: u64) -> Generated {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    // (label, kind, si, x, y, z)
    let mut cells: Vec<GenCell> = Vec::new();
    let stations: Vec<f64> = (0..=20).map(|k| L * k as f64 / 20.0).collect();
    for k in 1..=8 {
        let z = D * k as f64 / 8.0;
        for (si, &x) in stations.iter().enumerate() {
            cells.push((format!("WL{k}"), "waterline", si, x, wigley_y(x, z), z));
        }
    }
    for k in 1..=4 {
        let b = 0.5 * B * k as f64 / 5.0;
        for (si, &x) in stations.iter().enumerate() {
            if let Some(z) = wigley_z(x, b) {
                cells.push((format!("BT{k}"), "buttock", si, x, b, z));
            }
        }
    }
    finish(cells, noise_steps, planted, &mut rng)
}

type GenCell = (String, &'static str, usize, f64, f64, f64);

/// Noise, rounding, planted errors and the CSV texts of exact cells (label, kind, station, x, y, z).
fn finish(cells: Vec<GenCell>, noise_steps: f64, planted: usize, rng: &mut Rng) -> Generated {
    let round = |v: f64| (v / STEP).round() * STEP;
    let mut given: Vec<[f64; 2]> = cells
        .iter()
        .map(|c| {
            let e = if c.4 == 0.0 {
                0.0
            } else {
                noise_steps * STEP * rng.normal()
            };
            match c.1 {
                "waterline" => [round(c.4 + e).max(0.0), c.5],
                "buttock" => [c.4, round(c.5 + e)],
                _ => [round(c.4 + e), round(c.5 + noise_steps * STEP * rng.normal())],
            }
        })
        .collect();
    let mut errors = Vec::new();
    let mut used = std::collections::HashSet::new();
    while errors.len() < planted {
        let i = (rng.unit() * cells.len() as f64) as usize % cells.len();
        let c = &cells[i];
        if c.2 < 3
            || c.2 > 12
            || c.1 == "edge"
            || c.4 == 0.0
            || !used.insert((c.0.clone(), c.2))
            || used.iter().any(|u| u.1 == c.2 && u.0 != c.0)
        {
            continue;
        }
        let steps = (6.0 + 10.0 * rng.unit()).round() * if rng.unit() < 0.5 { -1.0 } else { 1.0 };
        let field = if c.1 == "waterline" { 0 } else { 1 };
        given[i][field] += steps * STEP;
        errors.push(format!(
            r#"{{"id": {}, "type": "transcription", "cells": [{{"line": "{}", "station_index": {}, "field": "{}"}}]}}"#,
            errors.len(),
            c.0,
            c.2,
            if field == 0 { "half_breadth" } else { "height" }
        ));
    }
    let header = "line,station_index,station_name,x,half_breadth,height,kind\n";
    let (mut table, mut truth) = (header.to_string(), header.to_string());
    for (c, g) in cells.iter().zip(&given) {
        let _ = writeln!(table, "{},{},{},{},{},{},{}", c.0, c.2, c.2, c.3, g[0], g[1], c.1);
        let _ = writeln!(truth, "{},{},{},{},{},{},{}", c.0, c.2, c.2, c.3, c.4, c.5, c.1);
    }
    Generated {
        table,
        truth,
        planted: format!("{{\"errors\": [{}]}}\n", errors.join(", ")),
    }
}

/// The hard-chine form's chine (y, z) and keel height at x ∈ (0, CL] (bow at 0).
fn chine(x: f64) -> (f64, f64, f64) {
    let t = x / CL;
    let yc = 0.5 * CB * 0.8 * (1.0 - (1.0 - t).powi(3)) + 0.5 * CB * 0.2 * t;
    let zc = CD * (0.25 + 0.35 * (1.0 - t) * (1.0 - t));
    let zk = CD * 0.3 * (1.0 - t).powi(3);
    (yc, zc, zk)
}

/// Length of the hard-chine form (inches).
pub const CL: f64 = 240.0;
/// Its beam.
pub const CB: f64 = 80.0;
/// Its depth (the sheer's height).
pub const CD: f64 = 40.0;
/// Flare of its topsides (dy/dz).
pub const FLARE: f64 = 0.15;

/// The hard-chine form at station x: half-breadth at height z (None outside the hull).
pub fn chine_form_y(x: f64, z: f64) -> Option<f64> {
    let (yc, zc, zk) = chine(x);
    if z < zk || z > CD {
        None
    } else if z <= zc {
        Some(yc * (z - zk) / (zc - zk))
    } else {
        Some(yc + (z - zc) * FLARE)
    }
}

/// The hard-chine form at station x: height at half-breadth b (None outside the hull).
pub fn chine_form_z(x: f64, b: f64) -> Option<f64> {
    let (yc, zc, zk) = chine(x);
    if b <= yc {
        Some(zk + (zc - zk) * b / yc)
    } else {
        let z = zc + (b - yc) / FLARE;
        (z <= CD).then_some(z)
    }
}

/// A hard-chine planing form (straight sections: a V bottom from the keel to the chine, flared
/// straight topsides above it), 16 stations, waterlines every 5 in, buttocks every 8 in, the
/// chine and the keel (y = 0) as edge lines; noise, rounding and planted errors as [`wigley`].
pub fn hard_chine(noise_steps: f64, planted: usize, seed: u64) -> Generated {
    let mut rng = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut cells: Vec<GenCell> = Vec::new();
    let stations: Vec<f64> = (1..=16).map(|k| CL * k as f64 / 16.0).collect();
    for k in 1..=7 {
        let z = 5.0 * k as f64;
        for (si, &x) in stations.iter().enumerate() {
            if let Some(y) = chine_form_y(x, z) {
                cells.push((format!("WL{k}"), "waterline", si, x, y, z));
            }
        }
    }
    for k in 1..=4 {
        let b = 8.0 * k as f64;
        for (si, &x) in stations.iter().enumerate() {
            if let Some(z) = chine_form_z(x, b) {
                cells.push((format!("BT{k}"), "buttock", si, x, b, z));
            }
        }
    }
    for (si, &x) in stations.iter().enumerate() {
        let (yc, zc, zk) = chine(x);
        cells.push(("chine".into(), "edge", si, x, yc, zc));
        cells.push(("keel".into(), "edge", si, x, 0.0, zk));
    }
    finish(cells, noise_steps, planted, &mut rng)
}
