//! G22 stroke limits and the machine's travel: the zone, and the check of every move.

use glam::DVec3;
use swarf_syntax::{Block, Dialect, Word};

use super::Requests;
use super::tools::tool_tip_shift;
use crate::machine::find;
use crate::state::State;
use crate::{Canon, Sink, Source, StrokeZone};

/// Runs a block (`run`) with its moves checked against G22 and the travel, reporting breaks.
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
        let message = format!(
            "this move {what} (machine coordinates); the control stops with an overtravel alarm"
        );
        st.error(block.span, "E-STROKE-LIMIT", message);
    }
    if guard.broken[1] {
        let message = "this move leaves the machine's travel (the setup's `travel_mm`); the machine stops with an overtravel alarm";
        st.error(block.span, "E-OVERTRAVEL", message);
    }
    requests
}

/// How close the checked chords keep to an arc, mm: the finest programmed step.
const ARC_TOLERANCE_MM: f64 = 0.001;

/// Checks the moves of one block against the G22 limit and the machine's travel.
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

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.inner.programmed(source, event);
    }

    fn stroke_zone(&mut self, source: Source, zone: Option<&StrokeZone>) {
        self.inner.stroke_zone(source, zone);
    }
}

/// Whether no move within the box `lo`–`hi` can break `zones`.
fn clear(zones: &[Option<StrokeZone>], lo: DVec3, hi: DVec3) -> bool {
    zones.iter().flatten().all(|z| {
        if z.inside_forbidden {
            (0..3).any(|i| hi[i] <= z.min[i] || lo[i] >= z.max[i])
        } else {
            (0..3).all(|i| lo[i] >= z.min[i] && hi[i] <= z.max[i])
        }
    })
}

/// G22 X Y Z I J K: the stroke limit (machine coordinates) / G23: off. Syntec protects the zone
/// between X and I (each axis needs its pair, COR-109); LNC keeps the tool inside (X Y Z + limits,
/// I J K − limits).
pub(super) fn stroke_limit(st: &mut State, w: &Word, words: &[Word], on: bool) {
    st.stroke_check = on;
    if !on {
        return;
    }
    let syntec = st.dialect == Dialect::Syntec;
    let mut min = DVec3::NEG_INFINITY;
    let mut max = DVec3::INFINITY;
    let mut given = false;
    for (i, (plus, minus)) in ([(b'X', b'I'), (b'Y', b'J'), (b'Z', b'K')].iter()).enumerate() {
        let hi = find(words, *plus).map(|x| st.length(x));
        let lo = find(words, *minus).map(|x| st.length(x));
        given |= hi.is_some() || lo.is_some();
        match (hi, lo) {
            (Some(a), Some(b)) if syntec && (a - b).abs() > 1e-9 => {
                (min[i], max[i]) = (a.min(b), a.max(b));
            }
            (Some(_), Some(_)) if syntec => {}
            (None, None) => {}
            _ if syntec => {
                let message = format!(
                    "G22 needs both limits of an axis ({} with {}): alarm COR-109, the protection is not activated",
                    *plus as char, *minus as char
                );
                st.error(w.span, "E-WORD-MISSING", message);
                st.stroke_check = false;
                return;
            }
            (hi, lo) => (max[i], min[i]) = (hi.unwrap_or(max[i]), lo.unwrap_or(min[i])),
        }
    }
    // Without limits in the block the machine's parameters apply (not in the setup); Syntec's
    // pairs all equal protect nothing.
    let nothing = syntec && min == DVec3::NEG_INFINITY;
    st.stroke_zone = (given && !nothing).then_some(StrokeZone {
        min,
        max,
        inside_forbidden: syntec,
    });
}
