//! Canonical machine events: what the control does, independent of how it was programmed.

use glam::DVec3;
use serde_json::{Value, json};
use swarf_syntax::codes::Code;

use crate::Sink;
use crate::state::plane_axes;

/// The block an event came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Source {
    /// Index of the block in `Program::blocks`.
    pub block: u32,
    /// 1-based line of the block in the text.
    pub line: u32,
}

/// A plane normal: the axis an arc turns around (`as usize`, its index: X 0, Y 1, Z 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Axis {
    /// G19 (YZ plane).
    X,
    /// G18 (ZX plane).
    Y,
    /// G17 (XY plane), the power-on plane.
    #[default]
    Z,
}

impl Axis {
    /// Lowercase name as used in the canonical JSON.
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self as usize]
    }
}

/// The length of (`du`, `dv`): `du.hypot(dv)` to within an ulp, a few times faster where the sum of
/// the squares neither overflows nor underflows (every arc is measured with it).
#[inline]
pub fn plane_length(du: f64, dv: f64) -> f64 {
    let squared = du * du + dv * dv;
    if (1e-280..1e280).contains(&squared) {
        squared.sqrt()
    } else {
        du.hypot(dv)
    }
}

/// The signed angle (radians, counter-clockwise positive) an arc turns through, an end at the start
/// a full turn, plus `turns` more; shared with the toolpath.
#[inline]
pub fn plane_sweep(start: (f64, f64), end: (f64, f64), ccw: bool, turns: u32) -> f64 {
    let ((su, sv), (eu, ev)) = (start, end);
    let mut sweep = if start == (0.0, 0.0) || end == (0.0, 0.0) {
        ev.atan2(eu) - sv.atan2(su)
    } else {
        (su * ev - sv * eu).atan2(su * eu + sv * ev)
    };
    let tau = std::f64::consts::TAU;
    if ccw {
        if sweep <= 1e-12 {
            sweep += tau;
        }
    } else if sweep >= -1e-12 {
        sweep -= tau;
    }
    sweep + f64::from(turns) * tau * sweep.signum()
}

/// An arc event's geometry in its plane (centre, both ends' radii and offsets, sweep), shared by
/// the stroke checks and the toolpath's chords so both put the points in the same places.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneArc {
    /// The plane's first axis (0 = X, 1 = Y, 2 = Z): angles are measured from it.
    pub iu: usize,
    /// The plane's second axis, a quarter turn counter-clockwise from `iu`.
    pub iv: usize,
    /// The plane normal's axis, along which a helix rises.
    pub iw: usize,
    /// The centre (its coordinate along the normal is not used).
    pub center: DVec3,
    /// The start's distance from the centre in the plane.
    pub radius: f64,
    /// The end's distance from the centre in the plane (a spiral's differs from `radius`).
    pub end_radius: f64,
    /// The signed angle turned through ([`plane_sweep`]).
    pub sweep: f64,
    /// The start's offset from the centre in (`iu`, `iv`).
    pub start_offset: (f64, f64),
    /// The end's offset from the centre in (`iu`, `iv`).
    pub end_offset: (f64, f64),
}

impl PlaneArc {
    /// The arc from `from` to `to` about `center` and `axis`, with `turns` extra turns.
    #[inline]
    pub fn new(from: DVec3, to: DVec3, center: DVec3, axis: Axis, ccw: bool, turns: u32) -> Self {
        let (iu, iv) = plane_axes(axis);
        let iw = 3 - iu - iv;
        let rel = |p: DVec3| (p[iu] - center[iu], p[iv] - center[iv]);
        let (start_offset, end_offset) = (rel(from), rel(to));
        PlaneArc {
            iu,
            iv,
            iw,
            center,
            radius: plane_length(start_offset.0, start_offset.1),
            end_radius: plane_length(end_offset.0, end_offset.1),
            sweep: plane_sweep(start_offset, end_offset, ccw, turns),
            start_offset,
            end_offset,
        }
    }

