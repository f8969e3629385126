//! Cutter radius compensation (G41/G42/G40): a filter on the motion events after `,C`/`,R`
//! corners. Each move in the plane is held back until the next is known; the corner between
//! them decides its compensated end: inside corners end where the offset paths meet; outside
//! corners get an arc about the corner (LinuxCNC, the `arc` mode) or the offset paths'
//! intersection, with two extra vectors when sharper than 90° (Fanuc, `intersection`). Other
//! events wait behind the held move (LinuxCNC any number of blocks, the Fanuc family one).
//! Geometry is in the machine frame, so it follows G68, G16 and scaling.
//!
//! A new side (G41 <-> G42; the Fanuc family, LinuxCNC refuses it) ends the held move where its
//! offset path meets the next move's, else square to its end; a new radius (a D word) counts
//! from the end of the block that gives it. A mirror of one plane axis reverses the material
//! side: Fanuc swaps G41/G42 itself, Syntec's programs do (`mirror_swaps_comp_side`). A lathe
//! tool (`orientation` 1–8, in G18) is reported at its imaginary tip, as LinuxCNC does.
//! Gouges (a move run backwards, corner paths that do not meet) are reported naming both
//! blocks; the path drawn stays what the control computes.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use swarf_syntax::{Diagnostic, Dialect, Span};

use crate::state::{MotionMode, State, plane_axes};
use crate::{Arc, Axis, Canon, CornerMode, Sink, Source};

/// LinuxCNC's angle below which a corner is taken as straight (TOLERANCE_CONCAVE_CORNER).
const LINUXCNC_SMALL: f64 = 0.05;
/// The angle below which a corner is straight in the other dialects (exact geometry).
const SMALL: f64 = 1e-9;
/// Lengths below this (mm) are zero.
const EPS: f64 = 1e-9;

/// Compensation kept between motion events.
#[derive(Debug, Clone, Default)]
pub(crate) struct Comp {
    /// The programmed position (machine frame) at the end of the last motion event.
    pub prog: DVec3,
    /// Where the tool is (the end of the last event sent), when off the programmed position.
    pub tool: Option<DVec3>,
    /// The move held back until the next move in the plane decides its end.
    pub held: Option<Held>,
    /// Events after the held move, sent on when it is.
    behind: Vec<(Source, Canon)>,
    /// The number of the block (in execution order) of the held move.
    held_run: u64,
    /// Whether the corner before the next move moved its start back (intersection mode).
    start_extended: bool,
    /// The tip direction of the lathe tool (0: a mill; see [`crate::Register::orientation`]).
    pub orientation: u8,
}

/// A compensated move held back.
#[derive(Debug, Clone)]
pub(crate) struct Held {
    /// The compensated move: its start is fixed, its end in the plane still moves.
    elem: Elem,
    /// The programmed corner at the end (plane coordinates).
    corner: DVec2,
    /// The direction of travel at the end, used for the corner (unit).
    tangent: DVec2,
    /// The signed offset (positive: the tool left of the path).
    offset: f64,
    /// The programmed line direction (unit) or arc sweep (radians), for the reversal check.
    prog_dir: DVec2,
    prog_sweep: f64,
    /// Whether the end was moved past the programmed one (intersection mode, outside corners).
    extended: bool,
    /// The line of the move before, whose corner decided the start.
    prev_line: u32,
    /// A Fanuc type-A start-up: an outside corner ends it at the next move's start vector.
    startup: bool,
}

/// A programmed move in the plane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Elem {
    source: Source,
    span: Span,
    rapid: bool,
    feed: f64,
    from: DVec3,
    to: DVec3,
    /// Centre (plane coordinates), direction and extra turns of an arc.
    arc: Option<(DVec2, bool, u32)>,
}

/// A curve of a compensated path, for intersections.
#[derive(Debug, Clone, Copy)]
enum Curve {
    Line { p: DVec2, d: DVec2 },
    Circle { c: DVec2, r: f64 },
}

