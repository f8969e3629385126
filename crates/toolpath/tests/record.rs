//! Recording canonical events into a toolpath: geometry, statistics and the line index.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Arc, Axis, Canon, Machine, Setup, Sink, Source, run};
use swarf_syntax::{Dialect, parse};
use swarf_toolpath::{Kinematics, SegmentKind, Toolpath, tessellate_arc};

#[test]
fn records_segments_lengths_bounds_and_time() {
    let program = parse(
        "G0 X10. Y0 Z5.\nG1 Z0 F600.\nG1 X40. F1200.\nG4 P1000\nM6 T3\nM30\n",
        Dialect::Fanuc,
    );
    let mut path = Toolpath::new(DVec3::ZERO, 6000.0);
    let diags = run(&program, Setup::default(), &mut path);
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(path.len(), 3);
    assert_eq!(
        path.kinds(),
        [SegmentKind::Rapid, SegmentKind::Feed, SegmentKind::Feed]
    );
    assert_eq!(path.lines(), [1, 2, 3]);
    assert_eq!(path.segment_start(2), DVec3::new(10.0, 0.0, 0.0));
    let b = path.bounds().unwrap();
    assert_eq!(b.min, DVec3::new(0.0, 0.0, 0.0));
    assert_eq!(b.max, DVec3::new(40.0, 0.0, 5.0));
    let rapid = (125.0f64).sqrt();
    assert!((path.rapid_length_mm() - rapid).abs() < 1e-9);
    assert!((path.feed_length_mm() - 35.0).abs() < 1e-9);
    // With the default 1000 mm/s² every move now also pays for speeding up and slowing down
    // (each starts and ends at rest: a rapid, then a 90° corner): a move long enough to reach
    // its speed v takes d/v + v/a. Rapid at 6000 mm/min = 100 mm/s (+0.1 s), 5 mm at
    // 600 mm/min = 0.5 s (+0.01 s), 30 mm at 1200 = 1.5 s (+0.02 s), then the 1 s dwell.
    let expected = rapid / 100.0 + 0.1 + 0.5 + 0.01 + 1.5 + 0.02 + 1.0;
    assert!(
        (path.estimated_secs() - expected).abs() < 1e-9,
        "{} s",
        path.estimated_secs()
    );
    assert_eq!(path.tools(), [3]);
    assert_eq!(path.lines().iter().position(|&l| l == 3), Some(2));
}

#[test]
fn arcs_are_tessellated_within_tolerance_and_end_exactly() {
    let from = DVec3::new(10.0, 0.0, 0.0);
    let to = DVec3::new(-10.0, 0.0, -2.0);
    let arc = Arc {
        to,
        center: DVec3::ZERO,
        axis: Axis::Z,
        ccw: true,
        turns: 0,
        feed_mm_per_min: 100.0,
    };
    let pts = tessellate_arc(from, &arc);
    assert!(pts.len() > 10);
    assert_eq!(*pts.last().unwrap(), to);
    for p in &pts {
        assert!(((p.x * p.x + p.y * p.y).sqrt() - 10.0).abs() < 1e-9);
        assert!(p.y >= -1e-9, "ccw from +x to -x goes through +y");
    }
    let mut path = Toolpath::new(from, 10_000.0);
    path.emit(
        Source { block: 0, line: 7 },
        &Canon::Arc(Arc {
            to: from,
            ccw: false,
            ..arc
        }),
    );
    assert!(path.lines().iter().all(|&l| l == 7));
    assert!((path.feed_length_mm() - 20.0 * std::f64::consts::PI).abs() < 0.05);
}

/// 1000 mm/s², rapids at 10 m/min, no per-axis limits.
fn kinematics() -> Kinematics {
    Kinematics::from_machine(&Machine::default())
}

fn feed(path: &mut Toolpath, line: u32, to: DVec3, feed_mm_per_min: f64) {
    path.emit(
        Source { block: line, line },
        &Canon::Feed {
            to,
            feed_mm_per_min,
        },
    );
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn a_short_move_never_reaches_its_feed() {
    // 1 mm at 100 mm/s would need 10 mm to reach the feed (v²/a): accelerate for half the
    // distance and brake for the other half, t = 2·sqrt(d/a).
    let mut path = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut path, 1, DVec3::X, 6000.0);
    let expected = 2.0 * (1.0f64 / 1000.0).sqrt();
    assert!(
        close(path.estimated_secs(), expected),
        "{}",
        path.estimated_secs()
    );
    assert_eq!(path.timeline().end_times(), [path.estimated_secs()]);
}

