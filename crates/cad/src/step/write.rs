//! The STEP writer.

use curve_repr::Vec3;

use crate::model::{CadCurve, CadModel, CadSurface};
use crate::number::real;
use crate::options::{ascii, StepSchema, WriteOptions};
use crate::{Result, Units};

/// Instances being written, numbered from 1 in order.
struct Data {
    lines: Vec<String>,
}

impl Data {
    /// Adds an instance and returns its number.
    fn add(&mut self, body: String) -> usize {
        self.lines.push(body);
        self.lines.len()
    }

    /// Reserves a number for an instance written later (it refers to later ones).
    fn reserve(&mut self) -> usize {
        self.add(String::new())
    }

    fn set(&mut self, id: usize, body: String) {
        self.lines[id - 1] = body;
    }
}

/// A STEP string literal.
fn text(value: &str) -> String {
    format!("'{}'", ascii(value, 200))
}

fn logical(value: bool) -> &'static str {
    if value {
        ".T."
    } else {
        ".F."
    }
}

/// `(a,b,…)`, broken after every eight items so that lines stay readable.
fn list<T: AsRef<str>>(items: &[T]) -> String {
    let mut out = String::from("(");
    for (i, item) in items.iter().enumerate() {
        if i > 0 {
            out.push(',');
            if i % 8 == 0 {
                out.push_str("\n    ");
            }
        }
        out.push_str(item.as_ref());
    }
    out.push(')');
    out
}

fn reference(id: usize) -> String {
    format!("#{id}")
}

/// Distinct knots and their multiplicities.
fn multiplicities(knots: &[f64]) -> (Vec<String>, Vec<String>) {
    let mut values: Vec<f64> = Vec::new();
    let mut counts: Vec<usize> = Vec::new();
    for &k in knots {
        match values.last() {
            Some(&last) if last == k => *counts.last_mut().unwrap_or(&mut 0) += 1,
            _ => {
                values.push(k);
                counts.push(1);
            }
        }
    }
    (
        counts.iter().map(ToString::to_string).collect(),
        values.iter().map(|&v| real(v)).collect(),
    )
}

fn point(data: &mut Data, p: &Vec3) -> usize {
    data.add(format!(
        "CARTESIAN_POINT('',({},{},{}))",
        real(p.x),
        real(p.y),
        real(p.z)
    ))
}

/// `B_SPLINE_CURVE_WITH_KNOTS`, or the complex instance with `RATIONAL_B_SPLINE_CURVE`
/// when the weights differ (entity names in alphabetical order, as Part 21 requires).
fn curve(data: &mut Data, curve: &CadCurve) -> usize {
    let c = &curve.curve;
    let points: Vec<String> = c
        .control_points()
        .iter()
        .map(|p| reference(point(data, p)))
        .collect();
    let (counts, values) = multiplicities(c.knots());
    let closed = logical(curve.is_closed());
    let name = text(&curve.name);
    let degree = c.degree();
    if curve.is_polynomial() {
        data.add(format!(
            "B_SPLINE_CURVE_WITH_KNOTS({name},{degree},{},.UNSPECIFIED.,{closed},.F.,\n  {},\n  {},.UNSPECIFIED.)",
            list(&points),
            list(&counts),
            list(&values)
        ))
    } else {
        let weights: Vec<String> = c.weights().iter().map(|&w| real(w)).collect();
        data.add(format!(
            "( BOUNDED_CURVE() B_SPLINE_CURVE({degree},{},.UNSPECIFIED.,{closed},.F.)\n  \
             B_SPLINE_CURVE_WITH_KNOTS({},{},.UNSPECIFIED.)\n  CURVE() GEOMETRIC_REPRESENTATION_ITEM()\n  \
             RATIONAL_B_SPLINE_CURVE({})\n  REPRESENTATION_ITEM({name}) )",
            list(&points),
            list(&counts),
            list(&values),
            list(&weights)
        ))
    }
}