    /// The start's angle in the plane (only the points between the ends need it).
    #[inline]
    pub fn start_angle(&self) -> f64 {
        let (su, sv) = self.start_offset;
        sv.atan2(su)
    }

    /// How many even steps keep every chord within `tolerance` mm of the arc (1 to 100 000).
    pub fn chords(&self, tolerance: f64) -> usize {
        let step = if self.radius > tolerance {
            2.0 * (1.0 - tolerance / self.radius).acos()
        } else {
            std::f64::consts::TAU / 4.0
        };
        ((self.sweep.abs() / step.max(1e-3)).ceil() as usize).clamp(1, 100_000)
    }

    /// The ends of `n` even steps along the arc (at least one), the last exactly `to`.
    pub fn points(&self, from: DVec3, to: DVec3, n: usize) -> impl Iterator<Item = DVec3> + use<> {
        let (arc, n) = (*self, n.max(1));
        let a0 = if n > 1 { self.start_angle() } else { 0.0 };
        // Angle, radius and rise each change evenly with the step.
        let between = move |k: usize| {
            let t = k as f64 / n as f64;
            let a = a0 + arc.sweep * t;
            let r = arc.radius + (arc.end_radius - arc.radius) * t;
            let mut p = DVec3::ZERO;
            p[arc.iu] = arc.center[arc.iu] + r * a.cos();
            p[arc.iv] = arc.center[arc.iv] + r * a.sin();
            p[arc.iw] = from[arc.iw] + (to[arc.iw] - from[arc.iw]) * t;
            p
        };
        (1..n).map(between).chain(std::iter::once(to))
    }
}

/// A circular or helical cutting move ([`Canon::Arc`]); its start is where the move before ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// End point.
    pub to: DVec3,
    /// Centre (its coordinate along `axis` is the start's).
    pub center: DVec3,
    /// Plane normal.
    pub axis: Axis,
    /// Counter-clockwise as seen from the positive end of `axis`.
    pub ccw: bool,
    /// Extra full turns beyond the first.
    pub turns: u32,
    /// Feed rate in mm/min.
    pub feed_mm_per_min: f64,
}

impl Arc {
    /// The arc's geometry in its plane, starting at `from`.
    #[inline]
    pub fn plane(&self, from: DVec3) -> PlaneArc {
        PlaneArc::new(from, self.to, self.center, self.axis, self.ccw, self.turns)
    }
}

/// One canonical event. Positions are millimetres in the machine frame, at the tool tip.
#[derive(Debug, Clone, PartialEq)]
pub enum Canon {
    /// Rapid positioning (G00) to `to`.
    Rapid {
        /// End point.
        to: DVec3,
    },
    /// Straight cutting move to `to` at `feed_mm_per_min`.
    Feed {
        /// End point.
        to: DVec3,
        /// Feed rate in mm/min.
        feed_mm_per_min: f64,
    },
    /// Circular or helical cutting move.
    Arc(Arc),
    /// A pause with the axes still.
    Dwell {
        /// Duration in seconds.
        secs: f64,
    },
    /// Tool change to tool `tool` (M06 with the selected T).
    ToolChange {
        /// The tool number.
        tool: u32,
    },
    /// Spindle on (clockwise or counter-clockwise) at `rpm`, or off.
    Spindle {
        /// `Some(true)` clockwise (M03), `Some(false)` counter-clockwise (M04), `None` stop (M05).
        clockwise: Option<bool>,
        /// Programmed speed.
        rpm: f64,
    },
    /// Oriented spindle stop (G76, G87), so the boring bar can shift away from the wall.
    Orient,
    /// The start of a canned cycle's hole: the motions up to the next `Hole` or block drill it.
    Hole {
        /// The cycle's G code in tenths (810 for G81, 831 for G83.1).
        cycle: u32,
        /// The hole's number in the run, from 1.
        index: u32,
        /// Where the hole starts: the R point (machine frame).
        top: DVec3,
        /// The hole's bottom (machine frame).
        bottom: DVec3,
    },
    /// Coolant on (M08) or off (M09).
    Coolant {
        /// Whether coolant flows after this event.
        on: bool,
    },
    /// Program stop M00 (`optional` for M01).
    Pause {
        /// Whether it is an optional stop.
        optional: bool,
    },
    /// End of program (M02/M30).
    End,
}

