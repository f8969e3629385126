//! Program flow, macros and coordinate systems, checked against the manuals' worked examples
//! (gcode-reference §7) where they state a result.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

mod support;

use glam::DVec3;
use support::run_with;
use swarf_interp::{Arc, Canon, Setup};
use swarf_syntax::{Diagnostic, Dialect, Severity};

fn run_text(text: &str, dialect: Dialect) -> (Vec<Canon>, Vec<Diagnostic>) {
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    run_with(text, dialect, setup)
}

/// End points of the motions, rounded to 0.001.
fn ends(events: &[Canon]) -> Vec<[f64; 3]> {
    support::ends_rounded(events, 1000.0)
}

fn errors(diags: &[Diagnostic]) -> Vec<&'static str> {
    diags
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| d.code)
        .collect()
}

#[test]
fn while_loop_and_variables_draw_a_staircase() {
    let text = "#1=0\nG01 F100\nWHILE [#1 LT 3] DO1\n#1=#1+1\nX#1 Y[#1*2]\nEND1\nM30\n";
    let (events, diags) = run_text(text, Dialect::Fanuc);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [[1.0, 2.0, 0.0], [2.0, 4.0, 0.0], [3.0, 6.0, 0.0]]
    );
}

#[test]
fn if_goto_skips_and_a_vacant_variable_leaves_the_word_out() {
    let text = "#2=5\nIF [#2 GT 4] GOTO 20\nG00 X99\nN20 G00 X1 Y#3\nM30\n";
    let (events, diags) = run_text(text, Dialect::Fanuc);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(ends(&events), [[1.0, 0.0, 0.0]]);
}

#[test]
fn subprogram_with_repeats_and_return() {
    // KT's format `M98 P2200L7` and Fanuc's `M98 P30010` (3 times O0010).
    let text = "O0001\nG91 G00\nM98 P2200 L3\nM98 P30010\nM30\nO2200\nX1.\nM99\nO0010\nY1.\nM99\n";
    let (events, diags) = run_text(text, Dialect::Kt);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [1.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
            [3.0, 1.0, 0.0],
            [3.0, 2.0, 0.0],
            [3.0, 3.0, 0.0]
        ]
    );
}

#[test]
fn kt_repeated_rotation_draws_an_octagon() {
    // E6: the shape O2100 once, then seven times more rotated by a further 45° each time.
    let text = "G92 G69 G17 X0 Y0;\nG01 F200 H01;\nM98 P2100;\nM98 P2200L7;\nG90 G00 X0 Y0;\nM30;\nO2200\nG91 G68 X0 Y0 R45;\nG90 M98 P2100;\nM99;\nO2100\nG90 G01 X0 Y-10;\nX4.142;\nX7.071 Y-7.071;\nM99;\n";
    let (events, diags) = run_text(text, Dialect::Kt);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    let pts = ends(&events);
    assert_eq!(pts.len(), 8 * 3 + 1);
    // Every vertex of the octagon is 10.824 from the centre (apothem 10).
    for p in pts.iter().take(24).skip(1).step_by(3) {
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        assert!((r - 10.824).abs() < 0.01, "{p:?} at {r}");
    }
    // The last copy ends at (7.071, -7.071) rotated by 315°: (0, -10).
    let last = pts[23];
    assert!(
        (last[0] - 0.0).abs() < 0.01 && (last[1] + 10.0).abs() < 0.01,
        "{last:?}"
    );
}

