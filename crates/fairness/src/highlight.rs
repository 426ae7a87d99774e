//! Highlight lines (Beier & Chen, *Highlight-line algorithm for realtime surface-quality
//! assessment*, CAD 26 (1994)), the visual check Zhang–Cheng §4.4–5 fair surfaces by.
//!
//! A family of parallel linear light sources lies in a light plane: line k passes through
//! A + k·d·D with direction E (E, D orthonormal, the plane's normal L = E × D). A surface
//! point S with unit normal N lies on highlight line k when the normal line S + μN meets light
//! line k. Where N is not parallel to the plane, the normal line meets the plane once, at
//! Q = S + μN with μ = (A − S)·L / (N·L), and it meets light line k exactly when
//! Q lies on it, i.e. when the **highlight function**
//!
//! h(u, v) = (Q − A)·D
//!
//! equals k·d. So the highlight lines are level sets of h: it is sampled on a fine (u, v)
//! grid and contoured by [`marching_squares`] at the light lines' levels. Normals that miss
//! the plane (N·L ≈ 0) leave a gap. The same [`LightSetup`] must be used before and after
//! fairing so that the pictures compare. O(samples) per surface.

use std::collections::HashMap;

use curve_repr::{Surface, Vec3};

/// Settings of the light and the sampling.
#[derive(Debug, Clone, PartialEq)]
pub struct HighlightSettings {
    /// Number of light lines across the highlight range (Zhang–Cheng used 20). Default 20.
    pub lines: usize,
    /// Samples per unit of the surface's larger parameter range, in each direction:
    /// the (u, v) grid has about `samples` × `samples` points. Default 160.
    pub samples: usize,
    /// Direction E of the light lines; default the surface's first principal direction.
    pub light_direction: Option<Vec3>,
}

impl Default for HighlightSettings {
    fn default() -> Self {
        Self {
            lines: 20,
            samples: 160,
            light_direction: None,
        }
    }
}

impl HighlightSettings {
    /// Sets the number of light lines.
    pub fn with_lines(mut self, lines: usize) -> Self {
        self.lines = lines;
        self
    }
    /// Sets the sampling density.
    pub fn with_samples(mut self, samples: usize) -> Self {
        self.samples = samples;
        self
    }
    /// Sets the light lines' direction.
    pub fn with_light_direction(mut self, direction: Vec3) -> Self {
        self.light_direction = Some(direction);
        self
    }
}

/// A light plane with its family of light lines, and the view the lines are drawn in.
#[derive(Debug, Clone, PartialEq)]
pub struct LightSetup {
    /// A point on light line 0.
    pub origin: Vec3,
    /// Unit direction E of the light lines.
    pub direction: Vec3,
    /// Unit direction D across the lines, in the plane.
    pub across: Vec3,
    /// The levels h = k·d of the light lines.
    pub levels: Vec<f64>,
    /// Unit view axes: drawn coordinates are (p·x_axis, p·y_axis).
    pub view: (Vec3, Vec3),
}

/// One highlight line, drawn in the view plane.
pub type Polyline = Vec<[f64; 2]>;

fn sample_grid<S: Surface + ?Sized>(surface: &S, samples: usize) -> (Vec<f64>, Vec<f64>) {
    let ((u0, u1), (v0, v1)) = surface.domain();
    let largest = (u1 - u0).abs().max((v1 - v0).abs()).max(f64::MIN_POSITIVE);
    let count = |a: f64, b: f64| (((b - a).abs() / largest) * samples as f64).ceil().max(2.0) as usize;
    let (nu, nv) = (count(u0, u1), count(v0, v1));
    let along = |a: f64, b: f64, n: usize| (0..=n).map(|k| a + (b - a) * k as f64 / n as f64).collect();
    (along(u0, u1, nu), along(v0, v1, nv))
}