fn left(t: DVec2) -> DVec2 {
    DVec2::new(-t.y, t.x)
}

fn cross(a: DVec2, b: DVec2) -> f64 {
    a.x * b.y - a.y * b.x
}

fn uv(p: DVec3, (u, v): (usize, usize)) -> DVec2 {
    DVec2::new(p[u], p[v])
}

fn with_uv(mut p: DVec3, q: DVec2, (u, v): (usize, usize)) -> DVec3 {
    p[u] = q.x;
    p[v] = q.y;
    p
}

/// The angle from `a` to `b` about `c` in the arc's direction, in [0, 2π).
fn sweep(a: DVec2, b: DVec2, c: DVec2, ccw: bool) -> f64 {
    let (pa, pb) = (a - c, b - c);
    let s = pb.y.atan2(pb.x) - pa.y.atan2(pa.x);
    let s = if ccw { s } else { -s }.rem_euclid(TAU);
    if s >= TAU - 1e-12 { 0.0 } else { s }
}

impl Elem {
    fn tangent_at(&self, p: DVec2, plane: (usize, usize)) -> DVec2 {
        match self.arc {
            Some((c, ccw, _)) => left(p - c).normalize_or_zero() * if ccw { 1.0 } else { -1.0 },
            None => (uv(self.to, plane) - uv(self.from, plane)).normalize_or_zero(),
        }
    }
    fn start_tangent(&self, plane: (usize, usize)) -> DVec2 {
        self.tangent_at(uv(self.from, plane), plane)
    }
    fn end_tangent(&self, plane: (usize, usize)) -> DVec2 {
        self.tangent_at(uv(self.to, plane), plane)
    }
    /// The start of the path offset by `s`.
    fn offset_start(&self, s: f64, plane: (usize, usize)) -> DVec2 {
        uv(self.from, plane) + left(self.start_tangent(plane)) * s
    }
    fn offset_end(&self, s: f64, plane: (usize, usize)) -> DVec2 {
        uv(self.to, plane) + left(self.end_tangent(plane)) * s
    }
    /// The offset path as a curve (`None`: an arc the tool does not fit in).
    fn offset_curve(&self, s: f64, plane: (usize, usize)) -> Option<Curve> {
        match self.arc {
            Some((c, ccw, _)) => {
                // The end's radius (LinuxCNC's choice, where the two differ within tolerance).
                let r1 = (uv(self.to, plane) - c).length();
                let r = if ccw { r1 - s } else { r1 + s };
                (r > EPS).then_some(Curve::Circle { c, r })
            }
            None => Some(Curve::Line {
                p: self.offset_start(s, plane),
                d: self.start_tangent(plane),
            }),
        }
    }
    /// The programmed sweep of an arc (full turns included), or 0 for a line.
    fn prog_sweep(&self, plane: (usize, usize)) -> f64 {
        match self.arc {
            Some((c, ccw, turns)) => {
                let s = sweep(uv(self.from, plane), uv(self.to, plane), c, ccw);
                let s = if s < 1e-12 { TAU } else { s };
                s + f64::from(turns) * TAU
            }
            None => 0.0,
        }
    }
}

impl Held {
    /// `elem` held back offset by `s` from `start` to `end` (plane), after line `prev`.
    fn of(elem: &Elem, s: f64, start: DVec3, end: DVec2, plane: (usize, usize), prev: u32) -> Held {
        let to = with_uv(elem.to, end, plane);
        Held {
            elem: Elem {
                from: start,
                to,
                ..*elem
            },
            corner: uv(elem.to, plane),
            tangent: elem.end_tangent(plane),
            offset: s,
            prog_dir: (uv(elem.to, plane) - uv(elem.from, plane)).normalize_or_zero(),
            prog_sweep: elem.prog_sweep(plane),
            extended: false,
            prev_line: prev,
            startup: false,
        }
    }

