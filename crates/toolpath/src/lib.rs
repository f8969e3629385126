//! A compact, struct-of-arrays record of a program's motions for drawing, picking, statistics
//! and playback.
//!
//! Segment `i` runs from `end(i - 1)` (or the start point for `i == 0`) to `end(i)`. Arcs are kept
//! as tessellated chords that share the arc's source line, so the renderer only sees lines.
//!
//! # Time model
//!
//! Every segment gets the time, in seconds from the program start, at which it ends
//! ([`Timeline`]). Each move follows a trapezoidal velocity profile: it accelerates at the
//! machine's acceleration from its entry speed towards its cruise speed (the programmed feed,
//! or the rapid rate limited per axis) and decelerates to its exit speed. The speeds at the
//! joins between moves are planned over the whole path (a forward pass from the start and a
//! backward pass from the end, the speed at each join being the lower of the two), so a run
//! of short moves speeds up and slows down across blocks the way a control with look-ahead
//! does. Joins are kept simple:
//!
//! - the tool is at rest at the program start, at the end of the last move, and around every
//!   dwell, tool change, spindle or coolant command, program stop and program end;
//! - a rapid starts and ends at rest (the in-position check at the end of a G00 block);
//! - between two cutting moves the tool keeps the lower of their cruise speeds when the
//!   direction changes by at most [`CORNER_DEGREES`] (arcs use their tangent at the join) and
//!   stops at any sharper corner;
//! - the chords of one arc join smoothly, and an arc's speed is capped at `sqrt(a·r)` so that
//!   its centripetal acceleration stays within the machine's acceleration `a`.
//!
//! The backward pass sees at least [`LOOKAHEAD_SEGMENTS`] segments ahead of a join (up to the
//! next stop), like a control's look-ahead buffer, which keeps recording linear in the number
//! of segments.

use std::collections::HashSet;

use glam::DVec3;
use swarf_interp::{Arc, Canon, Machine, PlaneArc, Sink, Source, StrokeZone};

/// What a segment is, for colouring and statistics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum SegmentKind {
    /// Rapid positioning.
    Rapid,
    /// Straight cutting move.
    Feed,
    /// A chord of a circular or helical cutting move.
    Arc,
}

/// The twelve edges of the axis-aligned box between `min` and `max`, as (from, to) pairs: the
/// outline drawn for a machine's travel or a stroke limit.
pub fn box_edges(min: DVec3, max: DVec3) -> Vec<(DVec3, DVec3)> {
    let corner = |i: usize| {
        DVec3::new(
            if i & 1 == 1 { max.x } else { min.x },
            if i & 2 == 2 { max.y } else { min.y },
            if i & 4 == 4 { max.z } else { min.z },
        )
    };
    let mut edges = Vec::with_capacity(12);
    for a in 0..8usize {
        for axis in 0..3 {
            let b = a | 1 << axis;
            if b != a {
                edges.push((corner(a), corner(b)));
            }
        }
    }
    edges
}

/// An axis-aligned box in millimetres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Smallest corner.
    pub min: DVec3,
    /// Largest corner.
    pub max: DVec3,
}

impl Bounds {
    /// Grows the box to contain `p`.
    pub fn include(&mut self, p: DVec3) {
        self.min = self.min.min(p);
        self.max = self.max.max(p);
    }

    /// The box's centre.
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// The box's size along each axis.
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }
}

/// Chord tolerance for arc tessellation, in millimetres.
pub const CHORD_TOLERANCE_MM: f64 = 0.01;

/// Joins between cutting moves whose direction changes by at most this many degrees are run
/// through without stopping; the tool stops at sharper corners.
pub const CORNER_DEGREES: f64 = 10.0;

/// How many segments back the time planner revises the speeds at joins when a move is added.
pub const LOOKAHEAD_SEGMENTS: usize = 4096;

/// A value of each segment that changes rarely, kept as runs: the first segment of each run and
/// the value it holds until the next run starts (a few runs for a whole program, where an
/// array of its own would take four bytes a segment).
#[derive(Debug, Clone, Default, PartialEq)]
struct Runs {
    starts: Vec<usize>,
    values: Vec<u32>,
}

impl Runs {
    /// Gives `segment` (the newest) `value`.
    #[inline]
    fn push(&mut self, segment: usize, value: u32) {
        if self.values.last() != Some(&value) {
            self.starts.push(segment);
            self.values.push(value);
        }
    }

    /// The value of each of the first `len` segments.
    fn expand(&self, len: usize) -> Vec<u32> {
        let mut out = Vec::with_capacity(len);
        for (i, value) in self.values.iter().enumerate() {
            let end = self.starts.get(i + 1).copied().unwrap_or(len).min(len);
            out.resize(end.max(out.len()), *value);
        }
        out
    }
}

/// The machine's motion limits used by the time model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Speed along the path of a rapid move, mm/s.
    pub rapid_mm_per_s: f64,
    /// Rapid rate of each axis X, Y, Z in mm/s (infinite where an axis sets no limit of its own).
    pub rapid_axes_mm_per_s: DVec3,
    /// Path acceleration and deceleration in mm/s² (infinite: none modelled).
    pub acceleration_mm_per_s2: f64,
}

impl Default for Kinematics {
    fn default() -> Self {
        Kinematics::from_machine(&Machine::default())
    }
}

impl Kinematics {
    /// The limits given by a setup's `[machine]` section. A rate that is not a positive
    /// finite number falls back to the path rapid rate (10 m/min when that is invalid too);
    /// an acceleration that is not positive and finite means none is modelled.
    pub fn from_machine(machine: &Machine) -> Self {
        let rapid = positive(machine.rapid_mm_per_min).unwrap_or(10_000.0);
        let axes = machine
            .rapid_xyz_mm_per_min
            .map_or([f64::INFINITY; 3], |rates| {
                rates.map(|r| positive(r).unwrap_or(f64::INFINITY))
            });
        Kinematics {
            rapid_mm_per_s: rapid / 60.0,
            rapid_axes_mm_per_s: DVec3::from_array(axes) / 60.0,
            acceleration_mm_per_s2: positive(machine.acceleration_mm_per_s2)
                .unwrap_or(f64::INFINITY),
        }
    }

    /// Speed along the path of a rapid in unit `direction`: the path rapid rate, lowered so
    /// that no axis exceeds its own rate.
    pub fn rapid_speed(&self, direction: DVec3) -> f64 {
        (0..3).fold(self.rapid_mm_per_s, |v, k| {
            let share = direction[k].abs();
            if share > 1e-12 {
                v.min(self.rapid_axes_mm_per_s[k] / share)
            } else {
                v
            }
        })
    }

    /// Seconds to run `length` mm with a trapezoidal velocity profile: from `entry` speed up
    /// towards `cruise` and down to `exit` (mm/s) at this acceleration. A move too short to
    /// reach `cruise` peaks where acceleration and deceleration meet. Zero for an empty move
    /// and for a move without a feed (`cruise <= 0`).
    pub fn move_secs(&self, length: f64, cruise: f64, entry: f64, exit: f64) -> f64 {
        self.move_secs_per(length, cruise, entry, exit, self.per_acceleration())
    }

    /// One over the acceleration, which [`Kinematics::move_secs_per`] takes: worked out once
    /// for a run of moves rather than a division each.
    fn per_acceleration(&self) -> f64 {
        1.0 / self.acceleration_mm_per_s2
    }

