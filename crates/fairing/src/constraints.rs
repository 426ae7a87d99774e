//! What must hold while a curve is faired: fixed points, restraining regions, a tolerance
//! band and end clamps, defined once for every strategy.
//!
//! Every strategy moves points through [`FairingState::move_point`](crate::FairingState::move_point),
//! which applies [`Constraints::constrain_move`]; the [`Pipeline`](crate::Pipeline) checks the
//! final result with [`Constraints::check`], so a buggy strategy cannot silently break a promise.
//!
//! Distances are Euclidean and measured from a point's ORIGINAL position (the input of the
//! whole pipeline), never from its current one: a chain of small moves cannot walk a point out
//! of its region.

use std::collections::BTreeSet;

use curve_repr::Vector;
use serde::{Deserialize, Serialize};

use crate::{Error, Result};

/// What the ends of an open curve keep.
///
/// Each level includes the ones before it. A closed curve has no ends: strategies reject any
/// clamp other than [`EndClamp::None`] for one.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EndClamp {
    /// The ends may move like any other point.
    #[default]
    None,
    /// The end points keep their positions (bit for bit). Honoured by the constraints
    /// themselves: [`Constraints::is_movable`] freezes points 0 and n − 1.
    G0,
    /// Also the end tangents of the curve are kept. The end points are frozen as for `G0`;
    /// the tangent is a property of the curve, not of the points, so a strategy honours it
    /// through its representation: an interpolating spline built with the clamped end
    /// condition, its end tangents taken from the spline through the ORIGINAL points, keeps
    /// them whatever interior point moves. A strategy that cannot do so (e.g. one whose
    /// spline has the parabolic-runout end condition) must return
    /// [`Error::ConstraintUnsupported`] from
    /// [`FairingStrategy::supports`](crate::FairingStrategy::supports).
    G1,
    /// Also the end curvatures are kept: the end points frozen as for `G0`, the end
    /// tangent and curvature kept by the representation (both end derivatives prescribed).
    /// A strategy whose representation has only one end condition per end (a cubic
    /// interpolating spline) can honour it only by freezing the first and last three points
    /// AND using a local end construction; otherwise it must report
    /// [`Error::ConstraintUnsupported`].
    G2,
}

impl EndClamp {
    /// The highest derivative order kept at the ends: `None` for no clamp, 0 for `G0`,
    /// 1 for `G1`, 2 for `G2`.
    pub fn order(self) -> Option<usize> {
        match self {
            EndClamp::None => None,
            EndClamp::G0 => Some(0),
            EndClamp::G1 => Some(1),
            EndClamp::G2 => Some(2),
        }
    }

    /// The name used in messages and on the command line (`g0`, `g1`, `g2`, `none`).
    pub fn name(self) -> &'static str {
        match self {
            EndClamp::None => "none",
            EndClamp::G0 => "g0",
            EndClamp::G1 => "g1",
            EndClamp::G2 => "g2",
        }
    }
}

/// The constraints every strategy honours.
///
/// Built with [`Default`] (no constraint) and the `with_*` setters:
///
/// ```
/// use fairing::{Constraints, EndClamp};
/// let c = Constraints::default()
///     .with_fixed([3, 7])
///     .with_tolerance(0.5)
///     .with_end_clamp(EndClamp::G0);
/// assert!(c.validate(10).is_ok());
/// assert!(!c.is_movable(0, 10) && !c.is_movable(3, 10) && c.is_movable(4, 10));
/// ```
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Constraints {
    fixed: BTreeSet<usize>,
    radii: Option<Vec<f64>>,
    tolerance: Option<f64>,
    end_clamp: EndClamp,
    /// Surface edges held to neighbours (only the surface `jump-lsq` takes them).
    #[serde(skip)]
    joins: Vec<crate::strategies::Join>,
}

impl Constraints {
    /// Adds points that never move (their coordinates stay bit for bit).
    pub fn with_fixed(mut self, indices: impl IntoIterator<Item = usize>) -> Self {
        self.fixed.extend(indices);
        self
    }

    /// Sets one restraining radius per point (Zhang–Cheng §2.3's restraining circles in 2D,
    /// §4's spheres in 3D): point i never leaves the closed ball of radius `radii[i]` around
    /// its original position. `f64::INFINITY` leaves a point unrestrained; 0 freezes it.
    ///
    /// These are the user's radii. Zhang–Cheng's automatic algorithm derives its own region
    /// from the data (radius |P_i − P̄_i|, P̄_i from their Eq. 11) at `init`; such a strategy
    /// keeps those radii itself and applies [`project_into_ball`] before
    /// [`FairingState::move_point`](crate::FairingState::move_point) applies these.
    pub fn with_restraining_radii(mut self, radii: Vec<f64>) -> Self {
        self.radii = Some(radii);
        self
    }

    /// Sets the tolerance band: no point moves farther than `distance` from its original
    /// position (the promise of Rhino's Fair command, `fair --tolerance D`).
    pub fn with_tolerance(mut self, distance: f64) -> Self {
        self.tolerance = Some(distance);
        self
    }

