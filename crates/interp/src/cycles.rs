//! Canned drilling cycles (G73, G74, G76, G81–G89) and Syntec's hole patterns (G134–G137.1): the
//! modal hole data and each cycle block's motions (§4.37–§4.51, §4.59; LinuxCNC as rs274ngc).
//!
//! Levels are kept in the program frame along the drilling axis (the plane's normal); every point
//! goes through [`State::to_machine`], so rotation, scaling, polar input and offsets apply.
//!
//! Fanuc family: R in G91 is from the initial level, Z in G91 from R; G98 returns to the initial
//! level, G99 to R; K (KT: L) repeats, K0 stores the data only. LinuxCNC: R in G91 is from the
//! current level, below R it moves up to R first, G98 returns to the higher of the start and R, and
//! L repeats with the G91 increments.

use glam::DVec3;
use swarf_syntax::{Block, Dialect, Quantity, Word, WordForm};

use crate::exec::{axis_words, given, move_feed, plane_words, target};
use crate::machine::find;
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
    /// Z (the bottom along the drilling axis) as last programmed (mm), and whether incremental.
    pub z: Option<(f64, bool)>,
    /// Peck depth (G73/G83), mm, positive.
    pub q: Option<f64>,
    /// Bottom dwell, seconds.
    pub p: Option<f64>,
    /// The level along the drilling axis (program frame) when the cycle mode was entered.
    pub initial: Option<f64>,
    /// The group-01 motion before the cycle (the Fanuc family keeps it: G80 returns to it).
    pub before: Option<MotionMode>,
    /// Syntec's `F2=` retract feed of G81 (mm/min as programmed).
    pub retract_feed: Option<f64>,
    /// GSK's slant angle E (degrees) and the drilling axis it was given for.
    pub slant: Option<(f64, usize)>,
    /// The program position when the cycle mode was entered (the slanted cycles' start).
    pub entry: Option<DVec3>,
}

/// Whether G code `tenths` is a canned cycle run in `dialect` (LinuxCNC's G76 threads).
pub(crate) fn runs(dialect: Dialect, tenths: u32) -> bool {
    match tenths {
        730 | 740 | 810 | 820 | 830 | 840 | 850 | 860 | 870 | 880 | 890 => true,
        760 => dialect != Dialect::LinuxCnc,
        831 | 841 | 851 | 871 | 881 | 891 => dialect == Dialect::Gsk,
        _ => false,
    }
}

/// Forgets the hole data (G80); the motion mode after: the one before (Fanuc family) or none.
pub(crate) fn cancel(st: &mut State) -> Option<MotionMode> {
    if st.dialect == Dialect::LinuxCnc {
        // rs274ngc keeps the last R and Z; it asks for them again when a cycle starts.
        st.cycle.initial = None;
        None
    } else {
        std::mem::take(&mut st.cycle).before
    }
}

/// The cycle mode is entered in this block: remember the initial level and the motion mode.
pub(crate) fn enter(st: &mut State) {
    st.cycle.initial = Some(st.program_pos[st.plane as usize]);
    st.cycle.entry = Some(st.program_pos);
    st.cycle.before = st.motion;
}

