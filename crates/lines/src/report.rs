//! The report of a faired table: per offset (old, new, move in rounding steps, flagged), per line
//! (inflections and vibrations before and after), view consistency before and after.

use serde::Serialize;

use crate::fit::Fit;
use crate::lofting::{dist, fit_summary, Source};
use crate::table::{Kind, Table};

/// One offset's fate.
#[derive(Clone, Debug, Serialize)]
pub struct OffsetReport {
    /// Its line's label.
    pub line: String,
    /// Its line's family.
    pub kind: Kind,
    /// Station index and name as in the file.
    pub station_index: i64,
    /// Station name.
    pub station_name: String,
    /// (x, y, z) as read (NaN-free: a missing coordinate is null).
    pub old: [Option<f64>; 3],
    /// (x, y, z) faired.
    pub new: [Option<f64>; 3],
    /// |new − old| in rounding steps.
    pub move_steps: f64,
    /// A suspect offset: moved more than three steps, or rejected by the robust fit. Its new
    /// value is the one the fair hull suggests.
    pub flagged: bool,
    /// Where the new value came from.
    pub source: Source,
}

/// Fairness of one line before and after.
#[derive(Clone, Debug, Serialize)]
pub struct LineReport {
    /// Label.
    pub line: String,
    /// Family.
    pub kind: Kind,
    /// Which coordinate as a function of x: "y" (plan) or "z" (profile).
    pub view: &'static str,
    /// Inflections (sign changes of the second divided differences above the noise floor).
    pub inflections_before: usize,
    /// After fairing.
    pub inflections_after: usize,
    /// Vibrations (sign changes of the third divided differences above the noise floor).
    pub vibrations_before: usize,
    /// After fairing.
    pub vibrations_after: usize,
}

/// Statistics of a set of distances, in rounding steps.
#[derive(Clone, Debug, Default, Serialize)]
pub struct Stats {
    /// How many.
    pub n: usize,
    /// Root mean square.
    pub rms: f64,
    /// Largest.
    pub max: f64,
}

