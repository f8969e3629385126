//! An arbitrary main program and an arbitrary file found for each program it calls (or refused,
//! with a reason), linked as the CLI links the files beside a program and run with small
//! limits: no panic, no hang, every diagnostic inside the linked texts.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_interp::{CanonRecorder, Setup};
use swarf_syntax::{Dialect, Lookup, Missing, decode, parse};

fuzz_target!(|bytes: &[u8]| {
    let [selector, split, rest @ ..] = bytes else {
        return;
    };
    let dialect = Dialect::ALL[usize::from(selector & 0x7f) % Dialect::ALL.len()];
    let refuse_numbers = selector & 0x80 != 0;
    let (main, called) = rest.split_at(usize::from(*split) * rest.len() / 256);
    let main = decode(main).text;
    let called = decode(called).text;
    let mut program = parse(&main, dialect);
    let linked = program.link_calls(main.len(), dialect, 4, |missing| match missing {
        Missing::Number(_) if refuse_numbers => Lookup::Refused(format!("{missing:?} refused")),
        _ => Lookup::Found(format!("{missing:?}"), called.clone()),
    });
    assert_eq!(linked.len(), program.linked.len());
    let end = program
        .linked
        .last()
        .map_or(main.len(), |l| l.first_byte as usize + l.len as usize);
    let mut setup = Setup::default();
    setup.machine.max_blocks = 10_000;
    setup.machine.max_motions = 100_000;
    let run = swarf_interp::run(&program, setup, &mut CanonRecorder::default());
    for d in program.diagnostics.iter().chain(&run) {
        assert!(d.span.start <= d.span.end && d.span.end as usize <= end, "{d:?}");
    }
});
