//! The methods `fair` knows: names, what they fair, the paper, and their parameters.
//!
//! This is the one list `fair methods` prints and `--method`, `--set` and `--config` are
//! checked against. Each strategy's engineer fills in its parameters here; the command wires
//! the name to the strategy in `commands::curve` / `commands::surface`.

use crate::error::{Error, Result};

/// Whether a method fairs curves or surfaces.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MethodKind {
    /// Curves (function or parametric).
    Curve,
    /// Surface grids.
    Surface,
}

impl MethodKind {
    /// `curve` or `surface`.
    pub fn name(self) -> &'static str {
        match self {
            MethodKind::Curve => "curve",
            MethodKind::Surface => "surface",
        }
    }
}

/// One parameter of a method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParameterInfo {
    /// The name `--set` takes.
    pub name: &'static str,
    /// Its default, as text.
    pub default: &'static str,
    /// What it means, one line.
    pub meaning: &'static str,
}

/// One method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MethodInfo {
    /// The name `--method` takes.
    pub name: &'static str,
    /// Curves or surfaces.
    pub kind: MethodKind,
    /// The paper (or baseline) it comes from, short.
    pub paper: &'static str,
    /// One line on what it does.
    pub summary: &'static str,
    /// Its parameters.
    pub parameters: &'static [ParameterInfo],
}

impl MethodInfo {
    /// The parameter called `name`.
    pub fn parameter(&self, name: &str) -> Option<&ParameterInfo> {
        self.parameters.iter().find(|p| p.name == name)
    }
}

/// The strain-energy family's parameters: `strain-energy` takes them all, its presets
/// `kjellander` and `poliakoff` (whose knots are fixed) all but `parametrization`, the last.
const STRAIN_ENERGY: &[ParameterInfo] = &[
    ParameterInfo {
        name: "energy-tolerance",
        default: "1e-6",
        meaning: "stop when one step changes the strain energy by at most this x E",
    },
    ParameterInfo {
        name: "radius-scale",
        default: "1",
        meaning: "automatic mode: restraining radius = this x |Eq. 11 point - P_i| (1 = the paper)",
    },
    ParameterInfo {
        name: "pairs",
        default: "off",
        meaning: "automatic mode: on = replace the two worst adjacent points together (Eq. 15)",
    },
    ParameterInfo {
        name: "replacement",
        default: "limit",
        meaning: "limit = Eq. 11/15 in one step; iterated = one application of Eq. 8/13 per step",
    },
    ParameterInfo {
        name: "max-iterations",
        default: "100000",
        meaning: "replacement steps at most",
    },
    ParameterInfo {
        name: "parametrization",
        default: "chord-length",
        meaning: "fixed knots: chord-length, uniform or centripetal",
    },
];
const STRAIN_ENERGY_PRESETS: &[ParameterInfo] = STRAIN_ENERGY.split_at(STRAIN_ENERGY.len() - 1).0;

/// Curve methods that fair planar curves only (Han's two-phase works on y(x) and on planar
/// curves through bisector frames); the others take 2D and 3D points.
pub const PLANAR_ONLY: &[&str] = &["two-phase"];

