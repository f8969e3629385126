//! Canned drilling cycles: hand-computed canonical motions per dialect.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Canon, CanonRecorder, Setup, ShiftDirection, run};
use swarf_syntax::{Dialect, parse};

/// Runs `text` (calculator input: integers are mm) and returns the events as short strings:
/// `R x y z` rapid, `F x y z` feed, `D s` dwell, `S dir` spindle, plus the diagnostic codes.
fn events(text: &str, dialect: Dialect) -> (Vec<String>, Vec<&'static str>) {
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, setup, &mut rec));
    let f = |v: f64| {
        let r = (v * 1e6).round() / 1e6;
        format!("{}", if r == 0.0 { 0.0 } else { r })
    };
    let out = rec
        .events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Rapid { to } => Some(format!("R {} {} {}", f(to.x), f(to.y), f(to.z))),
            Canon::Feed { to, .. } => Some(format!("F {} {} {}", f(to.x), f(to.y), f(to.z))),
            Canon::Dwell { secs } => Some(format!("D {}", f(*secs))),
            Canon::Spindle { clockwise, .. } => Some(format!("S {clockwise:?}")),
            Canon::Orient => Some("O".to_string()),
            _ => None,
        })
        .collect();
    (out, diags.iter().map(|d| d.code).collect())
}

fn ev(text: &str, dialect: Dialect) -> Vec<String> {
    let (out, diags) = events(text, dialect);
    assert!(
        diags
            .iter()
            .all(|c| !c.starts_with("E-") && *c != "W-NOT-INTERPRETED"),
        "{diags:?}"
    );
    out
}

fn s(list: &[&str]) -> Vec<String> {
    list.iter().map(|x| (*x).to_string()).collect()
}

#[test]
fn g81_g98_returns_to_the_initial_level_and_g99_to_r() {
    let out = ev(
        "G0 X0 Y0 Z50\nG98 G81 X10 Y20 R5 Z-10 F100\nX30\nG80\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 50",
            "R 10 20 50",
            "R 10 20 5",
            "F 10 20 -10",
            "R 10 20 50",
            "R 30 20 50",
            "R 30 20 5",
            "F 30 20 -10",
            "R 30 20 50",
        ])
    );
    let out = ev(
        "G0 X0 Y0 Z50\nG99 G81 X10 Y20 R5 Z-10 F100\nX30\nG98 X40\nG80\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 50",
            "R 10 20 50",
            "R 10 20 5",
            "F 10 20 -10",
            "R 10 20 5",
            // G99 keeps the initial level: the next hole starts at R.
            "R 30 20 5",
            "F 30 20 -10",
            "R 30 20 5",
            // G98 now: back to the initial level captured when the cycle started.
            "R 40 20 5",
            "F 40 20 -10",
            "R 40 20 50",
        ])
    );
}

#[test]
fn g82_dwells_at_the_bottom_and_g85_g89_feed_out_to_r() {
    let out = ev("G0 Z20\nG99 G82 X5 R2 Z-4 P1000 F60\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&[
            "R 0 0 20", "R 5 0 20", "R 5 0 2", "F 5 0 -4", "D 1", "R 5 0 2"
        ])
    );
    let out = ev("G0 Z20\nG98 G85 X5 R2 Z-4 F60\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&[
            "R 0 0 20", "R 5 0 20", "R 5 0 2", "F 5 0 -4", "F 5 0 2", "R 5 0 20"
        ])
    );
    let out = ev("G0 Z20\nG99 G89 X5 R2 Z-4 P500 F60\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&[
            "R 0 0 20", "R 5 0 20", "R 5 0 2", "F 5 0 -4", "D 0.5", "F 5 0 2"
        ])
    );
}

#[test]
fn g83_returns_to_r_between_pecks_and_g73_retracts_by_d() {
    // Q3 from R2 to Z-6: pecks to -1, -4, then the bottom; d = 1 mm (the default).
    let out = ev("G0 Z10\nG98 G83 X1 R2 Z-6 Q3 F50\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&[
            "R 0 0 10", "R 1 0 10", "R 1 0 2", "F 1 0 -1", "R 1 0 2", "R 1 0 0", "F 1 0 -4",
            "R 1 0 2", "R 1 0 -3", "F 1 0 -6", "R 1 0 10",
        ])
    );
    let out = ev("G0 Z10\nG99 G73 X1 R2 Z-6 Q3 F50\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&[
            "R 0 0 10", "R 1 0 10", "R 1 0 2", "F 1 0 -1", "R 1 0 0", "F 1 0 -4", "R 1 0 -3",
            "F 1 0 -6", "R 1 0 2",
        ])
    );
}

#[test]
fn g91_r_from_the_initial_level_z_from_r_and_k_repeats_by_the_increments() {
    // Initial 10; R = 10 - 8 = 2; bottom = 2 - 5 = -3; three holes 10 apart in X.
    let out = ev(
        "G0 X0 Y0 Z10\nG91 G99 G81 X10 R-8 Z-5 K3 F100\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 10",
            "R 10 0 10",
            "R 10 0 2",
            "F 10 0 -3",
            "R 10 0 2",
            "R 20 0 2",
            "F 20 0 -3",
            "R 20 0 2",
            "R 30 0 2",
            "F 30 0 -3",
            "R 30 0 2",
        ])
    );
}

