//! The work one request may ask of `fair serve`: points, grid nodes and iteration settings.
//!
//! The server shares its cores between everyone who reaches it, so each request's work is
//! bounded before any of it runs: a curve over [`MAX_CURVE_POINTS`] points or a grid over
//! [`MAX_SURFACE_NODES`] nodes is answered 413, an iteration setting over its bound in
//! [`ITERATION_LIMITS`] 422, each naming the limit. The deadline (`--deadline`) bounds the
//! time of what is left; these bound its memory and keep a request from asking for more
//! iterations than its deadline could ever give. `fair curve` and `fair surface` have no
//! such limits: they run on their caller's own machine and time.
//!
//! The points are counted while the body is read ([`Rows`]), so a body of a million points
//! is refused without ever holding more than twice the limit of them.

use std::collections::BTreeMap;
use std::fmt;

use fairing::catalog::{Catalog, MethodKind};
use serde::de::{Deserialize, Deserializer, SeqAccess, Visitor};
use serde_json::Value;

use super::http::Response;

/// The most points of a curve a request may send (to fair, measure or export).
pub(crate) const MAX_CURVE_POINTS: usize = 50_000;

/// The most nodes (rows × columns) of a grid a request may send.
pub(crate) const MAX_SURFACE_NODES: usize = 90_000;

/// The most points of a nurbs-weights request with one weight per point searched by
/// Nelder–Mead: its simplex holds (n + 1) × n numbers, 8 n² bytes (32 MB at this limit, 20 GB
/// at [`MAX_CURVE_POINTS`]).
pub(crate) const MAX_SIMPLEX_POINTS: usize = 2_000;

/// Iteration settings (`params`) and the largest value the server accepts for each: every
/// method's default is within them.
pub(crate) const ITERATION_LIMITS: &[(&str, u64)] = &[
    ("max-passes", 1_000),
    ("segment-passes", 100),
    ("max-iterations", 100_000),
    ("max-sweeps", 100_000),
    ("max-steps", 100_000),
];

/// The marker that starts the message of a [`Rows`] refusal, so that the body's reader can
/// tell it from a syntax error (serde adds the position after it).
const TOO_MANY: &str = "too many points";

/// The most rows a body's reader holds: twice the largest count any request may send, so
/// that a request just over its limit gets the message naming that limit, and a body of a
/// million points is dropped after reading this many.
const MOST_ROWS: usize = 2 * if MAX_CURVE_POINTS > MAX_SURFACE_NODES {
    MAX_CURVE_POINTS
} else {
    MAX_SURFACE_NODES
};

/// A list of coordinate rows that refuses, while it is read, more than [`MOST_ROWS`].
#[derive(Debug, Default, Clone, PartialEq)]
pub(crate) struct Rows(pub Vec<Vec<f64>>);

impl<'de> Deserialize<'de> for Rows {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Counted;
        impl<'de> Visitor<'de> for Counted {
            type Value = Rows;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a list of points, each a list of numbers")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Rows, A::Error> {
                let most = MOST_ROWS;
                let mut rows = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(most));
                while let Some(row) = seq.next_element::<Vec<f64>>()? {
                    if rows.len() == most {
                        return Err(serde::de::Error::custom(format!(
                            "{TOO_MANY}: more than {most}, this server's limit"
                        )));
                    }
                    rows.push(row);
                }
                Ok(Rows(rows))
            }
        }
        deserializer.deserialize_seq(Counted)
    }
}

/// A refusal of the body's reader that is a [`Rows`] count, as the 413 naming the limits.
pub(crate) fn too_many_rows(error: &serde_json::Error) -> Option<Response> {
    error.to_string().starts_with(TOO_MANY).then(|| {
        Response::error(
            413,
            format!(
                "points: far more than this server's limit of {MAX_CURVE_POINTS} curve points or {MAX_SURFACE_NODES} grid nodes per request; fair larger inputs with `fair curve` or `fair surface`"
            ),
        )
    })
}

/// A curve of `count` points, checked against [`MAX_CURVE_POINTS`] (413 past it).
pub(crate) fn curve_points(count: usize) -> Result<(), Response> {
    if count > MAX_CURVE_POINTS {
        return Err(Response::error(
            413,
            format!(
                "points: {count} points, more than this server's limit of {MAX_CURVE_POINTS} per curve; fair larger curves with `fair curve`"
            ),
        ));
    }
    Ok(())
}

/// A curve of `count` points faired by `method` with `params`: a nurbs-weights search with
/// one weight per point by Nelder–Mead (`law = per-point` with `solver = nelder-mead`, or
/// `auto` with a criterion L-BFGS cannot take) is checked against [`MAX_SIMPLEX_POINTS`]
/// (413 past it), every other method against [`MAX_CURVE_POINTS`] only.
pub(crate) fn curve_work(
    catalog: &Catalog,
    count: usize,
    method: Option<&str>,
    params: &BTreeMap<String, Value>,
) -> Result<(), Response> {
    curve_points(count)?;
    let Some(entry) = method
        .map(str::trim)
        .filter(|m| *m == "nurbs-weights")
        .and_then(|m| catalog.method(MethodKind::Curve, m).ok())
    else {
        return Ok(());
    };
    // A setting as given, else the method's own default (the catalogue's, written once).
    let text = |name: &str| -> String {
        match params.get(name).or_else(|| entry.defaults().get(name)) {
            Some(Value::String(s)) => s.trim().to_ascii_lowercase(),
            _ => String::new(),
        }
    };
    let simplex = text("law") == "per-point"
        && match text("solver").as_str() {
            "nelder-mead" => true,
            "auto" => optim::SmoothCriterion::from_name(&text("criterion")).is_none(),
            _ => false,
        };
    if simplex && count > MAX_SIMPLEX_POINTS {
        return Err(Response::error(
            413,
            format!(
                "points: {count} points, more than this server's limit of {MAX_SIMPLEX_POINTS} for nurbs-weights with law per-point searched by Nelder–Mead (its simplex holds n² numbers); use solver lbfgs, law bernstein, or `fair curve`"
            ),
        ));
    }
    Ok(())
}

