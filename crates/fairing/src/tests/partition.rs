use std::f64::consts::PI;

use curve_repr::Vec2;

use crate::partition::{blend, Frame};
use crate::{
    partition, Constraints, CurveGuard, EndClamp, Error, FairingState, PartitionSettings, Pipeline, Result,
    Segment, SegmentedFairing,
};

fn circle(n: usize, turn: f64) -> Vec<Vec2> {
    (0..n)
        .map(|i| turn * i as f64 / n as f64)
        .map(|t| Vec2::new(3.0 * t.cos(), 3.0 * t.sin()))
        .collect()
}

/// Han Fig. 5: x = 10(t³ − t)/(t² + 1), y = 10(t² − 1)/(t² + 1), t ∈ [−2, 2], 65 points.
fn strophoid() -> Vec<Vec2> {
    (0..65)
        .map(|i| -2.0 + 4.0 * i as f64 / 64.0)
        .map(|t: f64| {
            Vec2::new(
                10.0 * (t.powi(3) - t) / (t * t + 1.0),
                10.0 * (t * t - 1.0) / (t * t + 1.0),
            )
        })
        .collect()
}

/// Deterministic Gaussian noise (an LCG and Box–Muller), so the test needs no RNG crate API.
fn gaussian(seed: u64, count: usize) -> Vec<f64> {
    let mut state = seed;
    let mut uniform = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| (-2.0 * uniform().ln()).sqrt() * (2.0 * PI * uniform()).cos())
        .collect()
}

/// Every property a partition promises, checked from the definitions.
fn check_partition(points: &[Vec2], closed: bool, settings: &PartitionSettings, segments: &[Segment]) {
    let n = points.len();
    assert!(!segments.is_empty());
    let mut cover = vec![0usize; n];
    for (s, seg) in segments.iter().enumerate() {
        assert!(seg.indices.len() >= 2);
        // Consecutive indices along the curve.
        for w in seg.indices.windows(2) {
            assert_eq!(w[1], if closed { (w[0] + 1) % n } else { w[0] + 1 });
        }
        // A function in its frame: x strictly increasing.
        let local = seg.local_points(points);
        assert!(
            local.windows(2).all(|w| w[1].x > w[0].x),
            "segment {s} is not a function in its frame"
        );
        // Turning angle below the limit, measured independently: every edge direction in the
        // frame lies strictly within ±limit/2 of... the spread of frame angles is the turning.
        let angles: Vec<f64> = local
            .windows(2)
            .map(|w| (w[1].y - w[0].y).atan2(w[1].x - w[0].x))
            .collect();
        let spread = angles.iter().cloned().fold(f64::NEG_INFINITY, f64::max)
            - angles.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!(spread < settings.limit, "segment {s} turns {spread}");
        assert!((spread - seg.turning).abs() < 1e-9);
        // The frame is the bisector: extreme frame angles are symmetric about 0.
        let (lo, hi) = (
            angles.iter().cloned().fold(f64::INFINITY, f64::min),
            angles.iter().cloned().fold(f64::NEG_INFINITY, f64::max),
        );
        assert!((lo + hi).abs() < 1e-9, "segment {s}: frame angles {lo}..{hi}");
        for &i in &seg.indices {
            cover[i] += 1;
        }
        // The overlap with the next segment: the shared points are the same on both sides.
        let next = match segments.get(s + 1) {
            Some(next) => Some(next),
            None if closed => segments.first(),
            None => None,
        };
        match next {
            Some(next) => {
                let m = seg.overlap_after;
                assert_eq!(m, next.overlap_before);
                assert!(m >= 1 && m <= settings.overlap);
                assert_eq!(seg.indices[seg.indices.len() - m..], next.indices[..m]);
            }
            None => assert_eq!(seg.overlap_after, 0),
        }
    }
    if !closed {
        assert_eq!(segments[0].overlap_before, 0);
    }
    assert!(
        cover.iter().all(|&c| c == 1 || c == 2),
        "every point in one or two segments: {cover:?}"
    );
}