/// Every method, curves first.
pub const METHODS: &[MethodInfo] = &[
    MethodInfo {
        name: "two-phase",
        kind: MethodKind::Curve,
        paper: "Han et al., two-phase fairing of spline functions",
        summary: "coarse phase removes curvature vibrations, fine phase removes inflections",
        parameters: &[
            ParameterInfo {
                name: "coarse-lambda",
                default: "0.8",
                meaning: "fraction of each Phase-1 displacement applied, in (0, 1]",
            },
            ParameterInfo {
                name: "fine-lambda",
                default: "0.75",
                meaning: "Phase 2 Case 1: the neighbours move by -lambda times the centre's move",
            },
            ParameterInfo {
                name: "alpha-divisor",
                default: "5",
                meaning: "alpha rule: alpha = smaller neighbouring c / alpha-divisor",
            },
            ParameterInfo {
                name: "max-passes",
                default: "50",
                meaning: "full passes (coarse then fine) at most, per function segment",
            },
            ParameterInfo {
                name: "max-move-factor",
                default: "0.5",
                meaning: "guard: skip a case moving a point by more than this times the spacing",
            },
            ParameterInfo {
                name: "guard-window",
                default: "16",
                meaning: "points on each side over which a move's counts are rechecked",
            },
            ParameterInfo {
                name: "count-guard",
                default: "local",
                meaning: "refuse moves (local) or undo passes (pass) that raise a count, or none (off)",
            },
            ParameterInfo {
                name: "pair-min-sine",
                default: "0.05",
                meaning: "Phase 2 Case 2 solved exactly only if its 2x2 system is this well posed",
            },
            ParameterInfo {
                name: "max-run",
                default: "2",
                meaning: "longest wrong-sign run of c fixed; > 2 turns on the long-run option (dense noisy data)",
            },
            ParameterInfo {
                name: "stall-passes",
                default: "0",
                meaning: "stop after this many passes that reduce no count (0: never)",
            },
            ParameterInfo {
                name: "min-gain",
                default: "0",
                meaning: "stop after a pass lowering inflections + vibrations by less than this fraction (0: never)",
            },
            ParameterInfo {
                name: "denoise",
                default: "gcv",
                meaning: "remove the data's noise first with a smoothing spline (gcv), or not (off, the paper)",
            },
            ParameterInfo {
                name: "segment-passes",
                default: "3",
                meaning: "parametric input: partition-fair-blend passes (Han 4.2.4)",
            },
            ParameterInfo {
                name: "turning-limit",
                default: "120",
                meaning: "parametric input: largest turning angle of a segment, degrees",
            },
            ParameterInfo {
                name: "overlap",
                default: "5",
                meaning: "parametric input: points shared by adjacent segments",
            },
            ParameterInfo {
                name: "closed",
                default: "false",
                meaning: "parametric input: true for a closed curve (last point joins the first)",
            },
        ],
    },
    MethodInfo {
        name: "strain-energy",
        kind: MethodKind::Curve,
        paper: "Zhang & Cheng, strain-energy point replacement",
        summary: "replaces one or two bad points to minimise the strain energy (--points: interactive, else automatic)",
        parameters: STRAIN_ENERGY,
    },
    MethodInfo {
        name: "kjellander",
        kind: MethodKind::Curve,
        paper: "Kjellander (as a preset of Zhang & Cheng)",
        summary: "moves a bad point to remove the third-derivative jump",
        parameters: STRAIN_ENERGY_PRESETS,
    },
    MethodInfo {
        name: "poliakoff",
        kind: MethodKind::Curve,
        paper: "Poliakoff (as a preset of Zhang & Cheng)",
        summary: "moves a bad point to reduce the local strain energy",
        parameters: STRAIN_ENERGY_PRESETS,
    },
    MethodInfo {
        name: "batten",
        kind: MethodKind::Curve,
        paper: "Okada, batten fairing",
        summary: "a numerical batten through the points within adjustable ranges",
        parameters: &[
            ParameterInfo {
                name: "range",
                default: "inf",
                meaning: "adjustable range: no point moves farther than this from its data point",
            },
            ParameterInfo {
                name: "tangent-directions",
                default: "",
                meaning: "prescribed tangent directions, INDEX:DX,DY[,DZ] separated by ';'",
            },
            ParameterInfo {
                name: "update",
                default: "gauss-seidel",
                meaning: "Eq. 13 per iteration: gauss-seidel (one sweep), solve (whole system), jacobi",
            },
            ParameterInfo {
                name: "max-iterations",
                default: "1000",
                meaning: "batten iterations at most (each: Eq. 12 tangents, Eq. 13 positions)",
            },
            ParameterInfo {
                name: "max-sweeps",
                default: "10000",
                meaning: "update=solve: projected Gauss-Seidel sweeps at most when a range binds",
            },
        ],
    },
    MethodInfo {
        name: "nurbs-weights",
        kind: MethodKind::Curve,
        paper: "Nowacki et al., fairing NURBS by weights",
        summary: "changes weights (not points) by Nelder-Mead on an energy criterion",
        parameters: &[
            ParameterInfo {
                name: "criterion",
                default: "ek",
                meaning: "criterion minimised: e1, e2, e3, ek or ek-prime",
            },
            ParameterInfo {
                name: "law",
                default: "bernstein",
                meaning: "weight law: bernstein (the paper's 4 cubic coefficients) or per-point",
            },
            ParameterInfo {
                name: "max-iterations",
                default: "1000",
                meaning: "Nelder-Mead iterations at most",
            },
        ],
    },
    MethodInfo {
        name: "smoothing-spline",
        kind: MethodKind::Curve,
        paper: "baseline: smoothing spline (the papers' MST)",
        summary: "least-squares smoothing spline, a baseline to compare against",
        parameters: &[
            ParameterInfo {
                name: "p",
                default: "auto",
                meaning: "smoothing parameter in [0, 1] (csaps: 0 LSQ line, 1 interpolation) or auto",
            },
            ParameterInfo {
                name: "rule",
                default: "gcv",
                meaning: "how auto chooses p: gcv (generalised cross-validation) or trace (csaps's rule)",
            },
        ],
    },
    MethodInfo {
        name: "sapidis-farin",
        kind: MethodKind::Curve,
        paper: "baseline: Sapidis & Farin knot removal and reinsertion",
        summary: "removes curvature-slope jumps knot by knot, a baseline",
        parameters: &[
            ParameterInfo {
                name: "jump-reduction",
                default: "1e-3",
                meaning: "stop when the largest curvature-slope jump is this fraction of the initial one",
            },
            ParameterInfo {
                name: "max-move",
                default: "data",
                meaning: "how far a point may move without --tolerance: data (about five noise estimates), off, or a distance",
            },
            ParameterInfo {
                name: "max-iterations",
                default: "1000",
                meaning: "knots faired (removed and reinserted) at most",
            },
        ],
    },
    MethodInfo {
        name: "zhang-cheng",
        kind: MethodKind::Surface,
        paper: "Zhang & Cheng §4, bicubic surface fairing",
        summary: "automatic: boundary curves, then every interior point per step, largest z_ij first, in restraining spheres; with --points: the named points in pairs and 2x2 blocks (step 1.3)",
        parameters: &[
            ParameterInfo {
                name: "replacement",
                default: "limit",
                meaning: "limit (Eq. 21 and its pair/block analogues, solved once) or iterated (one application of Eq. 20/23/25)",
            },
            ParameterInfo {
                name: "objective",
                default: "network",
                meaning: "network (curve strain energy, Eq. 18-25) or thin-plate (Eq. 27-29; needs replacement=iterated)",
            },
            ParameterInfo {
                name: "boundary",
                default: "on",
                meaning: "on: fair the boundary curves first with the curve method (automatic mode, step 2.1); off: keep them",
            },
            ParameterInfo {
                name: "energy-tolerance",
                default: "1e-6",
                meaning: "stop when the network strain energy changes by at most this fraction in one step",
            },
            ParameterInfo {
                name: "max-steps",
                default: "1000",
                meaning: "step limit",
            },
            ParameterInfo {
                name: "parametrization",
                default: "chord-length",
                meaning: "knots, averaged over the grid lines and fixed while fairing: chord-length or uniform",
            },
        ],
    },
    MethodInfo {
        name: "kjellander",
        kind: MethodKind::Surface,
        paper: "Kjellander (as a preset of Zhang & Cheng §4)",
        summary: "one point per step: the interior point of largest z_ij moved to zero its jumps (uniform knots), in its restraining sphere",
        parameters: &[
            ParameterInfo {
                name: "replacement",
                default: "limit",
                meaning: "limit (Eq. 21 and its pair/block analogues, solved once) or iterated (one application of Eq. 20/23/25)",
            },
            ParameterInfo {
                name: "objective",
                default: "network",
                meaning: "network (curve strain energy, Eq. 18-25) or thin-plate (Eq. 27-29; needs replacement=iterated)",
            },
            ParameterInfo {
                name: "boundary",
                default: "off",
                meaning: "on: fair the boundary curves first with the curve method (automatic mode, step 2.1); off: keep them",
            },
            ParameterInfo {
                name: "energy-tolerance",
                default: "1e-6",
                meaning: "stop when the network strain energy changes by at most this fraction in one step",
            },
            ParameterInfo {
                name: "max-steps",
                default: "100000",
                meaning: "step limit",
            },
            ParameterInfo {
                name: "parametrization",
                default: "uniform",
                meaning: "knots, averaged over the grid lines and fixed while fairing: chord-length or uniform",
            },
        ],
    },
];

