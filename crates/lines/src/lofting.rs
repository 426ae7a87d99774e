//! Fairing a table as one hull: the settings, the fit of every offset at once and the cut of
//! every offset back from the hull.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::fit::{fit, parsimony_slack, Fit, How, Obs, Spline, REJECT};
use crate::report::{build_report, Report};
use crate::spline::{Band, Knots};
use crate::table::{Coord, Kind, Table};

/// How a table is faired.
#[derive(Clone, Debug, Default, Serialize, Deserialize, schemars::JsonSchema)]
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

/// One smooth region of the hull: v = S(x, u), a bicubic B-spline on clamped uniform knots,
/// with v the half-breadth y and u the height z (topsides, a round-bilge hull), or v the height
/// z and u the fraction y / y_k(x) of the way out from the centreline to the knuckle (the
/// bottom below a chine, nearly flat athwartships). The fraction and not y itself: the
/// bottom's half-breadth shrinks toward the bow, where the chine closes in on the keel, so in
/// (x, y) its domain is a wedge and its sections steepen as 1 / y_k(x), which a tensor-product
/// spline follows poorly (the forefoot sat 2.4 rounding steps high on the hard-chine tables);
/// in (x, u) the domain is a rectangle and a V bottom is z = a(x) + b(x)·u with a, b the keel's
/// and the chine's heights (see docs/experiments/lines-plan.md). y_k is a cubic spline on the
/// region's x knots, so the surface stays a bicubic B-spline in (x, u).
#[derive(Clone, Debug)]
pub struct Hull {
    pub(crate) s: Spline,
    value: Coord,
    region: String,
    /// y_k(x), the length of one unit of u, when u is a fraction (on the knots `s.kx`).
    pub(crate) scale: Option<Spline>,
}

impl Hull {
    /// Which coordinate the surface gives: y (then u is z) or z (then u is y).
    pub fn value(&self) -> Coord {
        self.value
    }

    /// The region's name: "hull", or "above " / "below " and the knuckle's label.
    pub fn region(&self) -> &str {
        &self.region
    }

    /// v at (x, u) and its partial derivatives (v, ∂v/∂x, ∂v/∂u).
    pub fn eval(&self, x: f64, u: f64) -> (f64, f64, f64) {
        self.s.eval(x, u)
    }

    /// The point (x, y, z) of the surface at (x, u).
    pub fn point(&self, x: f64, u: f64) -> [f64; 3] {
        let v = self.eval(x, u).0;
        match self.value {
            Coord::Z => [x, u * self.u_scale(x), v],
            _ => [x, v, u],
        }
    }

    /// The length of one unit of u at x: 1, or the knuckle's half-breadth y_k(x) where u is
    /// the fraction of the way out to it.
    pub fn u_scale(&self, x: f64) -> f64 {
        self.scale.as_ref().map_or(1.0, |s| s.eval(x, 0.0).0)
    }

