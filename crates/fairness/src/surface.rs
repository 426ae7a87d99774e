//! Indicators and energies of surfaces, through the [`Surface`] trait and the knot vectors.
//!
//! - Zhang–Cheng Eq. (26), corrected (papers/README.md): at an interior knot (u_i, v_j),
//!   z_ij = |S_uuu(u_i+, v_j) − S_uuu(u_i−, v_j)| + |S_vvv(u_i, v_j+) − S_vvv(u_i, v_j−)|.
//! - The thin-plate energy ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|² du dv (the integrand of
//!   Zhang–Cheng Eq. 27–29), by a Gauss–Legendre product rule on every knot cell. The default
//!   4 × 4 points are exact for bicubic polynomial patches (each term has degree ≤ 6 in u and
//!   in v); rational surfaces need more points.
//! - The network strain energy Σ_j ∫ |S_uu(u, v_j)|² du + Σ_i ∫ |S_vv(u_i, v)|² dv over every
//!   knot line (docs/CONTRACT.md's `e_s` of the surface kind), Gauss–Legendre per knot interval.
//!
//! The [`Surface`] trait does not expose knots, so every function and type here takes the
//! knot vectors u_0 < … < u_m and v_0 < … < v_n (the data parameters of an interpolating
//! surface).
//!
//! **Seams.** A surface closed in v (its knot line v = v_n is the knot line v = v_0 again, as
//! the teapot body's column 12 is its column 0) has no boundary there: its seam nodes are
//! interior nodes like any other, and [`surface_jumps_closed`] measures z across the seam,
//! S_vvv(u_i, v_0+) − S_vvv(u_i, v_n−), from the surface alone (independently of how the
//! surface was built). Likewise in u.

use curve_repr::{Side, Surface, Vec3};

use crate::quadrature::GaussLegendre;
use crate::{Criterion, Error, LocalIndicator, Result};

fn check_knots(what: &'static str, knots: &[f64]) -> Result<()> {
    if knots.len() < 2 {
        return Err(Error::TooFewPoints {
            what,
            needed: 2,
            got: knots.len(),
        });
    }
    if let Some(index) = knots.iter().position(|k| !k.is_finite()) {
        return Err(Error::NonFiniteInput { what, index });
    }
    if let Some(index) = knots.windows(2).position(|w| w[1] <= w[0]) {
        return Err(curve_repr::Error::NotIncreasing {
            what,
            index: index + 1,
            previous: knots[index],
            value: knots[index + 1],
        }
        .into());
    }
    Ok(())
}

/// A partial derivative that must exist and be finite.
#[allow(clippy::too_many_arguments)]
fn partial<S: Surface + ?Sized>(
    surface: &S,
    what: &'static str,
    u: f64,
    v: f64,
    du: usize,
    dv: usize,
    side_u: Side,
    side_v: Side,
) -> Result<Vec3> {
    match surface.partial_from(u, v, du, dv, side_u, side_v) {
        Some(p) if p.iter().all(|c| c.is_finite()) => Ok(p),
        _ => Err(Error::NonFinite {
            what,
            parameter: if du > 0 { u } else { v },
        }),
    }
}

/// z_ij of Zhang–Cheng Eq. (26) at every interior knot, rows i = 1 … m − 1, columns
/// j = 1 … n − 1 (so `result[i − 1][j − 1]` is z_ij). O(m n).
pub fn surface_jumps<S: Surface + ?Sized>(
    surface: &S,
    u_knots: &[f64],
    v_knots: &[f64],
) -> Result<Vec<Vec<f64>>> {
    surface_jumps_closed(surface, u_knots, v_knots, (false, false))
}

