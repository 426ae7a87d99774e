//! Concrete fairing strategies.

pub mod strain_energy;

pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