#[test]
fn k0_stores_the_data_only_and_a_block_without_axis_words_does_not_drill() {
    let out = ev(
        "G0 Z10\nG98 G81 X5 R2 Z-3 K0 F100\nR1\nX6\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&["R 0 0 10", "R 6 0 10", "R 6 0 1", "F 6 0 -3", "R 6 0 10"])
    );
}

#[test]
fn the_drilling_axis_follows_the_plane() {
    // G18: the drilling axis is Y; X and Z place the hole.
    let out = ev(
        "G0 X0 Y10 Z0\nG18 G98 G81 X3 Z4 R2 Y-5 F100\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&["R 0 10 0", "R 3 10 4", "R 3 2 4", "F 3 -5 4", "R 3 10 4"])
    );
    // G19: the drilling axis is X.
    let out = ev("G0 X10\nG19 G99 G81 Y3 Z4 R2 X-5 F100\n", Dialect::Fanuc);
    assert_eq!(
        out,
        s(&["R 10 0 0", "R 10 3 4", "R 2 3 4", "F -5 3 4", "R 2 3 4"])
    );
}

#[test]
fn g80_and_group_01_codes_cancel_the_cycle() {
    let out = ev("G0 Z10\nG81 X1 R2 Z-1 F100\nG80 X5\n", Dialect::Fanuc);
    assert_eq!(out.last().unwrap(), "R 5 0 10");
    let out = ev("G0 Z10\nG81 X1 R2 Z-1 F100\nG01 X5\n", Dialect::Fanuc);
    assert_eq!(out.last().unwrap(), "F 5 0 10");
    // After the cancel the data are gone: a new cycle without R and Z cannot drill.
    let (_, diags) = events("G0 Z10\nG81 X1 R2 Z-1 F100\nG80\nG81 X3\n", Dialect::Fanuc);
    assert!(diags.contains(&"E-WORD-MISSING"), "{diags:?}");
}

#[test]
fn linuxcnc_moves_up_to_r_first_and_l_repeats() {
    // Current Z 2 below R 3: up to R at the current XY first (rs274ngc).
    let out = ev(
        "G0 X0 Y0 Z2\nG98 G81 X1 Y2 Z0.5 R3 F10\n",
        Dialect::LinuxCnc,
    );
    assert_eq!(
        out,
        s(&["R 0 0 2", "R 0 0 3", "R 1 2 3", "F 1 2 0.5", "R 1 2 3"])
    );
    // G91: R from the current level, Z from R, L repeats by the increments.
    let out = ev(
        "G0 X0 Y0 Z5\nG91 G99 G81 X2 R-3 Z-4 L2 F10\n",
        Dialect::LinuxCnc,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 5", "R 2 0 5", "R 2 0 2", "F 2 0 -2", "R 2 0 2", "R 4 0 2", "F 4 0 -2",
            "R 4 0 2",
        ])
    );
}

#[test]
fn kt_l_spaces_holes_along_the_line_to_the_end_point() {
    // From X0 to X30 with L3: holes at 10, 20, 30; the start point is not drilled.
    let out = ev(
        "G0 X0 Y0 Z10\nG90 G99 G81 X30 R2 Z-1 L3 F100\n",
        Dialect::Kt,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 10",
            "R 10 0 10",
            "R 10 0 2",
            "F 10 0 -1",
            "R 10 0 2",
            "R 20 0 2",
            "F 20 0 -1",
            "R 20 0 2",
            "R 30 0 2",
            "F 30 0 -1",
            "R 30 0 2",
        ])
    );
}

#[test]
fn holes_go_through_the_work_offset_and_rotation() {
    let out = ev(
        "G0 X0 Y0 Z10\nG52 X100\nG68 X0 Y0 R90\nG98 G81 X10 R2 Z-1 F100\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        &out[out.len() - 4..],
        s(&["R 100 10 10", "R 100 10 2", "F 100 10 -1", "R 100 10 10"])
    );
}

const E53: &str = "N001 F1000. S500;\nN002 M03;\nN003 G90;\nN004 G00 X0. Y0. Z10.;\nN005 G17;\nN006 G90 G99;\nN007 G73 X5. Y5. Z-10. R-5. Q2.;\nN008 X15.;\nN009 Y15.;\nN010 G98 X5.;\nN011 X10. Y10. Z-20.;\nN012 G80;\nN013 M05;\nN014 M30;\n";

