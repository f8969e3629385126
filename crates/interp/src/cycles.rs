//! Canned drilling cycles (G73, G81–G83, G85, G89 and their relatives): the modal hole data and
//! the expansion of one cycle block into canonical motions, as the reference documents them
//! (§4.37–§4.51 and §4.59 of the G-code reference; LinuxCNC as rs274ngc runs them).
//!
//! All levels are kept in the program frame along the drilling axis (the normal of the selected
//! plane: Z in G17, Y in G18, X in G19); every point goes through [`State::to_machine`], so
//! rotation, scaling, polar coordinates and the offsets apply to the holes as to any move.
//!
//! Fanuc family: R in G91 is measured from the initial level (captured when the cycle mode is
//! entered), Z in G91 from R; G98 returns to the initial level, G99 to R; K (KT: L, the holes
//! along a line) repeats, K0 stores the data only. LinuxCNC: R in G91 is measured from the
//! current level, a current level below R moves up to R first, G98 returns to the higher of the
//! level at the block's start and R, and L repeats with the G91 increments.

use glam::DVec3;
use swarf_syntax::{Block, Diagnostic, Dialect, Quantity, Word, WordForm};

use crate::state::{MotionMode, State, plane_axes};
use crate::{Canon, Sink, Source};

/// LinuxCNC's fixed retract between pecks of G73/G83 (`G83_RAPID_DELTA`, 0.010 inch), mm.
const LINUXCNC_PECK_RETRACT_MM: f64 = 0.254;

/// Peck depth when Q is absent or zero (KT), mm.
const DEFAULT_Q_MM: f64 = 0.1;

/// The modal hole data of the canned cycles.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct CycleData {
    /// R as last programmed (mm), with whether it was incremental (G91).
    pub r: Option<(f64, bool)>,
    /// Z (the bottom along the drilling axis) as last programmed (mm), with whether it was
    /// incremental.
    pub z: Option<(f64, bool)>,
    /// Peck depth (G73/G83), mm, positive.
    pub q: Option<f64>,
    /// Bottom dwell, seconds.
    pub p: Option<f64>,
    /// The level along the drilling axis (program frame) when the cycle mode was entered.
    pub initial: Option<f64>,
    /// The group-01 motion before the cycle (the Fanuc family keeps it: G80 returns to it).
    pub before: Option<MotionMode>,
}

/// Whether a G code (tenths) is a canned cycle the interpreter expands.
pub(crate) fn runs(tenths: u32) -> bool {
    matches!(
        tenths,
        730 | 740 | 810 | 820 | 830 | 840 | 850 | 860 | 880 | 890
    )
}

/// Forgets the hole data and the initial level (G80 and group-01 codes in the Fanuc family);
/// returns the motion mode after G80: the group-01 mode from before the cycle in the Fanuc
/// family (the cycles are a group of their own there), none in LinuxCNC.
pub(crate) fn cancel(st: &mut State) -> Option<MotionMode> {
    if st.dialect == Dialect::LinuxCnc {
        // rs274ngc keeps the last R and Z; it asks for them again when a cycle starts.
        st.cycle.initial = None;
        None
    } else {
        let before = st.cycle.before;
        st.cycle = CycleData::default();
        before
    }
}

/// The cycle mode is entered in this block: remember the initial level and the motion mode.
pub(crate) fn enter(st: &mut State) {
    let (u, v) = plane_axes(st.plane);
    st.cycle.initial = Some(st.program_pos[3 - u - v]);
    st.cycle.before = st.motion;
}

