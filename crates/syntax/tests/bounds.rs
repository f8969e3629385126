//! Hostile texts stay within the parser's bounds: a program held whole is read up to the memory
//! it may take (`E-PROGRAM-SIZE`), a diagnostic quotes only a short excerpt of a long line, and
//! a called program's file that cannot be linked says why.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic, missing_docs)]

#[cfg(target_arch = "wasm32")]
use wasm_bindgen_test::wasm_bindgen_test as test;

use swarf_syntax::{
    Dialect, EXCERPT_CHARS, LineIndex, Lookup, MAX_PARSED_BYTES, Missing, ParseRun, Program, parse,
};

/// `text` parsed whole by a run that may hold at most `max` bytes.
fn parse_at_most(text: &str, max: usize) -> (Program, usize) {
    let mut run = ParseRun::new(Dialect::Fanuc);
    run.set_max_bytes(max);
    while !run.step(text, 1000) {}
    let held = run.held_bytes();
    (run.finish(), held)
}

#[test]
fn a_program_too_large_to_hold_is_read_up_to_its_bound() {
    let text = format!(
        "GOTO 1\nN1 #1=0\n{}GOTO 1\nM30\n",
        "#1=[#1+1]\n".repeat(100_000)
    );
    let max = 4 << 20;
    let (program, held) = parse_at_most(&text, max);
    let stops: Vec<_> = program
        .diagnostics
        .iter()
        .filter(|d| d.code == "E-PROGRAM-SIZE")
        .collect();
    assert_eq!(
        stops.len(),
        1,
        "{:?}",
        &program.diagnostics[..program.diagnostics.len().min(3)]
    );
    assert!(stops[0].message.contains("4 MiB"), "{}", stops[0].message);
    // It stops soon after the bound (a count every 16 KiB of text), and what is read is kept.
    assert!(held > max && held < max + (1 << 20), "{held}");
    let read = program.blocks.len();
    assert!(read > 1000 && read < 100_000, "{read} blocks");
    // The blocks are given room for no more than the bound holds, and the lines of a count.
    let room = program.blocks.capacity();
    let block = size_of::<swarf_syntax::Block>();
    assert!(
        room >= read && room <= max / block + (8 << 10) + 1,
        "{room}"
    );
    let cut = program.lines.line_of(stops[0].span.start);
    assert_eq!(program.blocks.last().unwrap().line as usize + 1, cut);
    assert_eq!(stops[0].span.end as usize, text.len());
    // The same text within the bound is read whole, without the error.
    let whole = parse(&text, Dialect::Fanuc);
    assert_eq!(whole.blocks.len(), 100_004);
    assert!(whole.diagnostics.iter().all(|d| d.code != "E-PROGRAM-SIZE"));
}

/// Diagnostics count towards the bound: a broken file whose every line is an error stops too.
#[test]
fn diagnostics_count_towards_the_bound() {
    let text = "Q\n".repeat(200_000);
    let (program, _) = parse_at_most(&text, 4 << 20);
    let last = program.diagnostics.last().unwrap();
    assert_eq!(last.code, "E-PROGRAM-SIZE");
    assert!(
        program.diagnostics.len() < 100_000,
        "{}",
        program.diagnostics.len()
    );
}

/// A text of more lines than a parse indexes (its line table may take half the bound) is read
/// up to there; the table holds no more lines than that.
#[test]
fn a_text_of_too_many_lines_is_indexed_and_read_up_to_the_bound() {
    let max = 1 << 20;
    let text = "\n".repeat(1 << 20);
    let (program, held) = parse_at_most(&text, max);
    let lines = max / 2 / 4;
    let stop = program.diagnostics.last().unwrap();
    assert_eq!(stop.code, "E-PROGRAM-SIZE");
    assert_eq!(stop.span.start as usize, lines);
    assert!(held <= max, "{held}");

    // A table made for fewer lines holds no more, whatever the line ends.
    let cut = LineIndex::at_most(&text, 1000);
    assert_eq!(cut.line_count(), 1000);
    assert_eq!(cut.line_start(999), 999);
    assert_eq!(LineIndex::at_most("a\r\nb\rc\n", 2).line_count(), 2);
}

/// A million-line program of plain moves, as CAM writes them, is held whole within the bound.
#[test]
fn a_million_plain_lines_fit_the_bound() {
    let line = "X123.456 Y-78.9 Z-1.5\n";
    let text = line.repeat(1_000_000);
    let mut run = ParseRun::new(Dialect::Fanuc);
    while !run.step(&text, 100_000) {}
    assert!(run.held_bytes() < MAX_PARSED_BYTES, "{}", run.held_bytes());
    let program = run.finish();
    assert_eq!(program.blocks.len(), 1_000_000);
    assert!(program.diagnostics.is_empty());
}

/// Every diagnostic that quotes the text quotes at most a short excerpt of it.
#[test]
fn a_diagnostic_quotes_a_short_excerpt_of_a_long_line() {
    let long = 100_000;
    for (dialect, text) in [
        (Dialect::Fanuc, format!("G1 X1 {}\n", "_".repeat(long))),
        (Dialect::Fanuc, format!("G1 {}\n", "XY".repeat(long))),
        (Dialect::Fanuc, format!("N{}\n", "9".repeat(long))),
        (Dialect::Fanuc, format!("G1 X{}\n", "9".repeat(long))),
        (Dialect::Fanuc, format!("#1=[{}[1]]\n", "A".repeat(long))),
        (Dialect::Fanuc, format!("#1=1.{}E5\n", "5".repeat(long))),
        (Dialect::LinuxCnc, format!("o100 {}\n", "x".repeat(long))),
        (Dialect::LinuxCnc, format!("#<{}> 1\n", "n".repeat(long))),
    ] {
        let program = parse(&text, dialect);
        assert!(!program.diagnostics.is_empty(), "{}", &text[..20]);
        for d in &program.diagnostics {
            assert!(
                d.message.chars().count() < EXCERPT_CHARS + 300,
                "{}: {}…",
                d.code,
                d.message.chars().take(300).collect::<String>()
            );
        }
    }
}

/// A call whose file is found and cannot be linked keeps the reason; past `max` files the rest
/// are not looked for, and say so.
#[test]
fn a_call_whose_file_is_refused_keeps_why() {
    let main = "M98 P1\nM98 P2\nM98 P3\nM30\n";
    let mut p = parse(main, Dialect::Fanuc);
    let linked = p.link_calls(main.len(), Dialect::Fanuc, 1, |missing| match missing {
        Missing::Number(1) => Lookup::Refused("O0001.nc is a folder, not a file".into()),
        Missing::Number(2) => Lookup::Found("O0002.nc".into(), "G0 X1.\nM99\n".into()),
        _ => Lookup::None,
    });
    assert_eq!(linked.len(), 1);
    assert_eq!(
        p.unlinked,
        vec![
            (
                Missing::Number(1),
                "O0001.nc is a folder, not a file".to_string()
            ),
            (
                Missing::Number(3),
                "not looked for: the program links 1 files, the most it may".to_string()
            ),
        ]
    );
}
