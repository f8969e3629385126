//! Reference points and machine coordinates: G28/G30, G29, G53 and Syntec's G37 measuring.

use glam::DVec3;
use swarf_syntax::{Block, Dialect, Word};

use super::Axes;
use super::motion::{feed_to, rapid_to, target};
use super::tools::tool_tip_shift;
use crate::machine::find;
use crate::state::{MotionMode, State};
use crate::{Sink, Source};

/// G28 (n = 1) / G30 Pn: rapid to the intermediate, then the reference point, axes given.
pub(super) fn reference(
    st: &mut State,
    words: &[Word],
    axes: &Axes<'_>,
    n: u8,
    source: Source,
    sink: &mut dyn Sink,
) {
    let point = match n {
        1 => 1,
        _ => find(words, b'P').map_or(2, |p| p.value.round().clamp(1.0, 4.0) as usize),
    };
    let reference = st.setup.reference_point(point) - tool_tip_shift(st);
    if axes.iter().all(Option::is_none) {
        if st.dialect == Dialect::LinuxCnc {
            // LinuxCNC: G28 with no axis word goes to the stored position for all axes.
            rapid_to(st, reference, source, sink);
        }
        return;
    }
    let mid = target(st, axes);
    for i in (0..3).filter(|&i| axes[i].is_some()) {
        st.intermediate[i] = Some(mid[i]);
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    let given = glam::BVec3::from(axes.map(|w| w.is_some()));
    let end = DVec3::select(given, reference, st.position);
    rapid_to(st, end, source, sink);
}

/// G29: from the reference point through the intermediate point to the programmed point.
pub(super) fn from_reference(st: &mut State, axes: &Axes<'_>, source: Source, sink: &mut dyn Sink) {
    let mut mid = st.program_pos;
    for (i, m) in st.intermediate.iter().enumerate() {
        if let (Some(_), Some(m)) = (axes[i], m) {
            mid[i] = *m;
        }
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    // G91: the target is relative to the intermediate point.
    let end = target(st, axes);
    let end_machine = st.to_machine(end);
    rapid_to(st, end_machine, source, sink);
}

/// G53: a one-shot machine-coordinate move in G00 or G01; whether the axis words were used.
pub(super) fn machine_move(
    st: &mut State,
    block: &Block,
    g53: &Word,
    axes: &Axes<'_>,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    if !st.absolute {
        if st.dialect == Dialect::LinuxCnc {
            let message = "G53 cannot be used in G91: the block is not run";
            st.error(g53.span, "E-G53-INCREMENTAL", message);
            return true;
        }
        // Syntec, LNC and Fanuc all ignore G53 in G91.
        let control = st.dialect.label();
        let message =
            format!("{control} ignores G53 in G91: the block is an ordinary incremental move");
        st.warning(g53.span, "W-G53-INCREMENTAL", message);
        return false;
    }
    let mut to = st.position;
    // Machine coordinates place the gauge line: the tip is the length offset below it.
    let tip = tool_tip_shift(st);
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            to[i] = st.length(w) - tip[i];
        }
    }
    match st.motion {
        Some(MotionMode::Linear) => {
            let p = st.to_program(to);
            feed_to(st, block, p, to, source, sink);
        }
        _ => rapid_to(st, to, source, sink),
    }
    true
}

/// Syntec G37 / G37.1: with P, the return to that reference point; G37 rapids to R above Z; the
/// measuring move is drawn in full to Z (G37.1: in machine coordinates, then back to Q or zero).
pub(super) fn measure(
    st: &mut State,
    block: &Block,
    g37: &Word,
    words: &[Word],
    machine_z: bool,
    source: Source,
    sink: &mut dyn Sink,
) {
    let Some(z) = find(words, b'Z') else {
        let message = "tool measurement needs the measuring position in Z (alarm MAR-330)";
        return st.fail(g37.span, "E-WORD-MISSING", message);
    };
    let z = st.length(z);
    let message = "a measuring move is drawn as its full programmed move (where the signal stops it is not known)";
    st.note(block.span, "N-PROBE", message);
    let tip = tool_tip_shift(st);
    if let Some(p) = find(words, b'P') {
        let n = p.value.round();
        if (1.0..=4.0).contains(&n) {
            let point = st.setup.reference_point(n as usize) - tip;
            rapid_to(st, point, source, sink);
        }
    }
    let end = if machine_z {
        st.position.with_z(z - tip.z)
    } else {
        let mut p = st.program_pos;
        if let Some(r) = find(words, b'R') {
            p.z = z + st.length(r);
            let start = st.to_machine(p);
            rapid_to(st, start, source, sink);
        }
        p.z = z;
        st.to_machine(p)
    };
    let program = st.to_program(end);
    feed_to(st, block, program, end, source, sink);
    if machine_z {
        let mut back = st.position;
        back.z = find(words, b'Q').map_or(0.0, |q| st.length(q)) - tip.z;
        rapid_to(st, back, source, sink);
    }
}
