//! Bad files and bad requests: an error that names what is wrong and where, never a panic.

use cad::{CadSettings, CadSurface, Error, Format, Shape, WriteOptions};
use curve_repr::BicubicSplineSurface;
use proptest::prelude::*;

use crate::common::{curves, grid};

fn line_of(result: cad::Result<cad::CadModel>) -> usize {
    match result {
        Err(Error::Parse { line, .. }) => line,
        other => panic!("expected a parse error, got {other:?}"),
    }
}

fn written(format: Format) -> String {
    let model = cad::CadModel {
        curves: curves()[..1].to_vec(),
        surfaces: vec![],
        units: cad::Units::Millimetre,
        tolerance: 1e-7,
    };
    cad::write(&model, format, &WriteOptions::default()).unwrap()
}

#[test]
fn broken_iges_names_the_line() {
    let text = written(Format::Iges);
    let lines: Vec<&str> = text.lines().collect();
    // A short line.
    let mut short = lines.clone();
    short[3] = "126,1";
    assert_eq!(line_of(cad::read(&short.join("\n"), Format::Iges)), 4);
    // A knot that is not a number (the 8th parameter), in the first parameter line.
    let first_p = lines
        .iter()
        .position(|l| l.as_bytes().get(72) == Some(&b'P'))
        .unwrap();
    let mut bad = lines.clone();
    let mut tokens: Vec<&str> = lines[first_p][..64].split(',').collect();
    tokens[7] = "x";
    let replaced = format!("{:<64}{}", tokens.join(","), &lines[first_p][64..]);
    bad[first_p] = &replaced;
    assert_eq!(line_of(cad::read(&bad.join("\n"), Format::Iges)), first_p + 1);
    // Parameter data cut short: the entity's first parameter line is named.
    let cut: Vec<&str> = lines.iter().take(first_p + 1).copied().collect();
    assert!(matches!(
        cad::read(&cut.join("\n"), Format::Iges),
        Err(Error::Parse { .. })
    ));
    assert!(matches!(
        cad::read("", Format::Iges),
        Err(Error::Parse { line: 1, .. })
    ));
}

#[test]
fn broken_step_names_the_line() {
    let text = written(Format::Step);
    let lines: Vec<String> = text.lines().map(str::to_string).collect();
    let spline = lines
        .iter()
        .position(|l| l.contains("B_SPLINE_CURVE_WITH_KNOTS"))
        .unwrap();
    // Multiplicities that do not match the knots.
    let multiplicities = spline
        + lines[spline..]
            .iter()
            .position(|l| l.trim_start().starts_with("(4,"))
            .unwrap();
    let mut bad = lines.clone();
    bad[multiplicities] = bad[multiplicities].replacen("(4,", "(3,", 1);
    assert_eq!(line_of(cad::read(&bad.join("\n"), Format::Step)), spline + 1);
    // A parenthesis missing.
    let mut unclosed = lines.clone();
    let point = lines
        .iter()
        .position(|l| l.contains("CARTESIAN_POINT('',(0."))
        .unwrap();
    unclosed[point] = unclosed[point].replace("));", ");");
    assert_eq!(line_of(cad::read(&unclosed.join("\n"), Format::Step)), point + 1);
    assert!(matches!(
        cad::read("ISO-10303-21;\nHEADER;\nENDSEC;\n", Format::Step),
        Err(Error::Parse { .. })
    ));
}

#[test]
fn broken_dxf_names_the_line() {
    let text = written(Format::Dxf);
    let lines: Vec<&str> = text.lines().collect();
    let spline = lines.iter().position(|l| *l == "SPLINE").unwrap();
    let count = spline + lines[spline..].iter().position(|l| l.trim() == "73").unwrap();
    let mut bad = lines.clone();
    bad[count + 1] = "999";
    assert_eq!(line_of(cad::read(&bad.join("\n"), Format::Dxf)), spline);
}

#[test]
fn requests_a_format_cannot_carry_are_refused() {
    let surface = CadSurface::from_bicubic(&BicubicSplineSurface::new(&grid(4, 4)).unwrap()).unwrap();
    let shape = Shape::Surface(surface);
    assert!(matches!(
        cad::export(
            &shape,
            Format::Dxf,
            &CadSettings::default(),
            &WriteOptions::default()
        ),
        Err(Error::Unsupported(_))
    ));
    let rebuild = CadSettings {
        fit_tolerance: Some(0.1),
        ..CadSettings::default()
    };
    assert!(matches!(
        cad::export(&shape, Format::Iges, &rebuild, &WriteOptions::default()),
        Err(Error::BadParameter { .. })
    ));
    assert!(matches!(
        cad::read_path("/nonexistent/x.igs", None),
        Err(Error::Io { .. })
    ));
    assert!(matches!(
        cad::read_path("points.csv", None),
        Err(Error::UnknownFormat(_))
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    /// A file cut short or with bytes changed reads as a model or as an error, never a panic.
    #[test]
    fn damaged_files_never_panic(
        format in prop::sample::select(Format::ALL.to_vec()),
        cut in 0.0..1.0f64,
        edits in prop::collection::vec((0.0..1.0f64, prop::sample::select(b",;()#.'0-9Ee \nHPD".to_vec())), 0..6),
    ) {
        let text = written(format);
        let mut bytes = text.into_bytes();
        bytes.truncate((bytes.len() as f64 * (0.5 + cut / 2.0)) as usize);
        for (at, byte) in edits {
            let len = bytes.len();
            if len > 0 {
                bytes[((len as f64 * at) as usize).min(len - 1)] = byte;
            }
        }
        let damaged = String::from_utf8_lossy(&bytes);
        let _ = cad::read(&damaged, format);
    }
}
