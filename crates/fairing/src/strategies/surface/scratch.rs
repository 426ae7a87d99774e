use super::*;
use curve_repr::{BicubicSurfaceSettings, GridTopology};

fn read(rel: &str) -> Vec<Vec<Vec3>> {
    let path = format!("{}/../../data/{rel}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(path).unwrap();
    let mut cells = Vec::new();
    for line in text.lines().skip(1) {
        let f: Vec<f64> = line.split(',').map(|x| x.trim().parse().unwrap()).collect();
        cells.push((f[0] as usize, f[1] as usize, Vec3::new(f[2], f[3], f[4])));
    }
    let rows = cells.iter().map(|c| c.0).max().unwrap() + 1;
    let cols = cells.iter().map(|c| c.1).max().unwrap() + 1;
    let mut net = vec![vec![Vec3::zeros(); cols]; rows];
    for (i, j, p) in cells { net[i][j] = p; }
    net
}

fn zmap(points: &[Vec3], r: usize, c: usize) -> (BicubicSplineSurface, Vec<((usize, usize), f64)>) {
    let t = GridTopology::detect(points, r, c);
    let s = BicubicSplineSurface::from_flat(points.to_vec(), r, c, &BicubicSurfaceSettings::default().with_topology(&t)).unwrap();
    let z: Vec<_> = s.interior_nodes().map(|(i, j)| ((i, j), s.z(i, j).unwrap())).collect();
    (s, z)
}

#[test]
fn scratch_teapot() {
    for rel in ["surface_utah_teapot/teapot_body_surface_points.csv", "surface_utah_teapot/teapot_body_control_net.csv"] {
        let net = read(rel);
        let (r, c) = (net.len(), net[0].len());
        let before: Vec<Vec3> = net.iter().flatten().copied().collect();
        let (_, z0) = zmap(&before, r, c);
        let mut sorted = z0.clone();
        sorted.sort_by(|a, b| b.1.total_cmp(&a.1));
        println!("{rel}: top z before {:?}", &sorted[..6]);
        let settings = SurfaceFairingSettings::zhang_cheng().with_guard(false).with_max_steps(1);
        let result = SurfaceFairing::new(settings).run(&net).unwrap();
        println!("topology {:?}", result.topology);
        let (_, z1) = zmap(result.surface.points(), r, c);
        let mut rise: Vec<_> = z0.iter().zip(&z1).map(|(a, b)| (a.0, a.1, b.1)).collect();
        rise.sort_by(|a, b| b.2.total_cmp(&a.2));
        println!("top z after 1 step {:?}", &rise[..6]);
        let radii = result.radii.unwrap();
        for &((i, j), _, _) in &rise[..4] {
            println!("node ({i},{j}) radius {} moved {}", radii[i * c + j], (result.surface.points()[i*c+j] - before[i*c+j]).norm());
        }
    }
}

#[test]
#[ignore]
fn scratch_speed() {
    let size = 200;
    let net: Vec<Vec<Vec3>> = (0..size)
        .map(|i| {
            (0..size)
                .map(|j| {
                    let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
                    let noise = 0.01 * ((i * 7919 + j * 104_729) as f64 * 12.9898).sin().fract();
                    Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + noise)
                })
                .collect()
        })
        .collect();
    for steps in [1usize, 5] {
        let t = std::time::Instant::now();
        let r = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_max_steps(steps)).run(&net).unwrap();
        println!("{steps} steps: {:?} {:?} z {} -> {}", t.elapsed(), r.termination, r.start.max_z, r.history.last().map_or(0.0, |s| s.max_z));
    }
}

#[test]
fn scratch_teapot_guarded() {
    for rel in ["surface_utah_teapot/teapot_body_surface_points.csv", "surface_utah_teapot/teapot_body_control_net.csv"] {
        let net = read(rel);
        let (r, c) = (net.len(), net[0].len());
        let before: Vec<Vec3> = net.iter().flatten().copied().collect();
        for (name, settings) in [("zc", SurfaceFairingSettings::zhang_cheng()), ("kj", SurfaceFairingSettings::kjellander())] {
            let result = SurfaceFairing::new(settings).run(&net).unwrap();
            let after = result.surface.points();
            let m = |p: &[Vec3], closed: bool| {
                let t = if closed { GridTopology::detect(p, r, c) } else { GridTopology::open() };
                let s = BicubicSplineSurface::from_flat(p.to_vec(), r, c, &BicubicSurfaceSettings::default().with_topology(&t)).unwrap();
                (s.max_z(), s.network_strain_energy())
            };
            println!("{rel} {name}: closed {:?} -> {:?}, open {:?} -> {:?}; steps {}, pinned {}, moved {}, refused steps {} moves {}, {:?} {:?}",
                m(&before, true), m(after, true), m(&before, false), m(after, false), result.steps, result.pinned.len(), result.moved.len(), result.refused_steps, result.refused_moves, result.termination, result.refusal);
        }
    }
}

