//! [`CurveKind`]: how a curve's points are read, one type for the catalogue, the measures and
//! CAD output.

/// How a curve's points are read: a function y(x) or a parametric curve. It decides which
/// spline measures the points (the spline function y(x) with its x–c polyline, or the natural
/// chord-length spline) and how a CAD rebuild counts curvature.
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
#[serde(rename_all = "kebab-case")]
pub enum CurveKind {
    /// A function y(x): planar points, x strictly increasing, the curve's parameter is x;
    /// methods keep x.
    Function,
    /// A parametric curve in 2D or 3D.
    #[default]
    Parametric,
}

impl CurveKind {
    /// `function` or `parametric`.
    pub fn name(self) -> &'static str {
        match self {
            CurveKind::Function => "function",
            CurveKind::Parametric => "parametric",
        }
    }
}