    /// Sets what the ends of an open curve keep.
    pub fn with_end_clamp(mut self, clamp: EndClamp) -> Self {
        self.end_clamp = clamp;
        self
    }

    /// Holds an edge of a surface net to a neighbour (the surface `jump-lsq`'s joins; other
    /// methods refuse them).
    pub fn with_join(mut self, join: crate::strategies::Join) -> Self {
        self.joins.push(join);
        self
    }

    /// The surface joins.
    pub fn joins(&self) -> &[crate::strategies::Join] {
        &self.joins
    }

    /// The fixed points, increasing.
    pub fn fixed(&self) -> &BTreeSet<usize> {
        &self.fixed
    }

    /// The restraining radii, if set.
    pub fn restraining_radii(&self) -> Option<&[f64]> {
        self.radii.as_deref()
    }

    /// The tolerance band, if set.
    pub fn tolerance(&self) -> Option<f64> {
        self.tolerance
    }

    /// The end clamp.
    pub fn end_clamp(&self) -> EndClamp {
        self.end_clamp
    }

    /// Whether no constraint at all is set.
    pub fn is_empty(&self) -> bool {
        *self == Constraints::default()
    }

    /// Checks the constraints against a curve of `n` points: fixed indices below `n`, one
    /// radius per point, radii and tolerance not negative and not NaN (infinity is allowed).
    pub fn validate(&self, n: usize) -> Result<()> {
        if let Some(&index) = self.fixed.range(n..).next() {
            return Err(Error::BadConstraint {
                reason: format!("fixed point {index} out of range for {n} points"),
            });
        }
        if let Some(radii) = &self.radii {
            if radii.len() != n {
                return Err(Error::BadConstraint {
                    reason: format!("{} restraining radii for {n} points", radii.len()),
                });
            }
            if let Some(index) = radii.iter().position(|r| r.is_nan() || *r < 0.0) {
                return Err(Error::BadConstraint {
                    reason: format!("restraining radius of point {index} is {}", radii[index]),
                });
            }
        }
        if let Some(d) = self.tolerance {
            if d.is_nan() || d < 0.0 {
                return Err(Error::BadConstraint {
                    reason: format!("tolerance {d} is negative or NaN"),
                });
            }
        }
        Ok(())
    }

    /// Whether point `index` of a curve of `n` points is an end frozen by the end clamp.
    pub fn is_clamped_end(&self, index: usize, n: usize) -> bool {
        self.end_clamp != EndClamp::None && (index == 0 || index + 1 == n)
    }

    /// The largest distance point `index` may move from its original position: the smaller
    /// of its restraining radius and the tolerance band (the intersection of two balls with
    /// one centre is the smaller ball); `f64::INFINITY` when neither is set.
    pub fn allowed_distance(&self, index: usize) -> f64 {
        let radius = self
            .radii
            .as_ref()
            .and_then(|r| r.get(index))
            .copied()
            .unwrap_or(f64::INFINITY);
        radius.min(self.tolerance.unwrap_or(f64::INFINITY))
    }

    /// Whether point `index` of a curve of `n` points may move at all: it is in range, not
    /// fixed, not a clamped end ([`EndClamp::G0`] and above freeze points 0 and n − 1) and its
    /// allowed distance is positive.
    pub fn is_movable(&self, index: usize, n: usize) -> bool {
        index < n
            && !self.fixed.contains(&index)
            && !self.is_clamped_end(index, n)
            && self.allowed_distance(index) > 0.0
    }

