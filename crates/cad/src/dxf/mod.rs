//! DXF (AutoCAD R2000, `AC1015`): the `SPLINE` entity.
//!
//! Written by hand rather than with the `dxf` crate: that crate prints every real with 12
//! fixed decimals (a knot of 1.2345678901234567e-5 would come back as 1.2346e-5), and its
//! build pulls in image and date libraries; the group codes of one entity and the table
//! boilerplate of a drawing are short.
//!
//! - [`write()`]: a complete R2000 drawing (header with `$INSUNITS` and `$MEASUREMENT`, the
//!   symbol tables, model and paper space blocks, a root dictionary) whose ENTITIES section
//!   holds one `SPLINE` per curve: degree, knots, control points, weights when the curve is
//!   rational, the planar flag and normal (0, 0, 1) for a 2D curve; each named curve on a
//!   layer of its name. Reals with the shortest digits that read back bit for bit. DXF has
//!   no exact B-spline surface (only ACIS bodies), so a model with surfaces is refused.
//! - [`read`]: every `SPLINE` of the ENTITIES section with control points (a spline given
//!   by fit points only is refused: its shape is whatever the reading program makes of the
//!   fit points), its layer as its name, and the unit from `$INSUNITS`.

use curve_repr::{NurbsCurve, Vec3};

use crate::model::{CadCurve, CadModel};
use crate::number::{parse_real, real};
use crate::options::WriteOptions;
use crate::{Error, Result, Units};

const FORMAT: &str = "DXF";

/// Group codes and values being written.
struct Writer {
    out: String,
    next_handle: u32,
}

impl Writer {
    fn pair(&mut self, code: u32, value: impl std::fmt::Display) {
        self.out.push_str(&format!("{code:>3}\n{value}\n"));
    }

    fn real(&mut self, code: u32, value: f64) {
        let text = real(value);
        self.pair(code, text);
    }

    fn point(&mut self, code: u32, p: &Vec3) {
        self.real(code, p.x);
        self.real(code + 10, p.y);
        self.real(code + 20, p.z);
    }

    fn handle(&mut self) -> String {
        let h = self.next_handle;
        self.next_handle += 1;
        format!("{h:X}")
    }

    /// A symbol table's header.
    fn table(&mut self, name: &str, handle: &str, count: usize) {
        self.pair(0, "TABLE");
        self.pair(2, name);
        self.pair(5, handle);
        self.pair(330, 0);
        self.pair(100, "AcDbSymbolTable");
        self.pair(70, count);
    }

    /// A symbol table record's common codes.
    fn record(&mut self, kind: &str, owner: &str, subclass: &str, name: &str) -> String {
        let handle = self.handle();
        self.pair(0, kind);
        self.pair(5, &handle);
        self.pair(330, owner);
        self.pair(100, "AcDbSymbolTableRecord");
        self.pair(100, subclass);
        self.pair(2, name);
        self.pair(70, 0);
        handle
    }
}

/// A layer name DXF accepts: printable ASCII without `<>/\":;?*|=',`, at most 255 characters,
/// `0` for an empty name.
fn layer_name(name: &str) -> String {
    let cleaned: String = name
        .chars()
        .map(|c| {
            if (' '..='~').contains(&c) && !"<>/\\\":;?*|=',`".contains(c) {
                c
            } else {
                '_'
            }
        })
        .take(255)
        .collect();
    if cleaned.trim().is_empty() {
        "0".into()
    } else {
        cleaned
    }
}