    /// The x and u domain: ((x0, x1), (u0, u1)).
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        let kx = &self.s.kx.t;
        let ku = &self.s.ku.as_ref().expect("a hull has two variables").t;
        ((kx[0], kx[kx.len() - 1]), (ku[0], ku[ku.len() - 1]))
    }

    /// The u where the section at x reaches v = target, nearest u0 (Newton, then a scan of the
    /// domain); None when the section does not reach it.
    pub fn solve_arg(&self, x: f64, target: f64, u0: f64) -> Option<f64> {
        let (_, (ua, ub)) = self.domain();
        let mut u = u0;
        for _ in 0..30 {
            let (v, _, vu) = self.eval(x, u);
            if vu.abs() < 1e-12 {
                break;
            }
            let du = (v - target) / vu;
            u -= du;
            if !u.is_finite() {
                break;
            }
            if du.abs() <= 1e-12 * (1.0 + u.abs()) {
                if (u - u0).abs() <= (ub - ua) {
                    return Some(u);
                }
                break;
            }
        }
        let n = 400;
        let h = (ub - ua) / n as f64;
        let f = |u: f64| self.eval(x, u).0 - target;
        for k in 0..n {
            for dir in [1.0, -1.0] {
                let a = u0 + dir * k as f64 * h;
                let c = a + dir * h;
                if c < ua - h || c > ub + h {
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

    /// The point of the section at x nearest (v0, u0) in the body plan, as (v, u) (Newton on
    /// the foot-point condition from u0, the second derivative dropped; distances in length,
    /// u scaled by [`Hull::u_scale`]).
    pub fn project(&self, x: f64, v0: f64, u0: f64) -> (f64, f64) {
        let g2 = self.u_scale(x).powi(2);
        let mut u = u0;
        for _ in 0..30 {
            let (v, _, vu) = self.eval(x, u);
            let step = (g2 * (u - u0) + (v - v0) * vu) / (g2 + vu * vu);
            u -= step;
            if step.abs() < 1e-12 * (1.0 + u.abs()) {
                break;
            }
        }
        (self.eval(x, u).0, u)
    }

    pub(crate) fn spline(&self) -> &Spline {
        &self.s
    }

    /// (u, v) of a point (x, y, z).
    fn uv(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        match self.value {
            Coord::Z => (y / self.u_scale(x), z),
            _ => (z, y),
        }
    }
}

/// Where a faired offset's value came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// Cut from the hull surface.
    Hull,
    /// The line faired alone (a knuckle, a profile-only or plan-only line, a table without
    /// redundant views). A knuckle's half-breadths are faired alone; its heights too, except
    /// above a bottom parametrised by the fraction of the way out to it, where they are the
    /// bottom's edge (see [`fair`]).
    Line,
    /// Kept as read (on the centreline, too few cells to fair, or a run of offsets along a line
    /// that the hull rejects and the crossing lines of the other views do not contradict: a
    /// feature such as a skeg, not a transcription error).
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
    /// Per cell: flagged as a suspect offset (its move exceeds three rounding steps, the
    /// robust fit rejected it, or it is held as part of a run the hull cannot follow).
    pub flagged: Vec<bool>,
    /// The hull's surfaces: one when the table has waterlines or buttocks and no knuckle, one
    /// on each side of the first knuckle edge otherwise; none without redundant views.
    pub hulls: Vec<Hull>,
    /// The rounding step used.
    pub step: f64,
    /// The report (serialisable).
    pub report: Report,
}

/// Fairs a table: the hull is fitted to every waterline, buttock and (non-knuckle) edge offset
/// at once, and every such offset is cut back from it. A knuckle edge (the first, when there are
/// several) is faired alone first and splits the hull into two regions holding its faired
/// points: y(x, z) above it, z(x, y / y_k(x)) below it ([`Hull`]). Below it its heights as read
/// are offsets of the bottom's edge (u = 1), fitted with the bottom's waterlines and buttocks,
/// and the knuckle's height is the bottom's edge there: near a nearly flat bottom (a waterline
/// meeting it close to the chine) a height error of the knuckle faired alone becomes many times
/// that in the waterline's half-breadth. Likewise its half-breadths as read are offsets of the
/// topsides' lower edge: the region above is fitted with them (at the bottom's edge heights),
/// and both regions are fitted again with the knuckle's half-breadths the topsides give there
/// (the bottom's scale of u), the region above then holding the knuckle's points. Faired alone
/// from sixteen noisy offsets, the chine's half-breadths were 1-3 steps off, and the straight
/// topsides pinned to them could not meet the discrepancy target.
/// Each region is fitted twice, with its sections free and at the straight-section limit
/// (straight across the girth at every x, as a V bottom or flared topsides are); the limit, the
/// simpler model, is fitted to the discrepancy target widened by its standard error
/// (`parsimony_slack`) and taken when it reaches it, rejects every offset the free fit rejects,
/// and any further offset it rejects is one the free fit only kept by bending to it (its
/// deleted move there is beyond the rejection threshold). On the final pass either fit's
/// smoothing is GCV's where that is smoother (offsets noisier than the tolerance). An offset
/// cut from one region onto the other's side of the knuckle is cut from the other. Knuckle
/// edges, profile-only and plan-only lines, and every line of a table without waterlines or
/// buttocks are faired alone (y(x) and z(x), the same penalty and tolerance). Offsets on the
/// centreline (y = 0 of a waterline) are held (below a knuckle they are cut from the bottom,
/// the bottom's half-breadth at their height, where that lies on the bottom);
/// an edge offset on it (a keel, stem or rabbet) keeps y = 0, projected onto the hull, or cut
/// at the centreline of a bottom below a knuckle.
/// Fails with [`Error::Setting`] for a non-positive step or tolerance and [`Error::Fit`] when
/// fewer than 8 offsets lie on the hull. O(n·bw²) per solve, with n the surface's coefficients
/// and bw its band (4·nu + 4); about 100 solves, and as many at the straight limit, whose
/// system has two unknowns per x coefficient; twice that with a knuckle whose half-breadths are
/// the bottom's scale.
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
    // lines faired alone (knuckles first: the hull's regions are split along them)
    let mut knuckle_fit: Option<(usize, Spline)> = None;
    let mut knuckle_y: Option<(usize, Spline)> = None;
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
                .map(|&i| Obs::new((t.cells[i].x, 0.0), t.cells[i].get_index(coord), true, false))
                .collect();
            let Some(f) = fit(
                Knots::uniform(x0, x1, pts.len() - 1),
                None,
                &obs,
                tol,
                &How::default(),
            ) else {
                continue;
            };
            for (k, &i) in pts.iter().enumerate() {
                values[i][coord] = f.spline.eval(t.cells[i].x, 0.0).0;
                sources[i] = Source::Line;
                if f.weight[k] == 0.0 {
                    rejected[i] = true;
                }
            }
            if use_hull && l.knuckle && coord == 2 && knuckle_fit.is_none() {
                knuckle_fit = Some((li, f.spline.clone()));
            }
            if use_hull && l.knuckle && coord == 1 && knuckle_y.is_none() {
                knuckle_y = Some((li, f.spline.clone()));
            }
        }
    }
    let mut hulls = Vec::new();
    let mut fits = Vec::new();
    if use_hull {
        let idx: Vec<usize> = (0..n).filter(|&i| surface_cell(i)).collect();
        // regions: one hull, or above (y(x, z)) and below (z(x, y)) the first knuckle edge,
        // each holding the knuckle's faired points
        let mut regions: Vec<(String, Coord, Vec<usize>, Vec<usize>)> = Vec::new();
        let mut band: Vec<usize> = Vec::new();
        let mut region_cells: Vec<Vec<usize>> = Vec::new();
        match &knuckle_fit {
            Some((kl, zk)) => {
                let (xa, xb) = (zk.kx.t[0], zk.kx.t[zk.kx.t.len() - 1]);
                let kz = |x: f64| zk.eval(x.clamp(xa, xb), 0.0).0;
                let held: Vec<usize> = t
                    .line_cells(*kl)
                    .into_iter()
                    .filter(|&i| values[i][1].is_finite() && values[i][2].is_finite())
                    .collect();
                // offsets within KNUCKLE_BAND steps of the knuckle's height could lie on either
                // side: they pull neither region and are cut from the one that moves them least
                let near: Vec<usize> = idx
                    .iter()
                    .copied()
                    .filter(|&i| (t.cells[i].z - kz(t.cells[i].x)).abs() <= KNUCKLE_BAND * step)
                    .collect();
                let (above, below): (Vec<usize>, Vec<usize>) = idx
                    .iter()
                    .filter(|i| !near.contains(i))
                    .partition(|&&i| t.cells[i].z >= kz(t.cells[i].x));
                band = near;
                let name = &t.lines[*kl].label;
                // below first: its fit gives the knuckle's heights that the region above holds
                regions.push((format!("below {name}"), Coord::Z, below, held.clone()));
                regions.push((format!("above {name}"), Coord::Y, above, held));
            }
            None => regions.push(("hull".into(), Coord::Y, idx.clone(), Vec::new())),
        }
        let snapshot = (values.clone(), rejected.clone(), sources.clone());
        // the knuckle's half-breadths the bottom's u is scaled by, from the topsides' fit
        let mut rescale: Option<Spline> = None;
        for pass in 0..2 {
            if pass == 1 {
                if rescale.is_none() {
                    break;
                }
                (values, rejected, sources) = snapshot.clone();
                if let (Some(r), Some(region)) = (&rescale, regions.first()) {
                    for &i in &region.3 {
                        values[i][1] = r.eval(values[i][0], 0.0).0;
                    }
                }
                hulls.clear();
                fits.clear();
                region_cells.clear();
            }
            let mut below_soft = false;
            for (name, value, cells, held) in regions.iter().cloned() {
                if cells.len() < 8 {
                    continue;
                }
                let pts: Vec<(f64, f64, f64)> = cells
                    .iter()
                    .map(|&i| (t.cells[i].x, t.cells[i].y, t.cells[i].z))
                    .chain(held.iter().map(|&i| (values[i][0], values[i][1], values[i][2])))
                    .collect();
                let (mut x0, mut x1) = (f64::MAX, f64::MIN);
                for &(x, _, _) in &pts {
                    x0 = x0.min(x);
                    x1 = x1.max(x);
                }
                if x1 <= x0 {
                    continue;
                }
                let xs = t.stations.len().max(2) - 1;
                let kx = Knots::uniform(x0, x1, xs.min(80));
                // below a knuckle, u is the fraction of the way out to it (see `Hull`)
                let scale = match (&knuckle_fit, &knuckle_y, value) {
                    (Some((kl, _)), Some((yl, yk)), Coord::Z) if kl == yl => match &rescale {
                        Some(r) => Some(r.clone()),
                        None => {
                            let (xa, xb) = (yk.kx.t[0], yk.kx.t[yk.kx.t.len() - 1]);
                            knuckle_scale(&kx, |x| yk.eval(x.clamp(xa, xb), 0.0).0, 4.0 * step)
                        }
                    },
                    _ => None,
                };
                if value == Coord::Z {
                    below_soft = scale.is_some();
                }
                // above a knuckle whose heights are the bottom's edge, its half-breadths as read are
                // offsets of the topsides' lower edge (at those heights)
                let soft_y = pass == 0 && value == Coord::Y && below_soft;
                let g = |x: f64| scale.as_ref().map_or(1.0, |s| s.eval(x, 0.0).0);
                let uv = |x: f64, y: f64, z: f64| {
                    if value == Coord::Z {
                        (y / g(x), z)
                    } else {
                        (z, y)
                    }
                };
                let (mut u0, mut u1) = (f64::MAX, f64::MIN);
                for &(x, y, z) in &pts {
                    let (u, _) = uv(x, y, z);
                    u0 = u0.min(u);
                    u1 = u1.max(u);
                }
                if u1 <= u0 {
                    continue;
                }
                // knots: one span per station interval and per plane of the u family (tried on
                // Block Island and the Wigley tuning tables: twice as many in either direction
                // follow the disagreeing offsets of Block Island instead of agreeing them)
                let family = if value == Coord::Z {
                    Kind::Buttock
                } else {
                    Kind::Waterline
                };
                let mut planes: Vec<f64> = t
                    .lines
                    .iter()
                    .filter(|l| l.kind == family)
                    .filter_map(|l| l.plane)
                    .collect();
                planes.sort_by(f64::total_cmp);
                planes.dedup();
                let us = planes.len().clamp(3, 40);
                let ku = Knots::uniform(u0, u1, us);
                let mut obs: Vec<Obs> = cells
                    .iter()
                    .map(|&i| {
                        let c = &t.cells[i];
                        let kind = t.lines[c.line].kind;
                        let (u, v) = uv(c.x, c.y, c.z);
                        let (my, mz) = (kind != Kind::Buttock, kind != Kind::Waterline);
                        let (mu, mv) = if value == Coord::Z { (my, mz) } else { (mz, my) };
                        let mut o = Obs::new((c.x, u), v, mv, mu);
                        o.u_scale = g(c.x);
                        o
                    })
                    .collect();
                // below a knuckle parametrised by the fraction (u = 1 on the knuckle), the knuckle's
                // heights as read are offsets of the bottom's edge, weighed with the rest (measured
                // in z; its half-breadths, faired alone and then from the topsides, are the scale of u)
                let soft = scale.is_some();
                for &i in &held {
                    let z = if soft { t.cells[i].z } else { values[i][2] };
                    let y = if soft_y { t.cells[i].y } else { values[i][1] };
                    let (u, v) = uv(values[i][0], y, z);
                    let mut o = if soft || soft_y {
                        Obs::new((values[i][0], u), v, true, false)
                    } else {
                        Obs::new((values[i][0], u), v, true, true)
                    };
                    o.held = !(soft || soft_y);
                    o.u_scale = g(values[i][0]);
                    obs.push(o);
                }
                // the straight-section limit (λ → ∞ across the girth) is taken when the offsets
                // allow it: it reaches the discrepancy target and rejects what the curved fit
                // rejects, and each offset it rejects beyond those the curved fit only kept by
                // bending to it (its deleted move there is a rejection too: a wrong offset, not
                // a curved section); as the simpler model it is given the target's slack
                // (`parsimony_slack`), which its x smoothing also follows. Either fit's λ is
                // GCV's where that is smoother, on the final pass only (a region fitted again
                // with the knuckle's half-breadths first gives them as they are)
                let interim = pass == 0 && below_soft;
                let straight_how = How {
                    straight: true,
                    slack: parsimony_slack(&obs),
                    gcv: !interim,
                    ..How::default()
                };
                let stf = fit(kx.clone(), Some(ku.clone()), &obs, tol, &straight_how);
                let only_straight: Vec<usize> = stf
                    .as_ref()
                    .map(|st| (0..obs.len()).filter(|&k| st.weight[k] == 0.0).collect())
                    .unwrap_or_default();
                let curved_how = How {
                    probe: &only_straight,
                    gcv: !interim,
                    ..How::default()
                };
                let curved = fit(kx, Some(ku), &obs, tol, &curved_how)
                    .ok_or_else(|| Error::Fit(format!("the {name} system is singular")))?;
                let f = match stf {
                    Some(st) if st.met && straight_rejections_hold(&st, &curved) => st,
                    _ => curved,
                };
                let h = Hull {
                    s: f.spline.clone(),
                    value,
                    region: name,
                    scale,
                };
                for (k, &i) in cells.iter().enumerate() {
                    let c = &t.cells[i];
                    let kind = t.lines[c.line].kind;
                    let (u, v) = h.uv(c.x, c.y, c.z);
                    let (mu, mv) = (obs[k].free_u, obs[k].free_v);
                    // below a knuckle, u = 0 is the centreline: a keel offset is cut there
                    // (see `on_centreline`)
                    let new = if h.scale.is_some() && on_centreline(kind, c.y) {
                        Some(h.point(c.x, 0.0))
                    } else if mv && !mu {
                        Some(h.point(c.x, u))
                    } else if mu && !mv {
                        h.solve_arg(c.x, v, u).map(|u2| h.point(c.x, u2))
                    } else {
                        let (_, u2) = h.project(c.x, v, u);
                        Some(h.point(c.x, u2))
                    };
                    match new {
                        Some(p) => {
                            // the plane coordinate of a waterline / buttock stays exact
                            // (and a centreline edge's y = 0: see `on_centreline`)
                            values[i] = [
                                c.x,
                                if kind == Kind::Buttock || on_centreline(kind, c.y) {
                                    c.y
                                } else {
                                    half_breadth(p[1])
                                },
                                if kind == Kind::Waterline { c.z } else { p[2] },
                            ];
                        }
                        None => rejected[i] = true,
                    }
                    sources[i] = Source::Hull;
                    if f.weight[k] == 0.0 {
                        rejected[i] = true;
                    }
                }
                // the knuckle's height is the bottom's edge (the region above, fitted next, holds it)
                if soft {
                    for (k, &i) in held.iter().enumerate() {
                        let (u, _) = h.uv(values[i][0], values[i][1], values[i][2]);
                        values[i][2] = h.eval(values[i][0], u).0;
                        if f.weight[cells.len() + k] == 0.0 {
                            rejected[i] = true;
                        }
                    }
                }
                if soft_y {
                    for (k, &i) in held.iter().enumerate() {
                        values[i][1] = half_breadth(h.eval(values[i][0], values[i][2]).0);
                        if f.weight[cells.len() + k] == 0.0 {
                            rejected[i] = true;
                        }
                    }
                }
                fits.push((h.region.clone(), f));
                hulls.push(h);
                region_cells.push(cells);
            }
            if pass == 0 && below_soft && hulls.len() == 2 {
                // the knuckle's half-breadth along x: the topsides' at the bottom's edge
                let (below, above) = (&hulls[0], &hulls[1]);
                let ((bx0, bx1), _) = below.domain();
                let ((ax0, ax1), _) = above.domain();
                let (y0, y1) = (bx0.max(ax0), bx1.min(ax1));
                if y1 > y0 {
                    let y = |x: f64| {
                        let x = x.clamp(y0, y1);
                        above.eval(x, below.eval(x, 1.0).0).0
                    };
                    rescale = knuckle_scale(&below.s.kx, y, 4.0 * step);
                }
            }
        }
        // back to the order above, below
        if knuckle_fit.is_some() {
            hulls.reverse();
            fits.reverse();
            region_cells.reverse();
        }
        // the knuckle bounds both regions: an offset cut from one region onto the other's side
        // of the knuckle (the extension of the topsides below a chine, where an offset near the
        // chine, or a wrong one, was assigned above it) is cut from the other region instead
        if let (Some((_, zk)), 2) = (&knuckle_fit, hulls.len()) {
            let (xa, xb) = (zk.kx.t[0], zk.kx.t[zk.kx.t.len() - 1]);
            let kz = |x: f64| zk.eval(x.clamp(xa, xb), 0.0).0;
            let side = |h: &Hull, p: &[f64; 3]| {
                let d = p[2] - kz(p[0]);
                if h.value == Coord::Y {
                    d >= -tol
                } else {
                    d <= tol
                }
            };
            for (r, cells) in region_cells.iter().enumerate() {
                for &i in cells {
                    if sources[i] != Source::Hull || side(&hulls[r], &values[i]) {
                        continue;
                    }
                    let c = &t.cells[i];
                    let other = &hulls[1 - r];
                    if let Some(p) = cut(other, c.x, c.y, c.z, t.lines[c.line].kind) {
                        if side(other, &p) {
                            values[i] = p;
                        }
                    }
                }
            }
        }
        // an offset near the knuckle is cut from the region that moves it least; a cut that
        // lies on its own region's side of the knuckle as the regions meet there (the bottom out
        // to its edge, u <= 1; the topsides above the bottom's edge) is preferred when it moves
        // the offset at most a rounding step more: a buttock through the chine at a station, cut
        // from the topsides' extension a fraction of a step below the chine, moved least by a
        // hundredth of a step and left the buttock with a hook and four inflections there
        let bottom = hulls.iter().find(|h| h.scale.is_some());
        let own_side = |h: &Hull, p: &[f64; 3]| match (h.value, bottom) {
            (Coord::Z, _) if h.scale.is_some() => p[1] <= h.u_scale(p[0]) * (1.0 + 1e-9),
            (Coord::Y, Some(b)) => {
                let ((x0, x1), _) = b.domain();
                p[2] >= b.eval(p[0].clamp(x0, x1), 1.0).0 - 1e-9 * (1.0 + p[2].abs())
            }
            _ => true,
        };
        // a rejected offset was given its region by its wrong value: where it is cut near the
        // knuckle it is cut as the band's offsets are (a buttock offset at the chine planted a
        // step high went to the topsides, whose extension a fraction of a step below the chine
        // cut it, and the buttock took a hook with four inflections there)
        if let (Some((_, zk)), 2) = (&knuckle_fit, hulls.len()) {
            let (xa, xb) = (zk.kx.t[0], zk.kx.t[zk.kx.t.len() - 1]);
            let kz = |x: f64| zk.eval(x.clamp(xa, xb), 0.0).0;
            for cells in &region_cells {
                for &i in cells {
                    if rejected[i]
                        && sources[i] == Source::Hull
                        && (values[i][2] - kz(values[i][0])).abs() <= KNUCKLE_BAND * step
                        && !band.contains(&i)
                    {
                        band.push(i);
                    }
                }
            }
        }
        for &i in &band {
            let c = &t.cells[i];
            let kind = t.lines[c.line].kind;
            let here = [c.x, c.y, c.z];
            let cuts: Vec<(bool, f64, [f64; 3])> = hulls
                .iter()
                .filter_map(|h| cut(h, c.x, c.y, c.z, kind).map(|p| (own_side(h, &p), dist(&here, &p), p)))
                .collect();
            let least = cuts.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
            // a rejected offset's value is wrong, and so is the move it measures: its cut is
            // the one on its region's side, whatever it moves
            let window = if rejected[i] { f64::INFINITY } else { step };
            let best = cuts
                .iter()
                .min_by(|a, b| {
                    let pa = !(a.0 && a.1 <= least + window);
                    let pb = !(b.0 && b.1 <= least + window);
                    pa.cmp(&pb).then(a.1.total_cmp(&b.1))
                })
                .map(|q| q.2);
            match best {
                Some(p) => {
                    values[i] = p;
                    sources[i] = Source::Hull;
                }
                None => rejected[i] = true,
            }
        }
        // a waterline's half-breadth of 0 below a knuckle is where the waterline meets the
        // centreline, or a half-breadth rounded to 0: cut from the bottom like the rest, it is the
        // bottom's own half-breadth at that height (0 where the plane passes below the keel).
        // Kept as read, it made the station's bottom step along the centreline from the faired
        // keel up to it (noisy hard-chine tables: an inflection at the bow's first station)
        if let Some(b) = hulls.iter().find(|h| h.scale.is_some()) {
            let ((x0, x1), _) = b.domain();
            for i in 0..n {
                let c = &t.cells[i];
                if t.lines[c.line].kind != Kind::Waterline || c.y != 0.0 || c.x < x0 || c.x > x1 {
                    continue;
                }
                // (not where the waterline passes above the knuckle: the bottom's extension)
                if let Some(p) = cut(b, c.x, c.y, c.z, Kind::Waterline).filter(|p| own_side(b, p)) {
                    values[i] = p;
                    sources[i] = Source::Hull;
                }
            }
        }
        if hulls.is_empty() {
            return Err(Error::Fit(format!(
                "{} offsets on the hull: too few for a surface",
                idx.len()
            )));
        }
    }
    if use_hull {
        hold_feature_runs(&t, &mut values, &mut sources, &mut rejected, tol);
    }
    let flagged: Vec<bool> = (0..n)
        .map(|i| {
            let c = &t.cells[i];
            let d = dist(&[c.x, c.y, c.z], &values[i]);
            rejected[i] || d > 3.0 * step * (1.0 + 1e-9)
        })
        .collect();
    let report = build_report(&t, &values, &sources, &flagged, step, tol, &fits, use_hull);
    Ok(Faired {
        table: t,
        values,
        sources,
        flagged,
        hulls,
        step,
        report,
    })
}

