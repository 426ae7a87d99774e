//! The constraints given on the command line and in a config file's `[constraints]`, checked
//! against the input: the catalogue's [`PlanConstraints`].
//!
//! `--fixed` and `--points` count from 0, the first data point; each index must name a point,
//! and no point may be both fixed and named bad. The command line wins over the config file.

use fairing::catalog::{ConfigConstraints, PlanConstraints};
use fairing::corners::Corners;
use fairing::EndClamp;

use crate::error::{Error, Result};

/// The constraints a front end was given (each `None` when not given, so that a config
/// file's `[constraints]` fills it in).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ConstraintRequest {
    /// Points that must not move (`--fixed`).
    pub fixed: Option<Vec<usize>>,
    /// Points known to be bad, which the method should move (`--points`).
    pub bad_points: Option<Vec<usize>>,
    /// The largest distance any point may move (`--tolerance`).
    pub tolerance: Option<f64>,
    /// The end condition kept (`--clamp-ends`).
    pub clamp_ends: Option<EndClamp>,
    /// The corners kept as G0 breaks (`--corners`; detected when not given).
    pub corners: Option<Corners>,
}

/// Reads the request, falling back on a config file's `[constraints]` for what it does not
/// give, and checks the indices against `count` points.
pub fn resolve(
    request: &ConstraintRequest,
    config: &ConfigConstraints,
    count: usize,
) -> Result<PlanConstraints> {
    let check = |option: &'static str, indices: &[usize]| -> Result<()> {
        match indices.iter().find(|i| **i >= count) {
            Some(i) => Err(Error::Argument {
                option,
                message: format!(
                    "index {i} is past the last point ({} points, indices 0 to {})",
                    count,
                    count.saturating_sub(1)
                ),
            }),
            None => Ok(()),
        }
    };
    let mut fixed = request
        .fixed
        .clone()
        .or_else(|| config.fixed.clone())
        .unwrap_or_default();
    let bad_points = request
        .bad_points
        .clone()
        .or_else(|| config.points.clone())
        .unwrap_or_default();
    check("--fixed", &fixed)?;
    check("--points", &bad_points)?;
    if let Some(i) = bad_points.iter().find(|i| fixed.contains(i)) {
        return Err(Error::Argument {
            option: "--points",
            message: format!("point {i} is also in --fixed"),
        });
    }
    fixed.sort_unstable();
    fixed.dedup();
    let clamp = request.clamp_ends.or(config.clamp_ends).unwrap_or(EndClamp::None);
    Ok(PlanConstraints {
        fixed,
        bad_points,
        tolerance: request.tolerance.or(config.tolerance),
        clamp,
        corners: request
            .corners
            .clone()
            .or_else(|| config.corners.clone())
            .unwrap_or_default(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_are_checked() {
        let none = ConfigConstraints::default();
        let request = ConstraintRequest {
            fixed: Some(vec![7, 2]),
            bad_points: Some(vec![4]),
            tolerance: Some(0.1),
            clamp_ends: None,
            corners: None,
        };
        let c = resolve(&request, &none, 8).unwrap();
        assert_eq!(c.fixed, vec![2, 7]);
        assert_eq!(c.bad_points, vec![4]);
        assert_eq!(c.tolerance, Some(0.1));
        let fixed = |f: Vec<usize>, p: Option<Vec<usize>>| ConstraintRequest {
            fixed: Some(f),
            bad_points: p,
            ..ConstraintRequest::default()
        };
        let e = resolve(&fixed(vec![8], None), &none, 8).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--fixed: index 8 is past the last point (8 points, indices 0 to 7)"
        );
        assert_eq!(e.exit_code(), 2);
        let e = resolve(&fixed(vec![3], Some(vec![3])), &none, 8).unwrap_err();
        assert!(e.to_string().contains("also in --fixed"));
    }

    #[test]
    fn the_request_wins_over_the_config() {
        let config = ConfigConstraints {
            fixed: Some(vec![1]),
            points: None,
            tolerance: Some(0.5),
            clamp_ends: Some(EndClamp::G2),
            corners: Some(Corners::None),
        };
        let request = ConstraintRequest {
            tolerance: Some(0.25),
            clamp_ends: Some(EndClamp::G0),
            ..ConstraintRequest::default()
        };
        let c = resolve(&request, &config, 8).unwrap();
        assert_eq!(c.fixed, vec![1]);
        assert_eq!(c.tolerance, Some(0.25));
        assert_eq!(c.clamp, EndClamp::G0);
        assert_eq!(
            c.corners,
            Corners::None,
            "the config's corners when the request has none"
        );
    }
}
