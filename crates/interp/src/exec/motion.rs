//! The block's move in its motion mode (rapid, feed, arc, thread, cycle) and G04 dwell.

use glam::{DVec2, DVec3};
use swarf_syntax::{Block, Dialect, Quantity, Word, WordForm};

use super::feeds::move_feed;
use super::{Axes, MAX_COUNT, axis_words, count_range};
use crate::machine::find;
use crate::state::{FeedMode, MotionMode, State, plane_axes};
use crate::{Arc, Canon, PlaneArc, Sink, Source, plane_length};

/// The program-frame end point of a move programmed with `axes` (G90/G91, polar).
pub(crate) fn target(st: &State, axes: &Axes<'_>) -> DVec3 {
    let mut p = st.program_pos;
    let mut axes = *axes;
    if let Some(pole) = st.polar {
        // The plane's words are the radius and angle about the pole.
        let (u, v) = plane_axes(st.plane);
        let rel = DVec2::new(p[u] - pole.x, p[v] - pole.y);
        let (mut r, mut a) = (rel.length(), rel.y.atan2(rel.x).to_degrees());
        if let Some(w) = axes[u].take() {
            let given = st.length(w);
            r = if st.absolute { given.abs() } else { r + given };
        }
        if let Some(w) = axes[v].take() {
            let given = st.angle(w);
            a = if st.absolute { given } else { a + given };
        }
        let (sin, cos) = a.to_radians().sin_cos();
        p[u] = pole.x + r * cos;
        p[v] = pole.y + r * sin;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let v = st.length(w);
            p[i] = if st.absolute { v } else { p[i] + v };
        }
    }
    p
}

/// The block's move in the current mode, where its words make one; whether it moved.
pub(super) fn motion(
    st: &mut State,
    block: &Block,
    words: &[Word],
    axes: &Axes<'_>,
    probe: bool,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    // Rotary axis words alone still make a move (the rotary position itself is not drawn), as do
    // I/J/K alone in an arc mode (a full circle).
    let arc_mode = matches!(st.motion, Some(MotionMode::Arc { .. }));
    let rotary_or_centre = words.iter().any(|w| {
        w.form == WordForm::Plain
            && (matches!(w.letter, b'A' | b'B' | b'C')
                || (arc_mode && matches!(w.letter, b'I' | b'J' | b'K')))
    });
    let cycle = matches!(st.motion, Some(MotionMode::Cycle(_)));
    if !(axes.iter().any(Option::is_some) || rotary_or_centre || cycle) {
        return false;
    }
    if probe {
        let message = "a skip or measuring move is drawn as its full programmed move (where the signal stops it is not known)";
        st.note(block.span, "N-PROBE", message);
    }
    let Some(mode) = st.motion else {
        let span = axes.iter().flatten().next().map_or(block.span, |w| w.span);
        let message = "axis words with no motion mode active (after G80): add G00 or G01";
        return st.fail(span, "E-NO-MOTION-MODE", message);
    };
    let mut p = target(st, axes);
    if matches!(mode, MotionMode::Rapid | MotionMode::Linear) {
        // G45–G48: the travel of each moving axis changes by the offset.
        p = crate::position::offset_line(st, block, words, axes, p);
    }
    let to = st.to_machine(p);
    let event = match mode {
        MotionMode::Rapid if !probe => Canon::Rapid { to },
        MotionMode::Arc { ccw } => {
            let offsets = axis_words(words, b'I');
            let radius = find(words, b'R');
            if offsets.iter().all(Option::is_none) && radius.is_none() {
                if st.dialect == Dialect::Syntec {
                    // Documented: no R and no I/J/K runs as G01 (the parser has said so).
                    return feed_to(st, block, p, to, source, sink);
                }
                let message = "G02/G03 needs the centre (I, J, K) or the radius (R)";
                return st.fail(block.span, "E-ARC-CENTER", message);
            }
            // The turns of a spiral or multi-turn arc: Syntec's L, LinuxCNC's P.
            let turns = match st.dialect {
                Dialect::Syntec => find(words, b'L'),
                Dialect::LinuxCnc => find(words, b'P'),
                _ => None,
            };
            return arc(st, block, p, (offsets, radius, turns), ccw, source, sink);
        }
        MotionMode::Thread => Canon::line(false, to, thread_feed(st, block, words)),
        MotionMode::Cycle(t) => return crate::cycles::run(st, block, words, t, source, sink),
        MotionMode::Linear
            if st.dialect.rules().comma_words
                && let Some((corner, span)) = corner_word(st, block) =>
        {
            // Held back one block: the next move decides where the corner goes.
            let from = st.position;
            let feed = move_feed(st, block, from.distance(to), None);
            // A corner held from the block before is cut against this move first.
            crate::corners::resolve(st, sink, &Canon::line(false, to, feed));
            st.position = to;
            st.program_pos = p;
            st.pending = Some(crate::corners::Pending {
                from,
                to,
                feed_mm_per_min: feed,
                source,
                corner,
                span,
            });
            return true;
        }
        MotionMode::Rapid | MotionMode::Linear => return feed_to(st, block, p, to, source, sink),
    };
    end_move(st, p, to, source, sink, &event)
}

