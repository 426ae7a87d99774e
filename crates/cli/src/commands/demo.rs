//! `fair demo`: every method on the embedded data sets, outputs in one directory.
//!
//! For each data set it writes the data (`data/`), a plot of the input, and for each method
//! of its kind the faired points, the report and the plot, through the same code as
//! `fair curve` / `fair surface`. Every run is attempted; a summary table is printed; the
//! command fails with the first error when any run failed.
//!
//! The interactive methods need `--points`; the demo will name the worst z_i there once the
//! indicators are wired (TODO for the lead: [`bad_points`]).

use crate::args::{DemoArgs, FairArgs, KindArg};
use crate::commands::{curve, surface};
use crate::error::{Error, Result};
use crate::input::{self, Source};
use crate::kind;
use crate::plots::{CurvePlot, SurfacePlot};
use crate::registry::{MethodKind, METHODS};

/// One embedded data set.
#[derive(Debug, Clone, Copy)]
pub struct Dataset {
    /// Short name used in file names.
    pub name: &'static str,
    /// What it is.
    pub about: &'static str,
    /// Curve or surface.
    pub kind: MethodKind,
    /// The CSV text.
    pub text: &'static str,
}

macro_rules! data {
    ($path:literal) => {
        include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/", $path))
    };
}

/// The embedded data sets (see `data/README.md` for provenance).
pub const DATASETS: &[Dataset] = &[
    Dataset {
        name: "naca2412-upper",
        about: "NACA 2412 upper surface, a clean analytic control",
        kind: MethodKind::Curve,
        text: data!("airfoil_naca2412/naca2412_upper.csv"),
    },
    Dataset {
        name: "ua2-180-upper",
        about: "UA(2)-180 upper surface, y oscillating by 3e-4",
        kind: MethodKind::Curve,
        text: data!("airfoil_ua2-180/ua2-180_upper.csv"),
    },
    Dataset {
        name: "r140-upper",
        about: "R140 upper surface, hand-digitised, the roughest",
        kind: MethodKind::Curve,
        text: data!("airfoil_r140/r140_upper.csv"),
    },
    Dataset {
        name: "gunnerus-wl03",
        about: "R/V Gunnerus waterline 3, flat-side ripple",
        kind: MethodKind::Curve,
        text: data!("hull_gunnerus/waterlines/wl_03.csv"),
    },
    Dataset {
        name: "block-island-sheer",
        about: "Block Island boat sheer line in 3D",
        kind: MethodKind::Curve,
        text: data!("hull_block_island_boat/sheer_3d.csv"),
    },
    Dataset {
        name: "teapot-body",
        about: "Utah teapot body control net, 13 x 13",
        kind: MethodKind::Surface,
        text: data!("surface_utah_teapot/teapot_body_control_net.csv"),
    },
];

/// SEAM: the bad points to name for the interactive methods (the largest z_i), once the
/// indicators are wired; `None` leaves `--points` unset.
pub fn bad_points(_dataset: &Dataset, _method: &str) -> Option<crate::args::IndexList> {
    None
}

fn run_args(input: String, method: &str, out: &std::path::Path, stem: &str, dataset: &Dataset) -> FairArgs {
    FairArgs {
        input,
        method: Some(method.to_string()),
        kind: KindArg::Auto,
        config: None,
        settings: Vec::new(),
        fixed: None,
        points: bad_points(dataset, method),
        tolerance: None,
        clamp_ends: None,
        output: Some(out.join(format!("{stem}.csv")).display().to_string()),
        report: Some(out.join(format!("{stem}.json"))),
        plot: Some(out.join(format!("{stem}.svg"))),
        quiet: true,
    }
}

/// Runs `fair demo`.
pub fn run(args: &DemoArgs) -> Result<()> {
    let data_dir = args.out.join("data");
    std::fs::create_dir_all(&data_dir).map_err(|e| Error::Write {
        path: data_dir.display().to_string(),
        reason: crate::input::io_reason(&e),
    })?;
    let mut lines = vec![format!("{:22} {:18} result", "data set", "method")];
    let mut first_error: Option<Error> = None;
    let mut failures = 0;
    let mut runs = 0;
    for dataset in DATASETS {
        let data_path = data_dir.join(format!("{}.csv", dataset.name));
        crate::output::write_text(&data_path.display().to_string(), dataset.text)?;
        let source = Source::from_text(&data_path.display().to_string(), dataset.text);
        let input_plot = args.out.join(format!("{}-input.svg", dataset.name));
        match dataset.kind {
            MethodKind::Curve => {
                let input = input::parse_curve(&source)?;
                let function = kind::detect(&input.points) == kind::CurveKind::Function;
                CurvePlot::of_input(dataset.about, &input.points, function)
                    .figure()
                    .write(&input_plot)?;
            }
            MethodKind::Surface => {
                let input = input::grid::parse(&source)?;
                let plot = SurfacePlot {
                    title: dataset.about.into(),
                    input: Some(input.grid),
                    ..SurfacePlot::default()
                };
                plot.figure().write(&input_plot)?;
            }
        }
        for method in METHODS.iter().filter(|m| m.kind == dataset.kind) {
            runs += 1;
            let stem = format!("{}-{}", dataset.name, method.name);
            let run_args = run_args(
                data_path.display().to_string(),
                method.name,
                &args.out,
                &stem,
                dataset,
            );
            let result = match dataset.kind {
                MethodKind::Curve => curve::run(&run_args),
                MethodKind::Surface => surface::run(&run_args),
            };
            let status = match result {
                Ok(()) => "ok".to_string(),
                Err(e) => {
                    failures += 1;
                    let text = e.one_line();
                    first_error.get_or_insert(e);
                    text
                }
            };
            lines.push(format!("{:22} {:18} {status}", dataset.name, method.name));
        }
    }
    lines.push(format!(
        "{} of {runs} runs succeeded; outputs in {}",
        runs - failures,
        args.out.display()
    ));
    if !args.quiet {
        crate::output::write_text("-", &(lines.join("\n") + "\n"))?;
    }
    match first_error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn embedded_data_parses() {
        for d in DATASETS {
            let source = Source::from_text(&format!("{}.csv", d.name), d.text);
            match d.kind {
                MethodKind::Curve => assert!(input::parse_curve(&source).unwrap().len() >= 3, "{}", d.name),
                MethodKind::Surface => assert!(input::grid::parse(&source).unwrap().grid.rows >= 3),
            }
        }
    }
}
