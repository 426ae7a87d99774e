//! Fairing a table as one hull: the settings, the lines faired alone, the fit of every offset
//! at once region by region, and the cut of every offset back from the hull. The hull's
//! regions are in `hull`, the knuckle that splits them in `knuckle`, the
//! runs of offsets kept as features in `features`.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::features::hold_feature_runs;
use crate::fit::{fit, parsimony_slack, Fit, How, Obs, Spline, REJECT};
pub use crate::hull::Hull;
use crate::hull::{half_breadth, on_centreline};
use crate::knuckle::{cut_centreline_waterlines, knuckle_scale, Knuckle, Region};
use crate::report::{build_report, Report};
use crate::spline::Knots;
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
    let mut state = Cells::read(&t);
    let use_hull = t.has_redundant_views();
    let knuckle = fair_alone(&t, &mut state, use_hull, tol);
    let mut hulls = Vec::new();
    let mut fits = Vec::new();
    if use_hull {
        let idx: Vec<usize> = (0..t.cells.len()).filter(|&i| on_hull(&t, i)).collect();
        // one region, or above (y(x, z)) and below (z(x, y)) the first knuckle edge
        let (regions, band) = match &knuckle {
            Some(k) => k.split(&t, &state.values, &idx, step),
            None => (
                vec![Region {
                    name: "hull".into(),
                    value: Coord::Y,
                    cells: idx.clone(),
                    held: Vec::new(),
                }],
                Vec::new(),
            ),
        };
        let fitted = fit_regions(&t, &mut state, &regions, knuckle.as_ref(), step, tol)?;
        if let Some(k) = &knuckle {
            if fitted.hulls.len() == 2 {
                k.recut_across(&t, &mut state, &fitted.hulls, &fitted.cells, tol);
            }
            k.cut_band(&t, &mut state, &fitted.hulls, &fitted.cells, band, step);
        }
        cut_centreline_waterlines(&t, &mut state, &fitted.hulls);
        if fitted.hulls.is_empty() {
            return Err(Error::Fit(format!(
                "{} offsets on the hull: too few for a surface",
                idx.len()
            )));
        }
        hold_feature_runs(&t, &mut state, tol);
        hulls = fitted.hulls;
        fits = fitted.fits;
    }
    let Cells {
        values,
        sources,
        rejected,
    } = state;
    let flagged: Vec<bool> = (0..t.cells.len())
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

/// Per cell of a table being faired: its value so far, where that came from, and whether a
/// fit rejected it.
#[derive(Clone)]
pub(crate) struct Cells {
    pub(crate) values: Vec<[f64; 3]>,
    pub(crate) sources: Vec<Source>,
    pub(crate) rejected: Vec<bool>,
}

impl Cells {
    /// Every cell as read, held, none rejected.
    fn read(t: &Table) -> Cells {
        let n = t.cells.len();
        Cells {
            values: t.cells.iter().map(|c| [c.x, c.y, c.z]).collect(),
            sources: vec![Source::Held; n],
            rejected: vec![false; n],
        }
    }
}

/// Whether cell `i` is an offset of the hull's surface: a waterline's off the centreline, a
/// buttock's, a non-knuckle edge's.
fn on_hull(t: &Table, i: usize) -> bool {
    let c = &t.cells[i];
    let l = &t.lines[c.line];
    match l.kind {
        Kind::Waterline => c.y != 0.0,
        Kind::Buttock => true,
        Kind::Edge => !l.knuckle,
        _ => false,
    }
}

/// Fairs the lines that are not cut from the hull (every line of a table without one; with
/// one, the knuckle edges and the profile-only and plan-only lines), y(x) and z(x) each with
/// the hull's penalty and tolerance, before the hull is fitted. Returns the first knuckle
/// edge, which splits the hull into regions. O(n) per line and solve.
fn fair_alone(t: &Table, state: &mut Cells, use_hull: bool, tol: f64) -> Option<Knuckle> {
    let mut knuckle_z: Option<(usize, Spline)> = None;
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
                .filter(|&i| state.values[i][coord].is_finite())
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
                state.values[i][coord] = f.spline.eval(t.cells[i].x, 0.0).0;
                state.sources[i] = Source::Line;
                if f.weight[k] == 0.0 {
                    state.rejected[i] = true;
                }
            }
            if use_hull && l.knuckle && coord == 2 && knuckle_z.is_none() {
                knuckle_z = Some((li, f.spline.clone()));
            }
            if use_hull && l.knuckle && coord == 1 && knuckle_y.is_none() {
                knuckle_y = Some((li, f.spline.clone()));
            }
        }
    }
    Knuckle::new(knuckle_z, knuckle_y)
}

/// The hull's regions as fitted: their surfaces, fits (with the region's name) and offsets,
/// the region above a knuckle first.
#[derive(Default)]
struct Fitted {
    hulls: Vec<Hull>,
    fits: Vec<(String, Fit)>,
    cells: Vec<Vec<usize>>,
}