/// Runs one block in cycle mode `tenths`: keeps the hole data, drills; whether it moved.
pub(crate) fn run(
    st: &mut State,
    block: &Block,
    words: &[Word],
    tenths: u32,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let plain = |letter: u8| find(words, letter);
    if let Some(w) = plain(b'P') {
        let secs = st.dialect.read(w, Quantity::CycleDwellP, false, false);
        st.cycle.p = Some(secs.max(0.0));
    }
    if tenths % 10 == 1 {
        return slanted(st, block, words, tenths, source, sink);
    }
    let n = st.plane as usize;
    let drills = b"XYZ".iter().any(|&l| plain(l).is_some());
    // The hole data of the block (Syntec: Q and R only from blocks that drill).
    let keeps = drills || st.dialect != Dialect::Syntec;
    if let Some(w) = plain(b"XYZ"[n]) {
        st.cycle.z = Some((st.length(w), !st.absolute));
    }
    if keeps && let Some(w) = plain(b'R') {
        st.cycle.r = Some((st.length(w), !st.absolute));
    }
    if keeps && let Some(w) = plain(b'Q') {
        st.cycle.q = Some(st.length(w).abs());
    }
    let f2 = (words.iter()).find(|w| w.letter == b'F' && w.form == WordForm::Indexed(2));
    st.cycle.retract_feed = f2.map(|w| w.value).or(st.cycle.retract_feed);
    st.cycle.initial.get_or_insert(st.program_pos[n]);
    // Repeats: K (L in KT and LinuxCNC), not modal.
    let repeat_letter = match st.dialect {
        Dialect::Kt | Dialect::LinuxCnc => b'L',
        _ => b'K',
    };
    let repeats = match plain(repeat_letter) {
        // The Fanuc family's K counts 0 to 9999 (an L runs until the run's limit on moves).
        Some(w) if repeat_letter == b'K' && w.value > f64::from(MAX_K_REPEATS) => {
            let message = format!("the repeat count K is 0 to {MAX_K_REPEATS}");
            return st.fail(w.span, "E-NUMBER-RANGE", message);
        }
        Some(w) if w.value >= 0.0 && w.value.fract() == 0.0 => w.value as u32,
        Some(w) => {
            let l = w.letter();
            let message = format!("the repeat count `{l}` must be a whole number, 0 or more");
            return st.fail(w.span, "E-NUMBER-RANGE", message);
        }
        None => 1,
    };
    if !drills || repeats == 0 {
        return false;
    }
    let Some(plan) = Plan::new(st, block, words, tenths) else {
        return false;
    };
    // Each hole at the block's point in the plane (G91: from the hole before).
    let plane = plane_words(st, &axis_words(words, b'X'));
    let hole = |st: &State| target(st, &plane);
    let start = st.program_pos;
    // KT's L: L holes equally spaced from the start point to the programmed point.
    let line = (st.dialect == Dialect::Kt).then(|| hole(st) - start);
    let mut next = |st: &State, i: u32| match line {
        Some(step) => start + step * f64::from(i) / f64::from(repeats),
        None => hole(st),
    };
    Drill::new(st, block, &plan, source, sink).holes(repeats, &mut next);
    true
}

/// The largest repeat count K of the Fanuc family's canned cycles.
const MAX_K_REPEATS: u32 = 9999;

/// Most holes one pattern block may drill (a runaway guard: G137.1 allows 9999 × 9999).
const MAX_PATTERN_HOLES: usize = 100_000;

/// Syntec's hole patterns (§4.63) about the block's point, the K0-stored cycle at each hole: G134
/// K holes on a circle of radius I from angle J (K < 0: clockwise), G135 K at spacing I along angle
/// J, G136 on radius I at pitch P (0.001° without a point), G137.1 a P × K grid at spacings I, J.
pub(crate) fn pattern(
    st: &mut State,
    block: &Block,
    code: &Word,
    words: &[Word],
    tenths: u32,
    source: Source,
    sink: &mut dyn Sink,
) {
    let Some(MotionMode::Cycle(cycle)) = st.motion else {
        let message = "a hole pattern runs the stored canned cycle: give the cycle first (e.g. `G81 Z_ R_ F_ K0`)";
        return st.fail(code.span, "E-PATTERN-NO-CYCLE", message);
    };
    let (u, v) = plane_axes(st.plane);
    let n = 3 - u - v;
    let mut origin = target(st, &plane_words(st, &axis_words(words, b'X')));
    origin[n] = st.program_pos[n];
    let length = |st: &State, letter: u8| find(words, letter).map(|w| st.length(w));
    let angle = |letter: u8| find(words, letter).map_or(0.0, |w| w.value);
    // A count word: a whole number from 1 to 9999 (sign kept for G134's direction).
    let count = |st: &mut State, letter: u8| -> Option<i64> {
        let Some(w) = find(words, letter) else {
            let l = char::from(letter);
            let message = format!("this hole pattern needs the number of holes `{l}`");
            return st.fail(code.span, "E-WORD-MISSING", message);
        };
        let k = w.value;
        if k.fract() != 0.0 || k == 0.0 || k.abs() > 9999.0 {
            let l = w.letter();
            let message =
                format!("the number of holes `{l}` must be a whole number from 1 to 9999");
            return st.fail(w.span, "E-NUMBER-RANGE", message);
        }
        Some(k as i64)
    };
    let at = |r: f64, degrees: f64| {
        let mut p = origin;
        let a = degrees.to_radians();
        p[u] += r * a.cos();
        p[v] += r * a.sin();
        p
    };
    let points: Vec<DVec3> = match tenths {
        1340 | 1350 | 1360 => {
            // Round a circle from angle J (G134, G136), or along a line at angle J (G135).
            let r = match length(st, b'I') {
                _ if tenths == 1350 => Some(0.0),
                Some(r) if r > 0.0 => Some(r),
                _ => {
                    let message = "this hole pattern needs a positive radius `I`";
                    st.fail(code.span, "E-WORD-MISSING", message)
                }
            };
            let (Some(r), Some(k)) = (r, count(st, b'K')) else {
                return;
            };
            let (dr, da) = match tenths {
                1340 => (0.0, 360.0 / k as f64),
                1350 => (length(st, b'I').unwrap_or(0.0), 0.0),
                _ => (0.0, find(words, b'P').map_or(0.0, thousandths)),
            };
            (0..k.abs())
                .map(|i| at(r + dr * i as f64, angle(b'J') + da * i as f64))
                .collect()
        }
        _ => {
            let (Some(nx), Some(ny)) = (count(st, b'P'), count(st, b'K')) else {
                return;
            };
            let (nx, ny) = (nx.unsigned_abs() as usize, ny.unsigned_abs() as usize);
            if nx.saturating_mul(ny) > MAX_PATTERN_HOLES {
                let message = format!(
                    "this grid has {} holes; more than {MAX_PATTERN_HOLES} are not drawn",
                    nx * ny
                );
                return st.fail(code.span, "E-PATTERN-SIZE", message);
            }
            let di = length(st, b'I').unwrap_or(0.0);
            let dj = length(st, b'J').unwrap_or(0.0);
            let mut points = Vec::with_capacity(nx * ny);
            for j in 0..ny {
                for step in 0..nx {
                    let i = if j % 2 == 0 { step } else { nx - 1 - step };
                    let mut p = origin;
                    p[u] += di * i as f64;
                    p[v] += dj * j as f64;
                    points.push(p);
                }
            }
            points
        }
    };
    let Some(plan) = Plan::new(st, block, words, cycle) else {
        return;
    };
    let Ok(count) = u32::try_from(points.len()) else {
        return;
    };
    let mut next =
        |_: &State, i: u32| (points.get(i.saturating_sub(1) as usize).copied()).unwrap_or(origin);
    Drill::new(st, block, &plan, source, sink).holes(count, &mut next);
}

