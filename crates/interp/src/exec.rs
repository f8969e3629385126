//! Executing one block's words in the controls' order: feed, speed and tool, the modal codes (units
//! first), coordinate-system and one-shot codes, motion, then M codes.

mod actions;
mod calls;
mod data_input;
mod feeds;
mod frames;
mod mcodes;
mod motion;
mod plain;
mod references;
mod stroke;
mod tools;

use glam::DVec3;
use smallvec::SmallVec;
use swarf_syntax::{Block, Diagnostic, Quantity, Word, WordForm};

use crate::machine::find;
use crate::state::{MotionMode, State, plane_axes};
use crate::{Sink, Source};
use actions::{Action, Actions};

pub(crate) use feeds::move_feed;
pub(crate) use motion::target;
pub(crate) use plain::{Shortcut, plain_block};

/// The axis words of a block, in millimetres where given.
pub(crate) type Axes<'w> = [Option<&'w Word>; 3];

/// What a block asks of the program's flow, carried out after it in order; the last decides.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Request {
    /// Stop the run (M02/M30, an alarm).
    Stop,
    /// `M98`/`M198`: call the subprogram the block's words name.
    Subprogram,
    /// `M99`: return from the call (to the block its P word names).
    Return,
    /// `G65`: call the macro.
    Macro(crate::state::MacroCall),
    /// After a move under G66 that kept the flow: call the modal macro (not from inside it).
    ModalMacro,
}

/// A block's requests (most blocks have none).
pub(crate) type Requests = SmallVec<[Request; 1]>;

/// The largest repeat or turn count a word may give (the manuals' 9999).
pub(crate) const MAX_COUNT: f64 = 9999.0;

/// The diagnostic for a count word out of 1–9999 (the count is clamped into the range).
pub(crate) fn count_range(w: &Word, what: &str) -> Diagnostic {
    let (l, v) = (w.letter(), w.value);
    let message =
        format!("`{l}{v}` is out of range: the number of {what} is 1 to 9999 (it is clamped)");
    Diagnostic::error(w.span, "E-NUMBER-RANGE", message)
}

/// Executes `words` (expressions evaluated): the G codes as actions, each stage in the controls'
/// order, every move checked against a G22 stroke limit or the machine's travel.
pub(crate) fn execute(
    st: &mut State,
    block: &Block,
    words: &[Word],
    source: Source,
    sink: &mut dyn Sink,
) -> Requests {
    stroke::checked(st, block, sink, |st, sink| {
        let Some(actions) = actions::of_block(st, words) else {
            return Requests::new();
        };
        if let Some(requests) = calls::macro_codes(st, words, &actions) {
            return requests;
        }
        let length_before = st.length_comp.map_or(0.0, |(_, o)| o);
        if !modal_codes(st, words, &actions, source, sink) {
            return Requests::from_elem(Request::Stop, 1);
        }
        let axes = axis_words(words, b'X');
        // In a block that runs a canned cycle K is the repeat count, not a length.
        let lengths = if matches!(st.motion, Some(MotionMode::Cycle(_))) {
            CYCLE_LENGTH_LETTERS
        } else {
            LENGTH_LETTERS
        };
        note_least_increment(st, lengths, words);
        let Some(consumed) = axis_codes(st, block, words, &axes, &actions, source, sink) else {
            return Requests::from_elem(Request::Stop, 1);
        };
        tools::follow_length_change(st, length_before);
        let probe = actions.iter().any(|(a, _)| matches!(a, Action::Probe));
        let moved = !consumed && motion::motion(st, block, words, &axes, probe, source, sink);
        // Without G codes the parser cannot tell which words the modal motion uses.
        if actions.is_empty() {
            motion::unused_arc_words(st, words);
        }
        let mut requests = mcodes::m_codes(st, words, source, sink);
        // G66: the modal macro is called after each move.
        if moved {
            requests.push(Request::ModalMacro);
        }
        requests
    })
}

/// The block's settings and modal codes, units first: T, D, H, the modes, S and F, work offset,
/// length and radius compensation, G22 and the motion mode. `false` when the run stops.
fn modal_codes(
    st: &mut State,
    words: &[Word],
    actions: &Actions<'_>,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    if !tools::settings(st, words) {
        return false;
    }
    let presets_spindle = actions.iter().any(|(a, _)| *a == Action::SetPosition);
    // Units first: the block's numbers are read in the new unit.
    for (a, _) in actions {
        match *a {
            Action::Metric(m) => st.metric = m,
            Action::Absolute(abs) => st.absolute = abs,
            Action::ArcCentres(abs) => st.arc_centres_absolute = abs,
            Action::Plane(p) => st.plane = p,
            Action::FeedMode(m) => st.feed_mode = m,
            Action::SpindleMode(css) => st.css = css,
            Action::PathMode(t) => st.path_mode = t,
            Action::ReturnLevel(initial) => st.return_initial = initial,
            Action::ModalMacro(false) => st.modal_macro = None,
            _ => {}
        }
    }
    feeds::spindle_speed(st, find(words, b'S'), presets_spindle);
    feeds::feed_word(st, find(words, b'F'));
    for (a, w) in actions {
        match *a {
            Action::WorkOffset => frames::work_offset(st, w, words),
            Action::LengthComp(sign) if !tools::length_comp(st, w, words, sign) => return false,
            Action::StrokeLimit(on) => {
                stroke::stroke_limit(st, w, words, on);
                sink.stroke_zone(source, st.stroke_zone.filter(|_| st.stroke_check).as_ref());
            }
            Action::CutterComp(t) if !tools::cutter_comp(st, w, words, t) => return false,
            Action::Motion(m) => motion::set_mode(st, m),
            _ => {}
        }
    }
    tools::new_registers(st, words, actions)
}

