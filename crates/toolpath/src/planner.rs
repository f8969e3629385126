//! The time planner: join speeds over a bounded look-ahead window, and the end times they give.

use glam::DVec3;

use crate::kinematics::Kinematics;
use crate::record::{Bounds, SegmentKind};

/// Joins between cutting moves whose direction changes by at most this many degrees are run
/// through without stopping; the tool stops at sharper corners.
pub const CORNER_DEGREES: f64 = 10.0;

/// How many segments back the time planner revises the speeds at joins when a move is added.
pub const LOOKAHEAD_SEGMENTS: usize = 4096;

/// The time model and the measures taken of each segment with it (lengths, bounds, the
/// corner between moves): the end times of the segments settled so far, and the plans of
/// those after them.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Timer {
    pub(crate) kinematics: Kinematics,
    /// One over its acceleration ([`Kinematics::per_acceleration`]).
    per_acceleration: f64,
    /// The settled end times (a prefix of the segments), kept where `keeps_times` is on.
    pub(crate) end_times: Vec<f64>,
    /// Whether every settled end time is kept (a path that keeps its segments) or only the
    /// last, `settled_secs` (a path that only measures them).
    pub(crate) keeps_times: bool,
    /// The end time of the last settled segment (0 before any), from which the next are timed.
    pub(crate) settled_secs: f64,
    /// The segments after the settled ones, whose join speeds may still change.
    pub(crate) window: Vec<Plan>,
    /// Where the last segment ends (the start before any).
    pub(crate) last_end: DVec3,
    /// Whether the last segment is a rapid.
    after_rapid: bool,
    /// The direction at the end of the last non-empty segment, as a vector and its length
    /// ([`Heading`]).
    last_direction: Option<Heading>,
    /// The last straight feed in mm/min and its cruise speed in mm/s: a run of moves at one
    /// feed divides once.
    last_feed: (f64, f64),
    /// The box of the start and every segment's end.
    pub(crate) bounds: Bounds,
    pub(crate) rapid_mm: f64,
    pub(crate) feed_mm: f64,
}

/// A segment as the path records it for the timer: its end and speed, and whether the tool
/// came to rest before it (see [`Timer::measure`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Note {
    pub(crate) to: DVec3,
    /// A straight move's feed in mm/min (unused for a rapid), an arc chord's cruise in mm/s.
    pub(crate) speed: f64,
    pub(crate) kind: SegmentKind,
    /// The tool came to rest before the segment.
    pub(crate) stop: bool,
}

/// How a segment joins the one before and leaves, beyond its end point: `None` for a
/// straight move (both come from its direction), else an arc chord's join and exit.
pub(crate) type ChordJoin = Option<(Join, Option<DVec3>)>;

impl Timer {
    pub(crate) fn new(kinematics: Kinematics, start: DVec3) -> Self {
        Timer {
            kinematics,
            per_acceleration: kinematics.per_acceleration(),
            end_times: Vec::new(),
            keeps_times: true,
            settled_secs: 0.0,
            window: Vec::new(),
            last_end: start,
            after_rapid: false,
            last_direction: None,
            last_feed: (0.0, 0.0),
            bounds: Bounds {
                min: start,
                max: start,
            },
            rapid_mm: 0.0,
            feed_mm: 0.0,
        }
    }

    /// Takes in segment `note` after `dwell` seconds: adds to the length, box and distances, and
    /// plans it with its cruise speed and join, from its direction or, for an arc's chord, `chord`.
    #[inline(always)]
    pub(crate) fn measure(&mut self, note: &Note, dwell: f64, chord: ChordJoin) {
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
        self.bounds.include(to);
        // `entry`: `None` for the next chord of an arc, else the new move's direction (`None`
        // inside for an empty move).
        let smooth = match entry {
            _ if stop => false,
            None => true,
            Some(_) if kind == SegmentKind::Rapid || self.after_rapid => false,
            Some(None) => true,
            Some(Some(entry)) => self
                .last_direction
                .is_none_or(|last| last.within_corner_of(entry)),
        };
        if let Some(exit) = exit {
            self.last_direction = Some(exit);
        }
        self.last_end = to;
        self.after_rapid = kind == SegmentKind::Rapid;
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
                self.settled_secs =
                    lone_end_time(&lone, k, self.per_acceleration, self.settled_secs);
                if self.keeps_times {
                    self.end_times.push(self.settled_secs);
                }
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

    /// End times of the first `count` unsettled segments, stopping after the last: each join runs
    /// at the lower of the forward speed and the backward pass's speed that can still stop.
    pub(crate) fn window_end_times(&self, count: usize) -> Vec<f64> {
        let mut times = Vec::with_capacity(count.min(self.window.len()));
        let start = self.settled_secs;
        window_end_times(&self.window, self.kinematics, start, count, &mut times);
        times
    }

    /// Writes the end times of the first `count` unsettled segments and forgets their plans.
    fn settle(&mut self, count: usize) {
        let count = count.min(self.window.len());
        if count == 0 {
            return;
        }
        // A path that only measures its segments keeps none of the times but the last.
        let times = &mut self.end_times;
        window_end_times(
            &self.window,
            self.kinematics,
            self.settled_secs,
            count,
            times,
        );
        self.settled_secs = times.last().copied().unwrap_or(self.settled_secs);
        if !self.keeps_times {
            times.clear();
        }
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
pub(crate) struct Plan {
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
pub(crate) enum Join {
    /// The next chord of the same arc.
    Continue,
    /// A new move: stop or not by kind and angle, `entry` being its direction at the start
    /// (`None` for an empty move).
    Corner { entry: Option<DVec3> },
}

/// Appends the end times of `window`'s first `count` segments from `start` seconds (see
/// [`Toolpath::window_end_times`]), writing join speeds where the times go, so no other buffer.
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

/// The end time of a window's only segment `p`, from `start` seconds to rest (as
/// [`window_end_times`]); a window of one starts at a stop, so its limit and entry speed are zero.
#[inline]
fn lone_end_time(p: &Plan, k: Kinematics, per_a: f64, start: f64) -> f64 {
    debug_assert!(
        p.limit <= 0.0 && p.forward <= 0.0,
        "a lone segment starts at rest"
    );
    start + (p.dwell + k.move_secs_per(p.length, p.cruise, 0.0, 0.0, per_a))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::xorshift;

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
                t += p.dwell
                    + k.move_secs_per(
                        p.length,
                        p.cruise,
                        speeds[0],
                        speeds[1],
                        k.per_acceleration(),
                    );
                t
            })
            .collect()
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
}