/// GSK's slanted-hole cycles (§4.52): G83.1–G85.1 into the end face (Z), G87.1–G89.1 into the side
/// (X), the tool tilted by E. The manual gives no geometry: R (from the initial plane) and the depth
/// (from R) are read along the tool, the return is to the initial plane, Q pecks (0.001 mm without
/// a point) go back to R, and the C-axis position is not drawn.
fn slanted(
    st: &mut State,
    block: &Block,
    words: &[Word],
    tenths: u32,
    source: Source,
    sink: &mut dyn Sink,
) -> bool {
    let end_face = matches!(tenths, 831 | 841 | 851);
    let (drill_axis, assoc, pos_letters, depth_letters) = if end_face {
        (2, 0, (b'X', b'U'), (b'Z', b'W'))
    } else {
        (0, 2, (b'Z', b'W'), (b'X', b'U'))
    };
    let position = find(words, pos_letters.0)
        .map(|w| (w, false))
        .or_else(|| find(words, pos_letters.1).map(|w| (w, true)));
    let depth = find(words, depth_letters.0).or_else(|| find(words, depth_letters.1));
    let c_word = find(words, b'C').or_else(|| find(words, b'H'));
    st.cycle.z = depth.map(|w| (st.length(w), true)).or(st.cycle.z);
    if let Some(w) = find(words, b'R') {
        st.cycle.r = Some((st.length(w), true));
    }
    if let Some(w) = find(words, b'Q') {
        // Q is in least input increments (0.001 mm) unless written with a decimal point.
        st.cycle.q = Some(st.mm(thousandths(w)).abs());
    }
    if let Some(w) = find(words, b'E') {
        st.cycle.slant = Some((w.value, drill_axis));
    }
    let entry = *st.cycle.entry.get_or_insert(st.program_pos);
    let repeats = match find(words, b'K') {
        Some(w) if w.value >= 0.0 && w.value <= 9999.0 && w.value.fract() == 0.0 => w.value as u32,
        Some(w) => {
            let message = "the repeat count K must be 0 or a whole number up to 9999";
            return st.fail(w.span, "E-NUMBER-RANGE", message);
        }
        None => 1,
    };
    let drills = position.is_some() || depth.is_some() || c_word.is_some();
    if !drills || repeats == 0 {
        return false;
    }
    let name = format!("G{}.{}", tenths / 10, tenths % 10);
    let angle = match st.cycle.slant {
        Some((e, axis)) if axis == drill_axis => e,
        Some(_) => {
            let message =
                "drills along another axis than the slant angle E was given for: give E again";
            return st.fail(block.span, "E-SLANT-ANGLE", format!("{name} {message}"));
        }
        None => 0.0,
    };
    if angle == 0.0 || angle.abs() > 60.0 {
        let message = if angle == 0.0 {
            format!(
                "{name} needs the slant angle E (E0 is an alarm: use the straight cycle for a straight hole)"
            )
        } else {
            format!("the slant angle E{angle} is out of range: −60° ≤ E ≤ 60°")
        };
        return st.fail(block.span, "E-SLANT-ANGLE", message);
    }
    let (Some((r_dist, _)), Some((depth_dist, _))) = (st.cycle.r, st.cycle.z) else {
        let l = char::from(depth_letters.0);
        let message = format!("{name} needs R and the depth `{l}` before it drills");
        return st.fail(block.span, "E-WORD-MISSING", message);
    };
    if let Some(c) = c_word {
        let message =
            "the C-axis angle of the hole is not drawn: the backplot shows X, Y and Z only";
        st.note(c.span, "N-C-AXIS", message);
    }
    let mut along = DVec3::ZERO;
    along[drill_axis] = angle.to_radians().cos();
    along[assoc] = angle.to_radians().sin();
    let peck = (st.cycle.q).filter(|q| *q > 0.0 && matches!(tenths, 831 | 871));
    // Its moves are along the slant, not at levels of a drilling axis.
    let plan = Plan {
        tenths,
        retract: st.setup.machine.peck_retract_mm.max(0.0),
        ..Plan::default()
    };
    let mut d = Drill::new(st, block, &plan, source, sink);
    for _ in 0..repeats {
        if d.stops() {
            break;
        }
        let mut start = d.st.program_pos;
        start[drill_axis] = entry[drill_axis];
        if let Some((w, incremental)) = position {
            let v = d.st.length(w);
            start[assoc] = if incremental || !d.st.absolute {
                d.st.program_pos[assoc] + v
            } else {
                v
            };
        }
        let at = |dist: f64| start + along * dist;
        let (r_point, bottom_point) = (at(r_dist), at(r_dist + depth_dist));
        d.mark(r_point, bottom_point);
        d.rapid(start);
        d.rapid(r_point);
        match tenths {
            841 | 881 => d.tap(bottom_point, r_point, d.st.spindle_dir.unwrap_or(true)),
            851 | 891 => {
                d.feed_to(bottom_point);
                d.dwell();
                d.feed_to(r_point);
            }
            _ => {
                if let Some(q) = peck {
                    let mut dist = q;
                    while dist < depth_dist.abs() - 1e-9 && !d.stops() {
                        d.feed_to(at(r_dist + dist * depth_dist.signum()));
                        d.rapid(r_point);
                        d.rapid(at(
                            r_dist + (dist - d.plan.retract).max(0.0) * depth_dist.signum()
                        ));
                        let Some(further) = d.next_peck(dist, q, false) else {
                            break;
                        };
                        dist = further;
                    }
                }
                d.feed_to(bottom_point);
                d.dwell();
                d.rapid(r_point);
            }
        }
        d.rapid(start);
    }
    true
}

