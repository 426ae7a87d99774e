//! Which kind of curve the points are: a function y(x) or a parametric curve.

use fairing::catalog::CurvePoints;

use crate::data::CurveData;
use crate::error::Result;

/// The kind a front end asks for: detected from the points, or given.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum KindChoice {
    /// A function when the points are planar with x strictly increasing, else parametric.
    #[default]
    Auto,
    /// A function y(x) (checked).
    Function,
    /// A parametric curve.
    Parametric,
}

/// The kind of a curve as the indicators and strategies see it (the catalogue's).
pub use fairing::catalog::CurveKind;

/// The first index `i` with x_{i+1} ≤ x_i of planar points, or `None` when x increases
/// strictly (also `None` for spatial points' absence of an answer: see [`detect`]).
pub fn first_non_increasing(points: &CurvePoints) -> Option<usize> {
    match points {
        CurvePoints::Planar(p) => p.windows(2).position(|w| w[1].x <= w[0].x),
        CurvePoints::Spatial(_) => Some(0),
    }
}

/// `--kind auto`: function when the points are planar with x strictly increasing, else
/// parametric. O(n).
pub fn detect(points: &CurvePoints) -> CurveKind {
    match points {
        CurvePoints::Planar(_) if first_non_increasing(points).is_none() => CurveKind::Function,
        _ => CurveKind::Parametric,
    }
}

/// What `--kind auto` tells the user when planar points are not a function: the first point
/// whose x does not increase, with its line (or number), and that the curve is faired as
/// parametric, so its x values may move. `None` for a function, spatial points or another
/// choice than [`KindChoice::Auto`]. One line. O(n).
pub fn auto_note(argument: KindChoice, input: &CurveData<'_>) -> Option<String> {
    let CurvePoints::Planar(p) = input.points else {
        return None;
    };
    if argument != KindChoice::Auto {
        return None;
    }
    let i = first_non_increasing(input.points)?;
    let place = match input.line_of(i + 1) {
        Some(line) => format!("{}:{line}", input.source),
        None => format!("{}: point {}", input.source, i + 1),
    };
    Some(format!(
        "{place}: x = {} {} x = {}, so x is not strictly increasing and the points are faired as a \
         parametric curve (x values may move); --kind function refuses such a file instead",
        p[i + 1].x,
        if p[i + 1].x == p[i].x {
            "repeats"
        } else {
            "follows"
        },
        p[i].x
    ))
}

/// How close two abscissae of a function may be, relative to the x range: closer than
/// 10⁻¹² of it, the spline's slope between them is 10¹² times the curve's typical slope and
/// its curvature beyond anything the data can mean — the points are one point up to
/// round-off.
pub const MIN_RELATIVE_SPACING: f64 = 1e-12;

/// The first `i` with 0 < x_{i+1} − x_i ≤ [`MIN_RELATIVE_SPACING`] · (x_max − x_min), for
/// increasing planar points. O(n).
pub fn first_too_close(points: &CurvePoints) -> Option<usize> {
    let CurvePoints::Planar(p) = points else {
        return None;
    };
    let (first, last) = (p.first()?.x, p.last()?.x);
    let limit = MIN_RELATIVE_SPACING * (last - first).abs();
    p.windows(2).position(|w| w[1].x - w[0].x <= limit)
}

