//! The tool and its offsets: T, D and H words, tool length (G43/G44/G49) and cutter radius
//! compensation (G40–G42) codes, and the offset registers they read.

use glam::DVec3;
use swarf_syntax::codes::Code;
use swarf_syntax::{Diagnostic, Dialect, Word, WordForm};

use super::actions::{Action, Actions};
use super::axis_words;
use crate::Axis;
use crate::machine::find;
use crate::state::{MotionMode, State, plane_axes};

/// S and T, D and H words; with M06 in the block, the selected tool is the one in the spindle
/// from here on (LinuxCNC changes the tool before it applies G43 or G41/G42). Returns `false`
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

/// Whether offset register (or LinuxCNC tool) `n`, named by the word at `span`, is one the
/// setup holds; `what` is what is read from it (`length`, `radius`, or `tool` for a LinuxCNC T
/// word). Number 0 is no register. One the setup does not hold reads as zeros: with a note when
/// the setup listed no registers at all (nothing is known of the machine's), with a warning in
/// the Fanuc family when it listed others, and in LinuxCNC, whose tool table must hold every
/// tool a program names, with an error: the run stops there (`false`), as LinuxCNC's does.
pub(super) fn known_register(st: &mut State, n: u32, span: swarf_syntax::Span, what: &str) -> bool {
    if n == 0 || st.setup.registers.contains_key(&n) {
        return true;
    }
    if !st.registers_listed {
        if what != "tool" {
            st.diagnostics.push(Diagnostic::note(
                span,
                "N-OFFSET-UNSET",
                format!("offset register {n} is not in the setup: its {what} is taken as 0"),
            ));
        }
        return true;
    }
    if st.dialect == Dialect::LinuxCnc {
        st.diagnostics.push(Diagnostic::error(
            span,
            "E-TOOL-UNKNOWN",
            format!(
                "tool {n} is not in the setup's tool table (its registers): LinuxCNC stops here (requested tool not found in the tool table)"
            ),
        ));
        return false;
    }
    st.diagnostics.push(Diagnostic::warning(
        span,
        "W-OFFSET-UNSET",
        format!("offset register {n} is not among the setup's registers: its {what} is taken as 0"),
    ));
    true
}

/// G40/G41/G42 (LinuxCNC also G41.1/G42.1): the side, and the radius from the D register
/// (geometry plus wear; LinuxCNC: the tool table's radius of tool D, or of the tool in the
/// spindle, and for G41.1/G42.1 half the diameter D). Returns `false` when the control alarms.
pub(super) fn cutter_comp(st: &mut State, w: &Word, words: &[Word], tenths: u32) -> bool {
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    if tenths == 400 {
        st.cutter_comp = 400;
        return true;
    }
    if linuxcnc {
        if st.cutter_comp != 400 {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-COMP-ON",
                "cutter radius compensation cannot be turned on when it is already on",
            ));
            return false;
        }
        if st.plane == Axis::X {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-COMP-PLANE",
                "LinuxCNC has cutter radius compensation in the XY and XZ planes only",
            ));
            return false;
        }
    }
    let d = find(words, b'D');
    if tenths == 411 || tenths == 421 {
        // LinuxCNC: G41.1/G42.1 D<diameter> [L<orientation>], L only in G18.
        let orientation = match find(words, b'L') {
            Some(l) if st.plane != Axis::Y => {
                st.diagnostics.push(Diagnostic::error(
                    l.span,
                    "E-COMP-PLANE",
                    format!(
                        "G{}.1 with an L word (a lathe tool orientation) needs the XZ plane (G18)",
                        tenths / 10
                    ),
                ));
                return false;
            }
            Some(l) if !(0.0..=9.0).contains(&l.value.round()) => {
                st.diagnostics.push(Diagnostic::error(
                    l.span,
                    "E-COMP-ORIENTATION",
                    "a lathe tool orientation is 0 to 9",
                ));
                return false;
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
        st.diagnostics.push(Diagnostic::error(
            d.map_or(w.span, |d| d.span),
            "E-COMP-PLANE",
            format!(
                "G{} with a lathe tool (orientation {orientation}) needs the XZ plane (G18)",
                tenths / 10
            ),
        ));
        return false;
    }
    st.cutter_comp = if tenths == 420 { 420 } else { 410 };
    st.comp.orientation = orientation;
    st.comp_radius = st
        .setup
        .registers
        .get(&n)
        .map_or(0.0, |r| r.radius + r.radius_wear);
    true
}

/// A D word in a block without G41/G42: while cutter compensation is on, the Fanuc family
/// takes the new register's radius (from the end of this block's move); LinuxCNC has no use for
/// it outside G41/G42 and G96 and stops with an error. Returns `false` when the run stops.
fn new_radius_register(st: &mut State, words: &[Word], css: bool) -> bool {
    let Some(d) = find(words, b'D') else {
        return true;
    };
    if st.dialect == Dialect::LinuxCnc {
        if css {
            return true;
        }
        st.diagnostics.push(Diagnostic::error(
            d.span,
            "E-WORD-UNUSED",
            "a D word without G41, G41.1, G42, G42.1 or G96 to use it (LinuxCNC changes the radius only with G40 and a new G41/G42)",
        ));
        return false;
    }
    if st.cutter_comp == 400 {
        return true;
    }
    let n = d.value.round().max(0.0) as u32;
    known_register(st, n, d.span, "radius");
    let r = st.setup.registers.get(&n).copied().unwrap_or_default();
    st.comp_radius = r.radius + r.radius_wear;
    st.comp.orientation = r.orientation;
    true
}

/// An H word in a block without G43/G44/G49 while length compensation is on selects the new
/// register at once (H00 cancels, as KT documents); Syntec's H names the tool to measure and
/// LinuxCNC applies H only with G43.
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
    let length = st
        .setup
        .registers
        .get(&n)
        .map_or(0.0, |r| r.length + r.length_wear);
    st.length_comp = Some((n, if st.length_plus { length } else { -length }));
}