/// Consecutive offsets of one line that the hull rejects or moves beyond six tolerances (the
/// robust fit's rejection line), this many or more, are a feature the smooth surface cannot
/// follow (a skeg, the edge of a flat of bottom, a deck's end), not transcription errors (one
/// wrong offset, far from its neighbours' agreement): they are kept as read (source
/// [`Source::Held`]) and stay flagged. Two: the planted errors of the generator's tables are
/// isolated, and Gunnerus's skeg and PX121's flat-of-bottom edge, which their data notes call
/// real features, are runs of two to five. Six tolerances and not three steps: on a noisy table
/// faired at its noise, two neighbouring noisy offsets can each move three steps. A run that
/// the crossing lines of the other views refute ([`refuted`]) is not held: two wrong offsets
/// can be neighbours too (planted table 602).
const FEATURE_RUN: usize = 2;

/// Holds runs of [`FEATURE_RUN`] or more suspect hull offsets along a line (see there) unless
/// the crossing lines refute them: their value is the input's again and they are marked
/// rejected (flagged). A refuted run keeps the hull's value, which the robust fit reached
/// without it (its offsets are rejected, or moved beyond six tolerances and weighted down).
fn hold_feature_runs(
    t: &Table,
    values: &mut [[f64; 3]],
    sources: &mut [Source],
    rejected: &mut [bool],
    tol: f64,
) {
    let suspect = |i: usize, values: &[[f64; 3]]| {
        let c = &t.cells[i];
        sources[i] == Source::Hull
            && (rejected[i] || dist(&[c.x, c.y, c.z], &values[i]) > 6.0 * tol * (1.0 + 1e-9))
    };
    let mut hold = Vec::new();
    for li in 0..t.lines.len() {
        let cells = t.line_cells(li);
        let mut k = 0;
        while k < cells.len() {
            if !suspect(cells[k], values) {
                k += 1;
                continue;
            }
            let mut e = k;
            while e + 1 < cells.len() && suspect(cells[e + 1], values) {
                e += 1;
            }
            if e + 1 - k >= FEATURE_RUN && !refuted(t, &cells[k..=e], values, sources, rejected, tol) {
                hold.extend_from_slice(&cells[k..=e]);
            }
            k = e + 1;
        }
    }
    for i in hold {
        let c = &t.cells[i];
        values[i] = [c.x, c.y, c.z];
        sources[i] = Source::Held;
        rejected[i] = true;
    }
}

