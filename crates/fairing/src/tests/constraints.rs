use curve_repr::{Vec2, Vec3};
use proptest::prelude::*;

use crate::{project_into_ball, Constraints, EndClamp, Error};

fn vec3() -> impl Strategy<Value = Vec3> {
    (-1e3..1e3f64, -1e3..1e3f64, -1e3..1e3f64).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn constraints(n: usize) -> impl Strategy<Value = Constraints> {
    (
        proptest::collection::vec(0..n, 0..3),
        proptest::option::of(proptest::collection::vec(
            prop_oneof![Just(0.0), 1e-9..10.0f64, Just(f64::INFINITY)],
            n,
        )),
        proptest::option::of(prop_oneof![Just(0.0), 1e-9..10.0f64]),
        prop_oneof![Just(EndClamp::None), Just(EndClamp::G0), Just(EndClamp::G2)],
    )
        .prop_map(|(fixed, radii, tolerance, clamp)| {
            let mut c = Constraints::default().with_fixed(fixed).with_end_clamp(clamp);
            if let Some(r) = radii {
                c = c.with_restraining_radii(r);
            }
            if let Some(t) = tolerance {
                c = c.with_tolerance(t);
            }
            c
        })
}

proptest! {
    #[test]
    fn projection_honours_every_constraint(c in constraints(6), index in 0..6usize, original in vec3(), proposed in vec3()) {
        let n = 6;
        prop_assert!(c.validate(n).is_ok());
        let result = c.constrain_move(index, n, &original, &proposed).unwrap();
        let frozen = c.fixed().contains(&index) || (c.end_clamp() != EndClamp::None && (index == 0 || index == n - 1));
        if frozen {
            // Bit for bit.
            for (a, b) in result.iter().zip(original.iter()) {
                prop_assert_eq!(a.to_bits(), b.to_bits());
            }
        }
        let allowed = c.allowed_distance(index);
        prop_assert!((result - original).norm() <= allowed, "moved {} allowed {}", (result - original).norm(), allowed);
        // Idempotent.
        let again = c.constrain_move(index, n, &original, &result).unwrap();
        prop_assert_eq!(again, result);
        // A projected move passes the final check.
        let mut originals = vec![Vec3::zeros(); n];
        originals[index] = original;
        let mut faired = originals.clone();
        faired[index] = result;
        prop_assert!(c.check(&originals, &faired).is_ok());
        // The projection is the nearest allowed point: on the segment towards the proposal.
        if !frozen && (proposed - original).norm() > allowed && allowed > 0.0 {
            let direction = (proposed - original).normalize();
            let along = (result - original).dot(&direction);
            prop_assert!(((result - original) - direction * along).norm() <= 1e-9 * (1.0 + allowed));
            prop_assert!((along - allowed).abs() <= 1e-9 * allowed.max(1.0));
        }
    }

    #[test]
    fn ball_projection_stays_inside_even_at_extreme_scales(scale in -300i32..300, x in -1.0..1.0f64, y in -1.0..1.0f64, r in 1e-6..1.0f64) {
        let s = 2f64.powi(scale / 2);
        let center = Vec2::new(0.1 * s, -0.3 * s);
        let proposed = center + Vec2::new(x, y) * s * 3.0;
        let radius = r * s;
        let q = project_into_ball(&center, radius, &proposed);
        prop_assert!((q - center).norm() <= radius);
        prop_assert_eq!(project_into_ball(&center, radius, &q), q);
    }
}

#[test]
fn non_finite_proposal_is_an_error() {
    let c = Constraints::default();
    let r = c.constrain_move(1, 3, &Vec2::zeros(), &Vec2::new(f64::NAN, 0.0));
    assert_eq!(r, Err(Error::NonFiniteMove { index: 1 }));
}

#[test]
fn validate_rejects_bad_constraints() {
    assert!(matches!(
        Constraints::default().with_fixed([5]).validate(5),
        Err(Error::BadConstraint { .. })
    ));
    assert!(Constraints::default().with_fixed([4]).validate(5).is_ok());
    assert!(matches!(
        Constraints::default()
            .with_restraining_radii(vec![1.0; 4])
            .validate(5),
        Err(Error::BadConstraint { .. })
    ));
    assert!(matches!(
        Constraints::default()
            .with_restraining_radii(vec![1.0, -1.0, 1.0])
            .validate(3),
        Err(Error::BadConstraint { .. })
    ));
    assert!(matches!(
        Constraints::default()
            .with_restraining_radii(vec![1.0, f64::NAN, 1.0])
            .validate(3),
        Err(Error::BadConstraint { .. })
    ));
    assert!(matches!(
        Constraints::default().with_tolerance(-0.1).validate(3),
        Err(Error::BadConstraint { .. })
    ));
}

#[test]
fn movability_accounts_for_end_clamps() {
    let c = Constraints::default()
        .with_end_clamp(EndClamp::G1)
        .with_fixed([2]);
    let movable: Vec<bool> = (0..6).map(|i| c.is_movable(i, 6)).collect();
    assert_eq!(movable, [false, true, false, true, true, false]);
    assert!(!c.is_movable(6, 6));
    let free = Constraints::default();
    assert!(free.is_movable(0, 6) && free.is_movable(5, 6));
}

#[test]
fn check_names_the_violated_point() {
    let original = vec![
        Vec2::new(0.0, 0.0),
        Vec2::new(1.0, 0.0),
        Vec2::new(2.0, 0.0),
        Vec2::new(3.0, 0.0),
    ];
    let mut faired = original.clone();
    let fixed = Constraints::default().with_fixed([2]);
    assert!(fixed.check(&original, &faired).is_ok());
    faired[2].y = 1e-300;
    assert!(matches!(
        fixed.check(&original, &faired),
        Err(Error::ConstraintViolated {
            index: 2,
            constraint: "fixed point",
            ..
        })
    ));

    let mut faired = original.clone();
    faired[1].y = 0.30000001;
    let band = Constraints::default().with_tolerance(0.3);
    assert!(matches!(
        band.check(&original, &faired),
        Err(Error::ConstraintViolated {
            index: 1,
            constraint: "tolerance",
            ..
        })
    ));
    faired[1].y = 0.3;
    assert!(band.check(&original, &faired).is_ok());

    let radii = Constraints::default()
        .with_restraining_radii(vec![1.0, 1.0, 0.1, 1.0])
        .with_tolerance(0.5);
    let mut faired = original.clone();
    faired[2].x += 0.2;
    assert!(matches!(
        radii.check(&original, &faired),
        Err(Error::ConstraintViolated {
            index: 2,
            constraint: "restraining radius",
            ..
        })
    ));

    let clamp = Constraints::default().with_end_clamp(EndClamp::G0);
    let mut faired = original.clone();
    faired[3].x = 3.0000000000000004;
    assert!(matches!(
        clamp.check(&original, &faired),
        Err(Error::ConstraintViolated {
            index: 3,
            constraint: "end clamp",
            ..
        })
    ));

    let mut short = original.clone();
    short.pop();
    assert!(Constraints::default().check(&original, &short).is_err());
}
