//! Concrete fairing strategies.

pub mod strain_energy;

pub use strain_energy::{Mode, Replacement, StrainEnergy, StrainEnergySettings};
pub mod surface;

pub use surface::{
    Objective, SurfaceFairing, SurfaceFairingResult, SurfaceFairingSettings, SurfaceMode, SurfaceStep,
};