/// A crossing offset departs from the hull when the fit rejects it or moves it beyond this
/// many tolerances (half the rejection line of six).
const CORROBORATE: f64 = 3.0;

/// Whether a run of suspect offsets along a line is refuted as a feature by the crossing lines
/// of the other views: a feature of the hull (a skeg, the edge of a flat of bottom) is one in
/// every view, so the lines crossing the run's stations near it (the waterlines bracketing a
/// buttock offset's height, the buttocks bracketing a waterline offset's half-breadth, both for
/// an edge) depart from the smooth hull there too; a run of wrong offsets is in one view only
/// and the crossing lines agree with the hull. Refuted: the run's stations have such crossing
/// offsets and none of them departs (rejected, or moved beyond [`CORROBORATE`] tolerances).
/// A table whose other views do not cross the run (a waterline grid) cannot refute it.
fn refuted(
    t: &Table,
    run: &[usize],
    values: &[[f64; 3]],
    sources: &[Source],
    rejected: &[bool],
    tol: f64,
) -> bool {
    let mut crossing = 0;
    let mut worst: f64 = 0.0;
    for &i in run {
        let c = &t.cells[i];
        let families: &[(Kind, usize)] = match t.lines[c.line].kind {
            Kind::Waterline => &[(Kind::Buttock, 1)],
            Kind::Buttock => &[(Kind::Waterline, 2)],
            Kind::Edge => &[(Kind::Waterline, 2), (Kind::Buttock, 1)],
            _ => &[],
        };
        for &(kind, coord) in families {
            let at = c.get_index(coord);
            // the nearest crossing offset of the family below and above the cell on its station
            let mut below: Option<(f64, usize)> = None;
            let mut above: Option<(f64, usize)> = None;
            for (j, d) in t.cells.iter().enumerate() {
                if d.station_index != c.station_index
                    || !d.on_station
                    || t.lines[d.line].kind != kind
                    || sources[j] != Source::Hull
                    || !d.get_index(coord).is_finite()
                {
                    continue;
                }
                let v = d.get_index(coord);
                if v <= at && below.is_none_or(|(b, _)| v > b) {
                    below = Some((v, j));
                }
                if v >= at && above.is_none_or(|(a, _)| v < a) {
                    above = Some((v, j));
                }
            }
            for (_, j) in below.into_iter().chain(above) {
                crossing += 1;
                let d = &t.cells[j];
                let m = if rejected[j] {
                    f64::INFINITY
                } else {
                    dist(&[d.x, d.y, d.z], &values[j]) / tol
                };
                worst = worst.max(m);
            }
        }
    }
    crossing > 0 && worst <= CORROBORATE
}

