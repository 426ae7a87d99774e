//! Writers of a faired table: the table in the input's layout, every line as its own CSV, the
//! JSON report, the hull as IGES or STEP (through the CAD crate) and an SVG of the three views.

use std::fmt::Write as _;
use std::path::Path;

use cad::{CadModel, CadSurface, Format, Shape, Units, WriteOptions};
use curve_repr::{NurbsSurface, Vec3};

use crate::error::{io, Error, Result};
use crate::lofting::Faired;
use crate::table::{Coord, Kind};

fn fmt_value(v: f64, step: f64) -> String {
    let dec = ((-step.log10()).ceil().max(0.0) as usize + 4).min(12);
    let s = format!("{v:.dec$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" || s.is_empty() {
        "0".into()
    } else {
        s
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The faired table as text in the input's layout: every row of the input in its order, a value
/// that did not move keeping its text, a moved one written with four decimals more than the step.
pub fn table_text(f: &Faired) -> String {
    let t = &f.table;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{}",
        t.header
            .iter()
            .map(|h| csv_field(h))
            .collect::<Vec<_>>()
            .join(",")
    );
    for r in &t.records {
        let mut fields = r.fields.clone();
        for &(cell, coord, col) in &r.refs {
            let k = match coord {
                Coord::X => 0,
                Coord::Y => 1,
                Coord::Z => 2,
            };
            let new = f.values[cell][k];
            let old = t.cells[cell].get(coord);
            if new.is_finite() && new != old && col < fields.len() {
                fields[col] = fmt_value(new, f.step);
            }
        }
        let _ = writeln!(
            out,
            "{}",
            fields.iter().map(|s| csv_field(s)).collect::<Vec<_>>().join(",")
        );
    }
    out
}

/// Writes the faired table in the input's layout, completely or not at all
/// ([`cad::atomic`]).
pub fn write_table(f: &Faired, path: impl AsRef<Path>) -> Result<()> {
    cad::atomic::write_text(path, table_text(f)).map_err(|e| written(&e))
}

/// The crate's error for an output that could not be written.
pub(crate) fn written(e: &cad::atomic::WriteError) -> Error {
    Error::Io {
        path: e.target.name(),
        message: e.error.to_string(),
    }
}

fn file_name(label: &str) -> String {
    label
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect::<String>()
        .trim_matches('_')
        .to_string()
}

/// Writes every line as its own CSV `x,y,z` (faired offsets sorted by x) as
/// `<dir>/line_<label>_<kind>.csv`, and every station as `<dir>/station_<index>.csv` (sorted by
/// z), creating `dir` if need be; all files or none ([`cad::atomic::Outputs`]). Returns the
/// files written.
pub fn write_lines(f: &Faired, dir: impl AsRef<Path>) -> Result<Vec<String>> {
    let dir = dir.as_ref();
    std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
    let files = lines_files(f);
    let mut outputs = cad::atomic::Outputs::new();
    for (name, text) in &files {
        outputs.add_text(cad::atomic::Target::File(dir.join(name)), text);
    }
    outputs.commit().map_err(|e| written(&e))?;
    Ok(files.into_iter().map(|(name, _)| name).collect())
}

/// What [`write_lines`] writes: each file's name and text, lines first, then stations. O(offsets).
pub fn lines_files(f: &Faired) -> Vec<(String, String)> {
    let t = &f.table;
    let mut written = Vec::new();
    let num = |v: f64| {
        if v.is_finite() {
            fmt_value(v, f.step)
        } else {
            String::new()
        }
    };
    let mut put = |name: String, idx: Vec<usize>| {
        let mut s = String::from("x,y,z\n");
        for i in idx {
            let v = f.values[i];
            let _ = writeln!(s, "{},{},{}", num(v[0]), num(v[1]), num(v[2]));
        }
        written.push((name, s));
    };
    for (li, l) in t.lines.iter().enumerate() {
        let kind = serde_json::to_value(l.kind)
            .ok()
            .and_then(|v| v.as_str().map(String::from))
            .unwrap_or_default();
        put(
            format!("line_{}_{}.csv", file_name(&l.label), kind),
            t.line_cells(li),
        );
    }
    for si in t.stations.keys() {
        let mut idx: Vec<usize> = (0..t.cells.len())
            .filter(|&i| t.cells[i].station_index == *si && t.cells[i].on_station)
            .filter(|&i| f.values[i][1].is_finite() && f.values[i][2].is_finite())
            .collect();
        idx.sort_by(|&a, &b| f.values[a][2].total_cmp(&f.values[b][2]));
        put(format!("station_{si:02}.csv"), idx);
    }
    written
}

/// The report as pretty JSON.
pub fn report_json(f: &Faired) -> String {
    serde_json::to_string_pretty(&f.report).unwrap_or_default()
}

fn units(u: Option<&str>) -> Units {
    match u {
        Some("in") => Units::Inch,
        Some("ft") => Units::Foot,
        Some("m") => Units::Metre,
        Some("cm") => Units::Centimetre,
        _ => Units::Millimetre,
    }
}

/// The hull's surfaces as a CAD model: each bicubic B-spline v = S(x, u) written exactly as a
/// B-spline surface with control points at the Greville abscissae (x̄ᵢ, ūⱼ) and value cᵢⱼ (a
/// polynomial function surface is its own control net there; where u is a fraction of the
/// knuckle's half-breadth y_k(x) = Σ dᵢ Nᵢ(x), the net's y is ūⱼ·dᵢ). Each spans the bounding box of
/// its offsets, so it runs past the stem, keel, sheer or knuckle where the hull has no offsets.
/// The unit is the table's (millimetres when unknown).
pub fn hull_model(f: &Faired) -> Result<CadModel> {
    if f.hulls.is_empty() {
        return Err(Error::Fit(
            "no hull surface: the table has no waterlines or buttocks".into(),
        ));
    }
    let name = Path::new(&f.table.path)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("hull")
        .to_string();
    let mut model: Option<CadModel> = None;
    for h in &f.hulls {
        let s = h.spline();
        let ku =
            s.ku.as_ref()
                .ok_or_else(|| Error::Fit("no hull surface".into()))?;
        let gx: Vec<f64> = (0..s.kx.count())
            .map(|i| (s.kx.t[i + 1] + s.kx.t[i + 2] + s.kx.t[i + 3]) / 3.0)
            .collect();
        let gu: Vec<f64> = (0..ku.count())
            .map(|j| (ku.t[j + 1] + ku.t[j + 2] + ku.t[j + 3]) / 3.0)
            .collect();
        let nu = ku.count();
        let net: Vec<Vec<Vec3>> = gx
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                gu.iter()
                    .enumerate()
                    .map(|(j, &u)| {
                        let v = s.c[i * nu + j];
                        if h.value() == Coord::Z {
                            // y = u·y_k(x): the product of a linear function of u and a cubic
                            // spline on the same x knots, whose control net is ūⱼ·dᵢ
                            let d = h.scale.as_ref().map_or(1.0, |k| k.c[i]);
                            Vec3::new(x, u * d, v)
                        } else {
                            Vec3::new(x, v, u)
                        }
                    })
                    .collect()
            })
            .collect();
        let weights = vec![vec![1.0; nu]; gx.len()];
        let surface = NurbsSurface::new(3, 3, s.kx.t.clone(), ku.t.clone(), net, weights)
            .map_err(|e| Error::Fit(format!("hull as a B-spline surface: {e}")))?;
        let shape = Shape::Surface(CadSurface::new(surface).with_name(format!("{name} {}", h.region())));
        match &mut model {
            None => model = Some(CadModel::of(shape, units(f.table.units.as_deref()), 0.5 * f.step)),
            Some(m) => m.push(shape),
        }
    }
    model.ok_or_else(|| Error::Fit("no hull surface".into()))
}