/// G43/G44 H / G49: the tool tip still follows the programmed Z; the offset is recorded.
/// G43/G44 H (`sign`: whether it adds) and G49 (`None`). Without H the Fanuc family takes the
/// last H word, LinuxCNC the tool in the spindle. Returns `false` when the run stops (LinuxCNC:
/// a tool its table does not hold).
pub(super) fn length_comp(st: &mut State, w: &Word, words: &[Word], sign: Option<bool>) -> bool {
    let Some(plus) = sign else {
        st.length_comp = None;
        return true;
    };
    let h_word = find(words, b'H');
    let h = match h_word {
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
    let length = st
        .setup
        .registers
        .get(&h)
        .map_or(0.0, |r| r.length + r.length_wear);
    st.length_comp = Some((h, if plus { length } else { -length }));
    st.length_plus = plus;
    true
}

/// Where the tool tip is relative to the gauge line under the active length offset (along the
/// plane's normal axis).
pub(super) fn tool_tip_shift(st: &State) -> DVec3 {
    let mut shift = DVec3::ZERO;
    if let Some((_, offset)) = st.length_comp {
        let (u, v) = plane_axes(st.plane);
        shift[3 - u - v] = offset;
    }
    shift
}

/// H and D words in a block without their codes, and a cutter compensation code in an arc
/// block (the Fanuc family alarms). `false` when the run stops.
pub(super) fn new_registers(st: &mut State, words: &[Word], actions: &Actions<'_>) -> bool {
    let has = |a: fn(&Action) -> bool| actions.iter().any(|(x, _)| a(x));
    new_length_register(st, words, has(|a| matches!(a, Action::LengthComp(_))));
    let comp_code = actions
        .iter()
        .find(|(a, _)| matches!(a, Action::CutterComp(_)));
    if comp_code.is_none()
        && !new_radius_register(st, words, has(|a| *a == Action::SpindleMode(true)))
    {
        return false;
    }
    if let Some((_, w)) = comp_code
        && st.dialect != Dialect::LinuxCnc
        && matches!(st.motion, Some(MotionMode::Arc { .. }))
        && axis_words(words).iter().any(Option::is_some)
    {
        st.diagnostics.push(Diagnostic::error(
            w.span,
            "E-COMP-ARC",
            format!(
                "{} starts or cancels cutter compensation only in a G00/G01 block, not with G02/G03: the control alarms and stops",
                Code::from_value(b'G', w.value).map_or_else(|| "G40–G42".to_string(), |c| c.to_string())
            ),
        ));
        return false;
    }
    true
}

/// LinuxCNC: a new length offset does not move the machine, but the point it controls is now
/// the tip, that much further from the gauge line, so the current coordinate changes at once (a
/// G91 move in the block starts from it). The Fanuc family adds the offset to the block's move
/// instead (`G91 G43 Z-32. H1` ends 32 below the old coordinate).
pub(super) fn follow_length_change(st: &mut State, length_before: f64) {
    let length_after = st.length_comp.map_or(0.0, |(_, o)| o);
    if length_after != length_before && st.dialect == Dialect::LinuxCnc {
        let (u, v) = plane_axes(st.plane);
        st.position[3 - u - v] -= length_after - length_before;
        st.resync();
    }
}
