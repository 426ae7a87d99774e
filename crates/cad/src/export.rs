//! The one entry point a command needs: take the faired shape, convert, (rebuild,) write.

use std::path::Path;
use std::str::FromStr;

use crate::model::{CadModel, Shape};
use crate::options::{StepSchema, WriteOptions};
use crate::rebuild::{rebuild, RebuildReport, RebuildTarget};
use crate::{dxf, iges, step, Error, Result, Units};

/// A CAD file format.
#[derive(
    Clone, Copy, Debug, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "kebab-case")]
pub enum Format {
    /// IGES 5.3 (`.igs`, `.iges`).
    Iges,
    /// STEP AP214/AP242 (`.step`, `.stp`).
    Step,
    /// DXF R2000 (`.dxf`), curves only.
    Dxf,
}

impl Format {
    /// Every format.
    pub const ALL: [Format; 3] = [Format::Iges, Format::Step, Format::Dxf];

    /// The format a file name's extension names (case-insensitive), `None` for others
    /// (`.csv`, `.json`, … are point formats).
    pub fn from_path(path: impl AsRef<Path>) -> Option<Format> {
        let extension = path.as_ref().extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "igs" | "iges" => Some(Format::Iges),
            "step" | "stp" => Some(Format::Step),
            "dxf" => Some(Format::Dxf),
            _ => None,
        }
    }

    /// The name `--cad` takes: `iges`, `step`, `dxf`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Iges => "iges",
            Format::Step => "step",
            Format::Dxf => "dxf",
        }
    }

    /// The usual file extension.
    pub fn extension(self) -> &'static str {
        match self {
            Format::Iges => "igs",
            Format::Step => "step",
            Format::Dxf => "dxf",
        }
    }
}

impl FromStr for Format {
    type Err = Error;

    /// `iges`/`igs`, `step`/`stp`, `dxf`, case-insensitive; else [`Error::UnknownFormat`].
    fn from_str(name: &str) -> Result<Format> {
        match name.trim().to_ascii_lowercase().as_str() {
            "iges" | "igs" => Ok(Format::Iges),
            "step" | "stp" => Ok(Format::Step),
            "dxf" => Ok(Format::Dxf),
            _ => Err(Error::UnknownFormat(name.to_string())),
        }
    }
}

impl std::fmt::Display for Format {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// How a faired shape is written: unit, tolerance, an optional rebuild, the STEP schema.
///
/// The single source of these settings: the command's `--control-points` and
/// `--fit-tolerance` and the config file's `[cad]` table read them from here.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, schemars::JsonSchema)]
#[serde(default, deny_unknown_fields, rename_all = "kebab-case")]
pub struct CadSettings {
    /// Length unit written into the file: mm, cm, m, um, in or ft (coordinates are not scaled).
    pub units: Units,
    /// Model resolution written into the file (IGES minimum resolution, STEP uncertainty).
    ///
    /// Unset: 1e-9 of the model's size for an exact curve (the accuracy of the conversion,
    /// with room), the largest deviation for a rebuilt one.
    pub tolerance: Option<f64>,
    /// Rebuild the curve with this many control points (least squares, The NURBS Book Eq. 9.63–9.69).
    ///
    /// Unset: the exact faired curve is written. At least degree + 1 and at most about half
    /// the number of faired points.
    pub control_points: Option<usize>,
    /// Rebuild with the fewest control points within this distance of every faired point.
    ///
    /// Unset: no rebuild. When no fit with at most half as many control points as points
    /// meets it, the exact curve is written and the report says so.
    pub fit_tolerance: Option<f64>,
    /// Degree of a rebuilt curve (the exact curve keeps its own, 3 for the splines).
    pub degree: usize,
    /// STEP application protocol: ap214 (read everywhere) or ap242.
    pub step_schema: StepSchema,
}

impl Default for CadSettings {
    fn default() -> Self {
        Self {
            units: Units::Millimetre,
            tolerance: None,
            control_points: None,
            fit_tolerance: None,
            degree: 3,
            step_schema: StepSchema::Ap214,
        }
    }
}

impl CadSettings {
    /// Refuses values out of range with [`Error::BadParameter`]: a tolerance or fit
    /// tolerance that is not finite and positive, a degree outside 1–9, fewer control points
    /// than degree + 1, and both a control-point count and a fit tolerance.
    pub fn validate(&self) -> Result<()> {
        let positive = |name: &'static str, value: Option<f64>| match value {
            Some(v) if !(v > 0.0 && v.is_finite()) => Err(Error::BadParameter {
                name,
                value: v.to_string(),
                reason: "must be finite and positive".into(),
            }),
            _ => Ok(()),
        };
        positive("tolerance", self.tolerance)?;
        positive("fit-tolerance", self.fit_tolerance)?;
        if !(1..=9).contains(&self.degree) {
            return Err(Error::BadParameter {
                name: "degree",
                value: self.degree.to_string(),
                reason: "must be between 1 and 9".into(),
            });
        }
        if let Some(n) = self.control_points {
            if n < self.degree + 1 {
                return Err(Error::BadParameter {
                    name: "control-points",
                    value: n.to_string(),
                    reason: format!("must be at least degree + 1 = {}", self.degree + 1),
                });
            }
            if self.fit_tolerance.is_some() {
                return Err(Error::BadParameter {
                    name: "control-points",
                    value: n.to_string(),
                    reason: "give either control-points or fit-tolerance, not both".into(),
                });
            }
        }
        Ok(())
    }

