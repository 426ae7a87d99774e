//! Which kind of curve the points are: a function y(x) or a parametric curve.

use crate::args::KindArg;
use crate::error::Result;
use crate::input::{CurveInput, Points};

/// The kind of a curve as the indicators and strategies see it (the catalogue's).
pub use fairing::catalog::CurveKind;

/// The first index `i` with x_{i+1} ≤ x_i of planar points, or `None` when x increases
/// strictly (also `None` for spatial points' absence of an answer: see [`detect`]).
pub fn first_non_increasing(points: &Points) -> Option<usize> {
    match points {
        Points::Planar(p) => p.windows(2).position(|w| w[1].x <= w[0].x),
        Points::Spatial(_) => Some(0),
    }
}

/// `--kind auto`: function when the points are planar with x strictly increasing, else
/// parametric. O(n).
pub fn detect(points: &Points) -> CurveKind {
    match points {
        Points::Planar(_) if first_non_increasing(points).is_none() => CurveKind::Function,
        _ => CurveKind::Parametric,
    }
}

/// Resolves `--kind` for an input: `function` is checked (planar, x strictly increasing) and
/// the first offending point is named with its line.
pub fn resolve(argument: KindArg, input: &CurveInput) -> Result<CurveKind> {
    match argument {
        KindArg::Auto => Ok(detect(&input.points)),
        KindArg::Parametric => Ok(CurveKind::Parametric),
        KindArg::Function => match (&input.points, first_non_increasing(&input.points)) {
            (Points::Spatial(_), _) => Err(input.point_error(0, "--kind function needs planar points x,y")),
            (Points::Planar(p), Some(i)) => Err(input.point_error(
                i + 1,
                format!(
                    "--kind function needs x strictly increasing, but x = {} follows x = {}",
                    p[i + 1].x,
                    p[i].x
                ),
            )),
            (Points::Planar(_), None) => Ok(CurveKind::Function),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::{parse_curve, Source};

    fn input(text: &str) -> CurveInput {
        parse_curve(&Source::from_text("k.csv", text)).unwrap()
    }

    #[test]
    fn auto_detection() {
        assert_eq!(detect(&input("0,0\n1,1\n2,0\n").points), CurveKind::Function);
        assert_eq!(detect(&input("0,0\n1,1\n1,0\n").points), CurveKind::Parametric);
        assert_eq!(detect(&input("2,0\n1,1\n0,0\n").points), CurveKind::Parametric);
        assert_eq!(detect(&input("0,0,0\n1,1,1\n").points), CurveKind::Parametric);
    }

    #[test]
    fn function_is_checked_with_line() {
        let e = resolve(KindArg::Function, &input("x,y\n0,0\n1,1\n0.5,0\n")).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("k.csv:4: --kind function needs x strictly increasing"),
            "{e}"
        );
        assert_eq!(
            resolve(KindArg::Parametric, &input("0,0\n1,1\n")).unwrap(),
            CurveKind::Parametric
        );
        assert!(resolve(KindArg::Function, &input("0,0,0\n1,1,1\n")).is_err());
    }
}