impl Canon {
    /// A straight move to `to`: a rapid when `rapid`, else a feed at `feed_mm_per_min`.
    pub fn line(rapid: bool, to: DVec3, feed_mm_per_min: f64) -> Canon {
        if rapid {
            Canon::Rapid { to }
        } else {
            Canon::Feed {
                to,
                feed_mm_per_min,
            }
        }
    }

    /// The end point for motion events.
    pub fn end_point(&self) -> Option<DVec3> {
        match self {
            Canon::Rapid { to } | Canon::Feed { to, .. } | Canon::Arc(Arc { to, .. }) => Some(*to),
            _ => None,
        }
    }

    /// The event as one JSON object of the `swarf canon` stream.
    pub fn to_json(&self, source: Source) -> Value {
        let p = |v: DVec3| json!([round(v.x), round(v.y), round(v.z)]);
        let fields = match self {
            Canon::Rapid { to } => json!({"kind": "rapid", "to": p(*to)}),
            Canon::Feed {
                to,
                feed_mm_per_min: f,
            } => json!({"kind": "feed", "to": p(*to), "feed": round(*f)}),
            Canon::Arc(a) => json!({
                "kind": "arc", "to": p(a.to), "center": p(a.center), "axis": a.axis.name(),
                "dir": if a.ccw { "ccw" } else { "cw" }, "turns": a.turns, "feed": round(a.feed_mm_per_min),
            }),
            Canon::Dwell { secs } => json!({"kind": "dwell", "secs": round(*secs)}),
            Canon::ToolChange { tool } => json!({"kind": "tool_change", "tool": tool}),
            Canon::Spindle { clockwise, rpm } => json!({
                "kind": "spindle",
                "dir": match clockwise { Some(true) => "cw", Some(false) => "ccw", None => "off" },
                "rpm": round(*rpm),
            }),
            Canon::Coolant { on } => json!({"kind": "coolant", "on": on}),
            Canon::Orient => json!({"kind": "orient"}),
            Canon::Hole {
                cycle: c,
                index: i,
                top: t,
                bottom: b,
            } => json!({
                "kind": "hole", "cycle": Code::g(*c).to_string(), "index": i, "top": p(*t), "bottom": p(*b),
            }),
            Canon::Pause { optional } => json!({"kind": "pause", "optional": optional}),
            Canon::End => json!({"kind": "end"}),
        };
        let mut out = json!({ "line": source.line });
        if let (Some(out), Value::Object(fields)) = (out.as_object_mut(), fields) {
            out.extend(fields);
        }
        out
    }
}

/// Rounds to 6 decimals (a nanometre) so printed streams are stable across platforms.
fn round(v: f64) -> f64 {
    let r = (v * 1e6).round() / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

/// A sink that keeps every event, for tests and the CLI.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CanonRecorder {
    /// The events in execution order.
    pub events: Vec<(Source, Canon)>,
}

impl Sink for CanonRecorder {
    fn emit(&mut self, source: Source, event: &Canon) {
        self.events.push((source, event.clone()));
    }
}

