//! [`SegmentedFairing`]: Han et al.'s arbitrary-curve pipeline (§4.2.4) as a strategy.

use curve_repr::Vec2;

use super::guard::{pass_keeps_counts, segment_moves};
use super::{blend, partition, CurveGuard, PartitionSettings};
use crate::{Error, FairingState, FairingStrategy, Result, StepOutcome};

/// Fairs one function segment y(x) in place: the inner method of [`SegmentedFairing`]
/// (Han's two-phase fairing, a smoothing spline, ...).
///
/// `x` increases strictly; `fixed[j]` marks points that must not move (fixed points and
/// clamped curve ends; moving them anyway is undone by the constraints). Only y may change,
/// so every move is normal to the frame's x axis. Any closure
/// `FnMut(&[f64], &mut [f64], &[bool]) -> Result<()>` is a segment fairer with the defaults.
pub trait SegmentFairer {
    /// The fairer's name, used in [`SegmentedFairing`]'s name and its errors.
    fn name(&self) -> &str {
        "segment"
    }

    /// The fewest points it can fair; shorter segments are left unchanged. Default 4.
    fn min_points(&self) -> usize {
        4
    }

    /// Whether [`prepare`](Self::prepare) may move the end points of an open curve (that are
    /// neither fixed nor clamped). The segments never move them; with `true` they keep where
    /// the preparation put them. Default `false`: the ends stay the data's.
    fn prepares_ends(&self) -> bool {
        false
    }

    /// Prepares the whole curve before the first pass (e.g. removes its noise): returns the
    /// new points, or `None` to leave them. `kept[i]` marks the points that must not move
    /// (fixed points, clamped ends, and, unless [`prepares_ends`](Self::prepares_ends), the
    /// ends of an open curve, which the segments never move either), `allowed[i]` how far point i may move (the tolerance band and radii, +∞
    /// without them). Called once per run, on the planar points in curve order (`closed`: the
    /// last joins the first). Default: `None`.
    fn prepare(
        &mut self,
        points: &[Vec2],
        closed: bool,
        kept: &[bool],
        allowed: &[f64],
    ) -> Result<Option<Vec<Vec2>>> {
        let _ = (points, closed, kept, allowed);
        Ok(None)
    }

    /// Fairs `y` over `x`.
    fn fair(&mut self, x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()>;
}

impl<F: FnMut(&[f64], &mut [f64], &[bool]) -> Result<()>> SegmentFairer for F {
    fn fair(&mut self, x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()> {
        self(x, y, fixed)
    }
}

/// Han §4.2.4: partition the planar curve into function segments, fair each in its frame,
/// move back, blend the overlaps; one such pass per step, `passes` steps in all.
///
/// Choices where the paper is silent (tested): the partition is recomputed at every pass
/// (moved points change the turning angles); all segments are faired from the same current
/// points (not one after another on already-blended points), so the result does not depend
/// on the order of segments; each segment's change is the displacement dy·(frame normal) and
/// the overlaps blend displacements with the linear ramp of [`blend()`]; the constraints
/// (tolerance band, radii, fixed points) are applied to the blended move in the original
/// frame by [`FairingState::move_point`]. End clamps beyond G0 are rejected (a function
/// fairer has no end-tangent condition in the original frame), as is any end clamp on a
/// closed curve.
///
/// Not in the paper: the blended moves pass the arbitrary-curve guard ([`CurveGuard`],
/// default [`CurveGuard::Local`]; [`CurveGuard::Off`] is §4.2.4 as printed), which refuses
/// moves that make the whole curve's own inflection and vibration counts worse (the segments'
/// fairer lowers the counts in its frame, not the curve's).
///
/// Cost per pass: O(n · overlap) plus the fairer's cost on every segment, plus the guard's
/// O(n · margin / chunk).
pub struct SegmentedFairing<F> {
    fairer: F,
    settings: PartitionSettings,
    passes: usize,
    done: usize,
    name: String,
    guard: CurveGuard,
}

impl<F: SegmentFairer> SegmentedFairing<F> {
    /// The default number of passes (the paper says "several times").
    pub const DEFAULT_PASSES: usize = 3;

    /// The default arbitrary-curve guard (its measurements: [`CurveGuard`]).
    pub const DEFAULT_CURVE_GUARD: CurveGuard = CurveGuard::Local;