    /// The held move's path through its end, for intersections.
    fn curve(&self, plane: (usize, usize)) -> Curve {
        let p = uv(self.elem.to, plane);
        match self.elem.arc {
            None => Curve::Line { p, d: self.tangent },
            Some((c, ..)) => Curve::Circle {
                c,
                r: (p - c).length(),
            },
        }
    }
}

/// The intersections of two curves.
fn intersect(a: Curve, b: Curve) -> Vec<DVec2> {
    match (a, b) {
        (Curve::Line { p: p1, d: d1 }, Curve::Line { p: p2, d: d2 }) => {
            let den = cross(d1, d2);
            if den.abs() < 1e-12 {
                return Vec::new();
            }
            vec![p1 + d1 * (cross(p2 - p1, d2) / den)]
        }
        (Curve::Line { p, d }, Curve::Circle { c, r })
        | (Curve::Circle { c, r }, Curve::Line { p, d }) => {
            let f = p - c;
            let b = f.dot(d);
            let disc = b * b - (f.length_squared() - r * r);
            if disc < -1e-9 * r.max(1.0) {
                return Vec::new();
            }
            let q = disc.max(0.0).sqrt();
            vec![p + d * (-b - q), p + d * (-b + q)]
        }
        (Curve::Circle { c: c1, r: r1 }, Curve::Circle { c: c2, r: r2 }) => {
            let dv = c2 - c1;
            let d = dv.length();
            if d < EPS {
                return Vec::new();
            }
            let a = (r1 * r1 - r2 * r2 + d * d) / (2.0 * d);
            let h2 = r1 * r1 - a * a;
            if h2 < -1e-9 * r1.max(1.0) {
                return Vec::new();
            }
            let h = h2.max(0.0).sqrt();
            let e = dv / d;
            let base = c1 + e * a;
            vec![base + left(e) * h, base - left(e) * h]
        }
    }
}

/// Whether a point lies on a curve.
fn on_curve(p: DVec2, c: Curve) -> bool {
    match c {
        Curve::Line { p: q, d } => cross(p - q, d).abs() < 1e-7,
        Curve::Circle { c, r } => ((p - c).length() - r).abs() < 1e-7,
    }
}

/// The signed offset asked for now (positive: left of the path, machine frame); `None` when off or
/// in a canned cycle. A one-axis mirror swaps the side where `mirror_swaps_comp_side` says.
fn wanted(st: &State) -> Option<f64> {
    if matches!(st.motion, Some(MotionMode::Cycle(_))) || st.cutter_comp == 400 {
        return None;
    }
    let mut side = if st.cutter_comp == 420 { -1.0 } else { 1.0 };
    // Fanuc swaps G41 and G42 under a one-axis mirror; Syntec's programs swap them.
    let machine = &st.setup.machine;
    let swaps = !matches!(st.dialect, Dialect::Syntec | Dialect::LinuxCnc);
    if machine.mirror_swaps_comp_side.unwrap_or(swaps) && st.reverses_arcs() {
        side = -side;
    }
    let s = st.comp_radius * side;
    (s.abs() > EPS).then_some(s)
}

/// The imaginary tip of a lathe tool from its nose centre (which compensation moves along the
/// offset path), by the radius in X and Z as `orientation` says; zero for mills, 9 and outside G18.
fn tip_shift(st: &State) -> DVec3 {
    let r = st.comp_radius.abs();
    if st.plane != Axis::Y || r < EPS {
        return DVec3::ZERO;
    }
    // The side of the nose centre the tip is on in X and Z, by orientation (0 and 9: none).
    const X: [i8; 10] = [0, -1, -1, 1, 1, 0, -1, 0, 1, 0];
    const Z: [i8; 10] = [0, 1, -1, -1, 1, 1, 0, -1, 0, 0];
    let o = usize::from(st.comp.orientation).min(9);
    DVec3::new(f64::from(X[o]) * r, 0.0, f64::from(Z[o]) * r)
}

