//! Exploration (not committed).
use curve_repr::{HermiteSpline, Vec2};
use fairing::two_phase::{CountGuard, TwoPhase, TwoPhaseSettings};
use fairing::{partition, PartitionSettings, Pipeline, SegmentedFairing};

fn read(path: &str) -> Vec<Vec2> {
    std::fs::read_to_string(path).unwrap().lines().skip(1).filter_map(|l| {
        let mut f = l.split(',').map(|v| v.trim().parse::<f64>().ok());
        Some(Vec2::new(f.next()??, f.next()??))
    }).collect()
}

fn kappa(points: &[Vec2]) -> Vec<f64> {
    let s = HermiteSpline::natural(points).unwrap();
    fairness::curvature::curvature_at_breaks(&s).unwrap()
}

fn infl(k: &[f64]) -> Vec<usize> {
    let m = k.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let idx: Vec<usize> = (0..k.len()).filter(|&i| k[i].abs() > 1e-12 * m).collect();
    idx.windows(2).filter(|w| k[w[0]] * k[w[1]] < 0.0).map(|w| w[1]).collect()
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let input = read(&args[1]);
    let out = &args[2];
    let mut s = TwoPhaseSettings::default();
    let mut p = PartitionSettings::default();
    let mut passes = 3;
    let mut closed = false;
    for a in &args[3..] {
        let (k, v) = a.split_once('=').unwrap();
        match k {
            "limit" => p = p.with_limit(v.parse::<f64>().unwrap().to_radians()),
            "overlap" => p = p.with_overlap(v.parse().unwrap()),
            "passes" => passes = v.parse().unwrap(),
            "max-passes" => s.max_passes = v.parse().unwrap(),
            "mmf" => s.max_move_factor = v.parse().unwrap(),
            "guard" => s.count_guard = match v { "off" => CountGuard::Off, "pass" => CountGuard::Pass, _ => CountGuard::Local },
            "alpha" => s.alpha_divisor = v.parse().unwrap(),
            "cl" => s.coarse_lambda = v.parse().unwrap(),
            "denoise" => s.denoise = if v == "off" { fairing::two_phase::Denoise::Off } else { fairing::two_phase::Denoise::Gcv },
            "max-run" => s.max_run = v.parse().unwrap(),
            "closed" => closed = v == "true",
            _ => panic!("{k}"),
        }
    }
    if std::env::var("DIAG").is_ok() {
        for sg in partition(&input, closed, &p).unwrap() {
            let local = sg.local_points(&input);
            let x: Vec<f64> = local.iter().map(|q| q.x).collect();
            let y: Vec<f64> = local.iter().map(|q| q.y).collect();
            let mut sp = curve_repr::SplineFunction::new(&x, &y, curve_repr::EndCondition::ParabolicRunout).unwrap();
            let before = fairing::two_phase::counts(&sp);
            let c0 = sp.c().to_vec();
            let passes = fairing::two_phase::fair_function(&mut sp, &s, &|k| k > 0 && k + 1 < x.len()).unwrap();
            let after = fairing::two_phase::counts(&sp);
            let c = sp.c();
            let m = c.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let signs: String = c.iter().map(|v| if v.abs() <= 1e-12 * m { '0' } else if *v > 0.0 { '+' } else { '-' }).collect();
            println!("seg {}..{} (vib,infl) {:?} -> {:?} in {} passes\n  {}", sg.indices[0], sg.indices[sg.indices.len()-1], before, after, passes, signs);
            if std::env::var("DIAG").as_deref() == Ok("2") {
                for k in 0..x.len() {
                    println!("   {:3} {:3} y {:+.4} -> {:+.4} (d {:+.4})  c {:+.4} -> {:+.4}", k, sg.indices[k], y[k], sp.y()[k], sp.y()[k]-y[k], c0[k], sp.c()[k]);
                }
            }
            for i in 0..x.len() {
                if let Some(case) = fairing::two_phase::detect_fine(&sp, i, s.max_run) {
                    let d = fairing::two_phase::fine_displacement(&sp, case, &s);
                    let worst = d.as_ref().map(|m| m.iter().map(|&(k, g)| g.abs() / (x[k] - x[k-1]).min(x[k+1]-x[k])).fold(0.0f64, f64::max));
                    println!("   case {:?} at {}..{:?}: max |γ|/h = {:?}", case.kind, case.first, case.second, worst);
                }
            }
        }
    }
    if std::env::var("FUNC").is_ok() {
        let x: Vec<f64> = input.iter().map(|q| q.x).collect();
        let y: Vec<f64> = input.iter().map(|q| q.y).collect();
        let n = x.len();
        let y = fairing::two_phase::denoise(s.denoise, &x, &y, &fairing::two_phase::Limits { keep: &|k| k == 0 || k + 1 == n, allowed: &|_| f64::INFINITY }).unwrap();
        let mut sp = curve_repr::SplineFunction::new(&x, &y, curve_repr::EndCondition::ParabolicRunout).unwrap();
        let before = fairing::two_phase::counts(&sp);
        let passes = fairing::two_phase::fair_function(&mut sp, &s, &|k| k > 0 && k + 1 < x.len()).unwrap();
        println!("function (vib, infl) {:?} -> {:?} in {passes} passes", before, fairing::two_phase::counts(&sp));
        let mut f = String::from("x,y\n");
        for (a, b) in x.iter().zip(sp.y()) { f += &format!("{a},{b}\n"); }
        std::fs::write(out, f).unwrap();
        return;
    }
    let k0 = kappa(&input);
    println!("before: {} inflections at {:?}", infl(&k0).len(), infl(&k0));
    let r = Pipeline::new(SegmentedFairing::new(TwoPhase::new(s)).with_partition(p).with_passes(passes))
        .with_closed(closed).with_max_iterations(passes).run(input.clone()).unwrap();
    let k1 = kappa(&r.points);
    println!("after: {} inflections at {:?}", infl(&k1).len(), infl(&k1));
    let segs = partition(&r.points, closed, &p).unwrap();
    for sg in &segs {
        println!("segment {}..{} turning {:.1}° ob {} oa {}", sg.indices[0], sg.indices[sg.indices.len()-1], sg.turning.to_degrees(), sg.overlap_before, sg.overlap_after);
    }
    let mut f = String::from("x,y\n");
    for q in &r.points { f += &format!("{},{}\n", q.x, q.y); }
    std::fs::write(out, f).unwrap();
}
