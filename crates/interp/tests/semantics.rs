//! Interpreter behaviour beyond the golden files: checks, limits and resumable stepping.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Arc, Canon, CanonRecorder, Interpreter, Setup, Status, run};
use swarf_syntax::{Dialect, parse};

/// Parses and runs `text` with calculator-type input (integers are millimetres, so these tests
/// are about semantics, not the decimal-point rule); returns the parse and run diagnostics.
fn run_text(text: &str, dialect: Dialect) -> (CanonRecorder, Vec<swarf_syntax::Diagnostic>) {
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    run_with(text, dialect, setup)
}

fn run_with(
    text: &str,
    dialect: Dialect,
    setup: Setup,
) -> (CanonRecorder, Vec<swarf_syntax::Diagnostic>) {
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, setup, &mut rec));
    (rec, diags)
}

fn first_x(rec: &CanonRecorder) -> f64 {
    match &rec.events[0].1 {
        Canon::Rapid { to } | Canon::Feed { to, .. } => to.x,
        other => panic!("{other:?}"),
    }
}

fn codes(diags: &[swarf_syntax::Diagnostic]) -> Vec<&'static str> {
    diags.iter().map(|d| d.code).collect()
}

#[test]
fn two_codes_of_one_group_last_wins_in_the_fanuc_family_and_alarm_in_linuxcnc() {
    let (rec, diags) = run_text("G00 G01 X5 F100\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["W-MODAL-LAST"]);
    assert!(matches!(rec.events[0].1, Canon::Feed { .. }));
    let (rec, diags) = run_text("G00 G01 X5 F100\n", Dialect::LinuxCnc);
    assert_eq!(codes(&diags), ["E-MODAL-CONFLICT"]);
    assert!(rec.events.is_empty());
}

#[test]
fn numbers_without_a_point_follow_the_decimal_point_rule() {
    // Fanuc, Syntec, KT, LNC: least input increment (0.001 mm), with a note once per run.
    for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::Kt, Dialect::Lnc] {
        let (rec, diags) = run_with("G00 X5500\nG00 X10\n", dialect, Setup::default());
        assert!((first_x(&rec) - 5.5).abs() < 1e-12, "{dialect}");
        assert_eq!(codes(&diags), ["N-LEAST-INCREMENT"], "{dialect}");
    }
    // GSK's examples and LinuxCNC read them as millimetres.
    for dialect in [Dialect::Gsk, Dialect::LinuxCnc] {
        let (rec, diags) = run_with("G00 X55\n", dialect, Setup::default());
        assert_eq!(first_x(&rec), 55.0, "{dialect}");
        assert!(diags.is_empty(), "{dialect}: {diags:?}");
    }
    // A decimal point always means millimetres; calculator-type input is a setting.
    let (rec, _) = run_with("G00 X55.\n", Dialect::Fanuc, Setup::default());
    assert_eq!(first_x(&rec), 55.0);
    let (rec, _) = run_text("G00 X55\n", Dialect::Fanuc);
    assert_eq!(first_x(&rec), 55.0);
    let setup = Setup::from_toml("[machine]\ncalculator_input = true\n").unwrap();
    let (rec, _) = run_with("G00 X55\n", Dialect::Syntec, setup);
    assert_eq!(first_x(&rec), 55.0);
    // Inch: the least increment is 0.0001 inch.
    let (rec, _) = run_with("G20 G00 X10000\n", Dialect::Fanuc, Setup::default());
    assert!((first_x(&rec) - 25.4).abs() < 1e-9);
}

#[test]
fn unsupported_codes_say_so() {
    // LinuxCNC's G76 is the lathe threading cycle.
    let (rec, diags) = run_text(
        "G76 P1.25 Z-10 I-1 J0.5 K1\nG01 X1 F100\n",
        Dialect::LinuxCnc,
    );
    assert_eq!(codes(&diags)[0], "W-NOT-INTERPRETED");
    assert_eq!(rec.events.len(), 1);
}