/// A word's value, in thousandths where it has no decimal point.
fn thousandths(w: &Word) -> f64 {
    w.value / if w.has_point { 1.0 } else { 1000.0 }
}

/// Everything about the holes of one cycle block that does not change from hole to hole.
#[derive(Default)]
struct Plan {
    tenths: u32,
    /// The drilling axis (program frame).
    n: usize,
    r: f64,
    bottom: f64,
    initial: f64,
    peck: Option<f64>,
    retract: f64,
    /// The tapping feed in mm/min where the dialect gives the pitch rather than the feed.
    tap_feed: Option<f64>,
    /// The feed of G81's retract (Syntec `F2=`), mm/min.
    retract_feed: Option<f64>,
    /// The shift of G76/G87 at the oriented stop (machine frame).
    shift: DVec3,
    /// LinuxCNC's G87: the entry offset I/J/K (program frame) and the back bore's start.
    back: Option<(DVec3, f64)>,
}

impl Plan {
    /// The plan of a cycle block, or `None` (with a diagnostic) when its data are incomplete.
    fn new(st: &mut State, block: &Block, words: &[Word], tenths: u32) -> Option<Plan> {
        let linuxcnc = st.dialect == Dialect::LinuxCnc;
        let n = st.plane as usize;
        let Some((z_word, z_inc)) = st.cycle.z else {
            let letter = char::from(b"XYZ"[n]);
            let message =
                format!("a canned cycle needs the hole bottom ({letter}) before it drills");
            return st.fail(block.span, "E-WORD-MISSING", message);
        };
        let Some((r_word, r_inc)) = st.cycle.r else {
            let message = "a canned cycle needs the R level before it drills";
            return st.fail(block.span, "E-WORD-MISSING", message);
        };
        // rs274ngc reads the kept R and Z in the distance mode in effect.
        let inc = |given: bool| if linuxcnc { !st.absolute } else { given };
        // The initial level: captured when the cycle mode was entered (rs274ngc's `cycle_il`).
        let initial = st.cycle.initial.unwrap_or(st.program_pos[n]);
        let r = if inc(r_inc) { initial + r_word } else { r_word };
        let bottom = if inc(z_inc) { r + z_word } else { z_word };
        let back_boring = tenths == 870 && !linuxcnc;
        if back_boring && bottom < r - 1e-9 {
            let message = "G87 bores upwards from R: the end level Z must be above the R level";
            return st.fail(block.span, "E-CYCLE-LEVELS", message);
        }
        if !back_boring && bottom > r + 1e-9 {
            let message =
                "the hole bottom is above the R level: a canned cycle drills towards the bottom";
            return st.fail(block.span, "E-CYCLE-LEVELS", message);
        }
        let peck = match tenths {
            730 | 830 => {
                let q = st.cycle.q.filter(|q| *q > 0.0);
                if linuxcnc && q.is_none() {
                    let message = "G73/G83 need a positive peck depth Q";
                    return st.fail(block.span, "E-WORD-MISSING", message);
                }
                q.or(Some(DEFAULT_Q_MM))
            }
            // Syntec's peck tapping: Q given (TYPE II or III by Pr4001).
            740 | 840 if st.dialect == Dialect::Syntec => st.cycle.q.filter(|q| *q > 0.0),
            _ => None,
        };
        let retract = if linuxcnc {
            LINUXCNC_PECK_RETRACT_MM
        } else {
            st.setup.machine.peck_retract_mm.max(0.0)
        };
        if matches!(tenths, 740 | 760 | 840 | 860 | 870 | 880) && st.spindle_dir.is_none() {
            let message = format!(
                "G{} needs the spindle turning (M03/M04 before the cycle); the control alarms here",
                tenths / 10
            );
            st.warning(block.span, "W-SPINDLE-STOPPED", message);
        }
        // Tapping feed: KT's F the pitch, Syntec's E threads per inch; under G94 pitch times rpm.
        let per_minute = st.feed_mode == crate::state::FeedMode::PerMinute;
        let pitch = match (tenths, st.dialect) {
            // KT: F is the pitch in mm, or I the threads per inch.
            (740 | 840, Dialect::Kt) => {
                let tpi = find(words, b'I').filter(|i| i.value > 0.0);
                Some(tpi.map_or(st.mm(st.feed_word), |i| 25.4 / i.value))
            }
            (740 | 840, Dialect::Syntec) if !st.block_has_feed => find(words, b'E')
                .filter(|e| e.value > 0.0)
                .map(|e| 25.4 / e.value),
            _ => None,
        };
        let tap_feed = pitch.filter(|_| per_minute).map(|p| p * st.spindle_rpm);
        let retract_feed = match (tenths, st.cycle.retract_feed) {
            (810, Some(f)) if st.dialect == Dialect::Syntec && f > 0.0 => {
                if st.setup.machine.fast_drilling {
                    Some(st.mm(f))
                } else {
                    let message = "`F2=` has no effect in normal drilling (Pr4008 = 0, the setup's `fast_drilling = false`): the tool retracts at rapid";
                    st.note(block.span, "N-F2-IGNORED", message);
                    None
                }
            }
            _ => None,
        };
        let shift = if matches!(tenths, 760 | 870) && !linuxcnc {
            shift_vector(st, block, n)
        } else {
            DVec3::ZERO
        };
        let back = if tenths == 870 && linuxcnc {
            Some(linuxcnc_back(st, block, words, n, bottom)?)
        } else {
            None
        };
        Some(Plan {
            tenths,
            n,
            r,
            bottom,
            initial,
            peck,
            retract,
            tap_feed,
            retract_feed,
            shift,
            back,
        })
    }
}