/// `B_SPLINE_SURFACE_WITH_KNOTS`, or the rational complex instance. The control point list
/// runs over i (along u) outside, j (along v) inside.
fn surface(data: &mut Data, surface: &CadSurface) -> usize {
    let s = &surface.surface;
    let (p, q) = s.degrees();
    let (ku, kv) = s.knot_vectors();
    let rows: Vec<String> = surface
        .control_rows()
        .iter()
        .map(|row| {
            let refs: Vec<String> = row.iter().map(|c| reference(point(data, c))).collect();
            list(&refs)
        })
        .collect();
    let net = format!("({})", rows.join(",\n  "));
    let (u_counts, u_values) = multiplicities(ku.knots());
    let (v_counts, v_values) = multiplicities(kv.knots());
    let name = text(&surface.name);
    if surface.is_polynomial() {
        data.add(format!(
            "B_SPLINE_SURFACE_WITH_KNOTS({name},{p},{q},\n  {net},\n  .UNSPECIFIED.,.F.,.F.,.F.,{},{},\n  {},\n  {},.UNSPECIFIED.)",
            list(&u_counts),
            list(&v_counts),
            list(&u_values),
            list(&v_values)
        ))
    } else {
        let weights: Vec<String> = surface
            .weight_rows()
            .iter()
            .map(|row| {
                let w: Vec<String> = row.iter().map(|&v| real(v)).collect();
                list(&w)
            })
            .collect();
        data.add(format!(
            "( BOUNDED_SURFACE() B_SPLINE_SURFACE({p},{q},\n  {net},\n  .UNSPECIFIED.,.F.,.F.,.F.)\n  \
             B_SPLINE_SURFACE_WITH_KNOTS({},{},\n  {},\n  {},.UNSPECIFIED.)\n  \
             GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(({}))\n  REPRESENTATION_ITEM({name}) SURFACE() )",
            list(&u_counts),
            list(&v_counts),
            list(&u_values),
            list(&v_values),
            weights.join(",\n  ")
        ))
    }
}

/// The length unit instance (and those it needs).
fn length_unit(data: &mut Data, units: Units) -> usize {
    match (units.step_prefix(), units.step_conversion_name()) {
        (Some(prefix), _) => data.add(format!(
            "( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT({prefix},.METRE.) )"
        )),
        (None, Some(name)) => {
            let millimetre = data.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )".into());
            let measure = data.add(format!(
                "LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{millimetre})",
                real(units.millimetres())
            ));
            let exponents = data.add("DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.)".into());
            data.add(format!(
                "( CONVERSION_BASED_UNIT('{name}',#{measure}) LENGTH_UNIT() NAMED_UNIT(#{exponents}) )"
            ))
        }
        (None, None) => data.add("( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )".into()),
    }
}