/// Sends a compensated event on: a lathe tool's moves (and arc centres) go to its imaginary tip.
fn put(st: &State, sink: &mut dyn Sink, source: Source, event: &Canon) {
    let d = tip_shift(st);
    if d == DVec3::ZERO {
        return sink.emit(source, event);
    }
    let mut shifted = event.clone();
    match &mut shifted {
        Canon::Rapid { to } | Canon::Feed { to, .. } => *to += d,
        Canon::Arc(a) => (a.to, a.center) = (a.to + d, a.center + d),
        _ => {}
    }
    sink.emit(source, &shifted);
}

/// Sends `event` on through cutter compensation.
#[inline]
pub(crate) fn emit(st: &mut State, sink: &mut dyn Sink, source: Source, event: &Canon) {
    let from = st.comp.prog;
    match event {
        Canon::Rapid { to } | Canon::Feed { to, .. } | Canon::Arc(Arc { to, .. }) => {
            st.comp.prog = *to;
            if st.comp.held.is_none() && wanted(st).is_none() {
                // Compensation off and nothing held: the move goes on as it is.
                st.comp.tool = None;
                return sink.emit(source, event);
            }
            motion(st, sink, source, from, event);
        }
        Canon::End => {
            close(st, sink, None);
            sink.emit(source, event);
        }
        _ if st.comp.held.is_some() => st.comp.behind.push((source, event.clone())),
        _ => sink.emit(source, event),
    }
}

// Kept out of `emit`, so that a move with compensation off skips its setup.
#[inline(never)]
fn motion(st: &mut State, sink: &mut dyn Sink, source: Source, from: DVec3, event: &Canon) {
    let want = wanted(st);
    let plane = plane_axes(st.plane);
    let held_offset = st.comp.held.as_ref().map(|h| h.offset);
    if want.is_some() || held_offset.is_some() {
        sink.programmed(source, event);
    }
    let (to, rapid, feed, arc) = match *event {
        Canon::Rapid { to } => (to, true, 0.0, None),
        Canon::Feed {
            to,
            feed_mm_per_min,
        } => (to, false, feed_mm_per_min, None),
        Canon::Arc(a) => {
            let arc = (uv(a.center, plane), a.ccw, a.turns);
            (a.to, false, a.feed_mm_per_min, Some(arc))
        }
        _ => return,
    };
    let elem = Elem {
        source,
        span: st.block_span,
        rapid,
        feed,
        from,
        to,
        arc,
    };
    let in_plane = arc.is_some() || (uv(to, plane) - uv(from, plane)).length() > EPS;
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    let Some(s) = want else {
        if held_offset.is_some() {
            // Cancel: the first move after G40.
            if arc.is_some() {
                let message = if linuxcnc {
                    "the move just after G40 must be straight, not an arc"
                } else {
                    "G40 is cancelled only in a G00/G01 move, not in G02/G03"
                };
                alarm(st, elem.span, "E-COMP-CANCEL", message);
            }
            // Fanuc type A: an inside corner ends the last move on the cancel move's offset.
            let cancel = (in_plane && arc.is_none() && !linuxcnc).then_some((&elem, f64::NAN));
            close(st, sink, cancel);
        }
        st.comp.tool = None;
        return sink.emit(source, event);
    };
    if !in_plane {
        if st.comp.held.is_some() {
            st.comp.behind.push((source, event.clone()));
        } else {
            let tool = st.comp.tool.unwrap_or(from);
            let moved = with_uv(to, uv(tool, plane), plane);
            st.comp.tool = Some(moved);
            put(st, sink, source, &with_end(event, moved));
        }
        return;
    }
    let Some(h) = &st.comp.held else {
        return startup(st, sink, elem, s);
    };
    let prev_line = h.elem.source.line;
    let tolerated = if linuxcnc { u64::MAX } else { 1 };
    let between = st.blocks_run.saturating_sub(st.comp.held_run + 1);
    let start = if between > tolerated {
        let (a, b) = (prev_line, source.line);
        let message = format!(
            "{between} blocks without motion in the plane between line {a} and line {b}: the control cannot look ahead that far, so the compensated path of line {a} ends square to it and line {b} starts from there (an overcut or undercut is possible)"
        );
        st.warning(elem.span, "W-COMP-LOOKAHEAD", message);
        close(st, sink, None)
    } else {
        close(st, sink, Some((&elem, s)))
    };
    start_from(st, elem, s, start, prev_line);
}