/// The G76/G87 shift at the oriented stop (machine frame): Q along `shift_direction`.
fn shift_vector(st: &mut State, block: &Block, n: usize) -> DVec3 {
    let q = match st.cycle.q.filter(|q| *q > 0.0) {
        Some(q) => q,
        None if st.dialect == Dialect::Kt => DEFAULT_Q_MM,
        None => 0.0,
    };
    let along = st.setup.machine.shift_direction.vector();
    if q > 0.0 && along[n].abs() > 0.5 {
        let message = "the G76/G87 shift direction of the setup (`shift_direction`) lies along the drilling axis: no shift is made";
        return st.fail(block.span, "E-SHIFT-DIRECTION", message);
    }
    if q > 0.0 && st.dialect == Dialect::Kt && along.z != 0.0 {
        let message = "KT shifts G76/G87 along ±X or ±Y only (status parameter P018 bits 4–5): no shift is made";
        return st.fail(block.span, "E-SHIFT-DIRECTION", message);
    }
    along * q
}

/// LinuxCNC's G87 words: the entry offset I, J, K (incremental) and the back bore's start level.
fn linuxcnc_back(
    st: &mut State,
    block: &Block,
    words: &[Word],
    n: usize,
    bottom: f64,
) -> Option<(DVec3, f64)> {
    let mut ijk = axis_words(words, b'I');
    let Some(level) = ijk[n].take() else {
        let l = char::from(b"IJK"[n]);
        let message = format!("G87 needs `{l}`, the level the back bore starts from");
        return st.fail(block.span, "E-WORD-MISSING", message);
    };
    let level = st.length(level);
    let offset = given(st, &ijk, DVec3::ZERO);
    Some((offset, if st.absolute { level } else { bottom + level }))
}

