//! The run's diagnostics, kept bounded: one met again at the same place is counted, at most
//! [`MAX_KEPT`] different ones are kept, and the alarms that stop a real control stop the run.

use std::collections::HashMap;

use swarf_syntax::{Diagnostic, Severity, Span};

/// Most different diagnostics a run keeps; the ones after are counted in a last note.
pub const MAX_KEPT: usize = 1000;

/// Errors that stop the machine itself (overtravel), where the run goes on after others.
const MACHINE_ALARMS: [&str; 2] = ["E-OVERTRAVEL", "E-STROKE-LIMIT"];

/// The diagnostics of a run, each code and place once with how often it was met.
#[derive(Debug, Clone, Default)]
pub(crate) struct Diagnostics {
    /// The number of the block run under way: a diagnostic given twice by it is met once.
    pub(crate) block: u64,
    /// The diagnostics kept, in order first met, with how often and in which run last met.
    kept: Vec<(Diagnostic, u64, u64)>,
    /// Code and place → index into `kept`.
    places: HashMap<(&'static str, Span), usize>,
    /// How often a diagnostic kept was met again (work of the run: only a loop repeats one).
    pub(crate) repeats: u64,
    /// Diagnostics met after `kept` was full, and where the first of them was.
    left_out: u64,
    first_left_out: Span,
    /// The diagnostic (in `kept`) that stops the run: a machine alarm, or an error met again.
    stop: Option<usize>,
}

impl Diagnostics {
    /// Adds a diagnostic of the run.
    pub(crate) fn push(&mut self, diagnostic: Diagnostic) {
        let key = (diagnostic.code, diagnostic.span);
        if let Some(&i) = self.places.get(&key) {
            if let Some((d, count, last)) = self.kept.get_mut(i)
                && *last != self.block
            {
                *count += 1;
                *last = self.block;
                self.repeats += 1;
                if d.severity == Severity::Error {
                    self.stop.get_or_insert(i);
                }
            }
            return;
        }
        if self.kept.len() >= MAX_KEPT {
            if self.left_out == 0 {
                self.first_left_out = diagnostic.span;
            }
            self.left_out += 1;
            return;
        }
        if MACHINE_ALARMS.contains(&diagnostic.code) {
            self.stop.get_or_insert(self.kept.len());
        }
        self.places.insert(key, self.kept.len());
        self.kept.push((diagnostic, 1, self.block));
    }

    /// Whether a diagnostic stops the run (see [`Diagnostics::push`]).
    pub(crate) fn stops(&self) -> bool {
        self.stop.is_some()
    }

    /// The diagnostics so far with their counts, then a note of those left out; none are left.
    pub(crate) fn take(&mut self) -> Vec<Diagnostic> {
        // The run stays stopped; no later diagnostic is the one it stopped at.
        let stop = self.stop;
        self.stop = stop.map(|_| usize::MAX);
        let left_out = std::mem::take(&mut self.left_out);
        self.places.clear();
        let mut out: Vec<Diagnostic> = std::mem::take(&mut self.kept)
            .into_iter()
            .enumerate()
            .map(|(i, (mut d, count, _))| {
                match (count, stop == Some(i)) {
                    (1, false) => {}
                    (1, true) => d.message.push_str(" (the run stops here)"),
                    (n, false) => d.message.push_str(&format!(" ({n} times)")),
                    (n, true) => d.message.push_str(&format!(
                        " ({n} times: the run came back to it, and stops here, as a control would have at the first)"
                    )),
                }
                d
            })
            .collect();
        if left_out > 0 {
            let message = format!(
                "{left_out} more diagnostics of the run from here on are left out: only the first {MAX_KEPT} different ones are kept"
            );
            let at = self.first_left_out;
            out.push(Diagnostic::note(at, "N-DIAGNOSTICS-LEFT-OUT", message));
        }
        out
    }
}
