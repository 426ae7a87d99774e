//! Every reader against mutated files: the files this crate writes, with the mutations of
//! [`crate::mutate`] (bytes flipped, cut, duplicated, nested 20 000 deep, numbers made huge,
//! NUL bytes, CR line ends, very long lines). The command's own readers (CSV, whitespace,
//! JSON, airfoils, grids) are fuzzed with the same mutations in `tests/cli/fuzz_readers.rs`. A reader may accept or refuse such a
//! file, but it must neither panic nor overflow its stack, and its message is one line of at
//! most 500 characters however much of the input is garbage.
//!
//! Deterministic (a seeded SplitMix64) and bounded by a case count, not by time, so a failure
//! reproduces; coverage-guided fuzzing is left out of CI.

use cad::{CadModel, Format, Units, WriteOptions};

use crate::common::{curves, surfaces};
use crate::mutate::{mutate, Rng};

/// The longest message a reader may give.
const LONGEST_MESSAGE: usize = 500;

/// Mutations per valid file; with 3 formats × 2 files this is a few seconds in a debug build.
const CASES: usize = 300;

fn valid_files(format: Format) -> Vec<String> {
    let all = curves();
    let mut models = vec![CadModel {
        curves: all[..2].to_vec(),
        surfaces: vec![],
        units: Units::Millimetre,
        tolerance: 1e-6,
    }];
    if format != Format::Dxf {
        models.push(CadModel {
            curves: vec![all[4].clone()],
            surfaces: surfaces(),
            units: Units::Metre,
            tolerance: 1e-7,
        });
    }
    models
        .iter()
        .map(|m| cad::write(m, format, &WriteOptions::default()).unwrap())
        .collect()
}

#[test]
fn mutated_files_are_read_or_refused_in_one_short_line() {
    for format in Format::ALL {
        let (mut accepted, mut refused) = (0, 0);
        for (f, text) in valid_files(format).iter().enumerate() {
            let mut rng = Rng(0x5eed ^ (f as u64) << 8 ^ format as u64);
            for case in 0..CASES {
                let bytes = mutate(text, &mut rng);
                let text = String::from_utf8_lossy(&bytes);
                let outcome = std::panic::catch_unwind(|| cad::read(&text, format));
                let Ok(result) = outcome else {
                    panic!("{format} file {f} case {case}: the reader panicked");
                };
                if let Ok(model) = &result {
                    assert!(
                        finite(model),
                        "{format} file {f} case {case}: a number read is not finite"
                    );
                    accepted += 1;
                } else {
                    refused += 1;
                }
                if let Err(e) = result {
                    let message = e.to_string();
                    assert!(
                        message.chars().count() <= LONGEST_MESSAGE && !message.contains(['\n', '\r']),
                        "{format} file {f} case {case}: a message of {} characters: {}",
                        message.chars().count(),
                        message.chars().take(200).collect::<String>()
                    );
                }
            }
        }
        eprintln!(
            "{format}: {} mutated files, {accepted} read, {refused} refused",
            accepted + refused
        );
        // Neither vacuous nor blind: some mutations survive, some are caught.
        assert!(
            accepted > 0 && refused > 0,
            "{format}: {accepted} read, {refused} refused"
        );
    }
}

/// Whether every number of a model read is finite: knots, control points and weights.
fn finite(model: &CadModel) -> bool {
    let curves = model.curves.iter().all(|c| {
        let curve = &c.curve;
        curve.knots().iter().all(|k| k.is_finite())
            && curve.weights().iter().all(|w| w.is_finite())
            && curve
                .control_points()
                .iter()
                .all(|p| p.iter().all(|v| v.is_finite()))
    });
    let surfaces = model.surfaces.iter().all(|s| {
        let surface = &s.surface;
        let (u, v) = surface.net_size();
        (0..u).all(|i| {
            (0..v).all(|j| {
                surface
                    .control_point(i, j)
                    .is_some_and(|p| p.iter().all(|c| c.is_finite()))
                    && surface.weight(i, j).is_some_and(f64::is_finite)
            })
        })
    });
    curves && surfaces && model.tolerance.is_finite()
}

#[test]
fn twenty_thousand_nested_parentheses_are_refused_naming_the_line() {
    let deep = format!(
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('',{}1.{});\nENDSEC;\nEND-ISO-10303-21;\n",
        "(".repeat(20_000),
        ")".repeat(20_000)
    );
    let message = cad::read(&deep, Format::Step).unwrap_err().to_string();
    assert!(message.starts_with("STEP line 5:"), "{message}");
    assert!(message.contains("nested"), "{message}");
}
