//! A parse run in bounded steps gives the same program as the whole parse.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_syntax::{Dialect, ParseRun, parse};

fn stepped(text: &str, dialect: Dialect, lines: usize) -> (swarf_syntax::Program, usize) {
    let mut run = ParseRun::new(text, dialect);
    let mut steps = 0;
    loop {
        let (read, total) = run.progress();
        assert!(read <= total);
        steps += 1;
        if run.step(text, lines) {
            break;
        }
        assert!(steps < 10_000, "the run ends");
    }
    assert!(run.is_done());
    (run.finish(), steps)
}

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
    assert!(
        program
            .diagnostics
            .iter()
            .any(|d| d.code == "N-AFTER-TAPE-END")
    );
    let mut run = ParseRun::new("", Dialect::Fanuc);
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
            let mut run = ParseRun::new(&text, dialect);
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