/// Ends a move at `to` (`p` in the program frame) and passes its event to the corner stage.
fn end_move(
    st: &mut State,
    p: DVec3,
    to: DVec3,
    source: Source,
    sink: &mut dyn Sink,
    event: &Canon,
) -> bool {
    st.position = to;
    st.program_pos = p;
    crate::corners::emit(st, sink, source, event);
    true
}

/// G33's feed along the programmed line: the lead (F; LinuxCNC's K) per spindle revolution.
fn thread_feed(st: &mut State, block: &Block, words: &[Word]) -> f64 {
    let lead = if st.dialect == Dialect::LinuxCnc {
        find(words, b'K').map_or(0.0, |k| st.length(k))
    } else {
        st.mm(st.feed_word)
    };
    let feed_mm_per_min = lead * st.spindle_rpm;
    if feed_mm_per_min <= 0.0 {
        let message = "G33 feeds the lead once per spindle revolution: it needs the lead and a spindle speed (S)";
        st.error(block.span, "E-NO-FEED", message);
    }
    feed_mm_per_min.max(0.0)
}

/// The block's `,C` or `,R` word as a corner in millimetres.
fn corner_word(st: &State, block: &Block) -> Option<(crate::corners::Corner, swarf_syntax::Span)> {
    if let Some(c) = block.comma_word(b'C') {
        return Some((crate::corners::Corner::Chamfer(st.length(c).abs()), c.span));
    }
    let r = block.comma_word(b'R')?;
    Some((crate::corners::Corner::Round(st.length(r).abs()), r.span))
}

pub(super) fn feed_to(
    st: &mut State,
    block: &Block,
    p: DVec3,
    to: DVec3,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let length = st.position.distance(to);
    let feed = move_feed(st, block, length, None);
    end_move(st, p, to, source, sink, &Canon::line(false, to, feed))
}

/// The words that shape an arc: centre offsets I/J/K, radius R and Syntec's turns L.
type ArcWords<'w> = (Axes<'w>, Option<&'w Word>, Option<&'w Word>);

