//! The short path for plain motion blocks (most blocks of a CAM program), held to the general
//! one by a property test.

use glam::DVec3;
use swarf_syntax::codes::{self, Code};
use swarf_syntax::{Block, Word, WordForm};

use super::actions::{Action, action};
use super::feeds::{feed_word, move_feed, spindle_speed};
use super::motion::motion;
use super::{Axes, LENGTH_LETTERS, note_least_increment};
use crate::machine::MotionCounter;
use crate::state::{FeedMode, MotionMode, State};
use crate::{Sink, Source};

/// What the short path for plain motion blocks ([`plain_block`]) may take in the current state.
/// Plain blocks do not change any of it, so it holds until another kind of block runs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Shortcut {
    /// The program → machine frame offset ([`State::base`]) where a straight move needs nothing
    /// more (offsets only, feed per minute, nothing held); `None`: straight moves take [`motion`].
    offsets: Option<DVec3>,
    /// Whether G02 and G03 are the dialect's arcs.
    arcs: bool,
}

impl Shortcut {
    /// The short path in `st`, or `None` where every block needs the general one: a G66 macro
    /// is called after each move, and [`super::execute`] checks moves against a G22 stroke limit or
    /// the machine's travel.
    pub(crate) fn of(st: &State) -> Option<Shortcut> {
        if st.modal_macro.is_some()
            || (st.stroke_check && st.stroke_zone.is_some())
            || st.setup.machine.travel_mm.is_some()
        {
            return None;
        }
        let direct = st.polar.is_none()
            && st.rotation.is_none()
            && st.scaling.is_none()
            && st.mirror == DVec3::ONE
            && st.wcs_rotation == 0.0
            && st.preset_rotation == 0.0
            && st.feed_mode == FeedMode::PerMinute
            && !st.css
            && st.pending.is_none()
            && st.comp.held.is_none()
            && st.cutter_comp == 400;
        Some(Shortcut {
            offsets: direct.then(|| st.base()),
            arcs: [2.0, 3.0].iter().all(|&g| {
                Code::from_value(b'G', g)
                    .and_then(|c| codes::lookup(st.dialect, c))
                    .and_then(|d| action(st.dialect, d.group, d.code.tenths))
                    == Some(Action::Motion(Some(MotionMode::Arc { ccw: g == 3.0 })))
            }),
        })
    }
}

/// The words of a plain motion block: one `G00`–`G03` at most, X/Y/Z, for an arc I/J/K and R,
/// and F and S words, all with literal values, in a G00–G03 mode (most blocks of a CAM program).
struct PlainWords<'w> {
    /// The motion mode after the block.
    mode: MotionMode,
    /// Whether an arc's centre is given (without an end point it is a full circle).
    centre: bool,
    /// The first F and S words.
    feed: Option<&'w Word>,
    spindle: Option<&'w Word>,
    /// Whether a length word may be read in least increments (no decimal point).
    least_increment: bool,
}

