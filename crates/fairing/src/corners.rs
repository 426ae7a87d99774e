//! Corners: points where a curve's direction breaks (an airfoil's sharp trailing edge, a hull
//! line's knuckle, a chine, a stem), kept as G0 breaks by every curve method.
//!
//! A smoother fitted across a corner rounds it: the trailing edge of a closed airfoil moves
//! inwards and the chord shortens, a knuckle becomes a fillet, and the fit's curvature spike
//! there costs inflections on both sides. The catalogue therefore splits a curve at its
//! corners, fairs each piece between two corners as an open curve with the corners fixed,
//! and joins the pieces ([`Catalog::run_curve_plan`](crate::catalog::Catalog::run_curve_plan)).
//!
//! **Detection** ([`detect`]): only on data whose noise is small against their spacing
//! ([`MAX_NOISE_TO_SPACING`]: tabulated offsets, airfoil tables, CAD points; a noisy scan's
//! corners are declared). The turn at point i over reach r is the angle between the
//! chords P_{i−r}P_i and P_iP_{i+r}; a corner turns by at least [`CORNER_TURN`] over every
//! reach r = 1, 2, 3, and then doubling while r stays within 2 % of the points (and, on an open
//! curve, within the points on either side; a corner of an open curve lies at least 3 points
//! from an end, 6 from 300 points on). A smooth curve sampled with more than eight
//! points per turn of 2π turns by less at r = 1; noise as large as the spacing turns a point
//! sharply over one step but not over chords many times the noise (the reaches that double);
//! a corner turns at every reach. Its turn is concentrated at the point: its two neighbours
//! turn by at most half as much over one step ([`MAX_NEIGHBOUR_TURN`]; a round nose sampled
//! too sparsely to resolve it turns at every reach but spreads its turn over its neighbours).
//! Of neighbouring candidates the one that turns most is kept.
//! Planar and spatial curves alike (the angle between the chords). O(n log n).

use std::f64::consts::PI;

use curve_repr::Vector;

/// The least turn (radians, at every reach) of a corner: 45°.
pub const CORNER_TURN: f64 = PI / 4.0;

/// Which points of a curve are corners.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Corners {
    /// The points [`detect`] finds (the default).
    #[default]
    Auto,
    /// None: every method fits across every point.
    None,
    /// These points (indices from 0), and no others.
    At(Vec<usize>),
}

/// The most the two neighbours of a corner may turn over one step, together, as a fraction of
/// the corner's own turn over one step ([`detect`]).
///
/// One half: on the embedded tables the Gunnerus waterline 3 knuckle's neighbours turn 0.42
/// of it and R140's trailing edge's 0.02, while the UA(2)-180 nose (three points over about
/// 110° of its round) turns 0.68 and an arc sampled evenly 2.
pub const MAX_NEIGHBOUR_TURN: f64 = 0.5;

/// The most noise, as a fraction of the spacing (the median, and the candidate's own two
/// steps), at which [`detect`] looks for corners.
///
/// Where the noise is comparable to the spacing, the turn over a few points is the noise's
/// (on the noisy analytic curves of `examples/default_judge.py`'s tuning set, from 1× noise,
/// where σ is 0.2–1.6 spacings, 45° turns at reaches 1–3 were found by the dozen on sines,
/// arcs and helices, and fairing the pieces apart left many times the clean inflections); at
/// a tenth of the spacing a turn of 45° over one point is no noise's. Data that noisy get no
/// corners unless they are declared.
pub const MAX_NOISE_TO_SPACING: f64 = 0.1;

/// The noise σ̂ of the points: jump-lsq's, the third differences' estimate of each coordinate
/// ([`difference_noise`](crate::smoothing::difference_noise)), root of the sum of squares.
/// O(n).
pub fn noise<const D: usize>(points: &[Vector<D>], closed: bool) -> f64 {
    crate::strategies::jump_lsq::curve_noise(points, [true; D], closed)
}

/// The median distance between consecutive points (0 for fewer than two). O(n).
fn median_spacing<const D: usize>(points: &[Vector<D>]) -> f64 {
    let mut chords: Vec<f64> = points.windows(2).map(|w| (w[1] - w[0]).norm()).collect();
    if chords.is_empty() {
        return 0.0;
    }
    let middle = chords.len() / 2;
    *chords.select_nth_unstable_by(middle, f64::total_cmp).1
}

impl Corners {
    /// `Auto` or `None` by the word every front end takes for them (`auto`, `none`); `None`
    /// for any other word (a front end then reads a list of indices).
    pub fn named(word: &str) -> Option<Corners> {
        match word {
            "auto" => Some(Corners::Auto),
            "none" => Some(Corners::None),
            _ => None,
        }
    }
}

