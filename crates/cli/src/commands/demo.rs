//! `fair demo`: every method on the embedded data sets, outputs in one directory.
//!
//! For each data set it writes the data (`data/`), the `fair inspect` report and plot
//! (`<name>-inspect.json`, `.svg`), and for each method of its kind the faired points, the
//! report and the plot, through the same code as `fair curve` / `fair surface`. It prints
//! the measures in the papers' style (n, inflections, vibrations, e_s, max_z), then one row
//! per run in the style of Han et al.'s Tables 1–2: inflections and vibrations before → after,
//! S_d, M_d, the energy before → after, the largest jump after and the time. Methods not available yet are listed as such; the command fails with the
//! first other error, after every run was attempted.
//!
//! Every method runs in its automatic mode with its default parameters (no `--points`).
//!
//! Three runs also write their faired result as a CAD file ([`CAD_FILES`]: one IGES, one
//! STEP, one DXF), through the same code as `fair curve -o FILE.igs`, beside the SVGs.

use fairing::catalog::{Catalog, MethodKind};

use crate::args::{DemoArgs, FairArgs, KindArg};
use crate::commands::{curve, inspect, surface, write_results};
use crate::input::Source;
use fair_door::cad::CadTarget;
use fair_door::error::{Error, Result};
use fair_door::report::Report;

pub(crate) use crate::input::embedded::DATASETS;

fn run_args(input: String, method: &str, out: &std::path::Path, stem: &str) -> FairArgs {
    FairArgs {
        input,
        method: Some(method.to_string()),
        kind: KindArg::Auto,
        columns: None,
        config: None,
        settings: Vec::new(),
        fixed: None,
        points: None,
        tolerance: None,
        clamp_ends: None,
        corners: None,
        joins: Vec::new(),
        output: Some(out.join(format!("{stem}.csv")).display().to_string()),
        report: Some(out.join(format!("{stem}.json"))),
        plot: Some(out.join(format!("{stem}.svg"))),
        quiet: true,
        print_config: false,
        batch: false,
        cad: Default::default(),
    }
}

fn count(value: Option<usize>) -> String {
    value.map_or("-".to_string(), |v| v.to_string())
}

/// The runs whose faired result the demo also writes as a CAD file `<data set>-<method>.<ext>`:
/// a hand-digitised airfoil faired by two-phase (IGES), the teapot body by Zhang–Cheng
/// (STEP, a bicubic B-spline surface) and a ship's waterline by strain-energy (DXF).
pub(crate) const CAD_FILES: [(&str, &str, cad::Format); 3] = [
    ("r140-upper", "two-phase", cad::Format::Iges),
    ("teapot-body", "zhang-cheng", cad::Format::Step),
    ("gunnerus-wl03", "strain-energy", cad::Format::Dxf),
];

/// The CAD file a demo run writes, if any: `<stem>.<ext>` beside its SVG.
fn cad_target(dataset: &str, method: &str, out: &std::path::Path, stem: &str) -> Option<CadTarget> {
    CAD_FILES
        .iter()
        .find(|(d, m, _)| *d == dataset && *m == method)
        .map(|&(_, _, format)| CadTarget {
            format,
            path: out
                .join(format!("{stem}.{}", format.extension()))
                .display()
                .to_string(),
            settings: cad::CadSettings::default(),
        })
}

/// Fairs one embedded curve as `fair curve` would (and writes its CAD file when `cad` says)
/// and returns its report.
fn fair_curve(catalog: &Catalog, args: &FairArgs, cad: Option<&CadTarget>, name: &str) -> Result<Report> {
    let input = crate::input::read_curve(&args.input)?;
    let mut faired = curve::process(catalog, &input, args, None)?;
    if let Some(target) = cad {
        let made =
            fair_door::cad::export_curve(target, &faired.report.curve, &faired.points, faired.kind, name)?;
        faired.report.extras.insert("cad".into(), made.summary);
        crate::output::write_text(&target.path, &made.text)?;
    }
    write_results(args, &faired.report, &faired.points_text, || faired.plot.figure())?;
    Ok(faired.report)
}

/// Fairs one embedded surface as `fair surface` would (and writes its CAD file when `cad`
/// says) and returns its report.
fn fair_surface(catalog: &Catalog, args: &FairArgs, cad: Option<&CadTarget>, name: &str) -> Result<Report> {
    let input = crate::input::read_surface(&args.input)?;
    let mut faired = surface::process(catalog, &input, args, None)?;
    if let Some(target) = cad {
        let made = fair_door::cad::export_surface(target, &faired.report.curve, &faired.grid, name)?;
        faired.report.extras.insert("cad".into(), made.summary);
        crate::output::write_text(&target.path, &made.text)?;
    }
    write_results(args, &faired.report, &faired.grid_text, || faired.plot.figure())?;
    Ok(faired.report)
}

/// `b→a` for a count before and after.
fn change(before: Option<usize>, after: Option<usize>) -> String {
    format!("{}→{}", count(before), count(after))
}