impl<'w> PlainWords<'w> {
    /// The block's words sorted out, its axis words into `axes` (in place: a copy costs more than
    /// the rest), or `None` unless a plain motion block of the current mode (arcs only if `arcs`).
    #[inline(always)]
    fn of(st: &State, arcs: bool, words: &'w [Word], axes: &mut Axes<'w>) -> Option<Self> {
        let mut code = None;
        let (mut centre, mut radius) = (false, false);
        let mut feed = None;
        let mut spindle = None;
        let mut least_increment = false;
        for w in words {
            if w.form != WordForm::Plain || w.expr.is_some() {
                return None;
            }
            let length = match w.letter {
                b'X' | b'Y' | b'Z' => {
                    axes[usize::from(w.letter - b'X')] = Some(w);
                    true
                }
                b'I' | b'J' | b'K' => {
                    centre = true;
                    true
                }
                b'R' => {
                    radius = true;
                    true
                }
                b'F' => {
                    feed = feed.or(Some(w));
                    false
                }
                b'S' => {
                    spindle = spindle.or(Some(w));
                    false
                }
                b'G' if code.is_none() => {
                    code = Some(w.value);
                    false
                }
                _ => return None,
            };
            least_increment |= length && !w.has_point && w.value != 0.0;
        }
        let mode = match code {
            None => st.motion?,
            Some(0.0) => MotionMode::Rapid,
            Some(1.0) => MotionMode::Linear,
            Some(2.0) => MotionMode::Arc { ccw: false },
            Some(3.0) => MotionMode::Arc { ccw: true },
            Some(_) => return None,
        };
        let fits = match mode {
            MotionMode::Arc { .. } => arcs,
            // I/J/K/R in a straight move are warned about by the general path.
            MotionMode::Rapid | MotionMode::Linear => !centre && !radius,
            _ => false,
        };
        if !fits || matches!(st.motion, Some(MotionMode::Cycle(_))) {
            return None;
        }
        Some(PlainWords {
            mode,
            centre,
            feed,
            spindle,
            least_increment,
        })
    }
}

/// Runs a plain motion block ([`PlainWords`]) as [`super::execute`] would, minus its other passes;
/// `None`, doing nothing, for other blocks, else whether the move went to `sink` as one segment.
pub(crate) fn plain_block(
    st: &mut State,
    short: Shortcut,
    block: &Block,
    source: Source,
    sink: &mut MotionCounter<'_>,
) -> Option<bool> {
    let words = &block.words[..];
    let mut axes: Axes<'_> = [None; 3];
    let plain = PlainWords::of(st, short.arcs, words, &mut axes)?;
    let mode = plain.mode;
    if st.css {
        spindle_speed(st, plain.spindle, false);
    } else if let Some(s) = plain.spindle.filter(|s| s.value >= 0.0) {
        // What `spindle_speed` does at constant spindle speed.
        st.spindle_rpm = s.value;
    }
    feed_word(st, plain.feed);
    st.motion = Some(mode);
    if plain.least_increment {
        note_least_increment(st, LENGTH_LETTERS, words);
    }
    let rapid = mode == MotionMode::Rapid;
    match short.offsets {
        Some(base) if rapid || mode == MotionMode::Linear => {
            if axes.iter().any(Option::is_some) {
                direct_move(st, base, block, &axes, rapid, source, sink);
            }
            Some(true)
        }
        // No end point and no centre (`G02 R5.`): only the mode is set.
        _ if axes.iter().any(Option::is_some) || plain.centre => {
            motion(st, block, words, &axes, false, source, sink);
            Some(false)
        }
        _ => Some(false),
    }
}

/// A plain straight move in the [`Shortcut`]'s offsets, as [`motion`] makes it: the transforms
/// reduce to adding the offsets, and the corner and compensation stages would pass it on.
#[inline(always)]
fn direct_move(
    st: &mut State,
    base: DVec3,
    block: &Block,
    axes: &Axes<'_>,
    rapid: bool,
    source: Source,
    sink: &mut MotionCounter<'_>,
) {
    // `target` without polar coordinates, then `State::to_machine` in the frame.
    let mut p = st.program_pos;
    for (i, w) in axes.iter().enumerate() {
        if let Some(w) = w {
            let v = st.length(w);
            p[i] = if st.absolute { v } else { p[i] + v };
        }
    }
    let to = p + base;
    // `move_feed` per minute, where the move's length does not count: only a feed that is not
    // positive needs its steps (and its diagnostic).
    let feed = match st.feed_mm_per_min {
        _ if rapid => 0.0,
        feed if feed > 0.0 => feed,
        _ => move_feed(st, block, 0.0, None),
    };
    st.position = to;
    st.program_pos = p;
    // What the compensation stage does with a move when it is off.
    st.comp.prog = to;
    st.comp.tool = None;
    // On the counter itself, not through a `dyn Sink`: no dispatch to it.
    sink.straight(source, rapid, to.x, to.y, to.z, feed);
}