/// The knuckle's half-breadth y_k(x) as a cubic spline on the knots `kx` (least squares to
/// the knuckle's faired spline `yk`, clamped to its ends, at eight points per span), the scale
/// of the bottom's u (see [`Hull`]); None where it comes within `min` of the centreline, as a
/// chine running into the stem does (the fraction is then undefined there).
fn knuckle_scale(kx: &Knots, yk: impl Fn(f64) -> f64, min: f64) -> Option<Spline> {
    let n = kx.count();
    let mut s = Spline {
        kx: kx.clone(),
        ku: None,
        c: vec![0.0; n],
    };
    let (x0, x1) = (kx.t[0], kx.t[kx.t.len() - 1]);
    let m = 8 * (n - 3);
    let mut ata = Band::zeros(n, 3);
    let mut atb = vec![0.0; n];
    for k in 0..=m {
        let x = x0 + (x1 - x0) * k as f64 / m as f64;
        let y = yk(x);
        let r = s.row(x, 0.0, 0);
        ata.add_outer(&r, 1.0);
        for &(i, w) in &r {
            atb[i] += w * y;
        }
    }
    s.c = ata.solve(&atb)?;
    let low = (0..=m).any(|k| s.eval(x0 + (x1 - x0) * k as f64 / m as f64, 0.0).0 <= min);
    (!low).then_some(s)
}

