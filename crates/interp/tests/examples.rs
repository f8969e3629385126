//! The reference's worked examples (gcode-reference §7, E1–E75) run through the interpreter,
//! with the results the manuals state or the reference derives, and short hand-written programs
//! for the codes no example shows, one per dialect family where the behaviour differs.
//!
//! Each example's G-code is embedded as written in the reference (KT/LNC/GSK `// …` comments
//! stripped; Syntec's `//` comments are real comments and kept). Where the OCR damaged a token
//! or the manual leaves the start point to a missing figure, the change is said in the test.
//!
//! Numbers without a decimal point: KT, LNC and Syntec read them in least input increments
//! (0.001 mm) unless calculator-type input is set (`mm()` below); the tests use the setting
//! where the manual's comments clearly mean millimetres (and say so), and the default where the
//! manual does not say (E21).
//!
//! Skipped (not run by the interpreter yet, or nothing to run): E2, E3, E29, E46 and E53–E64,
//! E70–E73 (canned cycles and hole patterns), E10 (G121 measurement and G10 L99), E14 (the
//! position of a rotary axis is not part of the motion stream), E15–E18 (GSK slanted cycles;
//! E18 shows format lines only), E25–E28 (G05, G05.1, G06.2, G12.1), E39 (its result is the
//! compensated contour), E40 (G43.4), E41 (G45–G48), E48 (G68.2/G53.1).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::DVec3;
use swarf_interp::{Arc, Axis, Canon, CanonRecorder, Setup, Source, run};
use swarf_syntax::{Diagnostic, Dialect, Severity, parse};

/// One run: the events with their sources, and the parse and run diagnostics.
struct Run {
    events: Vec<(Source, Canon)>,
    diags: Vec<Diagnostic>,
}

impl Run {
    /// The motion events with the line they came from.
    fn moves(&self) -> Vec<(u32, &Canon)> {
        self.events
            .iter()
            .filter(|(_, e)| e.end_point().is_some())
            .map(|(s, e)| (s.line, e))
            .collect()
    }

    /// The end points of the motions.
    fn ends(&self) -> Vec<DVec3> {
        self.events
            .iter()
            .filter_map(|(_, e)| e.end_point())
            .collect()
    }

    /// The lines that moved, in order.
    fn lines(&self) -> Vec<u32> {
        self.moves().iter().map(|(l, _)| *l).collect()
    }

    fn errors(&self) -> Vec<&'static str> {
        self.diags
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .map(|d| d.code)
            .collect()
    }

    fn codes(&self) -> Vec<&'static str> {
        self.diags.iter().map(|d| d.code).collect()
    }

    #[track_caller]
    fn assert_no_errors(&self) {
        assert!(self.errors().is_empty(), "{:#?}", self.diags);
    }

    fn dwells(&self) -> Vec<f64> {
        self.events
            .iter()
            .filter_map(|(_, e)| match e {
                Canon::Dwell { secs } => Some(*secs),
                _ => None,
            })
            .collect()
    }

    /// The arcs: end, centre, counter-clockwise, extra turns.
    fn arcs(&self) -> Vec<(DVec3, DVec3, bool, u32)> {
        self.events
            .iter()
            .filter_map(|(_, e)| match e {
                Canon::Arc(Arc {
                    to,
                    center,
                    ccw,
                    turns,
                    ..
                }) => Some((*to, *center, *ccw, *turns)),
                _ => None,
            })
            .collect()
    }

    /// The feed of every feed and arc move, mm/min.
    fn feeds(&self) -> Vec<f64> {
        self.events
            .iter()
            .filter_map(|(_, e)| match e {
                Canon::Feed {
                    feed_mm_per_min, ..
                }
                | Canon::Arc(Arc {
                    feed_mm_per_min, ..
                }) => Some(*feed_mm_per_min),
                _ => None,
            })
            .collect()
    }
}

fn run_in(text: &str, dialect: Dialect, setup: Setup) -> Run {
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, setup, &mut rec));
    Run {
        events: rec.events,
        diags,
    }
}

/// Calculator-type input: numbers without a decimal point are millimetres (and degrees).
fn mm() -> Setup {
    let mut setup = Setup::default();
    setup.machine.calculator_input = Some(true);
    setup
}

fn setup(toml: &str) -> Setup {
    Setup::from_toml(toml).unwrap()
}

fn v(p: [f64; 3]) -> DVec3 {
    DVec3::from_array(p)
}

#[track_caller]
fn assert_at(got: DVec3, want: [f64; 3], tol: f64) {
    assert!(
        got.abs_diff_eq(v(want), tol),
        "got ({:.4}, {:.4}, {:.4}), want {want:?}",
        got.x,
        got.y,
        got.z
    );
}

#[track_caller]
fn assert_path(got: &[DVec3], want: &[[f64; 3]], tol: f64) {
    assert_eq!(got.len(), want.len(), "{got:?}");
    for (g, w) in got.iter().zip(want) {
        assert_at(*g, *w, tol);
    }
}

/// The XY points of a polar position (radius, angle in degrees).
fn polar(r: f64, deg: f64) -> [f64; 2] {
    let (s, c) = deg.to_radians().sin_cos();
    [r * c, r * s]
}

#[track_caller]
fn assert_xy(got: DVec3, want: [f64; 2], tol: f64) {
    assert!(
        (got.x - want[0]).abs() < tol && (got.y - want[1]).abs() < tol,
        "got ({:.4}, {:.4}), want {want:?}",
        got.x,
        got.y
    );
}

/// The clockwise sweep in degrees from `a` to `b` about `c` (XY).
fn cw_sweep(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let aa = (a.y - c.y).atan2(a.x - c.x).to_degrees();
    let ab = (b.y - c.y).atan2(b.x - c.x).to_degrees();
    (aa - ab).rem_euclid(360.0)
}

// ---------------------------------------------------------------------------------------------
// KT (E1–E6)
// ---------------------------------------------------------------------------------------------

#[test]
fn e1_kt_tool_length_compensation_g43_h00() {
    // E1, KT Appendix 8: holes #1–#3 with G43 H01 (H01 = 4.0 as printed). The manual says the
    // end points are shifted by the offset; the reference derives the spindle (gauge line) Z
    // relative to the start: N2 −28, hole bottoms −49, −69, −53, and N12 (H00 cancels) back at
    // 0, with the XY moves summing to zero. Swarf's motion stream is the tool tip, which follows
    // the program while the gauge line sits the offset above it: tip = gauge − 4 under G43.
    // The numbers carry decimal points; the manual programs no F (the control would use the
    // active feed), so the G01 blocks report E-NO-FEED and nothing else goes wrong.
    let text = "N1 G91 G00 X120.0 Y80.0 ; (1)
N2 G43 Z-32.0 H01 ; (2)
N3 G01 Z-21.0 ; (3)
N4 G04 P2000 ; (4)
N5 G00 Z21.0 ; (5)
N6 X30.0 Y-50.0 ; (6)
N7 G01 Z-41.0 ; (7)
N8 G00 Z41.0 ; (8)
N9 X50.0 Y30.0 ; (9)
N10 G01 Z-25.0 ; (10)
N11 G04 P2000 ; (11)
N12 G00 Z57.0 H00 ; (12)
N13 X-200.0 Y-60.0 ; (13)
N14 M30 ;
";
    let r = run_in(text, Dialect::Kt, setup("[registers.1]\nlength = 4.0\n"));
    assert!(
        r.errors().iter().all(|c| *c == "E-NO-FEED"),
        "{:#?}",
        r.diags
    );
    let gauge = [-28.0, -49.0, -28.0, -28.0, -69.0, -28.0, -28.0, -53.0];
    let want_tip: Vec<f64> = gauge.iter().map(|z| z - 4.0).collect();
    let ends = r.ends();
    assert_eq!(ends.len(), 11, "{ends:?}");
    assert_at(ends[0], [120.0, 80.0, 0.0], 1e-9);
    for (k, z) in want_tip.iter().enumerate() {
        assert!((ends[k + 1].z - z).abs() < 1e-9, "move {}: {ends:?}", k + 1);
    }
    // The three holes.
    assert_at(ends[2], [120.0, 80.0, -53.0], 1e-9);
    assert_at(ends[5], [150.0, 30.0, -73.0], 1e-9);
    assert_at(ends[8], [200.0, 60.0, -57.0], 1e-9);
    // N12: H00 cancels; 57 up brings the gauge line (−53 + 57 − 4) and the tip to 0. N13: the
    // start again.
    assert_at(ends[9], [200.0, 60.0, 0.0], 1e-9);
    assert_at(ends[10], [0.0, 0.0, 0.0], 1e-9);
    // G04 P2000 is 2 s (KT's P in milliseconds).
    assert_eq!(r.dwells(), [2.0, 2.0]);
    assert!(matches!(r.events.last().unwrap().1, Canon::End));
}

#[test]
fn h_word_alone_changes_the_active_length_offset() {
    // E1's N12: `H00` while G43 is active cancels the offset (KT §4.23): the modal code #4008
    // reads 49 afterwards (KT has no G53), moved to as an X coordinate to show it. In the Fanuc
    // family an H word alone selects its register at once: G53 Z0 then puts the gauge line at
    // machine Z0 and the tip the new length (10) below it.
    let setup = || {
        setup(
            "[machine]\ncalculator_input = true\n[registers.1]\nlength = 4.0\n[registers.2]\nlength = 10.0\n",
        )
    };
    let r = run_in(
        "G43 Z-32 H01\nG00 X#4008\nG00 Z57 H00\nG00 X#4008\n",
        Dialect::Kt,
        setup(),
    );
    r.assert_no_errors();
    assert_eq!(r.ends()[1].x, 43.0);
    assert_eq!(r.ends()[3].x, 49.0);
    let r = run_in(
        "G43 Z-32 H01\nG00 Z0 H02\nG53 Z0\n",
        Dialect::Fanuc,
        setup(),
    );
    r.assert_no_errors();
    assert_at(r.ends()[2], [0.0, 0.0, -10.0], 1e-9);
}

#[test]
fn e4_kt_changing_the_pole() {
    // E4: `G00 X50 Y30` in polar mode is (50 mm, 30°) = (43.301, 25.000) (derived). The manual
    // means millimetres and degrees (calculator input). Its `...` lines are filled in here with
    // one move each to show the pole: after `G91 G16` the current point is the pole, after
    // `G90 G16` the work origin again.
    let text = "G90 G17 G16;
G00 X50 Y30;
G91 G16;
G90 X10 Y0;
G90 G16;
X10 Y90;
G15;
";
    let r = run_in(text, Dialect::Kt, mm());
    r.assert_no_errors();
    let ends = r.ends();
    assert_at(ends[0], [43.301, 25.0, 0.0], 1e-3);
    // Pole at (43.301, 25): 10 mm at 0° from it.
    assert_at(ends[1], [53.301, 25.0, 0.0], 1e-3);
    // Pole back at the origin: 10 mm at 90°.
    assert_at(ends[2], [0.0, 10.0, 0.0], 1e-9);
}