#[cfg(test)]
#[cfg(not(target_arch = "wasm32"))]
mod tests {
    use super::{Axis, PlaneArc, plane_length, plane_sweep};
    use glam::DVec3;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI, TAU};

    /// The distance in units in the last place between two finite non-negative numbers.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn plane_length_falls_back_where_the_squares_overflow_or_underflow() {
        assert_eq!(plane_length(0.0, 0.0), 0.0);
        assert_eq!(plane_length(3.0, -4.0), 5.0);
        assert_eq!(plane_length(3e300, 4e300), 3e300_f64.hypot(4e300));
        assert_eq!(plane_length(3e-300, 4e-300), 3e-300_f64.hypot(4e-300));
        assert_eq!(plane_length(f64::INFINITY, 1.0), f64::INFINITY);
        assert!(plane_length(f64::NAN, 1.0).is_nan());
    }

    #[test]
    fn plane_sweep_turns_the_programmed_way() {
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        // A quarter counter-clockwise is three quarters clockwise.
        assert!(close(
            plane_sweep((1.0, 0.0), (0.0, 1.0), true, 0),
            FRAC_PI_2
        ));
        assert!(close(
            plane_sweep((1.0, 0.0), (0.0, 1.0), false, 0),
            -3.0 * FRAC_PI_2
        ));
        // Half way round either way, on either side of the branch cut.
        assert!(close(plane_sweep((1.0, 0.0), (-1.0, 0.0), true, 0), PI));
        assert!(close(plane_sweep((1.0, 0.0), (-1.0, 0.0), false, 0), -PI));
        assert!(close(plane_sweep((-1.0, 0.0), (1.0, 0.0), true, 0), PI));
        assert!(close(plane_sweep((-1.0, -0.0), (1.0, 0.0), false, 0), -PI));
        // An end at the start is a full turn; each extra turn adds one.
        assert!(close(plane_sweep((0.0, 2.0), (0.0, 2.0), true, 0), TAU));
        assert!(close(
            plane_sweep((0.0, 2.0), (0.0, 2.0), false, 2),
            -3.0 * TAU
        ));
        assert!(close(
            plane_sweep((1.0, 0.0), (0.0, 1.0), true, 1),
            FRAC_PI_2 + TAU
        ));
        // An end at the centre: each end's angle on its own.
        assert!(close(
            plane_sweep((0.0, 0.0), (0.0, 1.0), true, 0),
            FRAC_PI_2
        ));
        assert!(close(
            plane_sweep((0.0, 1.0), (0.0, 0.0), false, 0),
            -FRAC_PI_2
        ));
    }

    #[test]
    fn plane_arc_steps_evenly_in_each_plane() {
        let close = |a: DVec3, b: DVec3| (a - b).length() < 1e-12;
        // G17, a half turn counter-clockwise rising 4 along Z: half way is a quarter round, up 2.
        let (from, to) = (DVec3::new(1.0, 0.0, 0.0), DVec3::new(-1.0, 0.0, 4.0));
        let arc = PlaneArc::new(from, to, DVec3::ZERO, Axis::Z, true, 0);
        assert_eq!((arc.iu, arc.iv, arc.iw), (0, 1, 2));
        let points: Vec<DVec3> = arc.points(from, to, 2).collect();
        assert_eq!(points.len(), 2);
        assert!(close(points[0], DVec3::new(0.0, 1.0, 2.0)), "{points:?}");
        assert_eq!(points[1], to);
        // One step is the end alone; none is taken as one.
        assert_eq!(arc.points(from, to, 1).collect::<Vec<_>>(), vec![to]);
        assert_eq!(arc.points(from, to, 0).collect::<Vec<_>>(), vec![to]);
        // G18 turns from Z towards X: a quarter counter-clockwise from +Z passes +X at 45°.
        let (from, to) = (DVec3::new(0.0, 3.0, 2.0), DVec3::new(2.0, 3.0, 0.0));
        let arc = PlaneArc::new(from, to, DVec3::new(0.0, 3.0, 0.0), Axis::Y, true, 0);
        assert!((arc.sweep - FRAC_PI_2).abs() < 1e-12);
        let h = 2.0 * std::f64::consts::FRAC_1_SQRT_2;
        let mid = arc.points(from, to, 2).next();
        assert!(
            mid.is_some_and(|p| close(p, DVec3::new(h, 3.0, h))),
            "{mid:?}"
        );
        // G19 turns from Y towards Z, clockwise here; a spiral's radius changes evenly.
        let (from, to) = (DVec3::new(5.0, 0.0, 1.0), DVec3::new(5.0, 0.0, -3.0));
        let arc = PlaneArc::new(from, to, DVec3::new(5.0, 0.0, 0.0), Axis::X, false, 0);
        assert_eq!((arc.radius, arc.end_radius), (1.0, 3.0));
        assert!((arc.sweep + PI).abs() < 1e-12);
        let points: Vec<DVec3> = arc.points(from, to, 2).collect();
        assert!(close(points[0], DVec3::new(5.0, 2.0, 0.0)), "{points:?}");
        // A full turn with an extra one: four steps a turn come back to the start twice.
        let start = DVec3::new(2.0, 0.0, 0.0);
        let arc = PlaneArc::new(start, start, DVec3::ZERO, Axis::Z, true, 1);
        let points: Vec<DVec3> = arc.points(start, start, 8).collect();
        assert!(close(points[3], start) && close(points[7], start));
        assert!(close(points[4], DVec3::new(0.0, 2.0, 0.0)));
    }

    #[test]
    fn chords_keep_within_the_tolerance_and_stay_bounded() {
        // A full turn of radius 10 within 0.01: each step's sagitta r·(1 − cos(step / 2)).
        let start = DVec3::new(10.0, 0.0, 0.0);
        let arc = PlaneArc::new(start, start, DVec3::ZERO, Axis::Z, true, 0);
        let n = arc.chords(0.01);
        assert!(n > 4 && 10.0 * (1.0 - (PI / n as f64).cos()) <= 0.01, "{n}");
        // A huge radius with many turns stays bounded, and so does a tolerance out of range.
        let far = DVec3::new(1e9, 0.0, 0.0);
        let huge = PlaneArc::new(far, far, DVec3::ZERO, Axis::Z, true, u32::MAX);
        assert_eq!(huge.chords(1e-6), 100_000);
        assert_eq!(huge.points(far, far, huge.chords(1e-6)).count(), 100_000);
        for tolerance in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(
                (1..=100_000).contains(&arc.chords(tolerance)),
                "{tolerance}"
            );
        }
    }

    proptest! {
        /// The angle between the ends' own angles, the programmed way round, plus the turns.
        #[test]
        fn plane_sweep_is_the_difference_of_the_ends_angles(
            a0 in -PI..PI,
            a1 in -PI..PI,
            r0 in 0.01..1e4_f64,
            r1 in 0.01..1e4_f64,
            ccw: bool,
            turns in 0..5_u32,
        ) {
            let (start, end) = ((r0 * a0.cos(), r0 * a0.sin()), (r1 * a1.cos(), r1 * a1.sin()));
            let sweep = plane_sweep(start, end, ccw, turns);
            let (s, e) = (start.1.atan2(start.0), end.1.atan2(end.0));
            // Its direction, the turns it makes, and the ends' angles.
            prop_assert_eq!(sweep > 0.0, ccw);
            let whole = (sweep.abs() / TAU).floor();
            prop_assert!(whole == f64::from(turns) || whole == f64::from(turns + 1));
            let off = (s + sweep - e).rem_euclid(TAU);
            prop_assert!(off.min(TAU - off) < 1e-9, "{sweep} from {s} to {e}");
        }

        /// Within an ulp of `hypot` over every magnitude a program can give.
        #[test]
        fn plane_length_is_hypot_to_within_an_ulp(
            du in -1e12..1e12_f64,
            dv in -1e12..1e12_f64,
            scale in -200..200_i32,
        ) {
            let (du, dv) = (du * 10f64.powi(scale), dv * 10f64.powi(scale));
            prop_assert!(ulps(plane_length(du, dv), du.hypot(dv)) <= 1);
        }
    }
}