/// The method called `name` for `kind`, or [`Error::UnknownMethod`] listing the known names.
pub fn find(name: &str, kind: MethodKind) -> Result<&'static MethodInfo> {
    METHODS
        .iter()
        .find(|m| m.kind == kind && m.name == name)
        .ok_or_else(|| Error::UnknownMethod {
            name: name.to_string(),
            kind: kind.name(),
            known: METHODS
                .iter()
                .filter(|m| m.kind == kind)
                .map(|m| m.name)
                .collect::<Vec<_>>()
                .join(", "),
        })
}

/// The table `fair methods` prints: one block per method, its parameters indented below it.
pub fn table() -> String {
    let width = METHODS.iter().map(|m| m.name.len()).max().unwrap_or(0);
    let mut text = String::new();
    for kind in [MethodKind::Curve, MethodKind::Surface] {
        text.push_str(&format!("{} methods:\n", kind.name()));
        for method in METHODS.iter().filter(|m| m.kind == kind) {
            text.push_str(&format!(
                "  {:width$}  {} ({})\n",
                method.name, method.summary, method.paper
            ));
            if method.parameters.is_empty() {
                text.push_str(&format!("  {:width$}    (no parameters yet)\n", ""));
            }
            for p in method.parameters {
                text.push_str(&format!(
                    "  {:width$}    {}={}  {}\n",
                    "", p.name, p.default, p.meaning
                ));
            }
        }
    }
    text
}