#[test]
fn a_long_move_cruises_at_its_feed() {
    // t = d/v + v/a: 100 mm at 100 mm/s, plus 0.1 s lost speeding up and slowing down.
    let mut path = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut path, 1, DVec3::new(0.0, 100.0, 0.0), 6000.0);
    assert!(
        close(path.estimated_secs(), 1.1),
        "{}",
        path.estimated_secs()
    );
}

#[test]
fn collinear_and_gently_bent_joins_keep_speed_sharp_corners_stop() {
    // Two collinear 50 mm moves run like one 100 mm move; the first ends after 0.1 s of
    // acceleration (5 mm) and 45 mm at full speed.
    let mut straight = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut straight, 1, DVec3::new(50.0, 0.0, 0.0), 6000.0);
    feed(&mut straight, 2, DVec3::new(100.0, 0.0, 0.0), 6000.0);
    let timeline = straight.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.55) && close(times[1], 1.1), "{times:?}");

    // A 5° bend is below the corner threshold: the same times (the second leg is 50 mm too).
    let mut bent = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut bent, 1, DVec3::new(50.0, 0.0, 0.0), 6000.0);
    let a = 5.0f64.to_radians();
    feed(
        &mut bent,
        2,
        DVec3::new(50.0 + 50.0 * a.cos(), 50.0 * a.sin(), 0.0),
        6000.0,
    );
    let timeline = bent.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.55) && close(times[1], 1.1), "{times:?}");

    // A 90° corner stops: each leg is 50/100 + 100/1000 s.
    let mut corner = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut corner, 1, DVec3::new(50.0, 0.0, 0.0), 6000.0);
    feed(&mut corner, 2, DVec3::new(50.0, 50.0, 0.0), 6000.0);
    let timeline = corner.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.6) && close(times[1], 1.2), "{times:?}");
}

#[test]
fn a_slower_next_move_is_entered_at_its_feed() {
    // 50 mm at 100 mm/s then 50 mm at 50 mm/s in line: the first accelerates 0→100 (5 mm,
    // 0.1 s), cruises 41.25 mm (0.4125 s) and brakes 100→50 (3.75 mm, 0.05 s); the second
    // cruises 48.75 mm at 50 (0.975 s) and brakes to rest (1.25 mm, 0.05 s).
    let mut path = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut path, 1, DVec3::new(50.0, 0.0, 0.0), 6000.0);
    feed(&mut path, 2, DVec3::new(100.0, 0.0, 0.0), 3000.0);
    let timeline = path.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.5625), "{times:?}");
    assert!(close(times[1], 0.5625 + 1.025), "{times:?}");
}

#[test]
fn many_tiny_moves_plan_across_blocks() {
    // 10 000 collinear moves of 0.01 mm: one 100 mm move for the planner, 1.1 s.
    let mut path = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    for k in 1..=10_000 {
        feed(
            &mut path,
            k,
            DVec3::new(f64::from(k) * 0.01, 0.0, 0.0),
            6000.0,
        );
    }
    assert!(
        (path.estimated_secs() - 1.1).abs() < 1e-6,
        "{}",
        path.estimated_secs()
    );
    let timeline = path.timeline();
    let times = timeline.end_times();
    assert_eq!(times.len(), path.len());
    assert!(times.windows(2).all(|w| w[0] <= w[1]));
    // Halfway along the tool is cruising: 5 mm of acceleration in 0.1 s, then 45 mm.
    assert!((times[4999] - 0.55).abs() < 1e-6, "{}", times[4999]);
}

#[test]
fn rapids_honour_per_axis_rates_and_stop_at_their_ends() {
    let setup = Setup::from_toml(
        "[machine]\nrapid_mm_per_min = 12000\nrapid_xyz_mm_per_min = [12000, 12000, 2400]\nacceleration_mm_per_s2 = 500\n",
    )
    .unwrap();
    assert_eq!(setup.machine.acceleration_mm_per_s2, 500.0);
    let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    // Down 100 mm in Z at 40 mm/s: 100/40 + 40/500 s.
    path.emit(
        Source::default(),
        &Canon::Rapid {
            to: DVec3::new(0.0, 0.0, -100.0),
        },
    );
    // Then (30, 0, 40) mm, Z carrying 0.8 of the motion: 40/0.8 = 50 mm/s along the path,
    // below X's 200/0.6; 50 mm at 50 mm/s + 50/500 s.
    path.emit(
        Source::default(),
        &Canon::Rapid {
            to: DVec3::new(30.0, 0.0, -60.0),
        },
    );
    // Then 200 mm in X alone at the path rate 200 mm/s: 1 + 0.4 s.
    path.emit(
        Source::default(),
        &Canon::Rapid {
            to: DVec3::new(230.0, 0.0, -60.0),
        },
    );
    let timeline = path.timeline();
    let times = timeline.end_times();
    let first = 2.5 + 0.08;
    let second = first + 1.0 + 0.1;
    assert!(
        close(times[0], first) && close(times[1], second),
        "{times:?}"
    );
    assert!(close(times[2], second + 1.4), "{times:?}");
}

