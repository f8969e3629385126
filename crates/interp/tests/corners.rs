//! `,C` chamfers and `,R` corner rounding between two G01 moves (LNC §4.2, Fanuc).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

mod support;

use glam::DVec3;
use swarf_interp::{Arc, Canon, Setup};
use swarf_syntax::{Diagnostic, Dialect};

fn run_text(text: &str, dialect: Dialect) -> (Vec<Canon>, Vec<Diagnostic>) {
    support::run_with(text, dialect, Setup::default())
}

/// The end points of the feeds.
fn feed_ends(events: &[Canon]) -> Vec<DVec3> {
    events
        .iter()
        .filter_map(|e| match e {
            Canon::Feed { to, .. } => Some(*to),
            _ => None,
        })
        .collect()
}

fn near(a: DVec3, b: [f64; 3]) -> bool {
    a.abs_diff_eq(DVec3::from_array(b), 1e-9)
}

#[test]
fn chamfer_cuts_equal_legs_from_the_corner() {
    let text = "G90 G00 X0 Y0\nG01 X10. Y0 ,C2. F100\nX10. Y10.\n";
    let (events, diags) = run_text(text, Dialect::Lnc);
    assert!(diags.is_empty(), "{diags:?}");
    let ends = feed_ends(&events);
    assert_eq!(ends.len(), 3, "{events:?}");
    assert!(near(ends[0], [8.0, 0.0, 0.0]));
    assert!(near(ends[1], [10.0, 2.0, 0.0]));
    assert!(near(ends[2], [10.0, 10.0, 0.0]));
}

#[test]
fn rounding_inserts_a_tangent_arc() {
    let text = "G90 G00 X0 Y0\nG01 X10. ,R3. F100\nY10.\n";
    let (events, diags) = run_text(text, Dialect::Fanuc);
    assert!(diags.is_empty(), "{diags:?}");
    match &events[..] {
        [
            Canon::Rapid { .. },
            Canon::Feed { to: a, .. },
            Canon::Arc(Arc {
                to: b, center, ccw, ..
            }),
            Canon::Feed { to: c, .. },
        ] => {
            assert!(near(*a, [7.0, 0.0, 0.0]), "{a}");
            assert!(near(*b, [10.0, 3.0, 0.0]), "{b}");
            assert!(near(*center, [7.0, 3.0, 0.0]), "{center}");
            assert!(*ccw, "a left turn rounds counter-clockwise");
            assert!(near(*c, [10.0, 10.0, 0.0]));
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_corner_needs_a_cutting_move_next() {
    let (events, diags) = run_text("G01 X10. ,C2. F100\nG00 Y10.\n", Dialect::Lnc);
    assert!(diags.iter().any(|d| d.code == "E-CORNER-NEXT"), "{diags:?}");
    // Drawn sharp: the full first move, then the rapid.
    assert!(matches!(events[0], Canon::Feed { to, .. } if near(to, [10.0, 0.0, 0.0])));
    assert!(matches!(events[1], Canon::Rapid { .. }));
    let (_, diags) = run_text("G01 X10. ,R2. F100\nM30\n", Dialect::Lnc);
    assert!(diags.iter().any(|d| d.code == "E-CORNER-NEXT"), "{diags:?}");
}

#[test]
fn consecutive_corners_are_each_cut() {
    // A square with a chamfer at two corners.
    let text = "G90 G00 X0 Y0\nG01 X10. ,C1. F100\nY10. ,C1.\nX0\n";
    let (events, diags) = run_text(text, Dialect::Lnc);
    assert!(diags.is_empty(), "{diags:?}");
    let ends = feed_ends(&events);
    let expected = [
        [9.0, 0.0, 0.0],
        [10.0, 1.0, 0.0],
        [10.0, 9.0, 0.0],
        [9.0, 10.0, 0.0],
        [0.0, 10.0, 0.0],
    ];
    assert_eq!(ends.len(), expected.len(), "{events:?}");
    for (e, x) in ends.iter().zip(expected) {
        assert!(near(*e, x), "{e} vs {x:?}");
    }
}
