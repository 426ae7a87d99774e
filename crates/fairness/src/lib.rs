//! Fairness indicators and criteria: the second axis of the fairing framework, how
//! unfairness is measured.
//!
//! Everything here works through the [`Curve`](curve_repr::Curve) and
//! [`Surface`](curve_repr::Surface) traits of `curve-repr`, so it applies to every
//! representation (spline function, Hermite spline, NURBS, surfaces) and to any new one.
//!
//! - [`indicator`]: the traits [`LocalIndicator`] (a value per point) and [`Criterion`] (one
//!   number), object safe, so that strategies and optimisers take any of them.
//! - [`sign`]: sign-change counting with docs/CONTRACT.md's drop rule (inflections, vibrations).
//! - [`curvature`]: κ and dκ/ds, signed in 2D and unsigned in 3D.
//! - [`quadrature`]: Gauss–Legendre and adaptive Gauss–Kronrod integration.
//! - [`energy`]: Nowacki's E1, E2, E3, Ek, Ek′.
//! - [`jumps`]: third-derivative jumps (Zhang–Cheng Eq. 17), curvature-slope jumps
//!   (Eq. 16, Sapidis–Farin), curvature vibrations (Han's e from (s, κ)).
//! - [`surface`]: the surface indicator z_ij (Zhang–Cheng Eq. 26), thin-plate and network
//!   strain energies.
//! - [`highlight`]: Beier–Chen highlight lines of a surface (the light setup, the highlight
//!   function, its level lines); drawing them is the caller's.
//! - [`displacement`]: Han's S_d and M_d.
//! - [`report`]: the serde blocks of the `fair` command's report.
//! - [`xc`]: Han's x–c polyline of a spline function (c_i, e_i, inflections, vibrations, Eq. 18).
//! - [`summary`]: the report's block of each kind (function, parametric, surface), per docs/CONTRACT.md.
//!
//! No input makes this crate panic or return NaN: failures are [`Error`]s.

pub mod curvature;
pub mod displacement;
pub mod energy;
pub mod error;
pub mod fixed_rule;
pub mod highlight;
pub mod indicator;
pub mod jumps;
pub mod quadrature;
pub mod report;
pub mod sign;
pub mod summary;
pub mod surface;
pub mod xc;

#[cfg(test)]
mod test_curves;

pub use curvature::CurvatureForm;
pub use displacement::Displacement;
pub use energy::{
    Ek, EkPrime, Energies, EnergyAccuracy, EnergyFlags, EnergyName, MeasuredEnergies, PieceQuadrature, E1,
    E2, E3,
};
pub use error::{Error, Result};
pub use indicator::{Criterion, FnCriterion, LocalIndicator};
pub use quadrature::{Adaptive, Estimate, GaussLegendre};
pub use report::FairnessSummary;
pub use sign::{sign_change_positions, sign_changes};
pub use xc::XcPolyline;
