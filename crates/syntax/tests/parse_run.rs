//! A parse run in bounded steps gives the same program as the whole parse.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_syntax::{Dialect, ParseRun, parse};

#[path = "../../../tests/support/parse_runs.rs"]
mod parse_runs;
use parse_runs::stepped;

#[test]
fn stepping_a_few_lines_at_a_time_equals_the_whole_parse() {
    let mut text = String::from("O1000\nG90 G21 G17\n");
    for i in 0..300 {
        text.push_str(&format!("N{} G01 X{}. Y$ F500.\n", i * 10, i % 7));
        if i % 13 == 0 {
            text.push_str("#1 = [#2 + 3] (a comment)\nG00 G01 X1\r\n");
        }
    }
    text.push_str("M30");
    for dialect in Dialect::ALL {
        let whole = parse(&text, dialect);
        for lines in [1, 7, 100, 1000] {
            let (program, steps) = stepped(&text, dialect, lines);
            assert_eq!(program, whole, "{dialect:?} in steps of {lines} lines");
            let total = text.lines().count();
            assert!(steps >= total / lines, "{steps} steps of {lines}");
        }
    }
    assert!(!parse(&text, Dialect::Fanuc).diagnostics.is_empty());
}

#[test]
fn a_stepped_run_stops_at_the_closing_tape_mark() {
    let text = "%\nG0 X1\nG1 X2 F100\n%\nG1 X$\nG1 Y$\n";
    let whole = parse(text, Dialect::Fanuc);
    let (program, _) = stepped(text, Dialect::Fanuc, 1);
    assert_eq!(program, whole);
    let program = whole;
    assert!(
        program
            .diagnostics
            .iter()
            .any(|d| d.code == "N-AFTER-TAPE-END")
    );
    let mut run = ParseRun::new(Dialect::Fanuc);
    assert!(run.step("", 0) || run.step("", 1));
    assert!(run.finish().blocks.is_empty());
}

#[test]
fn lines_from_a_source_give_the_program_of_the_text() {
    let mut text = String::from("%\nO1000\nG90 G21 G17\n");
    for i in 0..200 {
        text.push_str(&format!("N{} G01 X{}.5 Y-0.{i} F500.\n", i * 10, i % 7));
        if i % 11 == 0 {
            text.push_str("#1 = [#2 + 3] (a comment)\r\nG2 X1 R1.\n  \nX$\n");
        }
    }
    text.push_str("M30\n%\nG1 X$\n");
    for dialect in Dialect::ALL {
        let whole = parse(&text, dialect);
        for lines in [1, 9, 1000] {
            let mut run = ParseRun::new(dialect);
            // The lines come through the `LineSource` calls, not from the text at hand.
            let mut source: &str = &text;
            let mut steps = 0;
            while !run.step_from(&mut source, lines) {
                steps += 1;
                assert!(steps < 10_000, "the run ends");
            }
            assert_eq!(run.finish(), whole, "{dialect:?} in steps of {lines} lines");
        }
    }
}

/// Line endings and lengths that a run in steps must get right: `\r\n`, `\r\r\n`, a `\r`
/// inside a line and at the text's end, lines of blanks, and a plain line longer than the
/// longest line read whole (the rest is reported and skipped). Read in steps, from the text or
/// through a `LineSource`, each gives the whole parse.
#[test]
fn line_ends_read_in_steps_equal_the_whole_parse() {
    let long = format!("G1 X1{}\n", " Y2".repeat(400_000));
    let texts = [
        String::from("G1 X1\r\nG1 X2\r\r\nG1\rX3\nG1 X4\r"),
        String::from("G1 X1\n   \t \nX2\r\n\r\n\rG1\n  \r\n"),
        String::from("\r\n\n%\r\nG1 X1\r\n%\r\nX$\r\n"),
        format!("G1 X0\n{long}N10 G1 X5\n"),
    ];
    for text in &texts {
        for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
            let whole = parse(text, dialect);
            for lines in [1, 3, 1000] {
                let (program, _) = stepped(text, dialect, lines);
                assert_eq!(program, whole, "{dialect:?} in steps of {lines}");
                let mut run = ParseRun::new(dialect);
                while !run.step_from(&mut text.as_str(), lines) {}
                assert_eq!(run.finish(), whole, "{dialect:?} from a source by {lines}");
            }
        }
    }
}
