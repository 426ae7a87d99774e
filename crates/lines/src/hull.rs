//! One smooth region of the hull as a surface, and how an offset is cut back from it.

use crate::fit::Spline;
use crate::table::{Coord, Kind};

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
    pub(crate) value: Coord,
    pub(crate) region: String,
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
    pub(crate) fn uv(&self, x: f64, y: f64, z: f64) -> (f64, f64) {
        match self.value {
            Coord::Z => (y / self.u_scale(x), z),
            _ => (z, y),
        }
    }
}

/// The offset (x, y, z) of a line of family `kind` cut from hull region `h`: a waterline keeps
/// its z, a buttock its y, an edge point is projected (one on the centreline keeps y = 0, see
/// [`on_centreline`]); None where the section misses it.
pub(crate) fn cut(h: &Hull, x: f64, y: f64, z: f64, kind: Kind) -> Option<[f64; 3]> {
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
pub(crate) fn on_centreline(kind: Kind, y: f64) -> bool {
    kind == Kind::Edge && y == 0.0
}

/// A half-breadth cut from the hull, never below the centreline: where a region's section at
/// the forefoot lies above a low waterline at y = 0 (the plane misses the hull there), the
/// waterline's cut continues the section's extension across the centreline to a negative
/// half-breadth; the waterline ends on the centreline instead.
pub(crate) fn half_breadth(y: f64) -> f64 {
    if y < 0.0 {
        0.0
    } else {
        y
    }
}