/// Emits the moves of one hole.
struct Drill<'a, 's> {
    st: &'a mut State,
    block: &'a Block,
    plan: &'a Plan,
    source: Source,
    sink: &'s mut dyn Sink,
    /// The sink filled up: no more holes or pecks (reported once).
    halted: bool,
    /// A peck depth too small to go deeper was reported.
    stuck: bool,
}

impl<'a, 's> Drill<'a, 's> {
    fn new(
        st: &'a mut State,
        block: &'a Block,
        plan: &'a Plan,
        source: Source,
        sink: &'s mut dyn Sink,
    ) -> Self {
        Drill {
            st,
            block,
            plan,
            source,
            sink,
            halted: false,
            stuck: false,
        }
    }

    /// Drills `count` holes, the i-th (from 1) at `next(st, i)` (program frame).
    fn holes(&mut self, count: u32, next: &mut dyn FnMut(&State, u32) -> DVec3) {
        let linuxcnc = self.st.dialect == Dialect::LinuxCnc;
        let plan = self.plan;
        let r = plan.r;
        let mut current = self.st.program_pos[plan.n];
        let mut initial = plan.initial;
        if linuxcnc && initial < r {
            // rs274ngc: below the R level, straight up to it first.
            self.rapid(self.level(self.st.program_pos, r));
            (initial, current) = (r, r);
        }
        // G87 of the Fanuc family always returns to the initial level (G99 is ignored).
        let clear = if self.st.return_initial || (plan.tenths == 870 && !linuxcnc) {
            initial
        } else {
            r
        };
        for i in 1..=count {
            if self.stops() {
                break;
            }
            let hole = next(self.st, i);
            if linuxcnc && !(i == 1 && current > r) {
                // Later holes (and a first one from at or below R) move over at the clear level.
                current = clear;
            }
            self.mark(self.level(hole, plan.r), self.level(hole, plan.bottom));
            self.rapid(self.level(hole, current));
            if plan.tenths == 870 && !linuxcnc {
                self.back_bore(hole, current, clear);
            } else {
                if current != r && (!linuxcnc || current > r) {
                    self.rapid(self.level(hole, r));
                }
                self.hole(hole, clear);
            }
            current = clear;
        }
    }

    /// Whether the cycle stops making moves: the sink is full (reported once).
    fn stops(&mut self) -> bool {
        if !self.halted && self.sink.full() {
            self.halted = true;
            let message = "the canned cycle stops here: its holes and pecks would make more moves than the run may ([machine] max_motions), and they would not fit in memory";
            self.st.error(self.block.span, "E-MOTION-LIMIT", message);
        }
        self.halted
    }

    /// The next peck's depth, `q` past `depth`, or `None` (reported once) where `q` changes
    /// nothing.
    fn next_peck(&mut self, depth: f64, q: f64, down: bool) -> Option<f64> {
        let next = if down { depth - q } else { depth + q };
        if next != depth {
            return Some(next);
        }
        if !self.stuck {
            self.stuck = true;
            let message = format!(
                "the peck depth Q ({q:.3e} mm) is too small to go any deeper from {depth} mm: the rest of the hole is cut in one feed"
            );
            self.st.error(self.block.span, "E-CYCLE-PECK", message);
        }
        None
    }

    fn emit(&mut self, event: &Canon) {
        crate::corners::emit(self.st, self.sink, self.source, event);
    }

    /// A move to `p` (program frame), at rapid without `feed`; `shifted` by the G76/G87 shift.
    fn go(&mut self, p: DVec3, shifted: bool, feed: Option<f64>) {
        let mut to = self.st.to_machine(p);
        if shifted {
            to += self.plan.shift;
        }
        self.st.position = to;
        self.st.program_pos = p;
        self.emit(&Canon::line(feed.is_none(), to, feed.unwrap_or(0.0)));
    }

