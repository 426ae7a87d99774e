//! The data sets embedded in the command: `fair demo` runs every method on them and
//! `fair serve` offers them on its page.

use fairing::catalog::MethodKind;

/// One embedded data set.
#[derive(Debug, Clone, Copy)]
pub struct Dataset {
    /// Short name used in file names.
    pub name: &'static str,
    /// What it is.
    pub about: &'static str,
    /// Curve or surface.
    pub kind: MethodKind,
    /// The CSV text.
    pub text: &'static str,
}

macro_rules! data {
    ($path:literal) => {
        include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/", $path))
    };
}

/// The embedded data sets (see `data/README.md` for provenance).
pub const DATASETS: &[Dataset] = &[
    Dataset {
        name: "naca2412-upper",
        about: "NACA 2412 upper surface, a clean analytic control",
        kind: MethodKind::Curve,
        text: data!("airfoil_naca2412/naca2412_upper.csv"),
    },
    Dataset {
        name: "ua2-180-upper",
        about: "UA(2)-180 upper surface, y oscillating by 3e-4",
        kind: MethodKind::Curve,
        text: data!("airfoil_ua2-180/ua2-180_upper.csv"),
    },
    Dataset {
        name: "ua2-180sm-upper",
        about: "UA(2)-180 upper surface, the published smoothed twin",
        kind: MethodKind::Curve,
        text: data!("airfoil_ua2-180/ua2-180sm_upper.csv"),
    },
    Dataset {
        name: "r140-upper",
        about: "R140 upper surface, hand-digitised, the roughest",
        kind: MethodKind::Curve,
        text: data!("airfoil_r140/r140_upper.csv"),
    },
    Dataset {
        name: "block-island-wl36",
        about: "Block Island boat waterline 36 in, from the offsets table",
        kind: MethodKind::Curve,
        text: data!("hull_block_island_boat/waterlines/wl_36in.csv"),
    },
    Dataset {
        name: "gunnerus-wl03",
        about: "R/V Gunnerus waterline 3, flat-side ripple",
        kind: MethodKind::Curve,
        text: data!("hull_gunnerus/waterlines/wl_03.csv"),
    },
    Dataset {
        name: "block-island-sheer",
        about: "Block Island boat sheer line in 3D",
        kind: MethodKind::Curve,
        text: data!("hull_block_island_boat/sheer_3d.csv"),
    },
    Dataset {
        name: "teapot-body",
        about: "Utah teapot body control net, 13 x 13",
        kind: MethodKind::Surface,
        text: data!("surface_utah_teapot/teapot_body_control_net.csv"),
    },
];