/// The model as an R2000 DXF drawing (see the [module documentation](self)). Fails with
/// [`Error::Unsupported`] when the model holds a surface. O(size of the model).
pub fn write(model: &CadModel, _options: &WriteOptions) -> Result<String> {
    if !model.surfaces.is_empty() {
        return Err(Error::Unsupported(
            "DXF has no exact B-spline surface entity: write surfaces as IGES or STEP".into(),
        ));
    }
    let mut w = Writer {
        out: String::new(),
        next_handle: 0x20,
    };
    let mut layers: Vec<String> = model.curves.iter().map(|c| layer_name(&c.name)).collect();
    layers.retain(|l| l != "0");
    layers.sort();
    layers.dedup();
    let (low, high) = extents(model);

    w.pair(0, "SECTION");
    w.pair(2, "HEADER");
    w.pair(9, "$ACADVER");
    w.pair(1, "AC1015");
    w.pair(9, "$HANDSEED");
    // Handles up to 0x20 are the tables and dictionaries below; records and entities follow.
    let seed = 0x20 + 16 + layers.len() as u32 + 2 * model.curves.len() as u32;
    w.pair(5, format!("{seed:X}"));
    w.pair(9, "$INSUNITS");
    w.pair(70, model.units.dxf_code());
    w.pair(9, "$MEASUREMENT");
    w.pair(70, model.units.dxf_measurement());
    w.pair(9, "$EXTMIN");
    w.point(10, &low);
    w.pair(9, "$EXTMAX");
    w.point(10, &high);
    w.pair(0, "ENDSEC");

    w.pair(0, "SECTION");
    w.pair(2, "CLASSES");
    w.pair(0, "ENDSEC");

    w.pair(0, "SECTION");
    w.pair(2, "TABLES");
    w.table("VPORT", "8", 1);
    w.record("VPORT", "8", "AcDbViewportTableRecord", "*Active");
    let centre = (low + high) * 0.5;
    w.real(10, 0.0);
    w.real(20, 0.0);
    w.real(11, 1.0);
    w.real(21, 1.0);
    w.real(12, centre.x);
    w.real(22, centre.y);
    w.real(40, ((high - low).amax() * 1.1).max(1.0));
    w.real(41, 1.5);
    w.pair(0, "ENDTAB");
    w.table("LTYPE", "2", 3);
    for name in ["ByBlock", "ByLayer", "Continuous"] {
        w.record("LTYPE", "2", "AcDbLinetypeTableRecord", name);
        w.pair(3, if name == "Continuous" { "Solid line" } else { "" });
        w.pair(72, 65);
        w.pair(73, 0);
        w.real(40, 0.0);
    }
    w.pair(0, "ENDTAB");
    w.table("LAYER", "1", 1 + layers.len());
    for name in std::iter::once("0".to_string()).chain(layers.iter().cloned()) {
        w.record("LAYER", "1", "AcDbLayerTableRecord", &name);
        w.pair(62, 7);
        w.pair(6, "Continuous");
    }
    w.pair(0, "ENDTAB");
    w.table("STYLE", "5", 1);
    w.record("STYLE", "5", "AcDbTextStyleTableRecord", "Standard");
    w.real(40, 0.0);
    w.real(41, 1.0);
    w.real(50, 0.0);
    w.pair(71, 0);
    w.real(42, 2.5);
    w.pair(3, "txt");
    w.pair(4, "");
    w.pair(0, "ENDTAB");
    w.table("VIEW", "7", 0);
    w.pair(0, "ENDTAB");
    w.table("UCS", "6", 0);
    w.pair(0, "ENDTAB");
    w.table("APPID", "3", 1);
    w.record("APPID", "3", "AcDbRegAppTableRecord", "ACAD");
    w.pair(0, "ENDTAB");
    w.table("DIMSTYLE", "4", 1);
    w.pair(100, "AcDbDimStyleTable");
    let dimstyle = w.handle();
    w.pair(0, "DIMSTYLE");
    w.pair(105, &dimstyle);
    w.pair(330, "4");
    w.pair(100, "AcDbSymbolTableRecord");
    w.pair(100, "AcDbDimStyleTableRecord");
    w.pair(2, "Standard");
    w.pair(70, 0);
    w.pair(0, "ENDTAB");
    w.table("BLOCK_RECORD", "9", 2);
    let model_space = w.record("BLOCK_RECORD", "9", "AcDbBlockTableRecord", "*Model_Space");
    let paper_space = w.record("BLOCK_RECORD", "9", "AcDbBlockTableRecord", "*Paper_Space");
    w.pair(0, "ENDTAB");
    w.pair(0, "ENDSEC");

    w.pair(0, "SECTION");
    w.pair(2, "BLOCKS");
    for (owner, name) in [(&model_space, "*Model_Space"), (&paper_space, "*Paper_Space")] {
        let begin = w.handle();
        w.pair(0, "BLOCK");
        w.pair(5, &begin);
        w.pair(330, owner);
        w.pair(100, "AcDbEntity");
        w.pair(8, "0");
        w.pair(100, "AcDbBlockBegin");
        w.pair(2, name);
        w.pair(70, 0);
        w.point(10, &Vec3::zeros());
        w.pair(3, name);
        w.pair(1, "");
        let end = w.handle();
        w.pair(0, "ENDBLK");
        w.pair(5, &end);
        w.pair(330, owner);
        w.pair(100, "AcDbEntity");
        w.pair(8, "0");
        w.pair(100, "AcDbBlockEnd");
    }
    w.pair(0, "ENDSEC");

    w.pair(0, "SECTION");
    w.pair(2, "ENTITIES");
    for curve in &model.curves {
        spline(&mut w, curve, &model_space);
    }
    w.pair(0, "ENDSEC");

    w.pair(0, "SECTION");
    w.pair(2, "OBJECTS");
    w.pair(0, "DICTIONARY");
    w.pair(5, "C");
    w.pair(330, 0);
    w.pair(100, "AcDbDictionary");
    w.pair(281, 1);
    w.pair(3, "ACAD_GROUP");
    w.pair(350, "D");
    w.pair(0, "DICTIONARY");
    w.pair(5, "D");
    w.pair(330, "C");
    w.pair(100, "AcDbDictionary");
    w.pair(281, 1);
    w.pair(0, "ENDSEC");
    w.pair(0, "EOF");
    Ok(w.out)
}