#[test]
fn without_acceleration_moves_take_length_over_feed() {
    let machine = Machine {
        acceleration_mm_per_s2: 0.0,
        ..Machine::default()
    };
    let mut path = Toolpath::for_machine(DVec3::ZERO, &machine);
    feed(&mut path, 1, DVec3::new(10.0, 0.0, 0.0), 600.0);
    path.emit(
        Source::default(),
        &Canon::Rapid {
            to: DVec3::new(10.0, 0.0, 100.0),
        },
    );
    assert!(
        close(path.estimated_secs(), 1.0 + 0.6),
        "{}",
        path.estimated_secs()
    );
}

#[test]
fn arcs_join_tangent_lines_smoothly_and_respect_centripetal_acceleration() {
    // 50 mm along X at 100 mm/s into a tangent quarter circle of radius 10 (centripetal
    // limit sqrt(1000·10) = 100 mm/s): the line never slows down, so it takes 0.1 s to reach
    // speed plus 45 mm at 100 mm/s; the arc runs at 100 mm/s and brakes at its end.
    let mut path = Toolpath::with_kinematics(DVec3::ZERO, kinematics());
    feed(&mut path, 1, DVec3::new(50.0, 0.0, 0.0), 6000.0);
    path.emit(
        Source { block: 2, line: 2 },
        &Canon::Arc(Arc {
            to: DVec3::new(60.0, 10.0, 0.0),
            center: DVec3::new(50.0, 10.0, 0.0),
            axis: Axis::Z,
            ccw: true,
            turns: 0,
            feed_mm_per_min: 6000.0,
        }),
    );
    let timeline = path.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.55), "{times:?}");
    let arc_mm = path.feed_length_mm() - 50.0;
    let expected = 0.55 + arc_mm / 100.0 + 100.0 / (2.0 * 1000.0);
    assert!(
        close(path.estimated_secs(), expected),
        "{} vs {expected}",
        path.estimated_secs()
    );

    // A full circle of radius 1 at F6000 is held to sqrt(1000·1) mm/s: L/v + v/a.
    let mut small = Toolpath::with_kinematics(DVec3::new(1.0, 0.0, 0.0), kinematics());
    small.emit(
        Source::default(),
        &Canon::Arc(Arc {
            to: DVec3::new(1.0, 0.0, 0.0),
            center: DVec3::ZERO,
            axis: Axis::Z,
            ccw: true,
            turns: 0,
            feed_mm_per_min: 6000.0,
        }),
    );
    let v = 1000.0f64.sqrt();
    let expected = small.feed_length_mm() / v + v / 1000.0;
    assert!(
        close(small.estimated_secs(), expected),
        "{}",
        small.estimated_secs()
    );
}

#[test]
fn dwells_and_tool_changes_stop_the_tool_and_are_on_the_timeline() {
    let program = parse(
        "G1 X50. F6000.\nG4 P500\nX100.\nT2 M6\nX150.\nG4 P250\n",
        Dialect::Fanuc,
    );
    let mut path = Toolpath::default();
    let diags = run(&program, Setup::default(), &mut path);
    assert!(diags.is_empty(), "{diags:?}");
    // Each 50 mm leg starts and ends at rest: 0.6 s.
    let timeline = path.timeline();
    let times = timeline.end_times();
    assert!(close(times[0], 0.6), "{times:?}");
    assert!(close(times[1], 0.6 + 0.5 + 0.6), "{times:?}");
    assert!(close(times[2], 1.7 + 0.6), "{times:?}");
    assert!(close(path.estimated_secs(), 2.3 + 0.25));
    assert!(close(timeline.dwell_before(1), 0.5) && close(timeline.dwell_before(3), 0.25));
    let (start, end) = timeline.span(1).unwrap();
    assert!(close(start, 1.1) && close(end, 1.7));
    assert_eq!(path.segment_tools(), [0, 0, 2]);
    assert_eq!(path.tools(), [2]);

    // Where the tool is at a given time.
    assert_eq!(timeline.segment_at(0.0), Some(0));
    assert_eq!(timeline.segment_at(0.6), Some(0));
    assert_eq!(timeline.segment_at(0.8), Some(1));
    assert_eq!(timeline.segment_at(99.0), Some(2));
    assert_eq!(timeline.finished_at(0.0), 0);
    assert_eq!(timeline.finished_at(0.61), 1);
    assert_eq!(timeline.finished_at(99.0), 3);
    assert!(close(timeline.total_secs(), path.estimated_secs()));
}

