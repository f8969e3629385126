//! Arbitrary bytes are parsed and interpreted (with a small block limit): no panic, no hang.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_interp::{CanonRecorder, Setup};
use swarf_syntax::{Dialect, decode, parse};

fuzz_target!(|bytes: &[u8]| {
    let Some((&selector, rest)) = bytes.split_first() else {
        return;
    };
    let dialect = Dialect::ALL[usize::from(selector) % Dialect::ALL.len()];
    let text = decode(rest).text;
    let program = parse(&text, dialect);
    let mut setup = Setup::default();
    setup.machine.max_blocks = 10_000;
    let mut sink = CanonRecorder::default();
    let _ = swarf_interp::run(&program, setup, &mut sink);
});
