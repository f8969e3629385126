//! A program parsed in bounded steps, as the editor and `swarf stats` parse it (included with
//! `#[path]` by the parser's tests and its fuzz target, which hold it to the whole parse).

use swarf_syntax::{Dialect, ParseRun, Program};

/// How many steps a run of `text` may take: each step reads a line or more; past this the run
/// is not ending.
fn step_limit(text: &str) -> usize {
    2 * text.len() + 16
}

/// `text` read `lines` at a time (as the editor reads it), and the number of steps it took.
pub fn stepped(text: &str, dialect: Dialect, lines: usize) -> (Program, usize) {
    let mut run = ParseRun::new(dialect);
    let mut steps = 0;
    loop {
        let (_, read) = run.progress();
        assert!(read <= text.len(), "{read} of {} bytes read", text.len());
        steps += 1;
        if run.step(text, lines) {
            break;
        }
        assert!(steps < step_limit(text), "the run ends");
    }
    (run.finish(), steps)
}
