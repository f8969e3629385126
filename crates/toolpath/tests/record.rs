//! Recording canonical events into a toolpath: geometry, statistics and the line index.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Axis, Canon, Setup, Sink, Source, run};
use swarf_syntax::{Dialect, parse};
use swarf_toolpath::{SegmentKind, Toolpath, tessellate_arc};

#[test]
fn records_segments_lengths_bounds_and_time() {
    let program = parse(
        "G0 X10 Y0 Z5\nG1 Z0 F600\nG1 X40 F1200\nG4 P1000\nM6 T3\nM30\n",
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
    // 5 mm at 600 mm/min = 0.5 s, 30 mm at 1200 = 1.5 s, dwell 1 s, rapid at 6000 mm/min.
    let expected = 0.5 + 1.5 + 1.0 + rapid / 100.0;
    assert!((path.estimated_secs() - expected).abs() < 1e-9);
    assert_eq!(path.tools(), [3]);
    assert_eq!(path.first_segment_of_line(3), Some(2));
}

#[test]
fn arcs_are_tessellated_within_tolerance_and_end_exactly() {
    let from = DVec3::new(10.0, 0.0, 0.0);
    let to = DVec3::new(-10.0, 0.0, -2.0);
    let pts = tessellate_arc(from, to, DVec3::ZERO, Axis::Z, true, 0);
    assert!(pts.len() > 10);
    assert_eq!(*pts.last().unwrap(), to);
    for p in &pts {
        assert!(((p.x * p.x + p.y * p.y).sqrt() - 10.0).abs() < 1e-9);
        assert!(p.y >= -1e-9, "ccw from +x to -x goes through +y");
    }
    let mut path = Toolpath::new(from, 10_000.0);
    path.emit(
        Source { block: 0, line: 7 },
        &Canon::Arc {
            to: from,
            center: DVec3::ZERO,
            axis: Axis::Z,
            ccw: false,
            turns: 0,
            feed_mm_per_min: 100.0,
        },
    );
    assert!(path.lines().iter().all(|&l| l == 7));
    assert!((path.feed_length_mm() - 20.0 * std::f64::consts::PI).abs() < 0.05);
}