impl LightSetup {
    /// A light plane above `surface` (along its mean normal, one bounding-box diagonal away),
    /// light lines along `settings.light_direction` or the principal direction of the sampled
    /// points, spaced so that `settings.lines` lines span the 2nd–98th percentile of h on this
    /// surface; the
    /// view looks along the mean normal. `None` when the surface has no usable normal.
    pub fn for_surface<S: Surface + ?Sized>(surface: &S, settings: &HighlightSettings) -> Option<LightSetup> {
        let (us, vs) = sample_grid(surface, 24);
        let mut points = Vec::new();
        let mut normal = Vec3::zeros();
        for &u in &us {
            for &v in &vs {
                points.push(surface.eval(u, v));
                if let Some(n) = surface.normal(u, v) {
                    normal += n;
                }
            }
        }
        let normal = normal.try_normalize(1e-12)?;
        let centroid = points.iter().sum::<Vec3>() / points.len() as f64;
        let (low, high) = points.iter().fold(
            (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
            |(l, h), p| (l.inf(p), h.sup(p)),
        );
        let diagonal = (high - low).norm();
        // Principal direction in the plane normal to the mean normal (power iteration).
        let mut direction = settings.light_direction.unwrap_or_else(|| {
            let mut e = normal.cross(&Vec3::x());
            if e.norm() < 0.1 {
                e = normal.cross(&Vec3::y());
            }
            for _ in 0..50 {
                let mut next = Vec3::zeros();
                for p in &points {
                    let d = p - centroid;
                    let d = d - normal * d.dot(&normal);
                    next += d * d.dot(&e);
                }
                match next.try_normalize(1e-300) {
                    Some(n) => e = n,
                    None => break,
                }
            }
            e
        });
        direction = (direction - normal * direction.dot(&normal)).try_normalize(1e-12)?;
        let across = normal.cross(&direction);
        let origin = centroid + normal * diagonal.max(1e-9);
        let mut setup = LightSetup {
            origin,
            direction,
            across,
            levels: Vec::new(),
            view: (direction, across),
        };
        let values: Vec<f64> = {
            let (us, vs) = sample_grid(surface, settings.samples.max(8));
            us.iter()
                .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
                .filter_map(|(u, v)| setup.highlight(surface, u, v))
                .collect()
        };
        // The 2nd to 98th percentile of h: normals that graze the light plane send h far out
        // and would leave every line but one outside the surface's typical range.
        let mut sorted = values;
        sorted.sort_by(f64::total_cmp);
        let quantile = |q: f64| {
            let last = sorted.len().saturating_sub(1);
            sorted.get((last as f64 * q).round() as usize).copied()
        };
        let (Some(lo), Some(hi)) = (quantile(0.02), quantile(0.98)) else {
            return Some(setup);
        };
        if hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
            return Some(setup);
        }
        let lines = settings.lines.max(1);
        let spacing = (hi - lo) / lines as f64;
        setup.levels = (0..lines).map(|k| lo + (k as f64 + 0.5) * spacing).collect();
        Some(setup)
    }

    /// The plane's unit normal L = E × D.
    pub fn plane_normal(&self) -> Vec3 {
        self.direction.cross(&self.across)
    }

    /// The highlight function h(u, v) = (Q − A)·D (module docs), or `None` where the normal
    /// is undefined or (nearly) parallel to the light plane.
    pub fn highlight<S: Surface + ?Sized>(&self, surface: &S, u: f64, v: f64) -> Option<f64> {
        let point = surface.eval(u, v);
        let normal = surface.normal(u, v)?;
        let plane = self.plane_normal();
        let facing = normal.dot(&plane);
        if facing.abs() < 1e-3 {
            return None;
        }
        let mu = (self.origin - point).dot(&plane) / facing;
        let q = point + normal * mu;
        let h = (q - self.origin).dot(&self.across);
        h.is_finite().then_some(h)
    }

    /// Projects a point into the view plane.
    pub fn project(&self, p: &Vec3) -> [f64; 2] {
        [p.dot(&self.view.0), p.dot(&self.view.1)]
    }