/// G02/G03 in the program frame (centre from I/J/K or R), then through the transform. Syntec's L
/// makes a spiral of L turns whose end may be off the start's circle; LNC spirals to an end off it.
pub(super) fn arc(
    st: &mut State,
    block: &Block,
    p: DVec3,
    (offsets, radius, turns_word): ArcWords<'_>,
    ccw: bool,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let (u, v) = plane_axes(st.plane);
    let turns = turns_word.map_or(0, |l| {
        let n = l.value.round();
        if !(1.0..=MAX_COUNT).contains(&n) {
            st.diagnostics.push(count_range(l, "turns"));
        }
        n.clamp(1.0, MAX_COUNT) as u32 - 1
    });
    let from = st.program_pos;
    let mut center = from;
    if let Some(r) = radius.filter(|_| offsets.iter().all(Option::is_none)) {
        let r_mm = st.length(r);
        let (du, dv) = (p[u] - from[u], p[v] - from[v]);
        let chord = plane_length(du, dv);
        if chord < 1e-9 {
            let message =
                "an arc programmed with R cannot end where it starts: use I/J/K for a full circle";
            return st.fail(r.span, "E-ARC-CENTER", message);
        }
        let half = chord / 2.0;
        if r_mm.abs() + st.setup.machine.arc_tolerance_mm < half {
            let v = r.value;
            let message =
                format!("R{v} is smaller than half the distance to the end point ({half:.4} mm)");
            return st.fail(r.span, "E-ARC-RADIUS", message);
        }
        let h = (r_mm * r_mm - half * half).max(0.0).sqrt();
        // Left of the chord for a short counter-clockwise arc, right for a short clockwise one.
        let side = if ccw == (r_mm > 0.0) { 1.0 } else { -1.0 };
        center[u] = from[u] + du / 2.0 - side * h * dv / chord;
        center[v] = from[v] + dv / 2.0 + side * h * du / chord;
    } else {
        // LinuxCNC G90.1: the centre words are the centre's program coordinates.
        let absolute = st.arc_centres_absolute;
        let plane = ["YZ plane (G19)", "XZ plane (G18)", "XY plane (G17)"][st.plane as usize];
        for (i, w) in offsets.iter().enumerate() {
            if let Some(w) = w {
                if i == u || i == v {
                    let at = st.length(w);
                    center[i] = if absolute { at } else { from[i] + at };
                } else if st.dialect == Dialect::LinuxCnc {
                    let message = format!(
                        "`{}` is not a centre word of an arc in the {plane}: LinuxCNC refuses the block, which is not run",
                        w.letter()
                    );
                    return st.fail(w.span, "E-ARC-WORD", message);
                } else {
                    let l = w.letter();
                    let message = format!(
                        "`{l}` is not a centre offset in the selected plane and is ignored"
                    );
                    st.warning(w.span, "W-WORD-IGNORED", message);
                }
            }
        }
        if absolute && let Some(i) = [u, v].into_iter().find(|&i| offsets[i].is_none()) {
            let message = format!(
                "under G90.1 (absolute arc centres) an arc in the {plane} needs both centre words: `{}` is missing",
                char::from(b"IJK"[i])
            );
            return st.fail(block.span, "E-ARC-CENTER", message);
        }
        let r0 = plane_length(from[u] - center[u], from[v] - center[v]);
        let r1 = plane_length(p[u] - center[u], p[v] - center[v]);
        if r0 < 1e-9 {
            let message = "the arc's centre is at its start point";
            return st.fail(block.span, "E-ARC-CENTER", message);
        }
        // Off the circle (a spiral's radius goes from the start's to the end's).
        let off = (r0 - r1).abs();
        if off > st.setup.machine.arc_tolerance_mm && turns_word.is_none() {
            if st.dialect == Dialect::Lnc {
                let message = format!(
                    "the end point is {off:.4} mm off the arc: LNC changes the radius progressively from {r0:.4} mm to {r1:.4} mm"
                );
                st.warning(block.span, "W-ARC-SPIRAL", message);
            } else {
                let syntec = st.dialect == Dialect::Syntec;
                let alarm = if syntec { " (alarm COR-006)" } else { "" };
                let message = format!(
                    "the end point is {off:.4} mm off the arc: start radius {r0:.4} mm, end radius {r1:.4} mm{alarm}"
                );
                return st.fail(block.span, "E-ARC-RADIUS", message);
            }
        }
    }
    // G45–G48 on an arc: the centre stays, the end moves along its radius by the offset.
    let by_radius = radius.is_some() && offsets.iter().all(Option::is_none);
    let Some(p) = crate::position::offset_arc(st, block, by_radius, center, p, ccw) else {
        return false;
    };
    let to = st.to_machine(p);
    let spiral = turns_word.is_some();
    let mut machine_center = unequal_scaling_center(st, from, p, center, ccw, spiral)
        .unwrap_or_else(|| st.to_machine(center));
    let normal = 3 - u - v;
    // The centre lies in the start's plane.
    machine_center[normal] = st.position[normal];
    let ccw = ccw != st.reverses_arcs();
    let from_machine = st.position;
    // Only a feed in inverse time needs the arc's length and radius.
    let feed_mm_per_min = if st.feed_mode == FeedMode::InverseTime {
        let arc = PlaneArc::new(from_machine, to, machine_center, st.plane, ccw, turns);
        let length = (arc.sweep.abs() * (arc.radius + arc.end_radius) / 2.0)
            .hypot(to[normal] - from_machine[normal]);
        move_feed(st, block, length, Some(arc.radius))
    } else {
        move_feed(st, block, 0.0, None)
    };
    let arc = Canon::Arc(Arc {
        to,
        center: machine_center,
        axis: st.plane,
        ccw,
        turns,
        feed_mm_per_min,
    });
    end_move(st, p, to, source, sink, &arc)
}