    /// The rebuild these settings ask for, if any.
    pub fn rebuild_target(&self) -> Option<RebuildTarget> {
        match (self.control_points, self.fit_tolerance) {
            (Some(n), _) => Some(RebuildTarget::ControlPoints(n)),
            (None, Some(d)) => Some(RebuildTarget::Tolerance(d)),
            (None, None) => None,
        }
    }
}

/// A written file and what went into it.
#[derive(Clone, Debug, PartialEq)]
pub struct Export {
    /// The file's text.
    pub text: String,
    /// Its format.
    pub format: Format,
    /// The model written (the rebuilt curve when there was a rebuild).
    pub model: CadModel,
    /// The rebuild's report, when the settings asked for one.
    pub rebuild: Option<RebuildReport>,
}

/// The part of an [`Export`] a JSON report carries: `{"format", "units", "tolerance",
/// "degree", "control_points", "rebuild"}`.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ExportSummary {
    /// The format written.
    pub format: Format,
    /// The unit written.
    pub units: Units,
    /// The tolerance written.
    pub tolerance: f64,
    /// Degree of the (first) curve or surface written.
    pub degree: usize,
    /// Control points of the (first) curve written, or rows × columns of a surface.
    pub control_points: usize,
    /// The rebuild, if any.
    pub rebuild: Option<RebuildReport>,
}

impl Export {
    /// The summary for a JSON report.
    pub fn summary(&self) -> ExportSummary {
        let (degree, control_points) = match (self.model.curves.first(), self.model.surfaces.first()) {
            (Some(c), _) => (c.curve.degree(), c.curve.control_points().len()),
            (None, Some(s)) => {
                let (rows, columns) = s.surface.net_size();
                (s.surface.degrees().0, rows * columns)
            }
            (None, None) => (0, 0),
        };
        ExportSummary {
            format: self.format,
            units: self.model.units,
            tolerance: self.model.tolerance,
            degree,
            control_points,
            rebuild: self.rebuild.clone(),
        }
    }
}

/// Takes a faired shape (see [`Shape`]: `CadCurve::from_spline_function`,
/// `CadCurve::from_hermite`, `CadCurve::from_nurbs`, `CadSurface::from_bicubic`, …), rebuilds
/// it if `settings` ask for it ([`rebuild`]), and writes it in `format` with the unit and
/// tolerance of `settings` and the header fields of `options`.
///
/// Fails with [`Error::BadParameter`] on invalid settings or a rebuild asked of a surface,
/// [`Error::Unsupported`] for a surface in DXF, and as the rebuild fails. O(size of the shape)
/// without a rebuild.
pub fn export(
    shape: &Shape,
    format: Format,
    settings: &CadSettings,
    options: &WriteOptions,
) -> Result<Export> {
    settings.validate()?;
    let (shape, report) = match (shape, settings.rebuild_target()) {
        (Shape::Curve(curve), Some(target)) => {
            let (rebuilt, report) = rebuild(curve, target, settings.degree)?;
            (Shape::Curve(rebuilt), Some(report))
        }
        (Shape::Surface(_), Some(_)) => {
            return Err(Error::BadParameter {
                name: "control-points",
                value: settings
                    .control_points
                    .map_or_else(|| format!("{:?}", settings.fit_tolerance), |n| n.to_string()),
                reason: "a rebuild is for curves; surfaces are written exactly".into(),
            });
        }
        (shape, None) => (shape.clone(), None),
    };
    let mut model = CadModel::of(shape, settings.units, 0.0);
    let size = model.size();
    model.tolerance = match (settings.tolerance, &report) {
        (Some(t), _) => t,
        (None, Some(r)) => r.max_deviation.max(1e-9 * size),
        (None, None) => 1e-9 * size,
    };
    if model.tolerance.is_nan() || model.tolerance <= 0.0 {
        model.tolerance = 1e-9;
    }
    let text = write(&model, format, options)?;
    Ok(Export {
        text,
        format,
        model,
        rebuild: report,
    })
}

