//! Nowacki, Liu & Lü (FAIRSHAPE 1996), Table 1's layout: for each optimised criterion (rows),
//! every calculated criterion E1, E2, E3, Ek of the faired NURBS (columns), with the NUBS (unit
//! weights) as the first row. The weights follow the paper's cubic Bernstein law; the data
//! points never move.
//!
//! Our curves are the NACA 2412 upper surface and a Block Island waterline (the paper's own
//! curves are not published), so the numbers are ours, not the paper's.
//!
//! Run: `cargo run --example nowacki_table1`

use curve_repr::Vec2;
use optim::{CriterionName, CubicBernstein, NelderMeadSettings, NurbsWeightFairing};

fn read_csv(relative: &str) -> Result<Vec<Vec2>, Box<dyn std::error::Error>> {
    let path = format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path)?;
    let mut points = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let values: Vec<f64> = line
            .split(',')
            .map(|x| x.trim().parse())
            .collect::<Result<_, _>>()?;
        if let [x, y, ..] = values[..] {
            points.push(Vec2::new(x, y));
        }
    }
    Ok(points)
}

fn table(title: &str, relative: &str) -> Result<(), Box<dyn std::error::Error>> {
    let points = read_csv(relative)?;
    println!("\n{title} ({relative}, {} points)", points.len());
    println!(
        "{:<14}{:>14}{:>14}{:>14}{:>14}{:>8}",
        "optimised", "E1", "E2", "E3", "Ek", "iter"
    );
    let mut printed_nubs = false;
    for name in [
        CriterionName::E1,
        CriterionName::E2,
        CriterionName::E3,
        CriterionName::Ek,
    ] {
        let result = NurbsWeightFairing::new(CubicBernstein, name.criterion::<2>())
            .with_nelder_mead(NelderMeadSettings::default().with_max_iterations(1000))
            .run(&points)?;
        if !printed_nubs {
            let e = result.before;
            println!(
                "{:<14}{:>14.6e}{:>14.6e}{:>14.6e}{:>14.6e}{:>8}",
                "NUBS (w = 1)", e.e1, e.e2, e.e3, e.ek, ""
            );
            printed_nubs = true;
        }
        let e = result.after;
        println!(
            "{:<14}{:>14.6e}{:>14.6e}{:>14.6e}{:>14.6e}{:>8}",
            format!("min {name}"),
            e.e1,
            e.e2,
            e.e3,
            e.ek,
            result.iterations
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    table("NACA 2412 upper surface", "airfoil_naca2412/naca2412_upper.csv")?;
    table(
        "Block Island waterline 36 in",
        "hull_block_island_boat/waterlines/wl_36in.csv",
    )?;
    Ok(())
}
