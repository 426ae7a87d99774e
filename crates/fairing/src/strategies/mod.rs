//! Concrete fairing strategies, one module each.
//!
//! - [`strain_energy`]: Zhang–Cheng strain-energy point replacement for parametric curves
//!   (Kjellander and Poliakoff as presets).
//! - [`batten`]: Okada's numerical batten of Ferguson segments.
//! - [`smoothing_spline`]: the smoothing-spline baseline (the papers' MST), csaps convention.
//! - [`sapidis_farin`]: Sapidis–Farin knot removal and reinsertion on the cubic B-spline.
//! - [`surface`]: Zhang–Cheng bicubic surface fairing (Kjellander's surface method as preset).
//!
//! Han's two-phase method lives in [`crate::two_phase`].

pub mod batten;
pub mod sapidis_farin;
pub mod smoothing_spline;
pub mod strain_energy;
pub mod surface;

pub use batten::{Batten, BattenSettings, PositionUpdate, Tangents};
pub use sapidis_farin::{
    KnotStep, MoveBound, MoveRule, SapidisFarin, SapidisFarinSettings, SapidisFarinStop,
};
pub use smoothing_spline::{
    fit_parametric, CurveDomain, SmoothingRule, SmoothingSettings, SmoothingSpline, SmoothingSplineFairing,
};
pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
pub use surface::{
    Objective, SurfaceFairing, SurfaceFairingResult, SurfaceFairingSettings, SurfaceMode, SurfaceStep,
};