fn identity(_: &[f64], _: &mut [f64], _: &[bool]) -> Result<()> {
    Ok(())
}

#[test]
fn circle_partitions_into_function_segments_with_overlap() {
    let turn = 2.0 * PI * 0.97;
    let points = circle(64, turn);
    for limit in [PI, 2.0 * PI / 3.0, PI / 4.0] {
        let settings = PartitionSettings::default().with_limit(limit);
        let segments = partition(&points, false, &settings).unwrap();
        check_partition(&points, false, &settings, &segments);
        // On a smooth, finely sampled circle every overlap is the full k = 5 while segments
        // are long enough (at π/4 a segment has 9 points and overlaps shrink to 4 so that no
        // point lies in three segments).
        if limit > 2.0 {
            assert!(segments.windows(2).all(|w| w[0].overlap_after == 5));
        }
        // Greedy: each segment is maximal, adding the next edge would reach the limit.
        let step = turn / 64.0;
        for seg in &segments[..segments.len() - 1] {
            assert!(seg.turning + step >= limit - 1e-9);
        }
    }
    let segments = partition(&points, false, &PartitionSettings::default()).unwrap();
    assert!(
        segments.len() >= 3,
        "a full circle needs at least 3 segments below π"
    );
}

#[test]
fn an_unchanged_segmentation_reproduces_the_input_exactly() {
    for (points, closed) in [
        (circle(64, 2.0 * PI * 0.95), false),
        (strophoid(), false),
        (circle(50, 2.0 * PI), true),
    ] {
        let result = Pipeline::new(SegmentedFairing::new(identity).with_passes(2))
            .with_closed(closed)
            .run(points.clone())
            .unwrap();
        assert_eq!(result.points, points);
        assert!(result.moved.is_empty());
        assert_eq!(result.trace.move_count(), 0);
        assert_eq!(result.iterations, 2);
    }
}

#[test]
fn frame_round_trip_and_displacement() {
    let frame = Frame::new(Vec2::new(1.5, -2.0), 0.7);
    for p in circle(20, 2.0 * PI) {
        let back = frame.to_global(&frame.to_local(&p));
        assert!((back - p).norm() < 1e-14);
        // A change dy of the frame y is a move dy along the normal.
        let mut local = frame.to_local(&p);
        local.y += 0.25;
        assert!((frame.to_global(&local) - (p + frame.displacement(0.25))).norm() < 1e-14);
    }
    assert!((frame.axis.norm() - 1.0).abs() < 1e-15 && frame.axis.dot(&frame.normal()).abs() < 1e-15);
}

#[test]
fn overlaps_blend_with_linear_weights() {
    let points = circle(64, 2.0 * PI * 0.9);
    let segments = partition(&points, false, &PartitionSettings::default()).unwrap();
    assert!(segments.len() >= 2);
    // Segment s proposes the displacement (s, 0): an overlap point j of segments s and s + 1
    // gets (m − j)/(m + 1)·s + (j + 1)/(m + 1)·(s + 1) = s + (j + 1)/(m + 1).
    let displacements: Vec<Vec<Vec2>> = segments
        .iter()
        .enumerate()
        .map(|(s, seg)| vec![Vec2::new(s as f64, 0.0); seg.indices.len()])
        .collect();
    let blended = blend(points.len(), &segments, &displacements).unwrap();
    for (s, seg) in segments.iter().enumerate() {
        let m = seg.overlap_after;
        let tail = &seg.indices[seg.indices.len() - m..];
        for (j, &i) in tail.iter().enumerate() {
            let expected = s as f64 + (j + 1) as f64 / (m + 1) as f64;
            assert!(
                (blended[i].x - expected).abs() < 1e-14,
                "point {i}: {} vs {expected}",
                blended[i].x
            );
        }
        let own = &seg.indices[seg.overlap_before..seg.indices.len() - m];
        assert!(own.iter().all(|&i| blended[i].x == s as f64));
    }
    // Wrong lengths are errors, not panics.
    assert!(blend(points.len(), &segments, &displacements[1..]).is_err());
}

