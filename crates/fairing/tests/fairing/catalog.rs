//! The catalogue: parameter tables derived from the settings types, `--set` text and config
//! values read through the settings' schema, presets, plans and pipelines, criteria and
//! indicators by name.

use curve_repr::{Curve, Side, Vec2};
use fairing::catalog::{
    Catalog, ConfigFile, CriterionEntry, CurveJob, CurveKind, CurvePoints, MethodKind, ParameterMap,
    PlanConstraints,
};
use fairing::{Constraints, Error};
use fairness::FnCriterion;

/// The UA(2)-180 upper surface (x increasing), from `data/`.
pub(crate) fn ua2_180_upper() -> Vec<Vec2> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../data/airfoil_ua2-180/ua2-180_upper.csv"
    ))
    .unwrap();
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.trim().parse().unwrap()).collect();
            Vec2::new(v[0], v[1])
        })
        .collect()
}

fn sets(pairs: &[(&str, &str)]) -> ParameterMap {
    ParameterMap::from_sets(pairs.iter().copied())
}

#[test]
fn the_parameter_table_is_read_from_the_settings() {
    let catalog = Catalog::builtin();
    for kind in [MethodKind::Curve, MethodKind::Surface] {
        for method in catalog.methods(kind) {
            assert!(!method.parameters().is_empty(), "{}", method.name());
            for p in method.parameters() {
                // Kebab-case names, a one-line meaning from the field's doc comment, and the
                // default as the settings' Default serialises it.
                assert!(
                    p.name
                        .chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'),
                    "{}: {}",
                    method.name(),
                    p.name
                );
                assert!(
                    !p.meaning.is_empty() && !p.meaning.contains('\n'),
                    "{}: {}",
                    method.name(),
                    p.name
                );
                assert_eq!(
                    Some(&p.default_value),
                    method.defaults().get(&p.name),
                    "{}",
                    p.name
                );
            }
        }
    }
    let two_phase = catalog.method(MethodKind::Curve, "two-phase").unwrap();
    let defaults = fairing::two_phase::TwoPhaseSettings::default();
    let max_passes = two_phase.parameter("max-passes").unwrap();
    assert_eq!(max_passes.default, defaults.max_passes.to_string());
    assert_eq!(two_phase.parameter("coarse-lambda").unwrap().default, "0.8");
    assert_eq!(two_phase.parameter("count-guard").unwrap().default, "local");
    // The arbitrary-curve options are in the same list.
    for name in ["segment-passes", "turning-limit", "overlap", "closed"] {
        assert!(two_phase.parameter(name).is_some(), "{name}");
    }
    let table = catalog.table();
    assert!(table.contains("max-passes=50"), "{table}");
    assert!(table.contains("p=auto"), "{table}");
    assert!(table.contains("range=inf"), "{table}");
}

#[test]
fn set_text_is_read_by_the_parameter_type() {
    let catalog = Catalog::builtin();
    let strain = catalog.method(MethodKind::Curve, "strain-energy").unwrap();
    let settings = strain
        .settings(&sets(&[
            ("pairs", "on"),
            ("max-iterations", "20"),
            ("radius-scale", "inf"),
        ]))
        .unwrap();
    assert_eq!(settings["pairs"], true);
    assert_eq!(settings["max-iterations"], 20);
    assert_eq!(settings["radius-scale"], "inf");
    let typed: fairing::strategies::StrainEnergySettings = serde_json::from_value(settings).unwrap();
    assert!(typed.pairs && typed.radius_scale == f64::INFINITY && typed.max_iterations == 20);
    let smoothing = catalog.method(MethodKind::Curve, "smoothing-spline").unwrap();
    assert_eq!(smoothing.settings(&sets(&[("p", "auto")])).unwrap()["p"], "auto");
    assert_eq!(smoothing.settings(&sets(&[("p", "0.5")])).unwrap()["p"], 0.5);
    let two_phase = catalog.method(MethodKind::Curve, "two-phase").unwrap();
    assert_eq!(
        two_phase.settings(&sets(&[("max-passes", "20")])).unwrap()["max-passes"],
        20
    );
    // A value of the wrong type, or out of range, names the parameter and where it was given.
    let e = two_phase.settings(&sets(&[("max-passes", "2.5")])).unwrap_err();
    assert!(
        matches!(&e, Error::Parameter { origin, .. } if origin == "--set"),
        "{e}"
    );
    assert!(e.to_string().contains("max-passes"), "{e}");
    let e = two_phase.settings(&sets(&[("coarse-lambda", "3")])).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("--set: `two-phase`: coarse-lambda = 3 is out of range"),
        "{e}"
    );
    let e = smoothing.settings(&sets(&[("rule", "newton")])).unwrap_err();
    assert!(e.to_string().contains("gcv"), "{e}");
    // A config value given as a string is read like text; a typed one as it is.
    let mut given = ParameterMap::new();
    given.insert_json("pairs", serde_json::json!("off"), "c.toml:2");
    given.insert_json("energy-tolerance", serde_json::json!(1e-3), "c.toml:3");
    let settings = strain.settings(&given).unwrap();
    assert_eq!(settings["pairs"], false);
    assert_eq!(settings["energy-tolerance"], 1e-3);
    let mut given = ParameterMap::new();
    given.insert_json("max-iterations", serde_json::json!(-1), "c.toml:7");
    let e = strain.settings(&given).unwrap_err();
    assert_eq!(
        e.to_string(),
        "c.toml:7: `strain-energy`: max-iterations = -1 is out of range: an integer ≥ 0"
    );
}