const E5: &str = "N1 G90 G69 G54 G49 G40 G17 X-50 Y-50 Z30
N2 G68 X70 Y30 R45 (N2 G68 R45)
N3 G90 G01 X0 Y0 F800
N4 G91 X100
N5 G02 Y100 R100
N6 G03 X-100 I-50 J-50
N7 G01 Y-100
N8 G90 G69 X-50 Y-50
N9 M30
";

#[test]
fn e5_kt_rotation_about_a_centre() {
    // E5: the shape rotated 45° about (70, 30); the reference's end points per block. Integers
    // are millimetres here (calculator input).
    let r = run_in(E5, Dialect::Kt, mm());
    r.assert_no_errors();
    assert_eq!(r.lines(), [1, 3, 4, 5, 6, 7, 8]);
    let ends = r.ends();
    let want = [
        [-50.0, -50.0, 30.0],
        [41.716, -40.711, 30.0],
        [112.426, 30.0, 30.0],
        [41.716, 100.711, 30.0],
        [-28.995, 30.0, 30.0],
        [41.716, -40.711, 30.0],
        [-50.0, -50.0, 30.0],
    ];
    assert_path(&ends, &want, 1e-3);
    let arcs = r.arcs();
    // N5: clockwise R100; N6: counter-clockwise about (41.716, 30).
    assert!(!arcs[0].2);
    let n5_radius = arcs[0].0.distance(arcs[0].1);
    assert!((n5_radius - 100.0).abs() < 1e-6, "{n5_radius}");
    assert!(arcs[1].2);
    assert_at(arcs[1].1, [41.716, 30.0, 30.0], 1e-3);
}

#[test]
fn e5_kt_rotation_without_a_centre_turns_about_the_current_point() {
    // E5's alternative `G68 R45`: the current position (−50, −50) is the centre, so N3's
    // origin lands at (−50, −50) + rot45°(50, 50) = (−50, 20.711).
    let text = E5.replace("N2 G68 X70 Y30 R45 (N2 G68 R45)", "N2 G68 R45");
    let r = run_in(&text, Dialect::Kt, mm());
    r.assert_no_errors();
    assert_at(r.ends()[1], [-50.0, 20.711, 30.0], 1e-3);
}

#[test]
fn e6_kt_repeated_rotation_draws_an_octagon() {
    // E6: O2100 once unrotated, then 7 times more, each rotated a further 45° (G91 G68 R45):
    // a closed regular octagon of apothem 10 (vertices at radius 10.824), each copy starting
    // where the previous one ended. Integers are millimetres and degrees here.
    let text = "G92 G69 G17 X0 Y0;
G01 F200 H01;
M98 P2100;
M98 P2200L7;
G90 G00 X0 Y0;
M30;
O2200
G91 G68 X0 Y0 R45;
G90 M98 P2100;
M99;
O2100
G90 G01 X0 Y-10;
X4.142;
X7.071 Y-7.071;
M99;
";
    let r = run_in(text, Dialect::Kt, mm());
    r.assert_no_errors();
    let ends = r.ends();
    assert_eq!(ends.len(), 8 * 3 + 1);
    for copy in 0..8 {
        let turn = 45.0 * copy as f64;
        let (a, b, c) = (ends[3 * copy], ends[3 * copy + 1], ends[3 * copy + 2]);
        // (0, −10) rotated: where the previous copy ended.
        assert_xy(a, polar(10.0, -90.0 + turn), 1e-3);
        // The vertex (4.142, −10).
        assert!((b.truncate().length() - 10.824).abs() < 1e-3, "{b:?}");
        assert_xy(c, polar(10.0, -45.0 + turn), 1e-3);
    }
    // The eighth copy closes the octagon at (0, −10); the final G00 goes to the origin.
    assert_xy(ends[23], [0.0, -10.0], 1e-3);
    assert_at(ends[24], [0.0, 0.0, 0.0], 1e-9);
}

// ---------------------------------------------------------------------------------------------
// LNC (E7–E13)
// ---------------------------------------------------------------------------------------------

#[test]
fn e7_lnc_arc_absolute_and_incremental_draw_the_same_arc() {
    // E7: from the derived start (−30, −40), both lines draw the CCW arc about (−80, −60),
    // radius 53.852, to (−60, −10). The manual's two lines are alternatives; G90/G91 and the
    // start are added here (the figure is missing).
    for (mode, line) in [
        ("G90", "G03X-60.Y-10.I-50.J-20.F1000 ;"),
        ("G91", "G03X-30.Y30.I-50.J-20.F1000 ;"),
    ] {
        let text = format!("G90 G00 X-30. Y-40. ;\n{mode} ;\n{line}\n");
        let r = run_in(&text, Dialect::Lnc, Setup::default());
        r.assert_no_errors();
        let arcs = r.arcs();
        assert_eq!(arcs.len(), 1, "{mode}");
        let (to, center, ccw, turns) = arcs[0];
        assert_at(to, [-60.0, -10.0, 0.0], 1e-9);
        assert_at(center, [-80.0, -60.0, 0.0], 1e-9);
        assert!(ccw && turns == 0);
        assert!((center.distance(DVec3::new(-30.0, -40.0, 0.0)) - 53.852).abs() < 1e-3);
        assert_eq!(r.feeds(), [1000.0]);
    }
}

#[test]
fn e8_lnc_radius_sign_picks_the_minor_or_major_arc() {
    // E8: R25 is the arc under 180°, R−25 the one over 180°. The start is in the missing
    // figure; (−40, −50), 30 mm from the end, is chosen here.
    for (line, major) in [
        ("(1)G02X-70.Y-50.R25.F1000 ;", false),
        ("(2)G02X-70.Y-50.R-25.F1000 ;", true),
    ] {
        let text = format!("G00 X-40. Y-50. ;\n{line}\n");
        let r = run_in(&text, Dialect::Lnc, Setup::default());
        r.assert_no_errors();
        let (to, center, ccw, _) = r.arcs()[0];
        assert_at(to, [-70.0, -50.0, 0.0], 1e-9);
        assert!(!ccw);
        let start = DVec3::new(-40.0, -50.0, 0.0);
        assert!((center.distance(start) - 25.0).abs() < 1e-9);
        let sweep = cw_sweep(start, to, center);
        assert_eq!(sweep > 180.0, major, "{line}: {sweep}°");
    }
}

#[test]
fn e9_lnc_helix_z_feed() {
    // E9: F500 in the XY plane, radius 10, 360°, Z travel 2: Fz = 180·L/(π·R·θ)·F = 15.915
    // mm/min. The helix is programmed as a full circle with Z; Fz follows from the arc event.
    let text = "G00 X10. Y0 Z0 ;\nG03 X10. Y0 Z2. I-10. J0 F500 ;\n";
    let r = run_in(text, Dialect::Lnc, Setup::default());
    r.assert_no_errors();
    let (to, center, ccw, turns) = r.arcs()[0];
    assert_at(to, [10.0, 0.0, 2.0], 1e-9);
    assert_at(center, [0.0, 0.0, 0.0], 1e-9);
    assert!(ccw && turns == 0);
    let (radius, theta, l, f) = (10.0_f64, 360.0_f64, to.z, 500.0);
    let fz = 180.0 * l / (std::f64::consts::PI * radius * theta) * f;
    assert!((fz - 15.915).abs() < 1e-3, "{fz}");
}

#[test]
fn e11_lnc_absolute_and_incremental_reach_the_same_point() {
    // E11: from the derived start (30, 30) both blocks end at (90, 70). The manual means
    // millimetres (calculator input).
    for line in ["G90 X90 Y70 ;", "G91 X60 Y40 ;"] {
        let text = format!("G00 X30 Y30 ;\n{line}\n");
        let r = run_in(&text, Dialect::Lnc, mm());
        r.assert_no_errors();
        assert_path(&r.ends(), &[[30.0, 30.0, 0.0], [90.0, 70.0, 0.0]], 1e-9);
    }
}

#[test]
fn e12_lnc_g92_moves_every_work_origin() {
    // E12: with the tool at (150, 100), `G92 X80 Y60` makes the position (80, 60); the origin
    // moves by (+70, +40) in the old frame, and G55–G59 shift by the same amount (here G55 =
    // (10, 20) in the setup). Millimetres (calculator input).
    let text = "G00 X150 Y100 ;\nG92 X80 Y60;\nX80 Y60 ;\nX0 Y0 ;\nG55 X0 Y0 ;\n";
    let s = setup("[machine]\ncalculator_input = true\n[work_offsets]\nG55 = [10.0, 20.0, 0.0]\n");
    let r = run_in(text, Dialect::Lnc, s);
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [150.0, 100.0, 0.0],
            [150.0, 100.0, 0.0],
            [70.0, 40.0, 0.0],
            [80.0, 60.0, 0.0],
        ],
        1e-9,
    );
}

#[test]
fn e13_lnc_g92_names_the_programmed_point() {
    // E13: the programmed (uncompensated) point at the G92 block becomes (0, 0). D1 has no
    // radius in this setup, so the compensated path is the programmed one; `X50.` then ends at
    // (100, 100). The reference's trailing `. .` (elided blocks) is left out.
    let text = "G00X50.Y50.G41D1; G01Y100.F1000; G92X0.Y0.; X50.;\n";
    let r = run_in(text, Dialect::Lnc, Setup::default());
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[[50.0, 50.0, 0.0], [50.0, 100.0, 0.0], [100.0, 100.0, 0.0]],
        1e-9,
    );
}

// ---------------------------------------------------------------------------------------------
// Syntec (E19–E75)
// ---------------------------------------------------------------------------------------------

#[test]
fn e19_e65_syntec_g00_absolute_and_incremental() {
    // E19 (and E65, the same lines under G90/G91): from the figure's start (20, 20) both
    // commands reach (90, 40).
    for line in [
        "G90 G00 X90.0 Y40.0;   // straight move to the point, from its difference to the program zero",
        "G91 G00 X70.0 Y20.0;   // straight move to the point, from its difference to the start point",
    ] {
        let text = format!("G90 G00 X20. Y20.;\n{line}\n");
        let r = run_in(&text, Dialect::Syntec, Setup::default());
        r.assert_no_errors();
        assert_eq!(r.lines(), [1, 2]);
        assert_at(r.ends()[1], [90.0, 40.0, 0.0], 1e-9);
        assert!(matches!(r.moves()[1].1, Canon::Rapid { .. }));
    }
}