/// The first move after G41/G42: from where the tool is to the compensated end.
fn startup(st: &mut State, sink: &mut dyn Sink, elem: Elem, s: f64) {
    let plane = plane_axes(st.plane);
    let tool = st.comp.tool.unwrap_or(elem.from);
    let t = uv(tool, plane);
    let p = uv(elem.to, plane);
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    if let Some((c, ccw, turns)) = elem.arc {
        if !linuxcnc {
            let message = "G41/G42 starts only in a G00/G01 move, not in G02/G03";
            return refuse_start(st, sink, &elem, message);
        }
        // LinuxCNC: an arc through the compensated end, tangent to the tool where it is.
        if (p - t).length() <= s.abs() {
            let message =
                "the radius of the compensation entry arc is not greater than the tool radius";
            alarm(st, elem.span, "E-COMP-START", message);
        }
        let end = elem.offset_end(s, plane);
        let u = (c - end).normalize_or_zero();
        let den = 2.0 * u.dot(t - end);
        if den.abs() < EPS {
            let message = "the tool radius is not less than the entry arc's radius";
            return refuse_start(st, sink, &elem, message);
        }
        let center = end + u * ((t - end).length_squared() / den);
        let mut held = Held {
            prog_dir: DVec2::ZERO,
            prog_sweep: f64::INFINITY,
            ..Held::of(&elem, s, tool, end, plane, elem.source.line)
        };
        held.elem.arc = Some((center, ccw, turns));
        return hold(st, held);
    }
    let (dir, startup) = if linuxcnc {
        let d = p - t;
        if d.length() <= s.abs() {
            let message = "the compensation entry move is not longer than the tool radius";
            alarm(st, elem.span, "E-COMP-START", message);
        }
        (d.normalize_or_zero(), false)
    } else {
        let d = p - uv(elem.from, plane);
        let d = if d.length() > EPS { d } else { p - t };
        (d.normalize_or_zero(), true)
    };
    if dir == DVec2::ZERO {
        return sink.emit(elem.source, &as_event(&elem, st.plane));
    }
    let end = p + left(dir) * s;
    let held = Held {
        tangent: dir,
        prog_dir: (end - t).normalize_or_zero(),
        startup,
        ..Held::of(&elem, s, tool, end, plane, elem.source.line)
    };
    hold(st, held);
}

/// Holds `held` back from the block being run.
fn hold(st: &mut State, held: Held) {
    st.comp.held = Some(held);
    st.comp.held_run = st.blocks_run;
}

/// Compensation cannot start in `elem`: the alarm, and the move itself uncompensated.
fn refuse_start(st: &mut State, sink: &mut dyn Sink, elem: &Elem, message: &str) {
    alarm(st, elem.span, "E-COMP-START", message);
    st.comp.tool = None;
    sink.emit(elem.source, &as_event(elem, st.plane));
}

/// Holds `elem` offset by `s` from `start` (plane coordinates), after line `prev_line`.
fn start_from(st: &mut State, elem: Elem, s: f64, start: Option<DVec2>, prev_line: u32) {
    let plane = plane_axes(st.plane);
    let tool = st.comp.tool.unwrap_or(elem.from);
    let start = start.unwrap_or_else(|| elem.offset_start(s, plane));
    let end = elem.offset_end(s, plane);
    if elem.arc.is_some() && elem.offset_curve(s, plane).is_none() {
        let line = elem.source.line;
        let message = format!(
            "the arc of line {line} has a smaller radius than the tool: the tool cannot cut inside it"
        );
        gouge(st, elem.span, message);
    }
    let held = Held {
        extended: std::mem::take(&mut st.comp.start_extended),
        ..Held::of(&elem, s, with_uv(tool, start, plane), end, plane, prev_line)
    };
    hold(st, held);
}