/// The codes that take the block's axis words as their data (frames, G28, G10, G22, G04, patterns,
/// G53 …): whether they did (the words are then no move); `None` when the run stops.
fn axis_codes(
    st: &mut State,
    block: &Block,
    words: &[Word],
    axes: &Axes<'_>,
    actions: &Actions<'_>,
    source: Source,
    sink: &mut dyn Sink,
) -> Option<bool> {
    let mut consumed = false;
    for (a, w) in actions {
        match *a {
            Action::Polar(on) => frames::polar(st, on),
            Action::MeasuredRotation => frames::measured_rotation(st, w, words),
            Action::Rotation(on) => frames::rotation(st, w, words, on),
            Action::Scaling(on) => frames::scaling(st, w, words, on),
            Action::Mirror(on) => frames::mirror(st, words, on),
            Action::Local => frames::local(st, axes),
            Action::SetPosition => frames::set_position(st, axes),
            Action::PresetZero => frames::preset_zero(st, words),
            Action::Pattern(t) => crate::cycles::pattern(st, block, w, words, t, source, sink),
            Action::Measure(second) => {
                references::measure(st, block, w, words, second, source, sink);
            }
            Action::ResetShift => {
                st.shift = DVec3::ZERO;
                st.resync();
            }
            // G10 refused stops the run.
            Action::DataInput => {
                if !data_input::data_input(st, w, words) {
                    return None;
                }
            }
            Action::Dwell => motion::dwell(st, w, words, source, sink),
            Action::Reference(n) => references::reference(st, words, axes, n, source, sink),
            Action::FromReference => references::from_reference(st, axes, source, sink),
            Action::StoreReference(n) => {
                let points = &mut st.setup.machine.reference_points;
                if points.len() < n {
                    points.resize(n, [0.0; 3]);
                }
                points[n - 1] = st.position.to_array();
            }
            Action::Machine => {
                consumed |= references::machine_move(st, block, w, axes, source, sink);
            }
            Action::DynamicLength => {
                // The tool tip still follows the program; the offset is only recorded.
                st.length_comp = Some((0, axes[2].map_or(0.0, |z| st.length(z))));
                st.length_plus = true;
            }
            // Its limits are the G22 block's words (set with the modes).
            Action::StrokeLimit(_) => {}
            _ => continue,
        }
        // The codes above take the words as their data, not a move (G53 says whether it did).
        consumed |= match *a {
            Action::Rotation(on) | Action::Scaling(on) => on,
            Action::Polar(_) | Action::Machine => false,
            _ => true,
        };
    }
    Some(consumed)
}

/// The first plain words of the three letters from `first` (X, Y, Z or I, J, K), by axis.
pub(crate) fn axis_words(words: &[Word], first: u8) -> Axes<'_> {
    let mut axes: Axes<'_> = [None; 3];
    for w in words.iter().filter(|w| w.form == WordForm::Plain) {
        if let Some(i) = w.letter.checked_sub(first).filter(|i| *i < 3) {
            axes[usize::from(i)].get_or_insert(w);
        }
    }
    axes
}

/// `p` with each coordinate that `axes` gives replaced by its word's length (mm).
pub(crate) fn given(st: &State, axes: &Axes<'_>, p: DVec3) -> DVec3 {
    let coordinate = |i: usize| axes[i].map_or(p[i], |w| st.length(w));
    DVec3::new(coordinate(0), coordinate(1), coordinate(2))
}

/// The in-plane words of `axes` (a hole's position: the normal word is its bottom).
pub(crate) fn plane_words<'w>(st: &State, axes: &Axes<'w>) -> Axes<'w> {
    let (u, v) = plane_axes(st.plane);
    let mut plane: Axes<'w> = [None; 3];
    (plane[u], plane[v]) = (axes[u], axes[v]);
    plane
}

/// The letters whose plain words are lengths (read in least input increments without a point).
const LENGTH_LETTERS: &[u8] = b"XYZIJKRQ";

/// [`LENGTH_LETTERS`] in a block that runs a canned cycle, where K is the repeat count.
const CYCLE_LENGTH_LETTERS: &[u8] = b"XYZIJRQ";

/// Notes, once per run, that a length of `lengths` without a point is read in increments.
fn note_least_increment(st: &mut State, lengths: &[u8], words: &[Word]) {
    if st.noted_least_increment || st.calculator() {
        return;
    }
    let Some(w) = words.iter().find(|w| {
        lengths.contains(&w.letter)
            && w.form == WordForm::Plain
            && !w.has_point
            && w.expr.is_none()
            && w.value != 0.0
    }) else {
        return;
    };
    st.noted_least_increment = true;
    let (unit, units) = if st.metric {
        ("0.001 mm", "mm")
    } else {
        ("0.0001 inch", "inch")
    };
    let read = st.dialect.read(w, Quantity::Length, false, !st.metric);
    let (letter, value, control) = (w.letter(), w.value, st.dialect.label());
    let message = format!(
        "`{letter}{value}` has no decimal point: {control} reads it in least input increments ({unit}) as {read} {units}; write `{letter}{value}.` for {value} {units} (or set `calculator_input = true` under [machine])"
    );
    st.note(w.span, "N-LEAST-INCREMENT", message);
}
