//! G22 stroke limits and the machine's travel: the zone, and the check of every move against
//! them.

use glam::DVec3;
use swarf_syntax::{Block, Diagnostic, Dialect, Word};

use super::Requests;
use super::tools::tool_tip_shift;
use crate::machine::find;
use crate::state::State;
use crate::{Canon, Sink, Source, StrokeZone};

/// Runs a block (`run`) with its moves checked against the G22 stroke limit and the machine's
/// travel where they apply, and reports a move that breaks them.
pub(super) fn checked(
    st: &mut State,
    block: &Block,
    sink: &mut dyn Sink,
    run: impl FnOnce(&mut State, &mut dyn Sink) -> Requests,
) -> Requests {
    let stroke = st.stroke_zone.filter(|_| st.stroke_check);
    let travel = st.setup.machine.travel_mm.map(|[min, max]| StrokeZone {
        min: DVec3::from_array(min),
        max: DVec3::from_array(max),
        inside_forbidden: false,
    });
    if stroke.is_none() && travel.is_none() {
        return run(st, sink);
    }
    let mut guard = StrokeGuard {
        inner: sink,
        zones: [stroke, travel],
        from: st.position + tool_tip_shift(st),
        gauge: tool_tip_shift(st),
        broken: [false; 2],
    };
    let requests = run(st, &mut guard);
    if guard.broken[0] {
        let what = if stroke.is_some_and(|z| z.inside_forbidden) {
            "enters the G22 protected zone"
        } else {
            "leaves the G22 stroke limits"
        };
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-STROKE-LIMIT",
            format!(
                "this move {what} (machine coordinates); the control stops with an overtravel alarm"
            ),
        ));
    }
    if guard.broken[1] {
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-OVERTRAVEL",
            "this move leaves the machine's travel (the setup's `travel_mm`); the machine stops with an overtravel alarm",
        ));
    }
    requests
}

/// How close the checked chords keep to an arc, in mm: a micrometre, the finest step a position
/// is programmed in, so that an arc crossing a limit by more is caught.
const ARC_TOLERANCE_MM: f64 = 0.001;

/// Checks the moves of one block against the G22 stroke limit and the machine's travel before
/// passing them on.
struct StrokeGuard<'s> {
    inner: &'s mut dyn Sink,
    /// The G22 zone and the machine's travel, where they apply.
    zones: [Option<StrokeZone>; 2],
    /// The machine position (gauge line) before the next move.
    from: DVec3,
    /// The gauge line's offset from the tool tip.
    gauge: DVec3,
    /// Which of `zones` a move broke.
    broken: [bool; 2],
}

impl Sink for StrokeGuard<'_> {
    fn emit(&mut self, source: Source, event: &Canon) {
        let gauge = self.gauge;
        let (end, arc) = match event {
            Canon::Rapid { to } | Canon::Feed { to, .. } => (Some(*to), None),
            Canon::Arc(arc) => {
                let from = self.from - gauge;
                let plane = arc.plane(from);
                let reach = plane.radius.max(plane.end_radius);
                let (mut lo, mut hi) = (from.min(arc.to), from.max(arc.to));
                for i in [plane.iu, plane.iv] {
                    (lo[i], hi[i]) = (plane.center[i] - reach, plane.center[i] + reach);
                }
                // Only an arc whose box comes near a limit is walked chord by chord.
                if clear(&self.zones, lo + gauge, hi + gauge) {
                    (Some(arc.to), None)
                } else {
                    let n = plane.chords(ARC_TOLERANCE_MM);
                    (None, Some(plane.points(from, arc.to, n)))
                }
            }
            _ => (None, None),
        };
        for p in end.into_iter().chain(arc.into_iter().flatten()) {
            let p = p + gauge;
            for (zone, broken) in self.zones.iter().zip(&mut self.broken) {
                if let Some(zone) = zone {
                    *broken |= zone.violated_by(self.from, p);
                }
            }
            self.from = p;
        }
        self.inner.emit(source, event);
    }

    fn full(&self) -> bool {
        self.inner.full()
    }

    fn origin(&mut self, at: DVec3) {
        self.inner.origin(at);
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.inner.programmed(source, event);
    }

    fn stroke_zone(&mut self, source: Source, zone: Option<&StrokeZone>) {
        self.inner.stroke_zone(source, zone);
    }
}

/// Whether no move within the box from `lo` to `hi` can break `zones`: the box lies inside each
/// zone that keeps the tool in and outside each that keeps it out.
fn clear(zones: &[Option<StrokeZone>], lo: DVec3, hi: DVec3) -> bool {
    zones.iter().flatten().all(|z| {
        if z.inside_forbidden {
            (0..3).any(|i| hi[i] <= z.min[i] || lo[i] >= z.max[i])
        } else {
            (0..3).all(|i| lo[i] >= z.min[i] && hi[i] <= z.max[i])
        }
    })
}

/// G22 X Y Z I J K: the programmable stroke limit (machine coordinates) / G23: off. Syntec pairs
/// X with I (either may be the larger), protects the zone between them and refuses an axis given
/// without its pair (COR-109); an axis whose pair is equal is not protected. LNC keeps the tool
/// inside the limits (X Y Z the + limits, I J K the − limits); an axis not given is not limited
/// here (its user parameter is not in the setup).
pub(super) fn stroke_limit(st: &mut State, w: &Word, words: &[Word], on: bool) {
    st.stroke_check = on;
    if !on {
        return;
    }
    let syntec = st.dialect == Dialect::Syntec;
    let mut min = DVec3::NEG_INFINITY;
    let mut max = DVec3::INFINITY;
    let mut given = false;
    for (i, (plus, minus)) in [(b'X', b'I'), (b'Y', b'J'), (b'Z', b'K')]
        .iter()
        .enumerate()
    {
        let hi = find(words, *plus).map(|x| st.length(x));
        let lo = find(words, *minus).map(|x| st.length(x));
        given |= hi.is_some() || lo.is_some();
        match (hi, lo) {
            (Some(a), Some(b)) if syntec => {
                if (a - b).abs() > 1e-9 {
                    min[i] = a.min(b);
                    max[i] = a.max(b);
                }
            }
            (None, None) => {}
            _ if syntec => {
                st.diagnostics.push(Diagnostic::error(
                    w.span,
                    "E-WORD-MISSING",
                    format!(
                        "G22 needs both limits of an axis ({} with {}): alarm COR-109, the protection is not activated",
                        *plus as char, *minus as char
                    ),
                ));
                st.stroke_check = false;
                return;
            }
            (hi, lo) => {
                if let Some(hi) = hi {
                    max[i] = hi;
                }
                if let Some(lo) = lo {
                    min[i] = lo;
                }
            }
        }
    }
    // Without limits in the block the machine's parameters apply (not in the setup).
    st.stroke_zone = given.then_some(StrokeZone {
        min,
        max,
        inside_forbidden: syntec,
    });
    if syntec && (0..3).all(|i| min[i] == f64::NEG_INFINITY) {
        // Every pair was equal: nothing is protected.
        st.stroke_zone = None;
    }
}
