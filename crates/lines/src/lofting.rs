//! Fairing a table as one hull: the settings, the fit of every offset at once and the cut of
//! every offset back from the hull.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::fit::{fit, Fit, Obs, Spline};
use crate::report::{build_report, Report};
use crate::spline::Knots;
use crate::table::{Kind, Table};

/// How a table is faired.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Settings {
    /// The table's rounding step; default: inferred from its values ([`Table::step`]).
    pub step: Option<f64>,
    /// The tolerance per offset: the bound of its error. The hull is the smoothest whose robust
    /// RMS move is tol/√3, the RMS of an error spread evenly over ±tol; moves beyond six
    /// tolerances are rejected (flagged, and no longer pull the hull). Default: half the
    /// rounding step (rounding to the nearest step errs by at most that). Raise it for a table
    /// noisier than its rounding.
    pub tolerance: Option<f64>,
    /// Labels of the knuckle edges (G0 breaks: chine, knuckle); default: edge lines whose label
    /// contains "chine" or "knuckle". An empty list declares none.
    pub knuckles: Option<Vec<String>>,
}

impl Settings {
    fn validate(&self) -> Result<()> {
        for (name, v) in [("step", self.step), ("tolerance", self.tolerance)] {
            if let Some(v) = v {
                if !(v.is_finite() && v > 0.0) {
                    return Err(Error::Setting {
                        name,
                        message: format!("{v} is not a positive number"),
                    });
                }
            }
        }
        Ok(())
    }
}

/// The hull: half-breadth y = S(x, z), a bicubic B-spline on clamped uniform knots.
#[derive(Clone, Debug)]
pub struct Hull {
    pub(crate) s: Spline,
}

impl Hull {
    /// Half-breadth at (x, z) and its partial derivatives (y, ∂y/∂x, ∂y/∂z).
    pub fn eval(&self, x: f64, z: f64) -> (f64, f64, f64) {
        self.s.eval(x, z)
    }

    /// The x and z domain: ((x0, x1), (z0, z1)).
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        let kx = &self.s.kx.t;
        let kz = &self.s.ku.as_ref().expect("a hull has two variables").t;
        ((kx[0], kx[kx.len() - 1]), (kz[0], kz[kz.len() - 1]))
    }

    /// The height where the station at x crosses the buttock y = b, nearest z0 (Newton, then a
    /// scan of the domain); None when the station does not reach b.
    pub fn buttock_height(&self, x: f64, b: f64, z0: f64) -> Option<f64> {
        let (_, (za, zb)) = self.domain();
        let mut z = z0;
        for _ in 0..30 {
            let (y, _, yz) = self.eval(x, z);
            if yz.abs() < 1e-12 {
                break;
            }
            let dz = (y - b) / yz;
            z -= dz;
            if !z.is_finite() {
                break;
            }
            if dz.abs() <= 1e-12 * (1.0 + z.abs()) {
                if (z - z0).abs() <= (zb - za) {
                    return Some(z);
                }
                break;
            }
        }
        // scan outward from z0 for a sign change
        let n = 400;
        let h = (zb - za) / n as f64;
        let f = |z: f64| self.eval(x, z).0 - b;
        for k in 0..n {
            for dir in [1.0, -1.0] {
                let a = z0 + dir * k as f64 * h;
                let c = a + dir * h;
                if c < za - h || c > zb + h {
                    continue;
                }
                let (fa, fc) = (f(a), f(c));
                if fa == 0.0 {
                    return Some(a);
                }
                if fa * fc < 0.0 {
                    let (mut lo, mut hi, mut flo) = (a, c, fa);
                    for _ in 0..60 {
                        let m = 0.5 * (lo + hi);
                        let fm = f(m);
                        if fm * flo <= 0.0 {
                            hi = m;
                        } else {
                            lo = m;
                            flo = fm;
                        }
                    }
                    return Some(0.5 * (lo + hi));
                }
            }
        }
        None
    }

    /// The point of the station at x nearest (y0, z0) in the body plan (Newton on the foot
    /// point condition, from z0).
    pub fn project(&self, x: f64, y0: f64, z0: f64) -> (f64, f64) {
        let mut z = z0;
        for _ in 0..30 {
            let (y, _, yz) = self.eval(x, z);
            // f(z) = (z − z0) + (y − y0)·yz; f' ≈ 1 + yz² (second derivative dropped)
            let step = ((z - z0) + (y - y0) * yz) / (1.0 + yz * yz);
            z -= step;
            if step.abs() < 1e-12 * (1.0 + z.abs()) {
                break;
            }
        }
        (self.eval(x, z).0, z)
    }

    pub(crate) fn spline(&self) -> &Spline {
        &self.s
    }
}