/// The model as an ISO 10303-21 file of AP214 or AP242 (see the [module documentation](super)).
/// O(size of the model).
pub fn write(model: &CadModel, options: &WriteOptions) -> Result<String> {
    let version = env!("CARGO_PKG_VERSION");
    let (schema, protocol, year, application) = match options.step_schema {
        StepSchema::Ap214 => (
            "AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }",
            "automotive_design",
            2000,
            "core data for automotive mechanical design processes",
        ),
        StepSchema::Ap242 => (
            "AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }",
            "ap242_managed_model_based_3d_engineering",
            2013,
            "Managed model based 3d engineering",
        ),
    };
    let product_name = model
        .curves
        .iter()
        .map(|c| c.name.as_str())
        .chain(model.surfaces.iter().map(|s| s.name.as_str()))
        .find(|n| !n.is_empty())
        .unwrap_or("faired");
    let mut data = Data { lines: Vec::new() };
    let application_context = data.reserve();
    data.set(
        application_context,
        format!("APPLICATION_CONTEXT({})", text(application)),
    );
    data.add(format!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','{protocol}',{year},#{application_context})"
    ));
    let product_context = data.add(format!("PRODUCT_CONTEXT('',#{application_context},'mechanical')"));
    let product = data.add(format!(
        "PRODUCT({},{},'faired by fair',(#{product_context}))",
        text(product_name),
        text(product_name)
    ));
    data.add(format!("PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#{product}))"));
    let formation = data.add(format!("PRODUCT_DEFINITION_FORMATION('','',#{product})"));
    let definition_context = data.add(format!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{application_context},'design')"
    ));
    let definition = data.add(format!(
        "PRODUCT_DEFINITION('design','',#{formation},#{definition_context})"
    ));
    let shape = data.add(format!("PRODUCT_DEFINITION_SHAPE('','',#{definition})"));
    let representation = data.reserve();
    data.add(format!(
        "SHAPE_DEFINITION_REPRESENTATION(#{shape},#{representation})"
    ));
    // Units and uncertainty.
    let length = length_unit(&mut data, model.units);
    let angle = data.add("( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) )".into());
    let solid = data.add("( NAMED_UNIT(*) SI_UNIT($,.STERADIAN.) SOLID_ANGLE_UNIT() )".into());
    let uncertainty = data.add(format!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({}),#{length},'distance_accuracy_value','confusion accuracy')",
        real(model.tolerance)
    ));
    let context = data.add(format!(
        "( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{uncertainty}))\n  \
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid}))\n  \
         REPRESENTATION_CONTEXT('Context #1','3D Context with UNIT and UNCERTAINTY') )"
    ));
    let origin = data.add("CARTESIAN_POINT('',(0.,0.,0.))".into());
    let axis = data.add("DIRECTION('',(0.,0.,1.))".into());
    let reference_direction = data.add("DIRECTION('',(1.,0.,0.))".into());
    let placement = data.add(format!(
        "AXIS2_PLACEMENT_3D('',#{origin},#{axis},#{reference_direction})"
    ));
    let mut items: Vec<String> = model
        .curves
        .iter()
        .map(|c| reference(curve(&mut data, c)))
        .collect();
    items.extend(model.surfaces.iter().map(|s| reference(surface(&mut data, s))));
    let name = text(product_name);
    if model.surfaces.is_empty() {
        let set = data.add(format!("GEOMETRIC_CURVE_SET('',{})", list(&items)));
        data.set(
            representation,
            format!(
                "GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION({name},(#{placement},#{set}),#{context})"
            ),
        );
    } else {
        let set = data.add(format!("GEOMETRIC_SET('',{})", list(&items)));
        data.set(
            representation,
            format!(
                "GEOMETRICALLY_BOUNDED_SURFACE_SHAPE_REPRESENTATION({name},(#{placement},#{set}),#{context})"
            ),
        );
    }
    let mut out = String::new();
    out.push_str("ISO-10303-21;\nHEADER;\n");
    out.push_str("FILE_DESCRIPTION(('fair: faired curves and surfaces as exact B-splines'),'2;1');\n");
    out.push_str(&format!(
        "FILE_NAME({},'{}',({}),(''),'fair-cad {version}','fair {version}','');\n",
        text(&options.file_name),
        options.timestamp.iso(),
        text(&options.author)
    ));
    out.push_str(&format!("FILE_SCHEMA(('{schema}'));\nENDSEC;\nDATA;\n"));
    for (i, line) in data.lines.iter().enumerate() {
        out.push_str(&format!("#{} = {};\n", i + 1, line));
    }
    out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn knots_become_distinct_values_and_multiplicities() {
        let (counts, values) = multiplicities(&[0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0]);
        assert_eq!(counts, vec!["4", "2", "4"]);
        assert_eq!(values, vec!["0.", "0.5", "1."]);
        assert_eq!(list(&["a", "b"]), "(a,b)");
        assert_eq!(text("it's"), "'it_s'");
    }
}