    fn rapid(&mut self, p: DVec3) {
        self.go(p, false, None);
    }

    fn rapid_shifted(&mut self, p: DVec3) {
        self.go(p, true, None);
    }

    fn feed_to(&mut self, p: DVec3) {
        let length = self.st.position.distance(self.st.to_machine(p));
        let feed =
            (self.plan.tap_feed).unwrap_or_else(|| move_feed(self.st, self.block, length, None));
        self.go(p, false, Some(feed));
    }

    fn level(&self, mut hole: DVec3, level: f64) -> DVec3 {
        hole[self.plan.n] = level;
        hole
    }

    /// Tags the motions that follow as the next hole, from `top` to `bottom` (program frame).
    fn mark(&mut self, top: DVec3, bottom: DVec3) {
        self.st.holes = self.st.holes.saturating_add(1);
        let (top, bottom) = (self.st.to_machine(top), self.st.to_machine(bottom));
        let index = self.st.holes;
        self.emit(&Canon::Hole {
            cycle: self.plan.tenths,
            index,
            top,
            bottom,
        });
    }

    fn spindle(&mut self, clockwise: Option<bool>) {
        self.st.spindle_dir = clockwise;
        let rpm = clockwise.map_or(0.0, |_| self.st.spindle_rpm);
        self.emit(&Canon::Spindle { clockwise, rpm });
    }

    /// Spindle stop at the fixed angle.
    fn orient(&mut self) {
        self.spindle(None);
        self.emit(&Canon::Orient);
    }

    fn dwell(&mut self) {
        if let Some(secs) = self.st.cycle.p.filter(|s| *s > 0.0) {
            self.emit(&Canon::Dwell { secs });
        }
    }

    /// Taps to `down` and back out to `up`, stopping and dwelling at each reversal (GSK's slanted
    /// G84.1/G88.1 at the bottom only).
    fn tap(&mut self, down: DVec3, up: DVec3, forward: bool) {
        self.feed_to(down);
        self.spindle(None);
        self.dwell();
        self.spindle(Some(!forward));
        self.feed_to(up);
        self.spindle(None);
        if self.plan.tenths.is_multiple_of(10) {
            self.dwell();
        }
        self.spindle(Some(forward));
    }

    /// The Fanuc family's G87 back boring: oriented stop, shift, down to R, back, bore up to Z.
    fn back_bore(&mut self, hole: DVec3, current: f64, clear: f64) {
        let (r, bottom) = (self.plan.r, self.plan.bottom);
        let dir = self.st.spindle_dir;
        self.orient();
        self.rapid_shifted(self.level(hole, current));
        self.rapid_shifted(self.level(hole, r));
        self.rapid(self.level(hole, r));
        self.spindle(Some(true));
        self.bore_out_shifted(hole, bottom, clear, dir);
    }

    /// Bores to `end`, dwells, stops oriented, shifts out to `clear`, restarts: G76/G87's end.
    fn bore_out_shifted(&mut self, hole: DVec3, end: f64, clear: f64, dir: Option<bool>) {
        self.feed_to(self.level(hole, end));
        self.dwell();
        self.orient();
        self.rapid_shifted(self.level(hole, end));
        self.rapid_shifted(self.level(hole, clear));
        self.rapid(self.level(hole, clear));
        self.spindle(dir.or(Some(true)));
    }

