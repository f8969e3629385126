//! When each segment runs: the end times and the dwells between segments.

/// A dwell (G04) before a segment.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Dwell {
    /// The segment it comes before (the segment count when it follows the last segment).
    pub segment: usize,
    /// Seconds, all the dwells between the same two segments together.
    pub secs: f64,
}

/// When each segment runs, in seconds from the program start (serialized without its times,
/// which a web worker sends beside the rest).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Timeline {
    #[serde(skip)]
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
}

/// Seconds of dwell in `dwells` (in segment order) just before segment `i`.
pub(crate) fn dwell_before(dwells: &[Dwell], i: usize) -> f64 {
    let at = dwells.partition_point(|d| d.segment < i);
    dwells
        .get(at)
        .filter(|d| d.segment == i)
        .map_or(0.0, |d| d.secs)
}
