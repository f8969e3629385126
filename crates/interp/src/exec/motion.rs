//! The block's move in its motion mode (rapid, feed, arc, thread, canned cycle) and G04 dwell,
//! from the program frame to the machine's.

use glam::{DVec2, DVec3};
use swarf_syntax::{Block, Diagnostic, Dialect, Quantity, Word, WordForm};

use super::feeds::move_feed;
use super::{Axes, MAX_COUNT, count_range};
use crate::machine::find;
use crate::state::{FeedMode, MotionMode, State, plane_axes};
use crate::{Arc, Axis, Canon, PlaneArc, Sink, Source, plane_length};

/// The program-frame end point of a move programmed with `axes` (G90/G91, polar).
pub(super) fn target(st: &State, axes: &Axes<'_>) -> DVec3 {
    let mut p = st.program_pos;
    if let Some(pole) = st.polar {
        let (u, v) = plane_axes(st.plane);
        let rel = DVec2::new(p[u] - pole.pole.x, p[v] - pole.pole.y);
        let (mut r, mut a) = (rel.length(), rel.y.atan2(rel.x).to_degrees());
        if let Some(w) = axes[u] {
            let given = st.length(w);
            r = if st.absolute { given.abs() } else { r + given };
        }
        if let Some(w) = axes[v] {
            let given = st.angle(w);
            a = if st.absolute { given } else { a + given };
        }
        let (sin, cos) = a.to_radians().sin_cos();
        p[u] = pole.pole.x + r * cos;
        p[v] = pole.pole.y + r * sin;
        let normal = 3 - u - v;
        if let Some(w) = axes[normal] {
            let given = st.length(w);
            p[normal] = if st.absolute {
                given
            } else {
                p[normal] + given
            };
        }
        return p;
    }
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let v = st.length(w);
            p[i] = if st.absolute { v } else { p[i] + v };
        }
    }
    p
}

/// Whether an arc block has no end point but I/J/K (a full circle).
fn arc_full_circle(st: &State, words: &[Word]) -> bool {
    matches!(st.motion, Some(MotionMode::Arc { .. }))
        && words
            .iter()
            .any(|w| w.form == WordForm::Plain && matches!(w.letter, b'I' | b'J' | b'K'))
}