    /// From R down to the bottom and out to `clear`.
    fn hole(&mut self, hole: DVec3, clear: f64) {
        let (r, bottom) = (self.plan.r, self.plan.bottom);
        let linuxcnc = self.st.dialect == Dialect::LinuxCnc;
        match self.plan.tenths {
            730 | 830 => {
                let q = self.plan.peck.unwrap_or(DEFAULT_Q_MM);
                let full_out = self.plan.tenths == 830;
                let mut depth = r - q;
                while depth > bottom + 1e-9 && !self.stops() {
                    self.feed_to(self.level(hole, depth));
                    if full_out {
                        self.rapid(self.level(hole, r));
                    }
                    self.rapid(self.level(hole, (depth + self.plan.retract).min(r)));
                    let Some(deeper) = self.next_peck(depth, q, true) else {
                        break;
                    };
                    depth = deeper;
                }
                self.feed_to(self.level(hole, bottom));
                self.rapid(self.level(hole, clear));
            }
            850 | 890 => {
                self.feed_to(self.level(hole, bottom));
                if self.plan.tenths == 890 {
                    self.dwell();
                }
                if self.plan.tenths == 890 && linuxcnc {
                    // rs274ngc feeds G89 straight out to the clear level.
                    return self.feed_to(self.level(hole, clear));
                }
                self.feed_to(self.level(hole, r));
                if clear != r {
                    self.rapid(self.level(hole, clear));
                }
            }
            740 | 840 => {
                // Tapping: in, stop, dwell, reverse out, stop, forward again.
                let forward = self.plan.tenths == 840;
                if let Some(q) = self.plan.peck {
                    // Syntec's peck tapping: a Q at a time, out by d (Pr4001 = 1) or to R.
                    let fast = self.st.setup.machine.high_speed_peck_tapping;
                    let step_back = fast.then_some(self.plan.retract);
                    let mut depth = r - q;
                    while depth > bottom + 1e-9 && !self.stops() {
                        let out = step_back.map_or(r, |d| (depth + d).min(r));
                        self.tap(self.level(hole, depth), self.level(hole, out), forward);
                        let Some(deeper) = self.next_peck(depth, q, true) else {
                            break;
                        };
                        depth = deeper;
                    }
                }
                if linuxcnc {
                    // LinuxCNC's G84 outside XY rotates its points' axes, as rs274ngc does.
                    let plane = self.st.plane;
                    let swap = plane != crate::Axis::Z && self.plan.tenths == 840;
                    let out = |p: DVec3| match plane {
                        _ if !swap => p,
                        crate::Axis::Y => DVec3::new(p.y, p.z, p.x),
                        _ => DVec3::new(p.z, p.x, p.y),
                    };
                    if swap {
                        let message = "LinuxCNC runs G84 outside the XY plane with the axes of its feed moves rotated; they are drawn where the machine will go";
                        self.st
                            .warning(self.block.span, "W-LINUXCNC-G84-PLANE", message);
                    }
                    let (down, up) = (self.level(hole, bottom), self.level(hole, clear));
                    self.feed_to(out(down));
                    self.spindle(None);
                    self.spindle(Some(!forward));
                    self.dwell();
                    self.feed_to(out(up));
                    // rs274ngc only emits the points rotated: it goes on from where it meant to be.
                    self.st.program_pos = up;
                    self.st.position = self.st.to_machine(up);
                    self.spindle(None);
                    return self.spindle(Some(forward));
                }
                self.tap(self.level(hole, bottom), self.level(hole, r), forward);
                if clear != r {
                    self.rapid(self.level(hole, clear));
                }
            }
            760 => {
                // Fine boring: bore, dwell, oriented stop, shift away, out at rapid, shift back.
                self.bore_out_shifted(hole, bottom, clear, self.st.spindle_dir);
            }
            860 => {
                // Boring with spindle stop: out at rapid, the spindle restarted as it was.
                let dir = self.st.spindle_dir;
                self.feed_to(self.level(hole, bottom));
                if linuxcnc {
                    self.dwell();
                }
                self.spindle(None);
                self.rapid(self.level(hole, clear));
                self.spindle(dir.or(Some(true)));
            }
            870 => self.linuxcnc_back_bore(hole, clear),
            880 => {
                // Manual return: dwell, spindle stop, program stop, drawn back at the return level.
                let dir = self.st.spindle_dir;
                self.feed_to(self.level(hole, bottom));
                self.dwell();
                self.spindle(None);
                self.emit(&Canon::Pause { optional: false });
                let out = self.level(hole, clear);
                if linuxcnc {
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
                if self.plan.tenths == 820 {
                    self.dwell();
                }
                // Out at the `F2=` feed where one applies, else at rapid.
                self.go(self.level(hole, clear), false, self.plan.retract_feed);
            }
        }
    }

    /// LinuxCNC's G87 as rs274ngc runs it: by the offset entry, oriented, down to Z, bore up and
    /// back, out by the entry.
    fn linuxcnc_back_bore(&mut self, hole: DVec3, clear: f64) {
        let Some((offset, level)) = self.plan.back else {
            return;
        };
        let (r, bottom) = (self.plan.r, self.plan.bottom);
        let dir = self.st.spindle_dir;
        let entry = hole + offset;
        self.rapid(self.level(entry, r));
        self.orient();
        self.rapid(self.level(entry, bottom));
        self.rapid(self.level(hole, bottom));
        self.spindle(dir.or(Some(true)));
        self.feed_to(self.level(hole, level));
        self.feed_to(self.level(hole, bottom));
        self.orient();
        self.rapid(self.level(entry, bottom));
        self.rapid(self.level(entry, clear));
        self.rapid(self.level(hole, clear));
        self.spindle(dir.or(Some(true)));
    }
}
