//! The coordinate frame of a function segment (Han et al. §4.2.3).

use curve_repr::Vec2;

/// A rotated frame: origin at a segment's first point, x axis along the angular bisector of
/// the segment's extreme edge directions.
///
/// Han §4.2.3 (with the README's typo fixed): with u = argmax α_i and l = argmin α_i over the
/// segment's edges, the x axis bisects the angle from P_uP_{u+1} to P_lP_{l+1}, i.e. it has
/// the direction φ_0 + (α_u + α_l)/2 (φ_0 the direction of the walk's first edge). Every edge
/// direction is then within (α_u − α_l)/2 < π/2 of the axis, so x increases strictly along
/// the segment; [`partition`](super::partition) verifies this numerically.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The origin, in the original coordinates.
    pub origin: Vec2,
    /// The unit x axis, in the original coordinates.
    pub axis: Vec2,
}

impl Frame {
    /// The frame with `origin` and an x axis at `angle` radians (counter-clockwise from the
    /// original x axis).
    pub fn new(origin: Vec2, angle: f64) -> Self {
        Self {
            origin,
            axis: Vec2::new(angle.cos(), angle.sin()),
        }
    }

    /// The unit y axis (the x axis turned a quarter counter-clockwise).
    pub fn normal(&self) -> Vec2 {
        Vec2::new(-self.axis.y, self.axis.x)
    }

    /// A point in frame coordinates (x, y). O(1).
    pub fn to_local(&self, point: &Vec2) -> Vec2 {
        let d = point - self.origin;
        Vec2::new(d.dot(&self.axis), d.dot(&self.normal()))
    }

    /// A point given in frame coordinates, back in the original coordinates. O(1).
    pub fn to_global(&self, local: &Vec2) -> Vec2 {
        self.origin + self.axis * local.x + self.normal() * local.y
    }

    /// A change `dy` of a frame y coordinate (x unchanged), as a displacement in the original
    /// coordinates: `dy` times the unit normal. Moving points by displacements rather than
    /// through `to_global(to_local(p))` keeps untouched points bit-for-bit unchanged.
    pub fn displacement(&self, dy: f64) -> Vec2 {
        self.normal() * dy
    }
}