/// The block's move in the current motion mode, where its words make one: axis words, rotary
/// words alone, a canned cycle or a full circle. Returns whether the tool moved.
#[allow(clippy::too_many_arguments)]
pub(super) fn motion(
    st: &mut State,
    block: &Block,
    words: &[Word],
    axes: &Axes<'_>,
    probe: bool,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    // Rotary axis words alone still make a move (the rotary position itself is not drawn).
    let rotary = words
        .iter()
        .any(|w| w.form == WordForm::Plain && matches!(w.letter, b'A' | b'B' | b'C'));
    let cycle = matches!(st.motion, Some(MotionMode::Cycle(_)));
    if !(axes.iter().any(Option::is_some) || rotary || cycle || arc_full_circle(st, words)) {
        return false;
    }
    if probe {
        st.diagnostics.push(Diagnostic::note(
            block.span,
            "N-PROBE",
            "a skip or measuring move is drawn as its full programmed move (where the signal stops it is not known)",
        ));
    }
    let Some(mode) = st.motion else {
        let span = axes.iter().flatten().next().map_or(block.span, |w| w.span);
        st.diagnostics.push(Diagnostic::error(
            span,
            "E-NO-MOTION-MODE",
            "axis words with no motion mode active (after G80): add G00 or G01",
        ));
        return false;
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
            let offsets: Axes<'_> = {
                let mut o: Axes<'_> = [None; 3];
                for w in words.iter().filter(|w| w.form == WordForm::Plain) {
                    if let b'I' | b'J' | b'K' = w.letter {
                        o[usize::from(w.letter - b'I')] = Some(w);
                    }
                }
                o
            };
            let radius = find(words, b'R');
            if offsets.iter().all(Option::is_none) && radius.is_none() {
                if st.dialect == Dialect::Syntec {
                    // Documented: no R and no I/J/K runs as G01 (the parser has said so).
                    return feed_to(st, block, p, to, source, sink);
                }
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-ARC-CENTER",
                    "G02/G03 needs the centre (I, J, K) or the radius (R)",
                ));
                return false;
            }
            // Syntec's L: the number of turns of a spiral (or of a multi-turn arc); LinuxCNC's
            // P: the number of turns of a multi-turn arc or helix.
            let turns = match st.dialect {
                Dialect::Syntec => find(words, b'L'),
                Dialect::LinuxCnc => find(words, b'P'),
                _ => None,
            };
            return arc(st, block, p, (offsets, radius, turns), ccw, source, sink);
        }
        MotionMode::Thread => Canon::Feed {
            to,
            feed_mm_per_min: thread_feed(st, block, words),
        },
        MotionMode::Cycle(t) => {
            // The hole position: the block's in-plane words only (the normal word is the bottom).
            let (u, v) = plane_axes(st.plane);
            let mut plane_words: Axes<'_> = [None; 3];
            plane_words[u] = axes[u];
            plane_words[v] = axes[v];
            let hole = move |st: &State| target(st, &plane_words);
            let feed =
                |st: &mut State, block: &Block, length: f64| move_feed(st, block, length, None);
            return crate::cycles::run(st, block, words, t, &hole, &feed, source, sink);
        }
        MotionMode::Linear if st.dialect.rules().comma_words => {
            if let Some(corner) = corner_word(st, block) {
                // Held back one block: the next move decides where the corner goes.
                let from = st.position;
                let feed = move_feed(st, block, from.distance(to), None);
                // A corner held from the block before is cut against this move first.
                crate::corners::resolve(
                    st,
                    sink,
                    &Canon::Feed {
                        to,
                        feed_mm_per_min: feed,
                    },
                );
                st.position = to;
                st.program_pos = p;
                st.pending = Some(crate::corners::Pending {
                    from,
                    to,
                    feed_mm_per_min: feed,
                    source,
                    corner: corner.0,
                    span: corner.1,
                });
                return true;
            }
            return feed_to(st, block, p, to, source, sink);
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
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-NO-FEED",
            "G33 feeds the lead once per spindle revolution: it needs the lead and a spindle speed (S)",
        ));
    }
    feed_mm_per_min.max(0.0)
}

/// The block's `,C` or `,R` word as a corner in millimetres.
fn corner_word(st: &State, block: &Block) -> Option<(crate::corners::Corner, swarf_syntax::Span)> {
    let c = block.comma_word(b'C');
    let r = block.comma_word(b'R');
    match (c, r) {
        (Some(c), _) => Some((crate::corners::Corner::Chamfer(st.length(c).abs()), c.span)),
        (None, Some(r)) => Some((crate::corners::Corner::Round(st.length(r).abs()), r.span)),
        _ => None,
    }
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
    let feed_mm_per_min = move_feed(st, block, length, None);
    end_move(
        st,
        p,
        to,
        source,
        sink,
        &Canon::Feed {
            to,
            feed_mm_per_min,
        },
    )
}

/// The words that shape an arc: centre offsets I/J/K, radius R and Syntec's turns L.
type ArcWords<'w> = (Axes<'w>, Option<&'w Word>, Option<&'w Word>);

