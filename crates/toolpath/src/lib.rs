//! A compact, struct-of-arrays record of a program's motions for drawing, picking and statistics.
//!
//! Segment `i` runs from `end(i - 1)` (or the start point for `i == 0`) to `end(i)`. Arcs are kept
//! as tessellated chords that share the arc's source line, so the renderer only sees lines.

use glam::DVec3;
use swarf_interp::{Canon, Sink, Source};

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

/// The recorded motions of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Toolpath {
    start: DVec3,
    ends: Vec<DVec3>,
    kinds: Vec<SegmentKind>,
    lines: Vec<u32>,
    feeds: Vec<f32>,
    bounds: Option<Bounds>,
    rapid_mm: f64,
    feed_mm: f64,
    feed_secs: f64,
    dwell_secs: f64,
    tools: Vec<u32>,
    rapid_mm_per_min: f64,
}

impl Default for Toolpath {
    fn default() -> Self {
        Toolpath::new(DVec3::ZERO, 10_000.0)
    }
}

impl Toolpath {
    /// An empty toolpath starting at `start`; `rapid_mm_per_min` is used for the time estimate.
    pub fn new(start: DVec3, rapid_mm_per_min: f64) -> Self {
        Toolpath {
            start,
            ends: Vec::new(),
            kinds: Vec::new(),
            lines: Vec::new(),
            feeds: Vec::new(),
            bounds: None,
            rapid_mm: 0.0,
            feed_mm: 0.0,
            feed_secs: 0.0,
            dwell_secs: 0.0,
            tools: Vec::new(),
            rapid_mm_per_min: rapid_mm_per_min.max(1e-9),
        }
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

    /// Feed rate of each segment in mm/min (0 for rapids).
    pub fn feeds(&self) -> &[f32] {
        &self.feeds
    }

    /// The box containing every point of the path (`None` when nothing moved).
    pub fn bounds(&self) -> Option<Bounds> {
        self.bounds
    }

    /// Total rapid distance in mm.
    pub fn rapid_length_mm(&self) -> f64 {
        self.rapid_mm
    }

    /// Total cutting distance in mm.
    pub fn feed_length_mm(&self) -> f64 {
        self.feed_mm
    }

    /// Estimated run time in seconds (rapids at the rapid rate, cuts at their feed, dwells).
    pub fn estimated_secs(&self) -> f64 {
        self.rapid_mm / self.rapid_mm_per_min * 60.0 + self.feed_secs + self.dwell_secs
    }

    /// Tools used, in order of first use.
    pub fn tools(&self) -> &[u32] {
        &self.tools
    }

    /// The first segment caused by source `line` (1-based), for jumping from code to path.
    pub fn first_segment_of_line(&self, line: u32) -> Option<usize> {
        self.lines.iter().position(|&l| l == line)
    }

    fn push(&mut self, kind: SegmentKind, to: DVec3, line: u32, feed_mm_per_min: f64) {
        let from = self.ends.last().copied().unwrap_or(self.start);
        let length = from.distance(to);
        match kind {
            SegmentKind::Rapid => self.rapid_mm += length,
            SegmentKind::Feed | SegmentKind::Arc => {
                self.feed_mm += length;
                if feed_mm_per_min > 0.0 {
                    self.feed_secs += length / feed_mm_per_min * 60.0;
                }
            }
        }
        let bounds = self.bounds.get_or_insert(Bounds {
            min: from,
            max: from,
        });
        bounds.include(from);
        bounds.include(to);
        self.ends.push(to);
        self.kinds.push(kind);
        self.lines.push(line);
        self.feeds.push(feed_mm_per_min as f32);
    }
}

/// Chord tolerance for arc tessellation, in millimetres.
pub const CHORD_TOLERANCE_MM: f64 = 0.01;

impl Sink for Toolpath {
    fn emit(&mut self, source: Source, event: &Canon) {
        match event {
            Canon::Rapid { to } => self.push(SegmentKind::Rapid, *to, source.line, 0.0),
            Canon::Feed {
                to,
                feed_mm_per_min,
            } => self.push(SegmentKind::Feed, *to, source.line, *feed_mm_per_min),
            Canon::Arc {
                to,
                center,
                axis,
                ccw,
                turns,
                feed_mm_per_min,
            } => {
                let from = self.ends.last().copied().unwrap_or(self.start);
                for p in tessellate_arc(from, *to, *center, *axis, *ccw, *turns) {
                    self.push(SegmentKind::Arc, p, source.line, *feed_mm_per_min);
                }
            }
            Canon::Dwell { secs } => self.dwell_secs += secs,
            Canon::ToolChange { tool } => {
                if !self.tools.contains(tool) {
                    self.tools.push(*tool);
                }
            }
            Canon::Spindle { .. } | Canon::Coolant { .. } | Canon::Pause { .. } | Canon::End => {}
        }
    }
}

/// Points along an arc (excluding `from`, ending exactly at `to`) within [`CHORD_TOLERANCE_MM`].
pub fn tessellate_arc(
    from: DVec3,
    to: DVec3,
    center: DVec3,
    axis: swarf_interp::Axis,
    ccw: bool,
    turns: u32,
) -> Vec<DVec3> {
    use swarf_interp::Axis;
    // Map into plane coordinates (u, v, w) where w is along the axis, right-handed.
    let (iu, iv, iw) = match axis {
        Axis::Z => (0, 1, 2),
        Axis::Y => (2, 0, 1),
        Axis::X => (1, 2, 0),
    };
    let rel = |p: DVec3| (p[iu] - center[iu], p[iv] - center[iv]);
    let (su, sv) = rel(from);
    let (eu, ev) = rel(to);
    let radius = su.hypot(sv);
    let a0 = sv.atan2(su);
    let mut sweep = ev.atan2(eu) - a0;
    let tau = std::f64::consts::TAU;
    if ccw {
        if sweep <= 1e-12 {
            sweep += tau;
        }
    } else if sweep >= -1e-12 {
        sweep -= tau;
    }
    sweep += f64::from(turns) * tau * sweep.signum();
    let step = if radius > CHORD_TOLERANCE_MM {
        2.0 * (1.0 - CHORD_TOLERANCE_MM / radius).acos()
    } else {
        tau / 4.0
    };
    let n = ((sweep.abs() / step.max(1e-3)).ceil() as usize).clamp(1, 100_000);
    let end_radius = eu.hypot(ev);
    (1..=n)
        .map(|k| {
            if k == n {
                return to;
            }
            let t = k as f64 / n as f64;
            let a = a0 + sweep * t;
            let r = radius + (end_radius - radius) * t;
            let mut p = DVec3::ZERO;
            p[iu] = center[iu] + r * a.cos();
            p[iv] = center[iv] + r * a.sin();
            p[iw] = from[iw] + (to[iw] - from[iw]) * t;
            p
        })
        .collect()
}