    /// [`Kinematics::move_secs`] given `per_a`, [`Kinematics::per_acceleration`]: one division
    /// by the acceleration for every move of a run rather than four a move (the planner's
    /// passes time every move, and divisions take turns on one unit of the processor).
    #[inline]
    fn move_secs_per(&self, length: f64, cruise: f64, entry: f64, exit: f64, per_a: f64) -> f64 {
        if length <= 0.0 || cruise.is_nan() || cruise <= 0.0 {
            return 0.0;
        }
        let a = self.acceleration_mm_per_s2;
        if a.is_infinite() {
            return length / cruise;
        }
        let u = entry.clamp(0.0, cruise);
        let w = exit.clamp(0.0, cruise);
        let squared = (2.0 * a * length + u * u + w * w) / 2.0;
        // Without the square root where the move clearly reaches its feed (as in
        // `reach_capped`): the passes time every move, and square roots and divisions take
        // turns on one unit of the processor.
        let peak = if root_clearly_reaches(squared, cruise) {
            cruise
        } else {
            let peak = squared.sqrt();
            if peak < cruise {
                // Short of its feed, the move speeds up and slows down over its whole length,
                // with no steady part but the roundings of the two lengths (a few ulps of it):
                // the division that would time that part is spared.
                return ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a;
            }
            cruise
        };
        let speed_up = ((peak * peak - u * u) * (0.5 * per_a)).max(0.0);
        let slow_down = ((peak * peak - w * w) * (0.5 * per_a)).max(0.0);
        let steady = (length - speed_up - slow_down).max(0.0);
        ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a + steady / peak
    }

    /// The highest speed reachable after `length` mm starting at `speed`.
    fn reach(&self, speed: f64, length: f64) -> f64 {
        if length <= 0.0 {
            speed
        } else {
            (speed * speed + 2.0 * self.acceleration_mm_per_s2 * length).sqrt()
        }
    }

    /// `cap.min(self.reach(speed, length))` bit for bit, without the square root where the
    /// reachable speed is clearly above the cap (most joins of a long run at one feed): the
    /// planner's passes chain these, and a chain of square roots waits on each in turn.
    #[inline]
    fn reach_capped(&self, speed: f64, length: f64, cap: f64) -> f64 {
        if length > 0.0
            && root_clearly_reaches(
                speed * speed + 2.0 * self.acceleration_mm_per_s2 * length,
                cap,
            )
        {
            return cap;
        }
        cap.min(self.reach(speed, length))
    }
}

/// Whether the rounded square root of `squared` is surely at least `cap`, told without taking
/// it: the margin covers the roundings of cap² and of the root. False for a cap so small that
/// its square would underflow, where only the root itself can tell.
#[inline]
fn root_clearly_reaches(squared: f64, cap: f64) -> bool {
    cap > 1e-100 && squared >= cap * cap * (1.0 + 4.0 * f64::EPSILON)
}

fn positive(v: f64) -> Option<f64> {
    (v.is_finite() && v > 0.0).then_some(v)
}

/// A dwell (G04) before a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dwell {
    /// The segment it comes before (the segment count when it follows the last segment).
    pub segment: usize,
    /// Seconds, all the dwells between the same two segments together.
    pub secs: f64,
}

/// One hole of a canned cycle, for hole markers and hole counts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hole {
    /// The cycle's G code in tenths (810 for G81).
    pub cycle: u32,
    /// The hole's number in the run, from 1.
    pub index: u32,
    /// The R point the hole starts at (machine frame, mm).
    pub top: DVec3,
    /// The hole's bottom (machine frame, mm).
    pub bottom: DVec3,
    /// The tool that drills it.
    pub tool: u32,
    /// The 1-based line of the cycle block.
    pub line: u32,
    /// The first segment of its motions: they run up to the next hole's first segment or the
    /// next segment of another line.
    pub first_segment: usize,
}

/// What a segment of a canned cycle does in its hole, for colouring plunges and retracts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CycleMove {
    /// Into the hole along its axis at feed (drilling, boring, tapping in).
    Plunge,
    /// Out of the hole along its axis (feed or rapid).
    Retract,
    /// Any other move of the cycle (positioning, shifts).
    Other,
}

/// When each segment runs, in seconds from the program start.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Timeline {
    end_times: Vec<f64>,
    dwells: Vec<Dwell>,
}

impl Timeline {
    /// The time each segment ends (non-decreasing).
    pub fn end_times(&self) -> &[f64] {
        &self.end_times
    }

    /// The dwells, in segment order.
    pub fn dwells(&self) -> &[Dwell] {
        &self.dwells
    }

    /// The timeline of these end times and dwells (as [`Timeline::end_times`] and
    /// [`Timeline::dwells`] give them), for a copy sent from another thread or worker.
    pub fn from_parts(end_times: Vec<f64>, dwells: Vec<Dwell>) -> Self {
        Timeline { end_times, dwells }
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.end_times.len()
    }

    /// Whether there is no segment.
    pub fn is_empty(&self) -> bool {
        self.end_times.is_empty()
    }

    /// Seconds of dwell just before segment `i`.
    pub fn dwell_before(&self, i: usize) -> f64 {
        dwell_before(&self.dwells, i)
    }

    /// When segment `i` starts and ends moving (`None` past the end).
    pub fn span(&self, i: usize) -> Option<(f64, f64)> {
        let end = *self.end_times.get(i)?;
        let before = match i {
            0 => 0.0,
            _ => self.end_times.get(i - 1).copied().unwrap_or(0.0),
        };
        Some(((before + self.dwell_before(i)).min(end), end))
    }

    /// The whole run time: the end of the last segment plus any dwell after it.
    pub fn total_secs(&self) -> f64 {
        self.end_times.last().copied().unwrap_or(0.0) + self.dwell_before(self.len())
    }

    /// How many segments have finished at time `t`.
    pub fn finished_at(&self, t: f64) -> usize {
        self.end_times.partition_point(|&e| e <= t)
    }

    /// The segment running at time `t`: the first one that has not ended before `t` (so at
    /// the very end of a segment, that segment), or the last one after the end. `None` when
    /// there is no segment.
    pub fn segment_at(&self, t: f64) -> Option<usize> {
        let i = self.end_times.partition_point(|&e| e < t);
        (!self.end_times.is_empty()).then(|| i.min(self.end_times.len() - 1))
    }

    /// How far along segment `i` the tool is at time `t`, from 0 (its start, also while
    /// dwelling before it) to 1 (its end). Linear in time, a good enough place for a marker.
    pub fn fraction_at(&self, i: usize, t: f64) -> f64 {
        match self.span(i) {
            Some((start, end)) if end > start => ((t - start) / (end - start)).clamp(0.0, 1.0),
            Some((_, end)) => f64::from(u8::from(t >= end)),
            None => 1.0,
        }
    }
}

/// Seconds of dwell in `dwells` (in segment order) just before segment `i`.
fn dwell_before(dwells: &[Dwell], i: usize) -> f64 {
    let at = dwells.partition_point(|d| d.segment < i);
    dwells
        .get(at)
        .filter(|d| d.segment == i)
        .map_or(0.0, |d| d.secs)
}

/// The time model and the measures taken of each segment with it (lengths, bounds, the
/// corner between moves): the end times of the segments settled so far, and the plans of
/// those after them.
#[derive(Debug, Clone, PartialEq)]
struct Timer {
    kinematics: Kinematics,
    /// One over its acceleration ([`Kinematics::per_acceleration`]).
    per_acceleration: f64,
    /// The settled end times (a prefix of the segments).
    end_times: Vec<f64>,
    /// The segments after the settled ones, whose join speeds may still change.
    window: Vec<Plan>,
    /// Where the path starts, and where its last segment ends.
    start: DVec3,
    last_end: DVec3,
    /// The last segment's kind, and its direction at the end (of the last non-empty one), as
    /// a vector and its length ([`Heading`]).
    last_kind: Option<SegmentKind>,
    last_direction: Option<Heading>,
    /// The last straight feed in mm/min and its cruise speed in mm/s: a run of moves at one
    /// feed divides once.
    last_feed: (f64, f64),
    bounds: Option<Bounds>,
    rapid_mm: f64,
    feed_mm: f64,
}