#[test]
fn kt_rotation_about_a_centre_e5() {
    // E5: rotated end points stated by the reference.
    let text = "N1 G90 G69 G54 G49 G40 G17 X-50 Y-50 Z30\nN2 G68 X70 Y30 R45\nN3 G90 G01 X0 Y0 F800\nN4 G91 X100\nN5 G02 Y100 R100\nN6 G03 X-100 I-50 J-50\nN7 G01 Y-100\nN8 G90 G69 X-50 Y-50\nN9 M30\n";
    let (events, diags) = run_text(text, Dialect::Kt);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    let pts = ends(&events);
    let expected = [
        [-50.0, -50.0],
        [41.716, -40.711],
        [112.426, 30.0],
        [41.716, 100.711],
        [-28.995, 30.0],
        [41.716, -40.711],
        [-50.0, -50.0],
    ];
    for (p, e) in pts.iter().zip(expected) {
        assert!(
            (p[0] - e[0]).abs() < 0.002 && (p[1] - e[1]).abs() < 0.002,
            "{p:?} vs {e:?}"
        );
    }
    match &events[4] {
        Canon::Arc(Arc { center, ccw, .. }) => {
            assert!(*ccw);
            assert!((center.x - 41.716).abs() < 0.002 && (center.y - 30.0).abs() < 0.002);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn kt_polar_bolt_circle_e2_and_pole_change_e4() {
    let text = "G17 G54 G90 G16\nG00 X100 Y30\nY150\nY270\nG15\n";
    let (events, diags) = run_text(text, Dialect::Kt);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [86.603, 50.0, 0.0],
            [-86.603, 50.0, 0.0],
            [0.0, -100.0, 0.0]
        ]
    );
    let (events, _) = run_text("G90 G17 G16\nG00 X50 Y30\n", Dialect::Kt);
    assert_eq!(ends(&events), [[43.301, 25.0, 0.0]]);
    // Incremental angle (E3): +120° twice from 30°.
    let (events, _) = run_text("G17 G90 G16\nG00 X100 Y30\nG91 Y120\nY120\n", Dialect::Kt);
    let pts = ends(&events);
    assert!(
        (pts[2][0] - 0.0).abs() < 0.001 && (pts[2][1] + 100.0).abs() < 0.001,
        "{pts:?}"
    );
}

#[test]
fn g65_passes_arguments_as_local_variables() {
    let text = "O0001\nG65 P9001 A10. B2.\nG00 X#1\nM30\nO9001\nG00 X[#1*#2] Y#2\n#1=99\nM99\n";
    let (events, diags) = run_text(text, Dialect::Fanuc);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    // Locals are per call level: the caller's #1 is still vacant afterwards, so its `X#1`
    // is left out and the block does not move.
    assert_eq!(ends(&events), [[20.0, 2.0, 0.0]]);
}

#[test]
fn a_self_calling_subprogram_stops_at_the_nesting_limit() {
    let (_, diags) = run_text("M98 P10\nM30\nO0010\nM98 P10\nM99\n", Dialect::Fanuc);
    assert_eq!(errors(&diags), ["E-NESTING"]);
}

#[test]
fn an_endless_while_loop_stops_at_the_limit() {
    let mut setup = Setup::default();
    setup.machine.max_blocks = 1000;
    let (_, diags) = run_with("WHILE [1 EQ 1] DO1\n#1=#1+1\nEND1\n", Dialect::Fanuc, setup);
    assert_eq!(errors(&diags), ["E-RUNAWAY"]);
}

#[test]
fn missing_subprogram_and_label_are_reported() {
    let (_, diags) = run_text("M98 P1234\n", Dialect::Fanuc);
    assert_eq!(errors(&diags), ["E-SUBPROGRAM"]);
    let (_, diags) = run_text("GOTO 50\n", Dialect::Fanuc);
    assert_eq!(errors(&diags), ["E-MACRO-GOTO"]);
}

#[test]
fn macro_alarm_stops_the_run() {
    let (events, diags) = run_text("#3000=12\nG00 X1\n", Dialect::Fanuc);
    assert_eq!(errors(&diags), ["E-MACRO-ALARM"]);
    assert!(events.is_empty());
}

#[test]
fn linuxcnc_subroutines_loops_and_conditions() {
    let text = "o100 sub\nG01 X#1 Y#2 F100\no100 endsub\n#<n> = 0\no101 while [#<n> LT 2]\n#<n> = [#<n> + 1]\no100 call [#<n>] [10]\no101 endwhile\no102 if [#<n> EQ 2]\nG00 Z5\no102 else\nG00 Z-5\no102 endif\no103 repeat [2]\nG91 G00 X1\no103 endrepeat\nM2\n";
    let (events, diags) = run_text(text, Dialect::LinuxCnc);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [1.0, 10.0, 0.0],
            [2.0, 10.0, 0.0],
            [2.0, 10.0, 5.0],
            [3.0, 10.0, 5.0],
            [4.0, 10.0, 5.0]
        ]
    );
}