/// Offsets within this many rounding steps of a knuckle's height are cut from the region that
/// moves them least instead of being assigned to one by their (rounded) height.
const KNUCKLE_BAND: f64 = 2.0;

/// The offset (x, y, z) of a line of family `kind` cut from hull region `h`: a waterline keeps
/// its z, a buttock its y, an edge point is projected (one on the centreline keeps y = 0, see
/// [`on_centreline`]); None where the section misses it.
fn cut(h: &Hull, x: f64, y: f64, z: f64, kind: Kind) -> Option<[f64; 3]> {
    let (u, v) = h.uv(x, y, z);
    let (my, mz) = (kind != Kind::Buttock, kind != Kind::Waterline);
    let (mu, mv) = if h.value == Coord::Z { (my, mz) } else { (mz, my) };
    let p = if mv && !mu {
        h.point(x, u)
    } else if mu && !mv {
        h.point(x, h.solve_arg(x, v, u)?)
    } else {
        let (_, u2) = h.project(x, v, u);
        h.point(x, u2)
    };
    Some([
        x,
        if kind == Kind::Buttock || on_centreline(kind, y) {
            y
        } else {
            half_breadth(p[1])
        },
        if kind == Kind::Waterline { z } else { p[2] },
    ])
}

/// An edge offset at y = 0 lies on the centreline (a keel, stem or rabbet: the hull's plane of
/// symmetry), so its faired y stays exactly 0. On a region y(x, z) it is still projected in the
/// body plan (its height is the projection's), so it lies off the region's surface by the
/// projection's y: cut at y = 0 instead, it would take the surface's own height there, which
/// near the forefoot of a V bottom, where the sections steepen fast along x, is further from
/// the keel than the projection (see docs/experiments/lines-plan.md). On a bottom below a
/// knuckle, parametrised by the fraction of the way out to it, it is cut at u = 0: there the
/// bottom's sections are straight on noisy tables, and the projected keel sat up to a step off
/// the line through the bottom's other offsets, an inflection at most bottom stations.
fn on_centreline(kind: Kind, y: f64) -> bool {
    kind == Kind::Edge && y == 0.0
}

