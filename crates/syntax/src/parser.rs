//! The fault-tolerant block parser: each line is read on its own (the newline is the recovery
//! point), by the dialect's [`Rules`](crate::Rules); a problem inside a line becomes a
//! diagnostic, the offending characters are skipped, and reading goes on.
//!
//! [`ParseRun`] (`run.rs`) reads a text a bounded number of lines a step, each line with the
//! short reader of plain CAM lines (`plain.rs`) or the general one (`block.rs`; `statement.rs`
//! for O-words, macro keywords and assignments; `expr.rs`); `number.rs` scans both's numbers.

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

/// The most a parsed program may hold, in bytes, estimated from the sizes of its parts: its
/// line table (at most half of it), blocks, statements, expressions and diagnostics. A program
/// held whole (the editor's, or one that jumps or calls) is read up to there, with
/// `E-PROGRAM-SIZE`; one run piece by piece holds only its diagnostics and lines.
pub const MAX_PARSED_BYTES: usize = 256 << 20;

/// The longest line read in full (1 MiB); the rest of a longer line is reported and skipped.
const MAX_LINE_BYTES: usize = 1 << 20;