#[test]
fn syntec_e53_g73_pecks_at_the_manual_holes_and_returns_as_stated() {
    let out = ev(E53, Dialect::Syntec);
    // Hole 1: pecks end at Z-7, -9, -10 with a rapid retract of d = 1 mm (Pr4002) between.
    let hole1 = s(&[
        "R 5 5 10",
        "R 5 5 -5",
        "F 5 5 -7",
        "R 5 5 -6",
        "F 5 5 -9",
        "R 5 5 -8",
        "F 5 5 -10",
        "R 5 5 -5",
    ]);
    let at = out.iter().position(|e| e == "R 5 5 10").unwrap();
    assert_eq!(out[at..at + hole1.len()], hole1[..]);
    // The bottom of each hole: holes 1–4 at Z-10, hole 5 at the new Z-20.
    let bottoms: Vec<&String> = out
        .iter()
        .filter(|e| e.starts_with('F') && (e.ends_with(" -10") || e.ends_with(" -20")))
        .collect();
    assert_eq!(
        bottoms,
        [
            "F 5 5 -10",
            "F 15 5 -10",
            "F 15 15 -10",
            "F 5 15 -10",
            "F 10 10 -20"
        ]
    );
    // Holes 1–3 return to R (-5); from hole 4 (G98) to the initial point Z10, which stayed.
    assert!(out.contains(&"R 15 15 -5".to_string()));
    assert!(out.contains(&"R 5 15 10".to_string()));
    let moves: Vec<&String> = out.iter().filter(|e| !e.starts_with('S')).collect();
    assert_eq!(moves.last().unwrap().as_str(), "R 10 10 10");
    // Hole 5 starts from the initial point.
    assert!(out.contains(&"R 10 10 10".to_string()));
}

#[test]
fn syntec_e58_g83_returns_to_r_between_pecks() {
    let text = "N001 F1000. S500;\nN002 M03;\nN003 G90;\nN004 G00 X0. Y0. Z10.;\nN005 G17;\nN006 G90 G99;\nN007 G83 X5. Y5. Z-10. R-5. Q3.;\nN008 X15.;\nN009 Y15.;\nN010 G98 X5.;\nN011 G80;\nN012 M05;\nN013 M30;\n";
    let out = ev(text, Dialect::Syntec);
    // Pecks to Z-8 and then Z-10; between them rapid to R (-5) and down to d above -8.
    let hole1 = s(&[
        "R 5 5 10",
        "R 5 5 -5",
        "F 5 5 -8",
        "R 5 5 -5",
        "R 5 5 -7",
        "F 5 5 -10",
        "R 5 5 -5",
        "R 15 5 -5",
    ]);
    let at = out.iter().position(|e| e == "R 5 5 10").unwrap();
    assert_eq!(out[at..at + hole1.len()], hole1[..]);
    let moves: Vec<&String> = out.iter().filter(|e| !e.starts_with('S')).collect();
    assert_eq!(moves.last().unwrap().as_str(), "R 5 15 10");
}

#[test]
fn g84_taps_in_reverses_at_the_bottom_and_restarts_forward_at_r() {
    let out = ev(
        "G0 Z10 S500 M03\nG98 G84 X1 R2 Z-5 P1000 F1\n",
        Dialect::Fanuc,
    );
    assert_eq!(
        out,
        s(&[
            "R 0 0 10",
            "S Some(true)",
            "R 1 0 10",
            "R 1 0 2",
            "F 1 0 -5",
            "S None",
            "D 1",
            "S Some(false)",
            "F 1 0 2",
            "S None",
            "D 1",
            "S Some(true)",
            "R 1 0 10",
        ])
    );
    // G74: the other way round.
    let out = ev("G0 Z10 S500 M04\nG99 G74 X1 R2 Z-5 F1\n", Dialect::Fanuc);
    assert_eq!(
        out[4..],
        s(&[
            "F 1 0 -5",
            "S None",
            "S Some(true)",
            "F 1 0 2",
            "S None",
            "S Some(false)"
        ])[..]
    );
}

/// The feed rates of a KT program's cutting moves (calculator input: integers are mm).
fn kt_feeds(text: &str) -> Vec<f64> {
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    let mut rec = CanonRecorder::default();
    run(&parse(text, Dialect::Kt), setup, &mut rec);
    rec.events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Feed {
                feed_mm_per_min, ..
            } => Some(*feed_mm_per_min),
            _ => None,
        })
        .collect()
}

#[test]
fn kt_tapping_f_is_the_pitch() {
    let feeds = kt_feeds("G0 Z10 S600 M03\nG99 G84 X1 R2 Z-5 F1.5\n");
    assert_eq!(feeds, [900.0, 900.0]);
}

#[test]
fn g86_stops_the_spindle_and_g88_pauses_for_the_manual_return() {
    let out = ev("G0 Z10 S500 M03\nG99 G86 X1 R2 Z-5 F100\n", Dialect::Fanuc);
    assert_eq!(
        out[4..],
        s(&["F 1 0 -5", "S None", "R 1 0 2", "S Some(true)"])[..]
    );
    let program = parse(
        "G0 Z10 S500 M03\nG98 G88 X1 R2 Z-5 P500 F100\n",
        Dialect::Fanuc,
    );
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    let mut rec = CanonRecorder::default();
    run(&program, setup, &mut rec);
    let kinds: Vec<&Canon> = rec
        .events
        .iter()
        .map(|(_, e)| e)
        .filter(|e| !matches!(e, Canon::Hole { .. }))
        .skip(4)
        .collect();
    assert!(matches!(kinds[0], Canon::Feed { .. }));
    assert!(matches!(kinds[1], Canon::Dwell { .. }));
    assert!(matches!(
        kinds[2],
        Canon::Spindle {
            clockwise: None,
            ..
        }
    ));
    assert!(matches!(kinds[3], Canon::Pause { optional: false }));
    assert!(matches!(kinds[4], Canon::Rapid { to } if to.z == 10.0));
}