/// G02/G03 in the program frame (centre from I/J/K or from R), then through the transform.
/// With Syntec's L the arc is a spiral (or conical spiral) of L turns, a partial turn counting
/// as one, and its end need not lie on the start's circle; LNC changes the radius progressively
/// when the end is off the circle.
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
            st.diagnostics.push(Diagnostic::error(
                r.span,
                "E-ARC-CENTER",
                "an arc programmed with R cannot end where it starts: use I/J/K for a full circle",
            ));
            return false;
        }
        let half = chord / 2.0;
        if r_mm.abs() + st.setup.machine.arc_tolerance_mm < half {
            st.diagnostics.push(Diagnostic::error(
                r.span,
                "E-ARC-RADIUS",
                format!(
                    "R{} is smaller than half the distance to the end point ({half:.4} mm)",
                    r.value
                ),
            ));
            return false;
        }
        let h = (r_mm * r_mm - half * half).max(0.0).sqrt();
        // Left of the chord for a short counter-clockwise arc, right for a short clockwise one.
        let side = if ccw == (r_mm > 0.0) { 1.0 } else { -1.0 };
        center[u] = from[u] + du / 2.0 - side * h * dv / chord;
        center[v] = from[v] + dv / 2.0 + side * h * du / chord;
    } else {
        // LinuxCNC G90.1: the centre words are the centre's program coordinates.
        let absolute = st.arc_centres_absolute;
        let plane = match st.plane {
            Axis::Z => "XY plane (G17)",
            Axis::Y => "XZ plane (G18)",
            Axis::X => "YZ plane (G19)",
        };
        for (i, w) in offsets.iter().enumerate() {
            if let Some(w) = w {
                if i == u || i == v {
                    let at = st.length(w);
                    center[i] = if absolute { at } else { from[i] + at };
                } else if st.dialect == Dialect::LinuxCnc {
                    st.diagnostics.push(Diagnostic::error(
                        w.span,
                        "E-ARC-WORD",
                        format!(
                            "`{}` is not a centre word of an arc in the {plane}: LinuxCNC refuses the block, which is not run",
                            w.letter()
                        ),
                    ));
                    return false;
                } else {
                    st.diagnostics.push(Diagnostic::warning(
                        w.span,
                        "W-WORD-IGNORED",
                        format!(
                            "`{}` is not a centre offset in the selected plane and is ignored",
                            w.letter()
                        ),
                    ));
                }
            }
        }
        if absolute && let Some(i) = [u, v].into_iter().find(|&i| offsets[i].is_none()) {
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-CENTER",
                format!(
                    "under G90.1 (absolute arc centres) an arc in the {plane} needs both centre words: `{}` is missing",
                    char::from(b"IJK"[i])
                ),
            ));
            return false;
        }
        let r0 = plane_length(from[u] - center[u], from[v] - center[v]);
        let r1 = plane_length(p[u] - center[u], p[v] - center[v]);
        if r0 < 1e-9 {
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-CENTER",
                "the arc's centre is at its start point",
            ));
            return false;
        }
        if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm && turns_word.is_some() {
            // A spiral: the radius goes from the start's to the end's.
        } else if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm && st.dialect == Dialect::Lnc
        {
            st.diagnostics.push(Diagnostic::warning(
                block.span,
                "W-ARC-SPIRAL",
                format!(
                    "the end point is {:.4} mm off the arc: LNC changes the radius progressively from {r0:.4} mm to {r1:.4} mm",
                    (r0 - r1).abs()
                ),
            ));
        } else if (r0 - r1).abs() > st.setup.machine.arc_tolerance_mm {
            let alarm = if st.dialect == Dialect::Syntec {
                " (alarm COR-006)"
            } else {
                ""
            };
            st.diagnostics.push(Diagnostic::error(
                block.span,
                "E-ARC-RADIUS",
                format!(
                    "the end point is {:.4} mm off the arc: start radius {r0:.4} mm, end radius {r1:.4} mm{alarm}",
                    (r0 - r1).abs()
                ),
            ));
            return false;
        }
    }
    // G45–G48 on an arc: the centre stays, the end moves along its radius by the offset.
    let by_radius = radius.is_some() && offsets.iter().all(Option::is_none);
    let p = match crate::position::offset_arc(st, block, &block.words, by_radius, center, p, ccw) {
        Some(Some(q)) => q,
        Some(None) => p,
        None => return false,
    };
    let to = st.to_machine(p);
    let mut machine_center = st.to_machine(center);
    let normal = 3 - u - v;
    // The centre lies in the start's plane.
    machine_center[normal] = st.position[normal];
    let program_ccw = ccw;
    let ccw = ccw != st.reverses_arcs();
    if let Some(c) = unequal_scaling_center(st, from, p, center, program_ccw, turns_word.is_some())
    {
        machine_center = c;
        machine_center[normal] = st.position[normal];
    }
    let from_machine = st.position;
    // The arc's length and radius count only for a feed in inverse time: most arcs spare the
    // angles and radii they take.
    let feed_mm_per_min = if st.feed_mode == FeedMode::InverseTime {
        let arc = PlaneArc::new(from_machine, to, machine_center, st.plane, ccw, turns);
        let length = (arc.sweep.abs() * (arc.radius + arc.end_radius) / 2.0)
            .hypot(to[normal] - from_machine[normal]);
        move_feed(st, block, length, Some(arc.radius))
    } else {
        move_feed(st, block, 0.0, None)
    };
    end_move(
        st,
        p,
        to,
        source,
        sink,
        &Canon::Arc(Arc {
            to,
            center: machine_center,
            axis: st.plane,
            ccw,
            turns,
            feed_mm_per_min,
        }),
    )
}