    /// A driver around `fairer` with the default partition and passes.
    pub fn new(fairer: F) -> Self {
        let name = format!("segmented({})", fairer.name());
        Self {
            fairer,
            settings: PartitionSettings::default(),
            passes: Self::DEFAULT_PASSES,
            done: 0,
            name,
            guard: Self::DEFAULT_CURVE_GUARD,
        }
    }

    /// Sets the arbitrary-curve guard ([`CurveGuard::Off`]: Han §4.2.4 as printed).
    pub fn with_curve_guard(mut self, guard: CurveGuard) -> Self {
        self.guard = guard;
        self
    }

    /// Sets the partition settings.
    pub fn with_partition(mut self, settings: PartitionSettings) -> Self {
        self.settings = settings;
        self
    }

    /// Sets the number of passes (at least 1).
    pub fn with_passes(mut self, passes: usize) -> Self {
        self.passes = passes;
        self
    }

    /// The inner fairer.
    pub fn fairer(&self) -> &F {
        &self.fairer
    }
}

impl<F: SegmentFairer> FairingStrategy<2> for SegmentedFairing<F> {
    fn name(&self) -> &str {
        &self.name
    }

    fn init(&mut self, state: &mut FairingState<2>) -> Result<()> {
        self.settings.validate()?;
        if self.passes == 0 {
            return Err(Error::BadParameter {
                name: "passes",
                value: "0".into(),
                reason: "at least one pass",
            });
        }
        self.done = 0;
        let _ = state;
        Ok(())
    }

    fn step(&mut self, state: &mut FairingState<2>) -> Result<StepOutcome> {
        if self.done == 0 {
            let n = state.len();
            let closed = state.is_closed();
            let ends_kept = !closed && !self.fairer.prepares_ends();
            let kept: Vec<bool> = (0..n)
                .map(|i| !state.is_movable(i) || (ends_kept && (i == 0 || i + 1 == n)))
                .collect();
            let allowed: Vec<f64> = (0..n).map(|i| state.constraints().allowed_distance(i)).collect();
            if let Some(prepared) = self.fairer.prepare(state.points(), closed, &kept, &allowed)? {
                if prepared.len() != n {
                    return Err(curve_repr::Error::LengthMismatch {
                        what: "prepared points",
                        expected: n,
                        got: prepared.len(),
                    }
                    .into());
                }
                for (i, p) in prepared.into_iter().enumerate() {
                    if p != state.points()[i] {
                        state.move_point(i, p)?;
                    }
                }
            }
        }
        let points = state.points().to_vec();
        let segments = partition(&points, state.is_closed(), &self.settings)?;
        let mut displacements = Vec::with_capacity(segments.len());
        for segment in &segments {
            let local = segment.local_points(&points);
            let x: Vec<f64> = local.iter().map(|p| p.x).collect();
            let before: Vec<f64> = local.iter().map(|p| p.y).collect();
            let mut y = before.clone();
            if local.len() >= self.fairer.min_points() {
                let fixed: Vec<bool> = segment.indices.iter().map(|&i| !state.is_movable(i)).collect();
                self.fairer.fair(&x, &mut y, &fixed)?;
                if y.len() != before.len() {
                    return Err(curve_repr::Error::LengthMismatch {
                        what: "faired segment",
                        expected: before.len(),
                        got: y.len(),
                    }
                    .into());
                }
                if let Some(j) = y.iter().position(|v| !v.is_finite()) {
                    return Err(Error::NonFiniteMove {
                        index: segment.indices.get(j).copied().unwrap_or(0),
                    });
                }
            }
            displacements.push(
                y.iter()
                    .zip(&before)
                    .map(|(new, old)| segment.frame.displacement(new - old))
                    .collect::<Vec<Vec2>>(),
            );
        }
        let moves = blend(points.len(), &segments, &displacements)?;
        let moves = segment_moves(self.guard, &points, state.is_closed(), &segments, &moves);
        for (i, (p, d)) in points.iter().zip(&moves).enumerate() {
            if d.x != 0.0 || d.y != 0.0 {
                state.move_point(i, p + d)?;
            }
        }
        self.done += 1;
        if self.guard != CurveGuard::Off && !pass_keeps_counts(&points, state.points()) {
            // The pass raised a count of the whole curve: undo it; the next pass would
            // start from the same points, so the stage ends.
            for (i, p) in points.iter().enumerate() {
                if state.points()[i] != *p {
                    state.move_point(i, *p)?;
                }
            }
            self.done = self.passes;
        }
        Ok(if self.done >= self.passes {
            StepOutcome::done(None)
        } else {
            StepOutcome::running(None)
        })
    }
}