/// A hole event: cycle, index, top, bottom.
type HoleEvent = (u32, u32, DVec3, DVec3);

/// The hole events of a run, plus the diagnostic codes.
fn holes(text: &str, dialect: Dialect) -> (Vec<HoleEvent>, Vec<&'static str>) {
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, Setup::default(), &mut rec));
    let out = rec
        .events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Hole {
                cycle,
                index,
                top,
                bottom,
            } => Some((*cycle, *index, *top, *bottom)),
            _ => None,
        })
        .collect();
    (out, diags.iter().map(|d| d.code).collect())
}

fn close(a: DVec3, b: DVec3) -> bool {
    a.distance(b) < 1e-6
}

#[test]
fn syntec_e55_g76_shifts_away_from_the_wall_at_the_oriented_stop() {
    let text = "F1000. S500;\nM03;\nG90;\nG00 X0. Y0. Z10.;\nG17;\nG90 G99;\n\
                G76 X5. Y5. Z-10. R-5. Q2. P5.;\nG98 X15.;\nG80;\n";
    let out = ev(text, Dialect::Syntec);
    assert_eq!(
        out,
        s(&[
            "S Some(true)",
            "R 0 0 10",
            "R 5 5 10",
            "R 5 5 -5",
            "F 5 5 -10",
            "D 5",
            "S None",
            "O",
            "R 7 5 -10",
            "R 7 5 -5",
            "R 5 5 -5",
            "S Some(true)",
            // Hole 2 under G98: back to the initial level, shifted.
            "R 15 5 -5",
            "F 15 5 -10",
            "D 5",
            "S None",
            "O",
            "R 17 5 -10",
            "R 17 5 10",
            "R 15 5 10",
            "S Some(true)",
        ])
    );
    // The shift direction comes from the setup (Syntec Pr4020).
    let mut setup = Setup::default();
    setup.machine.shift_direction = ShiftDirection::MinusY;
    let program = parse(text, Dialect::Syntec);
    let mut rec = CanonRecorder::default();
    run(&program, setup, &mut rec);
    assert!(rec.events.iter().any(|(_, e)| matches!(e,
        Canon::Rapid { to } if close(*to, DVec3::new(5.0, 3.0, -10.0)))));
}

#[test]
fn kt_g76_shifts_by_the_default_q_and_rejects_a_z_shift() {
    let out = ev(
        "G0 X0 Y0 Z10 S500 M03\nG99 G76 X5 R2 Z-5 F100\n",
        Dialect::Kt,
    );
    assert!(out.contains(&"R 5.1 0 -5".to_string()), "{out:?}");
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    setup.machine.shift_direction = ShiftDirection::PlusZ;
    let program = parse(
        "G0 X0 Y0 Z10 S500 M03\nG99 G76 X5 R2 Z-5 F100\n",
        Dialect::Kt,
    );
    let mut rec = CanonRecorder::default();
    let diags = run(&program, setup, &mut rec);
    assert!(
        diags.iter().any(|d| d.code == "E-SHIFT-DIRECTION"),
        "{diags:?}"
    );
}

#[test]
fn syntec_e62_g87_bores_upwards_from_r_and_returns_to_the_initial_level() {
    let text = "F1000. S500;\nG90;\nG00 X0. Y0. Z10.;\nG17;\nG90;\nM03;\n\
                G99 G87 X5. Y5. Z10. R-30. Q5. P4.;\nX15.;\nG80;\n";
    let out = ev(text, Dialect::Syntec);
    assert_eq!(
        out[..16],
        s(&[
            "R 0 0 10",
            "S Some(true)",
            "R 5 5 10",
            "S None",
            "O",
            "R 10 5 10",
            "R 10 5 -30",
            "R 5 5 -30",
            "S Some(true)",
            "F 5 5 10",
            "D 4",
            "S None",
            "O",
            "R 10 5 10",
            "R 10 5 10",
            "R 5 5 10",
        ])[..]
    );
    // G99 is ignored: the second hole starts from the initial level too.
    assert!(out[16..].starts_with(&s(&["S Some(true)", "R 15 5 10", "S None", "O"])));
    // Z below R is an alarm for G87.
    let (_, diags) = events(
        "G0 X0 Y0 Z10 S500 M03\nG87 X5 R-30 Z-40 Q1 F100\n",
        Dialect::Fanuc,
    );
    assert!(diags.contains(&"E-CYCLE-LEVELS"), "{diags:?}");
}

