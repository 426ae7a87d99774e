//! `nurbs-weights` with the per-point law: L-BFGS on the exact gradient (`--set solver=lbfgs`)
//! against Nelder–Mead (`--set solver=nelder-mead`) on the same airfoil, and the refusal of
//! `lbfgs` with a criterion that has no differentiable form.

use std::process::Command;

fn data(relative: &str) -> String {
    format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"))
}

/// Runs per-point Ek with `solver` and returns the report.
fn run(solver: &str) -> serde_json::Value {
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let scratch = crate::scratch_dir("fair-nurbs-solver-");
    let dir = scratch.path();
    let report = dir.join(format!("{solver}.json"));
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(["curve", &input, "--method", "nurbs-weights", "--quiet"])
        .args(["--set", "law=per-point", "--set", "criterion=ek"])
        .args(["--set", &format!("solver={solver}")])
        // L-BFGS converges in ~36 iterations here; Nelder–Mead is cut at 300 (its Ek then
        // 16.697, still above L-BFGS's 16.681; at 1000 iterations 16.686).
        .args(["--set", "max-iterations=300"])
        .arg("-o")
        .arg(dir.join(format!("{solver}.csv")))
        .arg("--report")
        .arg(&report)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap()
}

#[test]
fn lbfgs_lowers_per_point_ek_below_nelder_mead() {
    let lbfgs = run("lbfgs");
    let nelder_mead = run("nelder-mead");
    assert_eq!(lbfgs["solver"], "lbfgs");
    assert_eq!(nelder_mead["solver"], "nelder-mead");
    assert!(lbfgs["gradient_evaluations"].as_u64().unwrap() > 0);
    assert_eq!(nelder_mead["gradient_evaluations"].as_u64().unwrap(), 0);
    let before = lbfgs["criterion_before"].as_f64().unwrap();
    let (ek_lbfgs, ek_nm) = (
        lbfgs["criterion_after"].as_f64().unwrap(),
        nelder_mead["criterion_after"].as_f64().unwrap(),
    );
    assert_eq!(nelder_mead["criterion_before"].as_f64().unwrap(), before);
    // The reported criterion is the adaptive Ek of the faired curve, for both solvers.
    assert_eq!(lbfgs["energies_faired"]["ek"].as_f64().unwrap(), ek_lbfgs);
    assert!(ek_lbfgs < before, "{ek_lbfgs} vs {before}");
    assert!(
        ek_lbfgs < ek_nm,
        "L-BFGS {ek_lbfgs} not below Nelder–Mead {ek_nm}"
    );
    let weights = lbfgs["curve"]["weights"].as_array().unwrap();
    let bound = optim_bound();
    assert!(weights
        .iter()
        .map(|w| w.as_f64().unwrap())
        .all(|w| w > 0.0 && w <= bound * (1.0 + 1e-12) && w >= (1.0 - 1e-12) / bound));
    assert!(lbfgs["max_residual"].as_f64().unwrap() < 1e-9);
}

/// e^{MAX_LOG_WEIGHT}: the per-point law's bound on a weight (w_0 = 1).
fn optim_bound() -> f64 {
    7f64.exp()
}

#[test]
fn lbfgs_without_a_differentiable_criterion_exits_2() {
    let input = data("airfoil_naca2412/naca2412_upper.csv");
    let output = Command::new(env!("CARGO_BIN_EXE_fair"))
        .args(["curve", &input, "--method", "nurbs-weights"])
        .args([
            "--set",
            "law=per-point",
            "--set",
            "criterion=e3",
            "--set",
            "solver=lbfgs",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("solver") && stderr.contains("ek or e2"),
        "{stderr}"
    );
}