/// A segment as the path records it for the timer: its end and speed, and whether the tool
/// came to rest before it (see [`Timer::measure`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Note {
    to: DVec3,
    /// A straight move's feed in mm/min (unused for a rapid), an arc chord's cruise in mm/s.
    speed: f64,
    kind: SegmentKind,
    /// The tool came to rest before the segment.
    stop: bool,
}

/// How a segment joins the one before and leaves, beyond its end point: `None` for a
/// straight move (both come from its direction), else an arc chord's join and exit.
type ChordJoin = Option<(Join, Option<DVec3>)>;

impl Timer {
    fn new(kinematics: Kinematics, start: DVec3) -> Self {
        Timer {
            kinematics,
            per_acceleration: kinematics.per_acceleration(),
            end_times: Vec::new(),
            window: Vec::new(),
            start,
            last_end: start,
            last_kind: None,
            last_direction: None,
            last_feed: (0.0, 0.0),
            bounds: None,
            rapid_mm: 0.0,
            feed_mm: 0.0,
        }
    }

    /// Takes in the newest segment `note`, after `dwell` seconds of dwell: its length, the
    /// box and the distances grow by it, and the planner gets it with its cruise speed and
    /// whether it joins the one before without stopping. A straight move's direction gives
    /// its join and, for a rapid, its cruise speed; an arc's chord comes with its own (`chord`).
    #[inline(always)]
    fn measure(&mut self, note: &Note, dwell: f64, chord: ChordJoin) {
        let Note {
            to,
            speed,
            kind,
            stop,
        } = *note;
        let delta = to - self.last_end;
        let length = delta.length();
        let (cruise, entry, exit) = match chord {
            // A feed of an ordinary length: its direction is the move itself over its length,
            // with no division (the corner test below takes the lengths).
            None if kind != SegmentKind::Rapid
                && (HEADING_LEAST..HEADING_MOST).contains(&length) =>
            {
                let cruise = if speed.to_bits() == self.last_feed.0.to_bits() {
                    self.last_feed.1
                } else {
                    let cruise = speed / 60.0;
                    self.last_feed = (speed, cruise);
                    cruise
                };
                let heading = Some(Heading::new(delta, length));
                (cruise, Some(heading), heading)
            }
            None => {
                // `delta.try_normalize()`, reusing the length.
                let rcp = 1.0 / length;
                let direction = (rcp.is_finite() && rcp > 0.0).then(|| delta * rcp);
                let cruise = match kind {
                    SegmentKind::Rapid => direction.map_or(self.kinematics.rapid_mm_per_s, |d| {
                        self.kinematics.rapid_speed(d)
                    }),
                    SegmentKind::Feed | SegmentKind::Arc => speed / 60.0,
                };
                let heading = direction.map(Heading::unit);
                (cruise, Some(heading), heading)
            }
            Some((Join::Continue, exit)) => (speed, None, exit.map(Heading::unit)),
            Some((Join::Corner { entry }, exit)) => (
                speed,
                Some(entry.map(Heading::unit)),
                exit.map(Heading::unit),
            ),
        };
        match kind {
            SegmentKind::Rapid => self.rapid_mm += length,
            SegmentKind::Feed | SegmentKind::Arc => self.feed_mm += length,
        }
        // Each segment starts where the last one ended, already inside the box.
        if let Some(bounds) = &mut self.bounds {
            bounds.include(to);
        } else {
            let mut bounds = Bounds {
                min: self.start,
                max: self.start,
            };
            bounds.include(to);
            self.bounds = Some(bounds);
        }
        // `entry`: `None` for the next chord of an arc, else the new move's direction (`None`
        // inside for an empty move).
        let smooth = match entry {
            _ if stop => false,
            None => true,
            Some(_) if kind == SegmentKind::Rapid || self.last_kind == Some(SegmentKind::Rapid) => {
                false
            }
            Some(None) => true,
            Some(Some(entry)) => self
                .last_direction
                .is_none_or(|last| last.within_corner_of(entry)),
        };
        if let Some(exit) = exit {
            self.last_direction = Some(exit);
        }
        self.last_end = to;
        self.last_kind = Some(kind);
        self.add(length, cruise, smooth, dwell);
    }

    /// Adds the newest segment to the planner. Segments are settled (their end times
    /// written) at every stop, and in batches of [`LOOKAHEAD_SEGMENTS`] when a long run
    /// without stops fills twice that, so each segment is planned a bounded number of times.
    #[inline(always)]
    fn add(&mut self, length: f64, cruise: f64, smooth: bool, dwell: f64) {
        let k = self.kinematics;
        let cruise = if cruise.is_nan() {
            0.0
        } else {
            cruise.max(0.0)
        };
        let limit = match self.window.last() {
            Some(previous) if smooth => previous.cruise.min(cruise),
            _ => 0.0,
        };
        if limit <= 0.0 {
            // Nothing before a stop changes any more.
            if let [lone] = self.window[..] {
                // A program that stops at every corner settles each move on its own.
                let start = self.end_times.last().copied().unwrap_or(0.0);
                self.end_times
                    .push(lone_end_time(&lone, k, self.per_acceleration, start));
                self.window.clear();
            } else {
                self.settle(self.window.len());
            }
        }
        let forward = self
            .window
            .last()
            .map_or(0.0, |p| k.reach_capped(p.forward, p.length, limit));
        self.window.push(Plan {
            length,
            cruise,
            limit,
            forward,
            dwell,
        });
        if self.window.len() >= 2 * LOOKAHEAD_SEGMENTS {
            self.settle(LOOKAHEAD_SEGMENTS);
        }
    }

    /// End times of the first `count` segments not settled yet, the tool stopping at the end
    /// of the last: a backward pass from there gives the highest speed at each join from which
    /// the tool can still stop in time, and each join runs at the lower of that and the
    /// forward speed.
    fn window_end_times(&self, count: usize) -> Vec<f64> {
        let mut times = Vec::with_capacity(count.min(self.window.len()));
        let start = self.end_times.last().copied().unwrap_or(0.0);
        window_end_times(&self.window, self.kinematics, start, count, &mut times);
        times
    }

    /// Writes the end times of the first `count` unsettled segments and forgets their plans.
    fn settle(&mut self, count: usize) {
        let count = count.min(self.window.len());
        if count == 0 {
            return;
        }
        let start = self.end_times.last().copied().unwrap_or(0.0);
        window_end_times(
            &self.window,
            self.kinematics,
            start,
            count,
            &mut self.end_times,
        );
        if count == self.window.len() {
            self.window.clear();
        } else {
            self.window.drain(..count);
        }
    }
}

/// Lengths of a straight feed whose direction is kept as the move and its length (see
/// [`Heading`]): products of two such lengths neither overflow nor lose precision.
const HEADING_LEAST: f64 = 1e-100;
const HEADING_MOST: f64 = 1e100;

/// A direction of travel: `vector` over `length` (1 for a unit vector), so that a straight
/// move's comes without a division (divisions and square roots take turns on one unit of the
/// processor, and the time model has several a move).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Heading {
    vector: DVec3,
    length: f64,
}

impl Heading {
    fn new(vector: DVec3, length: f64) -> Self {
        Heading { vector, length }
    }

    fn unit(vector: DVec3) -> Self {
        Heading::new(vector, 1.0)
    }