#[test]
fn e20_syntec_pocket_contour_absolute_and_incremental() {
    // E20: both programs trace P0 (0,0) → P1 (0,38) → P2 (20,45) → P3 (55,45) → P4 (55,10) →
    // P5 (45,0) → P0 at Z−10, starting and ending at Z10.
    let absolute = "N001 G00 X0.0 Y0.0 Z10.0;   // rapid above P0
N002 G90 G01 Z-10.0 F1000;  // feed to the bottom, 1000 mm/min
N003 Y38.0;                 // P0 -> P1
N004 X20.0 Y45.0;           // P1 -> P2
N005 X55.0;                 // P2 -> P3
N006 Y10.0;                 // P3 -> P4
N007 X45.0 Y0.0;            // P4 -> P5
N008 X0.0;                  // P5 -> P0
N009 G00 Z10.0;             // rapid back above P0
N010 M30;                   // end
";
    let incremental = "N001 G00 X0.0 Y0.0 Z10.0;
N002 G91 G01 Z-20.0 F1000;
N003 Y38.0;
N004 X20.0 Y7.0;
N005 X35.0;
N006 Y-35.0;
N007 X-10.0 Y-10.0;
N008 X-45.0;
N009 G00 Z20.0;
N011 M30;
";
    let want = [
        [0.0, 0.0, 10.0],
        [0.0, 0.0, -10.0],
        [0.0, 38.0, -10.0],
        [20.0, 45.0, -10.0],
        [55.0, 45.0, -10.0],
        [55.0, 10.0, -10.0],
        [45.0, 0.0, -10.0],
        [0.0, 0.0, -10.0],
        [0.0, 0.0, 10.0],
    ];
    for text in [absolute, incremental] {
        let r = run_in(text, Dialect::Syntec, Setup::default());
        r.assert_no_errors();
        assert_path(&r.ends(), &want, 1e-9);
        assert_eq!(r.feeds(), [1000.0; 7]);
        assert!(matches!(r.events.last().unwrap().1, Canon::End));
    }
    // The two one-line forms from the figure's start (20, 20).
    for line in [
        "G90 G01 X90.0 Y40.0;   // method 1 (absolute)",
        "G91 G01 X70.0 Y20.0;   // method 2 (incremental)",
    ] {
        let r = run_in(
            &format!("G00 X20. Y20.;\n{line}\n"),
            Dialect::Syntec,
            Setup::default(),
        );
        r.assert_no_errors();
        assert_at(r.ends()[1], [90.0, 40.0, 0.0], 1e-9);
    }
}

#[test]
fn e21_syntec_arcs_in_least_increments_and_a_full_circle() {
    // E21: the numbers have no decimal point, and the manual does not say what it means, so
    // Syntec's rule applies: µm. The arc's centre (2500, 1000) µm, radius 3162.3 µm, CCW from
    // (5500, 2000) to (1500, 4000); the full circle has centre (1000, 0) and radius 1000 µm.
    // The parenthesised incremental form is a comment in the program; it is run on its own too.
    let text = "G90 G00 X5500 Y2000;                            // rapid to the arc start
G17 G90 G03 X1500 Y4000 I-3000 J-1000 F200;     // absolute
(G17 G91 G03 X-4000 Y2000 I-3000 J-1000 F200;   // incremental)
";
    let incremental = "G90 G00 X5500 Y2000;\nG17 G91 G03 X-4000 Y2000 I-3000 J-1000 F200;\n";
    for text in [text, incremental] {
        let r = run_in(text, Dialect::Syntec, Setup::default());
        r.assert_no_errors();
        assert!(r.codes().contains(&"N-LEAST-INCREMENT"));
        assert_eq!(r.lines(), [1, 2]);
        let (to, center, ccw, _) = r.arcs()[0];
        assert_at(to, [1.5, 4.0, 0.0], 1e-9);
        assert_at(center, [2.5, 1.0, 0.0], 1e-9);
        assert!(ccw);
        assert!((center.distance(DVec3::new(5.5, 2.0, 0.0)) - 3.1623).abs() < 1e-4);
        assert_eq!(r.feeds(), [200.0]);
    }
    let r = run_in(
        "G90 G00 X0 Y0;\nG02 I1000 F100;   // cut a full circle\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    let (to, center, ccw, turns) = r.arcs()[0];
    assert_at(to, [0.0, 0.0, 0.0], 1e-9);
    assert_at(center, [1.0, 0.0, 0.0], 1e-9);
    assert!(!ccw && turns == 0);
}

#[test]
fn e22_syntec_helical_interpolation() {
    // E22: an XY arc CCW with Z linear to 90 at 600 mm/min. The start is in the missing figure;
    // (1000, 0, 0) is chosen, which makes the R1000 arc a quarter turn about the origin.
    let text = "G00 X1000. Y0 Z0;
G17 G03 X0.0 Y1000.0 R1000.0 Z90.0 F600;
// XY-plane arc, CCW, Z linear; helical cutting at 600 mm/min
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let (to, center, ccw, turns) = r.arcs()[0];
    assert_at(to, [0.0, 1000.0, 90.0], 1e-9);
    assert_at(center, [0.0, 0.0, 0.0], 1e-6);
    assert!(ccw && turns == 0);
    assert_eq!(r.feeds(), [600.0]);
}

#[test]
fn e23_syntec_spiral_and_conical_interpolation() {
    // E23: centre (0, 0); the radius shrinks from 100 at (100, 0) to 40 at (−40, 0), clockwise;
    // L3 = 3 turns, the partial half turn counting as one: 180° + 2 × 360° = 900°. The second
    // program also climbs to Z80 over 4 turns (a cone). No COR-006: L makes it a spiral.
    for (text, z, turns) in [
        ("G17 G00 X100. Y0 Z0; G02 X-40. I-100. L3;\n", 0.0, 2),
        ("G17 G00 X100. Y0 Z0; G02 X-40. I-100. Z80. L4;\n", 80.0, 3),
    ] {
        let r = run_in(text, Dialect::Syntec, Setup::default());
        r.assert_no_errors();
        let arcs = r.arcs();
        assert_eq!(arcs.len(), 1, "{text}");
        let (to, center, ccw, extra) = arcs[0];
        assert_at(to, [-40.0, 0.0, z], 1e-9);
        assert_at(center, [0.0, 0.0, 0.0], 1e-9);
        assert!(!ccw);
        assert_eq!(extra, turns, "{text}");
        let sweep = cw_sweep(DVec3::new(100.0, 0.0, 0.0), to, center) + 360.0 * f64::from(extra);
        assert!((sweep - (180.0 + 360.0 * f64::from(turns))).abs() < 1e-9);
    }
}

#[test]
fn e24_syntec_dwell() {
    // E24: `G04 X2500` = 2.5 s, `G04 P2500` = 2.5 s, `G04 P2.5` = 2 ms (no decimal point taken).
    // The OCR ran two lines together: the second `G04 X2.5` sits in the first line's comment
    // and is not run; it is run on its own below (2.5 s).
    let text = "G04 X2500; //dwell 2.5 sec G04 X2.5; //dwell 2.5 sec
G04 P2500; //dwell 2.5 sec
G04 P2.5; //dwell 2 msec (decimal point not accepted)
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_eq!(r.dwells(), [2.5, 2.5, 0.002]);
    let r = run_in(
        "G04 X2.5; //dwell 2.5 sec\n",
        Dialect::Syntec,
        Setup::default(),
    );
    assert_eq!(r.dwells(), [2.5]);
}

#[test]
fn e30_syntec_g22_protected_ranges() {
    // E30: `G22 X0. I0.` and `G22 X10. I10.` protect nothing (the pair's difference is 0);
    // `G22 X0. I10.` and `G22 X10. I0.` protect X0.–X10. (`IO.` is OCR for `I0.`.) The G22
    // words are limits, not a move. Checked by a move across X5 after each (protection starts
    // with the next block): into a protected zone it is an overtravel error.
    for (g22, protected) in [
        ("G22X0. I0.     // X not protected", false),
        ("G22X10. I10.   // X not protected", false),
        ("G22X0. I10.    // X0.–X10. protected", true),
        ("G22X10. I0.    // X0.–X10. protected", true),
    ] {
        let text = format!("G00 X-20.;\n{g22}\nG00 X-5.;\nG00 X20.;\n");
        let r = run_in(&text, Dialect::Syntec, Setup::default());
        assert_eq!(r.lines(), [1, 3, 4], "{g22}");
        let errors = r.errors();
        if protected {
            assert_eq!(errors, ["E-STROKE-LIMIT"], "{g22}");
            // The move to X−5 stays outside; the one through X0–X10 is the one reported.
            let d = r.diags.iter().find(|d| d.code == "E-STROKE-LIMIT").unwrap();
            assert_eq!(
                &text[d.span.start as usize..d.span.end as usize],
                "G00 X20."
            );
        } else {
            assert!(errors.is_empty(), "{g22}: {errors:?}");
        }
    }
    // `G22 X100. I200.` equals `G22 X200. I100.`; X without I is COR-109; G23 turns it off.
    for g22 in ["G22 X100. I200.", "G22 X200. I100."] {
        let r = run_in(
            &format!("{g22}\nG00 X150.\n"),
            Dialect::Syntec,
            Setup::default(),
        );
        assert_eq!(r.errors(), ["E-STROKE-LIMIT"], "{g22}");
    }
    let r = run_in("G22 X100.\nG00 X150.\n", Dialect::Syntec, Setup::default());
    assert_eq!(r.errors(), ["E-WORD-MISSING"]);
    assert!(r.diags[0].message.contains("COR-109"));
    let r = run_in(
        "G22 X100. I200.\nG23\nG00 X150.\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
}

#[test]
fn lnc_g22_keeps_the_tool_inside_its_limits() {
    // LNC §4.14: the G22 range is the soft limit (X Y Z the + limits, I J K the − limits, in
    // machine coordinates): a move out of it is the overtravel alarm; inside is fine.
    let text = "G22 X100. Y50. I-100. J-50.;\nG00 X90. Y40.;\nG00 X120.;\n";
    let r = run_in(text, Dialect::Lnc, Setup::default());
    assert_eq!(r.errors(), ["E-STROKE-LIMIT"]);
    assert_eq!(r.ends().len(), 2);
    let d = &r.diags[0];
    assert_eq!(
        &text[d.span.start as usize..d.span.end as usize],
        "G00 X120."
    );
}

/// Reference points for E31–E33 and E36: P1 (G28) and P2, P3 (G30), machine coordinates.
const REFERENCES: &str = "[machine]\nreference_points = [[400.0, 300.0, 0.0], [500.0, 100.0, 50.0], [-100.0, 200.0, 10.0]]\n";

#[test]
fn e31_syntec_g28_through_the_intermediate_point() {
    // E31: A → B (the intermediate point (50, 30), rapid) → C (the reference point, for the
    // axes given only). A = (10, 10, 5) is chosen (the figure is missing).
    let text = "G00 X10. Y10. Z5.;\nG90 G28 X50.0 Y30.0;//A→B→C, intermediate point (50,30)\n";
    let r = run_in(text, Dialect::Syntec, setup(REFERENCES));
    r.assert_no_errors();
    assert_eq!(r.lines(), [1, 2, 2]);
    assert_path(
        &r.ends(),
        &[[10.0, 10.0, 5.0], [50.0, 30.0, 5.0], [400.0, 300.0, 5.0]],
        1e-9,
    );
    assert!(
        r.moves()
            .iter()
            .all(|(_, e)| matches!(e, Canon::Rapid { .. }))
    );
    // `G28 X0;` returns X alone (through X0); the OCR ran the Y and Z forms into its comment,
    // so they are run one by one.
    let text = "G00 X10. Y10. Z5.;\nG28 X0; //reference return of X only G28 Y0; //Y only G28 Z0;//Z only\n";
    let r = run_in(text, Dialect::Syntec, setup(REFERENCES));
    r.assert_no_errors();
    assert_path(
        &r.ends()[1..],
        &[[0.0, 10.0, 5.0], [400.0, 10.0, 5.0]],
        1e-9,
    );
    for (line, want) in [
        ("G28 Y0; //Y only", [[10.0, 0.0, 5.0], [10.0, 300.0, 5.0]]),
        ("G28 Z0;//Z only", [[10.0, 10.0, 0.0], [10.0, 10.0, 0.0]]),
    ] {
        let r = run_in(
            &format!("G00 X10. Y10. Z5.;\n{line}\n"),
            Dialect::Syntec,
            setup(REFERENCES),
        );
        r.assert_no_errors();
        assert_path(&r.ends()[1..], &want, 1e-9);
    }
}

#[test]
fn e32_syntec_g29_returns_through_the_intermediate_point() {
    // E32: A → B → C (G28), the tool change, then C → B → D. Absolute: D = (40, 0).
    // Incremental: B = A + (20, 30) and D = B + (20, −30). A = (5, 5) is chosen. The `:` that
    // ends two blocks is OCR for `;` (the parser reads it so and warns).
    let absolute = "G00 X5. Y5.;
N001 G90 G28 X20.0 Y30.0:
//A→B→C, intermediate point (20,30), absolute
N002 M06;//tool change
N003 G29 X40.0 Y0.0;
// C→B→D; the target is the absolute coordinate of the point
";
    let incremental = "G00 X5. Y5.;
N001 G91 G28 X20.0 Y30.0;
//A→B→C, intermediate point (20,30), incremental
N002 M06;//tool change
N003 G29 X20.0 Y-30.0:
//C→B→D; the target is given as its difference from the intermediate point
";
    for (text, b, d) in [
        (absolute, [20.0, 30.0, 0.0], [40.0, 0.0, 0.0]),
        (incremental, [25.0, 35.0, 0.0], [45.0, 5.0, 0.0]),
    ] {
        let r = run_in(text, Dialect::Syntec, setup(REFERENCES));
        r.assert_no_errors();
        assert_path(
            &r.ends(),
            &[[5.0, 5.0, 0.0], b, [400.0, 300.0, 0.0], b, d],
            1e-9,
        );
        assert!(
            r.events
                .iter()
                .any(|(_, e)| matches!(e, Canon::ToolChange { .. }))
        );
    }
}

#[test]
fn e33_syntec_g30_to_the_second_and_third_reference_points() {
    // E33: the tool at A (60, 10): `G30 P2 X75.0 Y25.0` goes A → B (75, 25) → the 2nd
    // reference point; `G30 P3 X15.0 Y10.0` A → C (15, 10) → the 3rd. Only X and Y return.
    for (line, mid, reference) in [
        (
            "G30 P2 X75.0 Y25.0;//A→B→2nd reference point",
            [75.0, 25.0, 0.0],
            [500.0, 100.0, 0.0],
        ),
        (
            "G30 P3 X15.0 Y10.0;//A→C→3rd reference point",
            [15.0, 10.0, 0.0],
            [-100.0, 200.0, 0.0],
        ),
    ] {
        let text = format!("G00 X60. Y10.;\n{line}\n");
        let r = run_in(&text, Dialect::Syntec, setup(REFERENCES));
        r.assert_no_errors();
        assert_path(&r.ends(), &[[60.0, 10.0, 0.0], mid, reference], 1e-9);
    }
    // P omitted is P2 (Syntec and LNC); LNC's G29 also returns from a G30.
    let r = run_in(
        "G00 X60. Y10.;\nG30 X75. Y25.;\nG29 X0. Y0.;\n",
        Dialect::Lnc,
        setup(REFERENCES),
    );
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [60.0, 10.0, 0.0],
            [75.0, 25.0, 0.0],
            [500.0, 100.0, 0.0],
            [75.0, 25.0, 0.0],
            [0.0, 0.0, 0.0],
        ],
        1e-9,
    );
}

#[test]
fn e34_syntec_g31_skip_is_drawn_in_full() {
    // E34: where the skip signal stops the move is not known to a backplot, so the G31 move is
    // drawn to its programmed end (with a note) and the next block goes on from there:
    // relative to it under G91, to the absolute point under G90.
    for (text, want) in [
        (
            "N001 G31 G91 X100.0 F100; //original path until the obstacle is touched\nN002 Y100.0;\n",
            [[100.0, 0.0, 0.0], [100.0, 100.0, 0.0]],
        ),
        (
            "N001 G31 G90 X200.0 F100;//original path until the obstacle is touched\nN002 Y100.0;\n",
            [[200.0, 0.0, 0.0], [200.0, 100.0, 0.0]],
        ),
        (
            "N001 G31 G90 X100.0 F1000;//original path until the obstacle is touched\nN002 X130.0 Y70.0;\n",
            [[100.0, 0.0, 0.0], [130.0, 70.0, 0.0]],
        ),
    ] {
        let r = run_in(text, Dialect::Syntec, Setup::default());
        r.assert_no_errors();
        assert!(r.codes().contains(&"N-PROBE"));
        assert_path(&r.ends(), &want, 1e-9);
        // The skip move is a feed, the one-shot G31 leaves the modal G00 for N002.
        assert!(matches!(r.moves()[0].1, Canon::Feed { .. }));
        assert!(matches!(r.moves()[1].1, Canon::Rapid { .. }));
    }
}

#[test]
fn e35_syntec_g33_thread_lead() {
    // E35: a 1.5 mm lead to Z10: the feed is the lead per spindle revolution. The example
    // assumes a running spindle; S500 is added (1.5 × 500 = 750 mm/min).
    let text = "S500 M03;\nG33 Z10.0 F1.5;\n//thread with a 1.5 mm lead, end point Z 10 mm\n";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(&r.ends(), &[[0.0, 0.0, 10.0]], 1e-9);
    assert_eq!(r.feeds(), [750.0]);
    // Without a spindle speed the thread cannot feed.
    let r = run_in("G33 Z10.0 F1.5;\n", Dialect::Syntec, Setup::default());
    assert_eq!(r.errors(), ["E-NO-FEED"]);
}

#[test]
fn e36_syntec_g37_tool_measurement() {
    // E36: the G30 return, tool changes, and the G37 measuring moves along Z to −150 (the
    // comment reads `Z-150` as millimetres: calculator input) and, with P3, first back to the
    // 3rd reference point (all axes) then down to −200. The signal's position is not known, so
    // each measuring move is drawn in full (a feed at the modal F, Syntec's 1000 mm/min).
    let text = "G30 P2 X75.0 Y25.0; // return the tool to the 2nd reference point;
M06 T1; // change to tool 1;
H1; // after measuring, write the length into length offset 1;
G37 Z-150; // Z moves towards -150., measure the tool;
M06 T2; // change to tool 2;
H2; // after measuring, write the length into length offset 2;
G37 Z-150; // Z moves towards -150., measure the tool;
H3; // after measuring, write the length into length offset 3;
G37 P3 Z-200.; // return to the \"second\" reference point (sic, P3), current tool,
// Z moves towards -200., measure the tool;
";
    let mut s = setup(REFERENCES);
    s.machine.calculator_input = Some(true);
    let r = run_in(text, Dialect::Syntec, s);
    r.assert_no_errors();
    assert_eq!(r.lines(), [1, 1, 4, 7, 9, 9]);
    assert_path(
        &r.ends(),
        &[
            [75.0, 25.0, 0.0],
            [500.0, 100.0, 0.0],
            [500.0, 100.0, -150.0],
            [500.0, 100.0, -150.0],
            [-100.0, 200.0, 10.0],
            [-100.0, 200.0, -200.0],
        ],
        1e-9,
    );
    let tools: Vec<u32> = r
        .events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::ToolChange { tool } => Some(*tool),
            _ => None,
        })
        .collect();
    assert_eq!(tools, [1, 2]);
    // G37 without Z is MAR-330 (the block is refused).
    let r = run_in("G37 P2;\n", Dialect::Syntec, Setup::default());
    assert_eq!(r.errors(), ["E-WORD-MISSING"]);
    assert!(r.ends().is_empty());
}

