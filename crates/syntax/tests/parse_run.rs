//! A parse run in bounded steps gives the same program as the whole parse.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

use swarf_syntax::{Dialect, ParseRun, parse};

#[path = "../../../tests/support/parse_runs.rs"]
mod parse_runs;
use parse_runs::{grown, stepped};

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
    // Read as a file is read, a line a step: the run stops at the tape mark too.
    for chunk in [1, 5, 100] {
        assert_eq!(
            grown(text, Dialect::Fanuc, chunk, 1),
            whole,
            "chunks of {chunk}"
        );
    }
    let program = whole;
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

#[test]
fn a_grown_run_of_short_texts_equals_the_whole_parse() {
    // Texts of every length up to sixty lines, with and without a last newline, read in
    // pieces of a few lines from chunks of a few bytes.
    for len in 0..60 {
        let mut text = String::new();
        for i in 0..len {
            text.push_str(if i % 3 == 0 { "G1 X1.5\n" } else { "Y2\r\n" });
        }
        for tail in ["", "G0 Z9", "\n"] {
            let text = format!("{text}{tail}");
            let whole = parse(&text, Dialect::LinuxCnc);
            for lines in [1, 2, 5, 64] {
                for chunk in [1, 3, 16, 1000] {
                    assert_eq!(
                        grown(&text, Dialect::LinuxCnc, chunk, lines),
                        whole,
                        "{text:?} in chunks of {chunk}, steps of {lines}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_run_over_a_text_still_being_read_equals_the_whole_parse() {
    let mut text = String::from("O1000\nG90 G21 G17 (début: 加工)\n");
    for i in 0..120 {
        text.push_str(&format!("N{} G01 X{}. Y$ F500.\n", i * 10, i % 7));
        if i % 13 == 0 {
            text.push_str("#1 = [#2 + 3] (a comment)\nG00 G01 X1\r\n\n");
        }
    }
    for tail in ["M30", "M30\n", "M30\n%\n", "%\n"] {
        for head in ["", "%\n", "  \n%\n"] {
            let text = format!("{head}{text}{tail}\nG1 X$\n");
            for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
                let whole = parse(&text, dialect);
                for chunk in [1, 7, 64, 1000, 100_000] {
                    for lines in [1, 5, 1024] {
                        assert_eq!(
                            grown(&text, dialect, chunk, lines),
                            whole,
                            "{dialect:?} chunks of {chunk}, steps of {lines}: {head:?}…{tail:?}"
                        );
                    }
                }
            }
        }
    }
}

/// Line endings and lengths that a reader finding each line's end as it reads must get right:
/// `\r\n`, `\r\r\n`, a `\r` inside a line and at the text's end, lines of blanks, and a plain
/// line longer than the longest line read whole (the rest is reported and skipped). Read in
/// steps and as a text still being read, each gives the whole parse.
#[test]
fn line_ends_found_as_the_lines_are_read_equal_the_whole_parse() {
    let long = format!("G1 X1{}\n", " Y2".repeat(400_000));
    let texts = [
        (String::from("G1 X1\r\nG1 X2\r\r\nG1\rX3\nG1 X4\r"), 1),
        (String::from("G1 X1\n   \t \nX2\r\n\r\n\rG1\n  \r\n"), 1),
        (String::from("\r\n\n%\r\nG1 X1\r\n%\r\nX$\r\n"), 1),
        (format!("G1 X0\n{long}N10 G1 X5\n"), 4096),
    ];
    for (text, smallest_chunk) in &texts {
        for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
            let whole = parse(text, dialect);
            for lines in [1, 3, 1000] {
                let (program, _) = stepped(text, dialect, lines);
                assert_eq!(program, whole, "{dialect:?} in steps of {lines}");
                for chunk in [*smallest_chunk, 64, 100_000] {
                    assert_eq!(
                        grown(text, dialect, chunk.max(*smallest_chunk), lines),
                        whole,
                        "{dialect:?} chunks of {chunk}, steps of {lines}"
                    );
                }
            }
        }
    }
}

#[test]
fn the_blocks_handed_over_name_those_that_own_memory() {
    // Plain lines of up to four words own nothing; five words, a comment, a statement or a
    // program number make a block own memory.
    let mut text = String::new();
    let mut expected = Vec::new();
    for i in 0..40u32 {
        let line = match i % 8 {
            0 => "G1 X1. Y2. Z3. F100.",
            3 => "G0 X5. (move)",
            5 => "#1 = 2",
            6 => "O0100",
            _ => "G1 X1. Y2.",
        };
        if !matches!(i % 8, 1 | 2 | 4 | 7) {
            expected.push(i);
        }
        text.push_str(line);
        text.push('\n');
    }
    for dialect in [Dialect::Fanuc, Dialect::LinuxCnc] {
        let whole = parse(&text, dialect);
        // Indexed first (as the editor reads), or finding each line's end as it reads (as
        // `swarf stats` reads).
        for growing in [false, true] {
            let mut run = if growing {
                ParseRun::growing_unindexed(dialect)
            } else {
                ParseRun::new(&text, dialect)
            };
            let mut spare = Vec::with_capacity(16);
            let mut seen = Vec::new();
            let mut first = 0u32;
            loop {
                let done = if growing {
                    run.step_growing(text.as_bytes(), 0, true, 16)
                } else {
                    run.step(&text, 16)
                };
                let owning = run.take_owning();
                let mut blocks = run.swap_blocks(std::mem::take(&mut spare));
                for &at in &owning {
                    let b = &blocks[at as usize];
                    assert!(
                        b.words.spilled()
                            || b.program().is_some()
                            || !b.comments().is_empty()
                            || !b.statements().is_empty()
                    );
                }
                let all: Vec<u32> = (0..blocks.len() as u32)
                    .filter(|&at| {
                        let b = &blocks[at as usize];
                        b.words.len() > 4
                            || b.program().is_some()
                            || !b.comments().is_empty()
                            || !b.statements().is_empty()
                    })
                    .collect();
                assert_eq!(owning, all, "{dialect:?}, growing {growing}");
                seen.extend(owning.iter().map(|&at| first + at));
                first += blocks.len() as u32;
                let capacity = blocks.capacity();
                swarf_syntax::empty_blocks_known(&mut blocks, &owning);
                assert!(blocks.is_empty());
                assert_eq!(blocks.capacity(), capacity);
                spare = blocks;
                if done {
                    break;
                }
            }
            assert_eq!(first as usize, whole.blocks.len());
            assert_eq!(seen, expected, "{dialect:?}, growing {growing}");
        }
    }
}
