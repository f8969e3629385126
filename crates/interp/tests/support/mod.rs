//! What the interpreter's tests share (each test file uses some of it).
#![allow(dead_code)]

use swarf_interp::{Arc, Canon, CanonRecorder, Setup, run};
use swarf_syntax::{Diagnostic, Dialect, parse};

/// Parses and runs `text`; returns the events and the parser's and the run's diagnostics.
pub fn run_with(text: &str, dialect: Dialect, setup: Setup) -> (Vec<Canon>, Vec<Diagnostic>) {
    let program = parse(text, dialect);
    let mut rec = CanonRecorder::default();
    let mut diags = program.diagnostics.clone();
    diags.extend(run(&program, setup, &mut rec));
    (rec.events.into_iter().map(|(_, e)| e).collect(), diags)
}

/// The motions' end points, rounded to `1 / scale` (1000 rounds to 0.001).
pub fn ends_rounded(events: &[Canon], scale: f64) -> Vec<[f64; 3]> {
    events
        .iter()
        .filter_map(|e| match e {
            Canon::Rapid { to } | Canon::Feed { to, .. } | Canon::Arc(Arc { to, .. }) => Some(*to),
            _ => None,
        })
        .map(|p| {
            let r = |v: f64| (v * scale).round() / scale + 0.0;
            [r(p.x), r(p.y), r(p.z)]
        })
        .collect()
}