/// Syntec scales an arc's radius by the largest of the plane's two factors when G51 scales them
/// unequally (`G51 I2. J1.` cuts arcs like `G51 P2.`): the machine centre for the scaled end
/// points, on the same side as the programmed arc's. `None` when the scaling is equal.
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
        // A full circle: the centre offset, scaled by the largest factor (with the signs of
        // the factors, so a mirrored one still points the right way).
        c[u] = a[u] + offset.x * factor * s.factors[u].signum();
        c[v] = a[v] + offset.y * factor * s.factors[v].signum();
    } else {
        // The programmed arc's sweep decides between the short and the long way round.
        let sweep = PlaneArc::new(from, to, center, st.plane, ccw, 0)
            .sweep
            .abs();
        let long = sweep > std::f64::consts::PI;
        let ccw_scaled = ccw != st.reverses_arcs();
        let half = chord / 2.0;
        let h = (r * r - half * half).max(0.0).sqrt();
        let side = if ccw_scaled == long { -1.0 } else { 1.0 };
        c[u] = a[u] + du / 2.0 - side * h * dv / chord;
        c[v] = a[v] + dv / 2.0 + side * h * du / chord;
    }
    Some(st.place(c))
}

pub(super) fn dwell(
    st: &mut State,
    g4: &Word,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) {
    let secs = if let Some(p) = find(words, b'P') {
        st.dialect.read(p, Quantity::DwellP, false, false)
    } else if let Some(x) = find(words, b'X').or(find(words, b'U')) {
        st.dialect.read(x, Quantity::DwellX, false, false)
    } else {
        st.diagnostics.push(Diagnostic::error(
            g4.span,
            "E-WORD-MISSING",
            "G04 needs the dwell time in P or X",
        ));
        return;
    };
    if secs < 0.0 {
        st.diagnostics.push(Diagnostic::error(
            g4.span,
            "E-NUMBER-RANGE",
            "a dwell time cannot be negative",
        ));
        return;
    }
    crate::corners::emit(st, sink, source, &Canon::Dwell { secs });
}

pub(super) fn rapid_to(st: &mut State, to: DVec3, source: Source, sink: &mut dyn Sink) {
    let p = st.to_program(to);
    end_move(st, p, to, source, sink, &Canon::Rapid { to });
}

/// The motion mode a G code sets: entering or leaving a canned cycle mode takes the cycle's
/// steps; G80 in the Fanuc family leaves the group-01 mode as it is.
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
        st.diagnostics.push(Diagnostic::warning(
            w.span,
            "W-WORD-IGNORED",
            format!(
                "address `{}` is only used by G02/G03 here and is ignored",
                w.letter()
            ),
        ));
    }
}