#[test]
fn keeps_each_hole_with_its_tool_and_its_motions() {
    let program = parse(
        "T4 M06\nG0 X0 Y0 Z20.\nG99 G81 X10. Y10. R2. Z-5. F100\nX20.\nG80\nG0 X50.\n",
        Dialect::Fanuc,
    );
    let mut path = Toolpath::default();
    run(&program, Setup::default(), &mut path);
    let holes = path.holes();
    assert_eq!(holes.len(), 2);
    assert_eq!((holes[0].cycle, holes[0].index, holes[0].tool), (810, 1, 4));
    assert_eq!(holes[1].top, DVec3::new(20.0, 10.0, 2.0));
    assert_eq!(holes[1].bottom, DVec3::new(20.0, 10.0, -5.0));
    assert_eq!(path.holes_per_tool(), [(4, 2)]);
    // The segments of the cycle blocks belong to their holes, the later move to none.
    for segment in 0..path.len() {
        let line = path.lines()[segment];
        let hole = path.hole_of_segment(segment);
        match line {
            3 => assert_eq!(hole, Some(0), "segment {segment}"),
            4 => assert_eq!(hole, Some(1), "segment {segment}"),
            _ => assert_eq!(hole, None, "segment {segment}"),
        }
    }
}

#[test]
fn cycle_moves_tell_plunges_from_retracts_and_positioning() {
    use swarf_toolpath::CycleMove;
    let program = parse(
        "G0 X0 Y0 Z20.\nG98 G83 X10. Y10. R2. Z-5. Q3. F100\nG80\n",
        Dialect::Fanuc,
    );
    let mut path = Toolpath::default();
    run(&program, Setup::default(), &mut path);
    let roles: Vec<CycleMove> = path.cycle_moves().iter().map(|m| m.1).collect();
    // Over the hole, down to R, peck to −1, out to R, back down to 1 above the cut, peck to
    // −4, out, back down, to the bottom, out.
    use CycleMove::{Other, Plunge, Retract};
    assert_eq!(
        roles,
        [
            Other, Other, Plunge, Retract, Other, Plunge, Retract, Other, Plunge, Retract
        ]
    );
}

#[test]
fn keeps_each_program_zero_the_moves_came_from() {
    let setup = Setup::from_toml(
        "[work_offsets]\nG54 = [100.0, 50.0, -20.0]\nG55 = [200.0, 50.0, -20.0]\n",
    )
    .unwrap();
    let program = parse(
        "G54 G0 X0 Y0\nG55 X1.\nG54 X2.\nG52 X5.\nG1 X0 F100.\nG55\nM30\n",
        Dialect::Fanuc,
    );
    let mut path = Toolpath::default();
    run(&program, setup, &mut path);
    assert_eq!(
        path.origins(),
        [
            DVec3::new(100.0, 50.0, -20.0),
            DVec3::new(200.0, 50.0, -20.0),
            DVec3::new(105.0, 50.0, -20.0),
        ]
    );
}

#[test]
fn keeps_the_programmed_contour_of_compensated_blocks() {
    let program = parse(
        "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nX20.\nG40 G00 X30.\nM30\n",
        Dialect::Fanuc,
    );
    let mut setup = Setup::default();
    setup.registers.insert(
        1,
        swarf_interp::Register {
            radius: 2.0,
            ..Default::default()
        },
    );
    let mut path = Toolpath::new(DVec3::ZERO, 6000.0);
    run(&program, setup, &mut path);
    // The segments are the tool centre, 2 mm left of the contour: up X−2, along Y22.
    assert!(path.ends().contains(&DVec3::new(-2.0, 22.0, 0.0)));
    // The programmed contour is kept beside it, line by line.
    let programmed: Vec<(u32, DVec3)> = path
        .programmed()
        .iter()
        .map(|(l, e)| (*l, e.end_point().unwrap()))
        .collect();
    assert_eq!(
        programmed,
        [
            (2, DVec3::new(0.0, 0.0, 0.0)),
            (3, DVec3::new(0.0, 20.0, 0.0)),
            (4, DVec3::new(20.0, 20.0, 0.0)),
            (5, DVec3::new(30.0, 20.0, 0.0)),
        ]
    );
}