/// Refuses a function whose abscissae are closer than round-off can tell apart
/// ([`first_too_close`]), naming both lines.
fn check_spacing(input: &CurveData<'_>) -> Result<()> {
    let (Some(i), CurvePoints::Planar(p)) = (first_too_close(input.points), input.points) else {
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
pub fn resolve(argument: KindChoice, input: &CurveData<'_>) -> Result<CurveKind> {
    let kind = resolve_unchecked(argument, input)?;
    if kind == CurveKind::Function {
        check_spacing(input)?;
    }
    Ok(kind)
}

fn resolve_unchecked(argument: KindChoice, input: &CurveData<'_>) -> Result<CurveKind> {
    match argument {
        KindChoice::Auto => Ok(detect(input.points)),
        KindChoice::Parametric => Ok(CurveKind::Parametric),
        KindChoice::Function => match (input.points, first_non_increasing(input.points)) {
            (CurvePoints::Spatial(_), _) => {
                Err(input.point_error(0, "--kind function needs planar points x,y"))
            }
            (CurvePoints::Planar(p), Some(i)) => Err(input.point_error(
                i + 1,
                format!(
                    "--kind function needs x strictly increasing, but x = {} follows x = {}",
                    p[i + 1].x,
                    p[i].x
                ),
            )),
            (CurvePoints::Planar(_), None) => Ok(CurveKind::Function),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    /// Points of a CSV text `x,y[,z]` per line (after a header line when the first field is
    /// not a number), with their lines.
    struct Read {
        points: CurvePoints,
        lines: Vec<usize>,
    }

    impl Read {
        fn data(&self) -> CurveData<'_> {
            CurveData {
                points: &self.points,
                source: "k.csv",
                lines: &self.lines,
            }
        }
    }

    fn input(text: &str) -> Read {
        let mut rows = Vec::new();
        let mut lines = Vec::new();
        for (k, line) in text.lines().enumerate() {
            let fields: Vec<f64> = line.split(',').filter_map(|f| f.trim().parse().ok()).collect();
            if !fields.is_empty() {
                rows.push(fields);
                lines.push(k + 1);
            }
        }
        let points = match rows[0].len() {
            2 => CurvePoints::Planar(rows.iter().map(|r| Vec2::new(r[0], r[1])).collect()),
            _ => CurvePoints::Spatial(rows.iter().map(|r| Vec3::new(r[0], r[1], r[2])).collect()),
        };
        Read { points, lines }
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
        let e = resolve(KindChoice::Function, &input("x,y\n0,0\n1,1\n0.5,0\n").data()).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("k.csv:4: --kind function needs x strictly increasing"),
            "{e}"
        );
        assert_eq!(
            resolve(KindChoice::Parametric, &input("0,0\n1,1\n").data()).unwrap(),
            CurveKind::Parametric
        );
        assert!(resolve(KindChoice::Function, &input("0,0,0\n1,1,1\n").data()).is_err());
    }

    /// Auto on a repeated or swapped x: a note naming the line; nothing for a function, for
    /// spatial points or when the kind was given.
    #[test]
    fn auto_says_why_a_curve_is_parametric() {
        let swapped = input("x,y\n0,0\n2,1\n1,0\n3,1\n");
        let note = auto_note(KindChoice::Auto, &swapped.data()).unwrap();
        assert!(
            note.starts_with("k.csv:4: x = 1 follows x = 2, so x is not strictly increasing"),
            "{note}"
        );
        assert!(note.contains("parametric") && !note.contains('\n'), "{note}");
        let repeated = input("x,y\n0,0\n1,1\n1,0\n3,1\n");
        let note = auto_note(KindChoice::Auto, &repeated.data()).unwrap();
        assert!(note.starts_with("k.csv:4: x = 1 repeats x = 1"), "{note}");
        assert_eq!(auto_note(KindChoice::Parametric, &repeated.data()), None);
        assert_eq!(
            auto_note(KindChoice::Auto, &input("0,0\n1,1\n2,0\n").data()),
            None
        );
        assert_eq!(auto_note(KindChoice::Auto, &input("0,0,0\n1,1,1\n").data()), None);
    }

    /// Two abscissae 1e-15 apart: a clear message naming the line, for --kind auto too; as a
    /// parametric curve the points are fine.
    #[test]
    fn abscissae_within_round_off_are_refused_with_their_lines() {
        let text = "x,y\n0,0\n1,1\n1.000000000000001,0.5\n2,0\n";
        for kind in [KindChoice::Auto, KindChoice::Function] {
            let e = resolve(kind, &input(text).data()).unwrap_err();
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
            resolve(KindChoice::Parametric, &input(text).data()).unwrap(),
            CurveKind::Parametric
        );
        // Spacing of 1e-9 of the range is data, not round-off.
        assert_eq!(
            resolve(KindChoice::Auto, &input("0,0\n1e-9,0\n1,1\n").data()).unwrap(),
            CurveKind::Function
        );
    }
}