/// Writes the hull as IGES or STEP (from the extension: .igs/.iges, .stp/.step), completely
/// or not at all ([`cad::atomic`]).
pub fn write_hull(f: &Faired, path: impl AsRef<Path>) -> Result<()> {
    let path = path.as_ref();
    let text = hull_text(f, path)?;
    cad::atomic::write_text(path, text).map_err(|e| written(&e))
}

/// The text [`write_hull`] writes to `path` (its format from the extension, its name in the
/// header).
pub fn hull_text(f: &Faired, path: impl AsRef<Path>) -> Result<String> {
    let p = path.as_ref();
    let format = Format::from_path(p).ok_or_else(|| Error::Setting {
        name: "hull file",
        message: format!(
            "{}: the extension is none of .igs, .iges, .stp, .step, .dxf",
            p.display()
        ),
    })?;
    let model = hull_model(f)?;
    let options = WriteOptions {
        file_name: p
            .file_name()
            .and_then(|s| s.to_str())
            .unwrap_or("hull")
            .to_string(),
        timestamp: cad::Timestamp::from_unix(1_796_515_200),
        ..WriteOptions::default()
    };
    Ok(cad::write(&model, format, &options)?)
}

/// Signed curvature of the circle through three points (Menger): 4·area / (|ab|·|bc|·|ca|).
fn menger(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> f64 {
    let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    let d = |p: (f64, f64), q: (f64, f64)| ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
    let den = d(a, b) * d(b, c) * d(c, a);
    if den > 0.0 {
        2.0 * cross / den
    } else {
        0.0
    }
}

/// A curvature comb on a drawn polyline: at each interior point a tooth along the normal, of
/// length curvature × `scale`, the teeth's ends joined.
fn comb(s: &mut String, pts: &[(f64, f64)], scale: f64) {
    if pts.len() < 3 || scale == 0.0 {
        return;
    }
    let mut ends = Vec::new();
    for w in pts.windows(3) {
        let k = menger(w[0], w[1], w[2]);
        let (tx, ty) = (w[2].0 - w[0].0, w[2].1 - w[0].1);
        let n = (tx * tx + ty * ty).sqrt();
        if n == 0.0 {
            continue;
        }
        let (nx, ny) = (-ty / n, tx / n);
        let e = (w[1].0 - nx * k * scale, w[1].1 - ny * k * scale);
        let _ = writeln!(
            s,
            r##"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#c9a" stroke-width="0.3"/>"##,
            w[1].0, w[1].1, e.0, e.1
        );
        ends.push(e);
    }
    if ends.len() > 1 {
        let d: Vec<String> = ends.iter().map(|(a, b)| format!("{a:.1},{b:.1}")).collect();
        let _ = writeln!(
            s,
            r##"<polyline fill="none" stroke="#c9a" stroke-width="0.3" points="{}"/>"##,
            d.join(" ")
        );
    }
}

/// An SVG of the three views: profile (x, z) and half-breadth plan (x, y) one above the other,
/// body plan (y, z) beside them (stations aft of the middle to the right of the centreline,
/// forward ones mirrored to the left). Lines drawn through the faired offsets, each with a
/// curvature comb (the curvature of the circle through each offset and its neighbours, one scale
/// for the drawing); each flagged offset marked by a red circle at its input position and a red
/// stroke to its faired one.
pub fn svg(f: &Faired) -> String {
    let t = &f.table;
    let vals = &f.values;
    let fin = |v: f64| v.is_finite();
    let (mut x0, mut x1, mut y1, mut z0, mut z1) = (f64::MAX, f64::MIN, 0.0f64, f64::MAX, f64::MIN);
    for (c, v) in t.cells.iter().zip(vals) {
        for (a, b) in [(c.x, c.y), (v[0], v[1])] {
            x0 = x0.min(a);
            x1 = x1.max(a);
            if fin(b) {
                y1 = y1.max(b);
            }
        }
        for z in [c.z, v[2]] {
            if fin(z) {
                z0 = z0.min(z);
                z1 = z1.max(z);
            }
        }
    }
    if z0 > z1 {
        (z0, z1) = (0.0, 1.0);
    }
    let w = 800.0;
    let sc = w / (x1 - x0).max(1e-12);
    let (hp, hb) = ((z1 - z0) * sc, y1 * sc);
    let bw = 2.0 * y1 * sc;
    let pad = 10.0;
    let total_w = w + bw + 3.0 * pad;
    let total_h = hp + hb + 3.0 * pad;
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {total_w:.1} {total_h:.1}" font-size="8">"#
    );
    let prof = |x: f64, z: f64| (pad + (x - x0) * sc, pad + (z1 - z) * sc);
    let plan = |x: f64, y: f64| (pad + (x - x0) * sc, 2.0 * pad + hp + hb - y * sc);
    let xm = 0.5 * (x0 + x1);
    // comb teeth: curvature × this many drawing units (the largest tooth 15 units)
    let comb_scale = {
        let mut kmax: f64 = 0.0;
        for (li, l) in t.lines.iter().enumerate() {
            let k = if matches!(l.kind, Kind::Buttock | Kind::Profile) {
                2
            } else {
                1
            };
            let pts: Vec<(f64, f64)> = t
                .line_cells(li)
                .iter()
                .filter(|&&i| fin(vals[i][k]))
                .map(|&i| (vals[i][0] * sc, vals[i][k] * sc))
                .collect();
            for w in pts.windows(3) {
                kmax = kmax.max(menger(w[0], w[1], w[2]).abs());
            }
        }
        if kmax > 0.0 {
            15.0 / kmax
        } else {
            0.0
        }
    };
    let body = |x: f64, y: f64, z: f64| {
        let sgn = if x >= xm { 1.0 } else { -1.0 };
        (2.0 * pad + w + 0.5 * bw + sgn * y * sc, pad + (z1 - z) * sc)
    };
    let poly = |s: &mut String, pts: &[(f64, f64)], colour: &str| {
        if pts.len() < 2 {
            return;
        }
        comb(s, pts, comb_scale);
        let d: Vec<String> = pts.iter().map(|(a, b)| format!("{a:.1},{b:.1}")).collect();
        let _ = writeln!(
            s,
            r#"<polyline fill="none" stroke="{colour}" stroke-width="0.6" points="{}"/>"#,
            d.join(" ")
        );
    };
    for (li, l) in t.lines.iter().enumerate() {
        let idx = t.line_cells(li);
        let colour = match l.kind {
            Kind::Waterline => "#1f5fa8",
            Kind::Buttock => "#2a8a3a",
            _ => "#000",
        };
        if matches!(l.kind, Kind::Waterline | Kind::Edge | Kind::Plan) {
            let pts: Vec<(f64, f64)> = idx
                .iter()
                .filter(|&&i| fin(vals[i][1]))
                .map(|&i| plan(vals[i][0], vals[i][1]))
                .collect();
            poly(&mut s, &pts, colour);
        }
        if matches!(l.kind, Kind::Buttock | Kind::Edge | Kind::Profile) {
            let pts: Vec<(f64, f64)> = idx
                .iter()
                .filter(|&&i| fin(vals[i][2]))
                .map(|&i| prof(vals[i][0], vals[i][2]))
                .collect();
            poly(&mut s, &pts, colour);
        }
    }
    for (si, (_, x)) in &t.stations {
        let mut idx: Vec<usize> = (0..t.cells.len())
            .filter(|&i| t.cells[i].station_index == *si && t.cells[i].on_station)
            .filter(|&i| fin(vals[i][1]) && fin(vals[i][2]))
            .collect();
        idx.sort_by(|&a, &b| vals[a][2].total_cmp(&vals[b][2]));
        let pts: Vec<(f64, f64)> = idx.iter().map(|&i| body(*x, vals[i][1], vals[i][2])).collect();
        poly(&mut s, &pts, "#444");
    }
    for (i, c) in t.cells.iter().enumerate() {
        if !f.flagged[i] {
            continue;
        }
        let v = vals[i];
        let mut mark = |a: (f64, f64), b: (f64, f64)| {
            let _ = writeln!(
                s,
                r#"<circle cx="{:.1}" cy="{:.1}" r="3" fill="none" stroke="red"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="red"/>"#,
                a.0, a.1, a.0, a.1, b.0, b.1
            );
        };
        if fin(c.y) && fin(v[1]) {
            mark(plan(c.x, c.y), plan(v[0], v[1]));
        }
        if fin(c.z) && fin(v[2]) {
            mark(prof(c.x, c.z), prof(v[0], v[2]));
        }
        if fin(c.y) && fin(c.z) && c.on_station {
            mark(body(c.x, c.y, c.z), body(v[0], v[1], v[2]));
        }
    }
    let _ = writeln!(
        s,
        r#"<text x="{pad}" y="{:.1}">profile · half-breadth plan · body plan; red: flagged offsets ({})</text>"#,
        total_h - 2.0,
        f.report.flagged
    );
    s.push_str("</svg>\n");
    s
}