    /// Projects a proposed position of point `index` (of `n`) onto the set the constraints allow.
    ///
    /// A frozen point (see [`is_movable`](Self::is_movable)) gets its `original` position
    /// back, bit for bit. Otherwise the nearest point of the allowed ball (radius
    /// [`allowed_distance`](Self::allowed_distance) around `original`) is returned: the
    /// proposal itself if it lies inside, else the intersection of the sphere with the segment
    /// from the centre to the proposal (Zhang–Cheng, automatic algorithm step 2.3). The
    /// projection is idempotent and its result is never farther than the radius as computed
    /// by `(result - original).norm()` (see [`project_into_ball`]). O(D).
    ///
    /// Errors: [`Error::NonFiniteMove`] for a NaN or infinite proposal.
    pub fn constrain_move<const D: usize>(
        &self,
        index: usize,
        n: usize,
        original: &Vector<D>,
        proposed: &Vector<D>,
    ) -> Result<Vector<D>> {
        if proposed.iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFiniteMove { index });
        }
        if !self.is_movable(index, n) {
            return Ok(*original);
        }
        Ok(project_into_ball(
            original,
            self.allowed_distance(index),
            proposed,
        ))
    }

    /// Like [`constrain_move`](Self::constrain_move), but the coordinates in which `proposed`
    /// equals `current` (bit for bit) are kept: the projection onto the allowed ball moves
    /// only the coordinates the strategy changed. A function strategy that moves y only
    /// therefore never changes x, even when an earlier stage moved x so that the point is
    /// no longer level with its original (the ball's slice at the current x is then a
    /// smaller ball around the original's y). When the held coordinates equal the
    /// original's this is the same projection as `constrain_move`. O(D).
    ///
    /// If `current` itself lies outside the allowed ball (so that no point with its held
    /// coordinates is allowed), the full projection of `proposed` is returned.
    pub fn constrain_move_from<const D: usize>(
        &self,
        index: usize,
        n: usize,
        original: &Vector<D>,
        current: &Vector<D>,
        proposed: &Vector<D>,
    ) -> Result<Vector<D>> {
        if proposed.iter().any(|c| !c.is_finite()) {
            return Err(Error::NonFiniteMove { index });
        }
        if !self.is_movable(index, n) {
            return Ok(*original);
        }
        let radius = self.allowed_distance(index);
        // The coordinates the proposal leaves as they are (on the stack: a move is O(D)).
        let mut held = [0; D];
        let mut count = 0;
        for k in 0..D {
            if proposed[k] == current[k] {
                held[count] = k;
                count += 1;
            }
        }
        let held = &held[..count];
        if held.is_empty() || held.len() == D || !radius.is_finite() {
            return Ok(project_into_ball(original, radius, proposed));
        }
        // The slice of the ball through the held coordinates: centre = the original with the
        // held coordinates replaced, radius² = r² − (held offset)².
        let mut center = *original;
        let mut offset2 = 0.0;
        for &k in held {
            center[k] = current[k];
            offset2 += (current[k] - original[k]).powi(2);
        }
        let slice = radius * radius - offset2;
        if slice.is_nan() || slice < 0.0 || (current - original).norm() > radius {
            return Ok(project_into_ball(original, radius, proposed));
        }
        let mut candidate = project_into_ball(&center, slice.sqrt(), proposed);
        // Round-off: shrink toward the current point (which is allowed) until the full
        // distance holds as computed.
        for _ in 0..16 {
            if (candidate - original).norm() <= radius {
                return Ok(candidate);
            }
            candidate = current + (candidate - current) * (1.0 - 1e-12);
        }
        Ok(*current)
    }

    /// Checks that `faired` honours every constraint against `original`, naming the first
    /// violated point. Fixed points and clamped ends must be bit-for-bit equal (`==` on every
    /// coordinate); every point must lie within its allowed distance. The derivative part of
    /// a G1/G2 clamp is a property of the curve, not of the points, and is not checked here.
    /// O(n·D).
    pub fn check<const D: usize>(&self, original: &[Vector<D>], faired: &[Vector<D>]) -> Result<()> {
        let n = original.len();
        if faired.len() != n {
            return Err(curve_repr::Error::LengthMismatch {
                what: "faired points",
                expected: n,
                got: faired.len(),
            }
            .into());
        }
        self.validate(n)?;
        for (index, (p, q)) in original.iter().zip(faired).enumerate() {
            if q.iter().any(|c| !c.is_finite()) {
                return Err(Error::NonFiniteMove { index });
            }
            let frozen = self.fixed.contains(&index) || self.is_clamped_end(index, n);
            if frozen && p != q {
                return Err(Error::ConstraintViolated {
                    index,
                    constraint: if self.fixed.contains(&index) {
                        "fixed point"
                    } else {
                        "end clamp"
                    },
                    detail: format!("moved by {:e}", (q - p).norm()),
                });
            }
            let distance = (q - p).norm();
            let allowed = self.allowed_distance(index);
            if distance > allowed {
                let radius = self
                    .radii
                    .as_ref()
                    .and_then(|r| r.get(index))
                    .copied()
                    .unwrap_or(f64::INFINITY);
                return Err(Error::ConstraintViolated {
                    index,
                    constraint: if radius <= allowed {
                        "restraining radius"
                    } else {
                        "tolerance"
                    },
                    detail: format!("moved {distance:e}, allowed {allowed:e}"),
                });
            }
        }
        Ok(())
    }
}

/// The nearest point to `proposed` in the closed ball of `radius` around `center`.
///
/// Inside the ball (`(proposed - center).norm() <= radius`) the proposal is returned
/// unchanged, so the projection is idempotent. Outside, the point at `radius` along the
/// segment from the centre to the proposal; if rounding puts it a hair outside, the step is
/// shortened by a few ulps until `(result - center).norm() <= radius` holds as computed (the
/// centre itself is the last resort). A radius of 0 (or NaN) returns the centre. O(D).
pub fn project_into_ball<const D: usize>(center: &Vector<D>, radius: f64, proposed: &Vector<D>) -> Vector<D> {
    let offset = proposed - center;
    let distance = offset.norm();
    if distance <= radius {
        return *proposed;
    }
    if radius.is_nan() || radius <= 0.0 || !distance.is_finite() {
        return *center;
    }
    let mut scale = radius / distance;
    for attempt in 0..16 {
        let candidate = center + offset * scale;
        if (candidate - center).norm() <= radius {
            return candidate;
        }
        scale *= 1.0 - f64::EPSILON * f64::from(4u32 << attempt);
    }
    *center
}