/// A half-breadth cut from the hull, never below the centreline: where a region's section at
/// the forefoot lies above a low waterline at y = 0 (the plane misses the hull there), the
/// waterline's cut continues the section's extension across the centreline to a negative
/// half-breadth; the waterline ends on the centreline instead.
fn half_breadth(y: f64) -> f64 {
    if y < 0.0 {
        0.0
    } else {
        y
    }
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

/// The straight limit's rejections stand: it rejects every offset the curved fit rejects, and
/// each further one it rejects has a deleted move in the curved fit beyond the rejection
/// threshold (the curved fit kept it only by bending to it).
fn straight_rejections_hold(straight: &Fit, curved: &Fit) -> bool {
    let deleted = |k: usize| curved.deleted_moves.iter().find(|d| d.0 == k).map(|d| d.1);
    (0..straight.weight.len()).all(|k| match (straight.weight[k] == 0.0, curved.weight[k] == 0.0) {
        (false, true) => false,
        (true, false) => deleted(k).is_some_and(|m| m.abs() > REJECT * curved.scale),
        _ => true,
    })
}

pub(crate) fn fit_summary(f: &Fit) -> (f64, usize, usize) {
    (
        f.lambda,
        f.iterations,
        f.weight.iter().filter(|w| **w == 0.0).count(),
    )
}