/// Where a faired offset's value came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// Cut from the hull surface.
    Hull,
    /// The line faired alone (a knuckle, a profile-only or plan-only line, a table without
    /// redundant views).
    Line,
    /// Kept as read (on the centreline, or too few cells to fair).
    Held,
}

/// A faired table: the input, the new value of every cell, the hull and the report.
#[derive(Clone, Debug)]
pub struct Faired {
    /// The table as read.
    pub table: Table,
    /// New (x, y, z) per cell, in the table's cell order.
    pub values: Vec<[f64; 3]>,
    /// Where each value came from.
    pub sources: Vec<Source>,
    /// Per cell: flagged as a suspect offset (its move exceeds three rounding steps, or the
    /// robust fit rejected it).
    pub flagged: Vec<bool>,
    /// The hull surface, when the table has waterlines or buttocks.
    pub hull: Option<Hull>,
    /// The rounding step used.
    pub step: f64,
    /// The report (serialisable).
    pub report: Report,
}

/// Fairs a table: the hull is fitted to every waterline, buttock and (non-knuckle) edge offset
/// at once, and every such offset is cut back from it; knuckle edges, profile-only and
/// plan-only lines, and every line of a table without waterlines or buttocks are faired alone
/// (y(x) and z(x), the same penalty and tolerance). Offsets on the centreline (y = 0 of a
/// waterline) are held. O(cells·nu² + n·bw²) per solve, with n the surface's coefficients and bw
/// its band (4·nu + 4).
pub fn fair(table: &Table, settings: &Settings) -> Result<Faired> {
    settings.validate()?;
    let step = settings.step.unwrap_or(table.step);
    let tol = settings.tolerance.unwrap_or(0.5 * step);
    let mut t = table.clone();
    if let Some(k) = &settings.knuckles {
        for l in t.lines.iter_mut() {
            l.knuckle = l.kind == Kind::Edge && k.iter().any(|n| n == &l.label);
        }
    }
    let n = t.cells.len();
    let mut values: Vec<[f64; 3]> = t.cells.iter().map(|c| [c.x, c.y, c.z]).collect();
    let mut sources = vec![Source::Held; n];
    let mut rejected = vec![false; n];
    let surface_cell = |i: usize| -> bool {
        let c = &t.cells[i];
        let l = &t.lines[c.line];
        match l.kind {
            Kind::Waterline => c.y != 0.0,
            Kind::Buttock => true,
            Kind::Edge => !l.knuckle,
            _ => false,
        }
    };
    let use_hull = t.has_redundant_views();
    let mut hull = None;
    let mut hull_fit = None;
    if use_hull {
        let idx: Vec<usize> = (0..n).filter(|&i| surface_cell(i)).collect();
        let (mut x0, mut x1, mut z0, mut z1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for &i in &idx {
            let c = &t.cells[i];
            x0 = x0.min(c.x);
            x1 = x1.max(c.x);
            z0 = z0.min(c.z);
            z1 = z1.max(c.z);
        }
        if idx.len() < 8 || x1 <= x0 || z1 <= z0 {
            return Err(Error::Fit(format!(
                "{} offsets on the hull: too few for a surface",
                idx.len()
            )));
        }
        let xs = t.stations.len().max(2) - 1;
        let mut planes: Vec<f64> = t
            .lines
            .iter()
            .filter(|l| l.kind == Kind::Waterline)
            .filter_map(|l| l.plane)
            .collect();
        planes.sort_by(f64::total_cmp);
        planes.dedup();
        // knots: one span per station interval and per waterline (tried on Block Island and
        // the Wigley tuning tables: twice as many in either direction follow the disagreeing
        // offsets of Block Island instead of agreeing them)
        let zs = planes.len().clamp(3, 40);
        let kx = Knots::uniform(x0, x1, xs.min(80));
        let kz = Knots::uniform(z0, z1, zs);
        let obs: Vec<Obs> = idx
            .iter()
            .map(|&i| {
                let c = &t.cells[i];
                let kind = t.lines[c.line].kind;
                Obs {
                    at: (c.x, c.z),
                    target: c.y,
                    free_v: kind != Kind::Buttock,
                    free_u: kind != Kind::Waterline,
                }
            })
            .collect();
        let f =
            fit(kx, Some(kz), &obs, tol).ok_or_else(|| Error::Fit("the hull's system is singular".into()))?;
        let h = Hull { s: f.spline.clone() };
        for (k, &i) in idx.iter().enumerate() {
            let c = &t.cells[i];
            let kind = t.lines[c.line].kind;
            let v = &mut values[i];
            match kind {
                Kind::Waterline => v[1] = h.eval(c.x, c.z).0,
                Kind::Buttock => match h.buttock_height(c.x, c.y, c.z) {
                    Some(z) => v[2] = z,
                    None => rejected[i] = true,
                },
                _ => {
                    let (y, z) = h.project(c.x, c.y, c.z);
                    v[1] = y;
                    v[2] = z;
                }
            }
            sources[i] = Source::Hull;
            if f.weight[k] == 0.0 {
                rejected[i] = true;
            }
        }
        hull_fit = Some(f);
        hull = Some(h);
    }
    // lines faired alone
    for (li, l) in t.lines.iter().enumerate() {
        let alone = !use_hull || l.knuckle || matches!(l.kind, Kind::Profile | Kind::Plan);
        if !alone {
            continue;
        }
        let cells = t.line_cells(li);
        for coord in [1usize, 2] {
            let pts: Vec<usize> = cells
                .iter()
                .copied()
                .filter(|&i| values[i][coord].is_finite())
                .collect();
            if pts.len() < 3 {
                continue;
            }
            let (x0, x1) = (t.cells[pts[0]].x, t.cells[pts[pts.len() - 1]].x);
            if x1 <= x0 {
                continue;
            }
            let obs: Vec<Obs> = pts
                .iter()
                .map(|&i| Obs {
                    at: (t.cells[i].x, 0.0),
                    target: t.cells[i].get_index(coord),
                    free_v: true,
                    free_u: false,
                })
                .collect();
            let Some(f) = fit(Knots::uniform(x0, x1, pts.len() - 1), None, &obs, tol) else {
                continue;
            };
            for (k, &i) in pts.iter().enumerate() {
                values[i][coord] = f.spline.eval(t.cells[i].x, 0.0).0;
                sources[i] = Source::Line;
                if f.weight[k] == 0.0 {
                    rejected[i] = true;
                }
            }
        }
    }
    let flagged: Vec<bool> = (0..n)
        .map(|i| {
            let c = &t.cells[i];
            let d = dist(&[c.x, c.y, c.z], &values[i]);
            rejected[i] || d > 3.0 * step * (1.0 + 1e-9)
        })
        .collect();
    let report = build_report(
        &t,
        &values,
        &sources,
        &flagged,
        step,
        tol,
        hull_fit.as_ref(),
        use_hull,
    );
    Ok(Faired {
        table: t,
        values,
        sources,
        flagged,
        hull,
        step,
        report,
    })
}

/// Distance between two cells' values, missing coordinates ignored.
pub(crate) fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a.iter()
        .zip(b)
        .filter(|(p, q)| p.is_finite() && q.is_finite())
        .map(|(p, q)| (p - q) * (p - q))
        .sum::<f64>()
        .sqrt()
}

pub(crate) fn fit_summary(f: &Fit) -> (f64, usize, usize) {
    (
        f.lambda,
        f.iterations,
        f.weight.iter().filter(|w| **w == 0.0).count(),
    )
}
