//! Arbitrary bytes are parsed and interpreted (with a small block limit), into the canonical
//! stream and into the toolpath the backplot draws: no panic, no hang, and a toolpath whose
//! arrays agree, whose times run forward and whose box holds its points.
#![no_main]

use glam::DVec3;
use libfuzzer_sys::fuzz_target;
use swarf_interp::{CanonRecorder, Setup};
use swarf_syntax::{Dialect, decode, parse};
use swarf_toolpath::Toolpath;

fuzz_target!(|bytes: &[u8]| {
    let Some((&selector, rest)) = bytes.split_first() else {
        return;
    };
    let dialect = Dialect::ALL[usize::from(selector) % Dialect::ALL.len()];
    let text = decode(rest).text;
    let program = parse(&text, dialect);
    let mut setup = Setup::default();
    setup.machine.max_blocks = 10_000;
    setup.machine.max_motions = 100_000;
    // Twice: into the canonical stream, which has no limit, and into the toolpath, whose
    // segment limit (`Sink::full`, an arc's chords counting one each) can end a run sooner.
    let mut sink = CanonRecorder::default();
    let _ = swarf_interp::run(&program, setup.clone(), &mut sink);

    let mut path = Toolpath::for_machine(DVec3::ZERO, &setup.machine);
    let _ = swarf_interp::run(&program, setup, &mut path);
    let n = path.len();
    assert_eq!(path.ends().len(), n);
    assert_eq!(path.kinds().len(), n);
    assert_eq!(path.lines().len(), n);
    let timeline = path.timeline();
    let times = timeline.end_times();
    assert_eq!(times.len(), n);
    // Every time is a number (infinite only past a move too long to be one), none before the
    // one before it.
    assert!(times.iter().all(|t| !t.is_nan() && *t >= 0.0), "{times:?}");
    assert!(times.windows(2).all(|w| w[0] <= w[1]), "{times:?}");
    if let Some(bounds) = path.bounds() {
        for p in path.ends().iter().filter(|p| p.is_finite()) {
            assert!(
                p.cmpge(bounds.min).all() && p.cmple(bounds.max).all(),
                "{p} outside {bounds:?}"
            );
        }
    }
});