/// Ends the held move against `next` (NaN offset: G40; `None`: the run's end) and sends it on;
/// where the next move starts.
pub(crate) fn close(
    st: &mut State,
    sink: &mut dyn Sink,
    next: Option<(&Elem, f64)>,
) -> Option<DVec2> {
    let mut h = st.comp.held.take()?;
    let plane = plane_axes(st.plane);
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    let (small, dialect_mode) = if linuxcnc {
        (LINUXCNC_SMALL, CornerMode::Arc)
    } else {
        (SMALL, CornerMode::Intersection)
    };
    let mode = st.setup.machine.corner_mode.unwrap_or(dialect_mode);
    // Moves round the corner: (point, arc centre when it is an arc about the corner).
    let mut links: Vec<(DVec2, Option<(DVec2, bool)>)> = Vec::new();
    let mut start = None;
    if let Some((n, s2)) = next {
        let cancel = s2.is_nan();
        let s = h.offset;
        let e1 = uv(h.elem.to, plane);
        let t2 = n.start_tangent(plane);
        let t1 = h.tangent;
        let turn = cross(t1, t2).atan2(t1.dot(t2));
        // Straight back: inside only where the tool is outside an arc (LinuxCNC's h and m shapes).
        let reversal = turn.abs() > PI - small.max(1e-9);
        let inside = if reversal {
            (n.arc.or(h.elem.arc)).is_some_and(|(_, ccw, _)| (s > 0.0) != ccw)
        } else {
            turn * s > 0.0 && turn.abs() > small
        };
        let straight = turn.abs() <= small;
        // A new side offsets the next move from its start; a new radius counts from its end.
        let side_change = !cancel && s * s2 < 0.0;
        let s2v = if side_change { s2 } else { s };
        let s2p = n.offset_start(s2v, plane);
        // The next move starts at its offset start unless a branch below finds otherwise.
        start = (!cancel).then_some(s2p);
        if cancel {
            let line = Curve::Line { p: s2p, d: t2 };
            if inside && let Some(x) = first_met(intersect(h.curve(plane), line), &h, n, s, plane) {
                h.elem.to = with_uv(h.elem.to, x, plane);
            }
        } else if side_change || (linuxcnc && (s - s2).abs() > EPS) {
            // The Fanuc family: to where the paths meet on the new side, else square across.
            let crossing = (!linuxcnc).then(|| side_change_point(&h, n, s2, plane));
            if let Some(x) = crossing.flatten() {
                h.elem.to = with_uv(h.elem.to, x, plane);
                h.extended = true;
                st.comp.start_extended = true;
                start = Some(x);
            } else {
                links.push((s2p, None));
            }
        } else if straight {
            // LinuxCNC starts the next move where the last one ended.
            if linuxcnc {
                start = Some(e1);
            }
        } else if h.startup && !inside {
            // Fanuc type A start-up: to the next move's start vector.
            h.elem.to = with_uv(h.elem.to, s2p, plane);
        } else if inside {
            let found = n
                .offset_curve(s, plane)
                .and_then(|c| first_met(intersect(h.curve(plane), c), &h, n, s, plane));
            if let Some(x) = found {
                (h.elem.to, start) = (with_uv(h.elem.to, x, plane), Some(x));
            } else {
                let (a, b) = (h.elem.source.line, n.source.line);
                let message = format!(
                    "the tool does not fit in the inside corner between line {a} and line {b}: their offset paths do not meet"
                );
                gouge(st, n.span, message);
                links.push((s2p, None));
            }
        } else {
            match mode {
                CornerMode::Arc => links.push((s2p, (!n.rapid).then_some((h.corner, s < 0.0)))),
                CornerMode::Intersection => {
                    let r = s.abs();
                    let sharp = t1.dot(t2) < -1e-9;
                    // Where the held move ends and the next starts, each on its path (extended)
                    // or linked to it: sharper than 90°, two extra vectors of the radius along
                    // the moves; else where the offset paths meet.
                    let (x1, on1, x2, on2) = if sharp {
                        (
                            e1 + t1 * r,
                            h.elem.arc.is_none(),
                            s2p - t2 * r,
                            n.arc.is_none(),
                        )
                    } else {
                        let c2 = n.offset_curve(s, plane);
                        let x = c2
                            .and_then(|c| {
                                nearest(intersect(h.curve(plane), c), e1, s2p)
                                    .filter(|x| (*x - h.corner).length() < 2.0 * r + EPS)
                            })
                            .unwrap_or_else(|| {
                                h.corner + (left(t1) + left(t2)) * (s / (1.0 + t1.dot(t2)))
                            });
                        (
                            x,
                            on_curve(x, h.curve(plane)),
                            x,
                            c2.is_some_and(|c| on_curve(x, c)),
                        )
                    };
                    if on1 {
                        (h.elem.to, h.extended) = (with_uv(h.elem.to, x1, plane), true);
                    } else {
                        links.push((x1, None));
                    }
                    if sharp {
                        links.push((x2, None));
                    }
                    if on2 {
                        (start, st.comp.start_extended) = (Some(x2), true);
                    } else {
                        links.push((s2p, None));
                    }
                }
            }
        }
    }
    send(st, sink, &h, next.map(|(n, _)| n.source.line));
    let end = h.elem.to;
    let behind = std::mem::take(&mut st.comp.behind);
    let mut at = end;
    for (source, event) in behind {
        match event.end_point() {
            Some(to) => {
                at = with_uv(to, uv(end, plane), plane);
                put(st, sink, source, &with_end(&event, at));
            }
            None => sink.emit(source, &event),
        }
    }
    if let Some((n, _)) = next {
        for (p, arc) in links {
            if (p - uv(at, plane)).length() < 1e-6 {
                continue;
            }
            let to = with_uv(at, p, plane);
            let mut link = *n;
            (link.from, link.to, link.arc) = (at, to, arc.map(|(c, ccw)| (c, ccw, 0)));
            put(st, sink, n.source, &as_event(&link, st.plane));
            at = to;
        }
    }
    st.comp.tool = Some(at);
    start.or(Some(uv(at, plane)))
}

