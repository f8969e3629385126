//! Arbitrary bytes are decoded and parsed in bounded steps, as the editor and `swarf stats`
//! parse a long program (indexed whole, or read from a file a chunk at a time): the program is
//! the one the whole parse gives.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarf_syntax::{Dialect, Program, decode, parse};

#[path = "../../tests/support/parse_runs.rs"]
mod parse_runs;

/// Chunk sizes a file is read in (the last: the whole file at once).
const CHUNKS: [usize; 8] = [1, 2, 3, 7, 16, 64, 1000, 1 << 20];

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
    let chunk = CHUNKS[usize::from(how & 7)];
    let lines = 1 + usize::from((how >> 3) & 7);
    let text = decode(rest).text;
    let whole = parse(&text, dialect);
    let grown = parse_runs::grown(&text, dialect, chunk, lines);
    assert_same(
        &grown,
        &whole,
        &format!("read in chunks of {chunk}, {lines} lines a step"),
    );
    let (stepped, _) = parse_runs::stepped(&text, dialect, lines);
    assert_same(&stepped, &whole, &format!("{lines} lines a step"));
});