#[test]
fn e37_syntec_g37_1_tool_measurement_in_machine_coordinates() {
    // E37: as E36 with G37.1, whose Z is a machine coordinate; after measuring, Z retracts to
    // the safety point Q, by default the machine zero.
    let text = "G30 P2 X75.0 Y25.0; // return to the 2nd reference point;
M06 T1; // tool 1;
H1; // write into length offset 1;
G37.1 Z-150; // Z towards -150., measure;
M06 T2; // tool 2;
H2; // write into length offset 2;
G37.1 Z-150; // Z towards -150., measure;
H3; // write into length offset 3;
G37.1 P3 Z-200.; // return to the \"second\" reference point (sic), current tool,
// Z towards -200., measure;
";
    let mut s = setup(REFERENCES);
    s.machine.calculator_input = Some(true);
    let r = run_in(text, Dialect::Syntec, s);
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [75.0, 25.0, 0.0],
            [500.0, 100.0, 0.0],
            [500.0, 100.0, -150.0],
            [500.0, 100.0, 0.0],
            [500.0, 100.0, -150.0],
            [500.0, 100.0, 0.0],
            [-100.0, 200.0, 10.0],
            [-100.0, 200.0, -200.0],
            [-100.0, 200.0, 0.0],
        ],
        1e-9,
    );
}

#[test]
fn e38_syntec_flower_slot_programmed_contour() {
    // E38: the programmed vertices A (0,24), B (9,30), C (30,9), D (30,−9), E (9,−30),
    // F (−9,−30), G (−30,−9), H (−30,9), M (−9,30), back to A, alternating CCW R10 and CW R15
    // arcs. The D01 value is not given: with no radius in the setup the compensated path is
    // the programmed one.
    let text = "N001 T1 S1000 M03;
//tool 1 (10 mm end mill), spindle CW 1000 rpm
N002 G00 X0.0 Y0.0 Z10.0; //rapid above the program zero
N003 M08; //coolant on
N004 G90 G01 Z-10.0 F600;
//feed to the slot bottom, 600 mm/min
N005 G41 Y24.0 D01; //cutter comp left, program zero -> A
N006 G03 X9.0 Y30.0 R10.0; //A→B CCW arc
N007 G02 X30.0 Y9.0 R15.0; //B→C CW arc
N008 G03 X30.0 Y-9.0 R10.0; //C→D CCW arc
N009 G02 X9.0 Y-30.0 R15.0; //D→E CW arc
N010 G03 X-9.0 Y-30.0 R10.0;//E→F CCW arc
N011 G02 X-30.0 Y-9.0 R15.0;//F→G CW arc
N012 G03 X-30.0 Y9.0 R10.0; //G→H CCW arc
N013 G02 X-9.0 Y30.0 R15.0; //H→M CW arc
N014 G03 X0.0 Y24.0 R10.0; //M→A CCW arc
N015 G00 Z10.0; //Z up, back to the start
N016 G40 X0.0 Y0.0; //cancel cutter comp, back to the start
N017 M09; //coolant off
N018 M05; //spindle stop
N019 M30; //end
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let arcs = r.arcs();
    let vertices = [
        [9.0, 30.0],
        [30.0, 9.0],
        [30.0, -9.0],
        [9.0, -30.0],
        [-9.0, -30.0],
        [-30.0, -9.0],
        [-30.0, 9.0],
        [-9.0, 30.0],
        [0.0, 24.0],
    ];
    assert_eq!(arcs.len(), 9);
    let mut from = DVec3::new(0.0, 24.0, -10.0);
    for (k, ((to, center, ccw, _), want)) in arcs.iter().zip(vertices).enumerate() {
        assert_at(*to, [want[0], want[1], -10.0], 1e-9);
        assert_eq!(*ccw, k % 2 == 0);
        let radius = if k % 2 == 0 { 10.0 } else { 15.0 };
        assert!((center.distance(from) - radius).abs() < 1e-9);
        assert!((center.distance(*to) - radius).abs() < 1e-9);
        from = *to;
    }
    assert_at(*r.ends().last().unwrap(), [0.0, 0.0, 10.0], 1e-9);
}

