//! The constraints given on the command line and in a config file's `[constraints]`, checked
//! against the input: the catalogue's [`PlanConstraints`].
//!
//! `--fixed` and `--points` count from 0, the first data point; each index must name a point,
//! and no point may be both fixed and named bad. The command line wins over the config file.

use fairing::catalog::{ConfigConstraints, PlanConstraints};
use fairing::EndClamp;

use crate::args::{ClampEnds, FairArgs};
use crate::error::{Error, Result};

/// The library's end clamp for `--clamp-ends`.
pub fn end_clamp(clamp: Option<ClampEnds>) -> EndClamp {
    match clamp {
        None => EndClamp::None,
        Some(ClampEnds::G0) => EndClamp::G0,
        Some(ClampEnds::G1) => EndClamp::G1,
        Some(ClampEnds::G2) => EndClamp::G2,
    }
}

/// Reads the options, falling back on a config file's `[constraints]` for those not given on
/// the command line, and checks them against `count` points.
pub fn resolve(args: &FairArgs, config: &ConfigConstraints, count: usize) -> Result<PlanConstraints> {
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
    let mut fixed = args
        .fixed
        .as_ref()
        .map(|l| l.0.clone())
        .or_else(|| config.fixed.clone())
        .unwrap_or_default();
    let bad_points = args
        .points
        .as_ref()
        .map(|l| l.0.clone())
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
    let clamp = match args.clamp_ends {
        Some(_) => end_clamp(args.clamp_ends),
        None => config.clamp_ends.unwrap_or(EndClamp::None),
    };
    Ok(PlanConstraints {
        fixed,
        bad_points,
        tolerance: args.tolerance.or(config.tolerance),
        clamp,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::args::{Cli, Command};
    use clap::Parser;

    fn args(extra: &[&str]) -> FairArgs {
        let cli = Cli::try_parse_from(["fair", "curve", "in.csv"].iter().chain(extra).copied()).unwrap();
        match cli.command {
            Command::Curve(a) => a,
            _ => unreachable!(),
        }
    }

    #[test]
    fn indices_are_checked() {
        let none = ConfigConstraints::default();
        let c = resolve(
            &args(&["--fixed", "7,2", "--points", "4", "--tolerance", "0.1"]),
            &none,
            8,
        )
        .unwrap();
        assert_eq!(c.fixed, vec![2, 7]);
        assert_eq!(c.bad_points, vec![4]);
        assert_eq!(c.tolerance, Some(0.1));
        let e = resolve(&args(&["--fixed", "8"]), &none, 8).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--fixed: index 8 is past the last point (8 points, indices 0 to 7)"
        );
        assert_eq!(e.exit_code(), 2);
        let e = resolve(&args(&["--fixed", "3", "--points", "3"]), &none, 8).unwrap_err();
        assert!(e.to_string().contains("also in --fixed"));
    }

    #[test]
    fn the_command_line_wins_over_the_config() {
        let config = ConfigConstraints {
            fixed: Some(vec![1]),
            points: None,
            tolerance: Some(0.5),
            clamp_ends: Some(EndClamp::G2),
        };
        let c = resolve(&args(&["--tolerance", "0.25", "--clamp-ends", "g0"]), &config, 8).unwrap();
        assert_eq!(c.fixed, vec![1]);
        assert_eq!(c.tolerance, Some(0.25));
        assert_eq!(c.clamp, EndClamp::G0);
    }
}