#[test]
fn unknown_code_names_the_dialect() {
    let (_, diags) = run_text("G321 X1\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-UNKNOWN-CODE"]);
    assert!(diags[0].message.contains("Fanuc"));
    // A code another dialect has names that dialect.
    let (rec, diags) = run_text("G134 X0 Y0 I10 J0 K6\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-CODE-DIALECT"]);
    assert!(diags[0].message.contains("Syntec"), "{}", diags[0].message);
    assert!(diags[0].message.contains("LNC"), "{}", diags[0].message);
    assert!(rec.events.is_empty());
}

#[test]
fn feed_without_f_is_an_error() {
    let (rec, diags) = run_text("G01 X10\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-NO-FEED"]);
    assert_eq!(rec.events.len(), 1);
}

#[test]
fn syntec_reads_g70_as_inch() {
    let (rec, diags) = run_text("G70 G00 X1\n", Dialect::Syntec);
    assert!(diags.is_empty(), "{diags:?}");
    assert_eq!(
        rec.events[0].1,
        Canon::Rapid {
            to: DVec3::new(25.4, 0.0, 0.0)
        }
    );
    let (_, diags) = run_text("G70 G00 X1\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-CODE-DIALECT"]);
    assert!(diags[0].message.contains("Syntec"), "{}", diags[0].message);
    let (_, diags) = run_text("G20 G00 X1\n", Dialect::Syntec);
    assert_eq!(codes(&diags), ["E-CODE-DIALECT"]);
    assert!(diags[0].message.contains("G70/G71"), "{}", diags[0].message);
}

#[test]
fn dwell_units_follow_the_dialect() {
    let secs = |text: &str, d| match run_text(text, d).0.events[0].1 {
        Canon::Dwell { secs } => secs,
        ref other => panic!("{other:?}"),
    };
    assert_eq!(secs("G04 P2500\n", Dialect::Fanuc), 2.5);
    assert_eq!(secs("G04 P2.5\n", Dialect::LinuxCnc), 2.5);
    assert_eq!(secs("G04 X2500\n", Dialect::Syntec), 2.5);
    assert_eq!(secs("G04 X2.5\n", Dialect::Syntec), 2.5);
}

#[test]
fn stepping_in_small_budgets_gives_the_same_stream() {
    let text = "G0 X1\nG1 X2 F100\nG91 X1\nX1\nX1\nM30\n";
    let program = parse(text, Dialect::Fanuc);
    let (whole, _) = run_text(text, Dialect::Fanuc);
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    let mut interp = Interpreter::new(setup, Dialect::Fanuc);
    let mut rec = CanonRecorder::default();
    let mut steps = 0;
    while interp.step(&program, &mut rec, 1) == Status::Running {
        steps += 1;
        assert!(steps < 100);
    }
    assert_eq!(rec, whole);
    assert_eq!(interp.block_state().machine, DVec3::new(5.0, 0.0, 0.0));
}

#[test]
fn block_limit_stops_a_run_with_a_diagnostic() {
    let program = parse(&"G91 G0 X1.\n".repeat(50), Dialect::Fanuc);
    let mut setup = Setup::default();
    setup.machine.max_blocks = 10;
    let mut rec = CanonRecorder::default();
    let diags = run(&program, setup, &mut rec);
    assert_eq!(rec.events.len(), 10);
    assert_eq!(codes(&diags), ["E-RUNAWAY"]);
}

#[test]
fn blocks_with_parse_errors_are_not_run() {
    let (rec, diags) = run_text("G0 X$ \nG0 X3\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-WORD-VALUE", "E-SYNTAX-CHAR"]);
    assert_eq!(rec.events.len(), 1);
}

#[test]
fn arc_end_off_the_circle_is_an_alarm_that_names_syntec_cor_006() {
    let (rec, diags) = run_text("G0 X10\nG02 X0 Y5 I-10 F100\n", Dialect::Syntec);
    assert_eq!(codes(&diags), ["E-ARC-RADIUS"]);
    assert!(diags[0].message.contains("COR-006"), "{}", diags[0].message);
    assert_eq!(rec.events.len(), 1);
}