/// The reaches over which [`detect`] measures a turn on a curve of `n` points: 1, 2, 3, then
/// doubling while within 2 % of the points.
fn reaches(n: usize) -> Vec<usize> {
    let mut out = vec![1, 2, 3];
    let mut reach = 6;
    while reach <= n / 50 {
        out.push(reach);
        reach *= 2;
    }
    out
}

/// The angle (radians, in [0, π]) between the vectors `a` and `b`; 0 if either vanishes.
fn angle<const D: usize>(a: &Vector<D>, b: &Vector<D>) -> f64 {
    let (na, nb) = (a.norm(), b.norm());
    if na == 0.0 || nb == 0.0 {
        return 0.0;
    }
    // atan2 of |a × b| (from the Lagrange identity) and a · b: accurate at small angles too.
    let dot = a.dot(b);
    let cross = ((na * nb).powi(2) - dot * dot).max(0.0).sqrt();
    cross.atan2(dot)
}

/// The corners of a curve (`closed`: the last point joins the first, given once), sorted.
/// Fewer than 5 points have none. O(n log n).
pub fn detect<const D: usize>(points: &[Vector<D>], closed: bool) -> Vec<usize> {
    let n = points.len();
    if n < 5 {
        return Vec::new();
    }
    let sigma = noise(points, closed);
    if sigma > MAX_NOISE_TO_SPACING * median_spacing(points) {
        return Vec::new();
    }
    // Locally too: where the spacing shrinks (an airfoil's cosine-spaced trailing edge) the
    // noise is larger against it than the median says.
    let least_step = sigma / MAX_NOISE_TO_SPACING;
    let reaches = reaches(n);
    // Near an open curve's end only the short reaches fit, over which noise alone turns a
    // dense curve sharply: a corner there must be measured over at least the reaches up to 6
    // (up to 3 below 300 points).
    let needed = reaches.iter().copied().filter(|&r| r <= 6).max().unwrap_or(1);
    let turn = |i: usize| -> f64 {
        if !closed && (i < needed || i + needed >= n) {
            return 0.0;
        }
        let (before, after) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        if (points[i] - before).norm().min((after - points[i]).norm()) < least_step {
            return 0.0;
        }
        let mut least = f64::INFINITY;
        for &r in &reaches {
            let (before, after) = if closed {
                if 2 * r >= n {
                    break;
                }
                ((i + n - r) % n, (i + r) % n)
            } else {
                if r > i || i + r >= n {
                    break;
                }
                (i - r, i + r)
            };
            least = least.min(angle(&(points[i] - points[before]), &(points[after] - points[i])));
        }
        if least.is_finite() {
            least
        } else {
            0.0
        }
    };
    // The turn over one step, and whether it is concentrated at i: a round nose sampled too
    // sparsely to resolve it turns by 45° over every reach too, but its neighbours turn about
    // as much (an arc sampled evenly: together twice as much); a corner's neighbours lie on
    // its edges.
    let step_turn = |i: usize| -> f64 {
        if !closed && (i == 0 || i + 1 >= n) {
            return 0.0;
        }
        let (before, after) = (points[(i + n - 1) % n], points[(i + 1) % n]);
        angle(&(points[i] - before), &(after - points[i]))
    };
    let concentrated = |i: usize| {
        let beside = step_turn((i + n - 1) % n) + step_turn((i + 1) % n);
        beside <= MAX_NEIGHBOUR_TURN * step_turn(i)
    };
    let range = if closed { 0..n } else { 1..n - 1 };
    let turns: Vec<(usize, f64)> = range
        .map(|i| (i, turn(i)))
        .filter(|t| t.1 >= CORNER_TURN && concentrated(t.0))
        .collect();
    // Of candidates within three points of each other (cyclically when closed), the one that
    // turns most.
    let near = |a: usize, b: usize| {
        let d = a.abs_diff(b);
        (if closed { d.min(n - d) } else { d }) <= 3
    };
    // `turns` is sorted by index, so a candidate within three points of another is within three
    // places of it in `turns` (or, closed, among the first and last three places): O(k).
    let k = turns.len();
    let mut out: Vec<usize> = Vec::new();
    for (place, &(i, t)) in turns.iter().enumerate() {
        let around = place.saturating_sub(3)..(place + 4).min(k);
        let wrap = if closed {
            (0..3.min(k)).chain(k.saturating_sub(3)..k)
        } else {
            (0..0).chain(0..0)
        };
        let beaten = around.chain(wrap).any(|q| {
            let (j, u) = turns[q];
            j != i && near(i, j) && (u > t || (u == t && j < i))
        });
        if !beaten {
            out.push(i);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::{Vec2, Vec3};

    /// A deterministic normal-ish noise (sum of uniforms), for tests without rand.
    fn noise(seed: u64, n: usize, sigma: f64) -> Vec<f64> {
        let mut state = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        (0..n)
            .map(|_| sigma * ((0..12).map(|_| uniform()).sum::<f64>() - 6.0))
            .collect()
    }

    #[test]
    fn a_noisy_circle_and_a_noisy_sine_have_none() {
        for (n, seed) in [(40, 1), (200, 2), (2_000, 3)] {
            let e = noise(seed, 2 * n, 0.01);
            let circle: Vec<Vec2> = (0..n)
                .map(|k| {
                    let t = 2.0 * PI * k as f64 / n as f64;
                    Vec2::new(2.0 * t.cos() + e[2 * k], 2.0 * t.sin() + e[2 * k + 1])
                })
                .collect();
            assert_eq!(detect(&circle, true), Vec::<usize>::new(), "circle of {n}");
            let sine: Vec<Vec2> = (0..n)
                .map(|k| {
                    let x = 20.0 * k as f64 / (n - 1) as f64;
                    Vec2::new(x, (x / 2.0).sin() + e[k])
                })
                .collect();
            assert_eq!(detect(&sine, false), Vec::<usize>::new(), "sine of {n}");
        }
    }

    /// A straight line sampled as an airfoil (cosine spacing, 160 points) with noise of a
    /// tenth of the median spacing: near its ends the steps are far below the noise and
    /// the turns there the noise's; no corner is read there.
    #[test]
    fn the_noise_is_weighed_against_the_local_spacing() {
        let n = 160;
        let e = noise(5, n, 0.0006);
        let line: Vec<Vec2> = (0..n)
            .map(|k| {
                let x = (1.0 - (PI * k as f64 / (n - 1) as f64).cos()) / 2.0;
                Vec2::new(x, 0.1 * x + e[k])
            })
            .collect();
        let sigma = noise_of(&line);
        assert!(sigma < MAX_NOISE_TO_SPACING * median_spacing(&line), "{sigma}");
        assert_eq!(detect(&line, false), Vec::<usize>::new());
    }

    fn noise_of(points: &[Vec2]) -> f64 {
        super::noise(points, false)
    }

    /// A flat ellipse (semi-axes 1 and 0.2, 24 points even in its parameter) turns by more
    /// than 45° at every reach at its two tips (67°, 107°, 128°), but its neighbours turn 0.93
    /// as much over one step: no corner.
    #[test]
    fn a_sparsely_sampled_round_tip_is_no_corner() {
        let n = 24;
        let ellipse: Vec<Vec2> = (0..n)
            .map(|k| {
                let t = 2.0 * PI * k as f64 / n as f64;
                Vec2::new(t.cos(), 0.2 * t.sin())
            })
            .collect();
        assert_eq!(detect(&ellipse, true), Vec::<usize>::new());
    }

    /// A noisy square (20 points a side) has its four vertices and nothing else; a V-shaped
    /// function its knuckle; a helix bent at a point in 3D that point.
    #[test]
    fn vertices_and_knuckles_are_found_where_they_are() {
        let side = 20;
        let e = noise(7, 8 * side, 0.002);
        let vertices = [
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ];
        let square: Vec<Vec2> = (0..4 * side)
            .map(|k| {
                let (v, t) = (k / side, (k % side) as f64 / side as f64);
                let p = vertices[v] * (1.0 - t) + vertices[(v + 1) % 4] * t;
                Vec2::new(p.x + e[2 * k], p.y + e[2 * k + 1])
            })
            .collect();
        assert_eq!(detect(&square, true), [0, side, 2 * side, 3 * side]);
        let v: Vec<Vec2> = (0..41)
            .map(|k| {
                let x = k as f64 / 40.0;
                Vec2::new(x, (x - 0.6).abs() + 0.3 * x * x)
            })
            .collect();
        assert_eq!(detect(&v, false), [24]);
        let bent: Vec<Vec3> = (0..60)
            .map(|k| {
                let t = k as f64 / 10.0;
                let z = if k <= 30 { t } else { 3.0 - (t - 3.0) };
                Vec3::new(t.cos(), t.sin(), z)
            })
            .collect();
        assert_eq!(detect(&bent, false), [30]);
    }
}