    /// Whether the turn from this direction to `next` is at most [`CORNER_DEGREES`] (with a
    /// margin of 1e-12 on the cosine): the dot product of the two directions against the
    /// cosine, both sides times the two lengths.
    #[inline(always)]
    fn within_corner_of(self, next: Heading) -> bool {
        self.vector.dot(next.vector)
            >= (CORNER_DEGREES.to_radians().cos() - 1e-12) * (self.length * next.length)
    }
}

/// The planner's view of one of the segments not settled yet (see the crate documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Plan {
    length: f64,
    /// Cruise speed, mm/s.
    cruise: f64,
    /// Highest speed allowed at the join where the segment starts.
    limit: f64,
    /// Highest entry speed reachable from the program start.
    forward: f64,
    /// Seconds of dwell before the segment.
    dwell: f64,
}

/// How a new segment joins the previous one.
#[derive(Debug, Clone, Copy)]
enum Join {
    /// The next chord of the same arc.
    Continue,
    /// A new move: stop or not by kind and angle, `entry` being its direction at the start
    /// (`None` for an empty move).
    Corner { entry: Option<DVec3> },
}

/// The recorded motions of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    start: DVec3,
    ends: Vec<DVec3>,
    kinds: Vec<SegmentKind>,
    lines: Vec<u32>,
    /// The feed of each segment (its `f32` bits) and its tool, as runs: both change rarely.
    feeds: Runs,
    segment_tools: Runs,
    /// The time model (with the limits the path uses too) and the measures taken with it.
    timer: Timer,
    /// The most segments the path holds before it reports itself full (memory's limit).
    max_segments: usize,
    /// Every dwell, in segment order.
    dwells: Vec<Dwell>,
    tools: Listed<u32>,
    tool: u32,
    /// A non-motion event since the last segment: the next one starts at rest.
    stop_pending: bool,
    /// The holes drilled by canned cycles, in order.
    holes: Vec<Hole>,
    /// The program zeros the moves were programmed from, each once, in order of first use.
    origins: Listed<DVec3>,
    /// The programmed motions of blocks cut under cutter radius compensation.
    programmed: Vec<(u32, Canon)>,
    /// The G22 stroke limits the program switched on, each once, in order.
    zones: Listed<StrokeZone>,
}

/// The most tools, program zeros and G22 zones a toolpath lists: a loop that changes them at
/// every pass lists no more (they are marks and names, not motion).
const MAX_LISTED: usize = 10_000;

/// Values listed once each, in order of first use, at most [`MAX_LISTED`]; a value is looked
/// up by its bits in a set, not in the list.
#[derive(Debug, Clone, PartialEq)]
struct Listed<T> {
    items: Vec<T>,
    seen: HashSet<[u64; 7]>,
}

impl<T> Default for Listed<T> {
    fn default() -> Self {
        Listed {
            items: Vec::new(),
            seen: HashSet::new(),
        }
    }
}

impl<T> Listed<T> {
    fn add(&mut self, item: T, key: [u64; 7]) {
        if self.items.len() < MAX_LISTED && self.seen.insert(key) {
            self.items.push(item);
        }
    }
}

/// The bits of a point, for [`Listed`].
fn point_key(p: DVec3) -> [u64; 7] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits(), 0, 0, 0, 0]
}

impl Default for Toolpath {
    fn default() -> Self {
        Toolpath::new(DVec3::ZERO, 10_000.0)
    }
}

impl Toolpath {
    /// An empty toolpath starting at `start`, timed with rapids at `rapid_mm_per_min` and the
    /// default machine's other limits (see [`Machine`]).
    pub fn new(start: DVec3, rapid_mm_per_min: f64) -> Self {
        let machine = Machine {
            rapid_mm_per_min,
            ..Machine::default()
        };
        Toolpath::with_kinematics(start, Kinematics::from_machine(&machine))
    }

    /// An empty toolpath starting at `start`, timed with the limits of a setup's `[machine]`,
    /// and holding at most its `max_motions` segments (see [`Sink::full`]).
    pub fn for_machine(start: DVec3, machine: &Machine) -> Self {
        let mut path = Toolpath::with_kinematics(start, Kinematics::from_machine(machine));
        path.max_segments = max_segments(machine);
        path
    }

    /// Makes room for `segments` more segments at once (e.g. one per block of the program),
    /// sparing the copies of arrays that grow while a big program is recorded.
    pub fn reserve(&mut self, segments: usize) {
        self.ends.reserve(segments);
        self.kinds.reserve(segments);
        self.lines.reserve(segments);
        self.timer.end_times.reserve(segments);
    }

    /// An empty toolpath starting at `start`, timed with `kinematics`.
    pub fn with_kinematics(start: DVec3, kinematics: Kinematics) -> Self {
        Toolpath {
            start,
            ends: Vec::new(),
            kinds: Vec::new(),
            lines: Vec::new(),
            feeds: Runs::default(),
            segment_tools: Runs::default(),
            timer: Timer::new(kinematics, start),
            max_segments: max_segments(&Machine::default()),
            dwells: Vec::new(),
            tools: Listed::default(),
            tool: 0,
            stop_pending: false,
            holes: Vec::new(),
            origins: Listed::default(),
            programmed: Vec::new(),
            zones: Listed::default(),
        }
    }

    /// The programmed contour of the blocks cut under cutter radius compensation, as (line,
    /// programmed motion) in order: the segments hold the tool centre's compensated path, this
    /// the part's outline, so a backplot can draw both.
    pub fn programmed(&self) -> &[(u32, Canon)] {
        &self.programmed
    }

    /// Whether the segments of `line` were compensated (their programmed motion differs from
    /// the drawn one and is in [`Toolpath::programmed`]).
    pub fn is_compensated_line(&self, line: u32) -> bool {
        self.programmed.iter().any(|(l, _)| *l == line)
    }

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// Whether there is no segment.
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Where the tool was before the first segment.
    pub fn start(&self) -> DVec3 {
        self.start
    }

    /// Start point of segment `i`.
    pub fn segment_start(&self, i: usize) -> DVec3 {
        if i == 0 {
            self.start
        } else {
            self.ends.get(i - 1).copied().unwrap_or(self.start)
        }
    }

    /// End points of all segments.
    pub fn ends(&self) -> &[DVec3] {
        &self.ends
    }

    /// Kinds of all segments.
    pub fn kinds(&self) -> &[SegmentKind] {
        &self.kinds
    }

    /// 1-based source line of each segment.
    pub fn lines(&self) -> &[u32] {
        &self.lines
    }

    /// Feed rate of each segment in mm/min (0 for rapids); made on each call from the runs
    /// of equal feeds the path keeps.
    pub fn feeds(&self) -> Vec<f32> {
        self.feeds
            .expand(self.ends.len())
            .into_iter()
            .map(f32::from_bits)
            .collect()
    }

    /// The tool in the spindle during each segment (the last tool change's number; 0 before
    /// the first); made on each call from the runs the path keeps.
    pub fn segment_tools(&self) -> Vec<u32> {
        self.segment_tools.expand(self.ends.len())
    }

    /// When each segment runs (see the crate documentation for the model). Built on each
    /// call: the last segments' times are only settled when asked, since every new move may
    /// still change them.
    pub fn timeline(&self) -> Timeline {
        let timer = &self.timer;
        let mut end_times = timer.end_times.clone();
        end_times.extend(timer.window_end_times(timer.window.len()));
        Timeline {
            end_times,
            dwells: self.dwells.clone(),
        }
    }

    /// The limits the times are computed with.
    pub fn kinematics(&self) -> Kinematics {
        self.timer.kinematics
    }

