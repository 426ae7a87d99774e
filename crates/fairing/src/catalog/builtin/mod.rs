//! The built-in methods, one module each, and [`register`], which puts them, their presets,
//! the built-in criteria and the built-in indicators into a catalogue
//! ([`Catalog::builtin`](super::Catalog::builtin)).
//!
//! Each method is a [`CurveMethod`](super::CurveMethod) or
//! [`SurfaceMethod`](super::SurfaceMethod) whose settings are the strategy's own settings
//! struct: what it refuses (kinds, dimensions, end clamps, bad points) is said by its
//! `check`, what its report holds by its `run`.

mod batten;
mod jump_lsq;
pub(in crate::catalog) use jump_lsq::repeats_first;
mod nurbs_weights;
mod sapidis_farin;
mod smoothing_spline;
mod strain_energy;
mod surface;
mod surface_jump_lsq;
mod surface_smoothing;
mod two_phase;

pub use batten::BattenMethod;
pub use jump_lsq::JumpLsqMethod;
pub use nurbs_weights::NurbsWeightMethod;
pub use sapidis_farin::SapidisFarinMethod;
pub use smoothing_spline::SmoothingSplineMethod;
pub use strain_energy::StrainEnergyMethod;
pub use surface::SurfaceFairingMethod;
pub use surface_jump_lsq::SurfaceJumpLsqMethod;
pub use surface_smoothing::SurfaceSmoothingMethod;
pub use two_phase::{TwoPhaseCurveSettings, TwoPhaseMethod};

use curve_repr::{HermiteSpline, Vector};
use serde_json::json;

use super::{
    builtin_criteria, builtin_indicators, Catalog, CurveJob, MethodInfo, MethodKind, SharedIndicator,
};
use crate::{Error, Result};