#[test]
fn linuxcnc_g87_enters_at_the_offset_and_bores_back_as_rs274_does() {
    let out = ev(
        "G21 G0 X0 Y0 Z5 M3 S1000\nG98 G87 X10 Y20 R2 Z-5 I3 J0 K-20 F100\n",
        Dialect::LinuxCnc,
    );
    let motions: Vec<&String> = out
        .iter()
        .filter(|e| e.starts_with('R') || e.starts_with('F') || *e == "O")
        .collect();
    assert_eq!(
        motions,
        [
            "R 0 0 5",
            "R 10 20 5",
            "R 10 20 2",
            "R 13 20 2",
            "O",
            "R 13 20 -5",
            "R 10 20 -5",
            "F 10 20 -20",
            "F 10 20 -5",
            "O",
            "R 13 20 -5",
            "R 13 20 5",
            "R 10 20 5",
        ]
    );
    let (_, diags) = events(
        "G21 G0 X0 Y0 Z5 M3 S1000\nG98 G87 X10 Y20 R2 Z-5 I3 F100\n",
        Dialect::LinuxCnc,
    );
    assert!(diags.contains(&"E-WORD-MISSING"), "{diags:?}");
}

#[test]
fn syntec_e56_f2_retracts_at_the_retract_feed_unless_normal_drilling() {
    let text = "F1000. S500;\nG90;\nG00 X0. Y0. Z10.;\nG17;\nG90 G99;\n\
                G81 X5. Y5. Z-10. R-5. F2=1000;\nX15.;\nG80;\n";
    let program = parse(text, Dialect::Syntec);
    let mut rec = CanonRecorder::default();
    run(&program, Setup::default(), &mut rec);
    let after_bottom: Vec<&Canon> = rec
        .events
        .iter()
        .map(|(_, e)| e)
        .skip_while(|e| !matches!(e, Canon::Feed { to, .. } if to.z == -10.0))
        .skip(1)
        .take(1)
        .collect();
    assert!(
        matches!(after_bottom[0], Canon::Feed { to, feed_mm_per_min } if to.z == -5.0 && *feed_mm_per_min == 1000.0),
        "{after_bottom:?}"
    );
    let mut setup = Setup::default();
    setup.machine.fast_drilling = false;
    let mut rec = CanonRecorder::default();
    let diags = run(&program, setup, &mut rec);
    assert!(diags.iter().any(|d| d.code == "N-F2-IGNORED"));
    assert!(
        rec.events
            .iter()
            .all(|(_, e)| !matches!(e, Canon::Feed { to, .. } if to.z == -5.0))
    );
}

#[test]
fn every_hole_is_tagged_with_its_cycle_number_and_levels() {
    let (h, diags) = holes(
        "G0 X0 Y0 Z50.\nG99 G81 X10. Y20. R5. Z-10. F100\nX30.\nG83 X40. Q3. Z-12.\nG80\n",
        Dialect::Fanuc,
    );
    assert!(
        diags
            .iter()
            .all(|c| !c.starts_with("E-") && !c.starts_with("W-")),
        "{diags:?}"
    );
    assert_eq!(h.len(), 3);
    assert_eq!(
        h.iter().map(|x| (x.0, x.1)).collect::<Vec<_>>(),
        [(810, 1), (810, 2), (830, 3)]
    );
    assert!(close(h[1].2, DVec3::new(30.0, 20.0, 5.0)));
    assert!(close(h[2].3, DVec3::new(40.0, 20.0, -12.0)));
}

fn hole_points(text: &str) -> Vec<(f64, f64)> {
    let (h, diags) = holes(text, Dialect::Syntec);
    assert!(diags.iter().all(|c| !c.starts_with("E-")), "{diags:?}");
    h.iter()
        .map(|x| ((x.2.x * 1e3).round() / 1e3, (x.2.y * 1e3).round() / 1e3))
        .collect()
}

#[test]
fn syntec_e70_g134_drills_a_bolt_circle_about_the_incremental_centre() {
    let p = hole_points(
        "G92 X500.0 Y100.0;\nG91 G81 Z-10.0 R5.0 K0 F200;\nG134 X200.0 Y100.0 I100.0 J20.0 K6;\nG80;\n",
    );
    // Centre (700, 200) in the G92 frame, (200, 100) on the machine: the manual's offsets 100·(cos θ, sin θ) for θ = 20°, 80° … 320°.
    let expected = [
        (93.969, 34.202),
        (17.365, 98.481),
        (-76.604, 64.279),
        (-93.969, -34.202),
        (-17.365, -98.481),
        (76.604, -64.279),
    ];
    assert_eq!(p.len(), 6);
    for (got, (dx, dy)) in p.iter().zip(expected) {
        assert!(
            (got.0 - (200.0 + dx)).abs() < 1e-3 && (got.1 - (100.0 + dy)).abs() < 1e-3,
            "{p:?}"
        );
    }
}

