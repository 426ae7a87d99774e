//! The IGES writer.

use curve_repr::Curve;

use crate::model::{CadCurve, CadModel, CadSurface};
use crate::number::real;
use crate::options::{ascii, WriteOptions};
use crate::Result;

/// Data columns of a Global line (1–72) and of a Parameter line (1–64).
const GLOBAL_WIDTH: usize = 72;
const PARAMETER_WIDTH: usize = 64;

/// An IGES string constant: `nH` followed by the n characters (empty for an empty string,
/// which IGES reads as the default).
fn hollerith(text: &str) -> String {
    let text = ascii(text, 60);
    if text.is_empty() {
        String::new()
    } else {
        format!("{}H{}", text.len(), text)
    }
}

/// Packs parameters, each followed by `,` (the last by `;`), into lines of at most `width`
/// characters without splitting a parameter.
fn pack(parameters: &[String], width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for (i, p) in parameters.iter().enumerate() {
        let delimiter = if i + 1 == parameters.len() { ';' } else { ',' };
        let token = format!("{p}{delimiter}");
        if !line.is_empty() && line.len() + token.len() > width {
            lines.push(std::mem::take(&mut line));
        }
        line.push_str(&token);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// One entity: its type number, form, label and parameters (after the type number).
struct Entity {
    kind: u32,
    label: String,
    parameters: Vec<String>,
}

fn int(value: usize) -> String {
    value.to_string()
}

fn flag(value: bool) -> String {
    u8::from(value).to_string()
}

/// Entity 126 (IGES 5.3 §4.23): K, M, PROP1–4, knots T(−M)…T(N+M), weights W(0…K),
/// control points (X, Y, Z)(0…K), V(0), V(1), and the unit normal of a planar curve.
fn curve_entity(curve: &CadCurve) -> Entity {
    let c = &curve.curve;
    let count = c.control_points().len();
    let planar = curve.dimension == 2;
    let mut p = vec![
        int(count - 1),
        int(c.degree()),
        flag(planar),
        flag(curve.is_closed()),
        flag(curve.is_polynomial()),
        flag(false),
    ];
    p.extend(c.knots().iter().map(|&k| real(k)));
    p.extend(c.weights().iter().map(|&w| real(w)));
    for q in c.control_points() {
        p.extend([real(q.x), real(q.y), real(q.z)]);
    }
    let (start, end) = c.domain();
    p.extend([real(start), real(end)]);
    if planar {
        p.extend([real(0.0), real(0.0), real(1.0)]);
    } else {
        p.extend([real(0.0), real(0.0), real(0.0)]);
    }
    Entity {
        kind: 126,
        label: curve.name.clone(),
        parameters: p,
    }
}

/// Entity 128 (IGES 5.3 §4.24): K1, K2, M1, M2, PROP1–5, knots S and T, weights and control
/// points with the u index i varying fastest, U(0), U(1), V(0), V(1).
fn surface_entity(surface: &CadSurface) -> Entity {
    let s = &surface.surface;
    let (rows, columns) = s.net_size();
    let (p, q) = s.degrees();
    let (ku, kv) = s.knot_vectors();
    let mut out = vec![
        int(rows - 1),
        int(columns - 1),
        int(p),
        int(q),
        flag(false),
        flag(false),
        flag(surface.is_polynomial()),
        flag(false),
        flag(false),
    ];
    out.extend(ku.knots().iter().map(|&k| real(k)));
    out.extend(kv.knots().iter().map(|&k| real(k)));
    for j in 0..columns {
        for i in 0..rows {
            out.push(real(s.weight(i, j).unwrap_or(1.0)));
        }
    }
    for j in 0..columns {
        for i in 0..rows {
            let c = s.control_point(i, j).unwrap_or_default();
            out.extend([real(c.x), real(c.y), real(c.z)]);
        }
    }
    let ((u0, u1), (v0, v1)) = (ku.domain(), kv.domain());
    out.extend([real(u0), real(u1), real(v0), real(v1)]);
    Entity {
        kind: 128,
        label: surface.name.clone(),
        parameters: out,
    }
}

/// The 8-character entity label of a name: its first letters and digits, upper case.
fn label(name: &str) -> String {
    name.chars()
        .filter(char::is_ascii_alphanumeric)
        .take(8)
        .collect::<String>()
        .to_ascii_uppercase()
}

/// The model as an IGES 5.3 file (see the [module documentation](super)). O(size of the model).
pub fn write(model: &CadModel, options: &WriteOptions) -> Result<String> {
    let version = env!("CARGO_PKG_VERSION");
    let date = hollerith(&options.timestamp.iges());
    let global = vec![
        "1H,".to_string(),
        "1H;".to_string(),
        hollerith("fair"),
        hollerith(&options.file_name),
        hollerith(&format!("fair {version}")),
        hollerith(&format!("fair-cad {version}")),
        "32".into(),
        "308".into(),
        "15".into(),
        "308".into(),
        "15".into(),
        hollerith("fair"),
        real(1.0),
        model.units.iges_flag().to_string(),
        hollerith(model.units.iges_name()),
        "1".into(),
        real(1.0),
        date.clone(),
        real(model.tolerance),
        real(model.max_coordinate()),
        hollerith(&options.author),
        String::new(),
        "11".into(),
        "0".into(),
        date,
    ];
    let entities: Vec<Entity> = model
        .curves
        .iter()
        .map(curve_entity)
        .chain(model.surfaces.iter().map(surface_entity))
        .collect();
    let mut out = String::new();
    let start = [
        "fair: faired curves and surfaces as exact B-splines (entities 126, 128)",
        "read back with fair_cad::iges::read; opens in any IGES 5.3 reader",
    ];
    for (i, line) in start.iter().enumerate() {
        out.push_str(&format!("{:<72}S{:07}\n", line, i + 1));
    }
    let global_lines = pack(&global, GLOBAL_WIDTH);
    for (i, line) in global_lines.iter().enumerate() {
        out.push_str(&format!("{:<72}G{:07}\n", line, i + 1));
    }
    let mut directory = String::new();
    let mut parameters = String::new();
    let mut parameter_line = 1;
    for (k, entity) in entities.iter().enumerate() {
        let de = 2 * k + 1;
        let mut tokens = vec![entity.kind.to_string()];
        tokens.extend(entity.parameters.iter().cloned());
        let lines = pack(&tokens, PARAMETER_WIDTH);
        directory.push_str(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:07}\n",
            entity.kind, parameter_line, 0, 0, 0, 0, 0, 0, "00000000", de
        ));
        directory.push_str(&format!(
            "{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}{:>8}D{:07}\n",
            entity.kind,
            0,
            0,
            lines.len(),
            0,
            "",
            "",
            label(&entity.label),
            0,
            de + 1
        ));
        for line in lines {
            parameters.push_str(&format!("{:<64} {:07}P{:07}\n", line, de, parameter_line));
            parameter_line += 1;
        }
    }
    out.push_str(&directory);
    out.push_str(&parameters);
    let terminate = format!(
        "S{:07}G{:07}D{:07}P{:07}",
        start.len(),
        global_lines.len(),
        2 * entities.len(),
        parameter_line - 1
    );
    out.push_str(&format!("{:<72}T{:07}\n", terminate, 1));
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_pack_into_lines_without_splitting() {
        let p: Vec<String> = (0..40).map(|i| format!("{}.5", i * 1000)).collect();
        let lines = pack(&p, 64);
        assert!(lines.iter().all(|l| l.len() <= 64));
        assert!(lines.last().unwrap().ends_with(';'));
        assert_eq!(lines.concat().matches(',').count(), 39);
        assert_eq!(hollerith("MM"), "2HMM");
        assert_eq!(hollerith(""), "");
        assert_eq!(label("wl_03 hull"), "WL03HULL");
    }
}