#[test]
fn e42_syntec_scaling_by_half() {
    // E42: G51 about (125, 90) by 0.5; the reference's scaled positions per block.
    let text = "N001 G00 X0 Y0;
N002 G51 X125.0 Y90.0 P0.5;
//scaling centre X125, Y90, factor 0.5; blocks N003–N010 are scaled
N003 G00 X50.0 Y50.0; //rapid
N004 G01 Y70.0 F1000; //line, 1000 mm/min
N005 X100.0 Y150.0;
N006 G03 X150.0 I25.0; //arc, radius 25 mm
N007 G01 X200.0 Y70.0; //line
N008 Y50.0;
N009 X50.0;
N010 G00 X0.0 Y0.0; //rapid return
N011 G50; //scaling off
N012 M30; //end
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [0.0, 0.0, 0.0],
            [87.5, 70.0, 0.0],
            [87.5, 80.0, 0.0],
            [112.5, 120.0, 0.0],
            [137.5, 120.0, 0.0],
            [162.5, 80.0, 0.0],
            [162.5, 70.0, 0.0],
            [87.5, 70.0, 0.0],
            [62.5, 45.0, 0.0],
        ],
        1e-9,
    );
    let (_, center, ccw, _) = r.arcs()[0];
    assert_at(center, [125.0, 120.0, 0.0], 1e-9);
    assert!(ccw);
    assert!((center.distance(DVec3::new(137.5, 120.0, 0.0)) - 12.5).abs() < 1e-9);
}

#[test]
fn e43_syntec_unequal_scaling_uses_the_largest_factor_for_arcs() {
    // E43: I2 J1 doubles X only, but an arc's radius takes the largest factor (like P2): the
    // line goes to (100, 0) and the CW semicircle of R100 to (−100, 0).
    let text = "G51 X0. Y0. I2.0 J1.0
G00 X0. Y0.
G01 X50. Y0. F1000.
G02 X-50. Y0. R50.
G00 X0. Y0.
G50
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [0.0, 0.0, 0.0],
            [100.0, 0.0, 0.0],
            [-100.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ],
        1e-9,
    );
    let with_p = run_in(
        &text.replace("I2.0 J1.0", "P2.0"),
        Dialect::Syntec,
        Setup::default(),
    );
    assert_eq!(r.arcs(), with_p.arcs());
    let (_, center, ccw, _) = r.arcs()[0];
    assert_at(center, [0.0, 0.0, 0.0], 1e-9);
    assert!(!ccw);
}

#[test]
fn syntec_unequal_scaling_keeps_an_arc_on_its_circle() {
    // §4.26 where it matters: a quarter circle (50, 0) → (0, 50) about the origin under I2 J1
    // ends at (0, 50) from (100, 0); with the radius 50 × 2 the arc is the short CCW one through
    // those points, and both ends lie on it.
    let text = "G51 X0. Y0. I2.0 J1.0\nG00 X50. Y0.\nG03 X0. Y50. I-50. J0. F100.\n";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let (to, center, ccw, _) = r.arcs()[0];
    assert_at(to, [0.0, 50.0, 0.0], 1e-9);
    assert!(ccw);
    assert!((center.distance(DVec3::new(100.0, 0.0, 0.0)) - 100.0).abs() < 1e-9);
    assert!((center.distance(to) - 100.0).abs() < 1e-9);
}

/// E44's main program; the subprogram N100 follows it (reconstructed, see the test).
const E44_MAIN: &str = "N001 T1 S1000 M03; //tool 1, CW 1000 rpm
N002 M98 H100; //run the subprogram
N003 G51.1 X60.0; //mirror about X=60
N004 M98 H100; //run the subprogram
N005 G50.1; //mirror off
N006 G51.1 Y55.0; //mirror about Y=55
N007 M98 H100; //run the subprogram
N008 G50.1; //mirror off
N009 M05; //spindle stop
N010 M30; //end
";