#[test]
fn syntec_e71_e72_e73_line_arc_and_grid_patterns() {
    let line = hole_points("G91;\nG81 Z-10.0 R5.0 K0 F100;\nG135 X200.0 Y100.0 I100.0 J30.0 K5;\n");
    assert_eq!(
        line,
        [
            (200.0, 100.0),
            (286.603, 150.0),
            (373.205, 200.0),
            (459.808, 250.0),
            (546.41, 300.0)
        ]
    );
    let arc =
        hole_points("G91;\nG81 Z-10.0 R5.0 K0 F100;\nG136 X300.0 Y100.0 I300.0 J10.0 P15000 K6;\n");
    let offsets = [
        (295.442, 52.094),
        (271.892, 126.785),
        (229.813, 192.836),
        (172.073, 245.746),
        (102.606, 281.908),
        (26.147, 298.858),
    ];
    assert_eq!(arc.len(), 6);
    for (got, (dx, dy)) in arc.iter().zip(offsets) {
        assert!(
            (got.0 - (300.0 + dx)).abs() < 2e-3 && (got.1 - (100.0 + dy)).abs() < 2e-3,
            "{arc:?}"
        );
    }
    let grid =
        hole_points("G91;\nG81 Z-10.0 R5.0 K0 F20;\nG137.1 X300.0 Y-100.0 I50.0 P10 J100.0 K8;\n");
    assert_eq!(grid.len(), 80);
    let mut sorted = grid.clone();
    sorted.sort_by(|a, b| a.partial_cmp(b).unwrap());
    sorted.dedup();
    assert_eq!(sorted.len(), 80);
    for (x, y) in &grid {
        let (i, j) = ((x - 300.0) / 50.0, (y + 100.0) / 100.0);
        assert!(
            i.fract() == 0.0
                && (0.0..10.0).contains(&i)
                && j.fract() == 0.0
                && (0.0..8.0).contains(&j)
        );
    }
    // Row after row, each the way back of the one before.
    assert_eq!(grid[9], (750.0, -100.0));
    assert_eq!(grid[10], (750.0, 0.0));
}

#[test]
fn a_pattern_without_a_stored_cycle_or_with_a_bad_count_is_an_alarm() {
    let (_, diags) = holes("G134 X0 Y0 I10. J0 K6;\n", Dialect::Syntec);
    assert!(diags.contains(&"E-PATTERN-NO-CYCLE"), "{diags:?}");
    let (_, diags) = holes(
        "G91 G81 Z-10. R5. K0 F100;\nG134 X0 Y0 I10. J0 K2.5;\n",
        Dialect::Syntec,
    );
    assert!(diags.contains(&"E-NUMBER-RANGE"), "{diags:?}");
    let (_, diags) = holes(
        "G91 G81 Z-10. R5. K0 F100;\nG137.1 X0 Y0 I1. P9999 J1. K9999;\n",
        Dialect::Syntec,
    );
    assert!(diags.contains(&"E-PATTERN-SIZE"), "{diags:?}");
}

#[test]
fn lnc_list_only_cycles_say_the_manual_does_not_document_them() {
    for code in ["G181", "G173", "G77", "G36"] {
        let (out, diags) = events(
            &format!("G0 X0 Y0 Z10\n{code} X5 Y5 Z-5 R2 F100\nG0 X1\n"),
            Dialect::Lnc,
        );
        assert!(diags.contains(&"W-NOT-DOCUMENTED"), "{code}: {diags:?}");
        // The block is not run; the next one is.
        assert_eq!(out, s(&["R 0 0 10", "R 1 0 10"]), "{code}");
    }
    // Syntec's F2= is read by G81, not reported as ignored.
    let (_, diags) = events(
        "G0 Z10.\nG99 G81 X5. Y5. Z-10. R-5. F100 F2=1000\nG80\n",
        Dialect::Syntec,
    );
    assert!(diags.is_empty(), "{diags:?}");
}

#[test]
fn gsk_e15_slanted_end_face_drilling_leans_by_e_and_pecks_back_to_r() {
    let text = "G98;\nM3 S1500;\nG0 X50 C0 Z0;\nG83.1 X100 Z-30 R-10 Q5000 P3000 F200 E30;\nC120;\nG80 M05;\n";
    let (out, diags) = events(text, Dialect::Gsk);
    assert!(diags.iter().all(|c| !c.starts_with("E-")), "{diags:?}");
    assert!(diags.contains(&"N-C-AXIS"), "{diags:?}");
    let (s30, c30) = (0.5, 3f64.sqrt() / 2.0);
    let at = |d: f64| {
        let f = |v: f64| ((v * 1e6).round() / 1e6).to_string();
        (f(100.0 + d * s30), f(d * c30))
    };
    let (rx, rz) = at(-10.0);
    let (bx, bz) = at(-40.0);
    // To the hole on the initial plane, down the tilted axis to R.
    assert_eq!(out[..2], s(&["S Some(true)", "R 50 0 0"])[..]);
    assert_eq!(out[2], "R 100 0 0");
    assert_eq!(out[3], format!("R {rx} 0 {rz}"));
    // The first peck cuts 5 along the tilted axis, then back to R.
    let (px, pz) = at(-15.0);
    assert_eq!(out[4], format!("F {px} 0 {pz}"));
    assert_eq!(out[5], format!("R {rx} 0 {rz}"));
    // The last feed reaches the bottom 30 from R, dwells 3 s, and the tool returns.
    let bottom = out
        .iter()
        .position(|e| *e == format!("F {bx} 0 {bz}"))
        .unwrap();
    assert_eq!(out[bottom + 1], "D 3");
    assert_eq!(out[bottom + 2], format!("R {rx} 0 {rz}"));
    assert_eq!(out[bottom + 3], "R 100 0 0");
    // Two holes (C0 and C120, drawn at the same X and Z).
    let (holes, _) = holes(text, Dialect::Gsk);
    assert_eq!(holes.len(), 2);
    assert_eq!(holes[0].0, 831);
}

