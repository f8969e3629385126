//! Cutter radius compensation G41/G42/G40: start-up and cancel, corners of lines and arcs in
//! both corner modes, arcs whose radius changes by the offset, helices, the lookahead over blocks
//! without plane motion, gouge reports, compensation under G68, G16 and G51.1, and the manuals'
//! examples (Syntec §1.24's flower groove, §1.29's mirrored flower).
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use glam::{DVec2, DVec3};
use swarf_interp::{Arc, Canon, CornerMode, Register, Setup, Sink, Source, run};
use swarf_syntax::{Diagnostic, Dialect, Severity, parse};

/// Keeps the emitted (compensated) events and the programmed contour beside them.
#[derive(Default)]
struct Both {
    events: Vec<(Source, Canon)>,
    programmed: Vec<(Source, Canon)>,
}

impl Sink for Both {
    fn emit(&mut self, source: Source, event: &Canon) {
        self.events.push((source, event.clone()));
    }
    fn programmed(&mut self, source: Source, event: &Canon) {
        self.programmed.push((source, event.clone()));
    }
}

struct Out {
    events: Vec<(Source, Canon)>,
    programmed: Vec<(Source, Canon)>,
    diags: Vec<Diagnostic>,
}

impl Out {
    fn codes(&self) -> Vec<&'static str> {
        self.diags.iter().map(|d| d.code).collect()
    }
    fn errors(&self) -> Vec<&Diagnostic> {
        self.diags
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .collect()
    }
    /// The motion events (line, event).
    fn moves(&self) -> Vec<(u32, Canon)> {
        self.events
            .iter()
            .filter(|(_, e)| e.end_point().is_some())
            .map(|(s, e)| (s.line, e.clone()))
            .collect()
    }
    fn ends(&self) -> Vec<DVec3> {
        self.moves()
            .iter()
            .filter_map(|(_, e)| e.end_point())
            .collect()
    }
}

fn setup_with(radius: f64, mode: Option<CornerMode>) -> Setup {
    let mut s = Setup::default();
    s.registers.insert(
        1,
        Register {
            radius,
            ..Register::default()
        },
    );
    s.machine.corner_mode = mode;
    s
}

fn run_in(text: &str, dialect: Dialect, setup: Setup) -> Out {
    let program = parse(text, dialect);
    let mut sink = Both::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, setup, &mut sink));
    Out {
        events: sink.events,
        programmed: sink.programmed,
        diags,
    }
}

fn assert_at(p: DVec3, want: [f64; 3], tol: f64) {
    assert!(
        p.abs_diff_eq(DVec3::from_array(want), tol),
        "{p} is not at {want:?}"
    );
}

/// A piece of a path in the XY plane: a line, or an arc about `center`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    a: DVec2,
    b: DVec2,
    arc: Option<(DVec2, bool)>,
}

fn xy(p: DVec3) -> DVec2 {
    DVec2::new(p.x, p.y)
}

/// The angle from `a` to `b` about `c` in the arc's direction, in (0, 2π] (a full turn when
/// they meet).
fn sweep(a: DVec2, b: DVec2, c: DVec2, ccw: bool) -> f64 {
    let (pa, pb) = (a - c, b - c);
    let mut s = pb.y.atan2(pb.x) - pa.y.atan2(pa.x);
    if !ccw {
        s = -s;
    }
    let s = s.rem_euclid(std::f64::consts::TAU);
    if s < 1e-12 { std::f64::consts::TAU } else { s }
}