#[test]
fn e44_syntec_mirror_image_example_1() {
    // E44: the OCR ran two pairs of subprogram lines together (`… //rapid to the point G01
    // Y75.0; //line to point O` and `X80.0; //O→A X120.0; //A→B`), which would put G01 Y75.0
    // and X120.0 in comments; they are split back into their own lines here.
    let sub = "N100; //subprogram number
G00 X60.0 Y55.0; //rapid to the point
G01 Y75.0; //line to point O
X80.0; //O→A
X120.0; //A→B
Y105.0; //B→C
X80.0 Y95.0; //C→D
Y75.0; //D→A
M99;
//end of subprogram
";
    let r = run_in(
        &format!("{E44_MAIN}{sub}"),
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    let ends = r.ends();
    assert_eq!(ends.len(), 21);
    let passes = [
        // Original: O (60,75), A (80,75), B (120,75), C (120,105), D (80,95), A.
        [
            [60.0, 55.0],
            [60.0, 75.0],
            [80.0, 75.0],
            [120.0, 75.0],
            [120.0, 105.0],
            [80.0, 95.0],
            [80.0, 75.0],
        ],
        // Mirror about X = 60.
        [
            [60.0, 55.0],
            [60.0, 75.0],
            [40.0, 75.0],
            [0.0, 75.0],
            [0.0, 105.0],
            [40.0, 95.0],
            [40.0, 75.0],
        ],
        // Mirror about Y = 55.
        [
            [60.0, 55.0],
            [60.0, 35.0],
            [80.0, 35.0],
            [120.0, 35.0],
            [120.0, 5.0],
            [80.0, 15.0],
            [80.0, 35.0],
        ],
    ];
    for (k, pass) in passes.iter().enumerate() {
        for (i, p) in pass.iter().enumerate() {
            assert_xy(ends[7 * k + i], *p, 1e-9);
        }
    }
}

/// E45's subprogram (its `:` block ends are OCR for `;`, which the parser reads as such; the
/// translated label comment after `N100;` lost its `//`, restored here).
const E45_SUB: &str = "N100; //subprogram label
G00 X58.0 Y0.0 Z10.0; //rapid above the start
G01 Z-10.0: //feed to the bottom of the \"flower\" slot
G03 X49.36 Y7.9744 R8.0;//CCW arc, radius 8 mm
G03 X40.5415 Y29.2641 R50.0;
//CCW arc, radius 50 mm
G03 X29.2641 Y40.5415 R8.0:
//CCW arc, radius 8 mm
G03 X7.9744 Y49.36 R50.0;
//CCW arc, radius 50 mm
G03 X0.0 Y58.0 R8.0; //CCW arc, radius \"50mm\" (sic; R8.0 is programmed)
G00 Z10.0;
//rapid up above the end point
M99;
//subprogram end, continue the main program
";

#[test]
fn e45_syntec_mirrored_quadrants_complete_the_flower() {
    // E45: one quadrant per call; the mirror calls about X0, the point (0, 0) and Y0 complete
    // the four. D01 = 5 is stated, but cutter compensation is other work: with no radius in the
    // setup the programmed path is checked. Single-axis mirrors reverse the arcs.
    let main = "N001 T1 S1000 M03;
//tool 1 (10 mm end mill), CW 1000 rpm
N002 G41 D01; //cutter comp left with offset 1 (D01 = 5)
N003 M98 H100; //run the subprogram
N004 G42 D01; //cutter comp right with offset 1
N005 G51.1 X0.0; //mirror about the X=0 axis
N006 M98 H100; //run the subprogram
N007 G50.1; //mirror off
N008 G41 D01; //cutter comp left
N009 G51.1 X0.0 Y0.0; //mirror about the point X=0, Y=0
N010 M98 H100; //run the subprogram
N011 G50.1; //mirror off
N012 G42 D01; //cutter comp right
N013 G51.1 Y0.0; //mirror about the Y=0 axis
N014 M98 H100; //run the subprogram
N015 G50.1; //mirror off
N016 G40; //cancel cutter comp
N017 M05; //spindle stop
N018 M30; //end
";
    let r = run_in(
        &format!("{main}{E45_SUB}"),
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    let ends = r.ends();
    assert_eq!(ends.len(), 4 * 8);
    let quadrant = [
        [58.0, 0.0, 10.0],
        [58.0, 0.0, -10.0],
        [49.36, 7.9744, -10.0],
        [40.5415, 29.2641, -10.0],
        [29.2641, 40.5415, -10.0],
        [7.9744, 49.36, -10.0],
        [0.0, 58.0, -10.0],
        [0.0, 58.0, 10.0],
    ];
    for (k, sign) in [[1.0, 1.0], [-1.0, 1.0], [-1.0, -1.0], [1.0, -1.0]]
        .iter()
        .enumerate()
    {
        for (i, p) in quadrant.iter().enumerate() {
            assert_at(
                ends[8 * k + i],
                [p[0] * sign[0], p[1] * sign[1], p[2]],
                1e-9,
            );
        }
    }
    let arcs = r.arcs();
    assert_eq!(arcs.len(), 20);
    for (k, (_, center, ccw, _)) in arcs.iter().enumerate() {
        let pass = k / 5;
        // Passes 2 and 4 mirror one axis: clockwise.
        assert_eq!(*ccw, pass % 2 == 0, "arc {k}");
        // The R50 arcs turn about the centre of the flower.
        if k % 5 == 1 || k % 5 == 3 {
            assert_at(*center, [0.0, 0.0, -10.0], 1e-3);
        }
    }
}

#[test]
fn e47_syntec_g53_machine_coordinates_are_one_shot() {
    // E47: G92 sets the base system; G53 goes to a machine point in its block only; the next
    // block is in the work system again; G52 adds a local origin. With the tool at the machine
    // origin at the start, G92 X−200 Y−100 makes that point (−200, −100), an offset of
    // (200, 100) whatever the G54 origin: N002 → (300, 300); N003 → machine (300, 100);
    // N004 → (500, 100); N006 → the local origin (500, 300).
    let text = "N001 G92 X-200.0 Y-100.0; //set the base coordinate system
N002 G54 G90 X100.0 Y200.0; //to the point in the work coordinate system
N003 G53 X300.0 Y100.0; //to the point in machine coordinates
N004 X300.0 Y0;
// G53 is valid only in its block; this block continues in G54 to the work-coordinate point
N005 G52 X300.0 Y200.0;
//local coordinate system at the given point of the work coordinate system
N006 X0.0 Y0.0;
";
    let s = setup("[work_offsets]\nG54 = [10.0, 20.0, 0.0]\n");
    let r = run_in(text, Dialect::Syntec, s);
    r.assert_no_errors();
    assert_eq!(r.lines(), [2, 3, 4, 8]);
    assert_path(
        &r.ends(),
        &[
            [300.0, 300.0, 0.0],
            [300.0, 100.0, 0.0],
            [500.0, 100.0, 0.0],
            [500.0, 300.0, 0.0],
        ],
        1e-9,
    );
}

/// O0010 for E49/E50 (not in the manual): one move by the passed X and Y (#24, #25).
const O0010: &str = "O0010\nG91 G00 X#24 Y#25\nM99\n";

#[test]
fn e49_syntec_g65_calls_twenty_times_with_arguments() {
    // E49: O0010 runs 20 times, with X10.0 Y10.0 passed in (here as #24/#25, the Fanuc
    // argument assignment, which Syntec's manual does not spell out).
    let text = format!(
        "G65 P10 L20 X10.0 Y10.0;\n//call subprogram O0010 20 times in a row, passing X10.0 Y10.0 into it\nM30\n{O0010}"
    );
    let r = run_in(&text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let ends = r.ends();
    assert_eq!(ends.len(), 20);
    assert_at(ends[19], [200.0, 200.0, 0.0], 1e-9);
}

#[test]
fn e50_syntec_g66_calls_after_each_move() {
    // E50: after N003 and after N004, O0010 runs twice (L2) with X10.0 Y10.0; G67 cancels.
    let text = format!(
        "N001 G91
N002 G66 P10 L2 X10.0 Y10.0
//call subprogram O0010 twice, passing X10.0 Y10.0
N003 X20.0
//move X to 20.0, then call G66 P10 L2 X10.0 Y10.0
N004 Y20.0
//move Y to 20.0, then call G66 P10 L2 X10.0 Y10.0
N005 G67
//cancel the modal macro call
N006 X1.0
M30
{O0010}"
    );
    let r = run_in(&text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[
            [20.0, 0.0, 0.0],
            [30.0, 10.0, 0.0],
            [40.0, 20.0, 0.0],
            [40.0, 40.0, 0.0],
            [50.0, 50.0, 0.0],
            [60.0, 60.0, 0.0],
            [61.0, 60.0, 0.0],
        ],
        1e-9,
    );
}

#[test]
fn e51_syntec_rotation_of_a_polar_path_four_copies() {
    // E51: each pass is a CCW R50 arc about the origin from 50∠9.207° to 50∠80.793°, then a
    // CCW R8 semicircle to 50∠99.207°; four passes 90° apart close a ring with four bumps, each
    // starting where the previous one ended. `Y80.793.` has a stray `.` (OCR), dropped here.
    let text = "G54 X0 Y0 F3000.;
G16; // polar syntax on
G90 G00 X50. Y9.207; // to the start point
M98 H100; // 1st pass
G68 X0 Y0 R90.; // rotate 90°
M98 H100; // 2nd pass
G68 X0 Y0 R180.; // rotate 180°
M98 H100; // 3rd pass
G68 X0 Y0 R270.; // rotate 270°
M98 H100; // 4th pass
G69; // rotation off
G15; // polar syntax off
M30; // main program end
N100 // path subprogram start
G90 G01 X50. Y9.207 R8.;
G03 X50. Y80.793 R50.;
G03 X50. Y99.207 R8.;
M99; // path subprogram return
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let ends = r.ends();
    assert_eq!(ends.len(), 2 + 4 * 3);
    assert_xy(ends[1], [49.356, 8.0], 1e-3);
    let arcs = r.arcs();
    for pass in 0..4 {
        let turn = 90.0 * pass as f64;
        assert_xy(ends[2 + 3 * pass], polar(50.0, 9.207 + turn), 1e-3);
        let (to, center, ccw, _) = arcs[2 * pass];
        assert_xy(to, polar(50.0, 80.793 + turn), 1e-3);
        assert_xy(center, [0.0, 0.0], 1e-3);
        assert!(ccw);
        let (to, center, ccw, _) = arcs[2 * pass + 1];
        assert_xy(to, polar(50.0, 99.207 + turn), 1e-3);
        assert_xy(center, polar(49.356, 90.0 + turn), 1e-3);
        assert!(ccw);
    }
    // The fourth pass ends at the start: the ring is closed.
    assert_xy(ends[13], [49.356, 8.0], 1e-3);
}

#[test]
fn e52_syntec_ring_of_eight_and_mirrored_small_flowers() {
    // E52: eight passes of N100 rotated 45° apart close the ring; N200 draws four R10
    // semicircles around (−80, 0), and mirrored about Y = −40 (commanded while N200's G91 is
    // active; the axis is absolute) around (−80, −80). `G50:` is read as G50.1, the mirror
    // cancel the manual means (`:` is OCR for `;`). The holes: six on the R75 circle from 30°
    // (G134), then a 3 × 3 grid from (60, −60) at 20 and −20 (G137.1).
    let text = "G54 X0 Y0 F3000.;
G16;                        // polar syntax on
G90 G00 X50. Y9.207 R8.;    // to the start point
M98 H100;                   // 1st pass
G68 X0 Y0 R45.;             // rotate 45°
M98 H100;                   // 2nd pass
G68 X0 Y0 R90.:             // rotate 90°
M98 H100;                   // 3rd pass
G68 X0 Y0 R135.;            // rotate 135°
M98 H100:                   // 4th pass
G68 X0 Y0 R180.;            // rotate 180°
M98 H100;                   // 5th pass
G68 X0 Y0 R225.;            // rotate 225°
M98 H100;                   // 6th pass
G68 X0 Y0 R270.;            // rotate 270°
M98 H100;                   // 7th pass
G68 X0 Y0 R315.;            // rotate 315°
M98 H100;                   // 8th pass
G69;                        // rotation off
G15;                        // polar syntax off
G00 X-80. Y0.
M98 H200;                   // machine the first small flower
G51.1 Y-40.;                // mirror about the Y-40. axis
M98 H200;                   // machine the second small flower
G50.1;                      // mirror off
G90 G81 Z-20. R2. F1000. K0;  // G81 drilling cycle mode on
G134 X0 Y0 I75. J30. K6;    // circle-pattern drilling
G137.1 X60. Y-60. I20. J-20. P3 K3; // grid-pattern drilling
G80;                        // drilling cycle off
M02;                        // main program end
N100                        // path subprogram
G90 G01 X50. Y9.207;
G03 X50. Y35.793 R50.;
G03 X50. Y54.207 R8.;
M99;                        // path subprogram return
N200                        // small-flower subprogram start
G90 G00 X-70. Y10.;
G91 G03 X-20. R10.;
G03 Y-20. R10.;
G03 X20. R10.;
G03 Y20. R10.;
M99;                        // small-flower subprogram return
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    assert!(
        r.errors().is_empty(),
        "{:#?}",
        r.diags
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .collect::<Vec<_>>()
    );
    let ends = r.ends();
    for pass in 0..8 {
        let turn = 45.0 * pass as f64;
        assert_xy(ends[2 + 3 * pass], polar(50.0, 9.207 + turn), 1e-3);
        assert_xy(ends[3 + 3 * pass], polar(50.0, 35.793 + turn), 1e-3);
        assert_xy(ends[4 + 3 * pass], polar(50.0, 54.207 + turn), 1e-3);
    }
    // The ring closes: the eighth pass ends at the first pass's start.
    assert_xy(ends[25], polar(50.0, 9.207), 1e-3);
    // The flowers: G00 X−80 Y0, then the rapid to the first petal and four semicircles, twice.
    assert_xy(ends[26], [-80.0, 0.0], 1e-9);
    let flower = |start: usize, points: [[f64; 2]; 5], ccw: bool| {
        for (i, p) in points.iter().enumerate() {
            assert_xy(ends[start + i], *p, 1e-9);
        }
        for (k, (_, e)) in r.moves()[start + 1..start + 5].iter().enumerate() {
            match e {
                Canon::Arc(Arc { ccw: c, .. }) => assert_eq!(*c, ccw, "petal {k}"),
                other => panic!("{other:?}"),
            }
        }
    };
    flower(
        27,
        [
            [-70.0, 10.0],
            [-90.0, 10.0],
            [-90.0, -10.0],
            [-70.0, -10.0],
            [-70.0, 10.0],
        ],
        true,
    );
    flower(
        32,
        [
            [-70.0, -90.0],
            [-90.0, -90.0],
            [-90.0, -70.0],
            [-70.0, -70.0],
            [-70.0, -90.0],
        ],
        false,
    );
    // The petals' centres lie 10 from the flower's centre.
    for (k, (_, c, _, _)) in r.arcs()[16..24].iter().enumerate() {
        let middle = if k < 4 { [-80.0, 0.0] } else { [-80.0, -80.0] };
        let d = (c.x - middle[0]).hypot(c.y - middle[1]);
        assert!((d - 10.0).abs() < 1e-9, "{k}: {c:?}");
    }
    let holes: Vec<[f64; 2]> = r
        .events
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Hole { top, bottom, .. } => {
                assert!((top.z - 2.0).abs() < 1e-9 && (bottom.z + 20.0).abs() < 1e-9);
                Some([top.x, top.y])
            }
            _ => None,
        })
        .collect();
    assert_eq!(holes.len(), 15);
    for (k, h) in holes[..6].iter().enumerate() {
        let a = (30.0 + 60.0 * k as f64).to_radians();
        assert_xy(
            DVec3::new(h[0], h[1], 0.0),
            [75.0 * a.cos(), 75.0 * a.sin()],
            1e-9,
        );
    }
    let mut grid: Vec<[f64; 2]> = holes[6..].to_vec();
    grid.sort_by(|a, b| a.partial_cmp(b).unwrap());
    let mut expected = Vec::new();
    for x in [60.0, 80.0, 100.0] {
        for y in [-100.0, -80.0, -60.0] {
            expected.push([x, y]);
        }
    }
    for (g, e) in grid.iter().zip(&expected) {
        assert!(
            (g[0] - e[0]).abs() < 1e-9 && (g[1] - e[1]).abs() < 1e-9,
            "{grid:?}"
        );
    }
}

#[test]
fn e66_syntec_g92_offsets() {
    // E66: after G92 the current point (20, 15, 20) reads (5, 10, 15): the G92 offsets are
    // X 15, Y 5, Z 5 (#1901–#1903); the last move's target is (40, 30, 40) in the old frame.
    let text = "G90 //absolute
G01 X20.0 Y15.0 Z20.0 //cut to X20.0 Y15.0 Z20.0; program coordinates are now X20.0 Y15.0 Z20.0
G92 X5.0 Y10.0 Z15.0; //current program coordinates become X5.0 Y10.0 Z15.0; G92 offsets X=15, Y=5, Z=5 (old program coordinate - new program coordinate)
G01 X25.0 Y25.0 Z35.0 //cut to the new program coordinates X25.0 Y25.0 Z35.0
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(&r.ends(), &[[20.0, 15.0, 20.0], [40.0, 30.0, 40.0]], 1e-9);
    // The offsets, read back through a machine-coordinate move.
    let r = run_in(
        &format!("{text}G53 X#1901 Y#1902 Z#1903\n"),
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert_at(r.ends()[2], [15.0, 5.0, 5.0], 1e-9);
}

#[test]
fn e67_syntec_g92_1_zero_point_preset_with_rotation() {
    // E67 (§4.55 example 3): after N2 the machine stays at (20, 20), the program position is
    // (14.142, 0), #1901/#1902 = (10, 10) and #1930 = 45; N3 G01 X100. goes to program
    // (100, 0) = machine (10, 10) + rot45°(100, 0) = (80.711, 80.711) (the manual's labels are
    // swapped; the reference derives this reading). K1. is not explained and not used.
    let text = "N1 G90 G0 X20. Y20.
N2 G92.1 X10. Y10. K1. R45.
N3 G01 X100.
N4 M30
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_eq!(r.lines(), [1, 3]);
    assert_path(&r.ends(), &[[20.0, 20.0, 0.0], [80.711, 80.711, 0.0]], 1e-3);
    // The program position and the system variables after N2, read back by G53 moves.
    let probe = "N1 G90 G0 X20. Y20.\nN2 G92.1 X10. Y10. K1. R45.\nG53 X#5001 Y#5002\nG53 X#1901 Y#1902 Z#1930\n";
    let r = run_in(probe, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_at(r.ends()[1], [14.142, 0.0, 0.0], 1e-3);
    assert_at(r.ends()[2], [10.0, 10.0, 45.0], 1e-9);
}

#[test]
fn e68_syntec_g93_feed_from_length_and_radius() {
    // E68: Syntec's G93: F × the block's length for G01, F × the radius for G02/G03:
    // 1 × 10 = 10, 3 × 5 = 15, 5 × 10 = 50 mm/min.
    let text = "G71
G93
G01 X10. F1 // feed of this block 1*10 = 10 mm/min
G02 X20. R5. F3 // feed of this block 3*5 = 15 mm/min
G03 X0 R10. F5 // feed of this block 5*10 = 50 mm/min
M30
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_eq!(r.feeds(), [10.0, 15.0, 50.0]);
    assert_path(
        &r.ends(),
        &[[10.0, 0.0, 0.0], [20.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
        1e-9,
    );
    // F applies to its own block only: a cutting block without F is alarm Cor85.
    let r = run_in(
        "G93\nG01 X10. F1\nX20.\n",
        Dialect::Syntec,
        Setup::default(),
    );
    assert_eq!(r.errors(), ["E-NO-FEED"]);
    assert!(r.diags[0].message.contains("Cor85"));
}

#[test]
fn e69_syntec_g96_surface_speed_clamped_by_g92_s() {
    // E69: with a 10 mm cutter, 130 m/min is 1000 × 130 / (π × 10) = 4138 rpm (the manual
    // prints 4140), clamped by `G92 S2000` to 2000; `G97 S1300` holds 1300 rpm. The cutter is
    // tool 1 with radius 5 in the setup, selected by `T1` (the example names no tool). `G92 S`
    // is the clamp, not a speed and not a move.
    let cutter = "[registers.1]\nradius = 5.0\n";
    let rpms = |r: &Run| -> Vec<f64> {
        r.events
            .iter()
            .filter_map(|(_, e)| match e {
                Canon::Spindle { rpm, .. } => Some(*rpm),
                _ => None,
            })
            .collect()
    };
    let text = "T1;\nG92 S2000; //G92 limits the maximum spindle speed\nG96 S130 M03;//cutting speed held at 130 m/min\nG97 S1300 M03; //spindle held at 1300 rpm\n";
    let r = run_in(text, Dialect::Syntec, setup(cutter));
    r.assert_no_errors();
    assert!(r.ends().is_empty());
    assert_eq!(rpms(&r), [2000.0, 1300.0]);
    let r = run_in("T1;\nG96 S130 M03;\n", Dialect::Syntec, setup(cutter));
    let rpm = rpms(&r)[0];
    assert!((rpm - 4138.0).abs() < 0.1, "{rpm}");
}

#[test]
fn e74_syntec_t_s_and_f_words() {
    // E74: `T03 M06` changes to tool 3; `G97 S500 M03` is 500 rpm; F300 under G94 is 300
    // mm/min and F0.5 under G95 is 0.5 mm/rev, i.e. 250 mm/min at 500 rpm (derived). `G96 S150`
    // needs the cutter's diameter, which the example does not give (a note says so). `S1=150`
    // addresses spindle 1 and is reported as not interpreted.
    let text = "T03 M06; //select and change to tool 3
G96 S150 M03; //constant surface speed, 150 m/min
G97 S500 M03; //spindle held at 500 rpm
G94 G01 X100.0 Y100.0 F300;
//linear cut, 300 mm/min
G95 G01 X100.0 Y100.0 F0.5;
//linear cut, 0.5 mm/rev
M03 S1=150
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert!(matches!(r.events[0].1, Canon::ToolChange { tool: 3 }));
    assert!(r.codes().contains(&"N-CSS-DIAMETER"));
    assert!(r.codes().contains(&"W-NOT-INTERPRETED"));
    assert_eq!(r.feeds(), [300.0, 250.0]);
    assert!(r.events.iter().any(|(_, e)| *e
        == Canon::Spindle {
            clockwise: Some(true),
            rpm: 500.0
        }));
}

#[test]
fn e75_syntec_interrupt_program_square_and_modal_restore() {
    // E75: without the C49 signal (a backplot has none) the main program just cuts its square;
    // M96/M97 are reported as not interpreted. `X10,` is OCR for `X10.`. The interrupt
    // subprogram's body is run on its own from a G01 G91 state: `#30 := #1000` and
    // `#31 := #1004` save the modes, G00 Z100. changes them, `G#30 G#31` restores them, so the
    // move after M00 (added here) is an incremental feed.
    let main = "M96 P1111\nG00 X0 Y0 Z0\nG01 X10. F500\nY10.\nX0\nY0\nM97\nM30\n";
    let r = run_in(main, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_eq!(
        r.codes()
            .iter()
            .filter(|c| **c == "W-NOT-INTERPRETED")
            .count(),
        2
    );
    assert_path(
        &r.ends(),
        &[
            [0.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [10.0, 10.0, 0.0],
            [0.0, 10.0, 0.0],
            [0.0, 0.0, 0.0],
        ],
        1e-9,
    );
    let sub = "G91 G01 X1. F100
#30 := #1000; // save modal: G00/G01/G02/G03
#31 := #1004; // save modal: G90/G91
G00 Z100.; // rapid to the Z tool-check point
G#30 G#31; // restore the modal state
M00; // after M00 you may switch to manual mode and jog the axes
X5.
";
    let r = run_in(sub, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[[1.0, 0.0, 0.0], [1.0, 0.0, 100.0], [6.0, 0.0, 100.0]],
        1e-9,
    );
    assert!(matches!(r.moves()[2].1, Canon::Feed { .. }));
    assert!(
        r.events
            .iter()
            .any(|(_, e)| *e == Canon::Pause { optional: false })
    );
}

// ---------------------------------------------------------------------------------------------
// Codes without a worked example (or whose behaviour differs by dialect)
// ---------------------------------------------------------------------------------------------

#[test]
fn g04_dwell_units_per_dialect() {
    // §4.4: Syntec X with a point is seconds, without it ms, P ms (fraction dropped); LNC P and X
    // in seconds; KT's example P2000 = 2 s (ms, like Fanuc, whose X is seconds with a point);
    // LinuxCNC P in seconds. (GSK's 988TD list has no G04; its P is the cycles' dwell.)
    let cases: [(Dialect, &str, f64); 11] = [
        (Dialect::Syntec, "G04 X2500;", 2.5),
        (Dialect::Syntec, "G04 X2.5;", 2.5),
        (Dialect::Syntec, "G04 P2500;", 2.5),
        (Dialect::Syntec, "G04 P2.5;", 0.002),
        (Dialect::Lnc, "G04 P2.;", 2.0),
        (Dialect::Lnc, "G04 X1.5;", 1.5),
        (Dialect::Kt, "G04 P2000;", 2.0),
        (Dialect::Fanuc, "G04 P1500;", 1.5),
        (Dialect::Fanuc, "G04 X1.5;", 1.5),
        (Dialect::Fanuc, "G04 X1500;", 1.5),
        (Dialect::LinuxCnc, "G4 P1.5", 1.5),
    ];
    for (dialect, text, secs) in cases {
        let r = run_in(&format!("{text}\n"), dialect, Setup::default());
        r.assert_no_errors();
        assert_eq!(r.dwells(), [secs], "{dialect}: {text}");
    }
    // G04 without a time is an error.
    let r = run_in("G04;\n", Dialect::Lnc, Setup::default());
    assert_eq!(r.errors(), ["E-WORD-MISSING"]);
}

#[test]
fn syntec_g70_g71_inch_and_metric() {
    // §4.36: Syntec's G70/G71 are inch/metric (Fanuc's G20/G21). In inch an integer is
    // 0.0001 inch; centre offsets and feeds follow the unit.
    let r = run_in(
        "G70 G00 X1. Y10000;\nG01 X2. F10.;\nG71 G00 X1.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert_path(
        &r.ends(),
        &[[25.4, 25.4, 0.0], [50.8, 25.4, 0.0], [1.0, 25.4, 0.0]],
        1e-9,
    );
    assert!((r.feeds()[0] - 254.0).abs() < 1e-9);
    // Fanuc and LinuxCNC: G20/G21.
    for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
        let r = run_in("G20 G00 X1.\nG21 G00 X1.\n", dialect, Setup::default());
        r.assert_no_errors();
        assert_path(&r.ends(), &[[25.4, 0.0, 0.0], [1.0, 0.0, 0.0]], 1e-9);
    }
}

#[test]
fn g53_in_g91_per_dialect() {
    // §4.30: Syntec runs G53 only in G90 (in G91 the block is a plain incremental move), LNC
    // calls it invalid in G91, Fanuc ignores it there; LinuxCNC refuses the block.
    for dialect in [Dialect::Syntec, Dialect::Lnc, Dialect::Fanuc] {
        let r = run_in("G00 X10. Y10.\nG91 G53 X5.\n", dialect, Setup::default());
        r.assert_no_errors();
        assert!(r.codes().contains(&"W-G53-INCREMENTAL"), "{dialect}");
        assert_at(r.ends()[1], [15.0, 10.0, 0.0], 1e-9);
    }
    let r = run_in(
        "G0 X10 Y10\nG91 G53 X5\n",
        Dialect::LinuxCnc,
        Setup::default(),
    );
    assert_eq!(r.errors(), ["E-G53-INCREMENTAL"]);
    assert_eq!(r.ends().len(), 1);
    // In G90 it is a one-shot move in machine coordinates, unaffected by the work offset and
    // by rotation (LNC §4.30).
    let s = setup("[work_offsets]\nG54 = [100.0, 0.0, 0.0]\n");
    let r = run_in(
        "G68 X0. Y0. R90.;\nG53 X5. Y0.;\nX0. Y0.;\n",
        Dialect::Lnc,
        s,
    );
    r.assert_no_errors();
    // Back in the rotated work system: its origin is at (100, 0).
    assert_path(&r.ends(), &[[5.0, 0.0, 0.0], [100.0, 0.0, 0.0]], 1e-9);
}

#[test]
fn lnc_g68_needs_its_angle() {
    // LNC §4.35: R omitted is an alarm (Syntec and KT do not say; Swarf warns and turns 0°).
    let r = run_in(
        "G68 X0. Y0.;\nG01 X10. F100.;\n",
        Dialect::Lnc,
        Setup::default(),
    );
    assert_eq!(r.errors(), ["E-WORD-MISSING"]);
    assert_at(r.ends()[0], [10.0, 0.0, 0.0], 1e-9);
    let r = run_in(
        "G68 X0. Y0.;\nG01 X10. F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert!(r.codes().contains(&"W-WORD-MISSING"));
}

#[test]
fn lnc_g54_1_and_g10_l20_l2() {
    // LNC §4.9/§4.32: G10 L20 Pn sets the extended system n (G90 replaces, G91 adds), G54.1 Pn
    // selects it; G10 L2 P1 the G54 origin.
    let text = "G90 G10 L20 P3 X50. Y20.;
G91 G10 L20 P3 X5.;
G90 G54.1 P3 G00 X0. Y0.;
G10 L2 P1 X-10.;
G54 X0. Y0.;
";
    let r = run_in(text, Dialect::Lnc, Setup::default());
    r.assert_no_errors();
    assert_path(&r.ends(), &[[55.0, 20.0, 0.0], [-10.0, 0.0, 0.0]], 1e-9);
}

#[test]
fn syntec_g59_1_and_g10_register_data() {
    // Syntec §4.32: G59.1–G59.9 are systems 7–15 (from the setup here). §4.9: G10 L10 writes
    // the H geometry (G90 replaces, G91 adds); G43 H then places the gauge line the length
    // above the tip, which G53 shows.
    let s = setup("[work_offsets]\n\"G59.3\" = [1.0, 2.0, 3.0]\n");
    let r = run_in("G59.3 G00 X0. Y0. Z0.;\n", Dialect::Syntec, s);
    r.assert_no_errors();
    assert_at(r.ends()[0], [1.0, 2.0, 3.0], 1e-9);
    let text = "G90 G10 L10 P1 R40.;\nG91 G10 L10 P1 R2.;\nG90 G43 H1 Z0.;\nG53 Z0.;\n";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(&r.ends(), &[[0.0, 0.0, 0.0], [0.0, 0.0, -42.0]], 1e-9);
}

#[test]
fn syntec_planes_g18_g19_arcs() {
    // §4.3: G18 arcs are in ZX with I/K, G19 in YZ with J/K; the third axis moves linearly.
    let r = run_in(
        "G00 X10. Y0. Z0.;\nG18 G02 X0. Z10. I-10. K0. Y5. F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    match r.moves()[1].1 {
        Canon::Arc(Arc {
            to, center, axis, ..
        }) => {
            assert_at(*to, [0.0, 5.0, 10.0], 1e-9);
            assert_at(*center, [0.0, 0.0, 0.0], 1e-9);
            assert_eq!(*axis, Axis::Y);
        }
        other => panic!("{other:?}"),
    }
    let r = run_in(
        "G00 X0. Y10. Z0.;\nG19 G03 Y0. Z10. R10. F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    match r.moves()[1].1 {
        Canon::Arc(Arc {
            center, axis, ccw, ..
        }) => {
            assert_at(*center, [0.0, 0.0, 0.0], 1e-9);
            assert_eq!(*axis, Axis::X);
            assert!(*ccw);
        }
        other => panic!("{other:?}"),
    }
    // K in a G17 arc is COR-006-style inconsistent: ignored with a warning here.
    let r = run_in(
        "G00 X10.;\nG17 G03 X-10. I-10. K3. F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert!(r.codes().contains(&"W-WORD-IGNORED"));
}

#[test]
fn lnc_arc_end_off_the_circle_changes_radius_and_syntec_alarms() {
    // §4.3 LNC note 5: an end point off the circle makes the radius change progressively (a
    // warning); Syntec alarms COR-006 unless L makes it a spiral.
    let r = run_in(
        "G00 X10.;\nG03 X-12. Y0. I-10. F100.;\n",
        Dialect::Lnc,
        Setup::default(),
    );
    r.assert_no_errors();
    assert!(r.codes().contains(&"W-ARC-SPIRAL"));
    assert_at(r.arcs()[0].0, [-12.0, 0.0, 0.0], 1e-9);
    let r = run_in(
        "G00 X10.;\nG03 X-12. Y0. I-10. F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    assert_eq!(r.errors(), ["E-ARC-RADIUS"]);
    // With L the same block is a spiral of one turn.
    let r = run_in(
        "G00 X10.;\nG03 X-12. Y0. I-10. L1 F100.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert_eq!(r.arcs()[0].3, 0);
}

#[test]
fn syntec_g09_g61_g64_do_not_change_the_path() {
    // §4.8/§4.33: exact stop and the cutting modes change how corners are run, not where.
    let r = run_in(
        "G61 G01 X10. F100.;\nG09 X20.;\nG64 X30.;\nG62 P1 X40.;\nG63 X50.;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    assert_eq!(r.ends().len(), 5);
    assert_at(r.ends()[4], [50.0, 0.0, 0.0], 1e-9);
}

#[test]
fn syntec_polar_coordinates_with_g00() {
    // §4.11 Syntec: X radius, Y angle (+ CCW); under G91 both add to the previous point's.
    // E29's holes at 100 mm, 90°/210°/330° with G00 instead of the G81 cycle.
    let r = run_in(
        "G17 G90 G16;\nG00 X100.0 Y90.0;\nY210.0;\nY330.0;\nG91 Y120.0;\nG15;\n",
        Dialect::Syntec,
        Setup::default(),
    );
    r.assert_no_errors();
    let ends = r.ends();
    assert_xy(ends[0], [0.0, 100.0], 1e-3);
    assert_xy(ends[1], [-86.603, -50.0], 1e-3);
    assert_xy(ends[2], [86.603, -50.0], 1e-3);
    assert_xy(ends[3], [0.0, 100.0], 1e-3);
}

#[test]
fn syntec_g52_local_system_and_its_cancel() {
    // §4.29: G52 sets a local system inside the work system; `G52 X0 Y0 Z0` cancels it. The
    // "+" slot of E46 (N012–N031, without the drilling) in local coordinates about (30, 30).
    let text = "N012 G52 X30.0 Y30.0 Z0.0;
N013 G00 X0.0 Y0.0 Z10.0;
N014 G01 Z-12.0;
N016 G91 X20.0;
N017 Y10.0;
N018 X-10.0;
N019 Y10.0;
N020 X-20.0;
N021 Y-10.0;
N022 X-10.0;
N023 Y-20.0;
N024 X10.0;
N025 Y-10.0;
N026 X20.0;
N027 Y10.0;
N028 X10.0;
N029 Y10.0;
N030 G90 G00 Z10.0;
N031 G52 X0.0 Y0.0 Z0.0;
G00 X0.0 Y0.0;
";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let local = [
        [0.0, 0.0],
        [20.0, 0.0],
        [20.0, 10.0],
        [10.0, 10.0],
        [10.0, 20.0],
        [-10.0, 20.0],
        [-10.0, 10.0],
        [-20.0, 10.0],
        [-20.0, -10.0],
        [-10.0, -10.0],
        [-10.0, -20.0],
        [10.0, -20.0],
        [10.0, -10.0],
        [20.0, -10.0],
        [20.0, 0.0],
    ];
    let ends = r.ends();
    for (k, p) in local.iter().enumerate() {
        assert_xy(ends[k + 1], [p[0] + 30.0, p[1] + 30.0], 1e-9);
    }
    assert_at(ends[16], [50.0, 30.0, 10.0], 1e-9);
    assert_at(ends[17], [0.0, 0.0, 10.0], 1e-9);
}

#[test]
fn m_codes_stop_spindle_coolant_and_end() {
    // §5.1: M00/M01 pause, M03/M04/M05 spindle, M06 tool change with T, M08/M09 coolant,
    // M02/M30 end (nothing runs after). M99 in a subprogram with P returns to that block.
    let text = "T5 M06;\nS800 M03;\nM04;\nM05;\nM08;\nM09;\nM00;\nM01;\nM30;\nG00 X1.;\n";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    let events: Vec<Canon> = r.events.iter().map(|(_, e)| e.clone()).collect();
    assert_eq!(
        events,
        [
            Canon::ToolChange { tool: 5 },
            Canon::Spindle {
                clockwise: Some(true),
                rpm: 800.0
            },
            Canon::Spindle {
                clockwise: Some(false),
                rpm: 800.0
            },
            Canon::Spindle {
                clockwise: None,
                rpm: 0.0
            },
            Canon::Coolant { on: true },
            Canon::Coolant { on: false },
            Canon::Pause { optional: false },
            Canon::Pause { optional: true },
            Canon::End,
        ]
    );
    // Syntec `M99 P`: back to the main program's N label instead of the block after the call.
    let text = "M98 H100;\nG00 X1.;\nN20 G00 Y1.;\nM30;\nN100 G00 Z1.;\nM99 P20;\n";
    let r = run_in(text, Dialect::Syntec, Setup::default());
    r.assert_no_errors();
    assert_path(&r.ends(), &[[0.0, 0.0, 1.0], [0.0, 1.0, 1.0]], 1e-9);
}

#[test]
fn g95_feed_per_revolution_needs_a_spindle_speed() {
    // §4.57: F per revolution × rpm is the feed; with no S the move cannot feed (Fanuc family
    // and LinuxCNC alike).
    let r = run_in(
        "S1000\nG95 G01 X10. F0.1\n",
        Dialect::Fanuc,
        Setup::default(),
    );
    r.assert_no_errors();
    assert_eq!(r.feeds(), [100.0]);
    let r = run_in("G95 G01 X10. F0.1\n", Dialect::Fanuc, Setup::default());
    assert_eq!(r.errors(), ["E-NO-FEED"]);
    // LinuxCNC's G93: the move takes 1/F minutes, so the feed is F × its length.
    let r = run_in("G93 G1 X10 F2\n", Dialect::LinuxCnc, Setup::default());
    r.assert_no_errors();
    assert_eq!(r.feeds(), [20.0]);
}
