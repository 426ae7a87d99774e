//! Nowacki, Liu & Lü (FAIRSHAPE 1996), Table 1's layout: for each optimised criterion (rows),
//! every calculated criterion E1, E2, E3, Ek of the faired NURBS (columns), with the NUBS (unit
//! weights) as the first row. The weights follow the paper's cubic Bernstein law; the data
//! points never move.
//!
//! Our curves are the NACA 2412 upper surface, a Block Island waterline and the boat's
//! station 10 section (the paper's own
//! curves are not published), so the numbers are ours, not the paper's.
//!
//! Run: `cargo run --example nowacki_table1`

use curve_repr::Vec2;
use optim::{CriterionName, CubicBernstein, NelderMeadSettings, NurbsWeightFairing};

/// Reads columns `columns` of a CSV file under data/ as planar points.
fn read_csv(relative: &str, columns: [usize; 2]) -> Result<Vec<Vec2>, Box<dyn std::error::Error>> {
    let path = format!("{}/data/{relative}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path)?;
    let mut points = Vec::new();
    for line in text.lines().skip(1).filter(|l| !l.trim().is_empty()) {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let field = |c: usize| -> Result<f64, Box<dyn std::error::Error>> {
            Ok(fields.get(c).ok_or("missing column")?.parse()?)
        };
        points.push(Vec2::new(field(columns[0])?, field(columns[1])?));
    }
    Ok(points)
}

fn table(title: &str, relative: &str, columns: [usize; 2]) -> Result<(), Box<dyn std::error::Error>> {
    let points = read_csv(relative, columns)?;
    println!("\n{title} ({relative}, {} points)", points.len());
    println!(
        "{:<14}{:>14}{:>14}{:>14}{:>14}{:>8}{:>14}",
        "optimised", "E1", "E2", "E3", "Ek", "iter", "residual/size"
    );
    // The curve's size: the diagonal of the data's bounding box.
    let (low, high) = points.iter().fold(
        (Vec2::repeat(f64::INFINITY), Vec2::repeat(f64::NEG_INFINITY)),
        |(l, h), p| (l.inf(p), h.sup(p)),
    );
    let size = (high - low).norm();
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
            "{:<14}{:>14.6e}{:>14.6e}{:>14.6e}{:>14.6e}{:>8}{:>14.1e}",
            format!("min {name}"),
            e.e1,
            e.e2,
            e.e3,
            e.ek,
            result.iterations,
            result.max_residual / size
        );
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    table(
        "NACA 2412 upper surface",
        "airfoil_naca2412/naca2412_upper.csv",
        [0, 1],
    )?;
    table(
        "Block Island waterline 36 in",
        "hull_block_island_boat/waterlines/wl_36in.csv",
        [0, 1],
    )?;
    // A hull section: station 10 of the Block Island boat in its own plane, half-breadth y
    // against height z (columns 1 and 2 of x,y,z,source).
    table(
        "Block Island station 10 (y, z)",
        "hull_block_island_boat/sections/station_10.csv",
        [1, 2],
    )?;
    Ok(())
}