/// The inside corner's intersection nearest both the held move's end and the next's start.
fn first_met(xs: Vec<DVec2>, h: &Held, n: &Elem, s: f64, plane: (usize, usize)) -> Option<DVec2> {
    let e1 = uv(h.elem.to, plane);
    let s2 = n.offset_start(s, plane);
    let back = |x: DVec2| match h.elem.arc {
        None => (e1 - x).dot(h.tangent).abs(),
        Some((center, ccw, _)) => (x - center).length() * sweep(x, e1, center, ccw),
    };
    let forward = |x: DVec2| match n.arc {
        None => (x - s2).dot(n.start_tangent(plane)).abs(),
        Some((c, ccw, _)) => (x - c).length() * sweep(s2, x, c, ccw),
    };
    xs.into_iter()
        .filter(|p| p.is_finite())
        .min_by(|p, q| (back(*p) + forward(*p)).total_cmp(&(back(*q) + forward(*q))))
}

/// Where the held move's path meets the next move's on the other side, both going forwards.
fn side_change_point(h: &Held, n: &Elem, s2: f64, plane: (usize, usize)) -> Option<DVec2> {
    let c2 = n.offset_curve(s2, plane)?;
    let x = first_met(intersect(h.curve(plane), c2), h, n, s2, plane)?;
    let held_forward = h.elem.arc.is_some() || (x - uv(h.elem.from, plane)).dot(h.tangent) > EPS;
    let next_forward =
        n.arc.is_some() || (n.offset_end(s2, plane) - x).dot(n.start_tangent(plane)) > EPS;
    (held_forward && next_forward).then_some(x)
}