/// [`export`] into a file: the format from `format` or else the file's extension
/// ([`Format::from_path`]), the file's name recorded inside it. Fails with
/// [`Error::UnknownFormat`] when neither names a format and [`Error::Io`] when the file
/// cannot be written (nothing is written when the export fails; the file is written
/// completely or not at all, [`crate::atomic`]).
pub fn export_to_path(
    shape: &Shape,
    path: impl AsRef<Path>,
    format: Option<Format>,
    settings: &CadSettings,
) -> Result<Export> {
    let path = path.as_ref();
    let format = match format {
        Some(f) => f,
        None => Format::from_path(path).ok_or_else(|| Error::UnknownFormat(path.display().to_string()))?,
    };
    let options = WriteOptions {
        file_name: path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_string(),
        ..WriteOptions::default()
    };
    let export = export(shape, format, settings, &options)?;
    crate::atomic::write_text(path, &export.text).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.error.to_string(),
    })?;
    Ok(export)
}

/// Writes a model in `format`.
pub fn write(model: &CadModel, format: Format, options: &WriteOptions) -> Result<String> {
    match format {
        Format::Iges => iges::write(model, options),
        Format::Step => step::write(model, options),
        Format::Dxf => dxf::write(model, options),
    }
}

/// Reads a model in `format`.
pub fn read(text: &str, format: Format) -> Result<CadModel> {
    match format {
        Format::Iges => iges::read(text),
        Format::Step => step::read(text),
        Format::Dxf => dxf::read(text),
    }
}

/// Reads a CAD file, the format from `format` or else the extension. Fails with
/// [`Error::UnknownFormat`], [`Error::Io`], and as the reader fails (its line numbers are
/// the file's). A file that is not UTF-8 is read with its invalid bytes replaced (the formats
/// are ASCII).
pub fn read_path(path: impl AsRef<Path>, format: Option<Format>) -> Result<CadModel> {
    let path = path.as_ref();
    let format = match format {
        Some(f) => f,
        None => Format::from_path(path).ok_or_else(|| Error::UnknownFormat(path.display().to_string()))?,
    };
    let bytes = std::fs::read(path).map_err(|e| Error::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    read(&String::from_utf8_lossy(&bytes), format)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_from_names_and_extensions() {
        assert_eq!(Format::from_path("a/b.IGS"), Some(Format::Iges));
        assert_eq!(Format::from_path("b.stp"), Some(Format::Step));
        assert_eq!(Format::from_path("b.dxf"), Some(Format::Dxf));
        assert_eq!(Format::from_path("b.csv"), None);
        assert_eq!("STEP".parse::<Format>().unwrap(), Format::Step);
        assert!(matches!("svg".parse::<Format>(), Err(Error::UnknownFormat(_))));
        for f in Format::ALL {
            assert_eq!(f.name().parse::<Format>().unwrap(), f);
            assert_eq!(Format::from_path(format!("x.{}", f.extension())), Some(f));
        }
    }

    #[test]
    fn settings_refuse_what_they_cannot_do() {
        assert!(CadSettings::default().validate().is_ok());
        let bad = [
            CadSettings {
                tolerance: Some(0.0),
                ..CadSettings::default()
            },
            CadSettings {
                fit_tolerance: Some(f64::NAN),
                ..CadSettings::default()
            },
            CadSettings {
                degree: 0,
                ..CadSettings::default()
            },
            CadSettings {
                control_points: Some(3),
                ..CadSettings::default()
            },
            CadSettings {
                control_points: Some(8),
                fit_tolerance: Some(0.1),
                ..CadSettings::default()
            },
        ];
        for settings in bad {
            assert!(
                matches!(settings.validate(), Err(Error::BadParameter { .. })),
                "{settings:?}"
            );
        }
        let text = r#"{"units": "m", "control-points": 12, "step-schema": "ap242"}"#;
        let settings: CadSettings = serde_json::from_str(text).unwrap();
        assert_eq!(settings.units, Units::Metre);
        assert_eq!(settings.rebuild_target(), Some(RebuildTarget::ControlPoints(12)));
        assert!(serde_json::from_str::<CadSettings>(r#"{"unit": "m"}"#).is_err());
    }
}