#[cfg(test)]
mod tests {

    #[test]
    fn strain_energy_presets_take_all_but_the_parametrization() {
        let full = find("strain-energy", MethodKind::Curve).unwrap();
        assert!(full.parameter("parametrization").is_some());
        for preset in ["kjellander", "poliakoff"] {
            let method = find(preset, MethodKind::Curve).unwrap();
            assert!(method.parameter("parametrization").is_none(), "{preset}");
            assert_eq!(method.parameters.len(), full.parameters.len() - 1);
        }
    }

    use super::*;

    #[test]
    fn every_design_method_is_known() {
        for name in [
            "two-phase",
            "strain-energy",
            "kjellander",
            "poliakoff",
            "batten",
            "nurbs-weights",
            "smoothing-spline",
            "sapidis-farin",
        ] {
            assert_eq!(find(name, MethodKind::Curve).unwrap().name, name);
        }
        for name in ["zhang-cheng", "kjellander"] {
            assert_eq!(find(name, MethodKind::Surface).unwrap().kind, MethodKind::Surface);
        }
    }

    #[test]
    fn unknown_method_lists_known_ones() {
        let e = find("zhang-cheng", MethodKind::Curve).unwrap_err();
        assert!(e.to_string().contains("two-phase"), "{e}");
        assert_eq!(e.exit_code(), 2);
    }

    #[test]
    fn names_are_unique_per_kind() {
        for (i, a) in METHODS.iter().enumerate() {
            for b in &METHODS[i + 1..] {
                assert!(!(a.name == b.name && a.kind == b.kind), "{} twice", a.name);
            }
        }
    }

    #[test]
    fn table_lists_all() {
        let t = table();
        assert!(METHODS.iter().all(|m| t.contains(m.name)));
    }
}