/// z_ij of Zhang–Cheng Eq. (26) at every interior knot of a surface closed in u and/or v
/// (`closed` = (u, v)): along a closed direction the nodes are k = 0 … N − 1 (node 0 is the
/// seam, node N its repeat, not listed again) and the jump at the seam is taken between the
/// first interval's start and the last interval's end; along an open one k = 1 … N − 1. So
/// `result[a][b]` is z at (i, j) = (a + 1, b + 1) for an open surface and (a, b) along a
/// closed direction. Needs four knots along a closed direction. O(m n).
pub fn surface_jumps_closed<S: Surface + ?Sized>(
    surface: &S,
    u_knots: &[f64],
    v_knots: &[f64],
    closed: (bool, bool),
) -> Result<Vec<Vec<f64>>> {
    check_knots("u knots", u_knots)?;
    check_knots("v knots", v_knots)?;
    for (what, knots, is_closed) in [("u knots", u_knots, closed.0), ("v knots", v_knots, closed.1)] {
        if is_closed && knots.len() < 4 {
            return Err(Error::TooFewPoints {
                what,
                needed: 4,
                got: knots.len(),
            });
        }
    }
    // (parameter for the left limit, parameter for the right limit) at each node.
    let nodes = |k: &[f64], is_closed: bool| -> Vec<(f64, f64)> {
        let last = k.len() - 1;
        if is_closed {
            std::iter::once((k[last], k[0]))
                .chain(k[1..last].iter().map(|&t| (t, t)))
                .collect()
        } else {
            k[1..last].iter().map(|&t| (t, t)).collect()
        }
    };
    let (us, vs) = (nodes(u_knots, closed.0), nodes(v_knots, closed.1));
    us.iter()
        .map(|&(u_left, u_right)| {
            vs.iter()
                .map(|&(v_left, v_right)| {
                    let what = "third partial derivative";
                    // The u-jump runs along the u-line v = v_j: any of the node's two v
                    // parameters names it (they are the same line when closed).
                    let uuu_right = partial(surface, what, u_right, v_right, 3, 0, Side::Right, Side::Right)?;
                    let uuu_left = partial(surface, what, u_left, v_right, 3, 0, Side::Left, Side::Right)?;
                    let vvv_right = partial(surface, what, u_right, v_right, 0, 3, Side::Right, Side::Right)?;
                    let vvv_left = partial(surface, what, u_right, v_left, 0, 3, Side::Right, Side::Left)?;
                    Ok((uuu_right - uuu_left).norm() + (vvv_right - vvv_left).norm())
                })
                .collect::<Result<Vec<f64>>>()
        })
        .collect()
}

/// ∫∫ |S_uu|² + 2|S_uv|² + |S_vv|² over one cell [u0, u1] × [v0, v1] with a product rule
/// (the term of Zhang–Cheng Eq. 27–29 for patch (l, k)). O(points²).
pub fn thin_plate_cell<S: Surface + ?Sized>(
    surface: &S,
    u: (f64, f64),
    v: (f64, f64),
    rule: &GaussLegendre,
) -> Result<f64> {
    let (hu, hv) = (0.5 * (u.1 - u.0), 0.5 * (v.1 - v.0));
    let (mu, mv) = (0.5 * (u.0 + u.1), 0.5 * (v.0 + v.1));
    let mut sum = 0.0;
    for (x, wx) in rule.nodes().iter().zip(rule.weights()) {
        for (y, wy) in rule.nodes().iter().zip(rule.weights()) {
            let (s, t) = (mu + hu * x, mv + hv * y);
            let what = "second partial derivative";
            let suu = partial(surface, what, s, t, 2, 0, Side::Right, Side::Right)?;
            let suv = partial(surface, what, s, t, 1, 1, Side::Right, Side::Right)?;
            let svv = partial(surface, what, s, t, 0, 2, Side::Right, Side::Right)?;
            sum += wx * wy * (suu.norm_squared() + 2.0 * suv.norm_squared() + svv.norm_squared());
        }
    }
    let value = sum * hu * hv;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite {
            what: "thin-plate energy",
            parameter: u.0,
        })
    }
}