fn noise(i: usize, j: usize, s: usize) -> f64 {
    let x = ((i * 7919 + j * 104_729 + s * 1_299_709) as f64 * 12.9898).sin() * 43_758.545_3;
    2.0 * (x - x.floor()) - 1.0
}

#[test]
#[ignore]
fn scratch_grid() {
    let size = 200;
    let net: Vec<Vec<Vec3>> = (0..size)
        .map(|i| (0..size).map(|j| {
            let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
            Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + 0.01 * noise(i, j, 3))
        }).collect())
        .collect();
    for scale in [1.0, 3.0] {
        let t = std::time::Instant::now();
        let result = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_radius_scale(scale)).run(&net).unwrap();
        println!("scale {scale}: {:?}, steps {}, {:?} {:?}", t.elapsed(), result.steps, result.termination, result.refusal);
        for (k, s) in result.history.iter().enumerate().take(60) { if k % 5 == 0 { println!("  step {k}: z {:.3} e {:.3} moves {}", s.max_z, s.energy, s.moves); } }
        let s = &result.surface;
        let mut z: Vec<_> = s.interior_nodes().map(|(i, j)| ((i, j), s.z(i, j).unwrap())).collect();
        z.sort_by(|a, b| b.1.total_cmp(&a.1));
        let radii = result.radii.as_ref().unwrap();
        for &((i, j), v) in &z[..8] {
            let k = i * size + j;
            println!("  ({i},{j}) z {v:.3} radius {:.4} moved {:.4}", radii[k], (s.points()[k] - result.original[k]).norm());
        }
        let held = (0..size*size).filter(|&k| radii[k] > 0.0 && (s.points()[k] - result.original[k]).norm() >= radii[k] * (1.0 - 1e-9)).count();
        println!("  at their sphere: {held} of {}", (size-2)*(size-2));
    }
}

fn twisted() -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let clean: Vec<Vec<Vec3>> = (0..26).map(|i| {
        let angle = std::f64::consts::FRAC_PI_2 * i as f64 / 25.0;
        (0..9).map(|j| { let r = j as f64 - 4.0; Vec3::new(i as f64, r * angle.cos(), r * angle.sin()) }).collect()
    }).collect();
    let mut noisy = clean.clone();
    for i in 1..25 { for j in 1..8 {
        let angle = std::f64::consts::FRAC_PI_2 * i as f64 / 25.0;
        noisy[i][j] += Vec3::new(0.0, -angle.sin(), angle.cos()) * (0.03 * noise(i, j, 1));
    } }
    (clean, noisy)
}
fn panel() -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let clean: Vec<Vec<Vec3>> = (0..13).map(|i| (0..13).map(|j| {
        let (x, y) = (100.0 * i as f64, 75.0 * j as f64);
        Vec3::new(x, y, 60.0 * (1.0 - ((x - 600.0) / 700.0).powi(2)) + 25.0 * (y / 900.0).powi(2) + 0.02 * x)
    }).collect()).collect();
    let mut b = clean.clone();
    for ((i, j), h) in [((3, 4), 3.0), ((8, 3), -2.0), ((9, 3), -2.5), ((6, 8), 2.0), ((7, 9), 2.5)] { b[i][j].z += h; }
    (clean, b)
}
fn tube() -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let make = |a: f64| -> Vec<Vec<Vec3>> { (0..24).map(|i| (0..=32).map(|j| {
        let k = j % 32; let angle = std::f64::consts::TAU * k as f64 / 32.0; let z = 0.15 * i as f64;
        let r = 1.0 + 0.1 * z + a * noise(i, k, 2); Vec3::new(r * angle.cos(), r * angle.sin(), z) }).collect()).collect() };
    (make(0.0), make(0.01))
}
fn grid(size: usize) -> (Vec<Vec<Vec3>>, Vec<Vec<Vec3>>) {
    let make = |a: f64| -> Vec<Vec<Vec3>> { (0..size).map(|i| (0..size).map(|j| {
        let (x, y) = (i as f64 / 10.0, j as f64 / 10.0);
        Vec3::new(x, y, (0.3 * x).sin() * (0.2 * y).cos() + a * noise(i, j, 3)) }).collect()).collect() };
    (make(0.0), make(0.01))
}

