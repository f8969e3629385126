//! The fault-tolerant block parser.
//!
//! Each line is read on its own (the newline is the recovery point); a problem inside a line
//! becomes a diagnostic, the offending characters are skipped, and reading goes on. The lexical
//! rules come from the dialect's [`Rules`](crate::Rules) table.
//!
//! `run.rs` holds [`ParseRun`], which reads a text in steps of a bounded number of lines; each
//! line goes to the short reader of plain CAM lines (`plain.rs`) or to the general reader
//! (`block.rs`: blocks and words, with `statement.rs` for O-word lines, macro keywords and
//! assignments, and `expr.rs` for expressions); `number.rs` scans the numbers of both.

mod block;
mod expr;
mod number;
mod plain;
mod run;
mod statement;

pub use run::ParseRun;

use crate::{Dialect, Program};

/// Parses `text` as read by `dialect`. Never fails: problems are in `Program::diagnostics`.
pub fn parse(text: &str, dialect: Dialect) -> Program {
    let mut run = ParseRun::new(text, dialect);
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
