//! `,C` chamfers and `,R` corner rounding (LNC, §4.2): a G01 move ending in a corner word is held
//! back one block, then the corner is cut against the next move: equal legs of C for a chamfer, a
//! tangent arc of R for rounding, at the corner block's feed.

use glam::DVec3;
use swarf_syntax::Span;

use crate::state::{State, plane_axes};
use crate::{Arc, Canon, Sink, Source};

/// The corner asked for at the end of a G01 block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Corner {
    /// `,C`: chamfer legs of this length (mm) from the corner.
    Chamfer(f64),
    /// `,R`: rounding arc of this radius (mm).
    Round(f64),
}

/// A G01 move held back until the next block says where the path goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pending {
    /// Where the move starts and ends (machine frame).
    pub from: DVec3,
    pub to: DVec3,
    pub feed_mm_per_min: f64,
    pub source: Source,
    pub corner: Corner,
    /// The corner word, for diagnostics.
    pub span: Span,
}

/// Sends `event` to `sink`, first cutting the corner of a held-back move.
#[inline]
pub(crate) fn emit(st: &mut State, sink: &mut dyn Sink, source: Source, event: &Canon) {
    resolve(st, sink, event);
    crate::comp::emit(st, sink, source, event);
}

/// Cuts a held move's corner against `event` (sharp for no cutting move), not sending it.
#[inline]
pub(crate) fn resolve(st: &mut State, sink: &mut dyn Sink, event: &Canon) {
    let moves = matches!(
        event,
        Canon::Rapid { .. } | Canon::Feed { .. } | Canon::Arc(_) | Canon::Dwell { .. } | Canon::End
    );
    if moves && let Some(pending) = st.pending.take() {
        match event {
            Canon::Feed { to, .. } => return corner(st, sink, &pending, *to),
            Canon::Arc(_) => {
                let message = "a corner before an arc is not drawn yet: the corner is drawn sharp";
                st.warning(pending.span, "W-NOT-INTERPRETED", message);
            }
            _ => {
                let message = "a `,C`/`,R` corner needs a cutting move (G01–G03) in the next block; the corner is drawn sharp";
                st.error(pending.span, "E-CORNER-NEXT", message);
            }
        }
        feed(st, sink, &pending, pending.to);
    }
}

/// Emits a held-back move at the end of the run.
pub(crate) fn flush(st: &mut State, sink: &mut dyn Sink) {
    if let Some(pending) = st.pending.take() {
        let message =
            "a `,C`/`,R` corner needs a cutting move in the next block; the program ends first";
        st.error(pending.span, "E-CORNER-NEXT", message);
        feed(st, sink, &pending, pending.to);
    }
    crate::comp::close(st, sink, None);
}

/// A feed of the held-back move to `to` (its own end where the corner stays sharp).
fn feed(st: &mut State, sink: &mut dyn Sink, p: &Pending, to: DVec3) {
    let event = Canon::line(false, to, p.feed_mm_per_min);
    crate::comp::emit(st, sink, p.source, &event);
}

/// Cuts the corner between the held-back move and a feed to `next`.
fn corner(st: &mut State, sink: &mut dyn Sink, p: &Pending, next: DVec3) {
    let (u, v) = plane_axes(st.plane);
    let d1 = p.to - p.from;
    let d2 = next - p.to;
    let (l1, l2) = (d1.length(), d2.length());
    let in_plane = |d: DVec3| d[3 - u - v].abs() < 1e-9;
    if l1 < 1e-9 || l2 < 1e-9 || !in_plane(d1) || !in_plane(d2) {
        let message = "a corner is cut only between two moves in the selected plane: drawn sharp";
        st.warning(p.span, "W-CORNER-SKIPPED", message);
        return feed(st, sink, p, p.to);
    }
    let (a, b) = (d1 / l1, d2 / l2);
    let cross = a[u] * b[v] - a[v] * b[u];
    let cos = a.dot(b).clamp(-1.0, 1.0);
    if cross.abs() < 1e-9 {
        // Straight on (or straight back): there is no corner to cut.
        return feed(st, sink, p, p.to);
    }
    match p.corner {
        Corner::Chamfer(c) => {
            feed(st, sink, p, p.to - a * c);
            feed(st, sink, p, p.to + b * c);
        }
        Corner::Round(r) => {
            // The turn angle between the moves; the tangent points are r·tan(θ/2) from the corner.
            let turn = cos.acos();
            let t = r * (turn / 2.0).tan();
            let start = p.to - a * t;
            let end = p.to + b * t;
            let left = cross > 0.0;
            let mut normal = DVec3::ZERO;
            normal[u] = -a[v];
            normal[v] = a[u];
            let center = start + normal * if left { r } else { -r };
            feed(st, sink, p, start);
            let arc = Canon::Arc(Arc {
                to: end,
                center,
                axis: st.plane,
                ccw: left,
                turns: 0,
                feed_mm_per_min: p.feed_mm_per_min,
            });
            crate::comp::emit(st, sink, p.source, &arc);
        }
    }
}
