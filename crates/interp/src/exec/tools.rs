//! The tool and its offsets: T, D and H words, tool length (G43/G44/G49) and cutter radius
//! compensation (G40–G42) codes, and the offset registers they read.

use glam::DVec3;
use swarf_syntax::codes::Code;
use swarf_syntax::{Dialect, Word, WordForm};

use super::actions::{Action, Actions};
use super::axis_words;
use crate::Axis;
use crate::machine::find;
use crate::state::{MotionMode, State};

/// S and T, D and H words (with M06, the selected tool is in the spindle from here on); `false`
/// when the run stops: LinuxCNC selects only the tools of its table.
pub(super) fn settings(st: &mut State, words: &[Word]) -> bool {
    for w in words.iter().filter(|w| w.form == WordForm::Plain) {
        match w.letter {
            b'T' if w.value >= 0.0 => {
                let tool = w.value.round() as u32;
                if st.dialect == Dialect::LinuxCnc && !known_register(st, tool, w.span, "tool") {
                    return false;
                }
                st.tool = tool;
            }
            b'D' if w.value >= 0.0 => st.d_word = w.value.round() as u32,
            b'H' if w.value >= 0.0 && st.dialect != Dialect::Syntec => {
                st.h_word = w.value.round() as u32;
            }
            b'M' if w.value == 6.0 => st.spindle_tool = st.tool,
            _ => {}
        }
    }
    true
}

/// Whether register (or LinuxCNC tool) `n` is in the setup (0 is none); one it lacks reads as
/// zeros, with a note or warning, or in LinuxCNC an error (`false`).
pub(super) fn known_register(st: &mut State, n: u32, span: swarf_syntax::Span, what: &str) -> bool {
    if n == 0 || st.setup.registers.contains_key(&n) {
        return true;
    }
    if !st.registers_listed {
        if what != "tool" {
            let message =
                format!("offset register {n} is not in the setup: its {what} is taken as 0");
            st.note(span, "N-OFFSET-UNSET", message);
        }
        return true;
    }
    if st.dialect == Dialect::LinuxCnc {
        let message = format!(
            "tool {n} is not in the setup's tool table (its registers): LinuxCNC stops here (requested tool not found in the tool table)"
        );
        return st.fail(span, "E-TOOL-UNKNOWN", message);
    }
    let message =
        format!("offset register {n} is not among the setup's registers: its {what} is taken as 0");
    st.warning(span, "W-OFFSET-UNSET", message);
    true
}

/// G40/G41/G42 (LinuxCNC also G41.1/G42.1 with a diameter D): the side, and the radius from the D
/// register (LinuxCNC: tool D's, or the spindle tool's). `false` when the control alarms.
pub(super) fn cutter_comp(st: &mut State, w: &Word, words: &[Word], tenths: u32) -> bool {
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    if tenths == 400 {
        st.cutter_comp = 400;
        return true;
    }
    if linuxcnc {
        if st.cutter_comp != 400 {
            let message = "cutter radius compensation cannot be turned on when it is already on";
            return st.fail(w.span, "E-COMP-ON", message);
        }
        if st.plane == Axis::X {
            let message = "LinuxCNC has cutter radius compensation in the XY and XZ planes only";
            return st.fail(w.span, "E-COMP-PLANE", message);
        }
    }
    let d = find(words, b'D');
    let g = tenths / 10;
    if tenths == 411 || tenths == 421 {
        // LinuxCNC: G41.1/G42.1 D<diameter> [L<orientation>], L only in G18.
        let orientation = match find(words, b'L') {
            Some(l) if st.plane != Axis::Y => {
                let message = format!(
                    "G{g}.1 with an L word (a lathe tool orientation) needs the XZ plane (G18)"
                );
                return st.fail(l.span, "E-COMP-PLANE", message);
            }
            Some(l) if !(0.0..=9.0).contains(&l.value.round()) => {
                let message = "a lathe tool orientation is 0 to 9";
                return st.fail(l.span, "E-COMP-ORIENTATION", message);
            }
            Some(l) => l.value.round() as u8,
            None => 0,
        };
        st.cutter_comp = if tenths == 421 { 420 } else { 410 };
        st.comp_radius = d.map_or(0.0, |d| st.mm(d.value)) / 2.0;
        st.comp.orientation = orientation;
        return true;
    }
    let n = match d {
        Some(d) => d.value.round().max(0.0) as u32,
        None if linuxcnc => st.spindle_tool,
        None => st.d_word,
    };
    if !known_register(st, n, d.map_or(w.span, |d| d.span), "radius") {
        return false;
    }
    let orientation = st.setup.registers.get(&n).map_or(0, |r| r.orientation);
    if linuxcnc && st.plane != Axis::Y && !matches!(orientation, 0 | 9) {
        let message =
            format!("G{g} with a lathe tool (orientation {orientation}) needs the XZ plane (G18)");
        return st.fail(d.map_or(w.span, |d| d.span), "E-COMP-PLANE", message);
    }
    st.cutter_comp = if tenths == 420 { 420 } else { 410 };
    st.comp.orientation = orientation;
    st.comp_radius = st.setup.offsets(n).1;
    true
}

