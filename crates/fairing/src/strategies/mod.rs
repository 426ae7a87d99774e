//! Concrete fairing strategies.

pub mod batten;
pub mod strain_energy;

pub use batten::{Batten, BattenSettings, PositionUpdate, Tangents};
pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
pub mod smoothing_spline;

pub use smoothing_spline::{
    fit_parametric, CurveDomain, SmoothingRule, SmoothingSettings, SmoothingSpline, SmoothingSplineFairing,
};
pub mod sapidis_farin;

pub use sapidis_farin::{KnotStep, SapidisFarin, SapidisFarinSettings, SapidisFarinStop};