#[test]
fn keeps_the_stroke_limits_the_program_sets() {
    // LNC soft limits on X and Y (Z left open), then a Syntec-style zone set twice (kept once).
    let program = parse(
        "G22 X100. Y50. I-100. J-50.;\nG00 X90. Y40. Z10.;\nG01 X-20. Y-30. Z-5. F500.;\nG23;\nG22 X100. Y50. I-100. J-50.;\nM30;\n",
        Dialect::Lnc,
    );
    let mut path = Toolpath::default();
    let diags = run(&program, Setup::default(), &mut path);
    assert!(
        diags
            .iter()
            .all(|d| d.severity != swarf_syntax::Severity::Error),
        "{diags:?}"
    );
    assert_eq!(path.zones().len(), 1);
    let zone = path.zones()[0];
    assert_eq!(zone.min.truncate(), glam::DVec2::new(-100.0, -50.0));
    assert_eq!(zone.max.truncate(), glam::DVec2::new(100.0, 50.0));
    assert!(zone.min.z.is_infinite() && zone.max.z.is_infinite());
    assert!(!zone.inside_forbidden);
    // The open Z axis is drawn a tenth of the path's diagonal past its bounds (Z -5 … 10).
    let boxes = path.zone_boxes();
    assert_eq!(boxes.len(), 1);
    let (min, max) = boxes[0];
    let b = path.bounds().unwrap();
    let margin = (b.max - b.min).length() * 0.1;
    assert_eq!((min.x, min.y, max.x, max.y), (-100.0, -50.0, 100.0, 50.0));
    assert!((min.z - (-5.0 - margin)).abs() < 1e-9, "{min}");
    assert!((max.z - (10.0 + margin)).abs() < 1e-9, "{max}");
    // Twelve edges, each parallel to one axis.
    let edges = swarf_toolpath::box_edges(min, max);
    assert_eq!(edges.len(), 12);
    for (a, b) in edges {
        let d = b - a;
        assert_eq!([d.x, d.y, d.z].iter().filter(|c| **c != 0.0).count(), 1);
    }
}

#[test]
fn a_syntec_protected_zone_is_told_to_the_sink_and_g23_turns_it_off() {
    struct Zones(Vec<Option<swarf_interp::StrokeZone>>);
    impl Sink for Zones {
        fn emit(&mut self, _: Source, _: &Canon) {}
        fn stroke_zone(&mut self, _: Source, zone: Option<&swarf_interp::StrokeZone>) {
            self.0.push(zone.copied());
        }
    }
    let program = parse(
        "G22 X10. I0. Y20. J-5.\nG00 X-20.\nG23\nG22 X5. I5.\n",
        Dialect::Syntec,
    );
    let mut sink = Zones(Vec::new());
    run(&program, Setup::default(), &mut sink);
    // The last G22's only pair is equal: nothing is protected, so no zone.
    assert_eq!(sink.0.len(), 3, "{:?}", sink.0);
    let z = sink.0[0].unwrap();
    assert!(z.inside_forbidden);
    assert_eq!(z.min.truncate(), glam::DVec2::new(0.0, -5.0));
    assert_eq!(z.max.truncate(), glam::DVec2::new(10.0, 20.0));
    assert_eq!(sink.0[1..], [None, None]);
}

#[test]
fn straight_moves_taken_in_registers_record_as_their_events_do() {
    let moves = [
        (true, DVec3::new(10.0, 0.0, 5.0), 0.0),
        (false, DVec3::new(10.0, 0.0, 0.0), 600.0),
        (false, DVec3::new(40.0, 2.5, 0.0), 1200.0),
        (false, DVec3::new(40.0, 2.5, 0.0), 1200.0),
        (true, DVec3::new(-3.0, 7.0, 12.0), 0.0),
        (false, DVec3::new(0.0, 0.0, -1.0), 0.0),
    ];
    let mut by_event = Toolpath::new(DVec3::ZERO, 6000.0);
    let mut by_numbers = Toolpath::new(DVec3::ZERO, 6000.0);
    for (line, &(rapid, to, feed_mm_per_min)) in (1..).zip(&moves) {
        let event = if rapid {
            Canon::Rapid { to }
        } else {
            Canon::Feed {
                to,
                feed_mm_per_min,
            }
        };
        let source = Source { block: line, line };
        by_event.emit(source, &event);
        by_numbers.straight(source, rapid, to.x, to.y, to.z, feed_mm_per_min);
    }
    assert_eq!(by_numbers.len(), moves.len());
    assert_eq!(by_numbers, by_event);
    assert_eq!(by_numbers.kinds()[4], SegmentKind::Rapid);
    assert_eq!(by_numbers.ends()[2], DVec3::new(40.0, 2.5, 0.0));
}