/// Fits every region and cuts its offsets from it ([`fit_region`]). With a knuckle whose
/// half-breadths scale the bottom, a second pass starts again from the cells as they were
/// with the knuckle's half-breadths the topsides gave on the first (see [`fair`]).
fn fit_regions(
    t: &Table,
    state: &mut Cells,
    regions: &[Region],
    knuckle: Option<&Knuckle>,
    step: f64,
    tol: f64,
) -> Result<Fitted> {
    let snapshot = state.clone();
    // the knuckle's half-breadths the bottom's u is scaled by, from the topsides' fit
    let mut rescale: Option<Spline> = None;
    let mut out = Fitted::default();
    for pass in 0..2 {
        if pass == 1 {
            if rescale.is_none() {
                break;
            }
            *state = snapshot.clone();
            if let (Some(r), Some(region)) = (&rescale, regions.first()) {
                for &i in &region.held {
                    state.values[i][1] = r.eval(state.values[i][0], 0.0).0;
                }
            }
            out = Fitted::default();
        }
        let mut below_soft = false;
        for region in regions {
            let args = (pass, rescale.as_ref(), step, tol);
            if let Some((h, f)) = fit_region(t, state, region, knuckle, args, &mut below_soft)? {
                out.fits.push((h.region.clone(), f));
                out.hulls.push(h);
                out.cells.push(region.cells.clone());
            }
        }
        if pass == 0 && below_soft && out.hulls.len() == 2 {
            // the knuckle's half-breadth along x: the topsides' at the bottom's edge
            let (below, above) = (&out.hulls[0], &out.hulls[1]);
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
    if knuckle.is_some() {
        out.hulls.reverse();
        out.fits.reverse();
        out.cells.reverse();
    }
    Ok(out)
}

/// Fits one region on pass `pass` (with the bottom's scale `rescale` from the first pass) and
/// cuts its offsets from it: the surface on knots one span per station interval and per plane
/// of its u family, the free fit and the straight-section limit (see [`fair`]), each offset's
/// new value, rejections, and the knuckle's points the region gives (its heights from the
/// bottom, its half-breadths from the topsides on the first pass). `below_soft` is set by the
/// region below a knuckle (whether u there is the fraction of the way out to it) and read by
/// the region above. None where the region has fewer than 8 offsets or no extent. Fails where
/// the free fit's system is singular.
fn fit_region(
    t: &Table,
    state: &mut Cells,
    region: &Region,
    knuckle: Option<&Knuckle>,
    (pass, rescale, step, tol): (usize, Option<&Spline>, f64, f64),
    below_soft: &mut bool,
) -> Result<Option<(Hull, Fit)>> {
    let Region {
        name,
        value,
        cells,
        held,
    } = region;
    let value = *value;
    if cells.len() < 8 {
        return Ok(None);
    }
    let pts: Vec<(f64, f64, f64)> = cells
        .iter()
        .map(|&i| (t.cells[i].x, t.cells[i].y, t.cells[i].z))
        .chain(
            held.iter()
                .map(|&i| (state.values[i][0], state.values[i][1], state.values[i][2])),
        )
        .collect();
    let (mut x0, mut x1) = (f64::MAX, f64::MIN);
    for &(x, _, _) in &pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
    }
    if x1 <= x0 {
        return Ok(None);
    }
    let xs = t.stations.len().max(2) - 1;
    let kx = Knots::uniform(x0, x1, xs.min(80));
    // below a knuckle, u is the fraction of the way out to it (see `Hull`)
    let scale = match knuckle {
        Some(k) if value == Coord::Z && k.has_half_breadths() => {
            rescale.cloned().or_else(|| k.scale_on(&kx, 4.0 * step))
        }
        _ => None,
    };
    if value == Coord::Z {
        *below_soft = scale.is_some();
    }
    // above a knuckle whose heights are the bottom's edge, its half-breadths as read are
    // offsets of the topsides' lower edge (at those heights)
    let soft_y = pass == 0 && value == Coord::Y && *below_soft;
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
        return Ok(None);
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
    for &i in held {
        let z = if soft { t.cells[i].z } else { state.values[i][2] };
        let y = if soft_y { t.cells[i].y } else { state.values[i][1] };
        let (u, v) = uv(state.values[i][0], y, z);
        let mut o = if soft || soft_y {
            Obs::new((state.values[i][0], u), v, true, false)
        } else {
            Obs::new((state.values[i][0], u), v, true, true)
        };
        o.held = !(soft || soft_y);
        o.u_scale = g(state.values[i][0]);
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
    let interim = pass == 0 && *below_soft;
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
        region: name.clone(),
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
                state.values[i] = [
                    c.x,
                    if kind == Kind::Buttock || on_centreline(kind, c.y) {
                        c.y
                    } else {
                        half_breadth(p[1])
                    },
                    if kind == Kind::Waterline { c.z } else { p[2] },
                ];
            }
            None => state.rejected[i] = true,
        }
        state.sources[i] = Source::Hull;
        if f.weight[k] == 0.0 {
            state.rejected[i] = true;
        }
    }
    // the knuckle's height is the bottom's edge (the region above, fitted next, holds it)
    if soft {
        for (k, &i) in held.iter().enumerate() {
            let (u, _) = h.uv(state.values[i][0], state.values[i][1], state.values[i][2]);
            state.values[i][2] = h.eval(state.values[i][0], u).0;
            if f.weight[cells.len() + k] == 0.0 {
                state.rejected[i] = true;
            }
        }
    }
    if soft_y {
        for (k, &i) in held.iter().enumerate() {
            state.values[i][1] = half_breadth(h.eval(state.values[i][0], state.values[i][2]).0);
            if f.weight[cells.len() + k] == 0.0 {
                state.rejected[i] = true;
            }
        }
    }
    Ok(Some((h, f)))
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
