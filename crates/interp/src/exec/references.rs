//! Reference points and machine coordinates: G28/G30 and G29, G53, and Syntec's G37 tool
//! measurement.

use swarf_syntax::{Block, Diagnostic, Dialect, Word};

use super::Axes;
use super::motion::{feed_to, rapid_to, target};
use super::tools::tool_tip_shift;
use crate::machine::find;
use crate::state::{MotionMode, State};
use crate::{Sink, Source};

/// G28 (n = 1) / G30 Pn: rapid to the intermediate point, then to the reference point, for the
/// axes given.
pub(super) fn reference(
    st: &mut State,
    words: &[Word],
    axes: &Axes<'_>,
    n: u8,
    source: Source,
    sink: &mut dyn Sink,
) {
    let point = if n == 1 {
        1
    } else {
        find(words, b'P').map_or(2, |p| p.value.round().clamp(1.0, 4.0) as usize)
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
    for (i, w) in axes.iter().enumerate() {
        if w.is_some() {
            st.intermediate[i] = Some(mid[i]);
        }
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    let mut end = st.position;
    for (i, w) in axes.iter().enumerate() {
        if w.is_some() {
            end[i] = reference[i];
        }
    }
    rapid_to(st, end, source, sink);
}

/// G29: from the reference point through the intermediate point to the programmed point.
pub(super) fn from_reference(st: &mut State, axes: &Axes<'_>, source: Source, sink: &mut dyn Sink) {
    let mut mid = st.program_pos;
    for i in 0..3 {
        if axes[i].is_some()
            && let Some(m) = st.intermediate[i]
        {
            mid[i] = m;
        }
    }
    let mid_machine = st.to_machine(mid);
    rapid_to(st, mid_machine, source, sink);
    // G91: the target is relative to the intermediate point.
    let end = target(st, axes);
    let end_machine = st.to_machine(end);
    rapid_to(st, end_machine, source, sink);
}

/// G53: a one-shot move in machine coordinates, in the block's motion mode (G00 or G01).
/// Returns whether the block's axis words were used (`false`: they are an ordinary move).
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
            st.diagnostics.push(Diagnostic::error(
                g53.span,
                "E-G53-INCREMENTAL",
                "G53 cannot be used in G91: the block is not run",
            ));
            return true;
        }
        // Syntec: "only effective in G90; in G91 a plain incremental move"; LNC: "invalid in
        // G91"; Fanuc ignores it there too.
        st.diagnostics.push(Diagnostic::warning(
            g53.span,
            "W-G53-INCREMENTAL",
            format!(
                "{} ignores G53 in G91: the block is an ordinary incremental move",
                st.dialect.label()
            ),
        ));
        return false;
    }
    let mut to = st.position;
    // Machine coordinates place the spindle's gauge line: the tool tip is the active length
    // offset below it.
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

/// G37 / G37.1 (Syntec): with P, the return to reference point P (G30 style, all axes); G37
/// then rapids to R above Z when R is given; the measuring move is drawn in full to Z (a program
/// coordinate for G37, a machine coordinate for G37.1), and G37.1 retracts Z to the safety point
/// Q (machine coordinate) or the machine zero.
#[allow(clippy::too_many_arguments)]
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
        st.diagnostics.push(Diagnostic::error(
            g37.span,
            "E-WORD-MISSING",
            "tool measurement needs the measuring position in Z (alarm MAR-330)",
        ));
        return;
    };
    let z = st.length(z);
    st.diagnostics.push(Diagnostic::note(
        block.span,
        "N-PROBE",
        "a measuring move is drawn as its full programmed move (where the signal stops it is not known)",
    ));
    let tip = tool_tip_shift(st);
    if let Some(p) = find(words, b'P') {
        let n = p.value.round();
        if (1.0..=4.0).contains(&n) {
            let point = st.setup.reference_point(n as usize) - tip;
            rapid_to(st, point, source, sink);
        }
    }
    let end = if machine_z {
        let mut end = st.position;
        end.z = z - tip.z;
        end
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