/// Registers every built-in method, preset, criterion and indicator in `catalog`.
pub fn register(catalog: &mut Catalog) {
    for criterion in builtin_criteria() {
        catalog.register_criterion(criterion);
    }
    for indicator in builtin_indicators() {
        catalog.register_indicator(indicator);
    }
    catalog.register_curve(
        MethodInfo::new(
            "two-phase",
            "coarse phase removes curvature vibrations, fine phase removes inflections",
        )
        .with_paper("Han et al., two-phase fairing of spline functions"),
        TwoPhaseMethod,
    );
    catalog.register_curve(
        MethodInfo::new(
            "strain-energy",
            "replaces one or two bad points to minimise the strain energy (--points: interactive, else automatic)",
        )
        .with_paper("Zhang & Cheng, strain-energy point replacement"),
        StrainEnergyMethod,
    );
    let presets = [
        (
            "kjellander",
            "moves a bad point to remove the third-derivative jump",
            "Kjellander (as a preset of Zhang & Cheng)",
            "uniform",
        ),
        (
            "poliakoff",
            "moves a bad point to reduce the local strain energy",
            "Poliakoff (as a preset of Zhang & Cheng)",
            "chord-length",
        ),
    ];
    for (name, summary, paper, parametrization) in presets {
        let _ = catalog.register_preset(
            MethodKind::Curve,
            "strain-energy",
            MethodInfo::new(name, summary).with_paper(paper),
            json!({ "parametrization": parametrization }),
            &["parametrization"],
        );
    }
    catalog.register_curve(
        MethodInfo::new(
            "batten",
            "a numerical batten through the points within adjustable ranges",
        )
        .with_paper("Okada, batten fairing"),
        BattenMethod,
    );
    catalog.register_curve(
        MethodInfo::new(
            "nurbs-weights",
            "changes weights (not points) by Nelder-Mead on a criterion",
        )
        .with_paper("Nowacki et al., fairing NURBS by weights"),
        NurbsWeightMethod,
    );
    catalog.register_curve(
        MethodInfo::new(
            "smoothing-spline",
            "least-squares smoothing spline, a baseline to compare against",
        )
        .with_paper("baseline: smoothing spline (the papers' MST)"),
        SmoothingSplineMethod,
    );
    catalog.register_curve(
        MethodInfo::new(
            "jump-lsq",
            "least squares on the points with a penalty on their spline's third-derivative jump \
             differences, O(n), the weight chosen from the data's own noise",
        )
        .with_paper("Zhang & Cheng Eq. 17 / Han et al.'s e_i as a global objective (this project)"),
        JumpLsqMethod,
    );
    catalog.register_curve(
        MethodInfo::new(
            "sapidis-farin",
            "removes curvature-slope jumps knot by knot, a baseline",
        )
        .with_paper("baseline: Sapidis & Farin knot removal and reinsertion"),
        SapidisFarinMethod,
    );
    catalog.register_surface(
        MethodInfo::new(
            "zhang-cheng",
            "automatic: boundary curves, then every interior point per step, largest z_ij first, in \
             restraining spheres; with --points: the named points in pairs and 2x2 blocks (step 1.3)",
        )
        .with_paper("Zhang & Cheng §4, bicubic surface fairing"),
        SurfaceFairingMethod,
    );
    let _ = catalog.register_preset(
        MethodKind::Surface,
        "zhang-cheng",
        MethodInfo::new(
            "kjellander",
            "one point per step: the interior point of largest z_ij moved to zero its jumps (uniform \
             knots), in its restraining sphere",
        )
        .with_paper("Kjellander (as a preset of Zhang & Cheng §4)"),
        json!({
            "parametrization": "uniform",
            "boundary": false,
            "one-point-per-step": true,
            "max-steps": 100_000,
        }),
        &["one-point-per-step"],
    );
    catalog.register_surface(
        MethodInfo::new(
            "smoothing-spline",
            "tensor-product cubic smoothing spline per coordinate over the grid's parameters \
             (periodic across seams), a baseline; --set displacement=S_d matches a fairing's S_d",
        )
        .with_paper("baseline: csaps's NdGridCubicSmoothingSpline"),
        SurfaceSmoothingMethod,
    );
    catalog.register_surface(
        MethodInfo::new(
            "jump-lsq",
            "least squares on the nodes with a penalty on the bicubic surface's third-derivative \
             jumps across its knot lines in both directions, one weight per direction, both by GCV",
        )
        .with_paper(
            "Zhang & Cheng Eq. 17/26 as a global objective, tensor form of the curve jump-lsq (this project)",
        ),
        SurfaceJumpLsqMethod,
    );
}

/// The indicator called `name` for curves of dimension `D`, or a [`Error::BadValue`] of the
/// parameter `indicator` listing the registered ones.
pub(crate) fn indicator_for<const D: usize>(job: &CurveJob, name: &str) -> Result<SharedIndicator<D>> {
    let entry = job.catalog.indicator(name, "indicator").map_err(|e| match e {
        Error::UnknownName {
            what, name, known, ..
        } => Error::BadValue {
            name: "indicator".into(),
            message: format!("`{name}` is not {what} (known: {known})"),
        },
        other => other,
    })?;
    entry.for_dimension::<D>().ok_or_else(|| Error::BadValue {
        name: "indicator".into(),
        message: format!("`{name}` has no implementation for {D}D curves"),
    })
}

/// The report's `curve` for a parametric cubic Hermite spline: knots, points and tangents.
pub(crate) fn hermite_json<const D: usize>(
    spline: &HermiteSpline<D>,
    parametrization: &str,
) -> serde_json::Value {
    let rows = |v: &[Vector<D>]| {
        v.iter()
            .map(|p| p.iter().copied().collect::<Vec<f64>>())
            .collect::<Vec<_>>()
    };
    json!({
        "type": "hermite",
        "degree": 3,
        "end_condition": "natural",
        "parametrization": parametrization,
        "knots": spline.knots(),
        "points": rows(spline.points()),
        "tangents": rows(spline.tangents()),
    })
}