/// Runs one block in cycle mode `tenths`: stores the hole data and drills where the block has an
/// axis word. Returns whether the tool moved.
#[allow(clippy::too_many_arguments)]
pub(crate) fn run(
    st: &mut State,
    block: &Block,
    words: &[Word],
    tenths: u32,
    target: &dyn Fn(&State) -> DVec3,
    feed: &dyn Fn(&mut State, &Block, f64) -> f64,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let linuxcnc = st.dialect == Dialect::LinuxCnc;
    let (u, v) = plane_axes(st.plane);
    let n = 3 - u - v;
    let plain = |letter: u8| {
        words
            .iter()
            .find(|w| w.form == WordForm::Plain && w.letter == letter)
    };
    let axis_letter = |i: usize| b"XYZ"[i];
    let drills = [u, v, n].iter().any(|&i| plain(axis_letter(i)).is_some());
    // The hole data of the block (Syntec: Q and R only from blocks that drill).
    let keeps = drills || st.dialect != Dialect::Syntec;
    if let Some(w) = plain(axis_letter(n)) {
        st.cycle.z = Some((st.length(w), !st.absolute));
    }
    if keeps && let Some(w) = plain(b'R') {
        st.cycle.r = Some((st.length(w), !st.absolute));
    }
    if keeps && let Some(w) = plain(b'Q') {
        st.cycle.q = Some(st.length(w).abs());
    }
    if let Some(w) = plain(b'P') {
        st.cycle.p = Some(st.dialect.read(w, Quantity::DwellP, false, false).max(0.0));
    }
    if st.cycle.initial.is_none() {
        st.cycle.initial = Some(st.program_pos[n]);
    }
    // Repeats: K (L in KT and LinuxCNC), not modal.
    let repeat_letter = match st.dialect {
        Dialect::Kt | Dialect::LinuxCnc => b'L',
        _ => b'K',
    };
    let repeats = match plain(repeat_letter) {
        Some(w) if w.value >= 0.0 && w.value.fract() == 0.0 => w.value as u32,
        Some(w) => {
            st.diagnostics.push(Diagnostic::error(
                w.span,
                "E-NUMBER-RANGE",
                format!(
                    "the repeat count `{}` must be a whole number, 0 or more",
                    w.letter()
                ),
            ));
            return false;
        }
        None => 1,
    };
    if !drills || repeats == 0 {
        return false;
    }
    let Some((z_word, z_inc)) = st.cycle.z else {
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-WORD-MISSING",
            format!(
                "a canned cycle needs the hole bottom ({}) before it drills",
                char::from(axis_letter(n))
            ),
        ));
        return false;
    };
    let Some((r_word, r_inc)) = st.cycle.r else {
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-WORD-MISSING",
            "a canned cycle needs the R level before it drills",
        ));
        return false;
    };
    let start = st.program_pos;
    let mut current = start[n];
    // The initial level: captured when the cycle mode was entered (rs274ngc's `cycle_il`).
    let mut initial = st.cycle.initial.unwrap_or(current);
    let r = if r_inc { initial + r_word } else { r_word };
    let bottom = if z_inc { r + z_word } else { z_word };
    if bottom > r + 1e-9 {
        st.diagnostics.push(Diagnostic::error(
            block.span,
            "E-CYCLE-LEVELS",
            "the hole bottom is above the R level: a canned cycle drills towards the bottom",
        ));
        return false;
    }

    let peck = match tenths {
        730 | 830 => {
            let q = st.cycle.q.filter(|q| *q > 0.0);
            if linuxcnc && q.is_none() {
                st.diagnostics.push(Diagnostic::error(
                    block.span,
                    "E-WORD-MISSING",
                    "G73/G83 need a positive peck depth Q",
                ));
                return false;
            }
            q.or(Some(DEFAULT_Q_MM))
        }
        _ => None,
    };
    let retract = if linuxcnc {
        LINUXCNC_PECK_RETRACT_MM
    } else {
        st.setup.machine.peck_retract_mm.max(0.0)
    };
    if matches!(tenths, 740 | 840 | 860 | 880) && st.spindle_dir.is_none() {
        st.diagnostics.push(Diagnostic::warning(
            block.span,
            "W-SPINDLE-STOPPED",
            format!(
                "G{} needs the spindle turning (M03/M04 before the cycle); the control alarms here",
                tenths / 10
            ),
        ));
    }
    // Tapping feed: KT's F is the pitch, Syntec's E the threads per inch (F wins when given);
    // under G94 the feed is the pitch times the spindle speed.
    let per_minute = st.feed_mode == crate::state::FeedMode::PerMinute;
    let pitch = match (tenths, st.dialect) {
        (740 | 840, Dialect::Kt) => Some(st.mm(st.feed_word)),
        (740 | 840, Dialect::Syntec) if !st.block_has_feed => plain(b'E')
            .filter(|e| e.value > 0.0)
            .map(|e| 25.4 / e.value),
        _ => None,
    };
    let tap_feed = pitch.filter(|_| per_minute).map(|p| p * st.spindle_rpm);
    let mut d = Drill {
        st,
        block,
        feed,
        tap_feed,
        source,
        sink,
        n,
    };
    if linuxcnc && initial < r {
        // rs274ngc: below the R level, straight up to it first.
        let mut p = d.st.program_pos;
        p[n] = r;
        d.rapid(p);
        initial = r;
        current = r;
    }
    let clear = if d.st.return_initial { initial } else { r };
    // KT's L: L holes equally spaced from the start point to the programmed point.
    let line = (d.st.dialect == Dialect::Kt).then(|| target(d.st) - start);
    for i in 1..=repeats {
        let hole = match line {
            Some(step) => start + step * f64::from(i) / f64::from(repeats),
            None => target(d.st),
        };
        if linuxcnc && !(i == 1 && current > r) {
            // Later holes (and a first one from at or below R) move over at the clear level.
            current = clear;
        }
        d.rapid(d.level(hole, current));
        if current != r && (!linuxcnc || current > r) {
            d.rapid(d.level(hole, r));
        }
        d.hole(tenths, hole, r, bottom, clear, peck, retract);
        current = clear;
    }
    true
}

/// Emits the moves of one hole.
struct Drill<'a, 's> {
    st: &'a mut State,
    block: &'a Block,
    feed: &'a dyn Fn(&mut State, &Block, f64) -> f64,
    /// The tapping feed in mm/min where the dialect gives the pitch rather than the feed.
    tap_feed: Option<f64>,
    source: Source,
    sink: &'s mut dyn Sink,
    /// The drilling axis.
    n: usize,
}