#[test]
fn g52_g92_and_g10_move_the_work_frame() {
    let text =
        "G90 G54 G00 X0 Y0\nG52 X10 Y5\nX0 Y0\nG52 X0 Y0\nG10 L2 P1 X100\nX0\nG92 X0 Y0\nX1 Y1\n";
    let (events, diags) = run_text(text, Dialect::Fanuc);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [0.0, 0.0, 0.0],
            [10.0, 5.0, 0.0],
            // Cancelling G52 does not move: only X is programmed, Y stays at 5.
            [100.0, 5.0, 0.0],
            [101.0, 6.0, 0.0]
        ]
    );
}

#[test]
fn g53_is_a_one_shot_move_in_machine_coordinates() {
    let setup = Setup::from_toml(
        "[work_offsets]\nG54 = [100.0, 0.0, 0.0]\n[machine]\ncalculator_input = true\n",
    )
    .unwrap();
    let (events, _) = run_with("G90 G00 X0\nG53 X5\nX1\n", Dialect::Fanuc, setup);
    assert_eq!(
        ends(&events),
        [[100.0, 0.0, 0.0], [5.0, 0.0, 0.0], [101.0, 0.0, 0.0]]
    );
}

#[test]
fn g28_goes_through_the_intermediate_point_and_g29_comes_back() {
    // E32: G90 G28 X20 Y30; M06; G29 X40 Y0 (reference point at the machine origin here).
    let setup = Setup::from_toml(
        "[machine]\ncalculator_input = true\nreference_points = [[-10.0, -20.0, 0.0]]\n",
    )
    .unwrap();
    let (events, diags) = run_with(
        "G90 G00 X5 Y5\nG28 X20 Y30\nM06\nG29 X40 Y0\n",
        Dialect::Syntec,
        setup,
    );
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(
        ends(&events),
        [
            [5.0, 5.0, 0.0],
            [20.0, 30.0, 0.0],
            [-10.0, -20.0, 0.0],
            [20.0, 30.0, 0.0],
            [40.0, 0.0, 0.0]
        ]
    );
}

#[test]
fn mirror_reverses_arcs_and_scaling_scales() {
    let (events, _) = run_text(
        "G90 G00 X10 Y0\nG51.1 X0\nG03 X0 Y10 I-10 J0 F100\n",
        Dialect::Syntec,
    );
    match &events[1] {
        Canon::Arc(Arc { to, ccw, .. }) => {
            assert!(!ccw, "a mirrored arc runs the other way");
            assert!(to.abs_diff_eq(DVec3::new(0.0, 10.0, 0.0), 1e-9));
        }
        other => panic!("{other:?}"),
    }
    let (events, _) = run_text("G51 X0 Y0 P2.\nG00 X10 Y5\n", Dialect::Syntec);
    assert_eq!(ends(&events), [[20.0, 10.0, 0.0]]);
}

#[test]
fn lnc_g168_rotates_by_a_measured_angle() {
    let setup =
        Setup::from_toml("[machine]\ncalculator_input = true\nmeasured_angles = [90.0, 45.0]\n")
            .unwrap();
    let (events, diags) = run_with("G168 X0 Y0 Q1\nG00 X10 Y0\n", Dialect::Lnc, setup);
    assert!(errors(&diags).is_empty(), "{diags:?}");
    assert_eq!(ends(&events), [[0.0, 10.0, 0.0]]);
    let (_, diags) = run_text("G168 Q3\nG00 X1\n", Dialect::Lnc);
    assert_eq!(errors(&diags), ["E-MEASUREMENT"]);
}

#[test]
fn a_program_number_defined_twice_is_an_error_naming_both_lines() {
    let (_, diags) = run_text(
        "O1000\nM98 P2000\nM30\nO2000\nG0 X1.\nM99\nO2000\nG0 X2.\nM99\n",
        Dialect::Fanuc,
    );
    let twice: Vec<&Diagnostic> = diags
        .iter()
        .filter(|d| d.code == "E-PROGRAM-TWICE")
        .collect();
    assert_eq!(twice.len(), 1, "{diags:?}");
    assert!(
        twice[0].message.contains("O2000") && twice[0].message.contains("line 4"),
        "{}",
        twice[0].message
    );
    let (_, diags) = run_text("O1000\nG0 X1.\nM30\nO2000\nM99\n", Dialect::Fanuc);
    assert!(
        diags.iter().all(|d| d.code != "E-PROGRAM-TWICE"),
        "{diags:?}"
    );
}