    /// The box containing every point of the path (`None` when nothing moved).
    pub fn bounds(&self) -> Option<Bounds> {
        self.timer.bounds
    }

    /// Total rapid distance in mm.
    pub fn rapid_length_mm(&self) -> f64 {
        self.timer.rapid_mm
    }

    /// Total cutting distance in mm.
    pub fn feed_length_mm(&self) -> f64 {
        self.timer.feed_mm
    }

    /// Estimated run time in seconds: every move with acceleration, plus the dwells.
    pub fn estimated_secs(&self) -> f64 {
        let timer = &self.timer;
        let last = timer
            .window_end_times(timer.window.len())
            .last()
            .or(timer.end_times.last())
            .copied()
            .unwrap_or(0.0);
        last + dwell_before(&self.dwells, self.ends.len())
    }

    /// Tools used, in order of first use.
    pub fn tools(&self) -> &[u32] {
        &self.tools.items
    }

    /// The program zeros (work offsets with their shifts, machine frame) the moves were
    /// programmed from, each once, in order of first use.
    pub fn origins(&self) -> &[DVec3] {
        &self.origins.items
    }

    /// The G22 stroke limits (machine coordinates) the program switched on, each once, in
    /// order: for drawing the protected zones and soft limits.
    pub fn zones(&self) -> &[StrokeZone] {
        &self.zones.items
    }

    /// The corners (min, max; machine coordinates) of the boxes to draw for [`Self::zones`]:
    /// an axis a limit leaves open reaches a tenth of the toolpath's diagonal (at least 1 mm)
    /// past its bounds on that side.
    pub fn zone_boxes(&self) -> Vec<(DVec3, DVec3)> {
        let bounds = self.timer.bounds.unwrap_or(Bounds {
            min: self.start,
            max: self.start,
        });
        let margin = ((bounds.max - bounds.min).length() * 0.1).max(1.0);
        let or = |limit: f64, open: f64| if limit.is_finite() { limit } else { open };
        self.zones
            .items
            .iter()
            .map(|z| {
                let (mut min, mut max) = (DVec3::ZERO, DVec3::ZERO);
                for axis in 0..3 {
                    min[axis] = or(z.min[axis], bounds.min[axis].min(z.max[axis]) - margin);
                    max[axis] = or(z.max[axis], bounds.max[axis].max(z.min[axis]) + margin);
                }
                (min, max)
            })
            .collect()
    }

    /// The holes drilled by canned cycles, in order.
    pub fn holes(&self) -> &[Hole] {
        &self.holes
    }

    /// The number of holes each tool drills, by tool number in order of first use.
    pub fn holes_per_tool(&self) -> Vec<(u32, usize)> {
        let mut counts: Vec<(u32, usize)> = Vec::new();
        for hole in &self.holes {
            match counts.iter_mut().find(|(t, _)| *t == hole.tool) {
                Some((_, n)) => *n += 1,
                None => counts.push((hole.tool, 1)),
            }
        }
        counts
    }

    /// Every segment of a canned cycle with what it does in its hole, in segment order.
    pub fn cycle_moves(&self) -> Vec<(usize, CycleMove)> {
        let mut out = Vec::new();
        for (i, hole) in self.holes.iter().enumerate() {
            let end = self
                .holes
                .get(i + 1)
                .map_or(self.ends.len(), |h| h.first_segment)
                .min(self.ends.len());
            let axis = (hole.bottom - hole.top).normalize_or_zero();
            for s in hole.first_segment..end {
                if self.lines.get(s) != Some(&hole.line) {
                    break;
                }
                let d = self.ends[s] - self.segment_start(s);
                let along = d.dot(axis);
                let lateral = (d - axis * along).length();
                let on_axis = lateral <= 1e-6 * (1.0 + along.abs()) && along.abs() > 1e-9;
                let role = match self.kinds.get(s) {
                    Some(SegmentKind::Feed) if on_axis && along > 0.0 => CycleMove::Plunge,
                    _ if on_axis && along < 0.0 => CycleMove::Retract,
                    _ => CycleMove::Other,
                };
                out.push((s, role));
            }
        }
        out
    }

    /// The hole a segment drills (an index into [`Toolpath::holes`]), if it is one of a
    /// canned cycle's motions.
    pub fn hole_of_segment(&self, segment: usize) -> Option<usize> {
        let i = self
            .holes
            .partition_point(|h| h.first_segment <= segment)
            .checked_sub(1)?;
        let hole = self.holes.get(i)?;
        (self.lines.get(segment) == Some(&hole.line)).then_some(i)
    }

    /// The first segment caused by source `line` (1-based), for jumping from code to path.
    pub fn first_segment_of_line(&self, line: u32) -> Option<usize> {
        self.lines.iter().position(|&l| l == line)
    }

    /// Records a segment to `to` with `speed` (a straight move's feed in mm/min, an arc chord's
    /// cruise in mm/s) and, for an arc's chord, its join and exit (`chord`), then has the
    /// timer measure and time it.
    #[inline(always)]
    fn push(
        &mut self,
        kind: SegmentKind,
        to: DVec3,
        line: u32,
        feed_mm_per_min: f64,
        speed: f64,
        chord: ChordJoin,
    ) {
        self.ends.push(to);
        self.kinds.push(kind);
        self.lines.push(line);
        let segment = self.ends.len() - 1;
        self.feeds.push(segment, (feed_mm_per_min as f32).to_bits());
        self.segment_tools.push(segment, self.tool);
        // The dwells are in segment order and none comes after the newest segment yet.
        let dwell = match self.dwells.last() {
            Some(d) if d.segment == segment => d.secs,
            _ => 0.0,
        };
        let note = Note {
            to,
            speed,
            kind,
            stop: self.stop_pending,
        };
        self.stop_pending = false;
        self.timer.measure(&note, dwell, chord);
    }

    fn push_line(&mut self, kind: SegmentKind, to: DVec3, line: u32, feed_mm_per_min: f64) {
        self.push(kind, to, line, feed_mm_per_min, feed_mm_per_min, None);
    }

    fn push_arc(&mut self, arc: &Arc, line: u32) {
        let from = self.ends.last().copied().unwrap_or(self.start);
        let geometry = arc.plane(from);
        let radius = geometry
            .radius
            .min(geometry.end_radius)
            .max(CHORD_TOLERANCE_MM);
        let centripetal = (self.timer.kinematics.acceleration_mm_per_s2 * radius).sqrt();
        let cruise = (arc.feed_mm_per_min / 60.0).min(centripetal);
        let count = geometry.chords();
        // The points between the ends need the start's angle: an arc of one chord spares it.
        let mut a0 = None;
        for k in 0..count {
            let p = if k + 1 == count {
                arc.to
            } else {
                let a0 = *a0.get_or_insert_with(|| geometry.start_angle());
                geometry.between(a0, k + 1, count, from, arc.to)
            };
            let join = if k == 0 {
                Join::Corner {
                    entry: geometry.end_tangent(from, arc.to, false),
                }
            } else {
                Join::Continue
            };
            let exit = if k + 1 == count {
                geometry.end_tangent(from, arc.to, true)
            } else {
                None
            };
            self.push(
                SegmentKind::Arc,
                p,
                line,
                arc.feed_mm_per_min,
                cruise,
                Some((join, exit)),
            );
        }
    }

    /// A dwell, tool change or other non-motion command: the tool comes to rest.
    fn stop(&mut self) {
        self.stop_pending = true;
    }
}

