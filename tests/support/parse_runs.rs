//! A program parsed in bounded steps, as the editor and `swarf stats` parse it (included with
//! `#[path]` by the parser's tests and its fuzz target, which hold it to the whole parse).
#![allow(dead_code, reason = "each user takes part of this module")]

use swarf_syntax::{Dialect, LineIndex, ParseRun, Program};

/// How many steps a run of `text` may take: each step reads a line or more, or a chunk more
/// of the text; past this the run is not ending.
fn step_limit(text: &str) -> usize {
    2 * text.len() + 16
}

/// `text` read `lines` at a time by a run that indexes the whole text first (as the editor
/// reads it), and the number of steps it took.
pub fn stepped(text: &str, dialect: Dialect, lines: usize) -> (Program, usize) {
    let mut run = ParseRun::new(text, dialect);
    let mut steps = 0;
    loop {
        let (read, total) = run.progress();
        assert!(read <= total, "{read} of {total} lines read");
        steps += 1;
        if run.step(text, lines) {
            break;
        }
        assert!(steps < step_limit(text), "the run ends");
    }
    assert!(run.is_done());
    (run.finish(), steps)
}

/// `text` read as `swarf stats` reads a file, a chunk of `chunk` bytes at a time while it is
/// parsed: the run is given the whole lines read so far, `lines` at a time, then the rest at
/// the end, each time from the next line to read on (through the narrowest window: the lines
/// read are let go of). Such a run indexes no lines (its index holds the first line alone,
/// which is checked); the program comes back with the whole text's index, as `stats` makes it
/// to report diagnostics.
pub fn grown(text: &str, dialect: Dialect, chunk: usize, lines: usize) -> Program {
    let mut run = ParseRun::growing_unindexed(dialect);
    let (mut read, mut whole_lines, mut complete) = (0, 0, false);
    let mut steps = 0;
    loop {
        // Once the whole lines at hand are read, read a chunk more and keep its whole lines
        // (the rest waits for the next chunk).
        if !complete && run.offset() >= whole_lines {
            read = (read + chunk.max(1)).min(text.len());
            complete = read == text.len();
            whole_lines = if complete {
                read
            } else {
                text.as_bytes()[..read]
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |at| at + 1)
            };
        }
        let base = run.offset().min(whole_lines);
        let part = &text.as_bytes()[base..whole_lines];
        let done = run.step_growing(part, base, complete, lines);
        assert!(
            complete || run.offset() <= whole_lines,
            "no line is read before it ends"
        );
        steps += 1;
        assert!(steps < step_limit(text), "the run ends");
        if done {
            break;
        }
    }
    let base = run.offset().min(text.len());
    run.complete(&text.as_bytes()[base..], base);
    let mut program = run.finish();
    assert_eq!(program.lines.line_count(), 1, "no line is indexed");
    program.lines = LineIndex::new(text);
    program
}