#[test]
fn strophoid_partitions_into_function_segments() {
    let clean = strophoid();
    let noise = gaussian(5, 80);
    // Han perturbs 40 interior points; here points 12..52, σ = 0.05.
    let mut noisy = clean.clone();
    for (k, i) in (12..52).enumerate() {
        noisy[i] += Vec2::new(noise[2 * k], noise[2 * k + 1]) * 0.05;
    }
    for points in [&clean, &noisy] {
        for limit in [PI, 2.0 * PI / 3.0] {
            let settings = PartitionSettings::default().with_limit(limit);
            let segments = partition(points, false, &settings).unwrap();
            check_partition(points, false, &settings, &segments);
            assert!(segments.len() >= 2);
        }
    }
}

#[test]
fn closed_curves_partition_with_wrap_around_overlap() {
    // An ellipse, and a teardrop with a sharp tail (like an airfoil's trailing edge).
    let ellipse: Vec<Vec2> = (0..80)
        .map(|i| 2.0 * PI * i as f64 / 80.0)
        .map(|t| Vec2::new(5.0 * t.cos(), t.sin()))
        .collect();
    let teardrop: Vec<Vec2> = (0..60)
        .map(|i| 2.0 * PI * i as f64 / 60.0)
        .map(|t| Vec2::new(t.cos(), 0.4 * t.sin() * (1.0 - t.cos()).powf(1.5)))
        .collect();
    for points in [&ellipse, &teardrop] {
        for limit in [PI, 2.0 * PI / 3.0] {
            let settings = PartitionSettings::default().with_limit(limit);
            let segments = partition(points, true, &settings).unwrap();
            check_partition(points, true, &settings, &segments);
            assert!(segments[0].overlap_before >= 1);
        }
    }
    // The walk starts at the sharpest turn: the teardrop's tail, point 0.
    let segments = partition(&teardrop, true, &PartitionSettings::default()).unwrap();
    assert_eq!(segments[0].indices[0], 0);
    // A closed polygon turns by 2π: at least 3 segments below π.
    assert!(
        partition(&ellipse, true, &PartitionSettings::default())
            .unwrap()
            .len()
            >= 3
    );
}

#[test]
fn corners_sharper_than_the_limit_split_with_one_shared_point() {
    // An open polyline with a 150° turn at point 10.
    let mut points: Vec<Vec2> = (0..=10).map(|i| Vec2::new(i as f64, 0.0)).collect();
    let back = 150f64.to_radians();
    points.extend((1..=10).map(|i| Vec2::new(10.0 + i as f64 * back.cos(), i as f64 * back.sin())));
    let settings = PartitionSettings::default().with_limit(2.0 * PI / 3.0);
    let segments = partition(&points, false, &settings).unwrap();
    check_partition(&points, false, &settings, &segments);
    assert_eq!(segments.len(), 2);
    assert_eq!(segments[0].overlap_after, 1);
    assert_eq!(*segments[0].indices.last().unwrap(), 10);
}

#[test]
fn bad_partition_input_is_an_error() {
    let points = circle(10, 1.0);
    let bad = PartitionSettings::default().with_limit(3.5);
    assert!(matches!(
        partition(&points, false, &bad),
        Err(Error::BadParameter { name: "limit", .. })
    ));
    let bad = PartitionSettings::default().with_overlap(0);
    assert!(matches!(
        partition(&points, false, &bad),
        Err(Error::BadParameter { name: "overlap", .. })
    ));
    let mut repeated = points.clone();
    repeated[4] = repeated[3];
    assert!(matches!(
        partition(&repeated, false, &PartitionSettings::default()),
        Err(Error::Repr(curve_repr::Error::RepeatedPoint { index: 3 }))
    ));
    assert!(partition(&points[..1], false, &PartitionSettings::default()).is_err());
    assert!(partition(&points[..2], true, &PartitionSettings::default()).is_err());
    let mut nan = points.clone();
    nan[2].y = f64::INFINITY;
    assert!(partition(&nan, false, &PartitionSettings::default()).is_err());
    // Closed polygon whose last point repeats the first.
    let mut closed = circle(12, 2.0 * PI);
    closed.push(closed[0]);
    assert!(matches!(
        partition(&closed, true, &PartitionSettings::default()),
        Err(Error::Repr(curve_repr::Error::ClosingRepeat { last: 12 }))
    ));
}