/// One `SPLINE` entity.
fn spline(w: &mut Writer, curve: &CadCurve, owner: &str) {
    let c = &curve.curve;
    let rational = !curve.is_polynomial();
    let planar = curve.dimension == 2;
    let handle = w.handle();
    w.pair(0, "SPLINE");
    w.pair(5, &handle);
    w.pair(330, owner);
    w.pair(100, "AcDbEntity");
    w.pair(8, layer_name(&curve.name));
    w.pair(100, "AcDbSpline");
    if planar {
        w.point(210, &Vec3::new(0.0, 0.0, 1.0));
    }
    w.pair(70, 8 * u32::from(planar) + 4 * u32::from(rational));
    w.pair(71, c.degree());
    w.pair(72, c.knots().len());
    w.pair(73, c.control_points().len());
    w.pair(74, 0);
    w.real(42, 1e-10);
    w.real(43, 1e-10);
    for &k in c.knots() {
        w.real(40, k);
    }
    if rational {
        for &weight in c.weights() {
            w.real(41, weight);
        }
    }
    for p in c.control_points() {
        w.point(10, p);
    }
}

/// The bounding box of the control points (the origin for an empty model).
fn extents(model: &CadModel) -> (Vec3, Vec3) {
    let mut low = Vec3::from_element(f64::INFINITY);
    let mut high = Vec3::from_element(f64::NEG_INFINITY);
    for p in model.curves.iter().flat_map(|c| c.curve.control_points()) {
        low = low.inf(p);
        high = high.sup(p);
    }
    if low.x > high.x {
        (Vec3::zeros(), Vec3::zeros())
    } else {
        (low, high)
    }
}

/// One group: code, value, and the line of its code.
struct Group<'a> {
    code: i64,
    value: &'a str,
    line: usize,
}

fn groups(text: &str) -> Result<Vec<Group<'_>>> {
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r')).collect();
    let mut out = Vec::with_capacity(lines.len() / 2);
    let mut i = 0;
    while i + 1 < lines.len() {
        let code = lines[i].trim().parse::<i64>().map_err(|_| {
            Error::parse(
                FORMAT,
                i + 1,
                format!("`{}` is not a group code", lines[i].trim()),
            )
        })?;
        out.push(Group {
            code,
            value: lines[i + 1].trim(),
            line: i + 1,
        });
        i += 2;
    }
    if i < lines.len() && !lines[i].trim().is_empty() {
        return Err(Error::parse(FORMAT, i + 1, "a group code without a value"));
    }
    Ok(out)
}

fn number(group: &Group<'_>) -> Result<f64> {
    parse_real(group.value).ok_or_else(|| {
        Error::parse(
            FORMAT,
            group.line + 1,
            format!("group {}: `{}` is not a number", group.code, group.value),
        )
    })
}

