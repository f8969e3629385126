//! G45–G48 tool position offsets (Syntec §1.27, example E41; Fanuc the same).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Arc, Canon, CanonRecorder, Setup, run};
use swarf_syntax::{Dialect, parse};

fn run_text(text: &str, dialect: Dialect) -> (Vec<Canon>, Vec<&'static str>) {
    let setup = Setup::from_toml("[registers.1]\nradius = 5.0\n").unwrap();
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut codes: Vec<&'static str> = program.diagnostics.iter().map(|d| d.code).collect();
    codes.extend(run(&program, setup, &mut rec).iter().map(|d| d.code));
    let motions = rec
        .events
        .into_iter()
        .map(|(_, e)| e)
        .filter(|e| e.end_point().is_some())
        .collect();
    (motions, codes)
}

fn ends(motions: &[Canon]) -> Vec<[f64; 2]> {
    motions
        .iter()
        .filter_map(Canon::end_point)
        .map(|p| [p.x, p.y])
        .collect()
}

#[test]
fn e41_each_block_travels_as_the_manual_states() {
    // D1 = 5: the manual's comments give each block's travel in terms of D1.
    let text = "N001 G91 G46 G00 X80.0 Y50.0 D01;
N002 G47 G01 X50.0 F120.0;
N003 Y40.0;
N004 G48 X40.0;
N005 Y-40.0;
N006 G45 X30.0;
N007 G45 G03 X30.0 Y30.0 J30.0;
N008 G45 G01 Y20.0;
N009 G46 X0;
N010 G46 G02 X-30.0 Y30.0 J30.0;
N011 G45 G01 Y0;
N012 G47 X-120.0;
N013 G47 Y-80.0;
";
    let (motions, codes) = run_text(text, Dialect::Syntec);
    assert!(codes.iter().all(|c| !c.starts_with("E-")), "{codes:?}");
    let expected = [
        [75.0, 45.0],   // (80 - D1, 50 - D1)
        [135.0, 45.0],  // X 50 + 2·D1
        [135.0, 85.0],  // Y 40, not offset (one-shot)
        [165.0, 85.0],  // X 40 - 2·D1
        [165.0, 45.0],  // Y -40
        [200.0, 45.0],  // X 30 + D1
        [235.0, 75.0],  // the arc's radius 30 + D1 about its centre (200, 75)
        [235.0, 100.0], // Y 20 + D1
        [230.0, 100.0], // X0 under G91: -D1
        [205.0, 130.0], // the arc's radius 30 - D1 about (230, 130)
        [205.0, 135.0], // Y0: +D1
        [75.0, 135.0],  // X -(120 + 2·D1)
        [75.0, 45.0],   // Y -(80 + 2·D1)
    ];
    assert_eq!(ends(&motions), expected);
    match &motions[6] {
        Canon::Arc(Arc { center, ccw, .. }) => {
            assert_eq!(*center, DVec3::new(200.0, 75.0, 0.0));
            assert!(*ccw);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_written_minus_zero_sets_the_direction_and_g90_without_travel_is_not_offset() {
    let (motions, _) = run_text("G91 G45 G01 Y-0 D1 F100.\nG46 Y-0\n", Dialect::Syntec);
    assert_eq!(ends(&motions), [[0.0, -5.0], [0.0, 0.0]]);
    let (motions, _) = run_text(
        "G90 G01 X10. F100.\nG45 X10. D1\nG45 X20.\n",
        Dialect::Fanuc,
    );
    assert_eq!(ends(&motions), [[10.0, 0.0], [10.0, 0.0], [25.0, 0.0]]);
}

#[test]
fn arcs_must_be_quarter_or_three_quarter_with_ijk_and_no_cutter_compensation() {
    let (_, codes) = run_text(
        "G91 G01 X10. F100. D1\nG45 G03 X20. Y0 I10.\n",
        Dialect::Syntec,
    );
    assert!(codes.contains(&"E-POSITION-OFFSET"), "{codes:?}");
    let (_, codes) = run_text(
        "G91 G01 X10. F100. D1\nG45 G03 X10. Y10. R10.\n",
        Dialect::Syntec,
    );
    assert!(codes.contains(&"E-POSITION-OFFSET"), "{codes:?}");
    let (_, codes) = run_text(
        "G17 G90 G00 X-20. Y-20. D1\nG41 G01 X0 Y0 F100.\nG45 X10.\n",
        Dialect::Syntec,
    );
    assert!(codes.contains(&"E-POSITION-OFFSET"), "{codes:?}");
    // A missing register is said, and the move runs unchanged.
    let (motions, codes) = run_text("G91 G45 G01 X10. D7 F100.\n", Dialect::Fanuc);
    assert!(codes.contains(&"E-OFFSET-REGISTER"), "{codes:?}");
    assert_eq!(ends(&motions), [[10.0, 0.0]]);
}
