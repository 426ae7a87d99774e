//! Closed grid lines (seams) and collapsed ones (poles) of a net P_ij, i = 0..m, j = 0..n.
//!
//! A net is **closed in v** when its last column repeats its first (P_{i,n} = P_{i,0} for
//! every i: a body of revolution whose columns run round the axis, as the Utah teapot's), and
//! **closed in u** when its last row repeats its first. The layout keeps the repeated line, so
//! a closed net is written and read like any other; the bicubic surface built with
//! [`BicubicSurfaceSettings::with_closed_v`](super::BicubicSurfaceSettings::with_closed_v) is
//! then periodic across the seam (C2 there, like at any interior knot line).
//!
//! A **pole** is a boundary line collapsed to one point (P_{m,j} = P_{m,0} for every j: the
//! centre of the teapot's bottom). The surface needs nothing special there (the line through
//! the pole is constant, so its tangents vanish); a fairing keeps it one point.
//!
//! [`GridTopology::detect`] finds both, comparing points to 1e-12 of the net's bounding-box
//! diagonal ([`COINCIDENCE`]). O(m·n).

use crate::Vec3;

/// Relative distance (to the net's bounding-box diagonal) below which two points of a net
/// count as the same point for [`GridTopology::detect`].
pub const COINCIDENCE: f64 = 1e-12;

/// The boundary lines of a net that are collapsed to a point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Poles {
    /// Row i = 0 is one point.
    pub u_start: bool,
    /// Row i = m is one point.
    pub u_end: bool,
    /// Column j = 0 is one point.
    pub v_start: bool,
    /// Column j = n is one point.
    pub v_end: bool,
}

impl Poles {
    /// Whether any boundary line is a pole.
    pub fn any(&self) -> bool {
        self.u_start || self.u_end || self.v_start || self.v_end
    }

    /// Whether node (i, j) of an `u_count` × `v_count` net lies on a pole.
    pub fn contains(&self, i: usize, j: usize, u_count: usize, v_count: usize) -> bool {
        (self.u_start && i == 0)
            || (self.u_end && i + 1 == u_count)
            || (self.v_start && j == 0)
            || (self.v_end && j + 1 == v_count)
    }
}

/// Seams and poles of a net: closed in v when the last column repeats the first, in u when the
/// last row repeats the first; a pole is a boundary line collapsed to one point
/// ([`GridTopology::detect`] finds both).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct GridTopology {
    /// Row i = m repeats row i = 0: the net is periodic along u.
    pub closed_u: bool,
    /// Column j = n repeats column j = 0: the net is periodic along v.
    pub closed_v: bool,
    /// Boundary lines collapsed to a point (never on a closed direction's ends).
    pub poles: Poles,
}

impl GridTopology {
    /// An open net without poles.
    pub fn open() -> Self {
        Self::default()
    }

    /// Seams and poles of the flat net `points[i·v_count + j]` = P_ij: a direction is closed
    /// when its last line repeats its first and the net has at least four lines along it
    /// (three distinct and the repeat); a boundary line of an open direction is a pole when
    /// all its points coincide. Points coincide within [`COINCIDENCE`] × the bounding-box
    /// diagonal. A net whose points all coincide is open without poles. O(m·n).
    pub fn detect(points: &[Vec3], u_count: usize, v_count: usize) -> Self {
        if u_count < 2 || v_count < 2 || points.len() != u_count * v_count {
            return Self::default();
        }
        let tolerance = COINCIDENCE * diagonal(points);
        if tolerance == 0.0 || !tolerance.is_finite() {
            return Self::default();
        }
        let at = |i: usize, j: usize| points[i * v_count + j];
        let same = |a: Vec3, b: Vec3| (a - b).norm() <= tolerance;
        let closed_u = u_count >= 4 && (0..v_count).all(|j| same(at(0, j), at(u_count - 1, j)));
        let closed_v = v_count >= 4 && (0..u_count).all(|i| same(at(i, 0), at(i, v_count - 1)));
        Self::with_closure(points, u_count, v_count, closed_u, closed_v)
    }

