//! The first knuckle edge (a chine): faired alone, it splits the hull into the region above it,
//! y(x, z), and the bottom below it, z(x, y / y_k(x)) ([`Hull`]), and it decides from which
//! region an offset near it is cut.

use crate::fit::Spline;
use crate::hull::{cut, Hull};
use crate::lofting::{dist, Cells, Source};
use crate::spline::{Band, Knots};
use crate::table::{Coord, Kind, Table};

/// Offsets within this many rounding steps of a knuckle's height are cut from the region that
/// moves them least instead of being assigned to one by their (rounded) height.
const KNUCKLE_BAND: f64 = 2.0;

/// The first knuckle edge, faired alone: its line, its heights z_k(x) and, where the same
/// line's half-breadths could be faired too, y_k(x).
pub(crate) struct Knuckle {
    line: usize,
    z: Spline,
    y: Option<Spline>,
}

/// A region of the hull to fit: its name, the coordinate its surface gives, its offsets and
/// the knuckle's faired points it holds.
#[derive(Clone)]
pub(crate) struct Region {
    pub(crate) name: String,
    pub(crate) value: Coord,
    pub(crate) cells: Vec<usize>,
    pub(crate) held: Vec<usize>,
}

/// A faired spline of one variable, held constant beyond its knots.
fn clamped(s: &Spline, x: f64) -> f64 {
    let (xa, xb) = (s.kx.t[0], s.kx.t[s.kx.t.len() - 1]);
    s.eval(x.clamp(xa, xb), 0.0).0
}

impl Knuckle {
    /// The knuckle from the first knuckle line's faired heights `z` and the first knuckle
    /// line's faired half-breadths `y` (each with its line), None without heights. The
    /// half-breadths count only when they are the same line's.
    pub(crate) fn new(z: Option<(usize, Spline)>, y: Option<(usize, Spline)>) -> Option<Knuckle> {
        let (line, z) = z?;
        let y = y.filter(|(yl, _)| *yl == line).map(|(_, s)| s);
        Some(Knuckle { line, z, y })
    }

    /// The knuckle's height z_k(x).
    pub(crate) fn height(&self, x: f64) -> f64 {
        clamped(&self.z, x)
    }

    /// Whether the knuckle's half-breadths were faired (the bottom below it can then be
    /// parametrised by the fraction of the way out to it).
    pub(crate) fn has_half_breadths(&self) -> bool {
        self.y.is_some()
    }

    /// The knuckle's half-breadths as the bottom's scale of u on the knots `kx`
    /// ([`knuckle_scale`]); None without half-breadths or where they come within `min` of the
    /// centreline.
    pub(crate) fn scale_on(&self, kx: &Knots, min: f64) -> Option<Spline> {
        let y = self.y.as_ref()?;
        knuckle_scale(kx, |x| clamped(y, x), min)
    }

    /// The regions the knuckle splits the hull offsets `idx` into, below first (its fit gives
    /// the knuckle's heights that the region above holds), each holding the knuckle's faired
    /// points; and the band of offsets within [`KNUCKLE_BAND`] steps of its height, which could
    /// lie on either side: they pull neither region and are cut later ([`Knuckle::cut_band`]).
    pub(crate) fn split(
        &self,
        t: &Table,
        values: &[[f64; 3]],
        idx: &[usize],
        step: f64,
    ) -> (Vec<Region>, Vec<usize>) {
        let held: Vec<usize> = t
            .line_cells(self.line)
            .into_iter()
            .filter(|&i| values[i][1].is_finite() && values[i][2].is_finite())
            .collect();
        let near: Vec<usize> = idx
            .iter()
            .copied()
            .filter(|&i| (t.cells[i].z - self.height(t.cells[i].x)).abs() <= KNUCKLE_BAND * step)
            .collect();
        let (above, below): (Vec<usize>, Vec<usize>) = idx
            .iter()
            .filter(|i| !near.contains(i))
            .partition(|&&i| t.cells[i].z >= self.height(t.cells[i].x));
        let name = &t.lines[self.line].label;
        let regions = vec![
            Region {
                name: format!("below {name}"),
                value: Coord::Z,
                cells: below,
                held: held.clone(),
            },
            Region {
                name: format!("above {name}"),
                value: Coord::Y,
                cells: above,
                held,
            },
        ];
        (regions, near)
    }

