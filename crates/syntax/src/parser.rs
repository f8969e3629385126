//! The fault-tolerant parser: each line is read alone by the dialect's [`Rules`](crate::Rules),
//! and a problem in it becomes a diagnostic whose characters are skipped. [`ParseRun`] (`run.rs`)
//! reads lines in bounded steps, with `plain.rs` for plain CAM lines, else `block.rs`.

mod block;
mod expr;
mod number;
mod plain;
mod run;
mod statement;

pub use run::{ParseRun, ReadPoint};

use crate::{Dialect, Program};

/// Parses `text` as read by `dialect`. Never fails: problems are in `Program::diagnostics`.
pub fn parse(text: &str, dialect: Dialect) -> Program {
    let mut run = ParseRun::new(dialect);
    while !run.step(text, usize::MAX) {}
    run.finish()
}

/// Whether `c` is a blank between the items of a line.
fn is_blank(c: char) -> bool {
    c == ' ' || c == '\t'
}

/// The most a parsed program may hold, in bytes (estimated from its parts): one held whole stops
/// there with `E-PROGRAM-SIZE`; one run piece by piece keeps only its diagnostics and lines.
pub const MAX_PARSED_BYTES: usize = 256 << 20;

/// The longest line read in full (1 MiB); the rest of a longer line is reported and skipped.
const MAX_LINE_BYTES: usize = 1 << 20;