#[test]
fn gsk_slant_angle_zero_or_past_60_degrees_is_an_alarm() {
    for e in ["E0", "E61", ""] {
        let (out, diags) = events(
            &format!("G0 X50 Z0\nG85.1 X100 Z-30 R-10 F200 {e}\n"),
            Dialect::Gsk,
        );
        // The parser already refuses E0 and E61 (out of the manual's range).
        assert!(
            diags.contains(&"E-SLANT-ANGLE") || diags.contains(&"E-NUMBER-RANGE"),
            "{e}: {diags:?}"
        );
        assert_eq!(out.len(), 1, "{e}: {out:?}");
    }
    // The side cycles drill along X, leaning towards Z.
    let (out, diags) = events("G0 X50 Z0\nG89.1 Z-20 X-10 R-5 F200 E-45\n", Dialect::Gsk);
    assert!(diags.iter().all(|c| !c.starts_with("E-")), "{diags:?}");
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let f = |v: f64| ((v * 1e6).round() / 1e6).to_string();
    assert_eq!(
        out[2],
        format!("R {} 0 {}", f(50.0 - 5.0 * h), f(-20.0 + 5.0 * h))
    );
}

/// The manual's five-hole template (E53–E61, E63, E64), in every dialect with these cycles: holes 1–3 under G99 come back to R,
/// hole 4 sets G98 and comes back to the initial level, hole 5 sets a new bottom.
#[test]
fn manual_cycle_examples_drill_the_stated_holes_and_return_as_stated() {
    let cases = [
        (73, "Q2."),
        (74, "P2."),
        (76, "Q2. P5."),
        (81, ""),
        (82, "P2."),
        (83, "Q3."),
        (84, ""),
        (85, ""),
        (86, ""),
        (88, "P3."),
        (89, "P2."),
    ];
    let tops = [
        (5.0, 5.0),
        (15.0, 5.0),
        (15.0, 15.0),
        (5.0, 15.0),
        (10.0, 10.0),
    ];
    for dialect in [Dialect::Syntec, Dialect::Fanuc, Dialect::Kt, Dialect::Lnc] {
        for (code, extra) in cases {
            // LNC's list has no G88.
            if dialect == Dialect::Lnc && code == 88 {
                continue;
            }
            let spindle = if code == 74 { "M04" } else { "M03" };
            let text = format!(
                "F1000. S500;\n{spindle};\nG90;\nG00 X0. Y0. Z10.;\nG17;\nG90 G99;\n\
                 G{code} X5. Y5. Z-10. R-5. {extra};\nX15.;\nY15.;\nG98 X5.;\n\
                 X10. Y10. Z-20.;\nG80;\nM05;\nM30;\n"
            );
            let program = parse(&text, dialect);
            let mut rec = CanonRecorder::default();
            let mut diags = program.diagnostics.clone();
            diags.extend(run(&program, Setup::default(), &mut rec));
            assert!(
                diags
                    .iter()
                    .all(|d| d.severity < swarf_syntax::Severity::Error),
                "{dialect} G{code}: {diags:?}"
            );
            let mut holes = Vec::new();
            let mut last_z = Vec::new();
            let mut z = 10.0;
            for (_, e) in &rec.events {
                match e {
                    Canon::Hole { top, bottom, .. } => {
                        if !holes.is_empty() {
                            last_z.push(z);
                        }
                        holes.push((*top, *bottom));
                    }
                    Canon::Rapid { to } | Canon::Feed { to, .. } => z = to.z,
                    _ => {}
                }
            }
            last_z.push(z);
            assert_eq!(holes.len(), 5, "{dialect} G{code}");
            for (i, ((top, bottom), (x, y))) in holes.iter().zip(tops).enumerate() {
                let depth = if i == 4 { -20.0 } else { -10.0 };
                assert!(
                    close(*top, DVec3::new(x, y, -5.0)) && close(*bottom, DVec3::new(x, y, depth)),
                    "{dialect} G{code} hole {i}: {top} {bottom}"
                );
            }
            assert_eq!(last_z, [-5.0, -5.0, -5.0, 10.0, 10.0], "{dialect} G{code}");
        }
    }
}

