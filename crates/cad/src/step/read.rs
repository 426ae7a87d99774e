//! The STEP reader.

use std::collections::{BTreeMap, HashMap, HashSet};

use curve_repr::{Curve, NurbsCurve, NurbsSurface, Vec3};

use super::parse::{parse, Instance, Value};
use crate::model::{CadCurve, CadModel, CadSurface};
use crate::{Error, Result, Units};

const FORMAT: &str = "STEP";

struct Reader {
    instances: BTreeMap<usize, Instance>,
}

impl Reader {
    fn error(&self, instance: &Instance, id: usize, message: impl std::fmt::Display) -> Error {
        Error::parse(FORMAT, instance.line, format!("#{id}: {message}"))
    }

    /// The control point `value` refers to: `None` for a 2D point.
    fn point(&self, value: &Value, owner: &Instance, id: usize) -> Result<Option<Vec3>> {
        let target = value
            .reference()
            .and_then(|r| self.instances.get(&r))
            .ok_or_else(|| self.error(owner, id, "a control point is not a reference to an instance"))?;
        let coordinates = target
            .part("CARTESIAN_POINT")
            .and_then(|p| p.get(1))
            .and_then(Value::list)
            .ok_or_else(|| self.error(owner, id, "a control point is not a CARTESIAN_POINT"))?;
        let numbers: Vec<f64> = coordinates.iter().filter_map(Value::number).collect();
        match numbers.as_slice() {
            [x, y, z] => Ok(Some(Vec3::new(*x, *y, *z))),
            [_, _] => Ok(None),
            _ => Err(self.error(owner, id, "a CARTESIAN_POINT has neither 2 nor 3 coordinates")),
        }
    }

    fn numbers(&self, value: Option<&Value>, what: &str, owner: &Instance, id: usize) -> Result<Vec<f64>> {
        let items = value
            .and_then(Value::list)
            .ok_or_else(|| self.error(owner, id, format!("{what}: expected a list")))?;
        items
            .iter()
            .map(|v| {
                v.number()
                    .ok_or_else(|| self.error(owner, id, format!("{what}: a value is not a number")))
            })
            .collect()
    }

    fn integer(&self, value: Option<&Value>, what: &str, owner: &Instance, id: usize) -> Result<usize> {
        match value {
            Some(Value::Integer(v)) if *v >= 0 => Ok(*v as usize),
            _ => Err(self.error(owner, id, format!("{what}: expected a non-negative integer"))),
        }
    }

    /// Knots with multiplicities expanded.
    fn knots(
        &self,
        multiplicities: Option<&Value>,
        knots: Option<&Value>,
        owner: &Instance,
        id: usize,
    ) -> Result<Vec<f64>> {
        let counts = self.numbers(multiplicities, "knot multiplicities", owner, id)?;
        let values = self.numbers(knots, "knots", owner, id)?;
        if counts.len() != values.len() {
            return Err(self.error(
                owner,
                id,
                format!("{} multiplicities for {} knots", counts.len(), values.len()),
            ));
        }
        let mut out = Vec::new();
        for (&count, &value) in counts.iter().zip(&values) {
            if !(count >= 1.0 && count.fract() == 0.0 && count < 1e6) {
                return Err(self.error(owner, id, format!("knot multiplicity {count}")));
            }
            out.extend(std::iter::repeat_n(value, count as usize));
        }
        Ok(out)
    }

    /// The curve of instance `id`, `None` for a parameter-space (2D) curve.
    fn curve(&self, id: usize, instance: &Instance) -> Result<Option<(String, NurbsCurve<3>)>> {
        let (name, degree, points, multiplicities, knots, weights) = if instance.parts.len() == 1 {
            let p = instance.parts[0].1.as_slice();
            (p.first(), p.get(1), p.get(2), p.get(6), p.get(7), None)
        } else {
            let b = instance
                .part("B_SPLINE_CURVE")
                .ok_or_else(|| self.error(instance, id, "a complex B-spline curve without B_SPLINE_CURVE"))?;
            let k = instance.part("B_SPLINE_CURVE_WITH_KNOTS").unwrap_or(&[]);
            let name = instance.part("REPRESENTATION_ITEM").and_then(|r| r.first());
            let weights = instance.part("RATIONAL_B_SPLINE_CURVE").and_then(|r| r.first());
            (name, b.first(), b.get(1), k.first(), k.get(1), weights)
        };
        let degree = self.integer(degree, "degree", instance, id)?;
        let refs = points
            .and_then(Value::list)
            .ok_or_else(|| self.error(instance, id, "control points: expected a list"))?;
        let mut control = Vec::with_capacity(refs.len());
        for r in refs {
            match self.point(r, instance, id)? {
                Some(p) => control.push(p),
                None => return Ok(None),
            }
        }
        let knots = self.knots(multiplicities, knots, instance, id)?;
        let weights = match weights {
            Some(w) => self.numbers(Some(w), "weights", instance, id)?,
            None => vec![1.0; control.len()],
        };
        let curve =
            NurbsCurve::new(degree, knots, control, weights).map_err(|e| self.error(instance, id, e))?;
        let name = name.and_then(Value::text).unwrap_or("").to_string();
        Ok(Some((name, curve)))
    }