    /// The knuckle bounds both regions (`hulls`, above and below, with their offsets
    /// `region_cells`): an offset cut from one region onto the other's side of the knuckle (the
    /// extension of the topsides below a chine, where an offset near the chine, or a wrong one,
    /// was assigned above it) is cut from the other region instead.
    pub(crate) fn recut_across(
        &self,
        t: &Table,
        state: &mut Cells,
        hulls: &[Hull],
        region_cells: &[Vec<usize>],
        tol: f64,
    ) {
        let side = |h: &Hull, p: &[f64; 3]| {
            let d = p[2] - self.height(p[0]);
            if h.value == Coord::Y {
                d >= -tol
            } else {
                d <= tol
            }
        };
        for (r, cells) in region_cells.iter().enumerate() {
            for &i in cells {
                if state.sources[i] != Source::Hull || side(&hulls[r], &state.values[i]) {
                    continue;
                }
                let c = &t.cells[i];
                let other = &hulls[1 - r];
                if let Some(p) = cut(other, c.x, c.y, c.z, t.lines[c.line].kind) {
                    if side(other, &p) {
                        state.values[i] = p;
                    }
                }
            }
        }
    }

    /// Cuts the `band` of offsets near the knuckle ([`Knuckle::split`]), and the rejected
    /// offsets cut near it, from the region that moves them least; a cut that lies on its own
    /// region's side of the knuckle as the regions meet there (the bottom out to its edge,
    /// u <= 1; the topsides above the bottom's edge) is preferred when it moves the offset at
    /// most a rounding step more: a buttock through the chine at a station, cut from the
    /// topsides' extension a fraction of a step below the chine, moved least by a hundredth of
    /// a step and left the buttock with a hook and four inflections there. A rejected offset
    /// takes its own side's cut whatever it moves (its value is wrong, and so is the move it
    /// measures). Every band offset taking its own side's cut was measured and not kept: at a
    /// glancing crossing a tenth of a step in the knuckle's half-breadth moves the cut by
    /// several steps (docs/experiments/lines-plan.md). An offset no region cuts is rejected.
    pub(crate) fn cut_band(
        &self,
        t: &Table,
        state: &mut Cells,
        hulls: &[Hull],
        region_cells: &[Vec<usize>],
        mut band: Vec<usize>,
        step: f64,
    ) {
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
        if hulls.len() == 2 {
            for cells in region_cells {
                for &i in cells {
                    if state.rejected[i]
                        && state.sources[i] == Source::Hull
                        && (state.values[i][2] - self.height(state.values[i][0])).abs() <= KNUCKLE_BAND * step
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
            let window = if state.rejected[i] { f64::INFINITY } else { step };
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
                    state.values[i] = p;
                    state.sources[i] = Source::Hull;
                }
                None => state.rejected[i] = true,
            }
        }
    }
}

/// A waterline's half-breadth of 0 below a knuckle is where the waterline meets the centreline,
/// or a half-breadth rounded to 0: cut from the bottom (the region of `hulls` parametrised by
/// the fraction of the way out to the knuckle) like the rest, it is the bottom's own
/// half-breadth at that height (0 where the plane passes below the keel), unless the waterline
/// passes above the knuckle there (the bottom's extension). Kept as read, it made the station's
/// bottom step along the centreline from the faired keel up to it (noisy hard-chine tables: an
/// inflection at the bow's first station). Without such a bottom nothing changes.
pub(crate) fn cut_centreline_waterlines(t: &Table, state: &mut Cells, hulls: &[Hull]) {
    let Some(b) = hulls.iter().find(|h| h.scale.is_some()) else {
        return;
    };
    let ((x0, x1), _) = b.domain();
    for (i, c) in t.cells.iter().enumerate() {
        if t.lines[c.line].kind != Kind::Waterline || c.y != 0.0 || c.x < x0 || c.x > x1 {
            continue;
        }
        let own_side = |p: &[f64; 3]| p[1] <= b.u_scale(p[0]) * (1.0 + 1e-9);
        if let Some(p) = cut(b, c.x, c.y, c.z, Kind::Waterline).filter(own_side) {
            state.values[i] = p;
            state.sources[i] = Source::Hull;
        }
    }
}

/// The knuckle's half-breadth y_k(x) as a cubic spline on the knots `kx` (least squares to
/// the knuckle's faired spline `yk`, clamped to its ends, at eight points per span), the scale
/// of the bottom's u (see [`Hull`]); None where it comes within `min` of the centreline, as a
/// chine running into the stem does (the fraction is then undefined there).
pub(crate) fn knuckle_scale(kx: &Knots, yk: impl Fn(f64) -> f64, min: f64) -> Option<Spline> {
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