#[test]
fn unknown_names_are_refused_with_the_known_ones() {
    let catalog = Catalog::builtin();
    let batten = catalog.method(MethodKind::Curve, "batten").unwrap();
    let e = batten.settings(&sets(&[("zz", "1")])).unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("--set: `zz` is not a parameter of `batten`"),
        "{text}"
    );
    for name in [
        "range",
        "tangent-directions",
        "update",
        "max-iterations",
        "max-sweeps",
    ] {
        assert!(text.contains(name), "{text}");
    }
    // A surface method for a curve says what it fairs, not that it is unknown; and back.
    let e = catalog.method(MethodKind::Curve, "zhang-cheng").unwrap_err();
    assert!(
        matches!(
            e,
            Error::WrongKind {
                kind: "curve",
                fairs: "surface",
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        e.to_string().starts_with("`zhang-cheng` is a surface method"),
        "{e}"
    );
    assert!(e.to_string().contains("two-phase"), "{e}");
    let e = catalog.method(MethodKind::Surface, "two-phase").unwrap_err();
    assert!(matches!(e, Error::WrongKind { fairs: "curve", .. }), "{e:?}");
    let e = catalog.method(MethodKind::Curve, "wobble").unwrap_err();
    assert!(matches!(e, Error::UnknownMethod { .. }), "{e:?}");
}

#[test]
fn presets_are_entries_with_other_defaults() {
    let catalog = Catalog::builtin();
    let base = catalog.method(MethodKind::Curve, "strain-energy").unwrap();
    for (name, parametrization) in [("kjellander", "uniform"), ("poliakoff", "chord-length")] {
        let preset = catalog.method(MethodKind::Curve, name).unwrap();
        assert_eq!(preset.defaults()["parametrization"], parametrization);
        // The pinned parameter is neither listed nor accepted; the others are the base's.
        assert!(preset.parameter("parametrization").is_none());
        assert_eq!(preset.parameters().len(), base.parameters().len() - 1);
        let e = preset
            .settings(&sets(&[("parametrization", "centripetal")]))
            .unwrap_err();
        assert!(e.to_string().contains("not a parameter of `"), "{e}");
        assert!(preset.settings(&sets(&[("pairs", "on")])).is_ok());
    }
    let surface = catalog.method(MethodKind::Surface, "kjellander").unwrap();
    assert_eq!(surface.defaults()["boundary"], false);
    assert_eq!(surface.defaults()["max-steps"], 100_000);
    assert_eq!(surface.defaults()["one-point-per-step"], true);
    assert!(surface.parameter("one-point-per-step").is_none());
    // A preset of an unknown base, or with a default that is not a parameter, is refused.
    let mut catalog = Catalog::builtin();
    let info = fairing::catalog::MethodInfo::new("x", "x");
    assert!(catalog
        .register_preset(
            MethodKind::Curve,
            "nope",
            info.clone(),
            serde_json::json!({}),
            &[]
        )
        .is_err());
    assert!(catalog
        .register_preset(
            MethodKind::Curve,
            "batten",
            info,
            serde_json::json!({"zz": 1}),
            &[]
        )
        .is_err());
}

#[test]
fn a_config_pipeline_is_planned_and_run_by_the_library() {
    let catalog = Catalog::builtin();
    let text = "[constraints]\nfixed = [0, 29]\ntolerance = 5e-4\n\n[[stage]]\nmethod = \"smoothing-spline\"\np = 0.9999\n\n[[stage]]\nmethod = \"two-phase\"\nmax-passes = 10\n";
    let file = ConfigFile::parse("pipe.toml", text).unwrap();
    let plan = catalog
        .plan(
            MethodKind::Curve,
            None,
            "two-phase",
            Some(&file),
            &ParameterMap::new(),
        )
        .unwrap();
    assert_eq!(plan.name(), "smoothing-spline+two-phase");
    assert_eq!(plan.stages[1].settings["max-passes"], 10);
    assert_eq!(plan.constraints.tolerance, Some(5e-4));
    let points = ua2_180_upper();
    let constraints = PlanConstraints {
        fixed: vec![0, 29],
        bad_points: vec![],
        tolerance: Some(5e-4),
        clamp: fairing::EndClamp::None,
        corners: fairing::corners::Corners::Auto,
    };
    for kind in [CurveKind::Function, CurveKind::Parametric] {
        let input = CurvePoints::Planar(points.clone());
        let run = catalog.run_curve_plan(&plan, &input, kind, &constraints).unwrap();
        let faired = run.points.as_dimension::<2>().unwrap();
        assert_eq!(faired[0], points[0]);
        assert_eq!(faired[29], points[29]);
        for (p, q) in points.iter().zip(faired) {
            assert!((p - q).norm() <= 5e-4, "{kind:?}: {}", (p - q).norm());
        }
        let stages = run.extras["stages"].as_array().unwrap();
        assert_eq!(stages.len(), 2);
        assert_eq!(stages[0]["method"], "smoothing-spline");
        assert_eq!(run.termination, stages[1]["termination"].as_str().unwrap());
    }
    // The printed config reads back as the same plan.
    let printed = plan.render(&catalog, &constraints);
    let again = ConfigFile::parse("printed.toml", &printed).unwrap();
    let replan = catalog
        .plan(
            MethodKind::Curve,
            None,
            "two-phase",
            Some(&again),
            &ParameterMap::new(),
        )
        .unwrap();
    assert_eq!(replan.stages.len(), 2);
    for (a, b) in plan.stages.iter().zip(&replan.stages) {
        assert_eq!(a.settings, b.settings);
    }
    // A bad value in a stage names the file, line and stage.
    let file = ConfigFile::parse(
        "bad.toml",
        "[[stage]]\nmethod = \"batten\"\nupdate = \"newton\"\n",
    )
    .unwrap();
    let e = catalog
        .plan(
            MethodKind::Curve,
            None,
            "two-phase",
            Some(&file),
            &ParameterMap::new(),
        )
        .unwrap_err();
    assert!(e.to_string().starts_with("bad.toml:3 (stage 1): `update`"), "{e}");
    // A pipeline with --method or --set is ambiguous.
    let file = ConfigFile::parse("p.toml", "[[stage]]\nmethod = \"batten\"\n").unwrap();
    assert!(catalog
        .plan(
            MethodKind::Curve,
            Some("batten"),
            "two-phase",
            Some(&file),
            &ParameterMap::new()
        )
        .is_err());
}

/// The length of a planar curve (a user's criterion, for the test).
fn length_criterion() -> CriterionEntry {
    CriterionEntry::new("chord-sum", "Σ |C(t_{i+1}) − C(t_i)| over 8 samples per piece").planar(
        FnCriterion::<dyn Curve<2>, _>::new("chord-sum", |c: &(dyn Curve<2> + 'static)| {
            let breaks = c.breaks();
            let mut total = 0.0;
            for w in breaks.windows(2) {
                for k in 0..8 {
                    let (a, b) = (
                        w[0] + (w[1] - w[0]) * k as f64 / 8.0,
                        w[0] + (w[1] - w[0]) * (k + 1) as f64 / 8.0,
                    );
                    total += (c.jet(b, Side::Left)[0] - c.jet(a, Side::Right)[0]).norm();
                }
            }
            Ok(total)
        }),
    )
}

#[test]
fn criteria_are_registered_selected_and_evaluated_on_the_curve_as_represented() {
    let mut catalog = Catalog::builtin();
    catalog.register_criterion(length_criterion());
    let points = CurvePoints::Planar(ua2_180_upper());
    let constraints = Constraints::default();
    let job = CurveJob {
        method: "nurbs-weights",
        points: &points,
        kind: CurveKind::Parametric,
        constraints: &constraints,
        bad_points: &[],
        catalog: &catalog,
    };
    let entry = catalog.method(MethodKind::Curve, "nurbs-weights").unwrap();
    let settings = entry
        .settings(&sets(&[("criterion", "e2"), ("max-iterations", "60")]))
        .unwrap();
    let run = entry.fair_curve(&settings, &job).unwrap();
    assert!(run.moved.is_empty());
    let represented = run
        .represented
        .as_ref()
        .expect("nurbs-weights has its own curves");
    let before = catalog.criteria_of(&represented.before);
    let after = catalog.criteria_of(&represented.after);
    let names: Vec<&String> = before.keys().collect();
    assert_eq!(names, ["chord-sum", "e1", "e2", "e3", "ek", "ek-prime"]);
    let (b, a) = (*before["e2"].as_ref().unwrap(), *after["e2"].as_ref().unwrap());
    assert!(a <= b, "{a} > {b}");
    assert_eq!(run.extras["criterion_after"].as_f64().unwrap(), a);
    // The user's criterion can be minimised too; an unknown one is refused with the list.
    let settings = entry
        .settings(&sets(&[("criterion", "chord-sum"), ("max-iterations", "30")]))
        .unwrap();
    let run = entry.fair_curve(&settings, &job).unwrap();
    assert_eq!(run.extras["criterion"], "chord-sum");
    let settings = entry.settings(&sets(&[("criterion", "e9")])).unwrap();
    let e = entry.fair_curve(&settings, &job).unwrap_err();
    assert!(
        e.to_string().contains("chord-sum") && e.to_string().contains("e9"),
        "{e}"
    );
    // A planar-only criterion does not apply to a spatial curve, and is not reported for one.
    let spatial = fairing::catalog::measured_curve(
        CurveKind::Parametric,
        &CurvePoints::Spatial(
            (0..8)
                .map(|k| curve_repr::Vec3::new(k as f64, (k as f64).sin(), 0.1 * k as f64))
                .collect(),
        ),
    )
    .unwrap();
    assert!(!catalog.criteria_of(&spatial).contains_key("chord-sum"));
}

/// A report that has measured a curve's energies reads the built-in criteria from them (no
/// second integration: the curve is not even built) and evaluates only the others, on a
/// curve built once; an entry registered under a built-in's name is the user's and is
/// evaluated.
#[test]
fn criteria_that_are_energies_are_read_from_the_measured_energies() {
    let mut catalog = Catalog::builtin();
    let points = CurvePoints::Planar(ua2_180_upper());
    let measured = || fairing::catalog::measured_curve(CurveKind::Parametric, &points);
    let energies = fairing::catalog::measure_energies(&measured().unwrap())
        .unwrap()
        .values;
    let not_built = || -> fairing::Result<fairing::catalog::AnyCurve> { panic!("the curve was built") };
    let read = catalog.criteria_with(2, Some(&energies), not_built).unwrap();
    let names: Vec<&String> = read.keys().collect();
    assert_eq!(names, ["e1", "e2", "e3", "ek", "ek-prime"]);
    for name in fairness::EnergyName::ALL {
        assert_eq!(
            *read[name.label()].as_ref().unwrap(),
            energies.get(name),
            "{name:?}"
        );
    }
    // Without energies every criterion is evaluated, to the same values within the accuracy
    // of the adaptive rule (1e-10 relative).
    let evaluated = catalog.criteria_with(2, None, measured).unwrap();
    for name in fairness::EnergyName::ALL {
        let (a, b) = (energies.get(name), *evaluated[name.label()].as_ref().unwrap());
        assert!((a - b).abs() <= 1e-9 * a.abs(), "{name:?}: {a} {b}");
    }
    // A user's criterion, and a user's `e2` (the built-in replaced): both evaluated on the
    // curve, built once.
    catalog.register_criterion(length_criterion());
    catalog.register_criterion(
        CriterionEntry::new("e2", "twice E2 (a user's)").planar(FnCriterion::<dyn Curve<2>, _>::new(
            "e2",
            |c: &(dyn Curve<2> + 'static)| {
                Ok(2.0 * fairness::Criterion::evaluate(&fairness::E2::<2>::new(), c)?)
            },
        )),
    );
    let mut builds = 0;
    let mixed = catalog
        .criteria_with(2, Some(&energies), || {
            builds += 1;
            measured()
        })
        .unwrap();
    assert_eq!(builds, 1);
    assert!(*mixed["chord-sum"].as_ref().unwrap() > 0.9);
    let e2 = *mixed["e2"].as_ref().unwrap();
    assert!(
        (e2 - 2.0 * energies.e2).abs() <= 1e-9 * e2,
        "{e2} {}",
        energies.e2
    );
    assert_eq!(*mixed["e1"].as_ref().unwrap(), energies.e1);
    // Criteria of another dimension are not listed, and need no curve.
    let spatial = catalog.criteria_with(3, Some(&energies), not_built).unwrap();
    assert!(!spatial.contains_key("chord-sum") && spatial.contains_key("e1"));
}

/// A user's indicator that points at the middle break of any curve.
struct Middle;

impl fairness::LocalIndicator<dyn Curve<2>> for Middle {
    fn name(&self) -> &str {
        "middle"
    }
    fn values(&self, curve: &(dyn Curve<2> + 'static)) -> fairness::Result<Vec<f64>> {
        let n = curve.breaks().len();
        let mut values = vec![0.0; n];
        values[n / 2] = 1.0;
        Ok(values)
    }
}

#[test]
fn strategies_that_choose_where_to_act_take_an_indicator() {
    let mut catalog = Catalog::builtin();
    catalog.register_indicator(
        fairing::catalog::IndicatorEntry::new("middle", "the middle break").planar(Middle),
    );
    let points = CurvePoints::Planar(ua2_180_upper());
    let constraints = Constraints::default();
    let job = CurveJob {
        method: "",
        points: &points,
        kind: CurveKind::Parametric,
        constraints: &constraints,
        bad_points: &[],
        catalog: &catalog,
    };
    // Strain energy: one step moves the point the indicator picks (the paper's z_i picks
    // another on this airfoil).
    let entry = catalog.method(MethodKind::Curve, "strain-energy").unwrap();
    let run = |given: &[(&str, &str)]| {
        entry
            .fair_curve(&entry.settings(&sets(given)).unwrap(), &job)
            .unwrap()
    };
    let paper = run(&[("max-iterations", "1")]);
    let middle = run(&[("max-iterations", "1"), ("indicator", "middle")]);
    assert_eq!(middle.moved, vec![15]);
    assert_ne!(paper.moved, vec![15]);
    // A built-in alternative runs too, and changes the result.
    let other = run(&[("max-iterations", "5"), ("indicator", "curvature-slope-jump")]);
    assert!(other.iterations > 0);
    // Sapidis–Farin: every step fairs the knot the indicator picks; the paper's jump moves on.
    let entry = catalog.method(MethodKind::Curve, "sapidis-farin").unwrap();
    let run = |given: &[(&str, &str)]| {
        entry
            .fair_curve(&entry.settings(&sets(given)).unwrap(), &job)
            .unwrap()
    };
    let knots = |r: &fairing::catalog::CurveRun| -> Vec<f64> {
        r.extras["steps"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["knot"].as_f64().unwrap())
            .collect()
    };
    let paper = knots(&run(&[("max-iterations", "3")]));
    let middle = knots(&run(&[("max-iterations", "3"), ("indicator", "middle")]));
    assert_eq!(middle.len(), 3);
    assert!(middle.iter().all(|k| *k == middle[0]), "{middle:?}");
    assert!(paper.iter().any(|k| *k != paper[0]), "{paper:?}");
    let other = run(&[("max-iterations", "3"), ("indicator", "third-derivative-jump")]);
    assert!(other.iterations > 0);
    // An unknown indicator is refused with the registered ones.
    for method in ["strain-energy", "sapidis-farin"] {
        let entry = catalog.method(MethodKind::Curve, method).unwrap();
        let e = entry
            .fair_curve(&entry.settings(&sets(&[("indicator", "nope")])).unwrap(), &job)
            .unwrap_err();
        assert!(
            e.to_string().contains("middle") && e.to_string().contains("nope"),
            "{method}: {e}"
        );
    }
}

#[test]
fn a_surface_plan_prints_as_its_method_table_and_reads_back() {
    let catalog = Catalog::builtin();
    let plan = catalog
        .plan(
            MethodKind::Surface,
            Some("kjellander"),
            "zhang-cheng",
            None,
            &sets(&[("max-steps", "50"), ("boundary", "on")]),
        )
        .unwrap();
    let text = plan.render(&catalog, &PlanConstraints::default());
    assert!(
        text.contains("[kjellander]") && !text.contains("[[stage]]"),
        "{text}"
    );
    let file = ConfigFile::parse("s.toml", &text).unwrap();
    let again = catalog
        .plan(
            MethodKind::Surface,
            Some("kjellander"),
            "zhang-cheng",
            Some(&file),
            &ParameterMap::new(),
        )
        .unwrap();
    assert_eq!(again.stages[0].settings, plan.stages[0].settings);
    assert_eq!(again.stages[0].settings["max-steps"], 50);
    assert_eq!(again.stages[0].settings["boundary"], true);
}

/// Two-phase's `prepass` report field says what its noise pre-pass chose. On a noisy sine as
/// a function (200 points, σ = 0.01) it reports one `function` fit with the rule, λ,
/// difference order, end conditions and noise estimate of jump-lsq run alone with the
/// pre-pass's own choices (`rule`, `difference-order`, `function-ends` all `auto`) on the same
/// points; on a noisy open arc one `open` fit equal in the same way to jump-lsq run alone
/// with the curve pre-pass's choices (`rule = gcv`, `curve-ends = runout`, `difference-order =
/// auto`) but for GCV's trace factor γ, 1.4 in the pre-pass and not a setting of jump-lsq:
/// the same rule, ends and noise estimate, and a λ no smaller; on a noisy closed ellipse one `periodic` fit; on the same
/// ellipse with a corner, the `corner` and `through-corner` fits. With `denoise = gcv` it names
/// the cubic smoothing spline and has no jump-lsq report. With `denoise = off` it is null.
#[test]
fn two_phases_report_says_what_its_pre_pass_chose() {
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    let mut rng = rand::rngs::StdRng::seed_from_u64(18);
    let normal = Normal::new(0.0, 0.01).unwrap();
    let mut noisy = |p: Vec2| Vec2::new(p.x + normal.sample(&mut rng), p.y + normal.sample(&mut rng));
    let sine: Vec<Vec2> = (0..200)
        .map(|k| {
            let x = 0.1 * k as f64;
            let p = noisy(Vec2::new(x, (x / 2.0).sin()));
            Vec2::new(x, p.y)
        })
        .collect();
    let arc: Vec<Vec2> = (0..100)
        .map(|k| {
            let t = 1.5 * std::f64::consts::PI * k as f64 / 99.0;
            noisy(Vec2::new(2.0 * t.cos(), 2.0 * t.sin()))
        })
        .collect();
    let ellipse: Vec<Vec2> = (0..120)
        .map(|k| {
            let t = 2.0 * std::f64::consts::PI * k as f64 / 120.0;
            noisy(Vec2::new(3.0 * t.cos(), 2.0 * t.sin()))
        })
        .collect();
    // The same ellipse with its first point pulled out to a corner.
    let mut cornered = ellipse.clone();
    cornered[0] = Vec2::new(4.0, 0.0);
    let catalog = Catalog::builtin();
    let run = |method: &str, pairs: &[(&str, &str)], points: &[Vec2], kind: CurveKind| {
        let plan = catalog
            .plan(MethodKind::Curve, Some(method), method, None, &sets(pairs))
            .unwrap();
        catalog
            .run_curve_plan(
                &plan,
                &CurvePoints::Planar(points.to_vec()),
                kind,
                &PlanConstraints::default(),
            )
            .unwrap()
    };
    let same = |prepass: &serde_json::Value, alone: &fairing::catalog::CurveRun| {
        for field in [
            "rule",
            "lambda",
            "difference_order",
            "exponent",
            "ends",
            "sigma",
            "rms_displacement",
        ] {
            assert_eq!(
                prepass["jump_lsq"][field], alone.extras[field],
                "{field}: {prepass}"
            );
        }
    };
    let roles = |run: &fairing::catalog::CurveRun| -> Vec<String> {
        run.extras["prepass"]["fits"]
            .as_array()
            .unwrap()
            .iter()
            .map(|fit| fit["role"].as_str().unwrap().to_owned())
            .collect()
    };

    let function = run("two-phase", &[], &sine, CurveKind::Function);
    let prepass = &function.extras["prepass"];
    assert_eq!(roles(&function), ["function"], "{prepass}");
    assert_eq!(prepass["fits"][0]["smoother"], "jump-lsq", "{prepass}");
    assert!(prepass["bins"].is_null(), "{prepass}");
    let alone = run(
        "jump-lsq",
        &[
            ("rule", "auto"),
            ("difference-order", "auto"),
            ("function-ends", "auto"),
        ],
        &sine,
        CurveKind::Function,
    );
    same(&prepass["fits"][0], &alone);
    assert_eq!(prepass["fits"][0]["jump_lsq"]["exponent"], 8.0);

    let open = run("two-phase", &[], &arc, CurveKind::Parametric);
    assert_eq!(roles(&open), ["open"], "{}", open.extras["prepass"]);
    let alone = run(
        "jump-lsq",
        &[
            ("rule", "gcv"),
            ("curve-ends", "runout"),
            ("difference-order", "auto"),
        ],
        &arc,
        CurveKind::Parametric,
    );
    let fit = &open.extras["prepass"]["fits"][0]["jump_lsq"];
    for field in ["rule", "ends", "sigma"] {
        assert_eq!(fit[field], alone.extras[field], "{field}: {fit}");
    }
    let (mine, its) = (
        fit["lambda"].as_f64().unwrap(),
        alone.extras["lambda"].as_f64().unwrap(),
    );
    assert!(mine >= its, "λ {mine} against jump-lsq's {its}: {fit}");
    let closed = |points: &[Vec2]| run("two-phase", &[("closed", "true")], points, CurveKind::Parametric);
    assert_eq!(roles(&closed(&ellipse)), ["periodic"]);
    assert_eq!(roles(&closed(&cornered)), ["corner", "through-corner"]);

    let cubic = run("two-phase", &[("denoise", "gcv")], &sine, CurveKind::Function);
    assert_eq!(cubic.extras["prepass"]["fits"][0]["smoother"], "smoothing-spline");
    assert!(cubic.extras["prepass"]["fits"][0]["jump_lsq"].is_null());
    let off = run("two-phase", &[("denoise", "off")], &sine, CurveKind::Function);
    assert!(off.extras["prepass"].is_null());
}

/// `--set` and config values are checked against the range the settings declare on the
/// field (the schema's bounds), naming the method, the parameter, the value and the range;
/// a fraction for an integer says so instead of serde's "invalid type".
#[test]
fn values_outside_the_declared_range_are_refused_with_the_range() {
    let catalog = Catalog::builtin();
    let two_phase = catalog.method(MethodKind::Curve, "two-phase").unwrap();
    let e = two_phase.settings(&sets(&[("max-passes", "0")])).unwrap_err();
    assert_eq!(
        e,
        Error::OutOfRange {
            origin: "--set".into(),
            method: "two-phase".into(),
            setting: "max-passes".into(),
            value: "0".into(),
            allowed: "an integer ≥ 1".into(),
        }
    );
    assert_eq!(
        e.to_string(),
        "--set: `two-phase`: max-passes = 0 is out of range: an integer ≥ 1"
    );
    let e = two_phase.settings(&sets(&[("max-passes", "2.5")])).unwrap_err();
    assert_eq!(
        e.to_string(),
        "--set: `two-phase`: max-passes = 2.5: expected an integer ≥ 1"
    );
    for (name, value, allowed) in [
        ("coarse-lambda", "0", "a number in (0, 1]"),
        ("turning-limit", "180.5", "a number in (0, 180]"),
        ("fine-lambda", "1.5", "a number in (0, 1]"),
    ] {
        let e = two_phase.settings(&sets(&[(name, value)])).unwrap_err();
        assert!(
            matches!(&e, Error::OutOfRange { setting, allowed: a, .. } if setting == name && a == allowed),
            "{name}: {e}"
        );
    }
    // The edges themselves, and `auto`, are taken.
    for (name, value) in [
        ("max-passes", "1"),
        ("coarse-lambda", "1"),
        ("turning-limit", "180"),
        ("fine-lambda", "1"),
    ] {
        two_phase
            .settings(&sets(&[(name, value)]))
            .unwrap_or_else(|e| panic!("{name} = {value}: {e}"));
    }
    // A config file's value is refused at its line; other methods' ranges too.
    let file = ConfigFile::parse("c.toml", "# one\n[smoothing-spline]\np = 1.5\n").unwrap();
    let e = catalog
        .plan(
            MethodKind::Curve,
            Some("smoothing-spline"),
            "two-phase",
            Some(&file),
            &ParameterMap::new(),
        )
        .unwrap_err();
    assert_eq!(
        e.to_string(),
        "c.toml:3: `smoothing-spline`: p = 1.5 is out of range: a number in [0, 1]"
    );
    for (method, name, value) in [
        ("jump-lsq", "refits", "101"),
        ("batten", "range", "-1"),
        ("strain-energy", "energy-tolerance", "-1"),
    ] {
        let entry = catalog.method(MethodKind::Curve, method).unwrap();
        let e = entry.settings(&sets(&[(name, value)])).unwrap_err();
        assert!(matches!(e, Error::OutOfRange { .. }), "{method} {name}: {e}");
    }
    let surface = catalog.method(MethodKind::Surface, "zhang-cheng").unwrap();
    let e = surface.settings(&sets(&[("quantum-scale", "-2")])).unwrap_err();
    assert!(matches!(e, Error::OutOfRange { .. }), "{e}");
    // An echoed value is clipped: the message stays one short line.
    let long = "9".repeat(100_000);
    let e = catalog
        .method(MethodKind::Curve, "batten")
        .unwrap()
        .settings(&sets(&[("range", &format!("x{long}"))]))
        .unwrap_err();
    assert!(e.to_string().len() < 400, "{} characters", e.to_string().len());
    let e = catalog
        .method(MethodKind::Curve, "batten")
        .unwrap()
        .settings(&sets(&[(&long, "1")]))
        .unwrap_err();
    assert!(e.to_string().len() < 600, "{} characters", e.to_string().len());
    let e = catalog.method(MethodKind::Curve, &long).unwrap_err();
    assert!(e.to_string().len() < 600, "{} characters", e.to_string().len());
}

/// Every declared range agrees with the settings' own checks: for every built-in method
/// and every numeric parameter with a declared bound, the bound itself (when included) or
/// a value just inside it is accepted, so that no declaration is looser or stricter than
/// the method's `validate` at the edge.
#[test]
fn declared_ranges_agree_with_validation_at_their_edges() {
    let catalog = Catalog::builtin();
    let mut checked = 0;
    for kind in [MethodKind::Curve, MethodKind::Surface] {
        for entry in catalog.methods(kind) {
            for parameter in entry.parameters() {
                let Some(range) = fairing::catalog::NumberRange::of(&parameter.schema, entry.schema()) else {
                    continue;
                };
                for (bound, open, inward) in [
                    range.min.map(|(m, o)| (m, o, 1.0)),
                    range.max.map(|(m, o)| (m, o, -1.0)),
                ]
                .into_iter()
                .flatten()
                {
                    let step = if range.integer {
                        1.0
                    } else {
                        1e-9 * bound.abs().max(1.0)
                    };
                    let inside = if open { bound + inward * step } else { bound };
                    let outside = bound - inward * if open { 0.0 } else { step };
                    let text = |x: f64| {
                        if range.integer {
                            format!("{}", x as i64)
                        } else {
                            format!("{x}")
                        }
                    };
                    entry
                        .settings(&sets(&[(&parameter.name, &text(inside))]))
                        .unwrap_or_else(|e| panic!("{} {} = {}: {e}", entry.name(), parameter.name, inside));
                    // Integers below 0 are read as such; the range still refuses them.
                    let e = entry.settings(&sets(&[(&parameter.name, &text(outside))]));
                    assert!(
                        matches!(e, Err(Error::OutOfRange { .. })),
                        "{} {} = {}: {e:?}",
                        entry.name(),
                        parameter.name,
                        outside
                    );
                    checked += 1;
                }
            }
        }
    }
    assert!(checked > 30, "{checked} bounds");
}

/// `fair methods` prints every default as the shortest text that reads back to it, and a
/// default computed in other units is stored so that it prints as written (120, not
/// 119.99999999999999).
#[test]
fn defaults_print_as_written() {
    let catalog = Catalog::builtin();
    let two_phase = catalog.method(MethodKind::Curve, "two-phase").unwrap();
    assert_eq!(two_phase.parameter("turning-limit").unwrap().default, "120");
    assert_eq!(
        fairing::PartitionSettings::default().limit,
        2.0 * std::f64::consts::PI / 3.0
    );
    for kind in [MethodKind::Curve, MethodKind::Surface] {
        for entry in catalog.methods(kind) {
            for p in entry.parameters() {
                if let Some(x) = p.default_value.as_f64() {
                    assert_eq!(
                        p.default.parse::<f64>().ok(),
                        Some(x),
                        "{} {}",
                        entry.name(),
                        p.name
                    );
                    assert!(
                        !p.default.contains("9999") && !p.default.contains("0000001"),
                        "{} {} = {}",
                        entry.name(),
                        p.name,
                        p.default
                    );
                }
            }
        }
    }
}

/// A config file that names no known method, in a stage or as a table, is refused at its
/// line.
#[test]
fn config_method_names_are_checked_at_their_line() {
    let catalog = Catalog::builtin();
    let none = ParameterMap::new();
    let file = ConfigFile::parse(
        "p.toml",
        "[[stage]]\nmethod = \"two-phase\"\n\n[[stage]]\nmethod = \"nope\"\n",
    )
    .unwrap();
    let e = catalog
        .plan(MethodKind::Curve, None, "two-phase", Some(&file), &none)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("p.toml:5 (stage 2): unknown curve method `nope`"),
        "{e}"
    );
    let file = ConfigFile::parse("p.toml", "[[stage]]\nmethod = \"zhang-cheng\"\n").unwrap();
    let e = catalog
        .plan(MethodKind::Curve, None, "two-phase", Some(&file), &none)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("p.toml:2 (stage 1): `zhang-cheng` is a surface method"),
        "{e}"
    );
    let file = ConfigFile::parse("t.toml", "p = 0.5\n\n[nope]\nx = 1\n").unwrap();
    let e = catalog
        .plan(
            MethodKind::Curve,
            Some("smoothing-spline"),
            "two-phase",
            Some(&file),
            &none,
        )
        .unwrap_err();
    assert!(
        e.to_string().starts_with("t.toml:3: `[nope]` names no method"),
        "{e}"
    );
    // A table of a method that does not run (or of the other kind) is kept for when it does.
    let file = ConfigFile::parse("u.toml", "[zhang-cheng]\nenergy-tolerance = 1\n").unwrap();
    catalog
        .plan(
            MethodKind::Curve,
            Some("two-phase"),
            "two-phase",
            Some(&file),
            &none,
        )
        .unwrap();
}