/// A D word without G41/G42: under compensation the Fanuc family takes the new radius (from the end
/// of this block's move); LinuxCNC stops with an error (`false`) unless G96 uses it.
fn new_radius_register(st: &mut State, words: &[Word], css: bool) -> bool {
    let Some(d) = find(words, b'D') else {
        return true;
    };
    if st.dialect == Dialect::LinuxCnc {
        let message = "a D word without G41, G41.1, G42, G42.1 or G96 to use it (LinuxCNC changes the radius only with G40 and a new G41/G42)";
        return css || st.fail(d.span, "E-WORD-UNUSED", message);
    }
    if st.cutter_comp == 400 {
        return true;
    }
    let n = d.value.round().max(0.0) as u32;
    known_register(st, n, d.span, "radius");
    st.comp_radius = st.setup.offsets(n).1;
    st.comp.orientation = st.setup.registers.get(&n).map_or(0, |r| r.orientation);
    true
}

/// An H word without G43/G44/G49 under length compensation selects the new register at once (H00
/// cancels, as KT documents); not in Syntec (H names the tool to measure) or LinuxCNC.
fn new_length_register(st: &mut State, words: &[Word], has_code: bool) {
    if has_code
        || st.length_comp.is_none()
        || matches!(st.dialect, Dialect::Syntec | Dialect::LinuxCnc)
    {
        return;
    }
    let Some(h) = find(words, b'H') else {
        return;
    };
    let n = h.value.round().max(0.0) as u32;
    if n == 0 {
        st.length_comp = None;
        return;
    }
    known_register(st, n, h.span, "length");
    let length = st.setup.offsets(n).0;
    st.length_comp = Some((n, if st.length_plus { length } else { -length }));
}

/// G43/G44 H (`sign`: whether it adds) / G49 (`None`): the offset is recorded. Without H the Fanuc
/// family takes the last H word, LinuxCNC the spindle tool. `false` when the run stops.
pub(super) fn length_comp(st: &mut State, w: &Word, words: &[Word], sign: Option<bool>) -> bool {
    let Some(plus) = sign else {
        st.length_comp = None;
        return true;
    };
    let h = match find(words, b'H') {
        Some(h) => h.value.round() as u32,
        None if st.dialect == Dialect::LinuxCnc => st.spindle_tool,
        None => st.h_word,
    };
    if h == 0 {
        // H00 cancels (KT); LinuxCNC's tool 0 has no offsets.
        st.length_comp = None;
        return true;
    }
    if !known_register(st, h, w.span, "length") {
        return false;
    }
    let length = st.setup.offsets(h).0;
    st.length_comp = Some((h, if plus { length } else { -length }));
    st.length_plus = plus;
    true
}

/// The tool tip's shift from the gauge line under the length offset (along the normal).
pub(super) fn tool_tip_shift(st: &State) -> DVec3 {
    let mut shift = DVec3::ZERO;
    if let Some((_, offset)) = st.length_comp {
        shift[st.plane as usize] = offset;
    }
    shift
}

/// H and D words without their codes, and G40–G42 in an arc block; `false` when it stops.
pub(super) fn new_registers(st: &mut State, words: &[Word], actions: &Actions<'_>) -> bool {
    let has = |a: fn(&Action) -> bool| actions.iter().any(|(x, _)| a(x));
    new_length_register(st, words, has(|a| matches!(a, Action::LengthComp(_))));
    let comp_code = (actions.iter()).find(|(a, _)| matches!(a, Action::CutterComp(_)));
    if comp_code.is_none()
        && !new_radius_register(st, words, has(|a| *a == Action::SpindleMode(true)))
    {
        return false;
    }
    if let Some((_, w)) = comp_code
        && st.dialect != Dialect::LinuxCnc
        && matches!(st.motion, Some(MotionMode::Arc { .. }))
        && axis_words(words, b'X').iter().any(Option::is_some)
    {
        let code = Code::from_value(b'G', w.value).map_or("G40–G42".into(), |c| c.to_string());
        let message = format!(
            "{code} starts or cancels cutter compensation only in a G00/G01 block, not with G02/G03: the control alarms and stops"
        );
        return st.fail(w.span, "E-COMP-ARC", message);
    }
    true
}

/// LinuxCNC moves the current point to the new tip; the Fanuc family adds it to the move.
pub(super) fn follow_length_change(st: &mut State, length_before: f64) {
    let length_after = st.length_comp.map_or(0.0, |(_, o)| o);
    if length_after != length_before && st.dialect == Dialect::LinuxCnc {
        st.position[st.plane as usize] -= length_after - length_before;
        st.resync();
    }
}