    fn surface(&self, id: usize, instance: &Instance) -> Result<(String, NurbsSurface)> {
        let (name, degrees, net, u_mult, v_mult, u_knots, v_knots, weights) = if instance.parts.len() == 1 {
            let p = instance.parts[0].1.as_slice();
            (
                p.first(),
                (p.get(1), p.get(2)),
                p.get(3),
                p.get(8),
                p.get(9),
                p.get(10),
                p.get(11),
                None,
            )
        } else {
            let b = instance.part("B_SPLINE_SURFACE").ok_or_else(|| {
                self.error(
                    instance,
                    id,
                    "a complex B-spline surface without B_SPLINE_SURFACE",
                )
            })?;
            let k = instance.part("B_SPLINE_SURFACE_WITH_KNOTS").unwrap_or(&[]);
            let name = instance.part("REPRESENTATION_ITEM").and_then(|r| r.first());
            let weights = instance.part("RATIONAL_B_SPLINE_SURFACE").and_then(|r| r.first());
            (
                name,
                (b.first(), b.get(1)),
                b.get(2),
                k.first(),
                k.get(1),
                k.get(2),
                k.get(3),
                weights,
            )
        };
        let degree_u = self.integer(degrees.0, "degree in u", instance, id)?;
        let degree_v = self.integer(degrees.1, "degree in v", instance, id)?;
        let rows = net
            .and_then(Value::list)
            .ok_or_else(|| self.error(instance, id, "control points: expected a list of lists"))?;
        let mut control = Vec::with_capacity(rows.len());
        for row in rows {
            let refs = row
                .list()
                .ok_or_else(|| self.error(instance, id, "control points: expected a list of lists"))?;
            let mut points = Vec::with_capacity(refs.len());
            for r in refs {
                points.push(
                    self.point(r, instance, id)?
                        .ok_or_else(|| self.error(instance, id, "a surface control point is 2D"))?,
                );
            }
            control.push(points);
        }
        let knots_u = self.knots(u_mult, u_knots, instance, id)?;
        let knots_v = self.knots(v_mult, v_knots, instance, id)?;
        let weights = match weights {
            Some(w) => {
                let rows = w
                    .list()
                    .ok_or_else(|| self.error(instance, id, "weights: expected a list of lists"))?;
                rows.iter()
                    .map(|row| self.numbers(Some(row), "weights", instance, id))
                    .collect::<Result<Vec<_>>>()?
            }
            None => control.iter().map(|row| vec![1.0; row.len()]).collect(),
        };
        let surface = NurbsSurface::new(degree_u, degree_v, knots_u, knots_v, control, weights)
            .map_err(|e| self.error(instance, id, e))?;
        let name = name.and_then(Value::text).unwrap_or("").to_string();
        Ok((name, surface))
    }

    /// The unit of the model: the first length unit that is not the base of a
    /// conversion-based one.
    fn units(&self) -> Units {
        let bases: HashSet<usize> = self
            .instances
            .values()
            .filter_map(|i| i.part("LENGTH_MEASURE_WITH_UNIT"))
            .filter_map(|p| p.get(1).and_then(Value::reference))
            .collect();
        for (id, instance) in &self.instances {
            if instance.part("LENGTH_UNIT").is_none() || bases.contains(id) {
                continue;
            }
            if let Some(name) = instance
                .part("CONVERSION_BASED_UNIT")
                .and_then(|p| p.first())
                .and_then(Value::text)
            {
                return match name.to_ascii_uppercase().as_str() {
                    "INCH" | "INCHES" => Units::Inch,
                    "FOOT" | "FEET" => Units::Foot,
                    _ => Units::default(),
                };
            }
            if let Some(si) = instance.part("SI_UNIT") {
                return match si.first().and_then(Value::enumeration) {
                    Some("MILLI") => Units::Millimetre,
                    Some("CENTI") => Units::Centimetre,
                    Some("MICRO") => Units::Micrometre,
                    None => Units::Metre,
                    Some(_) => Units::default(),
                };
            }
        }
        Units::default()
    }

    fn tolerance(&self) -> f64 {
        self.instances
            .values()
            .filter_map(|i| i.part("UNCERTAINTY_MEASURE_WITH_UNIT"))
            .find_map(|p| p.first().and_then(Value::number))
            .unwrap_or(0.0)
    }
}