impl Piece {
    fn distance(&self, p: DVec2) -> f64 {
        match self.arc {
            None => {
                let d = self.b - self.a;
                let t = if d.length_squared() < 1e-18 {
                    0.0
                } else {
                    ((p - self.a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
                };
                (self.a + d * t - p).length()
            }
            Some((c, ccw)) => {
                let r = (self.a - c).length();
                let full = sweep(self.a, self.b, c, ccw);
                let at = sweep(self.a, p, c, ccw);
                let ends = (p - self.a).length().min((p - self.b).length());
                if at <= full + 1e-12 {
                    ((p - c).length() - r).abs().min(ends)
                } else {
                    ends
                }
            }
        }
    }
    fn point(&self, t: f64) -> DVec2 {
        match self.arc {
            None => self.a + (self.b - self.a) * t,
            Some((c, ccw)) => {
                let r = (self.a - c).length();
                let a0 = (self.a - c).y.atan2((self.a - c).x);
                let s = sweep(self.a, self.b, c, ccw) * t;
                let a = if ccw { a0 + s } else { a0 - s };
                c + DVec2::new(a.cos(), a.sin()) * r
            }
        }
    }
    /// The left normal of the direction of travel at `t`.
    fn left_normal(&self, t: f64) -> DVec2 {
        let tangent = match self.arc {
            None => (self.b - self.a).normalize(),
            Some((c, ccw)) => {
                let r = self.point(t) - c;
                let l = DVec2::new(-r.y, r.x).normalize();
                if ccw { l } else { -l }
            }
        };
        DVec2::new(-tangent.y, tangent.x)
    }
}

/// The XY pieces of a stream of motion events starting at `from`, with the line of each.
fn pieces(events: &[(u32, Canon)], mut from: DVec3) -> Vec<(u32, Piece)> {
    let mut out = Vec::new();
    for (line, e) in events {
        let to = e.end_point().unwrap();
        let arc = match e {
            Canon::Arc(Arc { center, ccw, .. }) => Some((xy(*center), *ccw)),
            _ => None,
        };
        if (xy(to) - xy(from)).length() > 1e-12 || arc.is_some() {
            out.push((
                *line,
                Piece {
                    a: xy(from),
                    b: xy(to),
                    arc,
                },
            ));
        }
        from = to;
    }
    out
}

fn distance_to(pieces: &[Piece], p: DVec2) -> f64 {
    pieces
        .iter()
        .map(|q| q.distance(p))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn outside_corners_get_an_arc_in_linuxcnc() {
    // A 20 mm square cut clockwise with the tool on its left: outside corners.
    let text =
        "G21 G17 G90 G00 X0 Y-10\nG41 D1 G01 X0 Y0 F100\nY20\nX20\nY0\nX0\nG40 G00 X-10\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let moves = r.moves();
    // Entry to (0, 0) + 2 left of the entry direction (+Y) = (−2, 0).
    assert_at(moves[1].1.end_point().unwrap(), [-2.0, 0.0, 0.0], 1e-9);
    // Up the left side 2 mm out, round the corner (0, 20) on an arc of radius 2.
    let arcs: Vec<_> = moves
        .iter()
        .filter_map(|(_, e)| match e {
            Canon::Arc(Arc {
                to, center, ccw, ..
            }) => Some((*to, *center, *ccw)),
            _ => None,
        })
        .collect();
    assert_eq!(arcs.len(), 3, "{moves:?}");
    let corners = [[0.0, 20.0], [20.0, 20.0], [20.0, 0.0]];
    for ((to, center, ccw), c) in arcs.iter().zip(corners) {
        assert_at(*center, [c[0], c[1], 0.0], 1e-9);
        assert!((xy(*to) - DVec2::from_array(c)).length() - 2.0 < 1e-9);
        assert!(
            !ccw,
            "the tool on the left of a clockwise path goes round clockwise"
        );
    }
    // The cancel move goes from the compensated point to the programmed one.
    assert_at(*r.ends().last().unwrap(), [-10.0, 0.0, 0.0], 1e-9);
}

#[test]
fn outside_corners_meet_at_the_intersection_in_fanuc() {
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nX20.\nY0\nX0\nG40 G00 X-10.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let ends = r.ends();
    // Type A start-up: to the next block's start vector (0, 0) + 2 left of +Y = (−2, 0).
    assert_at(ends[1], [-2.0, 0.0, 0.0], 1e-9);
    assert_at(ends[2], [-2.0, 22.0, 0.0], 1e-9);
    assert_at(ends[3], [22.0, 22.0, 0.0], 1e-9);
    assert_at(ends[4], [22.0, -2.0, 0.0], 1e-9);
    // The last side ends square to its end before the cancel move.
    assert_at(ends[5], [0.0, -2.0, 0.0], 1e-9);
    assert_at(ends[6], [-10.0, 0.0, 0.0], 1e-9);
    assert!(r.moves().iter().all(|(_, e)| !matches!(e, Canon::Arc(_))));
}

#[test]
fn sharp_outside_corners_get_two_extra_vectors() {
    // A 30° spike: the path turns by 150°, sharper than 90°, so the Fanuc family adds two
    // vectors of the radius along the moves instead of going out to the far intersection.
    let a = 150f64.to_radians();
    let (x, y) = (20.0 + 20.0 * a.cos(), 20.0 * a.sin());
    let text = format!(
        "G90 G00 X0 Y-10.\nG42 D1 G01 X0 Y0 F100.\nX20.\nX{x:.6} Y{y:.6}\nG40 G00 X0 Y-10.\nM30\n"
    );
    let r = run_in(&text, Dialect::Fanuc, setup_with(1.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let ends = r.ends();
    // (20, 0) offset right of +X is (20, −1); extended 1 along +X: (21, −1).
    assert_at(ends[2], [21.0, -1.0, 0.0], 1e-5);
    // The second vector: (20, 0) + right normal of the second move − 1 along it.
    let t2 = DVec2::new(a.cos(), a.sin());
    let n2 = DVec2::new(t2.y, -t2.x);
    let v2 = DVec2::new(20.0, 0.0) + n2 - t2;
    assert_at(ends[3], [v2.x, v2.y, 0.0], 1e-5);
    // Then along the offset of the second move.
    let end = DVec2::new(x, y) + n2;
    assert_at(ends[4], [end.x, end.y, 0.0], 1e-6);
}

#[test]
fn inside_corners_end_at_the_intersection() {
    // A pocket: the square counter-clockwise with the tool on the left, inside.
    let text = "G90 G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100.\nX20.\nY20.\nX0\nY0\nX10.\nG40 G00 X10. Y10.\nM30\n";
    for dialect in [Dialect::Fanuc, Dialect::Syntec] {
        let r = run_in(text, dialect, setup_with(2.0, None));
        assert!(r.errors().is_empty(), "{:?}", r.diags);
        let ends = r.ends();
        for (i, want) in [[18.0, 2.0], [18.0, 18.0], [2.0, 18.0], [2.0, 2.0]]
            .iter()
            .enumerate()
        {
            assert_at(ends[i + 2], [want[0], want[1], 0.0], 1e-9);
        }
    }
}

#[test]
fn arcs_grow_or_shrink_by_the_offset() {
    // A full circle of radius 10 counter-clockwise: G41 cuts inside (8), G42 outside (12).
    for (code, radius) in [("G41", 8.0), ("G42", 12.0)] {
        let text =
            format!("G90 G00 X0 Y0\n{code} D1 G01 X10. Y0 F100.\nG03 I-10.\nG40 G01 X0 Y0\nM30\n");
        let r = run_in(&text, Dialect::Fanuc, setup_with(2.0, None));
        assert!(r.errors().is_empty(), "{:?}", r.diags);
        let (start, (to, center)) = {
            let moves = r.moves();
            let i = moves
                .iter()
                .position(|(_, e)| matches!(e, Canon::Arc(_)))
                .unwrap();
            let start = moves[i - 1].1.end_point().unwrap();
            match &moves[i].1 {
                Canon::Arc(Arc { to, center, .. }) => (start, (*to, *center)),
                _ => unreachable!(),
            }
        };
        assert_at(center, [0.0, 0.0, 0.0], 1e-9);
        assert!(
            (start.distance(center) - radius).abs() < 1e-9,
            "{code}: {start}"
        );
        assert!((to.distance(center) - radius).abs() < 1e-9, "{code}: {to}");
    }
}

#[test]
fn a_helix_keeps_its_depth_change() {
    let text = "G90 G00 X0 Y0 Z0\nG42 D1 G01 X10. Y0 F100.\nG02 X-10. Y0 Z-5. R10.\nG01 X-20.\nG40 G00 X0 Y0\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(1.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let moves = r.moves();
    let (start, arc) = moves
        .windows(2)
        .find_map(|w| match &w[1].1 {
            Canon::Arc(Arc { to, center, .. }) => {
                Some((w[0].1.end_point().unwrap(), (*to, *center)))
            }
            _ => None,
        })
        .unwrap();
    // Right of a clockwise arc is inside: radius 9, from Z0 down to Z−5.
    assert!((xy(start) - xy(arc.1)).length() - 9.0 < 1e-9);
    assert!((start.z - 0.0).abs() < 1e-12);
    assert!((arc.0.z + 5.0).abs() < 1e-12);
    assert!((xy(arc.0) - xy(arc.1)).length() - 9.0 < 1e-9);
}

#[test]
fn a_negative_radius_swaps_the_side() {
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nX20.\nG40 G00 X20. Y-10.\nM30\n";
    let mut s = setup_with(0.0, None);
    s.registers.insert(
        1,
        Register {
            radius: 3.0,
            radius_wear: -5.0,
            ..Register::default()
        },
    );
    let r = run_in(text, Dialect::Fanuc, s);
    // Geometry 3 plus wear −5: −2, so G41 cuts 2 to the right: the inside corner of the
    // start-up up +Y and the move along +X is at (2, −2).
    let ends = r.ends();
    assert_at(ends[1], [2.0, -2.0, 0.0], 1e-9);
}

#[test]
fn blocks_without_plane_motion_wait_behind_the_corner() {
    // One Z move between two cutting blocks: the corner is still an intersection, and the Z
    // move happens there.
    let text = "G90 G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100.\nX20.\nZ-1.\nY20.\nG40 G01 Y30.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(!r.codes().contains(&"W-COMP-LOOKAHEAD"), "{:?}", r.diags);
    let ends = r.ends();
    assert_at(ends[2], [18.0, 2.0, 0.0], 1e-9);
    assert_at(ends[3], [18.0, 2.0, -1.0], 1e-9);
    assert_at(ends[4], [18.0, 20.0, -1.0], 1e-9);
    // Two blocks without plane motion are more than the Fanuc family looks ahead: the first
    // move ends square to its end, reported.
    let text = "G90 G00 X10. Y10.\nG41 D1 G01 X0 Y0 F100.\nX20.\nZ-1.\nM08\nY20.\nG40 G00 X10. Y10.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    let warning = r
        .diags
        .iter()
        .find(|d| d.code == "W-COMP-LOOKAHEAD")
        .expect("lookahead warning");
    assert!(warning.message.contains("line 3") && warning.message.contains("line 6"));
    assert_at(r.ends()[2], [20.0, 2.0, 0.0], 1e-9);
    // LinuxCNC waits for the next move whatever comes between.
    let text = "G21 G90 G00 X10 Y10\nG41 D1 G01 X0 Y0 F100\nX20\nZ-1\nM8\nG4 P1\nY20\nG40 G00 X10 Y10\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    assert!(
        r.ends()
            .iter()
            .any(|p| p.abs_diff_eq(DVec3::new(18.0, 2.0, -1.0), 1e-9))
    );
}

#[test]
fn a_groove_narrower_than_the_tool_is_reported_naming_both_blocks() {
    // A 3 mm step down and up again: with a 4 mm radius tool on the inside, the bottom's
    // compensated move runs backwards.
    let text = "G90 G00 X0 Y10.\nG41 D1 G01 X0 Y0 F100.\nX10.\nY-5.\nX13.\nY0\nX30.\nG40 G00 X30. Y10.\nM30\n";
    let r = run_in(text, Dialect::Syntec, setup_with(4.0, None));
    let gouge = r
        .diags
        .iter()
        .find(|d| d.code == "W-COMP-GOUGE")
        .unwrap_or_else(|| panic!("{:?}", r.diags));
    assert_eq!(gouge.severity, Severity::Warning);
    assert!(
        gouge.message.contains("line 5")
            && gouge.message.contains("line 4")
            && gouge.message.contains("line 6"),
        "{}",
        gouge.message
    );
    // The path is still drawn to the end.
    assert_at(*r.ends().last().unwrap(), [30.0, 10.0, 0.0], 1e-9);
    // Parameter 3819 makes it an alarm that stops the run.
    let mut s = setup_with(4.0, None);
    s.machine.overcut_alarm = true;
    let r = run_in(text, Dialect::Syntec, s);
    assert!(r.codes().contains(&"E-COMP-GOUGE"), "{:?}", r.diags);
    assert!(
        !r.ends()
            .iter()
            .any(|p| p.abs_diff_eq(DVec3::new(30.0, 10.0, 0.0), 1e-9))
    );
}

#[test]
fn an_inside_arc_smaller_than_the_tool_is_reported() {
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nG03 X4. Y0 R2.\nG01 X10.\nG40 G00 X10. Y-10.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(3.0, None));
    assert!(r.codes().contains(&"W-COMP-GOUGE"), "{:?}", r.diags);
}

#[test]
fn start_up_and_cancel_only_in_g00_g01_blocks() {
    // G41 in an arc block is refused by the same-block rules; in arc mode (G02 from a block
    // before) the control alarms and stops.
    let text = "G90 G00 X0 Y0\nG41 D1 G02 X10. Y0 R5. F100.\nG01 X20.\nM30\n";
    let r = run_in(text, Dialect::Syntec, setup_with(1.0, None));
    assert!(r.codes().contains(&"E-SAME-BLOCK"), "{:?}", r.diags);
    let text = "G90 G00 X0 Y0\nG02 X10. Y0 R5. F100.\nG41 D1 X20. Y0 R5.\nG01 X30.\nM30\n";
    let r = run_in(text, Dialect::Syntec, setup_with(1.0, None));
    assert!(r.codes().contains(&"E-COMP-ARC"), "{:?}", r.diags);
    assert_eq!(r.ends().len(), 2, "the control stops at the alarm");
    // LinuxCNC starts on an arc, but the move after G40 must be straight.
    let text = "G21 G90 G00 X0 Y0\nG41 D1 G02 X10 Y0 R5 F100\nG40\nG03 X0 Y0 R5\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(1.0, None));
    assert!(r.codes().contains(&"E-COMP-CANCEL"), "{:?}", r.diags);
}

#[test]
fn canned_cycles_ignore_compensation() {
    let text = "G90 G00 X0 Y0 Z10.\nG41 D1 G01 X10. Y0 F100.\nG81 X20. Y0 Z-5. R2.\nG80\nG40 G00 X0 Y0\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    // The hole is drilled at the programmed point.
    assert!(
        r.ends()
            .iter()
            .any(|p| p.abs_diff_eq(DVec3::new(20.0, 0.0, -5.0), 1e-9)),
        "{:?}",
        r.ends()
    );
}

/// The square of `outside_corners_meet_at_the_intersection_in_fanuc` under a frame change:
/// the compensated path is the frame's image of the unchanged one.
fn square_under(frame_on: &str, frame_off: &str) -> Vec<DVec3> {
    let text = format!(
        "{frame_on}\nG90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nX20.\nY0\nX0\nG40 G00 X-10.\n{frame_off}\nM30\n"
    );
    let r = run_in(&text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    r.ends()
}

#[test]
fn compensation_follows_rotation() {
    let plain = square_under("", "");
    let turned = square_under("G68 X0 Y0 R30.", "G69");
    let (s, c) = 30f64.to_radians().sin_cos();
    for (p, q) in plain.iter().zip(&turned) {
        let want = [p.x * c - p.y * s, p.x * s + p.y * c, p.z];
        assert_at(*q, want, 1e-9);
    }
}

#[test]
fn compensation_follows_polar_input() {
    // The same square in polar coordinates about the origin.
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nG16\nX20. Y90.\nX28.284271 Y45.\nX20. Y0\nG15\nX0 Y0\nG40 G00 X-10.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let plain = square_under("", "");
    for (p, q) in plain.iter().zip(r.ends().iter()) {
        assert!(p.abs_diff_eq(*q, 1e-5), "{p} vs {q}");
    }
}

#[test]
fn the_programmed_contour_is_kept_beside_the_compensated_one() {
    let text = "G90 G00 X-10. Y0\nG41 D1 G01 X0 Y0 F100.\nY20.\nX20.\nG40 G00 X30.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    let programmed: Vec<DVec3> = r
        .programmed
        .iter()
        .filter_map(|(_, e)| e.end_point())
        .collect();
    // The start-up, the two sides and the cancel move, as programmed.
    assert_eq!(programmed.len(), 4, "{programmed:?}");
    assert_at(programmed[1], [0.0, 20.0, 0.0], 1e-12);
    assert_at(programmed[2], [20.0, 20.0, 0.0], 1e-12);
    // And the moves before compensation are not repeated there.
    assert!(!programmed.contains(&DVec3::new(-10.0, 0.0, 0.0)));
}

#[test]
fn e38_syntec_flower_groove_is_cut_5_mm_left_of_the_contour() {
    // §1.24 with a 10 mm end mill (D01 = 5): the CCW R10 arcs are cut inside (R5), the CW R15
    // arcs outside (R20), about the programmed centres; the start-up goes from the origin to
    // A's start vector and G40 returns to the origin.
    let text = "N001 T1 S1000 M03;
N002 G00 X0.0 Y0.0 Z10.0;
N003 M08;
N004 G90 G01 Z-10.0 F600;
N005 G41 Y24.0 D01;
N006 G03 X9.0 Y30.0 R10.0;
N007 G02 X30.0 Y9.0 R15.0;
N008 G03 X30.0 Y-9.0 R10.0;
N009 G02 X9.0 Y-30.0 R15.0;
N010 G03 X-9.0 Y-30.0 R10.0;
N011 G02 X-30.0 Y-9.0 R15.0;
N012 G03 X-30.0 Y9.0 R10.0;
N013 G02 X-9.0 Y30.0 R15.0;
N014 G03 X0.0 Y24.0 R10.0;
N015 G00 Z10.0;
N016 G40 X0.0 Y0.0;
N017 M09;
N018 M05;
N019 M30;
";
    let r = run_in(text, Dialect::Syntec, setup_with(5.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    assert!(!r.codes().contains(&"W-COMP-GOUGE"), "{:?}", r.diags);
    let moves = r.moves();
    let mut from = DVec3::ZERO;
    let mut arcs = 0;
    for (line, e) in &moves {
        if let Canon::Arc(Arc {
            to, center, ccw, ..
        }) = e
        {
            let want = if *ccw { 5.0 } else { 20.0 };
            assert!((from.distance(*center) - want).abs() < 1e-9, "line {line}");
            assert!((to.distance(*center) - want).abs() < 1e-9, "line {line}");
            // The programmed arc of the block has the same centre.
            let programmed = r
                .programmed
                .iter()
                .find(|(s, _)| s.line == *line)
                .map(|(_, e)| e.clone());
            match programmed {
                Some(Canon::Arc(Arc { center: c, .. })) => assert_at(*center, c.to_array(), 1e-9),
                other => panic!("line {line}: {other:?}"),
            }
            arcs += 1;
        }
        from = e.end_point().unwrap();
    }
    assert_eq!(arcs, 9);
    assert_at(*r.ends().last().unwrap(), [0.0, 0.0, 10.0], 1e-9);
}

#[test]
fn e45_syntec_mirrored_flower_is_cut_alike_in_every_quadrant() {
    // §1.29 with D01 = 5: G41 on the first quadrant, G42 on the single-axis mirrors (which
    // reverse the path), G41 on the point mirror. Every quadrant's arcs are cut inside: the R8
    // arcs at R3 and the R50 arcs at R45, about the mirrored centres.
    let main = "N001 T1 S1000 M03;
N002 G41 D01;
N003 M98 H100;
N004 G42 D01;
N005 G51.1 X0.0;
N006 M98 H100;
N007 G50.1;
N008 G41 D01;
N009 G51.1 X0.0 Y0.0;
N010 M98 H100;
N011 G50.1;
N012 G42 D01;
N013 G51.1 Y0.0;
N014 M98 H100;
N015 G50.1;
N016 G40;
N017 M05;
N018 M30;
N100;
G00 X58.0 Y0.0 Z10.0;
G01 Z-10.0;
G03 X49.36 Y7.9744 R8.0;
G03 X40.5415 Y29.2641 R50.0;
G03 X29.2641 Y40.5415 R8.0;
G03 X7.9744 Y49.36 R50.0;
G03 X0.0 Y58.0 R8.0;
G00 Z10.0;
M99;
";
    let r = run_in(main, Dialect::Syntec, setup_with(5.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let moves = r.moves();
    let mut from = DVec3::ZERO;
    let mut radii = Vec::new();
    for (_, e) in &moves {
        if let Canon::Arc(Arc { to, center, .. }) = e {
            let r0 = from.distance(*center);
            assert!((to.distance(*center) - r0).abs() < 1e-6);
            radii.push(r0);
        }
        from = e.end_point().unwrap();
    }
    // Arcs of the corner moves aside, each quadrant cuts R3, R45, R3, R45, R3.
    let cut: Vec<f64> = radii
        .iter()
        .copied()
        .filter(|r| (r - 3.0).abs() < 1e-3 || (r - 45.0).abs() < 1e-3)
        .collect();
    assert_eq!(cut.len(), 20, "{radii:?}");
    for (k, r) in cut.iter().enumerate() {
        let want = if k % 5 == 1 || k % 5 == 3 { 45.0 } else { 3.0 };
        assert!((r - want).abs() < 1e-3, "arc {k}: {r}");
    }
}

/// The square of `square_under` under a mirror of X about 0, in `dialect`, with `code` on
/// the square and the setup's `mirror_swaps_comp_side`.
fn mirrored_square(dialect: Dialect, code: &str, swaps: Option<bool>) -> Vec<DVec3> {
    let text = format!(
        "G51.1 X0\nG90 G00 X0 Y-10.\n{code} D1 G01 X0 Y0 F100.\nY20.\nX20.\nY0\nX0\nG40 G00 X-10.\nG50.1\nM30\n"
    );
    let mut setup = setup_with(2.0, None);
    setup.machine.mirror_swaps_comp_side = swaps;
    let r = run_in(&text, dialect, setup);
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    r.ends()
}

fn is_mirror_image(plain: &[DVec3], mirrored: &[DVec3]) -> bool {
    plain.len() == mirrored.len()
        && plain
            .iter()
            .zip(mirrored)
            .all(|(p, q)| q.abs_diff_eq(DVec3::new(-p.x, p.y, p.z), 1e-9))
}

#[test]
fn fanuc_swaps_g41_and_g42_under_a_mirror() {
    let plain = square_under("", "");
    // Fanuc's programmable mirror image swaps the side itself: the same G41 cuts the mirror
    // image of the unmirrored square.
    let mirrored = mirrored_square(Dialect::Fanuc, "G41", None);
    assert!(is_mirror_image(&plain, &mirrored), "{mirrored:?}");
    // Taken as written instead, G41 cuts the other side of the mirrored path.
    let as_written = mirrored_square(Dialect::Fanuc, "G41", Some(false));
    assert!(!is_mirror_image(&plain, &as_written));
    assert!(is_mirror_image(
        &plain,
        &mirrored_square(Dialect::Fanuc, "G42", Some(false))
    ));
}

#[test]
fn syntec_takes_the_side_as_written_under_a_mirror() {
    // §1.29's flower swaps G41/G42 in the program for the single-axis mirrors.
    let plain = square_under("", "");
    assert!(is_mirror_image(
        &plain,
        &mirrored_square(Dialect::Syntec, "G42", None)
    ));
    assert!(!is_mirror_image(
        &plain,
        &mirrored_square(Dialect::Syntec, "G41", None)
    ));
    // The setup's key makes it swap like Fanuc.
    assert!(is_mirror_image(
        &plain,
        &mirrored_square(Dialect::Syntec, "G41", Some(true))
    ));
}

#[test]
fn a_point_mirror_keeps_the_side() {
    // Both plane axes mirrored: the path keeps its turning direction, nothing is swapped.
    let text = "G51.1 X0 Y0\nG90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nX20.\nY0\nX0\nG40 G00 X-10.\nG50.1\nM30\n";
    let plain = square_under("", "");
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    for (p, q) in plain.iter().zip(r.ends().iter()) {
        assert_at(*q, [-p.x, -p.y, p.z], 1e-9);
    }
}

#[test]
fn fanuc_changes_side_at_the_intersection_of_the_two_offset_paths() {
    // Up the Y axis with G41 (2 left: X−2), then G42 along X (2 right: Y18). The paths meet
    // at (−2, 18): the first move ends there and the second starts there.
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nG42 X20.\nG40 G01 X20. Y30.\nM30\n";
    for dialect in [Dialect::Fanuc, Dialect::Syntec, Dialect::Lnc] {
        let r = run_in(text, dialect, setup_with(2.0, None));
        assert!(r.errors().is_empty(), "{:?}", r.diags);
        let ends = r.ends();
        assert_at(ends[2], [-2.0, 18.0, 0.0], 1e-9);
        assert_at(ends[3], [20.0, 18.0, 0.0], 1e-9);
        assert_at(ends[4], [20.0, 30.0, 0.0], 1e-9);
        assert_eq!(ends.len(), 5, "no move across: {ends:?}");
        assert!(!r.codes().contains(&"W-COMP-GOUGE"), "{:?}", r.diags);
    }
    // Where the paths do not meet (straight on), the first move ends square to its end and
    // the tool crosses to the second's start vector.
    let text =
        "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nG42 Y40.\nG40 G01 X-10. Y40.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let ends = r.ends();
    assert_at(ends[2], [-2.0, 20.0, 0.0], 1e-9);
    assert_at(ends[3], [2.0, 20.0, 0.0], 1e-9);
    assert_at(ends[4], [2.0, 40.0, 0.0], 1e-9);
    // A line into an arc: G42 up X0 to (0, 20) runs at X2; G41, then G02 over the top about
    // (10, 20) cuts outside, radius 12. The line meets that circle first at
    // (2, 20 + √80), ahead of both: the line runs on to it and the arc starts there.
    let text = "G90 G00 X0 Y-10.\nG42 D1 G01 X0 Y0 F100.\nY20.\nG41\nG02 X20. Y20. I10.\nG40 G01 X20. Y0\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup_with(2.0, None));
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    let moves = r.moves();
    assert_at(
        moves[2].1.end_point().unwrap(),
        [2.0, 20.0 + 80f64.sqrt(), 0.0],
        1e-9,
    );
    match &moves[3].1 {
        Canon::Arc(Arc {
            to, center, ccw, ..
        }) => {
            assert_at(*center, [10.0, 20.0, 0.0], 1e-9);
            assert_at(*to, [22.0, 20.0, 0.0], 1e-9);
            assert!(!ccw);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn fanuc_applies_a_new_radius_from_the_end_of_its_block() {
    // D1 = 2, D2 = 4. The corner before the block with D2 is still the old radius's
    // (the intersection (−2, 22)); the block ends at the new offset (Y24) and runs slanted.
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nD2 X20.\nG40 G01 X20. Y0\nM30\n";
    let mut setup = setup_with(2.0, None);
    setup.registers.insert(
        2,
        Register {
            radius: 4.0,
            ..Register::default()
        },
    );
    for dialect in [Dialect::Fanuc, Dialect::Syntec] {
        let r = run_in(text, dialect, setup.clone());
        assert!(r.errors().is_empty(), "{:?}", r.diags);
        let ends = r.ends();
        assert_at(ends[2], [-2.0, 22.0, 0.0], 1e-9);
        assert_at(ends[3], [20.0, 24.0, 0.0], 1e-9);
    }
    // Straight on, the new radius also comes in over the block.
    let text = "G90 G00 X0 Y-10.\nG41 D1 G01 X0 Y0 F100.\nY20.\nD2 Y40.\nG40 G01 X10. Y40.\nM30\n";
    let r = run_in(text, Dialect::Fanuc, setup);
    let ends = r.ends();
    assert_at(ends[2], [-2.0, 20.0, 0.0], 1e-9);
    assert_at(ends[3], [-4.0, 40.0, 0.0], 1e-9);
}

#[test]
fn linuxcnc_changes_side_or_radius_only_through_g40() {
    // rs274: "Cannot turn cutter radius comp on when on", and a D word alone has no use.
    let text = "G21 G90 G00 X0 Y-10\nG41 D1 G01 X0 Y0 F100\nY20\nG42 X20\nY0\nG40 G00 X-10\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(2.0, None));
    assert!(r.codes().contains(&"E-COMP-ON"), "{:?}", r.diags);
    assert!(
        !r.ends()
            .iter()
            .any(|p| p.abs_diff_eq(DVec3::new(-10.0, 0.0, 0.0), 1e-9)),
        "the run stops at the error"
    );
    let text = "G21 G90 G00 X0 Y-10\nG41 D1 G01 X0 Y0 F100\nY20\nD2 X20\nY0\nG40 G00 X-10\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(2.0, None));
    let e = r
        .diags
        .iter()
        .find(|d| d.code == "E-WORD-UNUSED")
        .unwrap_or_else(|| panic!("{:?}", r.diags));
    assert_eq!(e.severity, Severity::Error);
    // The run stops there; the held move is sent on square to its end.
    let ends = r.ends();
    assert_eq!(ends.len(), 3, "{ends:?}");
    assert_at(ends[2], [-2.0, 20.0, 0.0], 1e-9);
    // With G96, D is the spindle speed limit.
    let text = "G21 G90 G96 D2000 S100 G00 X10 Y0\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup_with(2.0, None));
    assert!(!r.codes().contains(&"E-WORD-UNUSED"), "{:?}", r.diags);
}

/// The events of a G18 turning pass with compensation by register 1 (radius 0.5) of
/// orientation `o`.
fn turning_pass(dialect: Dialect, o: u8) -> Vec<(u32, Canon)> {
    let text = "G18 G90 G00 X20. Z5.\nG42 D1 G01 X10. Z0 F100.\nZ-10.\nG02 X14. Z-14. R4.\nG01 X20.\nG40 G00 X30. Z5.\nM30\n";
    let mut setup = Setup::default();
    setup.registers.insert(
        1,
        Register {
            radius: 0.5,
            orientation: o,
            ..Register::default()
        },
    );
    let r = run_in(text, dialect, setup);
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    r.moves()
}

#[test]
fn a_lathe_tool_reports_its_imaginary_tip() {
    // LinuxCNC's table: orientation → where the tip is from the nose centre (X, Z), in radii.
    let tip = [
        (1, [-1.0, 1.0]),
        (2, [-1.0, -1.0]),
        (3, [1.0, -1.0]),
        (4, [1.0, 1.0]),
        (5, [0.0, 1.0]),
        (6, [-1.0, 0.0]),
        (7, [0.0, -1.0]),
        (8, [1.0, 0.0]),
        (9, [0.0, 0.0]),
    ];
    for dialect in [Dialect::LinuxCnc, Dialect::Fanuc] {
        let centre = turning_pass(dialect, 0);
        for (o, [dx, dz]) in tip {
            let moves = turning_pass(dialect, o);
            assert_eq!(moves.len(), centre.len());
            let d = DVec3::new(dx * 0.5, 0.0, dz * 0.5);
            for ((line, a), (_, b)) in centre.iter().zip(&moves) {
                // The rapid before compensation and the cancel move are not shifted.
                let shift = if (2..=5).contains(line) {
                    d
                } else {
                    DVec3::ZERO
                };
                assert_at(
                    b.end_point().unwrap(),
                    (a.end_point().unwrap() + shift).to_array(),
                    1e-9,
                );
                if let (Canon::Arc(Arc { center: ca, .. }), Canon::Arc(Arc { center: cb, .. })) =
                    (a, b)
                {
                    assert_at(*cb, (*ca + shift).to_array(), 1e-9);
                }
            }
        }
    }
}

#[test]
fn linuxcnc_lathe_tools_compensate_in_g18_only() {
    let mut setup = Setup::default();
    setup.registers.insert(
        1,
        Register {
            radius: 0.5,
            orientation: 2,
            ..Register::default()
        },
    );
    let text = "G17 G21 G90 G00 X20 Y5\nG42 D1 G01 X10 Y0 F100\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, setup);
    assert!(r.codes().contains(&"E-COMP-PLANE"), "{:?}", r.diags);
    // G41.1/G42.1 take the orientation in L, in G18 only.
    let text = "G17 G21 G90 G00 X20 Y5\nG42.1 D1 L2 G01 X10 Y0 F100\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, Setup::default());
    assert!(r.codes().contains(&"E-COMP-PLANE"), "{:?}", r.diags);
    let with_l = "G18 G21 G90 G00 X20 Z5\nG42.1 D1 L3 G01 X10 Z0 F100\nZ-10\nG40 G00 X30\nM2\n";
    let without = "G18 G21 G90 G00 X20 Z5\nG42.1 D1 G01 X10 Z0 F100\nZ-10\nG40 G00 X30\nM2\n";
    let a = run_in(with_l, Dialect::LinuxCnc, Setup::default());
    let b = run_in(without, Dialect::LinuxCnc, Setup::default());
    assert!(a.errors().is_empty(), "{:?}", a.diags);
    // Orientation 3: the tip is +X −Z of the nose centre.
    assert_at(
        a.ends()[2],
        (b.ends()[2] + DVec3::new(0.5, 0.0, -0.5)).to_array(),
        1e-9,
    );
}

#[test]
fn linuxcnc_comp_turned_on_and_off_without_a_move_leaves_the_tool_alone() {
    // LinuxCNC's ccomp/early-exit: G41.1 then G40 with no move between; the next rapid moves
    // X only (LinuxCNC 2.6.12 and 2.7.7 sent Y and Z to 0).
    let text = "G20 G90 G0 X0.1 Y0.2 Z0.3\nG41.1 D0.1\nG40\nG0 X0.9\nM2\n";
    let r = run_in(text, Dialect::LinuxCnc, Setup::default());
    assert!(r.errors().is_empty(), "{:?}", r.diags);
    assert_at(
        *r.ends().last().unwrap(),
        [0.9 * 25.4, 0.2 * 25.4, 0.3 * 25.4],
        1e-9,
    );
}

#[cfg(not(target_arch = "wasm32"))]
mod properties {
    use super::*;
    use proptest::prelude::*;

    /// A closed contour around the origin: vertices at increasing angles, each side a line or
    /// an arc bulging by `bulge` times its chord (positive: outwards), programmed with R and
    /// three decimals so that the numbers the control reads are the contour's.
    fn contour_program(
        vertices: &[(f64, f64)],
        bulges: &[f64],
        code: &str,
    ) -> (String, Vec<Piece>) {
        let round = |v: f64| (v * 1000.0).round() / 1000.0;
        let points: Vec<DVec2> = vertices
            .iter()
            .map(|(a, r)| DVec2::new(round(r * a.cos()), round(r * a.sin())))
            .collect();
        let mut text = format!(
            "G90 G17 G00 X0 Y0\n{code} D1 G01 X{:.3} Y{:.3} F100.\n",
            points[0].x, points[0].y
        );
        let mut pieces = Vec::new();
        let n = points.len();
        // Round the contour, then once more along the first two sides to close the last
        // corner (the last side cut, before G40, is not checked: the cancel ends it).
        for k in 0..n + 2 {
            let (a, b) = (points[k % n], points[(k + 1) % n]);
            let bulge = bulges[k % n];
            if bulge.abs() < 0.02 {
                text.push_str(&format!("G01 X{:.3} Y{:.3}\n", b.x, b.y));
                pieces.push(Piece { a, b, arc: None });
            } else {
                // Sagitta h = bulge·chord; the contour runs counter-clockwise about the origin,
                // so an outward bulge is a clockwise arc. A short arc: its centre is left of
                // the chord when counter-clockwise.
                let chord = (b - a).length();
                let h = bulge.abs() * chord;
                let radius = round((chord * chord / 4.0 + h * h) / (2.0 * h));
                let ccw = bulge < 0.0;
                let d = (b - a) / chord;
                let left = DVec2::new(-d.y, d.x);
                let depth = (radius * radius - chord * chord / 4.0).max(0.0).sqrt();
                let center = (a + b) / 2.0 + left * if ccw { depth } else { -depth };
                let g = if ccw { "G03" } else { "G02" };
                text.push_str(&format!("{g} X{:.3} Y{:.3} R{radius:.3}\n", b.x, b.y));
                pieces.push(Piece {
                    a,
                    b,
                    arc: Some((center, ccw)),
                });
            }
        }
        text.push_str("G40 G01 X0 Y0\nM30\n");
        pieces.truncate(n);
        (text, pieces)
    }

    fn contour() -> impl Strategy<Value = (Vec<(f64, f64)>, Vec<f64>)> {
        // At least five vertices, no side spanning more than a third of the turn: the sides
        // and their bulges cannot cross each other.
        (5usize..9).prop_flat_map(|n| {
            (
                proptest::collection::vec((0.5f64..1.0, 40.0f64..60.0), n),
                proptest::collection::vec(
                    // Bulges small enough that two neighbouring dents never make a narrow
                    // crevasse (which gouges far from any corner, like on a control).
                    prop_oneof![Just(0.0), -0.12f64..-0.03, 0.03f64..0.12],
                    n,
                ),
            )
                .prop_map(move |(steps, bulges)| {
                    let total: f64 = steps.iter().map(|s| s.0).sum();
                    let mut angle = 0.0;
                    let vertices = steps
                        .iter()
                        .map(|(s, r)| {
                            let v = (angle, *r);
                            angle += s / total * std::f64::consts::TAU;
                            v
                        })
                        .collect();
                    (vertices, bulges)
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        #[test]
        fn compensated_paths_keep_the_radius(
            (vertices, bulges) in contour(),
            radius in 0.5f64..3.0,
            left in any::<bool>(),
            arc_mode in any::<bool>(),
        ) {
            let code = if left { "G41" } else { "G42" };
            let (text, contour) = contour_program(&vertices, &bulges, code);
            let mode = if arc_mode { CornerMode::Arc } else { CornerMode::Intersection };
            let r = run_in(&text, Dialect::Fanuc, setup_with(radius, Some(mode)));
            prop_assert!(r.errors().is_empty(), "{:?}\n{text}", r.diags);
            let gouged = r.codes().contains(&"W-COMP-GOUGE");
            let last_line = text.lines().count() as u32 - 1;
            let path = pieces(&r.moves(), DVec3::ZERO);
            // The start-up (line 2) and the cancel move (the line before the end) start or end
            // on the programmed path, and decide how the first side starts and the last side
            // ends; both are cut twice, and everything between is checked.
            let cut: Vec<Piece> = path
                .iter()
                .filter(|(l, _)| *l > 3 && *l < last_line - 1)
                .map(|(_, p)| *p)
                .collect();
            prop_assert!(cut.len() >= vertices.len(), "{text}");
            for piece in &cut {
                for i in 0..=16 {
                    let p = piece.point(f64::from(i) / 16.0);
                    let d = distance_to(&contour, p);
                    if !gouged {
                        prop_assert!(d > radius - 1e-6, "{p} is {d} from the contour\n{text}");
                    }
                    if arc_mode && !gouged {
                        prop_assert!((d - radius).abs() < 1e-6, "{p} is {d} from the contour\n{text}");
                    }
                }
            }
            if !gouged {
                let all: Vec<Piece> = path.iter().map(|(_, p)| *p).collect();
                let s = if left { radius } else { -radius };
                for piece in &contour {
                    let m = piece.point(0.5) + piece.left_normal(0.5) * s;
                    let d = distance_to(&all, m);
                    prop_assert!(d < 1e-6, "the offset midpoint {m} is {d} off the path\n{text}");
                }
            }
        }
    }
}