#[test]
#[ignore]
fn scratch_regions() {
    let nets = [("twisted", twisted()), ("panel", panel()), ("tube", tube()), ("grid100", grid(100))];
    for (name, (clean, noisy)) in &nets {
        let (r, c) = (noisy.len(), noisy[0].len());
        let flat = |n: &Vec<Vec<Vec3>>| -> Vec<Vec3> { n.iter().flatten().copied().collect() };
        let (cf, nf) = (flat(clean), flat(noisy));
        let rms = |a: &[Vec3]| (a.iter().zip(&cf).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt();
        let zm = |p: &[Vec3]| { let t = GridTopology::detect(p, r, c); BicubicSplineSurface::from_flat(p.to_vec(), r, c, &BicubicSurfaceSettings::default().with_topology(&t)).unwrap().max_z() };
        let (z0, rms0) = (zm(&nf), rms(&nf));
        for region in [Region::Sphere, Region::MedianFloor] {
            for scale in [1.0, 2.0, 3.0, 5.0, f64::INFINITY] {
                for tol in [1e-6, 1e-4] {
                    let t = std::time::Instant::now();
                    let res = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_region(region).with_radius_scale(scale).with_tolerance(tol)).run(noisy).unwrap();
                    let p = res.surface.points();
                    let sd: f64 = p.iter().zip(&nf).map(|(a, b)| (a - b).norm()).sum();
                    println!("{name:8} {region:?} ×{scale} tol {tol:e}: z {:.3}× rms {:.3}× S_d {:.3e} steps {} {:?} {:?} {:.0} ms",
                        zm(p) / z0, rms(p) / rms0, sd, res.steps, res.termination, res.refusal, t.elapsed().as_secs_f64() * 1e3);
                }
            }
        }
    }
}

#[test]
#[ignore]
fn scratch_profile() {
    let (_, noisy) = grid(std::env::var("SIZE").ok().and_then(|v| v.parse().ok()).unwrap_or(200));
    let t = std::time::Instant::now();
    let res = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_region(Region::MedianFloor).with_radius_scale(1.5).with_tolerance(1e-3).with_max_steps(30)).run(&noisy).unwrap();
    println!("{:?} steps {} {:?} {:?} pinned {} refused {} {}", t.elapsed(), res.steps, res.termination, res.refusal, res.pinned.len(), res.refused_steps, res.refused_moves);
    for s in &res.history { println!("  z {:.3} e {:.3} moves {}", s.max_z, s.energy, s.moves); }
}

#[test]
#[ignore]
fn scratch_steps() {
    for (name, (clean, noisy)) in [("grid100", grid(100)), ("twisted", twisted()), ("tube", tube()), ("panel", panel())] {
        let (r, c) = (noisy.len(), noisy[0].len());
        let flat = |n: &Vec<Vec<Vec3>>| -> Vec<Vec3> { n.iter().flatten().copied().collect() };
        let (cf, nf) = (flat(&clean), flat(&noisy));
        let rms = |a: &[Vec3]| (a.iter().zip(&cf).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt();
        let zm = |p: &[Vec3]| { let t = GridTopology::detect(p, r, c); BicubicSplineSurface::from_flat(p.to_vec(), r, c, &BicubicSurfaceSettings::default().with_topology(&t)).unwrap().max_z() };
        let (z0, rms0) = (zm(&nf), rms(&nf));
        for scale in [1.0, 1.5, 2.0] {
            let mut line = format!("{name} MF×{scale}:");
            for steps in [2, 4, 8, 16, 32, 64] {
                let res = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_region(Region::MedianFloor).with_radius_scale(scale).with_tolerance(0.0).with_max_steps(steps)).run(&noisy).unwrap();
                let p = res.surface.points();
                let e = res.history.last().map_or(0.0, |s| s.energy);
                line += &format!(" [{steps}: z {:.3} rms {:.3} e {:.4e}]", zm(p) / z0, rms(p) / rms0, e);
            }
            println!("{line}");
        }
    }
}

#[test]
#[ignore]
fn scratch_omega() {
    for (name, (clean, noisy)) in [("grid100", grid(100)), ("twisted", twisted()), ("tube", tube()), ("panel", panel())] {
        let (r, c) = (noisy.len(), noisy[0].len());
        let flat = |n: &Vec<Vec<Vec3>>| -> Vec<Vec3> { n.iter().flatten().copied().collect() };
        let (cf, nf) = (flat(&clean), flat(&noisy));
        let rms = |a: &[Vec3]| (a.iter().zip(&cf).map(|(p, q)| (p - q).norm_squared()).sum::<f64>() / a.len() as f64).sqrt();
        let zm = |p: &[Vec3]| { let t = GridTopology::detect(p, r, c); BicubicSplineSurface::from_flat(p.to_vec(), r, c, &BicubicSurfaceSettings::default().with_topology(&t)).unwrap().max_z() };
        let (z0, rms0) = (zm(&nf), rms(&nf));
        for omega in ["lazy", "sort"] {
            if omega == "sort" { std::env::set_var("SURFACE_SORT", "1"); } else { std::env::remove_var("SURFACE_SORT"); }
            let mut line = format!("{name} ω {omega}:");
            for steps in [4, 8, 16, 32] {
                let res = SurfaceFairing::new(SurfaceFairingSettings::zhang_cheng().with_region(Region::MedianFloor).with_radius_scale(1.5).with_tolerance(0.0).with_max_steps(steps)).run(&noisy).unwrap();
                let p = res.surface.points();
                let e = res.history.last().map_or(0.0, |s| s.energy);
                line += &format!(" [{steps}: z {:.3} rms {:.3} e {:.4e}{}]", zm(p) / z0, rms(p) / rms0, e, if res.refusal.is_some() {"R"} else {""});
            }
            println!("{line}");
        }
    }
}
