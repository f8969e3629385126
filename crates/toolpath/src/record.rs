//! The toolpath record: segments as parallel arrays plus holes, zeros and zones, as a [`Sink`].

use std::collections::HashSet;

use glam::{BVec3, DVec3};
use swarf_interp::{Arc, Canon, Machine, Sink, Source, StrokeZone};

use crate::arc::{CHORD_TOLERANCE_MM, end_tangent};
use crate::kinematics::Kinematics;
use crate::planner::{ChordJoin, Join, Note, Timer};
use crate::timeline::{Dwell, Timeline, dwell_before};

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
    let corner = |i: usize| DVec3::select(BVec3::new(i & 1 != 0, i & 2 != 0, i & 4 != 0), max, min);
    (0..8usize)
        .flat_map(|a| (0..3).map(move |axis| (a, a | 1 << axis)))
        .filter(|(a, b)| a != b)
        .map(|(a, b)| (corner(a), corner(b)))
        .collect()
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

/// The recorded motions of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    start: DVec3,
    /// The number of segments recorded.
    segments: usize,
    /// Whether the segments are kept (their ends, kinds, lines and end times) or only measured
    /// ([`Toolpath::measuring`]).
    keeps_segments: bool,
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

    /// A [`Toolpath::for_machine`] keeping only measures (counts, bounds, lengths, time, tools,
    /// holes, dwells, zeros, zones), not [`Toolpath::ends`] or [`Toolpath::timeline`].
    pub fn measuring(start: DVec3, machine: &Machine) -> Self {
        let mut path = Toolpath::for_machine(start, machine);
        path.keeps_segments = false;
        path.timer.keeps_times = false;
        path
    }

    /// Makes room for `segments` more segments at once (e.g. one per block of the program),
    /// up to the most the path holds, sparing the copies of arrays that grow while a big
    /// program is recorded.
    pub fn reserve(&mut self, segments: usize) {
        let len = self.ends.len();
        self.reserve_to(len + segments.min(self.max_segments.saturating_sub(len)));
    }

    /// Gives the segment arrays room for `total` segments in all (the timer's end times lag
    /// behind the ends, so they never grow past it first).
    fn reserve_to(&mut self, total: usize) {
        self.ends
            .reserve_exact(total.saturating_sub(self.ends.len()));
        self.kinds
            .reserve_exact(total.saturating_sub(self.kinds.len()));
        self.lines
            .reserve_exact(total.saturating_sub(self.lines.len()));
        let times = &mut self.timer.end_times;
        times.reserve_exact(total.saturating_sub(times.len()));
    }

    /// Grows full arrays twice over, but not past the path's most and a 64th (a block's remaining
    /// chords), so a path at its limit has little spare room; past that, a little at a time.
    #[cold]
    fn grow(&mut self) {
        let len = self.ends.len();
        let most = self.max_segments.saturating_add(self.max_segments / 64);
        let total = if len < most {
            len.max(64).saturating_mul(2).min(most)
        } else {
            len.saturating_add(len / 32 + 64)
        };
        self.reserve_to(total);
    }

    /// Gives back the spare room of the arrays, which grow ahead of what they hold, once the
    /// path is recorded: what is made from it next can take that memory.
    pub fn shrink_to_fit(&mut self) {
        self.ends.shrink_to_fit();
        self.kinds.shrink_to_fit();
        self.lines.shrink_to_fit();
        self.timer.end_times.shrink_to_fit();
        self.dwells.shrink_to_fit();
        self.holes.shrink_to_fit();
        self.programmed.shrink_to_fit();
    }

    /// An empty toolpath starting at `start`, timed with `kinematics`.
    pub fn with_kinematics(start: DVec3, kinematics: Kinematics) -> Self {
        Toolpath {
            start,
            segments: 0,
            keeps_segments: true,
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

    /// Number of segments.
    pub fn len(&self) -> usize {
        self.segments
    }

    /// Whether there is no segment.
    pub fn is_empty(&self) -> bool {
        self.segments == 0
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
        if !self.keeps_segments {
            return Timeline::from_parts(Vec::new(), Vec::new());
        }
        let timer = &self.timer;
        let window = timer.window_end_times(timer.window.len());
        let mut end_times = Vec::with_capacity(timer.end_times.len() + window.len());
        end_times.extend_from_slice(&timer.end_times);
        end_times.extend_from_slice(&window);
        Timeline::from_parts(end_times, self.dwells.clone())
    }

    /// The box containing every point of the path (`None` when nothing moved).
    pub fn bounds(&self) -> Option<Bounds> {
        (self.segments > 0).then_some(self.timer.bounds)
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
        let window = timer.window_end_times(timer.window.len());
        window.last().copied().unwrap_or(timer.settled_secs)
            + dwell_before(&self.dwells, self.segments)
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
        let bounds = self.timer.bounds;
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
        if self.keeps_segments {
            if self.ends.len() == self.ends.capacity() {
                self.grow();
            }
            self.ends.push(to);
            self.kinds.push(kind);
            self.lines.push(line);
        }
        let segment = self.segments;
        self.segments += 1;
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
        let from = self.timer.last_end;
        let geometry = arc.plane(from);
        let radius = geometry
            .radius
            .min(geometry.end_radius)
            .max(CHORD_TOLERANCE_MM);
        let centripetal = (self.timer.kinematics.acceleration_mm_per_s2 * radius).sqrt();
        let cruise = (arc.feed_mm_per_min / 60.0).min(centripetal);
        let count = geometry.chords(CHORD_TOLERANCE_MM);
        for (k, p) in geometry.points(from, arc.to, count).enumerate() {
            let join = if k == 0 {
                Join::Corner {
                    entry: end_tangent(&geometry, from, arc.to, false),
                }
            } else {
                Join::Continue
            };
            let exit = (k + 1 == count)
                .then(|| end_tangent(&geometry, from, arc.to, true))
                .flatten();
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
                let segment = self.segments;
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
                first_segment: self.segments,
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
        // `push` inlined here, not reached through `push_line`: the point goes on in registers
        // rather than through memory (the path's hottest call).
        self.push(kind, DVec3::new(x, y, z), source.line, feed, feed, None);
    }

    fn programmed(&mut self, source: Source, event: &Canon) {
        self.programmed.push((source.line, event.clone()));
    }

    /// Full when its segments and the rest it keeps with them (a dwell weighing as much as a
    /// segment, a hole or a compensated block's programmed motion as two, a change of feed or
    /// of tool as half) reach `max_motions` segments: the memory a run may take.
    fn full(&self) -> bool {
        self.segments
            + self.dwells.len()
            + 2 * (self.holes.len() + self.programmed.len())
            + (self.feeds.values.len() + self.segment_tools.values.len()).saturating_sub(2) / 2
            >= self.max_segments
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift;

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
    fn the_arrays_grow_to_the_most_the_path_holds_and_little_past() {
        let machine = Machine {
            max_motions: 10_000,
            ..Machine::default()
        };
        let mut path = Toolpath::for_machine(DVec3::ZERO, &machine);
        let source = Source { block: 0, line: 1 };
        let mut x = 0.0;
        while !path.full() {
            x += 1.0;
            path.straight(source, false, x, 0.0, 0.0, 100.0);
        }
        assert_eq!(path.len(), 10_000);
        let most = 10_000 + 10_000 / 64;
        for array in [
            path.ends.capacity(),
            path.lines.capacity(),
            path.kinds.capacity(),
        ] {
            assert!((10_000..=most).contains(&array), "{array}");
        }
        assert!(path.timer.end_times.capacity() <= most);
        // The rest of the block that filled it (an arc's chords) still goes in.
        for _ in 0..500 {
            x += 1.0;
            path.straight(source, false, x, 0.0, 0.0, 100.0);
        }
        assert_eq!(path.len(), 10_500);
        assert!(path.ends.capacity() < 11_000, "{}", path.ends.capacity());
        path.shrink_to_fit();
        assert_eq!(path.ends.capacity(), 10_500);
        assert_eq!(path.timeline().end_times().len(), 10_500);
    }
}