#[test]
fn arc_radius_too_small_or_full_circle_with_r_is_an_error() {
    let (_, diags) = run_text("G02 X30 Y0 R10 F100\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-ARC-RADIUS"]);
    let (_, diags) = run_text("G0 X5\nG02 X5 Y0 R10 F100\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-ARC-CENTER"]);
    let (_, diags) = run_text("G02 X5 Y5 F100\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["E-ARC-CENTER"]);
    // Syntec documents an arc with neither R nor I/J/K as a straight line.
    let (_, diags) = run_text("G02 X5 Y5 F100\n", Dialect::Syntec);
    assert_eq!(codes(&diags), ["W-ARC-AS-LINE"]);
}

#[test]
fn arc_words_outside_arcs_are_reported() {
    let (_, diags) = run_text("G01 X5 I3 F100\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["W-WORD-UNUSED"]);
    let (_, diags) = run_text("G01 X5 F100\nX6 I3\n", Dialect::Fanuc);
    assert_eq!(codes(&diags), ["W-WORD-IGNORED"]);
}

#[test]
fn inch_arcs_convert_centre_offsets() {
    let (rec, _) = run_text("G20 G0 X1\nG03 X-1 I-1 F10\n", Dialect::Fanuc);
    match &rec.events[1].1 {
        Canon::Arc(Arc {
            to, center, ccw, ..
        }) => {
            assert!(to.abs_diff_eq(DVec3::new(-25.4, 0.0, 0.0), 1e-9));
            assert!(center.abs_diff_eq(DVec3::ZERO, 1e-9));
            assert!(*ccw);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn a_word_given_twice_stops_the_block() {
    for text in ["G0 X1 X2\n", "G1 X1 F100 F200\n", "G2 X1 I1 I2 F100\n"] {
        let (rec, diags) = run_text(text, Dialect::Fanuc);
        assert_eq!(codes(&diags), ["E-WORD-TWICE"], "{text}");
        assert!(rec.events.is_empty(), "{text}");
    }
}

#[test]
fn linuxcnc_p_gives_the_turns_of_an_arc_and_counts_stay_in_range() {
    let (rec, diags) = run_text("G17 G2 X0 Y0 I1 P3 F100\n", Dialect::LinuxCnc);
    assert!(diags.is_empty(), "{diags:?}");
    assert!(
        rec.events
            .iter()
            .any(|(_, e)| matches!(e, Canon::Arc(Arc { turns: 2, .. })))
    );
    let (_, diags) = run_text("G17 G2 X0 Y0 I1 P0 F100\n", Dialect::LinuxCnc);
    assert_eq!(codes(&diags), ["E-NUMBER-RANGE"]);
}

#[test]
fn a_move_past_the_machine_travel_is_an_overtravel_alarm() {
    let setup =
        Setup::from_toml("[machine]\ntravel_mm = [[-500.0, -300.0, -400.0], [0.0, 0.0, 0.0]]\n")
            .unwrap();
    let (_, diags) = run_with(
        "G0 X-100. Y-100.\nG1 Z-50. F100.\n",
        Dialect::Fanuc,
        setup.clone(),
    );
    assert!(diags.is_empty(), "{diags:?}");
    let (rec, diags) = run_with(
        "G0 X-100. Y-100.\nG1 X-600. F100.\n",
        Dialect::Fanuc,
        setup.clone(),
    );
    assert_eq!(codes(&diags), ["E-OVERTRAVEL"]);
    // The move is still drawn where the program sends it.
    assert!(
        rec.events
            .iter()
            .any(|(_, e)| e.end_point().is_some_and(|p| p.x == -600.0))
    );
    // An arc that bulges past the travel is caught too.
    let (_, diags) = run_with(
        "G0 X-10. Y-100.\nG3 X-10. Y-60. R20. F100.\n",
        Dialect::Fanuc,
        setup.clone(),
    );
    assert_eq!(codes(&diags), ["E-OVERTRAVEL"]);
    // A half turn of radius 50 whose widest point passes X0 by 5 µm between the chords of 64
    // a turn, and the same arc 10 µm to the left, clear of it.
    for (from, to, want) in [(-58.677, -41.313, 1), (-58.687, -41.323, 0)] {
        let text = format!("G0 X{from} Y-149.24\nG3 X{to} Y-50.76 I8.682 J49.24 F100.\n");
        let (_, diags) = run_with(&text, Dialect::Fanuc, setup.clone());
        assert_eq!(codes(&diags), ["E-OVERTRAVEL"][..want], "{text}");
    }
}