    /// The given closures, with the poles detected (as [`detect`](Self::detect) does) on the
    /// ends of the open directions. O(m·n).
    pub fn with_closure(
        points: &[Vec3],
        u_count: usize,
        v_count: usize,
        closed_u: bool,
        closed_v: bool,
    ) -> Self {
        let mut topology = Self {
            closed_u,
            closed_v,
            poles: Poles::default(),
        };
        if u_count < 2 || v_count < 2 || points.len() != u_count * v_count {
            return topology;
        }
        let tolerance = COINCIDENCE * diagonal(points);
        if tolerance == 0.0 || !tolerance.is_finite() {
            return topology;
        }
        let at = |i: usize, j: usize| points[i * v_count + j];
        let same = |a: Vec3, b: Vec3| (a - b).norm() <= tolerance;
        let row_is_point = |i: usize| (1..v_count).all(|j| same(at(i, j), at(i, 0)));
        let column_is_point = |j: usize| (1..u_count).all(|i| same(at(i, j), at(0, j)));
        topology.poles = Poles {
            u_start: !closed_u && row_is_point(0),
            u_end: !closed_u && row_is_point(u_count - 1),
            v_start: !closed_v && column_is_point(0),
            v_end: !closed_v && column_is_point(v_count - 1),
        };
        topology
    }

    /// Whether the net is closed in some direction or has a pole.
    pub fn is_special(&self) -> bool {
        self.closed_u || self.closed_v || self.poles.any()
    }
}

/// The bounding-box diagonal of finite points (0 for none).
pub(crate) fn diagonal(points: &[Vec3]) -> f64 {
    let mut low = Vec3::repeat(f64::INFINITY);
    let mut high = Vec3::repeat(f64::NEG_INFINITY);
    for p in points.iter().filter(|p| p.iter().all(|c| c.is_finite())) {
        low = low.inf(p);
        high = high.sup(p);
    }
    if low.x.is_finite() {
        (high - low).norm()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cylinder-like net: rows along the axis, columns round it, the last column repeating
    /// the first; optionally the last row collapsed to the axis.
    fn tube(rows: usize, columns: usize, pole: bool) -> Vec<Vec3> {
        let mut points = Vec::new();
        for i in 0..rows {
            for j in 0..columns {
                let angle = std::f64::consts::TAU * (j % (columns - 1)) as f64 / (columns - 1) as f64;
                let r = if pole && i + 1 == rows {
                    0.0
                } else {
                    1.0 + 0.1 * i as f64
                };
                points.push(Vec3::new(r * angle.cos(), r * angle.sin(), i as f64));
            }
        }
        points
    }

    #[test]
    fn seams_and_poles_are_found() {
        let t = GridTopology::detect(&tube(5, 9, true), 5, 9);
        assert!(t.closed_v && !t.closed_u);
        assert_eq!(
            t.poles,
            Poles {
                u_end: true,
                ..Poles::default()
            }
        );
        assert!(t.poles.contains(4, 3, 5, 9) && !t.poles.contains(3, 3, 5, 9));
        let open = GridTopology::detect(&tube(5, 9, false), 5, 9);
        assert!(open.closed_v && !open.poles.any());
        // Transposed: the seam is a row.
        let points = tube(5, 9, false);
        let transposed: Vec<Vec3> = (0..9)
            .flat_map(|j| (0..5).map(move |i| (i, j)))
            .map(|(i, j)| points[i * 9 + j])
            .collect();
        let t = GridTopology::detect(&transposed, 9, 5);
        assert!(t.closed_u && !t.closed_v);
    }

    #[test]
    fn a_seam_off_by_more_than_the_tolerance_is_open_and_small_nets_are_never_closed() {
        let mut points = tube(5, 9, false);
        points[2 * 9 + 8].z += 1e-9;
        assert!(!GridTopology::detect(&points, 5, 9).closed_v);
        // Three columns, the third repeating the first: too few distinct lines to close.
        let three: Vec<Vec3> = (0..3)
            .flat_map(|i| [0.0, 1.0, 0.0].map(|y| Vec3::new(i as f64, y, 0.0)))
            .collect();
        assert!(!GridTopology::detect(&three, 3, 3).closed_v);
        assert_eq!(
            GridTopology::detect(&[Vec3::zeros(); 9], 3, 3),
            GridTopology::open()
        );
    }
}
