//! Arbitrary bytes are decoded and parsed in bounded steps, as the editor and `swarf stats`
//! parse a long program (from the text, or through a `LineSource`): the program is the one the
//! whole parse gives.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_syntax::{Dialect, ParseRun, Program, decode, parse};

#[path = "../../tests/support/parse_runs.rs"]
mod parse_runs;

/// The same program; values are compared as printed, so that a NaN equals itself.
fn assert_same(stepped: &Program, whole: &Program, how: &str) {
    if stepped != whole {
        assert_eq!(format!("{stepped:?}"), format!("{whole:?}"), "{how}");
    }
}

fuzz_target!(|bytes: &[u8]| {
    let [dialect, how, rest @ ..] = bytes else {
        return;
    };
    let dialect = Dialect::ALL[usize::from(*dialect) % Dialect::ALL.len()];
    let lines = 1 + usize::from(how & 63);
    let text = decode(rest).text;
    let whole = parse(&text, dialect);
    let (stepped, _) = parse_runs::stepped(&text, dialect, lines);
    assert_same(&stepped, &whole, &format!("{lines} lines a step"));
    let mut run = ParseRun::new(dialect);
    while !run.step_from(&mut text.as_str(), lines) {}
    assert_same(
        &run.finish(),
        &whole,
        &format!("{lines} lines a step from a source"),
    );
});