/// The intersection nearest both ends of a corner.
fn nearest(points: Vec<DVec2>, a: DVec2, b: DVec2) -> Option<DVec2> {
    points.into_iter().filter(|p| p.is_finite()).min_by(|p, q| {
        let dp = (*p - a).length() + (*p - b).length();
        let dq = (*q - a).length() + (*q - b).length();
        dp.total_cmp(&dq)
    })
}

/// Sends the held move on, checked against its programmed direction (`next`: the next line).
fn send(st: &mut State, sink: &mut dyn Sink, h: &Held, next: Option<u32>) {
    let plane = plane_axes(st.plane);
    let (a, b) = (uv(h.elem.from, plane), uv(h.elem.to, plane));
    let reversed = match h.elem.arc {
        None => h.prog_dir != DVec2::ZERO && (b - a).dot(h.prog_dir) < -1e-7,
        Some((center, ccw, turns)) => {
            let s = sweep(a, b, center, ccw) + f64::from(turns) * TAU;
            // Trimming shortens an arc; one that crossed itself wraps round to nearly a turn.
            let limit = h.prog_sweep + if h.extended { PI } else { 0.1 };
            (a - b).length() > 1e-7 && s > limit
        }
    };
    if reversed {
        let (line, prev) = (h.elem.source.line, h.prev_line);
        let next = next.unwrap_or(line);
        let message = format!(
            "the compensated move of line {line} runs backwards against its programmed direction between the corners with line {prev} and line {next}: the tool cuts into the part (a groove or pocket narrower than the tool, or a step smaller than the radius)"
        );
        gouge(st, h.elem.span, message);
    }
    let mut elem = h.elem;
    // An arc trimmed to nothing (no full turn) goes on as a straight feed.
    if (a - b).length() < 1e-9 && h.prog_sweep < TAU - 1e-9 && elem.arc.is_some_and(|c| c.2 == 0) {
        (elem.arc, elem.rapid) = (None, false);
    }
    put(st, sink, elem.source, &as_event(&elem, st.plane));
}

/// A gouge: a warning, or an alarm where the control alarms (LinuxCNC, Syntec's 3819).
fn gouge(st: &mut State, span: Span, message: String) {
    if st.dialect == Dialect::LinuxCnc || st.setup.machine.overcut_alarm {
        alarm(st, span, "E-COMP-GOUGE", message);
    } else {
        st.warning(span, "W-COMP-GOUGE", message);
    }
}

/// An alarm: the run stops before the next block.
fn alarm(st: &mut State, span: Span, code: &'static str, message: impl Into<String>) {
    let d = Diagnostic::error(span, code, message);
    match st.alarm {
        None => st.alarm = Some(d),
        Some(_) => st.diagnostics.push(d),
    }
}

/// `event` with its end point moved to `end`.
fn with_end(event: &Canon, end: DVec3) -> Canon {
    let mut event = event.clone();
    if let Canon::Rapid { to } | Canon::Feed { to, .. } | Canon::Arc(Arc { to, .. }) = &mut event {
        *to = end;
    }
    event
}

/// The programmed move as an event, in the plane with normal `axis`.
fn as_event(e: &Elem, axis: Axis) -> Canon {
    match e.arc {
        Some((c, ccw, turns)) => Canon::Arc(Arc {
            to: e.to,
            center: with_uv(e.from, c, plane_axes(axis)),
            axis,
            ccw,
            turns,
            feed_mm_per_min: e.feed,
        }),
        None => Canon::line(e.rapid, e.to, e.feed),
    }
}