/// The parameter trims of every `TRIMMED_CURVE`, by basis curve.
fn trims(instances: &BTreeMap<usize, Instance>) -> HashMap<usize, (f64, f64)> {
    let parameter = |v: &Value| -> Option<f64> {
        v.list()?.iter().find_map(|item| match item {
            Value::Typed(name, inner) if name == "PARAMETER_VALUE" => inner.first()?.number(),
            _ => None,
        })
    };
    instances
        .values()
        .filter_map(|i| i.part("TRIMMED_CURVE"))
        .filter_map(|p| {
            let basis = p.get(1)?.reference()?;
            let (a, b) = (parameter(p.get(2)?)?, parameter(p.get(3)?)?);
            Some((basis, (a.min(b), a.max(b))))
        })
        .collect()
}

/// The curve on [a, b] ⊂ its domain, exactly: a and b inserted to multiplicity p (The NURBS
/// Book A5.1), then the control points and knots between them kept.
pub(crate) fn restrict(curve: &NurbsCurve<3>, a: f64, b: f64) -> curve_repr::Result<NurbsCurve<3>> {
    let (start, end) = curve.domain();
    let (a, b) = (a.max(start), b.min(end));
    if a >= b || a.is_nan() || b.is_nan() || (a == start && b == end) {
        return Ok(curve.clone());
    }
    let p = curve.degree();
    let mut c = curve.clone();
    for t in [a, b] {
        if t > start && t < end {
            let s = c.knots().iter().filter(|&&k| k == t).count();
            if s < p {
                c = c.insert_knot(t, p - s)?;
            }
        }
    }
    let knots = c.knots();
    // k: the last index of a; l: the first index of b.
    let k = knots.iter().rposition(|&u| u == a).unwrap_or(p);
    let l = knots.iter().position(|&u| u == b).unwrap_or(knots.len() - p - 1);
    let mut new_knots = vec![a; p + 1];
    new_knots.extend_from_slice(&knots[k + 1..l]);
    new_knots.extend(std::iter::repeat_n(b, p + 1));
    let range = k - p..l;
    NurbsCurve::new(
        p,
        new_knots,
        c.control_points()[range.clone()].to_vec(),
        c.weights()[range].to_vec(),
    )
}

/// Reads every B-spline curve and surface of a STEP file (see the [module
/// documentation](super)). Fails with [`Error::Parse`] naming the line on bad syntax or a
/// B-spline whose data are wrong; a file without one reads as an empty model. O(size).
pub fn read(text: &str) -> Result<CadModel> {
    let reader = Reader {
        instances: parse(text)?,
    };
    let boundaries: HashSet<usize> = reader
        .instances
        .values()
        .filter(|i| i.part("SURFACE_CURVE").is_some() || i.part("SEAM_CURVE").is_some())
        .filter_map(|i| {
            let p = i.part("SURFACE_CURVE").or_else(|| i.part("SEAM_CURVE"))?;
            p.get(1)?.reference()
        })
        .collect();
    let trims = trims(&reader.instances);
    let mut model = CadModel {
        curves: Vec::new(),
        surfaces: Vec::new(),
        units: reader.units(),
        tolerance: reader.tolerance(),
    };
    for (&id, instance) in &reader.instances {
        if instance.part("B_SPLINE_CURVE_WITH_KNOTS").is_some() && !boundaries.contains(&id) {
            if let Some((name, curve)) = reader.curve(id, instance)? {
                let curve = match trims.get(&id) {
                    Some(&(a, b)) => restrict(&curve, a, b).map_err(|e| reader.error(instance, id, e))?,
                    None => curve,
                };
                model.curves.push(CadCurve::new(curve).with_name(name));
            }
        } else if instance.part("B_SPLINE_SURFACE_WITH_KNOTS").is_some() {
            let (name, surface) = reader.surface(id, instance)?;
            model.surfaces.push(CadSurface::new(surface).with_name(name));
        }
    }
    Ok(model)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn restriction_keeps_the_curve_between_the_trims() {
        let curve = NurbsCurve::new(
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 0.7, 1.0, 1.0, 1.0, 1.0],
            vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(1.0, 2.0, 0.0),
                Vec3::new(2.0, -1.0, 1.0),
                Vec3::new(3.0, 0.5, 0.0),
                Vec3::new(4.0, 2.0, -1.0),
                Vec3::new(5.0, 0.0, 0.0),
            ],
            vec![1.0, 2.0, 1.0, 0.5, 1.0, 1.0],
        )
        .unwrap();
        for (a, b) in [(0.2, 0.9), (0.4, 0.7), (0.0, 0.55), (0.3, 1.0)] {
            let part = restrict(&curve, a, b).unwrap();
            assert_eq!(part.domain(), (a, b));
            for k in 0..=50 {
                let t = a + (b - a) * k as f64 / 50.0;
                assert!(
                    (part.point(t) - curve.point(t)).norm() < 1e-13,
                    "[{a}, {b}] at {t}"
                );
            }
        }
        assert_eq!(restrict(&curve, -1.0, 2.0).unwrap(), curve);
    }
}
