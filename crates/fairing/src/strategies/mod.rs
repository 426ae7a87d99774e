//! Concrete fairing strategies, one module each.
//!
//! - [`strain_energy`]: Zhang–Cheng strain-energy point replacement for parametric curves
//!   (Kjellander and Poliakoff as presets).
//! - [`batten`]: Okada's numerical batten of Ferguson segments.
//! - [`smoothing_spline`]: the smoothing-spline baseline (the papers' MST), csaps convention.
//! - [`jump_lsq`]: least squares on the points with a penalty on the roughness of their
//!   spline's third-derivative jumps, O(n), λ chosen automatically.
//! - [`sapidis_farin`]: Sapidis–Farin knot removal and reinsertion on the cubic B-spline.
//! - [`surface`]: Zhang–Cheng bicubic surface fairing (Kjellander's surface method as preset).
//! - [`surface_jump_lsq`]: least squares on a net's nodes with a penalty on its bicubic surface's
//!   third-derivative jumps in both directions, λ by GCV (surface `jump-lsq`).
//! - [`surface_smoothing`]: the surface baseline, a tensor-product cubic smoothing spline (csaps's `NdGridCubicSmoothingSpline`, periodic across seams).
//!
//! Han's two-phase method lives in [`crate::two_phase`].

pub mod batten;
pub mod jump_lsq;
pub mod sapidis_farin;
pub mod smoothing_spline;
pub mod strain_energy;
pub mod surface;
pub mod surface_jump_lsq;
pub mod surface_smoothing;
mod tournament;

pub use batten::{Batten, BattenSettings, PositionUpdate, Tangents};
pub use jump_lsq::{
    CurveEnds, FunctionEnds, JumpLsq, JumpLsqReport, JumpLsqSettings, LambdaRule, AUTO_NOISE_FACTOR,
    EXPONENT_DEFAULT, ORDER_AUTO_MAX,
};
pub use sapidis_farin::{
    KnotStep, MoveBound, MoveRule, SapidisFarin, SapidisFarinSettings, SapidisFarinStop,
};
pub use smoothing_spline::{
    fit_parametric, CurveDomain, SmoothingRule, SmoothingSettings, SmoothingSpline, SmoothingSplineFairing,
};
pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
pub use surface::{
    Closure, Objective, RefusalRule, Region, SurfaceFairing, SurfaceFairingResult, SurfaceFairingSettings,
    SurfaceMode, SurfaceStep, SweepOrder,
};
pub use surface_jump_lsq::{
    Continuity, Join, JoinEdge, JoinMeasure, JoinReport, SurfaceJumpLsq, SurfaceJumpLsqResult,
    SurfaceJumpLsqSettings,
};
pub use surface_smoothing::{
    smooth_grid, SurfaceSmoothing, SurfaceSmoothingResult, SurfaceSmoothingSettings,
};
