//! Airfoil `.dat` files: Selig and Lednicer.
//!
//! Selig: a name line, then `x y` pairs around the contour (usually trailing edge, upper
//! surface, leading edge, lower surface, trailing edge). Lednicer: a name line, a line with the
//! point counts of the upper and the lower surface (`17. 17.`), then each surface from the
//! leading edge to the trailing edge, often separated by blank lines. A Lednicer file is
//! recognised by that counts line (two integers of at least 2, which no chord-normalised
//! coordinate pair is); it is held in memory as one Selig-ordered contour (upper reversed,
//! then lower, the leading edge once when both surfaces start there).

use super::table::number;
use super::{CurveInput, CurvePoints, InputFormat, Source};
use curve_repr::Vec2;
use fair_door::error::{Error, Result};

/// Parses a Selig or Lednicer file.
pub(super) fn parse(source: &Source) -> Result<CurveInput> {
    let path = source.name.as_str();
    let mut lines = super::numbered_lines(&source.text).map(|(i, l)| (i, l.trim()));
    let name = loop {
        match lines.next() {
            Some((_, "")) => continue,
            Some((line, l)) => {
                // A first line of two numbers is a coordinate pair, not a name: taking it as the
                // name would drop a point without a word.
                let fields: Vec<&str> = l.split_whitespace().collect();
                if let [x, y] = fields.as_slice() {
                    if number(x).is_ok() && number(y).is_ok() {
                        return Err(Error::Parse {
                            path: path.into(),
                            line,
                            message: format!(
                                "`{}` is a coordinate pair, but an airfoil .dat file starts with a \
                                 name line (add one, or give the points as CSV `x,y`)",
                                super::echo(l)
                            ),
                        });
                    }
                }
                break l.to_string();
            }
            None => {
                return Err(Error::Empty {
                    path: path.into(),
                    reason: "the file is empty".into(),
                })
            }
        }
    };
    let mut pairs: Vec<(usize, Vec2)> = Vec::new();
    for (line, text) in lines {
        if text.is_empty() || text.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = text.split_whitespace().collect();
        let [x, y] = fields.as_slice() else {
            return Err(Error::Parse {
                path: path.into(),
                line,
                message: format!("{} fields, expected two numbers `x y`", fields.len()),
            });
        };
        let parse = |field: &str, axis: &str| {
            number(field).map_err(|problem| Error::Parse {
                path: path.into(),
                line,
                message: format!("{axis}: {problem}"),
            })
        };
        pairs.push((line, Vec2::new(parse(x, "x")?, parse(y, "y")?)));
    }
    let Some(&(counts_line, counts)) = pairs.first() else {
        return Err(Error::Empty {
            path: path.into(),
            reason: "no coordinates after the name line".into(),
        });
    };
    if is_count(counts.x) && is_count(counts.y) {
        return lednicer(path, name, counts_line, counts, &pairs[1..]);
    }
    Ok(CurveInput {
        points: CurvePoints::Planar(pairs.iter().map(|(_, p)| *p).collect()),
        format: InputFormat::Selig { name },
        source: path.into(),
        lines: pairs.iter().map(|(l, _)| *l).collect(),
        notes: Vec::new(),
    })
}

fn is_count(v: f64) -> bool {
    v >= 2.0 && v.fract() == 0.0 && v < 1e9
}

fn lednicer(
    path: &str,
    name: String,
    counts_line: usize,
    counts: Vec2,
    pairs: &[(usize, Vec2)],
) -> Result<CurveInput> {
    // is_count guarantees small non-negative integers.
    let (upper, lower) = (counts.x as usize, counts.y as usize);
    if upper + lower != pairs.len() {
        return Err(Error::Parse {
            path: path.into(),
            line: counts_line,
            message: format!(
                "Lednicer counts {upper} + {lower} do not match the {} coordinate lines that follow",
                pairs.len()
            ),
        });
    }
    let (upper_pairs, lower_pairs) = pairs.split_at(upper);
    let shared_leading_edge =
        matches!((upper_pairs.first(), lower_pairs.first()), (Some(a), Some(b)) if a.1 == b.1);
    let skip = usize::from(shared_leading_edge);
    let ordered: Vec<&(usize, Vec2)> = upper_pairs
        .iter()
        .rev()
        .chain(lower_pairs.iter().skip(skip))
        .collect();
    Ok(CurveInput {
        points: CurvePoints::Planar(ordered.iter().map(|(_, p)| *p).collect()),
        format: InputFormat::Lednicer {
            name,
            upper,
            lower,
            shared_leading_edge,
        },
        source: path.into(),
        lines: ordered.iter().map(|(l, _)| *l).collect(),
        notes: Vec::new(),
    })
}
