//! G45–G48 tool position offsets (§4.25 of the reference; Syntec and Fanuc): a one-shot change
//! of the block's travel on every axis it moves, by the radius in the D register — G45 one
//! radius longer, G46 one shorter, G47 two longer, G48 two shorter — in the direction of travel.
//! Under G91 a zero axis word still moves by the offset, its sign written (`Y0` +, `Y-0` −) giving
//! the direction; under G90 an axis that does not move is not offset. Arcs keep their centre and
//! take the radius plus the offset, and must be 90° or 270° with I/J/K (COR-081); the offsets
//! cannot run with G41/G42 (COR-082). The tool's position afterwards is where it really went:
//! the next incremental move starts there.

use glam::DVec3;
use swarf_syntax::{Block, Dialect, Word, WordForm};

use crate::state::{State, plane_axes};

/// The G45–G48 code of a block, as the factor of the radius added to the travel; `None` without
/// one, or (reported) under G41/G42, which the offsets may not run with (COR-082).
fn factor(st: &mut State, block: &Block, words: &[Word]) -> Option<(f64, &'static str)> {
    if !matches!(st.dialect, Dialect::Fanuc | Dialect::Syntec) {
        return None;
    }
    let (k, code) = words
        .iter()
        .filter(|w| w.letter == b'G' && w.form == WordForm::Plain && w.expr.is_none())
        .find_map(|w| match w.value {
            45.0 => Some((1.0, "G45")),
            46.0 => Some((-1.0, "G46")),
            47.0 => Some((2.0, "G47")),
            48.0 => Some((-2.0, "G48")),
            _ => None,
        })?;
    if matches!(st.cutter_comp, 410 | 420) {
        let message = format!("{code} cannot run under G41/G42 (COR-082); the move is not offset");
        return st.fail(block.span, "E-POSITION-OFFSET", message);
    }
    Some((k, code))
}

/// The offset radius of the block's D register (geometry + wear), or `None` with a diagnostic.
fn radius(st: &mut State, block: &Block, code: &str) -> Option<f64> {
    let d = st.d_word;
    if let Some(r) = st.setup.registers.get(&d) {
        Some(r.radius + r.radius_wear)
    } else {
        let message = format!(
            "{code} needs a D register with the offset (D{d} is not in the setup); the move is not offset"
        );
        st.fail(block.span, "E-OFFSET-REGISTER", message)
    }
}

/// The straight move's target `p` (program frame) with the block's position offset applied to
/// every axis with a word in `axes`.
pub(crate) fn offset_line(
    st: &mut State,
    block: &Block,
    words: &[Word],
    axes: &[Option<&Word>; 3],
    p: DVec3,
) -> DVec3 {
    let Some((k, code)) = factor(st, block, words) else {
        return p;
    };
    let Some(r) = radius(st, block, code) else {
        return p;
    };
    let mut out = p;
    for (i, w) in axes.iter().enumerate() {
        let Some(w) = w else { continue };
        let travel = p[i] - st.program_pos[i];
        let direction = if travel.abs() > 1e-12 {
            travel.signum()
        } else if !st.absolute {
            // A zero under G91: its written sign is the direction.
            1f64.copysign(w.value)
        } else {
            0.0
        };
        out[i] += direction * k * r;
    }
    out
}

/// An arc under G45–G48: the centre stays, the radius grows or shrinks by the offset, so the
/// end moves along its radius. Returns the end (program frame), or `None` (with COR-081) when
/// the arc is not a 90° or 270° arc given by I/J/K.
pub(crate) fn offset_arc(
    st: &mut State,
    block: &Block,
    by_radius: bool,
    center: DVec3,
    end: DVec3,
    ccw: bool,
) -> Option<DVec3> {
    let Some((k, code)) = factor(st, block, &block.words) else {
        return Some(end);
    };
    let (u, v) = plane_axes(st.plane);
    let start = st.program_pos;
    let a0 = (start[v] - center[v]).atan2(start[u] - center[u]);
    let a1 = (end[v] - center[v]).atan2(end[u] - center[u]);
    let turn = (a1 - a0).to_degrees();
    let sweep = if ccw { turn } else { -turn }.rem_euclid(360.0);
    let quarter = (sweep - 90.0).abs() < 1e-6 || (sweep - 270.0).abs() < 1e-6;
    if by_radius || !quarter {
        let message = format!(
            "under {code} an arc must be 90° or 270° with its centre in I/J/K (COR-081); this block is not run"
        );
        return st.fail(block.span, "E-POSITION-OFFSET", message);
    }
    let r = radius(st, block, code)?;
    let mut rel = end - center;
    rel[3 - u - v] = 0.0;
    let length = rel.length();
    if length < 1e-12 {
        return Some(end);
    }
    let mut out = end;
    let grown = rel * ((length + k * r) / length);
    out[u] = center[u] + grown[u];
    out[v] = center[v] + grown[v];
    Some(out)
}