/// Appends to `out` the end times of the first `count` segments of `window`, the first
/// starting at `start` seconds (see [`Toolpath::window_end_times`]). The join speeds are
/// written where the times go and replaced by them in turn, so no other buffer is needed; a
/// window of one segment is timed directly.
fn window_end_times(window: &[Plan], k: Kinematics, start: f64, count: usize, out: &mut Vec<f64>) {
    let count = count.min(window.len());
    if let [p] = window {
        if count == 1 {
            out.push(lone_end_time(p, k, k.per_acceleration(), start));
        }
        return;
    }
    // The entry speed of each segment: the lower of the forward speed and the highest speed
    // from which the tool can still stop at the end of the window.
    let base = out.len();
    out.resize(base + window.len(), 0.0);
    let entries = &mut out[base..];
    let mut backward = 0.0;
    for (entry, p) in entries.iter_mut().zip(window).rev() {
        backward = k.reach_capped(backward, p.length, p.limit);
        *entry = p.forward.min(backward);
    }
    let per_a = k.per_acceleration();
    let mut t = start;
    for i in 0..count {
        let p = &window[i];
        let exit = entries.get(i + 1).copied().unwrap_or(0.0);
        t += p.dwell + k.move_secs_per(p.length, p.cruise, entries[i], exit, per_a);
        entries[i] = t;
    }
    out.truncate(base + count);
}

/// The end time of a window's only segment `p`, which starts at `start` seconds and ends at
/// rest (what [`window_end_times`] gives for a window of one). A window of one starts at a
/// stop (the window only restarts at one, and a partial settle leaves many segments), so its
/// limit and entry speed are zero.
#[inline]
fn lone_end_time(p: &Plan, k: Kinematics, per_a: f64, start: f64) -> f64 {
    debug_assert!(
        p.limit <= 0.0 && p.forward <= 0.0,
        "a lone segment starts at rest"
    );
    start + (p.dwell + k.move_secs_per(p.length, p.cruise, 0.0, 0.0, per_a))
}

/// The most segments a toolpath for `machine` holds: as many as the moves a run may make, an
/// arc's chords counting one each (a loop of arcs fills the memory faster than one of lines).
fn max_segments(machine: &Machine) -> usize {
    usize::try_from(machine.max_motions).unwrap_or(usize::MAX)
}

impl Sink for Toolpath {
    fn origin(&mut self, at: DVec3) {
        self.origins.add(at, point_key(at));
    }

    fn stroke_zone(&mut self, _source: Source, zone: Option<&StrokeZone>) {
        if let Some(zone) = zone {
            let [a, b, c, ..] = point_key(zone.min);
            let [d, e, f, ..] = point_key(zone.max);
            self.zones
                .add(*zone, [a, b, c, d, e, f, u64::from(zone.inside_forbidden)]);
        }
    }

    fn emit(&mut self, source: Source, event: &Canon) {
        match event {
            Canon::Rapid { to } => self.push_line(SegmentKind::Rapid, *to, source.line, 0.0),
            Canon::Feed {
                to,
                feed_mm_per_min,
            } => self.push_line(SegmentKind::Feed, *to, source.line, *feed_mm_per_min),
            Canon::Arc(arc) => self.push_arc(arc, source.line),
            Canon::Dwell { secs } => {
                self.stop();
                let secs = if secs.is_finite() { secs.max(0.0) } else { 0.0 };
                let segment = self.ends.len();
                match self.dwells.last_mut() {
                    Some(d) if d.segment == segment => d.secs += secs,
                    _ => self.dwells.push(Dwell { segment, secs }),
                }
            }
            Canon::ToolChange { tool } => {
                self.stop();
                self.tool = *tool;
                self.tools.add(*tool, [u64::from(*tool), 0, 0, 0, 0, 0, 0]);
            }
            Canon::Hole {
                cycle,
                index,
                top,
                bottom,
            } => self.holes.push(Hole {
                cycle: *cycle,
                index: *index,
                top: *top,
                bottom: *bottom,
                tool: self.tool,
                line: source.line,
                first_segment: self.ends.len(),
            }),
            Canon::Spindle { .. }
            | Canon::Coolant { .. }
            | Canon::Pause { .. }
            | Canon::Orient
            | Canon::End => {
                self.stop();
            }
        }
    }

    fn straight(&mut self, source: Source, rapid: bool, x: f64, y: f64, z: f64, feed: f64) {
        let kind = if rapid {
            SegmentKind::Rapid
        } else {
            SegmentKind::Feed
        };
        self.push_line(kind, DVec3::new(x, y, z), source.line, feed);
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.programmed.push((source.line, event.clone()));
    }

    /// Full when its segments and the rest it keeps with them (a dwell weighing as much as a
    /// segment, a hole or a compensated block's programmed motion as two) reach
    /// `max_motions` segments: the memory a run may take.
    fn full(&self) -> bool {
        self.ends.len() + self.dwells.len() + 2 * (self.holes.len() + self.programmed.len())
            >= self.max_segments
    }
}

/// What drawing and timing an arc need beyond its plane geometry: its chords and tangents.
trait ArcDrawing {
    /// How many chords the arc takes to stay within [`CHORD_TOLERANCE_MM`].
    fn chords(&self) -> usize;
    /// The unit direction of motion at parameter `t` (`None` for a degenerate arc).
    fn tangent(&self, from: DVec3, to: DVec3, t: f64) -> Option<DVec3>;
    /// [`ArcDrawing::tangent`] at the start (`end` false) or the end, the angle's cosine and
    /// sine read off that end's offset from the centre rather than worked out from the angle.
    fn end_tangent(&self, from: DVec3, to: DVec3, end: bool) -> Option<DVec3>;
    /// The unit direction of motion where the radius is `r` and the angle has cosine `cos`
    /// and sine `sin`.
    fn tangent_with(&self, from: DVec3, to: DVec3, r: f64, cos: f64, sin: f64) -> Option<DVec3>;
}

impl ArcDrawing for PlaneArc {
    fn chords(&self) -> usize {
        let tau = std::f64::consts::TAU;
        let step = if self.radius > CHORD_TOLERANCE_MM {
            2.0 * (1.0 - CHORD_TOLERANCE_MM / self.radius).acos()
        } else {
            tau / 4.0
        };
        ((self.sweep.abs() / step.max(1e-3)).ceil() as usize).clamp(1, 100_000)
    }

    fn tangent(&self, from: DVec3, to: DVec3, t: f64) -> Option<DVec3> {
        let a = self.start_angle() + self.sweep * t;
        let r = self.radius + (self.end_radius - self.radius) * t;
        self.tangent_with(from, to, r, a.cos(), a.sin())
    }

    fn end_tangent(&self, from: DVec3, to: DVec3, end: bool) -> Option<DVec3> {
        let (r, (u, v)) = if end {
            (self.end_radius, self.end_offset)
        } else {
            (self.radius, self.start_offset)
        };
        if r > 0.0 {
            self.tangent_with(from, to, r, u / r, v / r)
        } else {
            self.tangent(from, to, f64::from(u8::from(end)))
        }
    }

    fn tangent_with(&self, from: DVec3, to: DVec3, r: f64, cos: f64, sin: f64) -> Option<DVec3> {
        let dr = self.end_radius - self.radius;
        let mut d = DVec3::ZERO;
        d[self.iu] = dr * cos - r * sin * self.sweep;
        d[self.iv] = dr * sin + r * cos * self.sweep;
        d[self.iw] = to[self.iw] - from[self.iw];
        d.try_normalize()
    }
}