/// The thin-plate energy over the whole knot grid, the sum of [`thin_plate_cell`] over every
/// cell. O(m n points²).
pub fn thin_plate_energy<S: Surface + ?Sized>(
    surface: &S,
    u_knots: &[f64],
    v_knots: &[f64],
    rule: &GaussLegendre,
) -> Result<f64> {
    check_knots("u knots", u_knots)?;
    check_knots("v knots", v_knots)?;
    let mut total = 0.0;
    for u in u_knots.windows(2) {
        for v in v_knots.windows(2) {
            total += thin_plate_cell(surface, (u[0], u[1]), (v[0], v[1]), rule)?;
        }
    }
    Ok(total)
}

/// The network strain energy Σ_j ∫ |S_uu(u, v_j)|² du + Σ_i ∫ |S_vv(u_i, v)|² dv over all
/// knot lines, boundary lines included, Gauss–Legendre per knot interval. O(m n points).
pub fn network_strain_energy<S: Surface + ?Sized>(
    surface: &S,
    u_knots: &[f64],
    v_knots: &[f64],
    rule: &GaussLegendre,
) -> Result<f64> {
    check_knots("u knots", u_knots)?;
    check_knots("v knots", v_knots)?;
    let mut total = 0.0;
    for &v in v_knots {
        total += rule.integrate_pieces(
            "network strain energy",
            |u| {
                surface
                    .partial_from(u, v, 2, 0, Side::Right, Side::Right)
                    .map_or(f64::NAN, |p| p.norm_squared())
            },
            u_knots,
        )?;
    }
    for &u in u_knots {
        total += rule.integrate_pieces(
            "network strain energy",
            |v| {
                surface
                    .partial_from(u, v, 0, 2, Side::Right, Side::Right)
                    .map_or(f64::NAN, |p| p.norm_squared())
            },
            v_knots,
        )?;
    }
    Ok(total)
}

/// Settings shared by the surface indicators: the knot vectors and the quadrature points.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotGrid {
    /// u_0 < … < u_m.
    pub u_knots: Vec<f64>,
    /// v_0 < … < v_n.
    pub v_knots: Vec<f64>,
    /// Gauss–Legendre points per direction and knot interval (default 4: exact for bicubic
    /// polynomial patches).
    pub points: usize,
    /// Whether the surface is closed in (u, v): [`SurfaceJump`] then measures z across the
    /// seam too ([`surface_jumps_closed`]). Default open.
    pub closed: (bool, bool),
}

impl KnotGrid {
    /// The grid with 4 quadrature points.
    pub fn new(u_knots: Vec<f64>, v_knots: Vec<f64>) -> Self {
        KnotGrid {
            u_knots,
            v_knots,
            points: 4,
            closed: (false, false),
        }
    }

    /// Sets which directions are closed (u, v).
    pub fn with_closed(mut self, closed_u: bool, closed_v: bool) -> Self {
        self.closed = (closed_u, closed_v);
        self
    }

    /// Sets the Gauss–Legendre points per direction and knot interval.
    pub fn with_points(mut self, points: usize) -> Self {
        self.points = points;
        self
    }
}

/// [`LocalIndicator`] of [`surface_jumps_closed`] (of [`surface_jumps`] for an open grid),
/// flattened row by row (i outer, j inner).
#[derive(Clone, Debug, PartialEq)]
pub struct SurfaceJump(pub KnotGrid);

impl<S: Surface + ?Sized> LocalIndicator<S> for SurfaceJump {
    fn name(&self) -> &str {
        "surface-jump"
    }
    fn values(&self, surface: &S) -> Result<Vec<f64>> {
        Ok(
            surface_jumps_closed(surface, &self.0.u_knots, &self.0.v_knots, self.0.closed)?
                .into_iter()
                .flatten()
                .collect(),
        )
    }
}

/// [`Criterion`] of [`thin_plate_energy`].
#[derive(Clone, Debug, PartialEq)]
pub struct ThinPlateEnergy(pub KnotGrid);