#[test]
fn syntec_peck_tapping_backs_out_to_r_or_by_d_between_pecks() {
    let text = "G0 X0 Y0 Z10.\nS500 M03\nG99 G84 X5. R-5. Z-12. Q3. F1000.\n";
    let (out, diags) = events(text, Dialect::Syntec);
    assert!(diags.iter().all(|c| !c.starts_with("E-")), "{diags:?}");
    let feeds: Vec<&String> = out.iter().filter(|e| e.starts_with('F')).collect();
    // TYPE III (Pr4001 = 0): every peck backs out to R, the spindle reversed.
    assert_eq!(
        feeds,
        [
            "F 5 0 -8",
            "F 5 0 -5",
            "F 5 0 -11",
            "F 5 0 -5",
            "F 5 0 -12",
            "F 5 0 -5"
        ]
    );
    let reversals = out.iter().filter(|e| *e == "S Some(false)").count();
    assert_eq!(reversals, 3);
    // TYPE II (Pr4001 = 1): backs out by d (1 mm).
    let mut setup = Setup::default();
    setup.machine.high_speed_peck_tapping = true;
    let program = parse(text, Dialect::Syntec);
    let mut rec = CanonRecorder::default();
    run(&program, setup, &mut rec);
    let zs: Vec<f64> = rec
        .events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Feed { to, .. } => Some(to.z),
            _ => None,
        })
        .collect();
    assert_eq!(zs, [-8.0, -7.0, -11.0, -10.0, -12.0, -5.0]);
}

#[test]
fn kt_tapping_i_gives_threads_per_inch() {
    let feeds = kt_feeds("G0 Z10 S600 M03\nG99 G84 X1 R2 Z-5 I20\n");
    // 20 threads per inch: a 1.27 mm pitch at 600 rpm.
    assert_eq!(feeds.len(), 2);
    assert!(
        feeds.iter().all(|f| (f - 1.27 * 600.0).abs() < 1e-9),
        "{feeds:?}"
    );
}

#[test]
fn gsk_e17_slanted_flexible_tapping_reverses_at_the_bottom() {
    let text = "G98;\nG0 X0 Z200;\nM3 S800;\nG84.1 Z-30 R-10 P1000 F1600 E30;\nG80;\nM30;\n";
    let (out, diags) = events(text, Dialect::Gsk);
    assert!(diags.iter().all(|c| !c.starts_with("E-")), "{diags:?}");
    let (s30, c30) = (0.5, 3f64.sqrt() / 2.0);
    let f = |v: f64| ((v * 1e6).round() / 1e6).to_string();
    let r = format!("R {} 0 {}", f(-10.0 * s30), f(200.0 - 10.0 * c30));
    let bottom = format!("F {} 0 {}", f(-40.0 * s30), f(200.0 - 40.0 * c30));
    let back = format!("F {} 0 {}", f(-10.0 * s30), f(200.0 - 10.0 * c30));
    // In along the tilted axis, stop, dwell 1 s, reverse, out to R, stop, forward, back up.
    let at = out.iter().position(|e| *e == r).unwrap();
    assert_eq!(
        out[at + 1..at + 9],
        s(&[
            &bottom,
            "S None",
            "D 1",
            "S Some(false)",
            &back,
            "S None",
            "S Some(true)",
            "R 0 0 200",
        ])[..]
    );
}

#[test]
fn linuxcnc_g84_outside_xy_feeds_with_its_axes_rotated_as_linuxcnc_does() {
    // LinuxCNC's test interp/g84/g18: in G18 the feed to (X1, Y-1, Z1) is emitted at
    // (-1, 1, 1) and the way out to (1, 2, 1) at (2, 1, 1); the next hole starts from where
    // rs274ngc meant to be.
    let (out, diags) = events(
        "G21 G18 G0 X0 Y2 Z0 M3 S100\nG98 G84 X1 Z1 Y-1 R1 F10\nG84 X1 Z2 Y0.5 R3\n",
        Dialect::LinuxCnc,
    );
    assert!(diags.contains(&"W-LINUXCNC-G84-PLANE"), "{diags:?}");
    let motions: Vec<&String> = out
        .iter()
        .filter(|e| e.starts_with('R') || e.starts_with('F'))
        .collect();
    assert_eq!(
        motions,
        [
            "R 0 2 0",
            "R 1 2 1",
            "R 1 1 1",
            "F -1 1 1",
            "F 2 1 1",
            "R 1 3 1",
            "R 1 3 2",
            "F 0.5 2 1",
            "F 3 2 1",
        ]
    );
    // G19: (Z, X, Y).
    let (out, _) = events(
        "G21 G19 G0 X2 Y0 Z0 M3 S100\nG98 G84 Y1 Z1 X-1 R1 F10\n",
        Dialect::LinuxCnc,
    );
    assert!(out.contains(&"F 1 -1 1".to_string()), "{out:?}");
    // The Fanuc family taps along the drilling axis.
    let (out, diags) = events(
        "G18 G0 X0 Y2 Z0 S100 M3\nG98 G84 X1 Z1 Y-1 R1 F10\n",
        Dialect::Fanuc,
    );
    assert!(!diags.contains(&"W-LINUXCNC-G84-PLANE"));
    assert!(out.contains(&"F 1 -1 1".to_string()), "{out:?}");
}