/// Points along `arc` after `from`, the last exactly `arc.to`, within [`CHORD_TOLERANCE_MM`].
pub fn tessellate_arc(from: DVec3, arc: &Arc) -> Vec<DVec3> {
    let plane = arc.plane(from);
    plane.points(from, arc.to, plane.chords())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use swarf_interp::Axis;

    /// The end times by the plain two-pass definition: every entry speed from a backward pass
    /// into its own array, then the moves timed in order.
    fn reference_end_times(window: &[Plan], k: Kinematics, start: f64, count: usize) -> Vec<f64> {
        let mut entries = vec![0.0; window.len() + 1];
        let mut backward = 0.0;
        for (entry, p) in entries.iter_mut().zip(window).rev() {
            backward = p.limit.min(k.reach(backward, p.length));
            *entry = p.forward.min(backward);
        }
        let mut t = start;
        window
            .iter()
            .zip(entries.windows(2))
            .take(count)
            .map(|(p, speeds)| {
                t += p.dwell + k.move_secs(p.length, p.cruise, speeds[0], speeds[1]);
                t
            })
            .collect()
    }

    /// The next number of a xorshift sequence (reproducible test data without a crate).
    fn xorshift(seed: &mut u64) -> u64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        *seed
    }

    /// A straight feed's direction kept as the move and its length turns the same corners as
    /// its unit vector: random moves of 1 µm to 1 km, turns near the limit among them, and the
    /// limit itself.
    #[test]
    fn a_direction_without_a_division_turns_corners_as_the_unit_vector_does() {
        let limit = CORNER_DEGREES.to_radians().cos() - 1e-12;
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let unit = |seed: &mut u64| {
            let mut v = || (xorshift(seed) % 2001) as f64 / 1000.0 - 1.0;
            DVec3::new(v(), v(), v())
        };
        let mut checked = 0;
        for i in 0..20_000 {
            let a = unit(&mut seed);
            let b = if i % 2 == 0 {
                unit(&mut seed)
            } else {
                // A turn of about the limit: `a` turned about a perpendicular axis.
                let axis = a.any_orthonormal_vector();
                let turn = CORNER_DEGREES + (xorshift(&mut seed) % 2001) as f64 / 1000.0 - 1.0;
                glam::DQuat::from_axis_angle(axis, turn.to_radians()) * a
            };
            let scale = |seed: &mut u64| 10f64.powi((xorshift(seed) % 10) as i32 - 3);
            let (a, b) = (a * scale(&mut seed), b * scale(&mut seed));
            let (la, lb) = (a.length(), b.length());
            if la == 0.0 || lb == 0.0 {
                continue;
            }
            let unit_dot = (a * (1.0 / la)).dot(b * (1.0 / lb));
            if (unit_dot - limit).abs() < 1e-13 {
                continue;
            }
            let kept = Heading::new(a, la).within_corner_of(Heading::new(b, lb));
            assert_eq!(kept, unit_dot >= limit, "{a} {b}");
            checked += 1;
        }
        assert!(checked > 19_000, "{checked}");
        // Exactly at the limit, both ways of writing the direction count the turn as smooth.
        let a = DVec3::new(3.0, 0.0, 0.0);
        let b =
            glam::DQuat::from_rotation_z(CORNER_DEGREES.to_radians()) * DVec3::new(0.5, 0.0, 0.0);
        assert!(Heading::new(a, a.length()).within_corner_of(Heading::new(b, b.length())));
        assert!(Heading::unit(a.normalize()).within_corner_of(Heading::unit(b.normalize())));
    }

    #[test]
    fn window_end_times_match_the_two_pass_definition_bit_for_bit() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || (xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64;
        for kinematics in [
            Kinematics::default(),
            Kinematics {
                acceleration_mm_per_s2: f64::INFINITY,
                ..Kinematics::default()
            },
        ] {
            for n in (1..80).flat_map(|n| std::iter::repeat_n(n, if n < 8 { 50 } else { 2 })) {
                let window: Vec<Plan> = (0..n)
                    .map(|i| {
                        let cruise = if next() < 0.1 { 0.0 } else { 200.0 * next() };
                        let limit = if i == 0 { 0.0 } else { cruise * next() };
                        Plan {
                            length: if next() < 0.1 { 0.0 } else { 20.0 * next() },
                            cruise,
                            limit,
                            forward: limit * next(),
                            dwell: if next() < 0.2 { next() } else { 0.0 },
                        }
                    })
                    .collect();
                let start = 100.0 * next();
                for count in 0..=n + 1 {
                    let want = reference_end_times(&window, kinematics, start, count);
                    let mut got = vec![1.5];
                    window_end_times(&window, kinematics, start, count, &mut got);
                    let bits = |v: &[f64]| v.iter().map(|t| t.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&got[1..]), bits(&want), "n {n} count {count}");
                    if n == 1 && count == 1 {
                        let lone = lone_end_time(
                            &window[0],
                            kinematics,
                            kinematics.per_acceleration(),
                            start,
                        );
                        assert_eq!(lone.to_bits(), want[0].to_bits());
                    }
                }
            }
        }
    }

    /// A speed, length or feed for the tests of the model's arithmetic, from the random `r`: one
    /// in eight an edge value (zeros, the smallest and largest, infinity, NaN, a negative one),
    /// else a random magnitude around the speeds and lengths of real moves.
    fn edge_or_random(r: u64) -> f64 {
        const EDGES: [f64; 11] = [
            0.0,
            -0.0,
            1e-300,
            1e-100,
            1.0,
            5.0,
            16.666_666_666_666_668,
            1e154,
            f64::INFINITY,
            f64::NAN,
            -1.0,
        ];
        if r.is_multiple_of(8) {
            EDGES[(r / 8 % EDGES.len() as u64) as usize]
        } else {
            let scale = 10f64.powi((r % 13) as i32 - 6);
            scale * (r >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn capped_reach_is_the_plain_one_bit_for_bit() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        let mut value = move || edge_or_random(xorshift(&mut seed));
        for acceleration in [500.0, 1e-3, 1e9, f64::INFINITY] {
            let k = Kinematics {
                acceleration_mm_per_s2: acceleration,
                ..Kinematics::default()
            };
            for _ in 0..200_000 {
                let (speed, length, cap) = (value(), value(), value());
                let want = cap.min(k.reach(speed, length));
                let got = k.reach_capped(speed, length, cap);
                assert_eq!(
                    got.to_bits(),
                    want.to_bits(),
                    "speed {speed} length {length} cap {cap} acceleration {acceleration}"
                );
            }
            // Right at the cap: the root lands on it, just under or just over.
            for i in 0..10_000 {
                let cap = 1.0 + f64::from(i) * 1e-3;
                let length = 0.25;
                let speed = (cap * cap - 2.0 * acceleration.min(1e3) * length)
                    .max(0.0)
                    .sqrt();
                let want = cap.min(k.reach(speed, length));
                assert_eq!(k.reach_capped(speed, length, cap).to_bits(), want.to_bits());
            }
        }
    }

    /// [`Kinematics::move_secs_per`] as written before it spared the square root of a move
    /// that reaches its feed and the division of one that does not.
    fn plain_move_secs(k: &Kinematics, length: f64, cruise: f64, entry: f64, exit: f64) -> f64 {
        if length <= 0.0 || cruise.is_nan() || cruise <= 0.0 {
            return 0.0;
        }
        let a = k.acceleration_mm_per_s2;
        if a.is_infinite() {
            return length / cruise;
        }
        let per_a = k.per_acceleration();
        let u = entry.clamp(0.0, cruise);
        let w = exit.clamp(0.0, cruise);
        let peak = cruise.min(((2.0 * a * length + u * u + w * w) / 2.0).sqrt());
        let speed_up = ((peak * peak - u * u) * (0.5 * per_a)).max(0.0);
        let slow_down = ((peak * peak - w * w) * (0.5 * per_a)).max(0.0);
        let steady = (length - speed_up - slow_down).max(0.0);
        ((peak - u).max(0.0) + (peak - w).max(0.0)) * per_a + steady / peak
    }

    /// `got` is `want` to the bit where the move reaches its feed, and where it does not, no
    /// more than the steady part the shortcut leaves out: the roundings of the lengths over
    /// which the move speeds up and slows down, a few ulps of the squared speeds over `a`.
    fn same_move_time(k: &Kinematics, length: f64, cruise: f64, entry: f64, exit: f64, got: f64) {
        let want = plain_move_secs(k, length, cruise, entry, exit);
        let a = k.acceleration_mm_per_s2;
        let timed = length > 0.0 && cruise > 0.0 && a.is_finite();
        let (u, w) = (
            entry.clamp(0.0, cruise.max(0.0)),
            exit.clamp(0.0, cruise.max(0.0)),
        );
        let squared = (2.0 * a * length + u * u + w * w) / 2.0;
        let short_of_feed = timed && squared.sqrt() < cruise;
        if short_of_feed && want.is_finite() {
            let noise = 16.0 * f64::EPSILON * squared / (a * squared.sqrt());
            assert!(
                got <= want && want - got <= 1e-12 * want + noise,
                "length {length} cruise {cruise} entry {entry} exit {exit} a {a}: {got} {want}"
            );
        } else {
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "length {length} cruise {cruise} entry {entry} exit {exit} a {a}"
            );
        }
    }

    #[test]
    fn a_move_is_timed_as_with_the_square_root_and_the_division() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut value = move || edge_or_random(xorshift(&mut seed));
        for acceleration in [1000.0, 500.0, 1e-3, 1e9, f64::INFINITY] {
            let k = Kinematics {
                acceleration_mm_per_s2: acceleration,
                ..Kinematics::default()
            };
            let per_a = k.per_acceleration();
            for _ in 0..200_000 {
                let (length, cruise, entry, exit) = (value(), value(), value(), value());
                let got = k.move_secs_per(length, cruise, entry, exit, per_a);
                same_move_time(&k, length, cruise, entry, exit, got);
            }
            // Right at the feed: the peak speed's root lands on it, just under or just over.
            for i in 0..10_000 {
                let cruise = 1.0 + f64::from(i) * 1e-3;
                let entry = 0.5 * cruise;
                // Where (2aL + u² + w²) / 2 is the feed squared.
                let length = (cruise * cruise - entry * entry) / acceleration.min(1e12);
                let length = length * (1.0 + f64::from(i % 7) * f64::EPSILON - 3.0 * f64::EPSILON);
                let got = k.move_secs_per(length, cruise, entry, entry, per_a);
                same_move_time(&k, length, cruise, entry, entry, got);
            }
        }
        // A move so short that 2aL underflows to zero, from rest to rest: it takes no time
        // (2·sqrt(L/a) is about 1e-160 s), not the endless time its zero peak speed gives.
        let k = Kinematics {
            acceleration_mm_per_s2: 1e-3,
            ..Kinematics::default()
        };
        for (entry, exit) in [(0.0, 0.0), (-1.0, 0.0), (0.0, -0.0)] {
            let got = k.move_secs_per(5e-324, 1.0, entry, exit, k.per_acceleration());
            assert!((0.0..1e-150).contains(&got), "{entry} {exit}: {got}");
        }
    }

    #[test]
    fn runs_give_back_every_segment_value() {
        let mut seed = 0x1234_5678_9abc_def1_u64;
        for len in [0usize, 1, 2, 7, 100, 1000] {
            for changes in [1u64, 3, 50] {
                let mut runs = Runs::default();
                let mut plain = Vec::new();
                let mut value = 0u32;
                for segment in 0..len {
                    xorshift(&mut seed);
                    if seed % 100 < changes {
                        value = (seed >> 40) as u32 % 4;
                    }
                    runs.push(segment, value);
                    plain.push(value);
                }
                assert_eq!(runs.expand(len), plain, "len {len} changes {changes}");
                assert!(runs.values.len() <= plain.len());
            }
        }
        // The feeds keep their bits: a negative zero and a NaN come back as they went in.
        let mut path = Toolpath::default();
        for feed in [100.0, -0.0, 0.0, f64::NAN, 100.0] {
            path.emit(
                Source { block: 0, line: 1 },
                &Canon::Feed {
                    to: DVec3::X,
                    feed_mm_per_min: feed,
                },
            );
        }
        let bits: Vec<u32> = path.feeds().iter().map(|f| f.to_bits()).collect();
        let want: Vec<u32> = [100.0f32, -0.0, 0.0, f32::NAN, 100.0]
            .iter()
            .map(|f| f.to_bits())
            .collect();
        assert_eq!(bits, want);
    }

    #[test]
    fn arc_tangents_follow_the_direction_of_travel() {
        let from = DVec3::new(10.0, 0.0, 0.0);
        let to = DVec3::new(0.0, 10.0, 0.0);
        let ccw = PlaneArc::new(from, to, DVec3::ZERO, Axis::Z, true, 0);
        let start = ccw.tangent(from, to, 0.0).unwrap();
        let end = ccw.tangent(from, to, 1.0).unwrap();
        assert!(start.abs_diff_eq(DVec3::Y, 1e-12), "{start}");
        assert!(end.abs_diff_eq(-DVec3::X, 1e-12), "{end}");
        let cw = PlaneArc::new(from, to, DVec3::ZERO, Axis::Z, false, 0);
        let start = cw.tangent(from, to, 0.0).unwrap();
        assert!(start.abs_diff_eq(-DVec3::Y, 1e-12), "{start}");
    }

    #[test]
    fn sweeps_and_end_tangents_agree_with_the_angles_of_the_ends() {
        let mut seed = 0x007a_9ee7_d50f_u64;
        let mut next = move || (xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
        for case in 0..2000 {
            let point = |next: &mut dyn FnMut() -> f64| {
                DVec3::new(100.0 * next(), 100.0 * next(), 10.0 * next())
            };
            let (from, mut to, center) = (point(&mut next), point(&mut next), point(&mut next));
            // Some arcs end where they start, at the centre, or are helices or spirals.
            match case % 5 {
                0 => to = from,
                1 => to = center,
                _ => {}
            }
            let axis = [Axis::X, Axis::Y, Axis::Z][case % 3];
            let (ccw, turns) = (next() < 0.0, u32::from(case % 7 == 0));
            let arc = PlaneArc::new(from, to, center, axis, ccw, turns);
            // The sweep is the end's angle less the start's, brought round to the direction
            // (a full turn where the end is the start, and one more for each extra turn).
            let (iu, iv) = (arc.iu, arc.iv);
            let angle = |p: DVec3| (p[iv] - center[iv]).atan2(p[iu] - center[iu]);
            let tau = std::f64::consts::TAU;
            let raw = angle(to) - angle(from);
            let turn = (arc.sweep - raw) / tau;
            let most = tau * f64::from(turns + 1);
            assert!(
                (turn - turn.round()).abs() < 1e-9
                    && (arc.sweep > 0.0) == ccw
                    && arc.sweep.abs() <= most + 1e-9
                    && arc.sweep.abs() > most - tau,
                "case {case}: sweep {} against {raw}",
                arc.sweep
            );
            for (end, t) in [(false, 0.0), (true, 1.0)] {
                let (quick, plain) = (arc.end_tangent(from, to, end), arc.tangent(from, to, t));
                match (quick, plain) {
                    (Some(q), Some(p)) => assert!(q.abs_diff_eq(p, 1e-9), "case {case}: {q} {p}"),
                    _ => assert_eq!(quick, plain, "case {case}"),
                }
            }
        }
    }
}
