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

/// How close two abscissae of a function may be, relative to the x range: closer than
/// 10⁻¹² of it, the spline's slope between them is 10¹² times the curve's typical slope and
/// its curvature beyond anything the data can mean — the points are one point up to
/// round-off.
pub const MIN_RELATIVE_SPACING: f64 = 1e-12;

/// The first `i` with 0 < x_{i+1} − x_i ≤ [`MIN_RELATIVE_SPACING`] · (x_max − x_min), for
/// increasing planar points. O(n).
pub fn first_too_close(points: &Points) -> Option<usize> {
    let Points::Planar(p) = points else {
        return None;
    };
    let (first, last) = (p.first()?.x, p.last()?.x);
    let limit = MIN_RELATIVE_SPACING * (last - first).abs();
    p.windows(2).position(|w| w[1].x - w[0].x <= limit)
}

/// Refuses a function whose abscissae are closer than round-off can tell apart
/// ([`first_too_close`]), naming both lines.
fn check_spacing(input: &CurveInput) -> Result<()> {
    let (Some(i), Points::Planar(p)) = (first_too_close(&input.points), &input.points) else {
        return Ok(());
    };
    let line = |k: usize| {
        input
            .line_of(k)
            .map_or(format!("point {k}"), |l| format!("line {l}"))
    };
    Err(input.point_error(
        i + 1,
        format!(
            "x = {} is only {:.1e} after x = {} on {} ({:.0e} of the x range): a function y(x) through both \
             has a slope ~1e12 times the curve's; merge or remove one of them, or fair with --kind parametric",
            p[i + 1].x,
            p[i + 1].x - p[i].x,
            p[i].x,
            line(i),
            (p[i + 1].x - p[i].x) / (p[p.len() - 1].x - p[0].x)
        ),
    ))
}

/// Resolves `--kind` for an input: `function` is checked (planar, x strictly increasing and
/// no two abscissae within round-off of each other) and the first offending point is named
/// with its line.
pub fn resolve(argument: KindArg, input: &CurveInput) -> Result<CurveKind> {
    let kind = resolve_unchecked(argument, input)?;
    if kind == CurveKind::Function {
        check_spacing(input)?;
    }
    Ok(kind)
}

fn resolve_unchecked(argument: KindArg, input: &CurveInput) -> Result<CurveKind> {
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

    /// Two abscissae 1e-15 apart: a clear message naming the line, for --kind auto too; as a
    /// parametric curve the points are fine.
    #[test]
    fn abscissae_within_round_off_are_refused_with_their_lines() {
        let text = "x,y\n0,0\n1,1\n1.000000000000001,0.5\n2,0\n";
        for kind in [KindArg::Auto, KindArg::Function] {
            let e = resolve(kind, &input(text)).unwrap_err();
            let line = e.one_line();
            assert!(
                line.starts_with("k.csv:4: x = 1.000000000000001 is only"),
                "{line}"
            );
            assert!(
                line.contains("line 3") && line.contains("--kind parametric"),
                "{line}"
            );
            assert_eq!(e.exit_code(), 2);
        }
        assert_eq!(
            resolve(KindArg::Parametric, &input(text)).unwrap(),
            CurveKind::Parametric
        );
        // Spacing of 1e-9 of the range is data, not round-off.
        assert_eq!(
            resolve(KindArg::Auto, &input("0,0\n1e-9,0\n1,1\n")).unwrap(),
            CurveKind::Function
        );
    }
}