/// A toolpath is full when what it holds reaches `max_motions` segments: a loop whose every
/// move changes the tool and the feed keeps half as many segments as a loop of plain moves (a
/// change weighs half a segment), so that its memory stays within the same bound.
#[test]
fn changes_of_feed_and_tool_count_towards_the_motion_limit() {
    let mut setup = Setup::default();
    setup.machine.max_motions = 1000;
    let segments = |text: &str| {
        let program = parse(text, Dialect::Fanuc);
        let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
        let diags = run(&program, setup.clone(), &mut path);
        let codes: Vec<_> = diags.iter().map(|d| d.code).collect();
        assert_eq!(codes, ["E-MOTION-LIMIT"], "{text}");
        path.len()
    };
    assert_eq!(segments("G01 F100\nN1 X1.\nX0\nGOTO 1\n"), 1000);
    assert_eq!(
        segments("N1 T1 M6 G01 X1. F100\nT2 M6 X0 F200\nGOTO 1\n"),
        501
    );
}

/// A path that only measures its segments gives the figures of one that keeps them, to the bit,
/// and fills up at the same segment, holding none of them.
#[test]
fn a_measuring_path_gives_the_figures_of_a_kept_one() {
    // Rapids, feeds, arcs, a dwell, tool changes, holes, and a long smooth run of moves (more
    // than the planner's look-ahead holds before it settles a batch).
    let mut text = String::from(
        "G0 X10. Y0 Z5.\nT1 M6\nG1 Z0 F600.\nG2 X20. Y10. R10.\nG4 P500\n\
         G81 X30. Y30. Z-2. R1. F100.\nX40.\nG80\nT2 M6\nG1 X0 Y0 F1200.\n",
    );
    for i in 0..3 * swarf_toolpath::LOOKAHEAD_SEGMENTS {
        let y = if i % 2 == 0 { 0.01 } else { 0.0 };
        text.push_str(&format!("X{}. Y{y}\n", i + 1));
    }
    text.push_str("G0 Z50.\nM30\n");
    let program = parse(&text, Dialect::Fanuc);
    let setup = Setup::default();
    let mut kept = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    let mut measured = Toolpath::measuring(DVec3::ZERO, &setup.machine);
    assert!(run(&program, setup.clone(), &mut kept).is_empty());
    assert!(run(&program, setup.clone(), &mut measured).is_empty());
    assert!(kept.len() > 3 * swarf_toolpath::LOOKAHEAD_SEGMENTS);
    assert_eq!(measured.len(), kept.len());
    assert_eq!(measured.bounds(), kept.bounds());
    assert_eq!(
        measured.rapid_length_mm().to_bits(),
        kept.rapid_length_mm().to_bits()
    );
    assert_eq!(
        measured.feed_length_mm().to_bits(),
        kept.feed_length_mm().to_bits()
    );
    assert_eq!(
        measured.estimated_secs().to_bits(),
        kept.estimated_secs().to_bits()
    );
    assert_eq!(measured.tools(), [1, 2]);
    assert_eq!(measured.tools(), kept.tools());
    assert_eq!(measured.holes(), kept.holes());
    assert_eq!(measured.holes_per_tool(), [(1, 2)]);
    assert!(measured.ends().is_empty() && measured.kinds().is_empty());
    assert!(measured.lines().is_empty() && measured.timeline().is_empty());

    // Both stop at the same segment of a loop that fills them.
    let mut setup = Setup::default();
    setup.machine.max_motions = 1000;
    let program = parse(
        "N1 T1 M6 G01 X1. F100\nT2 M6 X0 F200\nGOTO 1\n",
        Dialect::Fanuc,
    );
    let mut kept = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    let mut measured = Toolpath::measuring(DVec3::ZERO, &setup.machine);
    run(&program, setup.clone(), &mut kept);
    run(&program, setup, &mut measured);
    assert_eq!((measured.len(), kept.len()), (501, 501));
}