impl Stats {
    fn of(d: &[f64]) -> Self {
        if d.is_empty() {
            return Self::default();
        }
        Self {
            n: d.len(),
            rms: (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt(),
            max: d.iter().fold(0.0, |a, b| a.max(b.abs())),
        }
    }
}

/// The report of [`crate::fair`].
#[derive(Clone, Debug, Serialize)]
pub struct Report {
    /// The input file.
    pub table: String,
    /// Its layout.
    pub layout: crate::table::Layout,
    /// Its unit, where known.
    pub units: Option<String>,
    /// The rounding step.
    pub step: f64,
    /// The tolerance per offset.
    pub tolerance: f64,
    /// "hull" (one surface behind the views) or "lines alone" (no redundant views).
    pub method: &'static str,
    /// Whether view consistency can be measured: false for a table without waterlines or
    /// buttocks (only edge lines, like the sharpie's): no two views share a point.
    pub consistency_measurable: bool,
    /// A sentence on the above.
    pub note: String,
    /// Per hull region: its smoothing weight (dimensionless), outer iterations and rejected
    /// offsets.
    pub hull_fit: Vec<HullFit>,
    /// Station leave-one-out (each interior station offset against the cubic through its two
    /// neighbours on each side, in y at its height), in steps, before and after.
    pub consistency_before: Stats,
    /// After.
    pub consistency_after: Stats,
    /// Moves of every offset, in steps.
    pub moves: Stats,
    /// Offsets moved more than one step.
    pub moved_above_one_step: usize,
    /// Suspect offsets.
    pub flagged: usize,
    /// Inflections summed over every line, before and after.
    pub inflections: [usize; 2],
    /// Vibrations summed over every line, before and after.
    pub vibrations: [usize; 2],
    /// Per offset.
    pub offsets: Vec<OffsetReport>,
    /// Per line.
    pub lines: Vec<LineReport>,
}

/// The hull fit's summary.
#[derive(Clone, Debug, Serialize)]
pub struct HullFit {
    /// The region ("hull", "above chine", "below chine").
    pub region: String,
    /// Smoothing weight: the discrepancy principle's, or GCV's where `lambda_rule` says so.
    pub lambda: f64,
    /// Which rule chose `lambda`: "discrepancy", or "gcv" (a region whose offsets are noisier
    /// than the tolerance, where GCV's is the smoother).
    pub lambda_rule: String,
    /// Outer (reweighting) iterations.
    pub iterations: usize,
    /// Offsets the robust fit rejected.
    pub rejected: usize,
    /// The region's sections are straight across the girth (the limit of the smoothing across
    /// it, taken where the offsets allow it).
    pub straight: bool,
}

fn opt(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// Sign changes of `d` after dropping |d| ≤ thr.
fn sign_changes(d: &[f64], thr: f64) -> usize {
    let s: Vec<f64> = d.iter().copied().filter(|v| v.abs() > thr).collect();
    s.windows(2).filter(|w| w[0] * w[1] < 0.0).count()
}

fn divided(x: &[f64], v: &[f64]) -> Vec<f64> {
    x.windows(2)
        .zip(v.windows(2))
        .map(|(a, b)| (b[1] - b[0]) / (a[1] - a[0]))
        .collect()
}

/// (inflections, vibrations) of v(x): sign changes of the second and third divided
/// differences, values below a tenth of what a one-step bump at the median spacing h produces
/// (step/h², step/h³) dropped, as lines_check counts them.
pub(crate) fn counts(x: &[f64], v: &[f64], step: f64) -> (usize, usize) {
    if x.len() < 4 {
        return (0, 0);
    }
    let mut gaps: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    if gaps.iter().any(|g| *g <= 0.0) {
        return (0, 0);
    }
    gaps.sort_by(f64::total_cmp);
    let h = gaps[gaps.len() / 2];
    let d1 = divided(x, v);
    let d2 = divided(&x[1..], &d1)
        .into_iter()
        .zip(x.windows(3))
        .map(|(d, w)| d * (w[1] - w[0]) / (0.5 * (w[2] - w[0])))
        .collect::<Vec<_>>();
    let x2: Vec<f64> = x.windows(3).map(|w| w[1]).collect();
    let d3 = divided(&x2, &d2);
    (
        sign_changes(&d2, 0.1 * step / (h * h)),
        sign_changes(&d3, 0.1 * step / (h * h * h)),
    )
}

/// Station leave-one-out in y (steps) of values `vals`.
fn station_loo(t: &Table, vals: &[[f64; 3]], step: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for (_, x) in t.stations.values() {
        let mut p: Vec<(f64, f64)> = t
            .cells
            .iter()
            .enumerate()
            .filter(|(_, c)| c.on_station && (c.x - x).abs() <= 1e-9 * x.abs().max(1.0))
            .filter(|(_, c)| matches!(t.lines[c.line].kind, Kind::Waterline | Kind::Buttock | Kind::Edge))
            .map(|(i, _)| (vals[i][2], vals[i][1]))
            .filter(|(z, y)| z.is_finite() && y.is_finite())
            .collect();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        p.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-9 * a.0.abs().max(1.0));
        for i in 2..p.len().saturating_sub(2) {
            let st = [p[i - 2], p[i - 1], p[i + 1], p[i + 2]];
            let z = p[i].0;
            let pred: f64 = (0..4)
                .map(|j| {
                    let l: f64 = (0..4)
                        .filter(|&m| m != j)
                        .map(|m| (z - st[m].0) / (st[j].0 - st[m].0))
                        .product();
                    l * st[j].1
                })
                .sum();
            let slope = (p[i + 1].1 - p[i - 1].1) / (p[i + 1].0 - p[i - 1].0);
            out.push((p[i].1 - pred).abs() / (1.0 + slope * slope).sqrt() / step);
        }
    }
    out
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn build_report(
    t: &Table,
    vals: &[[f64; 3]],
    sources: &[Source],
    flagged: &[bool],
    step: f64,
    tol: f64,
    hulls: &[(String, Fit)],
    use_hull: bool,
) -> Report {
    let old: Vec<[f64; 3]> = t.cells.iter().map(|c| [c.x, c.y, c.z]).collect();
    let moves: Vec<f64> = old.iter().zip(vals).map(|(a, b)| dist(a, b) / step).collect();
    let offsets = t
        .cells
        .iter()
        .enumerate()
        .map(|(i, c)| OffsetReport {
            line: t.lines[c.line].label.clone(),
            kind: t.lines[c.line].kind,
            station_index: c.station_index,
            station_name: c.station_name.clone(),
            old: old[i].map(opt),
            new: vals[i].map(opt),
            move_steps: moves[i],
            flagged: flagged[i],
            source: sources[i],
        })
        .collect();
    let mut lines = Vec::new();
    for (li, l) in t.lines.iter().enumerate() {
        let cells = t.line_cells(li);
        for (coord, view) in [(1usize, "y"), (2, "z")] {
            let wanted = match l.kind {
                Kind::Waterline | Kind::Plan => coord == 1,
                Kind::Buttock | Kind::Profile => coord == 2,
                Kind::Edge => true,
            };
            if !wanted {
                continue;
            }
            let x: Vec<f64> = cells.iter().map(|&i| old[i][0]).collect();
            let a: Vec<f64> = cells.iter().map(|&i| old[i][coord]).collect();
            let b: Vec<f64> = cells.iter().map(|&i| vals[i][coord]).collect();
            let (ib, vb) = counts(&x, &a, step);
            let (ia, va) = counts(&x, &b, step);
            lines.push(LineReport {
                line: l.label.clone(),
                kind: l.kind,
                view,
                inflections_before: ib,
                inflections_after: ia,
                vibrations_before: vb,
                vibrations_after: va,
            });
        }
    }
    let note = if use_hull {
        "one hull surface behind every waterline, buttock and edge offset; every view is cut from it"
            .to_string()
    } else {
        "no waterlines or buttocks: no two views share a point, so view consistency cannot be measured; every line faired alone".to_string()
    };
    Report {
        table: t.path.clone(),
        layout: t.layout,
        units: t.units.clone(),
        step,
        tolerance: tol,
        method: if use_hull { "hull" } else { "lines alone" },
        consistency_measurable: use_hull,
        note,
        hull_fit: hulls
            .iter()
            .map(|(region, f)| {
                let (lambda, iterations, rejected) = fit_summary(f);
                HullFit {
                    region: region.clone(),
                    lambda,
                    iterations,
                    rejected,
                    straight: f.straight,
                    lambda_rule: if f.by_gcv { "gcv" } else { "discrepancy" }.into(),
                }
            })
            .collect(),
        consistency_before: Stats::of(&station_loo(t, &old, step)),
        consistency_after: Stats::of(&station_loo(t, vals, step)),
        moves: Stats::of(&moves),
        moved_above_one_step: moves.iter().filter(|m| **m > 1.0 + 1e-9).count(),
        flagged: flagged.iter().filter(|f| **f).count(),
        inflections: [
            lines.iter().map(|l| l.inflections_before).sum(),
            lines.iter().map(|l| l.inflections_after).sum(),
        ],
        vibrations: [
            lines.iter().map(|l| l.vibrations_before).sum(),
            lines.iter().map(|l| l.vibrations_after).sum(),
        ],
        offsets,
        lines,
    }
}