/// Syntec scales an arc's radius by the larger plane factor when G51 scales them unequally: the
/// machine centre for the scaled ends, on the programmed arc's side; `None` for equal scaling.
fn unequal_scaling_center(
    st: &State,
    from: DVec3,
    to: DVec3,
    center: DVec3,
    ccw: bool,
    spiral: bool,
) -> Option<DVec3> {
    let s = st.scaling?;
    let (u, v) = plane_axes(st.plane);
    let (fu, fv) = (s.factors[u].abs(), s.factors[v].abs());
    if spiral || (fu - fv).abs() < 1e-12 {
        return None;
    }
    let factor = fu.max(fv);
    let (a, b) = (st.scaled(from), st.scaled(to));
    let offset = DVec2::new(center[u] - from[u], center[v] - from[v]);
    let r = offset.length() * factor;
    let (du, dv) = (b[u] - a[u], b[v] - a[v]);
    let chord = plane_length(du, dv);
    let mut c = a;
    if chord < 1e-9 {
        // A full circle: the centre offset scaled by the largest factor, with the factors' signs.
        c[u] = a[u] + offset.x * factor * s.factors[u].signum();
        c[v] = a[v] + offset.y * factor * s.factors[v].signum();
    } else {
        // The programmed arc's sweep decides between the short and the long way round.
        let programmed = PlaneArc::new(from, to, center, st.plane, ccw, 0);
        let long = programmed.sweep.abs() > std::f64::consts::PI;
        let ccw_scaled = ccw != st.reverses_arcs();
        let half = chord / 2.0;
        let h = (r * r - half * half).max(0.0).sqrt();
        let side = if ccw_scaled == long { -1.0 } else { 1.0 };
        c[u] = a[u] + du / 2.0 - side * h * dv / chord;
        c[v] = a[v] + dv / 2.0 + side * h * du / chord;
    }
    Some(st.place(c))
}

pub(super) fn dwell(st: &mut State, w: &Word, words: &[Word], source: Source, sink: &mut dyn Sink) {
    let secs = if let Some(p) = find(words, b'P') {
        st.dialect.read(p, Quantity::DwellP, false, false)
    } else if let Some(x) = find(words, b'X').or(find(words, b'U')) {
        st.dialect.read(x, Quantity::DwellX, false, false)
    } else {
        let message = "G04 needs the dwell time in P or X";
        return st.fail(w.span, "E-WORD-MISSING", message);
    };
    if secs < 0.0 {
        return st.fail(w.span, "E-NUMBER-RANGE", "a dwell time cannot be negative");
    }
    crate::corners::emit(st, sink, source, &Canon::Dwell { secs });
}

pub(super) fn rapid_to(st: &mut State, to: DVec3, source: Source, sink: &mut dyn Sink) {
    let p = st.to_program(to);
    end_move(st, p, to, source, sink, &Canon::Rapid { to });
}

/// The motion mode a G code sets, entering or leaving a canned cycle mode.
pub(super) fn set_mode(st: &mut State, m: Option<MotionMode>) {
    let was_cycle = matches!(st.motion, Some(MotionMode::Cycle(_)));
    st.motion = match m {
        Some(MotionMode::Cycle(_)) => {
            if !was_cycle {
                crate::cycles::enter(st);
            }
            m
        }
        None if was_cycle => crate::cycles::cancel(st),
        // Fanuc family: G80 is group 09 and leaves the group-01 mode as it is.
        None if st.dialect != Dialect::LinuxCnc => st.motion,
        _ => {
            if was_cycle {
                crate::cycles::cancel(st);
            }
            m
        }
    };
}

/// Warns of I/J/K/R words in a block without G codes whose motion mode does not use them.
pub(super) fn unused_arc_words(st: &mut State, words: &[Word]) {
    if matches!(
        st.motion,
        Some(MotionMode::Arc { .. } | MotionMode::Cycle(_))
    ) {
        return;
    }
    for w in words
        .iter()
        .filter(|w| w.form == WordForm::Plain && matches!(w.letter, b'I' | b'J' | b'K' | b'R'))
    {
        let l = w.letter();
        let message = format!("address `{l}` is only used by G02/G03 here and is ignored");
        st.warning(w.span, "W-WORD-IGNORED", message);
    }
}