/// Reads every `SPLINE` of the ENTITIES section (see the [module documentation](self)).
/// Fails with [`Error::Parse`] naming the line on a malformed file or spline, and
/// [`Error::Unsupported`] for a spline given by fit points only. O(size of the file).
pub fn read(text: &str) -> Result<CadModel> {
    let groups = groups(text)?;
    let mut model = CadModel {
        curves: Vec::new(),
        surfaces: Vec::new(),
        units: Units::default(),
        tolerance: 0.0,
    };
    let mut section = "";
    let mut i = 0;
    while i < groups.len() {
        let g = &groups[i];
        if g.code == 0 && g.value == "SECTION" {
            section = groups.get(i + 1).filter(|n| n.code == 2).map_or("", |n| n.value);
            i += 2;
            continue;
        }
        if section == "HEADER" && g.code == 9 && g.value == "$INSUNITS" {
            if let Some(value) = groups.get(i + 1).filter(|v| v.code == 70) {
                model.units = Units::from_dxf(number(value)? as i64).unwrap_or_default();
            }
        }
        if section == "ENTITIES" && g.code == 0 && g.value == "SPLINE" {
            let end = groups[i + 1..]
                .iter()
                .position(|h| h.code == 0)
                .map_or(groups.len(), |k| i + 1 + k);
            model.curves.push(spline_entity(&groups[i..end])?);
            i = end;
            continue;
        }
        i += 1;
    }
    Ok(model)
}

/// The curve of one `SPLINE` entity's groups (the first is `0 SPLINE`).
fn spline_entity(groups: &[Group<'_>]) -> Result<CadCurve> {
    let line = groups[0].line;
    let mut degree = None;
    let mut knots = Vec::new();
    let mut weights = Vec::new();
    let mut points: Vec<Vec3> = Vec::new();
    let mut fit_points = 0;
    let mut layer = String::new();
    let mut expected_knots = None;
    let mut expected_points = None;
    for g in &groups[1..] {
        match g.code {
            8 => layer = g.value.to_string(),
            71 => degree = Some(number(g)? as usize),
            72 => expected_knots = Some(number(g)? as usize),
            73 => expected_points = Some(number(g)? as usize),
            74 => fit_points = number(g)? as usize,
            40 => knots.push(number(g)?),
            41 => weights.push(number(g)?),
            10 => points.push(Vec3::new(number(g)?, 0.0, 0.0)),
            20 | 30 => {
                let value = number(g)?;
                let p = points.last_mut().ok_or_else(|| {
                    Error::parse(FORMAT, g.line, format!("group {} before a group 10", g.code))
                })?;
                p[(g.code / 10 - 1) as usize] = value;
            }
            _ => {}
        }
    }
    if points.is_empty() {
        return Err(if fit_points > 0 {
            Error::Unsupported(format!(
                "DXF line {line}: the SPLINE is given by {fit_points} fit points only; its shape depends on the program that fits them"
            ))
        } else {
            Error::parse(FORMAT, line, "a SPLINE without control points")
        });
    }
    for (what, expected, got) in [
        ("knots", expected_knots, knots.len()),
        ("control points", expected_points, points.len()),
    ] {
        if let Some(expected) = expected.filter(|&e| e != got) {
            return Err(Error::parse(
                FORMAT,
                line,
                format!("the SPLINE announces {expected} {what} and has {got}"),
            ));
        }
    }
    if weights.is_empty() {
        weights = vec![1.0; points.len()];
    }
    let degree = degree.ok_or_else(|| Error::parse(FORMAT, line, "a SPLINE without a degree (group 71)"))?;
    let curve = NurbsCurve::new(degree, knots, points, weights)
        .map_err(|e| Error::parse(FORMAT, line, format!("SPLINE: {e}")))?;
    let name = if layer == "0" { String::new() } else { layer };
    Ok(CadCurve::new(curve).with_name(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_names_are_cleaned() {
        assert_eq!(layer_name("wl 03/a:b"), "wl 03_a_b");
        assert_eq!(layer_name(""), "0");
        assert_eq!(layer_name("  "), "0");
    }

    #[test]
    fn fit_point_splines_are_refused_and_bad_groups_name_their_line() {
        let fit = "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\n3\n74\n2\n11\n0.0\n21\n0.0\n11\n1.0\n21\n1.0\n0\nENDSEC\n0\nEOF\n";
        assert!(matches!(read(fit), Err(Error::Unsupported(_))));
        let bad = "0\nSECTION\n2\nENTITIES\n0\nSPLINE\n71\nthree\n0\nENDSEC\n";
        assert!(matches!(read(bad), Err(Error::Parse { line: 8, .. })));
        assert!(matches!(read("x\ny\n"), Err(Error::Parse { line: 1, .. })));
    }
}
