//! Concrete fairing strategies.

pub mod batten;
pub mod strain_energy;

pub use batten::{Batten, BattenSettings, PositionUpdate, Tangents};
pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
