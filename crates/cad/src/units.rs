//! Length units, as each format names them.
//!
//! The coordinates are written as they are; the unit only says what they mean (IGES Global
//! parameters 14–15, STEP's length unit in the representation context, DXF's `$INSUNITS`).

/// The length unit written into a CAD file's header (coordinates are never scaled).
#[derive(
    Clone,
    Copy,
    Debug,
    Default,
    PartialEq,
    Eq,
    Hash,
    serde::Serialize,
    serde::Deserialize,
    schemars::JsonSchema,
)]
pub enum Units {
    /// Millimetres (the CAD default).
    #[default]
    #[serde(rename = "mm")]
    Millimetre,
    /// Centimetres.
    #[serde(rename = "cm")]
    Centimetre,
    /// Metres (ship lines are often drawn in metres).
    #[serde(rename = "m")]
    Metre,
    /// Micrometres.
    #[serde(rename = "um")]
    Micrometre,
    /// Inches.
    #[serde(rename = "in")]
    Inch,
    /// Feet.
    #[serde(rename = "ft")]
    Foot,
}

impl Units {
    /// Every unit, in the order of the enum.
    pub const ALL: [Units; 6] = [
        Units::Millimetre,
        Units::Centimetre,
        Units::Metre,
        Units::Micrometre,
        Units::Inch,
        Units::Foot,
    ];

    /// The short name (`mm`, `cm`, `m`, `um`, `in`, `ft`), as `--set units=` spells it.
    pub fn name(self) -> &'static str {
        match self {
            Units::Millimetre => "mm",
            Units::Centimetre => "cm",
            Units::Metre => "m",
            Units::Micrometre => "um",
            Units::Inch => "in",
            Units::Foot => "ft",
        }
    }

    /// The unit of a short name, case-insensitive; `None` for others.
    pub fn from_name(name: &str) -> Option<Units> {
        Units::ALL
            .into_iter()
            .find(|u| u.name().eq_ignore_ascii_case(name.trim()))
    }

    /// Millimetres per unit.
    pub fn millimetres(self) -> f64 {
        match self {
            Units::Millimetre => 1.0,
            Units::Centimetre => 10.0,
            Units::Metre => 1000.0,
            Units::Micrometre => 1e-3,
            Units::Inch => 25.4,
            Units::Foot => 304.8,
        }
    }

    /// IGES 5.3 Global parameter 14, the units flag (1 inch, 2 mm, 4 ft, 6 m, 9 µm, 10 cm).
    pub fn iges_flag(self) -> u32 {
        match self {
            Units::Inch => 1,
            Units::Millimetre => 2,
            Units::Foot => 4,
            Units::Metre => 6,
            Units::Micrometre => 9,
            Units::Centimetre => 10,
        }
    }

    /// IGES 5.3 Global parameter 15, the units name (`IN`, `MM`, `FT`, `M`, `UM`, `CM`).
    pub fn iges_name(self) -> &'static str {
        match self {
            Units::Inch => "IN",
            Units::Millimetre => "MM",
            Units::Foot => "FT",
            Units::Metre => "M",
            Units::Micrometre => "UM",
            Units::Centimetre => "CM",
        }
    }

    /// The unit of an IGES units flag, or of its name when the flag is 3 ("see parameter 15").
    pub fn from_iges(flag: i64, name: &str) -> Option<Units> {
        let by_flag = Units::ALL.into_iter().find(|u| i64::from(u.iges_flag()) == flag);
        by_flag.or_else(|| {
            let name = name.trim().trim_start_matches(['.', ' ']);
            Units::ALL
                .into_iter()
                .find(|u| u.iges_name().eq_ignore_ascii_case(name) || u.name().eq_ignore_ascii_case(name))
                .or_else(|| match name.to_ascii_uppercase().as_str() {
                    "INCH" | "INCHES" => Some(Units::Inch),
                    "MILLIMETER" | "MILLIMETRE" => Some(Units::Millimetre),
                    "METER" | "METRE" => Some(Units::Metre),
                    "FOOT" | "FEET" => Some(Units::Foot),
                    _ => None,
                })
        })
    }

    /// DXF `$INSUNITS` (1 inch, 2 ft, 4 mm, 5 cm, 6 m, 13 µm).
    pub fn dxf_code(self) -> u32 {
        match self {
            Units::Inch => 1,
            Units::Foot => 2,
            Units::Millimetre => 4,
            Units::Centimetre => 5,
            Units::Metre => 6,
            Units::Micrometre => 13,
        }
    }

    /// The unit of a DXF `$INSUNITS` code; `None` for unitless (0) and the others.
    pub fn from_dxf(code: i64) -> Option<Units> {
        Units::ALL.into_iter().find(|u| i64::from(u.dxf_code()) == code)
    }

    /// DXF `$MEASUREMENT`: 0 imperial, 1 metric.
    pub fn dxf_measurement(self) -> u32 {
        match self {
            Units::Inch | Units::Foot => 0,
            _ => 1,
        }
    }

    /// The STEP SI prefix of a metric unit (`$` for metres), `None` for inch and foot, which
    /// STEP writes as conversion-based units.
    pub fn step_prefix(self) -> Option<&'static str> {
        match self {
            Units::Millimetre => Some(".MILLI."),
            Units::Centimetre => Some(".CENTI."),
            Units::Metre => Some("$"),
            Units::Micrometre => Some(".MICRO."),
            Units::Inch | Units::Foot => None,
        }
    }

    /// The STEP name of a conversion-based unit (`INCH`, `FOOT`), `None` for SI units.
    pub fn step_conversion_name(self) -> Option<&'static str> {
        match self {
            Units::Inch => Some("INCH"),
            Units::Foot => Some("FOOT"),
            _ => None,
        }
    }
}

impl std::fmt::Display for Units {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_unit_reads_back_from_each_format_code() {
        for u in Units::ALL {
            assert_eq!(Units::from_name(u.name()), Some(u));
            assert_eq!(Units::from_iges(i64::from(u.iges_flag()), ""), Some(u));
            assert_eq!(Units::from_iges(3, u.iges_name()), Some(u));
            assert_eq!(Units::from_dxf(i64::from(u.dxf_code())), Some(u));
            assert_eq!(serde_json::to_string(&u).unwrap(), format!("\"{}\"", u.name()));
            assert!(u.step_prefix().is_some() != u.step_conversion_name().is_some());
        }
        assert_eq!(Units::from_iges(3, "INCH"), Some(Units::Inch));
        assert_eq!(Units::from_dxf(0), None);
    }
}