/// The comparison columns of one run, in the style of Han et al.'s Tables 1–2. The energy is
/// E_s of the spline through the points, except for methods that report the criterion they
/// optimise on their own representation (nurbs-weights: the points, hence E_s, do not change),
/// whose criterion is shown; the row names which (`(e_s)`, `(ek)`, ...), since the column
/// holds either.
fn row(report: &Report) -> String {
    let (b, a) = (&report.before, &report.after);
    let number = |key: &str| report.extras.get(key).and_then(serde_json::Value::as_f64);
    let (before, after, label) = match (number("criterion_before"), number("criterion_after")) {
        (Some(before), Some(after)) => {
            let name = report
                .extras
                .get("criterion")
                .and_then(|v| v.as_str())
                .unwrap_or("criterion");
            (before, after, format!(" ({name})"))
        }
        _ => (b.e_s, a.e_s, " (e_s)".to_string()),
    };
    format!(
        "{:>9} {:>9} {:>10.3e} {:>10.3e} {:>11.4e}→{:<11.4e} {:>10.3e} {:>9.1}{label}",
        change(b.inflections, a.inflections),
        change(b.vibrations, a.vibrations),
        report.s_d,
        report.m_d,
        before,
        after,
        a.max_z,
        report.elapsed_ms
    )
}

/// Runs `fair demo`.
///
/// First `fair inspect` on every data set (report `<name>-inspect.json`, plot
/// `<name>-inspect.svg`) and a table of the measures in the papers' style; then every method
/// of the data set's kind. A method that is not available yet is listed as such and is not
/// a failure; any other error of a run makes the command fail (after every run was tried).
pub(crate) fn run(catalog: &Catalog, args: &DemoArgs) -> Result<()> {
    let data_dir = args.out.join("data");
    std::fs::create_dir_all(&data_dir).map_err(|e| Error::Write {
        path: data_dir.display().to_string(),
        reason: fair_door::error::io_reason(&e),
    })?;
    let mut measures = vec![format!(
        "{:20} {:10} {:>4} {:>5} {:>5} {:>12} {:>12}",
        "data set", "kind", "n", "infl", "vib", "e_s", "max_z"
    )];
    let mut lines = vec![format!(
        "{:20} {:18} {:>9} {:>9} {:>10} {:>10} {:>23} {:>10} {:>9}",
        "data set", "method", "infl", "vib", "S_d", "M_d", "energy before -> after", "max_z", "ms"
    )];
    let mut first_error: Option<Error> = None;
    let (mut failures, mut unavailable, mut runs) = (0, 0, 0);
    for dataset in DATASETS {
        let data_path = data_dir.join(format!("{}.csv", dataset.name));
        crate::output::write_text(&data_path.display().to_string(), dataset.text)?;
        let source = Source::from_text(&data_path.display().to_string(), dataset.text);
        let stem = args.out.join(format!("{}-inspect", dataset.name));
        let surface = dataset.kind == MethodKind::Surface;
        let report = inspect::inspect(
            catalog,
            &source,
            KindArg::Auto,
            surface,
            Some(&stem.with_extension("svg")),
        )?;
        crate::output::write_text(
            &stem.with_extension("json").display().to_string(),
            &report.to_json()?,
        )?;
        let m = &report.before;
        measures.push(format!(
            "{:20} {:10} {:>4} {:>5} {:>5} {:>12.4e} {:>12.4e}",
            dataset.name,
            report.kind.name(),
            report.n,
            count(m.inflections),
            count(m.vibrations),
            m.e_s,
            m.max_z
        ));
        let mut not_available = Vec::new();
        for method in catalog.methods(dataset.kind) {
            runs += 1;
            let name = method.name();
            let stem = format!("{}-{name}", dataset.name);
            let run_args = run_args(data_path.display().to_string(), name, &args.out, &stem);
            let cad = cad_target(dataset.name, name, &args.out, &stem);
            let result = match dataset.kind {
                MethodKind::Curve => fair_curve(catalog, &run_args, cad.as_ref(), dataset.name),
                MethodKind::Surface => fair_surface(catalog, &run_args, cad.as_ref(), dataset.name),
            };
            let status = match result {
                Ok(report) => row(&report),
                Err(Error::NotAvailable { .. }) => {
                    not_available.push(name.to_owned());
                    continue;
                }
                Err(Error::NotApplicable { message, .. }) => {
                    runs -= 1;
                    lines.push(format!(
                        "{:20} {:18} does not apply: {message}",
                        dataset.name, name
                    ));
                    continue;
                }
                Err(e) => {
                    failures += 1;
                    let text = e.one_line();
                    first_error.get_or_insert(e);
                    text
                }
            };
            lines.push(format!("{:20} {:18} {status}", dataset.name, name));
        }
        if !not_available.is_empty() {
            unavailable += not_available.len();
            lines.push(format!(
                "{:20} {:18} {}",
                dataset.name,
                "not available yet:",
                not_available.join(", ")
            ));
        }
    }
    lines.push(format!(
        "{} of {runs} runs succeeded, {unavailable} not available yet, {failures} failed; outputs in {}",
        runs - failures - unavailable,
        args.out.display()
    ));
    if !args.quiet {
        let text = measures.join("\n") + "\n\n" + &lines.join("\n") + "\n";
        crate::output::write_text("-", &text)?;
    }
    match first_error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input;

    #[test]
    fn every_cad_file_names_a_data_set_and_a_method_of_its_kind() {
        let catalog = Catalog::builtin();
        let formats: std::collections::HashSet<_> = CAD_FILES.iter().map(|c| c.2).collect();
        assert_eq!(formats.len(), 3, "one file per format");
        for (dataset, method, _) in CAD_FILES {
            let d = DATASETS.iter().find(|d| d.name == dataset).expect(dataset);
            assert!(
                catalog.methods(d.kind).any(|m| m.name() == method),
                "{dataset}: {method}"
            );
        }
    }

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