    /// The highlight lines of `surface` under this light, sampled on a (u, v) grid of about
    /// `samples` × `samples` points, contoured and drawn in the view plane. O(samples²).
    pub fn lines<S: Surface + ?Sized>(&self, surface: &S, samples: usize) -> Vec<Polyline> {
        let (us, vs) = sample_grid(surface, samples.max(8));
        let values: Vec<Vec<f64>> = us
            .iter()
            .map(|&u| {
                vs.iter()
                    .map(|&v| self.highlight(surface, u, v).unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        let mut out = Vec::new();
        for &level in &self.levels {
            for line in marching_squares(&values, level) {
                let drawn = line
                    .iter()
                    .map(|&[a, b]| {
                        let u = interpolate(&us, a);
                        let v = interpolate(&vs, b);
                        self.project(&surface.eval(u, v))
                    })
                    .collect();
                out.push(drawn);
            }
        }
        out
    }
}

/// The value at fractional index `t` of an increasing sample list.
fn interpolate(samples: &[f64], t: f64) -> f64 {
    let last = samples.len().saturating_sub(1);
    let k = (t.floor().max(0.0) as usize).min(last.saturating_sub(1));
    let f = t - k as f64;
    match (samples.get(k), samples.get(k + 1)) {
        (Some(a), Some(b)) => a + (b - a) * f,
        (Some(a), None) => *a,
        _ => 0.0,
    }
}

/// The level set `values = level` of a sampled grid `values[a][b]`, as polylines in
/// fractional index coordinates (a, b), by marching squares: each cell's edges whose end
/// values straddle the level get a crossing by linear interpolation; a cell with two
/// crossings joins them, one with four (a saddle) pairs them by the cell's mean value; the
/// segments are chained through the crossings they share. Cells with a NaN corner are
/// skipped. O(cells).
pub fn marching_squares(values: &[Vec<f64>], level: f64) -> Vec<Vec<[f64; 2]>> {
    let rows = values.len();
    let columns = values.iter().map(Vec::len).min().unwrap_or(0);
    if rows < 2 || columns < 2 {
        return Vec::new();
    }
    // A crossing is identified by its grid edge: (a, b, horizontal?) — horizontal means the
    // edge from (a, b) to (a + 1, b).
    type Key = (usize, usize, bool);
    let above = |x: f64| x > level;
    let crossing = |key: Key| -> [f64; 2] {
        let (a, b, along_a) = key;
        let (p, q) = if along_a {
            (values[a][b], values[a + 1][b])
        } else {
            (values[a][b], values[a][b + 1])
        };
        let t = ((level - p) / (q - p)).clamp(0.0, 1.0);
        if along_a {
            [a as f64 + t, b as f64]
        } else {
            [a as f64, b as f64 + t]
        }
    };
    let mut links: HashMap<Key, Vec<Key>> = HashMap::new();
    let mut link = |x: Key, y: Key| {
        links.entry(x).or_default().push(y);
        links.entry(y).or_default().push(x);
    };
    for a in 0..rows - 1 {
        for b in 0..columns - 1 {
            let corners = [
                values[a][b],
                values[a + 1][b],
                values[a + 1][b + 1],
                values[a][b + 1],
            ];
            if corners.iter().any(|c| !c.is_finite()) {
                continue;
            }
            // Edges in order around the cell: bottom, right, top, left.
            let edges: [(Key, usize, usize); 4] = [
                ((a, b, true), 0, 1),
                ((a + 1, b, false), 1, 2),
                ((a, b + 1, true), 3, 2),
                ((a, b, false), 0, 3),
            ];
            let cut: Vec<Key> = edges
                .iter()
                .filter(|(_, p, q)| above(corners[*p]) != above(corners[*q]))
                .map(|(k, _, _)| *k)
                .collect();
            match cut.len() {
                2 => link(cut[0], cut[1]),
                4 => {
                    let centre_above = above(corners.iter().sum::<f64>() / 4.0);
                    // Corner 0 above ⇔ its neighbours are below (saddle). Join the crossings
                    // around the corners that share the centre's side.
                    if centre_above == above(corners[0]) {
                        link(cut[0], cut[1]);
                        link(cut[2], cut[3]);
                    } else {
                        link(cut[0], cut[3]);
                        link(cut[1], cut[2]);
                    }
                }
                _ => {}
            }
        }
    }
    // Chain: start at ends (one link) first, then what is left (closed loops).
    let mut keys: Vec<Key> = links.keys().copied().collect();
    keys.sort_unstable_by_key(|k| (links[k].len() != 1, *k));
    let mut used: HashMap<Key, bool> = HashMap::new();
    let mut out = Vec::new();
    for start in keys {
        if used.get(&start).copied().unwrap_or(false) {
            continue;
        }
        let mut chain = vec![crossing(start)];
        used.insert(start, true);
        let mut current = start;
        loop {
            let next = links[&current]
                .iter()
                .copied()
                .find(|k| !used.get(k).copied().unwrap_or(false));
            match next {
                Some(k) => {
                    used.insert(k, true);
                    chain.push(crossing(k));
                    current = k;
                }
                None => {
                    // Close a loop.
                    if links[&current].contains(&start) && chain.len() > 2 {
                        chain.push(crossing(start));
                    }
                    break;
                }
            }
        }
        if chain.len() >= 2 {
            out.push(chain);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use curve_repr::BicubicSplineSurface;

    #[test]
    fn marching_squares_traces_a_circle() {
        let n = 41;
        let values: Vec<Vec<f64>> = (0..n)
            .map(|a| {
                (0..n)
                    .map(|b| ((a as f64 - 20.0).powi(2) + (b as f64 - 20.0).powi(2)).sqrt())
                    .collect()
            })
            .collect();
        let lines = marching_squares(&values, 12.3);
        assert_eq!(lines.len(), 1);
        let line = &lines[0];
        assert_eq!(line.first(), line.last(), "a closed loop");
        assert!(line.len() > 60);
        for p in line {
            let r = ((p[0] - 20.0).powi(2) + (p[1] - 20.0).powi(2)).sqrt();
            assert!((r - 12.3).abs() < 0.05, "{r}");
        }
        // Two lines for a level that cuts the square's corners off twice (open chains).
        let saddle: Vec<Vec<f64>> = (0..n)
            .map(|a| (0..n).map(|b| (a as f64 - 20.0) * (b as f64 - 20.0)).collect())
            .collect();
        let lines = marching_squares(&saddle, 50.0);
        assert_eq!(lines.len(), 2);
        for line in &lines {
            for p in line {
                assert!(((p[0] - 20.0) * (p[1] - 20.0) - 50.0).abs() < 2.0);
            }
        }
    }

    /// A bumpy height field as a bicubic surface.
    fn bump() -> BicubicSplineSurface {
        let grid: Vec<Vec<Vec3>> = (0..9)
            .map(|i| {
                (0..9)
                    .map(|j| {
                        let (x, y) = (i as f64, j as f64);
                        Vec3::new(
                            x,
                            y,
                            0.4 * (-((x - 4.0).powi(2) + (y - 4.0).powi(2)) / 4.0).exp() + 0.05 * x,
                        )
                    })
                    .collect()
            })
            .collect();
        BicubicSplineSurface::new(&grid).unwrap()
    }

    #[test]
    fn on_a_highlight_line_the_normal_line_meets_the_light_line() {
        let surface = bump();
        let setup = LightSetup::for_surface(&surface, &HighlightSettings::default().with_lines(10)).unwrap();
        assert_eq!(setup.levels.len(), 10);
        let mut checked = 0;
        for (k, &level) in setup.levels.iter().enumerate() {
            // Walk along v = const in u until h crosses the level, then bisect.
            let ((u0, u1), (v0, v1)) = surface.domain();
            for step in 1..8 {
                let v = v0 + (v1 - v0) * step as f64 / 8.0;
                let f = |u: f64| setup.highlight(&surface, u, v).map(|h| h - level);
                let mut grid: Vec<f64> = (0..=200).map(|t| u0 + (u1 - u0) * t as f64 / 200.0).collect();
                grid.retain(|&u| f(u).is_some());
                for w in grid.windows(2) {
                    let (fa, fb) = (f(w[0]).unwrap(), f(w[1]).unwrap());
                    if fa * fb < 0.0 {
                        let (mut a, mut b) = (w[0], w[1]);
                        for _ in 0..60 {
                            let m = 0.5 * (a + b);
                            if f(m).unwrap() * f(a).unwrap() <= 0.0 {
                                b = m
                            } else {
                                a = m
                            }
                        }
                        let u = 0.5 * (a + b);
                        // Distance between the normal line and light line k (skew-line formula).
                        let s = surface.eval(u, v);
                        let n = surface.normal(u, v).unwrap();
                        let a_k = setup.origin + setup.across * level;
                        let cross = n.cross(&setup.direction);
                        let distance = (a_k - s).dot(&cross).abs() / cross.norm();
                        assert!(distance < 1e-9, "line {k}: distance {distance}");
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 10, "{checked}");
    }

    #[test]
    fn drawn_lines_lie_on_their_levels() {
        let surface = bump();
        let setup = LightSetup::for_surface(&surface, &HighlightSettings::default()).unwrap();
        let lines = setup.lines(&surface, 120);
        assert!(lines.len() >= setup.levels.len());
        // On a plane every normal line is parallel, so h is affine in the point and the
        // highlight lines are straight: h at a midpoint is the mean of h at the ends.
        let flat: Vec<Vec<Vec3>> = (0..4)
            .map(|i| {
                (0..4)
                    .map(|j| Vec3::new(i as f64, j as f64, 0.3 * i as f64))
                    .collect()
            })
            .collect();
        let flat = BicubicSplineSurface::new(&flat).unwrap();
        let h = |u: f64, v: f64| setup.highlight(&flat, u, v).unwrap();
        let (a, b) = ((0.2, 0.4), (2.6, 1.9));
        let mid = h(0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
        assert!((mid - 0.5 * (h(a.0, a.1) + h(b.0, b.1))).abs() < 1e-9);
        assert!((h(a.0, a.1) - h(b.0, b.1)).abs() > 1e-3);
    }
}