impl Drill<'_, '_> {
    fn rapid(&mut self, p: DVec3) {
        let to = self.st.to_machine(p);
        self.st.position = to;
        self.st.program_pos = p;
        crate::corners::emit(self.st, self.sink, self.source, &Canon::Rapid { to });
    }

    fn feed_to(&mut self, p: DVec3) {
        let to = self.st.to_machine(p);
        let length = self.st.position.distance(to);
        let feed_mm_per_min = match self.tap_feed {
            Some(f) => f,
            None => (self.feed)(self.st, self.block, length),
        };
        self.st.position = to;
        self.st.program_pos = p;
        crate::corners::emit(
            self.st,
            self.sink,
            self.source,
            &Canon::Feed {
                to,
                feed_mm_per_min,
            },
        );
    }

    fn level(&self, hole: DVec3, level: f64) -> DVec3 {
        let mut p = hole;
        p[self.n] = level;
        p
    }

    fn spindle(&mut self, clockwise: Option<bool>) {
        self.st.spindle_dir = clockwise;
        let rpm = if clockwise.is_some() {
            self.st.spindle_rpm
        } else {
            0.0
        };
        crate::corners::emit(
            self.st,
            self.sink,
            self.source,
            &Canon::Spindle { clockwise, rpm },
        );
    }

    fn dwell(&mut self) {
        if let Some(secs) = self.st.cycle.p.filter(|s| *s > 0.0) {
            crate::corners::emit(self.st, self.sink, self.source, &Canon::Dwell { secs });
        }
    }

    /// From R down to the bottom and out to `clear`.
    #[allow(clippy::too_many_arguments)]
    fn hole(
        &mut self,
        tenths: u32,
        hole: DVec3,
        r: f64,
        bottom: f64,
        clear: f64,
        peck: Option<f64>,
        retract: f64,
    ) {
        match tenths {
            730 | 830 => {
                let q = peck.unwrap_or(DEFAULT_Q_MM);
                let mut depth = r - q;
                while depth > bottom + 1e-9 {
                    self.feed_to(self.level(hole, depth));
                    if tenths == 830 {
                        self.rapid(self.level(hole, r));
                    }
                    self.rapid(self.level(hole, (depth + retract).min(r)));
                    depth -= q;
                }
                self.feed_to(self.level(hole, bottom));
                self.rapid(self.level(hole, clear));
            }
            850 | 890 => {
                self.feed_to(self.level(hole, bottom));
                if tenths == 890 {
                    self.dwell();
                }
                if tenths == 890 && self.st.dialect == Dialect::LinuxCnc {
                    // rs274ngc feeds G89 straight out to the clear level.
                    self.feed_to(self.level(hole, clear));
                    return;
                }
                self.feed_to(self.level(hole, r));
                if clear != r {
                    self.rapid(self.level(hole, clear));
                }
            }
            740 | 840 => {
                // Tapping: in with the spindle forward (G84 clockwise, G74 counter-clockwise),
                // stop, dwell, reverse and feed out, stop, (dwell,) forward again.
                let forward = tenths == 840;
                let linuxcnc = self.st.dialect == Dialect::LinuxCnc;
                self.feed_to(self.level(hole, bottom));
                self.spindle(None);
                if !linuxcnc {
                    self.dwell();
                }
                self.spindle(Some(!forward));
                if linuxcnc {
                    self.dwell();
                    self.feed_to(self.level(hole, clear));
                    self.spindle(None);
                    self.spindle(Some(forward));
                    return;
                }
                self.feed_to(self.level(hole, r));
                self.spindle(None);
                self.dwell();
                self.spindle(Some(forward));
                if clear != r {
                    self.rapid(self.level(hole, clear));
                }
            }
            860 => {
                // Boring with spindle stop: out at rapid, the spindle restarted as it was.
                let dir = self.st.spindle_dir;
                self.feed_to(self.level(hole, bottom));
                if self.st.dialect == Dialect::LinuxCnc {
                    self.dwell();
                }
                self.spindle(None);
                self.rapid(self.level(hole, clear));
                self.spindle(dir.or(Some(true)));
            }
            880 => {
                // Manual return: dwell, spindle stop, a program stop where the operator
                // retracts; the tool is drawn back at the return level before the spindle
                // restarts (rs274ngc leaves it at the bottom).
                let dir = self.st.spindle_dir;
                self.feed_to(self.level(hole, bottom));
                self.dwell();
                self.spindle(None);
                crate::corners::emit(
                    self.st,
                    self.sink,
                    self.source,
                    &Canon::Pause { optional: false },
                );
                let out = self.level(hole, clear);
                if self.st.dialect == Dialect::LinuxCnc {
                    // rs274ngc draws no return but carries on from the clear level.
                    self.st.position = self.st.to_machine(out);
                    self.st.program_pos = out;
                } else {
                    self.rapid(out);
                }
                self.spindle(dir.or(Some(true)));
            }
            _ => {
                // G81, G82.
                self.feed_to(self.level(hole, bottom));
                if tenths == 820 {
                    self.dwell();
                }
                self.rapid(self.level(hole, clear));
            }
        }
    }
}