/// A segment fairer: a few Jacobi steps of Laplacian smoothing of y over x (interior points).
fn smooth_y(x: &[f64], y: &mut [f64], fixed: &[bool]) -> Result<()> {
    for _ in 0..2 {
        let old = y.to_vec();
        for i in 1..y.len() - 1 {
            if !fixed[i] {
                let t = (x[i] - x[i - 1]) / (x[i + 1] - x[i - 1]);
                y[i] = 0.5 * old[i] + 0.5 * ((1.0 - t) * old[i - 1] + t * old[i + 1]);
            }
        }
    }
    Ok(())
}

#[test]
fn segmented_fairing_smooths_a_noisy_closed_curve_within_its_constraints() {
    let n = 120;
    let clean = circle(n, 2.0 * PI);
    let noise = gaussian(11, n);
    let noisy: Vec<Vec2> = clean
        .iter()
        .zip(&noise)
        .map(|(p, e)| p * (1.0 + 0.01 * e))
        .collect();
    let radius_error =
        |pts: &[Vec2]| (pts.iter().map(|p| (p.norm() - 3.0).powi(2)).sum::<f64>() / n as f64).sqrt();
    let constraints = Constraints::default().with_fixed([7]).with_tolerance(0.05);
    let result = Pipeline::new(SegmentedFairing::new(smooth_y).with_passes(2))
        .with_closed(true)
        .with_constraints(constraints.clone())
        .run(noisy.clone())
        .unwrap();
    assert!(constraints.check(&noisy, &result.points).is_ok());
    assert_eq!(result.points[7], noisy[7]);
    // Four Jacobi steps damp white noise to about 0.44 of its rms and shrink the circle by
    // about 0.008 (a Laplacian's bias): about 0.52 of the noisy error in all.
    assert!(
        radius_error(&result.points) < 0.7 * radius_error(&noisy),
        "{} vs {}",
        radius_error(&result.points),
        radius_error(&noisy)
    );
    assert_eq!(result.iterations, 2);
}

#[test]
fn segmented_fairing_rejects_what_it_cannot_honour() {
    let err = Pipeline::new(SegmentedFairing::new(identity))
        .with_constraints(Constraints::default().with_end_clamp(EndClamp::G1))
        .run(strophoid())
        .unwrap_err();
    assert!(matches!(err, Error::ConstraintUnsupported { .. }));
    // G0 is honoured: the ends stay, bit for bit, even when the fairer moves them (the
    // curve guard off: flattening every segment wrecks the curve's counts).
    let flatten = |_: &[f64], y: &mut [f64], _: &[bool]| -> Result<()> {
        y.iter_mut().for_each(|v| *v = 0.0);
        Ok(())
    };
    let points = strophoid();
    let result = Pipeline::new(
        SegmentedFairing::new(flatten)
            .with_passes(1)
            .with_curve_guard(CurveGuard::Off),
    )
    .with_constraints(Constraints::default().with_end_clamp(EndClamp::G0))
    .run(points.clone())
    .unwrap();
    assert_eq!(result.points[0], points[0]);
    assert_eq!(result.points[64], points[64]);
    assert!(result.moved.len() > 50);
    let mut state = FairingState::new(points, Constraints::default(), false).unwrap();
    assert!(state.move_point(65, Vec2::zeros()).is_err());
}