/// A grid of `rows` × `columns` nodes, checked against [`MAX_SURFACE_NODES`] (413 past it).
pub(crate) fn surface_nodes(rows: usize, columns: usize) -> Result<(), Response> {
    let nodes = rows.saturating_mul(columns);
    if nodes > MAX_SURFACE_NODES {
        return Err(Response::error(
            413,
            format!(
                "points: a {rows} × {columns} grid has {nodes} nodes, more than this server's limit of {MAX_SURFACE_NODES}; fair larger grids with `fair surface`"
            ),
        ));
    }
    Ok(())
}

/// The request's `params`, each iteration setting checked against [`ITERATION_LIMITS`]
/// (422 naming the setting and its limit). Values that are not numbers are left to the
/// method's own reading (which refuses them with its own message).
pub(crate) fn iterations(params: &BTreeMap<String, Value>) -> Result<(), Response> {
    for (name, limit) in ITERATION_LIMITS {
        let Some(value) = params.get(*name) else {
            continue;
        };
        let number = match value {
            Value::Number(n) => n.as_f64(),
            Value::String(s) => s.trim().parse::<f64>().ok(),
            _ => None,
        };
        if let Some(number) = number.filter(|n| *n > *limit as f64) {
            return Err(Response::error(
                422,
                format!(
                    "params.{name}: {number} is over this server's limit of {limit}; `fair curve` and `fair surface` take more"
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_counted_while_read() {
        let few: Rows = serde_json::from_str("[[0, 1], [2, 3.5]]").unwrap();
        assert_eq!(few.0, vec![vec![0.0, 1.0], vec![2.0, 3.5]]);
        let most = MOST_ROWS;
        let text = format!("[{}[0,0]]", "[0,0],".repeat(most));
        let error = serde_json::from_str::<Rows>(&text).unwrap_err();
        let refusal = too_many_rows(&error).expect("a count refusal");
        assert_eq!(refusal.status, 413);
        let bad = serde_json::from_str::<Rows>("[[0, true]]").unwrap_err();
        assert!(too_many_rows(&bad).is_none());
    }

    #[test]
    fn limits_name_themselves() {
        assert!(curve_points(MAX_CURVE_POINTS).is_ok());
        let r = curve_points(MAX_CURVE_POINTS + 1).unwrap_err();
        assert_eq!(r.status, 413);
        assert!(String::from_utf8_lossy(&r.body).contains("50000"));
        let params = |pairs: &[(&str, &str)]| -> BTreeMap<String, Value> {
            pairs
                .iter()
                .map(|(k, v)| (k.to_string(), serde_json::json!(v)))
                .collect()
        };
        let simplex = params(&[("law", "per-point"), ("solver", "nelder-mead")]);
        assert!(curve_work(
            &Catalog::builtin(),
            MAX_SIMPLEX_POINTS,
            Some("nurbs-weights"),
            &simplex
        )
        .is_ok());
        let r = curve_work(
            &Catalog::builtin(),
            MAX_SIMPLEX_POINTS + 1,
            Some("nurbs-weights"),
            &simplex,
        )
        .unwrap_err();
        assert_eq!(r.status, 413);
        assert!(String::from_utf8_lossy(&r.body).contains("2000"));
        let e3 = params(&[("law", "per-point"), ("criterion", "e3")]);
        assert!(curve_work(&Catalog::builtin(), 5_000, Some("nurbs-weights"), &e3).is_err());
        let lbfgs = params(&[("law", "per-point")]);
        assert!(curve_work(&Catalog::builtin(), 5_000, Some("nurbs-weights"), &lbfgs).is_ok());
        assert!(curve_work(&Catalog::builtin(), 5_000, Some("two-phase"), &simplex).is_ok());
        assert!(surface_nodes(300, 300).is_ok());
        assert_eq!(surface_nodes(301, 300).unwrap_err().status, 413);
        assert_eq!(surface_nodes(usize::MAX, 2).unwrap_err().status, 413);
        let ok = BTreeMap::from([("max-passes".to_string(), serde_json::json!(50))]);
        assert!(iterations(&ok).is_ok());
        let over = BTreeMap::from([("max-iterations".to_string(), serde_json::json!("200000"))]);
        let r = iterations(&over).unwrap_err();
        assert_eq!(r.status, 422);
        let text = String::from_utf8_lossy(&r.body).to_string();
        assert!(
            text.contains("params.max-iterations") && text.contains("100000"),
            "{text}"
        );
    }
}
