//! Every reader of the command against mutated files: CSV (with a header and labels, and
//! without), whitespace tables, JSON (an object with other keys, and a bare array), Selig and
//! Lednicer airfoils, surface grids — each read by its extension and, sniffed, as standard
//! input. The mutations are the CAD readers' ([`crate::mutate`], shared with
//! `crates/cad/tests/cad/fuzz.rs`): bytes flipped, cut, duplicated, brackets nested 20 000
//! deep, numbers made huge, NUL bytes, CR line ends, lines of 10 000+ characters.
//!
//! A reader may accept or refuse a mutated file, but it must not panic; a refusal is one line
//! of at most [`LONGEST`] characters; an accepted file has only finite numbers. Deterministic
//! (seeded) and bounded by a case count, so a failure reproduces; a few seconds in a debug
//! build.

use fair::fair_cli::input::{self, Source};

use crate::mutate::{mutate, Rng};

/// The longest message a reader may give, `FILE:LINE: ` included.
const LONGEST: usize = 500;

/// Mutations per sample and way of reading it.
const CASES: usize = 1000;

/// Valid samples: (what, file name, text).
fn samples() -> Vec<(&'static str, &'static str, String)> {
    let rows = |f: &dyn Fn(usize, f64, f64) -> String| -> String {
        (0..30)
            .map(|k| {
                let x = k as f64 / 29.0;
                f(k, x, (3.0 * x).sin() * 0.25 + 1e-3 * k as f64)
            })
            .collect()
    };
    let json_points = (0..30)
        .map(|k| format!("[{}, {}]", k as f64 / 29.0, (k as f64 / 9.0).cos()))
        .collect::<Vec<_>>()
        .join(",\n  ");
    let mut grid = String::from("i,j,x,y,z\n");
    let mut moved_grid = String::from("x, y, z, j, i\n");
    for i in 0..5 {
        for j in 0..4 {
            let z = 0.1 * (i * j) as f64 + 0.01 * ((i + j) % 2) as f64;
            grid.push_str(&format!("{i},{j},{i},{j},{z}\n"));
            moved_grid.push_str(&format!("{i}, {j}, {z}, {j}, {i}\n"));
        }
    }
    let upper: String = (0..15)
        .map(|k| {
            let x = k as f64 / 14.0;
            format!("{x:.6} {:.6}\n", 0.1 * (std::f64::consts::PI * x).sin())
        })
        .collect();
    let lower: String = (0..15)
        .map(|k| {
            let x = k as f64 / 14.0;
            format!("{x:.6} {:.6}\n", -0.06 * (std::f64::consts::PI * x).sin())
        })
        .collect();
    let selig: String = upper
        .lines()
        .rev()
        .chain(lower.lines().skip(1))
        .map(|l| format!("{l}\n"))
        .collect();
    vec![
        (
            "csv",
            "labelled.csv",
            format!("x,y,z,station\n{}", rows(&|k, x, y| format!("{x},{y},{},st {k}\n", 0.5 * y))),
        ),
        ("csv", "plain.csv", rows(&|_, x, y| format!("{x},{y}\n"))),
        (
            "whitespace",
            "named.txt",
            format!("y x label\n{}", rows(&|k, x, y| format!("{y} {x} p{k}\n"))),
        ),
        ("whitespace", "plain.txt", rows(&|_, x, y| format!("{x}\t{y}\n"))),
        (
            "json",
            "doc.json",
            format!(
                "{{\n \"name\": \"section 3\",\n \"id\": 12345678901234567890123,\n \"points\": [\n  {json_points}\n ],\n \"meta\": {{\"units\": \"m\", \"tags\": [1, 2.5e-3, null, true]}}\n}}\n"
            ),
        ),
        ("json", "bare.json", format!("[{json_points}]")),
        ("selig", "foil.dat", format!("NACA-like foil\n{selig}")),
        ("lednicer", "led.dat", format!("LEDNICER FOIL\n15. 15.\n\n{upper}\n{lower}")),
        ("grid", "grid.csv", grid),
        ("grid", "moved.csv", moved_grid),
    ]
}

/// What a reader did with one mutated file: `true` when it accepted it.
fn outcome(what: &str, source: &Source) -> Result<bool, String> {
    let read = std::panic::catch_unwind(|| {
        if what == "grid" {
            input::grid::parse(source).map(|s| s.grid.points.iter().all(|p| p.iter().all(|c| c.is_finite())))
        } else {
            input::parse_curve(source).map(|c| c.points.first_non_finite().is_none())
        }
    });
    match read {
        Err(_) => Err("the reader panicked".into()),
        Ok(Ok(true)) => Ok(true),
        Ok(Ok(false)) => Err("a number read is not finite".into()),
        Ok(Err(e)) => {
            let message = e.to_string();
            if message.chars().count() > LONGEST || message.contains(['\n', '\r']) {
                Err(format!(
                    "a message of {} characters or lines: {}",
                    message.chars().count(),
                    message.chars().take(200).collect::<String>()
                ))
            } else {
                Ok(false)
            }
        }
    }
}

#[test]
fn mutated_files_are_read_or_refused_in_one_short_line() {
    let started = std::time::Instant::now();
    // (format, accepted, refused)
    let mut counts: Vec<(&str, usize, usize)> = Vec::new();
    for (s, (what, name, text)) in samples().into_iter().enumerate() {
        // The sample itself is read.
        assert_eq!(
            outcome(what, &Source::from_text(name, &text)),
            Ok(true),
            "{name} unmutated"
        );
        let mut rng = Rng(0xf00d ^ (s as u64) << 12);
        let (mut accepted, mut refused) = (0, 0);
        for case in 0..CASES {
            let bytes = mutate(&text, &mut rng);
            let mutated = String::from_utf8_lossy(&bytes);
            // Half by the file's extension, half sniffed from standard input.
            let source_name = if case % 2 == 0 { name } else { "-" };
            let source = Source::from_text(source_name, &mutated);
            match outcome(what, &source) {
                Ok(true) => accepted += 1,
                Ok(false) => refused += 1,
                Err(problem) => panic!("{name} case {case} (as {source_name}): {problem}"),
            }
        }
        match counts.iter_mut().find(|c| c.0 == what) {
            Some(c) => {
                c.1 += accepted;
                c.2 += refused;
            }
            None => counts.push((what, accepted, refused)),
        }
    }
    for (what, accepted, refused) in &counts {
        eprintln!(
            "{what}: {} mutated files, {accepted} read, {refused} refused",
            accepted + refused
        );
        // Neither vacuous nor blind: some mutations survive, some are caught.
        assert!(
            *accepted > 0 && *refused > 0,
            "{what}: {accepted} read, {refused} refused"
        );
    }
    eprintln!("{:.1} s", started.elapsed().as_secs_f64());
}
