//! The constraints given on the command line, checked against the input.
//!
//! `--fixed` and `--points` count from 0, the first data point; each index must name a point,
//! and no point may be both fixed and named bad. The fairing crate turns these into its own
//! constraint types.

use crate::args::{ClampEnds, FairArgs};
use crate::config::ConfigConstraints;
use crate::error::{Error, Result};

/// What must hold while fairing, as given by the user.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Constraints {
    /// Points that must not move (sorted, from 0).
    pub fixed: Vec<usize>,
    /// The bad points for the interactive methods (in the order given, from 0).
    pub bad_points: Vec<usize>,
    /// No point moves farther than this.
    pub tolerance: Option<f64>,
    /// What is kept at the ends.
    pub clamp_ends: Option<ClampEnds>,
}

impl Constraints {
    /// Reads the options and checks them against `count` points.
    pub fn from_args(args: &FairArgs, count: usize) -> Result<Constraints> {
        Constraints::from_args_and_config(args, &ConfigConstraints::default(), count)
    }

    /// Reads the options, falling back on a config file's `[constraints]` for those not given
    /// on the command line, and checks them against `count` points.
    pub fn from_args_and_config(
        args: &FairArgs,
        config: &ConfigConstraints,
        count: usize,
    ) -> Result<Constraints> {
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
        Ok(Constraints {
            fixed,
            bad_points,
            tolerance: args.tolerance.or(config.tolerance),
            clamp_ends: args.clamp_ends.or(config.clamp_ends),
        })
    }
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
        let c = Constraints::from_args(
            &args(&["--fixed", "7,2", "--points", "4", "--tolerance", "0.1"]),
            8,
        )
        .unwrap();
        assert_eq!(c.fixed, vec![2, 7]);
        assert_eq!(c.bad_points, vec![4]);
        assert_eq!(c.tolerance, Some(0.1));
        let e = Constraints::from_args(&args(&["--fixed", "8"]), 8).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--fixed: index 8 is past the last point (8 points, indices 0 to 7)"
        );
        assert_eq!(e.exit_code(), 2);
        let e = Constraints::from_args(&args(&["--fixed", "3", "--points", "3"]), 8).unwrap_err();
        assert!(e.to_string().contains("also in --fixed"));
    }
}