impl<S: Surface + ?Sized> Criterion<S> for ThinPlateEnergy {
    fn name(&self) -> &str {
        "thin-plate-energy"
    }
    fn evaluate(&self, surface: &S) -> Result<f64> {
        let rule = GaussLegendre::new(self.0.points)?;
        thin_plate_energy(surface, &self.0.u_knots, &self.0.v_knots, &rule)
    }
}

/// [`Criterion`] of [`network_strain_energy`].
#[derive(Clone, Debug, PartialEq)]
pub struct NetworkStrainEnergy(pub KnotGrid);

impl<S: Surface + ?Sized> Criterion<S> for NetworkStrainEnergy {
    fn name(&self) -> &str {
        "network-strain-energy"
    }
    fn evaluate(&self, surface: &S) -> Result<f64> {
        let rule = GaussLegendre::new(self.0.points)?;
        network_strain_energy(surface, &self.0.u_knots, &self.0.v_knots, &rule)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_curves::{HeightSurface, Kinked};

    fn surface(c: f64) -> HeightSurface {
        HeightSurface {
            f: Kinked {
                alpha: 2.0,
                beta: -1.0,
                knot: 1.0,
            },
            g: Kinked {
                alpha: 0.5,
                beta: 4.0,
                knot: 2.0,
            },
            c,
            domain: ((0.0, 3.0), (0.0, 4.0)),
        }
    }

    /// S = (u, v, f(u) + g(v) + c u²v) with f‴ jumping by β − α = −3 at u = 1 and g‴ by 3.5
    /// at v = 2: z = 3 on the line u = 1, 3.5 on the line v = 2, 6.5 where they cross, 0
    /// elsewhere (c u²v is smooth and adds nothing).
    #[test]
    fn surface_jumps_find_the_constructed_jumps() {
        let u = [0.0, 1.0, 2.0, 3.0];
        let v = [0.0, 1.0, 2.0, 3.0, 4.0];
        let z = surface_jumps(&surface(0.7), &u, &v).unwrap();
        let expected = [[3.0, 6.5, 3.0], [0.0, 3.5, 0.0]];
        assert_eq!(z.len(), 2);
        for (row, want) in z.iter().zip(&expected) {
            assert_eq!(row.len(), 3);
            for (g, w) in row.iter().zip(want) {
                assert!((g - w).abs() < 1e-12, "{z:?}");
            }
        }
        let flat = SurfaceJump(KnotGrid::new(u.to_vec(), v.to_vec()));
        assert_eq!(flat.max_value(&surface(0.7)).unwrap(), 6.5);
    }

    /// For the height u²v (f = g = 0, c = 1): S_uu = (0, 0, 2v), S_uv = (0, 0, 2u), S_vv = 0.
    /// Thin plate over [0, U] × [0, V]: ∫∫ 4v² + 8u² = 4UV³/3 + 8VU³/3.
    /// Network: Σ_j ∫₀^U 4v_j² du = 4U Σ_j v_j² (the v-lines add nothing).
    #[test]
    fn energies_of_a_polynomial_surface() {
        let s = HeightSurface {
            f: Kinked {
                alpha: 0.0,
                beta: 0.0,
                knot: 1.0,
            },
            g: Kinked {
                alpha: 0.0,
                beta: 0.0,
                knot: 1.0,
            },
            c: 1.0,
            domain: ((0.0, 2.0), (0.0, 3.0)),
        };
        let u = vec![0.0, 0.5, 2.0];
        let v = vec![0.0, 1.0, 1.5, 3.0];
        let (uu, vv) = (2.0_f64, 3.0_f64);
        let plate = ThinPlateEnergy(KnotGrid::new(u.clone(), v.clone()))
            .evaluate(&s)
            .unwrap();
        let expected = 4.0 * uu * vv.powi(3) / 3.0 + 8.0 * vv * uu.powi(3) / 3.0;
        assert!((plate - expected).abs() < 1e-12 * expected, "{plate} {expected}");
        let network = NetworkStrainEnergy(KnotGrid::new(u, v.clone()))
            .evaluate(&s)
            .unwrap();
        let expected = 4.0 * uu * v.iter().map(|x| x * x).sum::<f64>();
        assert!(
            (network - expected).abs() < 1e-12 * expected,
            "{network} {expected}"
        );
    }

    /// With the kinked f, S_uu = f″(u) + 2cv is piecewise linear in u: the per-interval rule
    /// stays exact because the kink is at a knot. Checked against a 64-point rule per cell.
    #[test]
    fn thin_plate_with_kinks_at_knots_is_exact() {
        let s = surface(0.3);
        let u = vec![0.0, 1.0, 3.0];
        let v = vec![0.0, 2.0, 4.0];
        let four = thin_plate_energy(&s, &u, &v, &GaussLegendre::new(4).unwrap()).unwrap();
        let many = thin_plate_energy(&s, &u, &v, &GaussLegendre::new(64).unwrap()).unwrap();
        assert!((four - many).abs() < 1e-12 * many);
    }

    /// A noisy tube closed in v: z across the seam, from one-sided partials of the surface,
    /// equals the bicubic surface's own O(1) jump formula at every node, the seam's included,
    /// and the open measure leaves the seam column out.
    #[test]
    fn jumps_across_a_seam_match_the_periodic_surface() {
        use curve_repr::{BicubicSplineSurface, BicubicSurfaceSettings};
        let (rows, columns) = (6, 10);
        let grid: Vec<Vec<Vec3>> = (0..rows)
            .map(|i| {
                (0..columns)
                    .map(|j| {
                        let k = j % (columns - 1);
                        let angle = std::f64::consts::TAU * k as f64 / (columns - 1) as f64;
                        let r = 1.0 + 0.05 * ((3 * i + 7 * k) as f64).sin();
                        Vec3::new(r * angle.cos(), r * angle.sin(), 0.4 * i as f64)
                    })
                    .collect()
            })
            .collect();
        let settings = BicubicSurfaceSettings::default().with_closed_v(true);
        let s = BicubicSplineSurface::with_settings(&grid, &settings).unwrap();
        let z = surface_jumps_closed(&s, s.u_knots(), s.v_knots(), (false, true)).unwrap();
        assert_eq!((z.len(), z[0].len()), (rows - 2, columns - 1));
        for (a, row) in z.iter().enumerate() {
            for (b, &value) in row.iter().enumerate() {
                let own = s.z(a + 1, b).unwrap();
                assert!(
                    (value - own).abs() < 1e-9 * (1.0 + own),
                    "({a}, {b}): {value} vs {own}"
                );
            }
        }
        assert!(z.iter().all(|row| row[0] > 1e-3), "the seam has jumps of its own");
        let open = surface_jumps(&s, s.u_knots(), s.v_knots()).unwrap();
        assert_eq!(open[0].len(), columns - 2);
        let indicator =
            SurfaceJump(KnotGrid::new(s.u_knots().to_vec(), s.v_knots().to_vec()).with_closed(false, true));
        let (measured, own) = (indicator.max_value(&s).unwrap(), s.max_z());
        assert!((measured - own).abs() < 1e-9 * own, "{measured} vs {own}");
    }

    #[test]
    fn bad_knots_are_errors() {
        let s = surface(0.0);
        assert!(matches!(
            surface_jumps(&s, &[0.0], &[0.0, 1.0]),
            Err(Error::TooFewPoints { .. })
        ));
        assert!(surface_jumps(&s, &[0.0, 0.0, 1.0], &[0.0, 1.0]).is_err());
        assert!(surface_jumps(&s, &[0.0, f64::NAN], &[0.0, 1.0]).is_err());
        let grid = KnotGrid::new(vec![0.0, 1.0], vec![0.0, 1.0]).with_points(0);
        assert!(ThinPlateEnergy(grid.clone()).evaluate(&s).is_err());
        assert!(NetworkStrainEnergy(grid).evaluate(&s).is_err());
    }
}
